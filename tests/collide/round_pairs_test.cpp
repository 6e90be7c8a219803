// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Closed-form contacts of spheres and capsules with each other and with boxes (round_pairs.hpp):
// hand-computed cases, degenerate cases, a randomised comparison with an independent computation
// (distances by golden-section search on the cores, depths of crossing cores by a dense search
// over normals of D's support function), manifolds, and bodies resting on a floor.
#include "support/quantile.hpp"
#include "support/approx.hpp"
#include "support/poses.hpp"
#include "support/sim.hpp"

#include "scenes/random.hpp"

#include <xeno/collide/collide.hpp>

#include <algorithm>
#include <vector>

using namespace xeno;
using xeno::test::at;
using xeno::test::near;
using xeno::test::quantile;

namespace {

template <class T>
Quat<T> about(const Vec3<T>& axis, double angle) {
    return Quat<T>::from_axis_angle(axis, T(angle));
}

// Independent reference, in double: a round shape is a core segment p–q swept by r (a box has
// r = 0 and its own description); nothing here calls the code under test.
struct RefShape {
    bool box = false;
    Vec3<double> p, q;     // core segment (round shapes)
    double r = 0;          // radius (round shapes)
    Vec3<double> c;        // centre (boxes)
    Vec3<double> axis[3];  // world axes (boxes)
    Vec3<double> e;        // half extents (boxes)
};

template <class T>
RefShape reference(const Shape<T>& s, const Transform<T>& pose) {
    const Transform<double> t = pose.template cast<double>();
    RefShape out;
    if (const auto* sphere = std::get_if<Sphere<T>>(&s)) {
        out.p = out.q = t.position;
        out.r = double(sphere->radius());
    } else if (const auto* capsule = std::get_if<Capsule<T>>(&s)) {
        const Vec3<double> half = rotate(t.orientation, Vec3<double>{0, double(capsule->half_height()), 0});
        out.p = t.position - half;
        out.q = t.position + half;
        out.r = double(capsule->radius());
    } else {
        const auto& b = std::get<Box<T>>(s);
        out.box = true;
        out.c = t.position;
        for (int i = 0; i < 3; ++i) out.axis[i] = rotate(t.orientation, Vec3<double>::axis(i));
        out.e = Vec3<double>(b.half_extents());
    }
    return out;
}

// Support distance along n (any length).
double support(const RefShape& s, const Vec3<double>& n) {
    if (s.box) {
        double h = dot(s.c, n);
        for (int i = 0; i < 3; ++i) h += s.e[i] * std::abs(dot(s.axis[i], n));
        return h;
    }
    return std::max(dot(s.p, n), dot(s.q, n)) + s.r * length(n);
}

// Distance from a point to the core (segment, or the box itself).
double core_distance(const RefShape& s, const Vec3<double>& x) {
    if (s.box) {
        double sq = 0;
        for (int i = 0; i < 3; ++i) {
            const double v = std::abs(dot(x - s.c, s.axis[i])) - s.e[i];
            if (v > 0) sq += v * v;
        }
        return std::sqrt(sq);
    }
    const Vec3<double> d = s.q - s.p;
    const double len_sq = dot(d, d);
    const double t = len_sq > 0 ? std::clamp(dot(x - s.p, d) / len_sq, 0.0, 1.0) : 0.0;
    return length(x - (s.p + d * t));
}

// How far x lies outside the shape (0 on or inside).
double outside(const RefShape& s, const Vec3<double>& x) { return std::max(core_distance(s, x) - s.r, 0.0); }

// Minimum over t in [0, 1] of a convex function, by golden-section search.
template <class F>
double golden_min(F&& f) {
    double lo = 0, hi = 1;
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = f(x1), f2 = f(x2);
    for (int i = 0; i < 200; ++i) {
        if (f1 < f2) {
            hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(x1);
        } else {
            lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(x2);
        }
    }
    return std::min({f(0), f(1), f1, f2});
}

// Distance between the cores of a round shape a and a shape b (round or box).
double core_gap(const RefShape& a, const RefShape& b) {
    return golden_min([&](double t) { return core_distance(b, a.p + (a.q - a.p) * t); });
}

// min over unit n of h_A(n) + h_B(−n): the signed depth (negative: the distance apart), by a dense
// search (Fibonacci sphere) refined by a shrinking pattern search.
double dense_depth(const RefShape& a, const RefShape& b) {
    auto h = [&](const Vec3<double>& n) { return support(a, n) + support(b, -n); };
    Vec3<double> best_n{1, 0, 0};
    double best = h(best_n);
    const int count = 4000;
    for (int i = 0; i < count; ++i) {
        const double z = 1 - (2 * i + 1.0) / count, rho = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
        const Vec3<double> n{rho * std::cos(phi), rho * std::sin(phi), z};
        if (h(n) < best) best = h(n), best_n = n;
    }
    for (double step = 0.05; step > 1e-12; step *= 0.5) {
        for (bool improved = true; improved;) {
            improved = false;
            const Vec3<double> t1 = any_perpendicular(best_n), t2 = cross(best_n, t1);
            for (int k = 0; k < 8; ++k) {
                const double angle = k * 3.14159265358979 / 4;
                const Vec3<double> n = normalized(best_n + (t1 * std::cos(angle) + t2 * std::sin(angle)) * step);
                if (h(n) < best) best = h(n), best_n = n, improved = true;
            }
        }
    }
    return best;
}

// The depth of a round shape's core cutting into a box, plus its radius: the distance from the
// origin to the boundary of K = box ⊖ core, the hull of corners minus segment ends, whose facets
// are found by brute force over every plane through three of its points.
double polytope_depth(const RefShape& round, const RefShape& box) {
    std::vector<Vec3<double>> v;
    for (int corner = 0; corner < 8; ++corner) {
        Vec3<double> x = box.c;
        for (int i = 0; i < 3; ++i) x += box.axis[i] * (((corner >> i) & 1) ? box.e[i] : -box.e[i]);
        v.push_back(x - round.p);
        v.push_back(x - round.q);
    }
    double best = 1e300;
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                const Vec3<double> c = cross(v[j] - v[i], v[k] - v[i]);
                if (length(c) < 1e-9) continue;  // collinear
                const Vec3<double> m = c / length(c);
                const double d = dot(m, v[i]);
                double above = -1e300, below = 1e300;
                for (const Vec3<double>& x : v) above = std::max(above, dot(m, x) - d), below = std::min(below, dot(m, x) - d);
                if (above <= 1e-10) best = std::min(best, d);         // a facet with outward normal m
                else if (below >= -1e-10) best = std::min(best, -d);  // ... with outward normal −m
            }
    return round.r + best;
}

// The exact signed depth of a pair with at least one round shape (a must be round).
double exact_depth(const RefShape& a, const RefShape& b) {
    const double gap = core_gap(a, b);
    if (gap > 1e-7) return a.r + b.r - gap;
    return b.box ? polytope_depth(a, b) : dense_depth(a, b);  // the cores touch or cross
}

template <class T>
T scale_of(const Shape<T>& a, const Shape<T>& b) {
    return bounding_radius(a) + bounding_radius(b);
}

// A shape of the round pairs: sphere, capsule or box, sizes 1:1 to 1:10.
template <class T>
Shape<T> random_shape(scenes::Random& rng, int kind) {
    const T s = rng.uniform(T(0.2), T(2));
    if (kind == 0) return Sphere<T>(s * rng.uniform(T(0.3), T(1)));
    if (kind == 1) return Capsule<T>(s * rng.uniform(T(0.1), T(0.6)), s * rng.uniform(T(0), T(1)));
    return Box<T>(s * rng.uniform(T(0.1), T(1)), s * rng.uniform(T(0.1), T(1)), s * rng.uniform(T(0.1), T(1)));
}

}  // namespace

TEST_CASE_TEMPLATE("sphere-sphere and sphere-capsule contacts are the closed forms, in both orders", T, float, double) {
    const Shape<T> small = Sphere<T>(T(0.5)), big = Sphere<T>(T(1));
    // Centres 1.3 apart along (3, 4, 12)/13: depth 0.2, points on each surface along the line.
    const Vec3<T> dir{T(3) / T(13), T(4) / T(13), T(12) / T(13)};
    const Transform<T> ta = at(T(1), T(2), T(3), about<T>(Vec3<T>::unit_x(), 0.7));
    const Transform<T> tb{ta.position + dir * T(1.3), about<T>(Vec3<T>::unit_z(), -1.1)};
    const Penetration<T> p = collide(small, ta, big, tb);
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.2), T(1e-6)));
    CHECK(near(p.normal, dir, T(1e-6)));
    CHECK(near(p.point_a, ta.position + dir * T(0.5), T(1e-6)));  // on A's surface
    CHECK(near(p.point_b, tb.position - dir * T(1), T(1e-6)));    // on B's surface
    CHECK(near(p.point_a - p.point_b, p.normal * p.depth, T(1e-6)));
    const Penetration<T> q = collide(big, tb, small, ta);
    REQUIRE(q.hit);
    CHECK(near(q.depth, T(0.2), T(1e-6)));
    CHECK(near(q.normal, -dir, T(1e-6)));
    CHECK(near(q.point_a, tb.position - dir * T(1), T(1e-6)));
    CHECK(intersect(small, ta, big, tb));
    CHECK_FALSE(intersect(small, ta, big, Transform<T>{ta.position + dir * T(1.51), tb.orientation}));

    // A capsule (radius 0.3, half height 1) lying along x; a sphere of 0.5 beside its side and
    // beyond its end.
    const Shape<T> capsule = Capsule<T>(T(0.3), T(1));
    const Transform<T> tc = at(T(0), T(0), T(0), about<T>(Vec3<T>::unit_z(), 1.5707963267948966));
    const Penetration<T> side = collide(capsule, tc, small, at(T(0.4), T(0.7), T(0)));
    REQUIRE(side.hit);
    CHECK(near(side.depth, T(0.1), T(1e-6)));
    CHECK(near(side.normal, Vec3<T>::unit_y(), T(1e-6)));
    CHECK(near(side.point_b, Vec3<T>{T(0.4), T(0.2), T(0)}, T(1e-6)));
    CHECK(near(side.point_a, Vec3<T>{T(0.4), T(0.3), T(0)}, T(1e-6)));
    const Penetration<T> side_ba = collide(small, at(T(0.4), T(0.7), T(0)), capsule, tc);
    REQUIRE(side_ba.hit);
    CHECK(near(side_ba.depth, T(0.1), T(1e-6)));
    CHECK(near(side_ba.normal, -Vec3<T>::unit_y(), T(1e-6)));
    // Beyond the end (1, 0, 0): the sphere's centre at (1.6, 0.3, 0), distance sqrt(0.45).
    const Penetration<T> end = collide(small, at(T(1.6), T(0.3), T(0)), capsule, tc);
    REQUIRE(end.hit);
    const T d = std::sqrt(T(0.45));
    CHECK(near(end.depth, T(0.8) - d, T(1e-6)));
    CHECK(near(end.normal, Vec3<T>{T(-0.6), T(-0.3), T(0)} / d, T(1e-6)));
}

TEST_CASE_TEMPLATE("capsule-capsule contacts are the closed forms: crossed, skew, end to end, parallel", T, float, double) {
    const Shape<T> a = Capsule<T>(T(0.2), T(1)), b = Capsule<T>(T(0.3), T(0.5));
    const T half_pi = T(1.5707963267948966);
    // Crossed at right angles, B along x at height 0.4 above A (along y) at z = 0: the closest
    // points are the crossing; depth 0.5 − 0.4 along z.
    const Transform<T> ta = at(T(0), T(0), T(0));
    const Transform<T> tb = at(T(0), T(0.2), T(0.4), Quat<T>::from_axis_angle(Vec3<T>::unit_z(), half_pi));
    const Penetration<T> p = collide(a, ta, b, tb);
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.1), T(1e-6)));
    CHECK(near(p.normal, Vec3<T>::unit_z(), T(1e-6)));
    CHECK(near(p.point_a, Vec3<T>{T(0), T(0.2), T(0.2)}, T(1e-6)));
    CHECK(near(p.point_b, Vec3<T>{T(0), T(0.2), T(0.1)}, T(1e-6)));
    // The same pair turned as a whole: the answer turns with it.
    const Quat<T> turn = about<T>(normalized(Vec3<T>{T(1), T(2), T(3)}), 0.9);
    const Vec3<T> shift{T(5), T(-2), T(1)};
    const Penetration<T> turned =
        collide(a, Transform<T>{shift, turn}, b, Transform<T>{shift + rotate(turn, tb.position), turn * tb.orientation});
    REQUIRE(turned.hit);
    CHECK(near(turned.depth, T(0.1), T(1e-6)));
    CHECK(near(turned.normal, rotate(turn, Vec3<T>::unit_z()), T(1e-6)));
    CHECK(near(turned.point_b, shift + rotate(turn, Vec3<T>{T(0), T(0.2), T(0.1)}), T(1e-5)));
    // End to end on one line: B's lower end 0.45 above A's upper end.
    const Penetration<T> ends = collide(a, ta, b, at(T(0), T(1) + T(0.45) + T(0.5), T(0)));
    REQUIRE(ends.hit);
    CHECK(near(ends.depth, T(0.05), T(1e-6)));
    CHECK(near(ends.normal, Vec3<T>::unit_y(), T(1e-6)));
    // Parallel, side by side, 0.45 apart: depth 0.05 along x, in both orders.
    const Penetration<T> par = collide(a, ta, b, at(T(0.45), T(0.3), T(0)));
    REQUIRE(par.hit);
    CHECK(near(par.depth, T(0.05), T(1e-6)));
    CHECK(near(par.normal, Vec3<T>::unit_x(), T(1e-6)));
    const Penetration<T> par_ba = collide(b, at(T(0.45), T(0.3), T(0)), a, ta);
    REQUIRE(par_ba.hit);
    CHECK(near(par_ba.depth, T(0.05), T(1e-6)));
    CHECK(near(par_ba.normal, -Vec3<T>::unit_x(), T(1e-6)));
    // Skew axes: A along y, B along z through (0.3, 1.3, 0): A's upper end (0, 1, 0) against B's
    // middle, 0.3·√2 apart.
    const Transform<T> skew = at(T(0.3), T(1.3), T(0), Quat<T>::from_axis_angle(Vec3<T>::unit_x(), half_pi));
    const Penetration<T> s = collide(a, ta, b, skew);
    REQUIRE(s.hit);
    const T gap = std::sqrt(T(0.18));
    CHECK(near(s.depth, T(0.5) - gap, T(1e-6)));
    CHECK(near(s.normal, Vec3<T>{T(0.3), T(0.3), T(0)} / gap, T(1e-6)));
}

TEST_CASE_TEMPLATE("sphere-box and capsule-box contacts are the closed forms: face, edge, corner, inside", T, float, double) {
    const Shape<T> box = Box<T>(T(1), T(0.5), T(2)), ball = Sphere<T>(T(0.5));
    const Quat<T> turn = about<T>(normalized(Vec3<T>{T(1), T(-2), T(0.5)}), 1.3);
    const Vec3<T> origin{T(3), T(-1), T(2)};
    const Transform<T> tbox{origin, turn};
    auto local = [&](T x, T y, T z) { return Transform<T>{origin + rotate(turn, Vec3<T>{x, y, z}), Quat<T>::identity()}; };
    // Face: centre 0.3 above the top face.
    Penetration<T> p = collide(box, tbox, ball, local(T(0.5), T(0.8), T(1)));
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.2), T(1e-6)));
    CHECK(near(p.normal, rotate(turn, Vec3<T>::unit_y()), T(1e-6)));
    CHECK(near(p.point_a, origin + rotate(turn, Vec3<T>{T(0.5), T(0.5), T(1)}), T(1e-6)));
    // Edge (x, y): centre at (1.2, 0.8, 0), 0.3 and 0.2 beyond the two faces.
    p = collide(ball, local(T(1.2), T(0.8), T(0)), box, tbox);
    REQUIRE(p.hit);
    const T edge = std::sqrt(T(0.04) + T(0.09));
    CHECK(near(p.depth, T(0.5) - edge, T(1e-6)));
    CHECK(near(p.normal, -rotate(turn, Vec3<T>{T(0.2), T(0.3), T(0)} / edge), T(1e-6)));  // ball A -> box B
    // Corner: (1.1, 0.6, 2.2).
    p = collide(box, tbox, ball, local(T(1.1), T(0.6), T(2.2)));
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.5) - std::sqrt(T(0.06)), T(1e-6)));
    // Centre inside, nearest to the +x face (0.2 away): out through that face, depth r + 0.2.
    p = collide(box, tbox, ball, local(T(0.8), T(0.1), T(-0.5)));
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.7), T(1e-6)));
    CHECK(near(p.normal, rotate(turn, Vec3<T>::unit_x()), T(1e-6)));
    // Capsule (r 0.25, h 0.5) standing on the top face, lower end 0.1 into the face's plane
    // (centre 0.5 + 0.25 − 0.1 + 0.5 above the box centre): depth 0.1, normal the face's.
    const Shape<T> capsule = Capsule<T>(T(0.25), T(0.5));
    const Transform<T> standing{origin + rotate(turn, Vec3<T>{T(0.2), T(1.15), T(-1)}), turn};
    p = collide(box, tbox, capsule, standing);
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.1), T(1e-6)));
    CHECK(near(p.normal, rotate(turn, Vec3<T>::unit_y()), T(1e-6)));
    CHECK(near(p.point_b, origin + rotate(turn, Vec3<T>{T(0.2), T(0.4), T(-1)}), T(1e-6)));
    p = collide(capsule, standing, box, tbox);
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.1), T(1e-6)));
    CHECK(near(p.normal, -rotate(turn, Vec3<T>::unit_y()), T(1e-6)));
    // A capsule lying across the box's +x edge region, its core 0.1 outside both the +x and +y
    // faces' planes (axis along z): an edge contact, depth 0.25 − 0.1·√2.
    const Transform<T> along_z{origin + rotate(turn, Vec3<T>{T(1.1), T(0.6), T(0)}),
                               turn * Quat<T>::from_axis_angle(Vec3<T>::unit_x(), T(1.5707963267948966))};
    p = collide(box, tbox, capsule, along_z);
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.25) - T(0.1) * std::sqrt(T(2)), T(1e-6)));
    CHECK(near(p.normal, rotate(turn, Vec3<T>{T(1), T(1), T(0)} / std::sqrt(T(2))), T(1e-6)));
    // Its core cutting into the box (axis along x through (0, 0.45, 0)): out through the top face,
    // depth 0.05 + 0.25.
    p = collide(box, tbox, capsule,
                Transform<T>{origin + rotate(turn, Vec3<T>{T(0), T(0.45), T(0)}),
                             turn * Quat<T>::from_axis_angle(Vec3<T>::unit_z(), T(1.5707963267948966))});
    REQUIRE(p.hit);
    CHECK(near(p.depth, T(0.3), T(1e-6)));
    CHECK(near(p.normal, rotate(turn, Vec3<T>::unit_y()), T(1e-6)));
}

TEST_CASE_TEMPLATE("degenerate round pairs give finite, exact answers", T, float, double) {
    const Shape<T> s1 = Sphere<T>(T(0.5)), s2 = Sphere<T>(T(0.7)), c1 = Capsule<T>(T(0.2), T(0.6)),
                   c2 = Capsule<T>(T(0.3), T(0.6));
    const Shape<T> box = Box<T>(T(0.4), T(0.5), T(0.6));
    const Transform<T> t = at(T(1), T(2), T(3), about<T>(Vec3<T>::unit_y(), 0.4));
    auto check = [&](const Penetration<T>& p, T depth) {
        REQUIRE(p.hit);
        CHECK(is_finite(p.normal));
        CHECK(is_finite(p.point_a));
        CHECK(is_finite(p.point_b));
        CHECK(near(length(p.normal), T(1), T(1e-6)));
        CHECK(near(p.depth, depth, T(1e-6)));
        CHECK(near(p.point_a - p.point_b, p.normal * p.depth, T(1e-5)));
    };
    check(collide(s1, t, s2, t), T(1.2));  // coincident centres
    check(collide(s1, t, c1, t), T(0.7));  // a centre on the other's axis
    check(collide(c1, t, c2, t), T(0.5));  // identical axes
    check(collide(c1, t, c2, Transform<T>{t.position, t.orientation * about<T>(Vec3<T>::unit_x(), 1.0)}),
          T(0.5));  // crossing axes
    check(collide(c1, t, c2, Transform<T>{t.position + rotate(t.orientation, Vec3<T>{T(0), T(0.3), T(0)}), t.orientation}),
          T(0.5));  // overlapping parallel axes
    // A sphere's centre at the box's centre: out through the nearest face (x, 0.4 away).
    const Penetration<T> inside = collide(box, t, s1, t);
    check(inside, T(0.9));
    CHECK(near(std::abs(dot(inside.normal, rotate(t.orientation, Vec3<T>::unit_x()))), T(1), T(1e-6)));
    check(collide(s1, t, box, t), T(0.9));
    // A capsule's whole core inside the box, along the box's y: out through x (0.4 + 0.2).
    check(collide(box, t, c1, t), T(0.6));
    check(collide(c1, t, box, t), T(0.6));
    // Manifolds of the same pairs are finite too.
    for (const auto& [x, y] : {std::pair{&s1, &s2}, std::pair{&c1, &c2}, std::pair{&box, &c1}, std::pair{&c2, &box}}) {
        const ContactManifold<T> m = generate_contacts(*x, t, *y, t, T(0.02));
        REQUIRE(m.count >= 1);
        CHECK(is_finite(m.normal));
        for (int i = 0; i < m.count; ++i)
            CHECK((is_finite(m.points[i].point_a) && is_finite(m.points[i].point_b) && std::isfinite(m.points[i].depth)));
    }
}

TEST_CASE_TEMPLATE("round pairs match an independent computation at random, both orders, points on their bodies", T, float,
                   double) {
    scenes::Random rng(1201);
    const T tol = std::is_same_v<T, float> ? T(2e-5) : T(1e-9);  // of the pair's size
    int hits = 0, speculative = 0;
#ifdef XENO_SANITIZE
    const int pairs = 600;
#else
    const int pairs = 6000;
#endif
    for (int k = 0; k < pairs; ++k) {
        // Kinds: sphere-sphere, sphere-capsule, capsule-capsule, sphere-box, capsule-box.
        const int kinds[5][2] = {{0, 0}, {0, 1}, {1, 1}, {0, 2}, {1, 2}};
        const int* kind = kinds[k % 5];
        const Shape<T> a = random_shape<T>(rng, kind[0]), b = random_shape<T>(rng, kind[1]);
        const T scale = scale_of(a, b);
        const Transform<T> ta{rng.in_box(Vec3<T>{T(3), T(3), T(3)}), rng.rotation<T>()};
        const Transform<T> tb{ta.position + rng.direction<T>() * (scale * rng.uniform(T(0), T(1.05))), rng.rotation<T>()};
        const RefShape ra = reference(a, ta), rb = reference(b, tb);
        const double exact = exact_depth(ra, rb);
        CAPTURE(k);
        CAPTURE(exact);
        for (int order = 0; order < 2; ++order) {
            const Shape<T>& x = order == 0 ? a : b;
            const Shape<T>& y = order == 0 ? b : a;
            const Transform<T>& tx = order == 0 ? ta : tb;
            const Transform<T>& ty = order == 0 ? tb : ta;
            const RefShape& rx = order == 0 ? ra : rb;
            const RefShape& ry = order == 0 ? rb : ra;
            const Penetration<T> p = collide(x, tx, y, ty);
            CHECK(p.hit == intersect(x, tx, y, ty));
            if (std::abs(exact) > double(tol * scale)) CHECK(p.hit == (exact > 0));
            if (p.hit) {
                ++hits;
                CHECK(std::abs(double(p.depth) - exact) <= double(tol * scale));
                CHECK(near(length(p.normal), T(1), T(1e-5)));
                // The normal achieves the depth: h_x(n) + h_y(−n) = depth.
                const Vec3<double> n(p.normal);
                CHECK(std::abs(support(rx, n) + support(ry, -n) - double(p.depth)) <= double(tol * scale));
                // Points on their own bodies, depth apart along the normal.
                CHECK(outside(rx, Vec3<double>(p.point_a)) <= double(tol * scale));
                CHECK(outside(ry, Vec3<double>(p.point_b)) <= double(tol * scale));
                CHECK(length(Vec3<double>(p.point_a - p.point_b) - n * double(p.depth)) <= double(tol * scale));
            }
            // The world's manifold: its deepest point is the exact depth, speculative ones included.
            const T margin = T(0.1) * scale;
            const ContactManifold<T> m = generate_contacts(x, tx, y, ty, margin);
            if (exact > -double(margin) + double(tol * scale)) {
                REQUIRE(m.count >= 1);
                T deepest = m.points[0].depth;
                for (int i = 1; i < m.count; ++i) deepest = std::max(deepest, m.points[i].depth);
                CHECK(std::abs(double(deepest) - exact) <= double(tol * scale));
                speculative += exact < 0 ? 1 : 0;
                for (int i = 0; i < m.count; ++i) {
                    const ManifoldPoint<T>& mp = m.points[i];
                    CHECK(mp.depth > -margin);
                    CHECK(outside(ry, Vec3<double>(mp.point_b)) <= double(tol * scale));
                    CHECK(length(Vec3<double>(mp.point_a - mp.point_b) - Vec3<double>(m.normal) * double(mp.depth)) <=
                          double(tol * scale));
                }
            } else if (exact < -double(margin) - double(tol * scale)) {
                CHECK(m.count == 0);
            }
        }
    }
    CHECK(hits > pairs / 2);
    CHECK(speculative > pairs / 50);
}

TEST_CASE_TEMPLATE("regression (issue 12): round pairs report the exact minimum depth, not MPR's", T, float, double) {
    // On 332467a (MPR and refinement) these pairs gave depth / minimum: sphere-sphere p99 1.07,
    // sphere-box p99 1.68 and max 2.1, capsule-capsule median 1.02 and max 2.2. The minimum here is
    // computed in the test (exact_depth).
    scenes::Random rng(1202);
    std::vector<double> sphere_sphere, sphere_box, capsule_capsule;
    const double tol = std::is_same_v<T, float> ? 1e-4 : 1e-9;
    for (int k = 0; k < 1500; ++k) {
        const int kinds[3][2] = {{0, 0}, {0, 2}, {1, 1}};
        const int* kind = kinds[k % 3];
        const Shape<T> a = random_shape<T>(rng, kind[0]), b = random_shape<T>(rng, kind[1]);
        const T scale = scale_of(a, b);
        const Transform<T> ta{rng.in_box(Vec3<T>{T(1), T(1), T(1)}), rng.rotation<T>()};
        const Transform<T> tb{ta.position + rng.direction<T>() * (scale * rng.uniform(T(0), T(0.9))), rng.rotation<T>()};
        const double exact = exact_depth(reference(a, ta), reference(b, tb));
        if (exact < 0.01 * double(scale)) continue;
        const Penetration<T> p = collide(a, ta, b, tb);
        REQUIRE(p.hit);
        (k % 3 == 0 ? sphere_sphere : k % 3 == 1 ? sphere_box : capsule_capsule).push_back(double(p.depth) / exact);
    }
    const char* names[] = {"sphere-sphere", "sphere-box", "capsule-capsule"};
    const std::vector<double>* sets[] = {&sphere_sphere, &sphere_box, &capsule_capsule};
    for (int i = 0; i < 3; ++i) {
        const std::vector<double>* ratios = sets[i];
        REQUIRE(ratios->size() > 200);
        MESSAGE(names[i] << " depth / exact minimum: median " << quantile(*ratios, 0.5) << " p99 " << quantile(*ratios, 0.99)
                         << " max " << quantile(*ratios, 1.0) << " min " << quantile(*ratios, 0.0));
        CHECK(quantile(*ratios, 1.0) <= 1 + tol);
        CHECK(quantile(*ratios, 0.0) >= 1 - tol);
    }
}

TEST_CASE_TEMPLATE("a capsule along a box face and nearly parallel capsules get two points, crossing ones three", T, float,
                   double) {
    const Shape<T> floor = Box<T>(T(5), T(0.5), T(5));
    const Shape<T> capsule = Capsule<T>(T(0.3), T(0.6));
    const Quat<T> flat = about<T>(Vec3<T>::unit_z(), 1.5707963267948966);
    const Transform<T> origin = at(T(0), T(0), T(0));
    // Lying flat 0.01 into the floor: two points at the segment's ends, both 0.01 deep, either order.
    for (int order = 0; order < 2; ++order) {
        const Transform<T> lying = at(T(1), T(0.79), T(-2), flat);
        const ContactManifold<T> m = order == 0 ? generate_contacts(floor, origin, capsule, lying, T(0.02))
                                                : generate_contacts(capsule, lying, floor, origin, T(0.02));
        REQUIRE(m.count == 2);
        CHECK(near(m.normal, Vec3<T>::unit_y() * (order == 0 ? T(1) : T(-1)), T(1e-6)));
        for (int i = 0; i < 2; ++i) {
            CHECK(near(m.points[i].depth, T(0.01), T(1e-5)));
            const Vec3<T>& on_capsule = order == 0 ? m.points[i].point_b : m.points[i].point_a;
            const Vec3<T>& on_floor = order == 0 ? m.points[i].point_a : m.points[i].point_b;
            CHECK(near(std::abs(on_capsule.x - T(1)), T(0.6), T(1e-5)));
            CHECK(near(on_capsule.y, T(0.49), T(1e-5)));
            CHECK(near(on_floor.y, T(0.5), T(1e-5)));
        }
    }
    // Tilted so that one end is 0.015 above the floor (a speculative point with its gap), the
    // other 0.01 into it.
    const T lift = T(0.025) / T(1.2);
    const Transform<T> tilted{{T(0), T(0.8 - 0.01 + 0.0125), T(0)},
                              Quat<T>::from_axis_angle(Vec3<T>::unit_z(), T(1.5707963267948966) + std::asin(lift))};
    const ContactManifold<T> t = generate_contacts(floor, origin, capsule, tilted, T(0.02));
    REQUIRE(t.count == 2);
    const T d0 = std::min(t.points[0].depth, t.points[1].depth), d1 = std::max(t.points[0].depth, t.points[1].depth);
    const T centre_height = T(0.8 - 0.01 + 0.0125), half_drop = T(0.6) * lift;
    CHECK(near(d1, T(0.3) - (centre_height - half_drop - T(0.5)), T(1e-5)));
    CHECK(near(d0, T(0.3) - (centre_height + half_drop - T(0.5)), T(1e-5)));
    CHECK(d0 < T(0));
    // Hanging over the floor's edge at x = 5: only the part over the face, from x = 4.7 to 5.
    const ContactManifold<T> edge = generate_contacts(floor, origin, capsule, at(T(4.7), T(0.79), T(0), flat), T(0.02));
    REQUIRE(edge.count == 2);
    CHECK(near(std::max(edge.points[0].point_b.x, edge.points[1].point_b.x), T(5), T(1e-5)));
    CHECK(near(std::min(edge.points[0].point_b.x, edge.points[1].point_b.x), T(4.1), T(1e-5)));
    // Standing upright: one point under the lower end.
    CHECK(generate_contacts(floor, origin, capsule, at(T(0), T(1.39), T(0)), T(0.02)).count == 1);

    // Parallel capsules side by side, B offset along the axis by 0.4: the overlap of their
    // extents, two points 0.05 deep.
    const Shape<T> log = Capsule<T>(T(0.25), T(1));
    const ContactManifold<T> par =
        generate_contacts(log, at(T(0), T(0), T(0), flat), log, at(T(0.4), T(0.45), T(0), flat), T(0.02));
    REQUIRE(par.count == 2);
    CHECK(near(par.normal, Vec3<T>::unit_y(), T(1e-6)));
    CHECK(near(std::min(par.points[0].point_b.x, par.points[1].point_b.x), T(-0.6), T(1e-5)));
    CHECK(near(std::max(par.points[0].point_b.x, par.points[1].point_b.x), T(1), T(1e-5)));
    for (int i = 0; i < 2; ++i) CHECK(near(par.points[i].depth, T(0.05), T(1e-5)));
    // Crossing at 4° in the middle: the two ends and the crossing point (deepest, exact depth).
    const ContactManifold<T> cross = generate_contacts(log, at(T(0), T(0), T(0), flat), log,
                                                       at(T(0), T(0.45), T(0), about<T>(Vec3<T>::unit_y(), 0.07) * flat), T(0.1));
    REQUIRE(cross.count == 3);
    T deepest = cross.points[0].depth;
    for (int i = 1; i < 3; ++i) deepest = std::max(deepest, cross.points[i].depth);
    CHECK(near(deepest, T(0.05), T(1e-5)));
    // Crossing at right angles: one point.
    CHECK(generate_contacts(log, at(T(0), T(0), T(0), flat), log,
                            at(T(0), T(0.45), T(0), about<T>(Vec3<T>::unit_x(), 1.5707963267948966)), T(0.02))
              .count == 1);
    // Spheres: always one point, speculative ones with their gap.
    const ContactManifold<T> s =
        generate_contacts(Shape<T>(Sphere<T>(T(0.5))), origin, Shape<T>(Sphere<T>(T(0.5))), at(T(0), T(1.01), T(0)), T(0.02));
    REQUIRE(s.count == 1);
    CHECK(near(s.points[0].depth, T(-0.01), T(1e-6)));
    CHECK(generate_contacts(Shape<T>(Sphere<T>(T(0.5))), origin, Shape<T>(Sphere<T>(T(0.5))), at(T(0), T(1.03), T(0)), T(0.02))
              .count == 0);
}

// Regression: a clipped part shorter than a thousandth of the pair's size counted as one point,
// and the pair's size is the larger shape's: on a box of half size 400 (a game's ground) a
// capsule with a core shorter than 0.57 m touched by one end, which rocked it end to end as it
// rolled (tests/dynamics/motion_test.cpp).
TEST_CASE_TEMPLATE("regression: a short capsule lying on a large box touches it by both ends of its core", T, float, double) {
    const Shape<T> capsule = Capsule<T>(T(0.33), T(0.2));
    const Quat<T> flat = about<T>(Vec3<T>::unit_x(), 1.5707963267948966);  // the core along z
    for (const T half_size : {T(1), T(50), T(400), T(5000)}) {
        CAPTURE(half_size);
        const Shape<T> ground = Box<T>(half_size, T(0.5), half_size);
        const ContactManifold<T> m =
            generate_contacts(ground, at(T(0), T(-0.5), T(0)), capsule, at(T(0.5), T(0.329), T(0), flat), T(0.02));
        REQUIRE(m.count == 2);
        CHECK(near(std::min(m.points[0].point_b.z, m.points[1].point_b.z), T(-0.2), T(1e-4)));
        CHECK(near(std::max(m.points[0].point_b.z, m.points[1].point_b.z), T(0.2), T(1e-4)));
        for (int i = 0; i < 2; ++i) CHECK(near(m.points[i].depth, T(0.001), T(2e-4)));
    }
}

TEST_CASE_TEMPLATE("intersect agrees with collide on the closed-form pairs and on boxes", T, float, double) {
    scenes::Random rng(1203);
    int hits = 0;
    for (int k = 0; k < 3000; ++k) {
        const Shape<T> a = random_shape<T>(rng, int(rng.index(3))), b = random_shape<T>(rng, int(rng.index(3)));
        const Transform<T> ta{rng.in_box(Vec3<T>{T(1), T(1), T(1)}), rng.rotation<T>()};
        const Transform<T> tb{ta.position + rng.direction<T>() * (scale_of(a, b) * rng.uniform(T(0), T(1))), rng.rotation<T>()};
        const bool hit = collide(a, ta, b, tb).hit;
        CHECK(intersect(a, ta, b, tb) == hit);
        hits += hit ? 1 : 0;
    }
    CHECK(hits > 500);
}

TEST_CASE_TEMPLATE("a capsule resting on a box floor stays level on two points, a sphere rests at its radius", T, float, double) {
    World<T> w;  // default settings
    scenes::add_ground(w);
    BodyDef<T> lying;
    lying.position = {T(0), T(0.35), T(0)};
    lying.orientation = about<T>(Vec3<T>::unit_z(), 1.5707963267948966);
    const BodyId capsule = w.create_body(Capsule<T>(T(0.3), T(0.6)), lying);
    BodyDef<T> ball_def;
    ball_def.position = {T(3), T(0.55), T(0)};
    const BodyId ball = w.create_body(Sphere<T>(T(0.5)), ball_def);
    T worst_tilt = T(0);
    test::simulate(w, T(3), [&](int step) {
        if (step < 60) return;  // after a second to settle
        const Vec3<T> axis = rotate(w.body(capsule).orientation(), Vec3<T>::unit_y());
        worst_tilt = std::max(worst_tilt, std::abs(axis.y));
    });
    CHECK(worst_tilt < T(1e-3));  // level: no rocking about an end
    CHECK(std::abs(w.body(capsule).position().y - T(0.3)) <= w.settings().linear_slop);
    CHECK(std::abs(w.body(ball).position().y - T(0.5)) <= w.settings().linear_slop);
    int capsule_points = 0;
    for (const Contact<T>& c : w.contacts())
        if (c.a == capsule || c.b == capsule) capsule_points = c.manifold.count;
    CHECK(capsule_points == 2);
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The narrow phase as the world calls it: normal refinement and whole manifolds by clipping.
#include "support/quantile.hpp"
#include "support/approx.hpp"
#include "support/poses.hpp"

#include "scenes/random.hpp"

#include <xeno/collide/collide.hpp>
#include <xeno/collide/sat.hpp>
#include <xeno/shape/polyhedra.hpp>

#include <algorithm>
#include <cstring>
#include <limits>
#include <vector>

using namespace xeno;
using xeno::test::at;
using xeno::test::near;
using xeno::test::quantile;

TEST_CASE_TEMPLATE("refinement snaps a slightly tilted resting contact to the face normal", T, float, double) {
    const Box<T> cube_box(T(0.5), T(0.5), T(0.5)), slab_box(T(3), T(0.5), T(3));
    const Shape<T> cube = cube_box, slab = slab_box;
    scenes::Random rng(31);
    for (int k = 0; k < 200; ++k) {
        const Quat<T> tilt = Quat<T>::from_axis_angle(rng.direction<T>(), rng.uniform(T(-0.01), T(0.01)));
        const Transform<T> tb{{rng.uniform(T(-2), T(2)), T(0.995), rng.uniform(T(-2), T(2))}, tilt};
        const Penetration<T> raw = mpr_penetration(slab_box, at(T(0), T(0), T(0)), cube_box, tb);
        const Penetration<T> p = collide(slab, at(T(0), T(0), T(0)), cube, tb);
        REQUIRE(p.hit);
        REQUIRE(raw.hit);
        CHECK(p.normal == Vec3<T>::unit_y());   // exactly the face normal
        CHECK(p.depth <= raw.depth + T(1e-3));  // face axes win within a slack
        const SeparatingAxis<T> exact = separating_axis(slab_box, at(T(0), T(0), T(0)), cube_box, tb);
        CHECK(near(p.depth, exact.depth, T(1e-5)));
    }
}

TEST_CASE_TEMPLATE("refined depth is never below the exact minimum and is closer to it than MPR's", T, float, double) {
    scenes::Random rng(32);
    const Box<T> a(T(0.5), T(0.5), T(0.5));
    const Box<T> b(T(0.8), T(0.3), T(0.5));
    const Shape<T> sa = a, sb = b;
    std::vector<T> mpr_ratio, refined_ratio;
    const T eps = std::is_same_v<T, float> ? T(1e-4) : T(1e-9);
    for (int k = 0; k < 4000; ++k) {
        const Transform<T> ta{Vec3<T>::zero(), rng.rotation<T>()};
        const Transform<T> tb{rng.in_box(Vec3<T>{T(1.1), T(1.1), T(1.1)}), rng.rotation<T>()};
        const SeparatingAxis<T> exact = separating_axis(a, ta, b, tb);
        if (exact.depth < T(1e-3)) continue;
        const Penetration<T> raw = mpr_penetration(a, ta, b, tb);
        const Penetration<T> p = collide(sa, ta, sb, tb);
        REQUIRE(raw.hit);
        REQUIRE(p.hit);
        CHECK(p.depth >= exact.depth - eps);
        CHECK(p.depth <= raw.depth + T(1e-3));  // faces win within a slack
        mpr_ratio.push_back(raw.depth / exact.depth);
        refined_ratio.push_back(p.depth / exact.depth);
    }
    REQUIRE(mpr_ratio.size() > 1000);
    MESSAGE("depth / exact minimum, MPR:     median " << quantile(mpr_ratio, 0.5) << " p90 " << quantile(mpr_ratio, 0.9)
                                                      << " p99 " << quantile(mpr_ratio, 0.99) << " max "
                                                      << quantile(mpr_ratio, 1.0));
    MESSAGE("depth / exact minimum, refined: median " << quantile(refined_ratio, 0.5) << " p90 " << quantile(refined_ratio, 0.9)
                                                      << " p99 " << quantile(refined_ratio, 0.99) << " max "
                                                      << quantile(refined_ratio, 1.0));
    CHECK(quantile(refined_ratio, 0.9) <= quantile(mpr_ratio, 0.9));
    CHECK(quantile(refined_ratio, 0.5) < T(1.001));
}

// Regression: the tolerances of refinement, MPR and the least-depth expansion were fractions of
// the pair's size, the sum of both shapes' radii, so the larger shape set them. A 10 cm hull at
// the edge of a box of half size 400: refinement took the box's face up to 6.5 cm deeper than
// the least depth, and in float MPR stopped 5.7 mm short and missed overlaps that deep. The same
// poses against the edge of a 1 m box are the reference: the geometry near the edge is the same.
TEST_CASE_TEMPLATE("regression: a small hull at the edge of a 400 m box overlaps it as at the edge of a 1 m box", T, float,
                   double) {
    const Shape<T> hull = make_box_polyhedron(Vec3<T>{T(0.05), T(0.03), T(0.04)});
    scenes::Random rng(11);
    const T round_off = std::is_same_v<T, float> ? T(1.5e-3) : T(1e-6);  // 16 ε × 566 m, the pair's size
    int compared = 0;
    for (int k = 0; k < 4000; ++k) {
        const Vec3<T> offset = rng.in_box(Vec3<T>::one() * T(0.06));
        const Quat<T> turn = rng.rotation<T>();
        T depth[2];
        for (int i = 0; i < 2; ++i) {
            const T half_size = i == 0 ? T(1) : T(400);
            const Penetration<T> p = collide(Shape<T>(Box<T>(half_size, half_size, half_size)), at(T(0), T(0), T(0)), hull,
                                             Transform<T>{Vec3<T>{half_size, half_size, T(0)} + offset, turn});
            depth[i] = p.hit ? p.depth : T(-1);
        }
        if (!(depth[0] > round_off && depth[0] < T(0.02))) continue;  // the contacts of a hull against a ledge
        CAPTURE(k);
        CAPTURE(depth[0]);
        CAPTURE(depth[1]);
        // Each within 1 % of the least depth (the expansion's stop), the larger pair's also within
        // round-off at its coordinates, once for MPR's stop and once for the expansion's.
        CHECK(std::abs(depth[1] - depth[0]) <= T(2) * round_off + T(0.02) * depth[0]);
        ++compared;
    }
    CHECK(compared > 800);
}

TEST_CASE_TEMPLATE("a box resting on a box gets four points at once", T, float, double) {
    const Shape<T> cube = Box<T>(T(0.5), T(0.5), T(0.5));
    const ContactManifold<T> m = generate_contacts(cube, at(T(0), T(0), T(0)), cube, at(T(0), T(0.99), T(0)), T(0.02));
    REQUIRE(m.count == 4);
    CHECK(m.normal == Vec3<T>::unit_y());
    for (int i = 0; i < 4; ++i) {
        CHECK(near(m.points[i].depth, T(0.01), T(1e-5)));
        CHECK(near(std::abs(m.points[i].point_a.x), T(0.5), T(1e-5)));
        CHECK(near(std::abs(m.points[i].point_a.z), T(0.5), T(1e-5)));
        CHECK(near(m.points[i].point_a.y, T(0.5), T(1e-5)));
        CHECK(near(m.points[i].point_b.y, T(0.49), T(1e-5)));
    }
    // Offset and turned: the contact patch is the overlap of the two squares, clipped.
    const ContactManifold<T> o =
        generate_contacts(cube, at(T(0), T(0), T(0)), cube,
                          at(T(0.6), T(0.98), T(0), Quat<T>::from_axis_angle(Vec3<T>::unit_y(), T(0.3))), T(0.02));
    REQUIRE(o.count == 4);
    for (int i = 0; i < 4; ++i) {
        CHECK(near(o.points[i].depth, T(0.02), T(1e-5)));
        CHECK(o.points[i].point_a.x <= T(0.5) + T(1e-5));  // within A's top face
        CHECK(o.points[i].point_a.x >= T(0.6) - T(0.5) * (std::cos(T(0.3)) + std::sin(T(0.3))) - T(1e-5));
    }
}

TEST_CASE_TEMPLATE("speculative contacts report the gap as negative depth within the margin only", T, float, double) {
    const Shape<T> cube = Box<T>(T(0.5), T(0.5), T(0.5));
    const ContactManifold<T> near_gap = generate_contacts(cube, at(T(0), T(0), T(0)), cube, at(T(0.1), T(1.01), T(0)), T(0.02));
    REQUIRE(near_gap.count == 4);
    CHECK(near(near_gap.normal, Vec3<T>::unit_y()));
    for (int i = 0; i < 4; ++i) CHECK(near(near_gap.points[i].depth, T(-0.01), T(1e-4)));
    CHECK(generate_contacts(cube, at(T(0), T(0), T(0)), cube, at(T(0.1), T(1.03), T(0)), T(0.02)).count == 0);
    CHECK(generate_contacts(cube, at(T(0), T(0), T(0)), cube, at(T(0.1), T(1.01), T(0)), T(0)).count == 0);
}

TEST_CASE_TEMPLATE("round and flat shapes on a box get the manifold their shape allows", T, float, double) {
    const Shape<T> ground = Box<T>(T(5), T(0.5), T(5));
    const Transform<T> origin = at(T(0), T(0), T(0));
    // Sphere: one point under its centre.
    const ContactManifold<T> s = generate_contacts(ground, origin, Shape<T>(Sphere<T>(T(0.5))), at(T(1), T(0.99), T(2)), T(0.02));
    REQUIRE(s.count == 1);
    CHECK(near(s.points[0].depth, T(0.01), T(1e-3)));
    CHECK(near(s.points[0].point_b, Vec3<T>{T(1), T(0.49), T(2)}, T(1e-3)));
    // Cylinder standing on its cap: four points on the rim.
    const ContactManifold<T> c =
        generate_contacts(ground, origin, Shape<T>(Cylinder<T>(T(0.4), T(0.5))), at(T(0), T(0.99), T(0)), T(0.02));
    REQUIRE(c.count == 4);
    for (int i = 0; i < 4; ++i) {
        CHECK(near(c.points[i].depth, T(0.01), T(1e-4)));
        CHECK(near(length(Vec3<T>{c.points[i].point_b.x, T(0), c.points[i].point_b.z}), T(0.4), T(1e-4)));
    }
    // Capsule lying flat: two points at the segment's ends.
    const Quat<T> flat = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 2);
    const ContactManifold<T> k =
        generate_contacts(ground, origin, Shape<T>(Capsule<T>(T(0.3), T(0.6))), at(T(0), T(0.79), T(0), flat), T(0.02));
    REQUIRE(k.count == 2);
    CHECK(near(std::abs(k.points[0].point_b.x), T(0.6), T(1e-3)));
    CHECK(near(std::abs(k.points[1].point_b.x), T(0.6), T(1e-3)));
    CHECK(near(k.points[0].depth, T(0.01), T(1e-3)));
    // Cylinder lying on its side: a line contact, two points.
    const ContactManifold<T> side =
        generate_contacts(ground, origin, Shape<T>(Cylinder<T>(T(0.4), T(0.5))), at(T(0), T(0.89), T(0), flat), T(0.02));
    CHECK(side.count == 2);
    // Cone on its base: four rim points.
    const ContactManifold<T> cone =
        generate_contacts(ground, origin, Shape<T>(Cone<T>(T(0.5), T(1))), at(T(0), T(0.74), T(0)), T(0.02));
    CHECK(cone.count == 4);
}

TEST_CASE_TEMPLATE("crossed edges give a single contact at the crossing", T, float, double) {
    const Shape<T> cube = Box<T>(T(0.5), T(0.5), T(0.5));
    const T reach = std::sqrt(T(0.5));
    const ContactManifold<T> m = generate_contacts(
        cube, at(T(0), T(0), T(0), Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 4)), cube,
        at(T(0), T(2) * reach - T(0.02), T(0), Quat<T>::from_axis_angle(Vec3<T>::unit_x(), ScalarTraits<T>::pi / 4)), T(0.02));
    REQUIRE(m.count == 1);
    CHECK(near(m.normal, Vec3<T>::unit_y(), T(1e-3)));
    CHECK(near(m.points[0].depth, T(0.02), T(1e-3)));
    CHECK(near(m.points[0].point_a, Vec3<T>{T(0), reach, T(0)}, T(1e-2)));
}

TEST_CASE_TEMPLATE("manifolds from random pairs are finite, unit-normal and never deeper than the refined depth", T, float,
                   double) {
    scenes::Random rng(33);
    const Shape<T> shapes[] = {Box<T>(T(0.5), T(0.3), T(0.7)), Sphere<T>(T(0.4)),     Capsule<T>(T(0.25), T(0.5)),
                               Cylinder<T>(T(0.4), T(0.4)),    Cone<T>(T(0.5), T(1)), make_regular_prism(5, T(0.5), T(0.4))};
    int contacts = 0;
    for (int k = 0; k < 4000; ++k) {
        const Shape<T>& a = shapes[rng.index(6)];
        const Shape<T>& b = shapes[rng.index(6)];
        const Transform<T> ta{rng.in_box(Vec3<T>{T(0.7), T(0.7), T(0.7)}), rng.rotation<T>()};
        const Transform<T> tb{rng.in_box(Vec3<T>{T(0.7), T(0.7), T(0.7)}), rng.rotation<T>()};
        const ContactManifold<T> m = generate_contacts(a, ta, b, tb, T(0.02));
        CHECK(m.count >= 0);
        CHECK(m.count <= 4);
        if (m.count == 0) continue;
        ++contacts;
        CHECK(near(length(m.normal), T(1), T(1e-4)));
        for (int i = 0; i < m.count; ++i) {
            CHECK(is_finite(m.points[i].point_a));
            CHECK(is_finite(m.points[i].point_b));
            CHECK(std::isfinite(m.points[i].depth));
            CHECK(m.points[i].depth >= T(-0.02) - T(1e-4));
        }
    }
    CHECK(contacts > 2000);
}

namespace {

template <class T>
bool same_bits(const Vec3<T>& u, const Vec3<T>& v) {
    return std::memcmp(&u, &v, sizeof u) == 0;
}

}  // namespace

TEST_CASE_TEMPLATE("regression: collide(A, B) and collide(B, A) agree bit for bit for every pair of kinds, centres together too",
                   T, float, double) {
    // The round pairs used to answer in the order given: round-off apart each way round, and where
    // the normal is free (coincident centres) another normal. Two boxes still do (their answers
    // agree to rounding, checked apart), so a face normal of an unrotated first box stays exact.
    scenes::Random rng(34);
    const Shape<T> shapes[] = {Box<T>(T(0.5), T(0.3), T(0.7)), Sphere<T>(T(0.4)),     Capsule<T>(T(0.25), T(0.5)),
                               Cylinder<T>(T(0.4), T(0.4)),    Cone<T>(T(0.5), T(1)), make_regular_prism(5, T(0.5), T(0.4))};
    int hits = 0;
    for (int k = 0; k < 36 * 40; ++k) {
        const Shape<T>& a = shapes[k % 6];
        const Shape<T>& b = shapes[k / 6 % 6];
        const Transform<T> ta{rng.in_box(Vec3<T>{T(0.7), T(0.7), T(0.7)}), rng.rotation<T>()};
        Transform<T> tb{ta.position + rng.direction<T>() * rng.uniform(T(0), T(1.2)), rng.rotation<T>()};
        if (k / 36 % 4 == 0) tb.position = ta.position;
        CAPTURE(k);
        const Penetration<T> ab = collide(a, ta, b, tb), ba = collide(b, tb, a, ta);
        REQUIRE(ab.hit == ba.hit);
        CHECK(intersect(a, ta, b, tb) == ab.hit);
        CHECK(intersect(b, tb, a, ta) == ab.hit);
        if (!ab.hit) continue;
        ++hits;
        if (k % 6 == 0 && k / 6 % 6 == 0) {  // two boxes
            // With the centres together, axes of equal overlap tie and either way may take another.
            const T tolerance = T(64) * ScalarTraits<T>::epsilon;
            CHECK(near(ab.depth, ba.depth, tolerance));
            if (tb.position != ta.position) {
                CHECK(near(ab.normal, -ba.normal, tolerance));
                CHECK(near(ab.point_a, ba.point_b, tolerance));
                CHECK(near(ab.point_b, ba.point_a, tolerance));
            }
            continue;
        }
        CHECK(same_bits(ab.normal, -ba.normal));
        CHECK(same_bits(ab.point_a, ba.point_b));
        CHECK(same_bits(ab.point_b, ba.point_a));
        CHECK(std::memcmp(&ab.depth, &ba.depth, sizeof(T)) == 0);
    }
    CHECK(hits > 36 * 20);
}

TEST_CASE_TEMPLATE("regression: a box lying flat on another gets the same contact point either way round", T, float, double) {
    // collide() took the incident box's support corner as the point whenever it lay over the
    // reference face, though a whole face of that box was as deep: a 0.5 m cube resting 0.1 deep
    // on a 1 m one got a corner of its face one way round and the face's middle the other, 0.71 m
    // apart. Now both give the middle of the overlap, to rounding, whatever the two boxes' turn
    // about the normal, the overhang, and the pose of the whole pair.
    scenes::Random rng(35);
    const Shape<T> large = Box<T>(T(1), T(0.6), T(0.8)), small = Box<T>(T(0.5), T(0.3), T(0.4));
    for (int k = 0; k < 200; ++k) {
        CAPTURE(k);
        const Quat<T> whole = k < 20 ? Quat<T>::identity() : rng.rotation<T>();
        const Quat<T> turn = k < 10 ? Quat<T>::identity() : Quat<T>::from_axis_angle(Vec3<T>::unit_y(), rng.uniform(T(-3), T(3)));
        const Vec3<T> offset{rng.uniform(T(-1.2), T(1.2)), T(0.6 + 0.3 - 0.05), rng.uniform(T(-1), T(1))};
        const Transform<T> ta{Vec3<T>{T(2), T(-1), T(3)}, whole};
        const Transform<T> tb{ta.position + rotate(whole, offset), whole * turn};
        const Penetration<T> ab = collide(large, ta, small, tb), ba = collide(small, tb, large, ta);
        REQUIRE(ab.hit == ba.hit);
        if (!ab.hit) continue;
        const T tolerance = std::is_same_v<T, float> ? T(1e-5) : T(1e-12);
        CHECK(near(ab.depth, T(0.05), T(20) * tolerance));
        CHECK(near(ab.point_a, ba.point_b, tolerance));
        CHECK(near(ab.point_b, ba.point_a, tolerance));
    }
}

// Two finite poses at ±max of T are farther apart than T holds: the offset overflowed to inf,
// and two boxes there "hit" with depth inf and NaN points. Nothing spans that distance.
TEST_CASE_TEMPLATE("regression: shapes at opposite ends of T's range do not touch", T, float, double) {
    const T far = std::numeric_limits<T>::max();
    const Shape<T> box = Box<T>(T(1), T(1), T(1));
    const Shape<T> ball = Sphere<T>(T(1));
    for (const Vec3<T>& axis : {Vec3<T>::unit_x(), Vec3<T>::unit_y(), Vec3<T>::unit_z()}) {
        const Transform<T> a{axis * far, Quat<T>::identity()}, b{axis * -far, Quat<T>::identity()};
        CHECK_FALSE(collide(box, a, box, b).hit);
        CHECK_FALSE(intersect(box, a, box, b));
        CHECK_FALSE(collide(ball, a, box, b).hit);
        CHECK_FALSE(intersect(box, b, ball, a));
    }
}

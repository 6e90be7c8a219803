// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A sphere against a cylinder or a cone in closed form (sphere_solid.hpp): hand-computed rim
// cases, and random pairs checked against an independent computation in double. The least depth
// of two convex shapes is the least, over directions u, of h_A(u) + h_B(-u) (their support
// functions); for a solid S and a sphere of centre c and radius r that is r + h_S(u) - c·u, and
// h_S has a closed form for both solids (written here, not taken from the library).
#include "support/approx.hpp"

#include "scenes/random.hpp"

#include <xeno/collide/collide.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace xeno;
using xeno::test::near;

namespace {

struct RefSolid {
    bool cone = false;
    double radius = 0, half_height = 0, height = 0;  // half_height: cylinder; height: cone
    Vec3<double> position;
    Quat<double> orientation;

    Vec3<double> local(const Vec3<double>& world_point) const { return inverse_rotate(orientation, world_point - position); }
    /// h_S(u) for a unit u (world).
    double support(const Vec3<double>& u) const {
        const Vec3<double> d = inverse_rotate(orientation, u);
        const double across = std::sqrt(d.x * d.x + d.z * d.z);
        const double h = cone ? std::max(0.75 * height * d.y, -0.25 * height * d.y + radius * across)
                              : radius * across + half_height * std::abs(d.y);
        return h + dot(position, u);
    }
    /// How far a point is outside the solid along its worst face (≤ 0 inside).
    double outside(const Vec3<double>& world_point) const {
        const Vec3<double> p = local(world_point);
        const double rho = std::sqrt(p.x * p.x + p.z * p.z);
        if (!cone) return std::max(rho - radius, std::abs(p.y) - half_height);
        const double base = -0.25 * height, slant = std::sqrt(radius * radius + height * height);
        return std::max(base - p.y, ((rho - radius) * height + (p.y - base) * radius) / slant);
    }
};

template <class T>
Vec3<double> to_double(const Vec3<T>& v) {
    return {double(v.x), double(v.y), double(v.z)};
}
template <class T>
Quat<double> to_double(const Quat<T>& q) {
    return {double(q.w), double(q.x), double(q.y), double(q.z)};
}

std::vector<Vec3<double>> golden_spiral_directions(int n) {
    std::vector<Vec3<double>> out;
    const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / n, ring = std::sqrt(1.0 - y * y);
        out.push_back({ring * std::cos(golden * i), y, ring * std::sin(golden * i)});
    }
    return out;
}

}  // namespace

TEST_CASE_TEMPLATE("regression: a sphere on a cylinder's or a cone's rim gets the exact normal, depth and points", T, float,
                   double) {
    // MPR stopped within its tolerance on the rim's curve: these three cases had normals 0.85°,
    // 6.5° and 5.3° off, depths 0.2 % too deep and the solid's point 1.5–2.1 mm outside it.
    const Shape<T> ball = Sphere<T>(T(0.3));
    const Transform<T> origin{};
    {  // nearest the rim (0.5, 1, 0): distance √0.08, along (1, 1, 0)/√2
        const Penetration<T> p =
            collide(Shape<T>(Cylinder<T>(T(0.5), T(1))), origin, ball, Transform<T>{{T(0.7), T(1.2), T(0)}, {}});
        REQUIRE(p.hit);
        CHECK(near(p.depth, T(0.3 - std::sqrt(0.08)), T(1e-6)));
        CHECK(near(p.normal, Vec3<T>{T(std::sqrt(0.5)), T(std::sqrt(0.5)), T(0)}, T(1e-6)));
        CHECK(near(p.point_a, Vec3<T>{T(0.5), T(1), T(0)}, T(1e-6)));
        CHECK(near(p.point_b, p.point_a - p.normal * p.depth, T(1e-6)));
    }
    {  // a cone's rim from below and outside: nearest the rim point at the centre's azimuth
        const Vec3<double> c{-0.5129, -0.3828, -0.3882};
        const double rho = std::sqrt(c.x * c.x + c.z * c.z);
        const Vec3<double> rim{c.x * 0.6 / rho, -0.35, c.z * 0.6 / rho};
        const Penetration<T> p =
            collide(Shape<T>(Cone<T>(T(0.6), T(1.4))), origin, ball, Transform<T>{{T(c.x), T(c.y), T(c.z)}, {}});
        REQUIRE(p.hit);
        CHECK(near(double(p.depth), 0.3 - length(c - rim), 1e-6));
        CHECK(near(to_double(p.normal), normalized(c - rim), 1e-6));
        CHECK(near(to_double(p.point_a), rim, 1e-6));
    }
}

TEST_CASE_TEMPLATE("a sphere against a cylinder or a cone: the least depth over all directions, either way round", T, float,
                   double) {
    scenes::Random rng(41);
    const std::vector<Vec3<double>> directions = golden_spiral_directions(4000);
    const double tolerance = std::is_same_v<T, float> ? 2e-5 : 1e-10;
    int hits = 0, inside = 0;
    for (int k = 0; k < 400; ++k) {
        CAPTURE(k);
        RefSolid ref;
        ref.cone = k % 2 == 1;
        ref.radius = double(rng.uniform(T(0.2), T(1)));
        ref.half_height = double(rng.uniform(T(0.1), T(1)));
        ref.height = 2 * ref.half_height;
        const Shape<T> solid =
            ref.cone ? Shape<T>(Cone<T>(T(ref.radius), T(ref.height))) : Shape<T>(Cylinder<T>(T(ref.radius), T(ref.half_height)));
        const Transform<T> solid_pose{rng.in_box(Vec3<T>{T(1), T(1), T(1)}), rng.rotation<T>()};
        ref.position = to_double(solid_pose.position);
        ref.orientation = to_double(solid_pose.orientation);
        const T r = rng.uniform(T(0.05), T(0.6));
        // Centres from inside the solid to just beyond the ball's reach of it.
        const Transform<T> ball_pose{solid_pose.position + rng.in_box(Vec3<T>{T(1.2), T(1.2), T(1.2)}), rng.rotation<T>()};
        const Shape<T> ball = Sphere<T>(r);
        const Vec3<double> c = to_double(ball_pose.position);
        const auto depth_along = [&](const Vec3<double>& u) { return double(r) + ref.support(u) - dot(c, u); };
        double least = depth_along(directions[0]);
        for (const Vec3<double>& u : directions) least = std::min(least, depth_along(u));
        const Penetration<T> p = collide(solid, solid_pose, ball, ball_pose);
        const Penetration<T> q = collide(ball, ball_pose, solid, solid_pose);
        CHECK(intersect(solid, solid_pose, ball, ball_pose) == p.hit);
        CHECK(q.hit == p.hit);
        if (!p.hit) {
            CHECK(least <= 1e-2);  // the sampled directions' least depth: near the true one, never below
            continue;
        }
        ++hits;
        inside += ref.outside(c) < 0;
        const Vec3<double> n = to_double(p.normal);
        CHECK(near(length(n), 1.0, tolerance));
        CHECK(std::abs(double(p.depth) - depth_along(n)) <= tolerance);  // the depth along its own normal
        CHECK(double(p.depth) <= least + tolerance);                     // and no direction shallower
        // point_b on the ball, point_a on the solid's surface (on its support plane along n, not outside it)
        CHECK(length(to_double(p.point_b) - (c - n * double(r))) <= tolerance);
        CHECK(length(to_double(p.point_a) - (to_double(p.point_b) + n * double(p.depth))) <= tolerance);
        CHECK(std::abs(ref.support(n) - dot(to_double(p.point_a), n)) <= tolerance);
        CHECK(ref.outside(to_double(p.point_a)) <= tolerance);
        // Either way round: the same contact, seen from the other side, bit for bit.
        CHECK(q.depth == p.depth);
        CHECK(q.normal == -p.normal);
        CHECK(q.point_a == p.point_b);
        CHECK(q.point_b == p.point_a);
    }
    CHECK(hits > 80);  // 108 of the 400
    CHECK(inside > 10);
}

TEST_CASE_TEMPLATE("a sphere's manifold with a cylinder or a cone is its one exact contact, speculative within the margin", T,
                   float, double) {
    const Shape<T> ball = Sphere<T>(T(0.25));
    const Shape<T> cylinder = Cylinder<T>(T(0.5), T(1));
    const Transform<T> origin{};
    // Resting on the cap, 1 cm deep; then 2 cm above it, within a 5 cm margin.
    ContactManifold<T> m = generate_contacts(cylinder, origin, ball, Transform<T>{{T(0.1), T(1.24), T(0.2)}, {}}, T(0.05));
    REQUIRE(m.count == 1);
    CHECK(near(m.normal, Vec3<T>::unit_y()));
    CHECK(near(m.points[0].depth, T(0.01)));
    CHECK(near(m.points[0].point_a, Vec3<T>{T(0.1), T(1), T(0.2)}));
    m = generate_contacts(cylinder, origin, ball, Transform<T>{{T(0.1), T(1.27), T(0.2)}, {}}, T(0.05));
    REQUIRE(m.count == 1);
    CHECK(near(m.points[0].depth, T(-0.02)));
    CHECK(generate_contacts(cylinder, origin, ball, Transform<T>{{T(0.1), T(1.31), T(0.2)}, {}}, T(0.05)).count == 0);
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Ray casts and point tests against every shape type, compared with closed-form hits; then the
// world's queries.
#include "support/approx.hpp"
#include "support/sim.hpp"

#include "scenes/random.hpp"

#include <xeno/collide/raycast.hpp>
#include <xeno/shape/polyhedra.hpp>

using namespace xeno;
using xeno::test::near;

namespace {
template <class T>
Ray<T> ray(const Vec3<T>& from, const Vec3<T>& to) {
    return {from, normalized(to - from), length(to - from)};
}
}  // namespace

TEST_CASE_TEMPLATE("rays hit every shape where the closed form says", T, float, double) {
    const Transform<T> at_origin{};
    // Sphere r = 1 from x = -5: enters at x = -1, distance 4, normal -x.
    auto s = raycast(Shape<T>(Sphere<T>(T(1))), at_origin, ray(Vec3<T>{T(-5), T(0), T(0)}, Vec3<T>{T(5), T(0), T(0)}));
    REQUIRE(s);
    CHECK(near(s->distance, T(4)));
    CHECK(near(s->fraction, T(0.4)));
    CHECK(near(s->normal, -Vec3<T>::unit_x()));
    // Off-axis: the chord at height 0.6 starts at x = -0.8.
    s = raycast(Shape<T>(Sphere<T>(T(1))), at_origin, ray(Vec3<T>{T(-5), T(0.6), T(0)}, Vec3<T>{T(5), T(0.6), T(0)}));
    REQUIRE(s);
    CHECK(near(s->point.x, T(-0.8), T(1e-5)));
    CHECK(near(s->normal, Vec3<T>{T(-0.8), T(0.6), T(0)}, T(1e-5)));
    // Box from above onto its top face.
    auto b = raycast(Shape<T>(Box<T>(T(1), T(0.5), T(2))), at_origin, ray(Vec3<T>{T(0.3), T(4), T(-1)}, Vec3<T>{T(0.3), T(-4), T(-1)}));
    REQUIRE(b);
    CHECK(near(b->distance, T(3.5)));
    CHECK(near(b->normal, Vec3<T>::unit_y()));
    // Capsule (r 0.5, half length 1, along y): side at x = -0.5, end cap top at y = 1.5.
    auto c = raycast(Shape<T>(Capsule<T>(T(0.5), T(1))), at_origin, ray(Vec3<T>{T(-3), T(0.7), T(0)}, Vec3<T>{T(3), T(0.7), T(0)}));
    REQUIRE(c);
    CHECK(near(c->distance, T(2.5)));
    CHECK(near(c->normal, -Vec3<T>::unit_x()));
    c = raycast(Shape<T>(Capsule<T>(T(0.5), T(1))), at_origin, ray(Vec3<T>{T(0), T(5), T(0)}, Vec3<T>{T(0), T(-5), T(0)}));
    REQUIRE(c);
    CHECK(near(c->distance, T(3.5)));
    CHECK(near(c->normal, Vec3<T>::unit_y()));
    // Cylinder (r 1, half height 0.5): cap from above, side from the side.
    auto y = raycast(Shape<T>(Cylinder<T>(T(1), T(0.5))), at_origin, ray(Vec3<T>{T(0.5), T(3), T(0.5)}, Vec3<T>{T(0.5), T(-3), T(0.5)}));
    REQUIRE(y);
    CHECK(near(y->distance, T(2.5)));
    CHECK(near(y->normal, Vec3<T>::unit_y()));
    y = raycast(Shape<T>(Cylinder<T>(T(1), T(0.5))), at_origin, ray(Vec3<T>{T(0), T(0.2), T(-4)}, Vec3<T>{T(0), T(0.2), T(4)}));
    REQUIRE(y);
    CHECK(near(y->distance, T(3)));
    CHECK(near(y->normal, -Vec3<T>::unit_z()));
    CHECK_FALSE(raycast(Shape<T>(Cylinder<T>(T(1), T(0.5))), at_origin, ray(Vec3<T>{T(1.5), T(3), T(0)}, Vec3<T>{T(1.5), T(-3), T(0)})));
    // Cone (r 1, H 2): base at y = -0.5, apex at 1.5. Horizontal ray at y = 0.5 meets the side
    // where the radius is (1.5 - 0.5) / 2 = 0.5; from below it meets the base.
    const Shape<T> cone = Cone<T>(T(1), T(2));
    auto k = raycast(cone, at_origin, ray(Vec3<T>{T(-3), T(0.5), T(0)}, Vec3<T>{T(3), T(0.5), T(0)}));
    REQUIRE(k);
    CHECK(near(k->distance, T(2.5), T(1e-5)));
    CHECK(near(k->normal, normalized(Vec3<T>{T(-2), T(1), T(0)}), T(1e-5)));
    k = raycast(cone, at_origin, ray(Vec3<T>{T(0.2), T(-3), T(0.2)}, Vec3<T>{T(0.2), T(3), T(0.2)}));
    REQUIRE(k);
    CHECK(near(k->distance, T(2.5)));
    CHECK(near(k->normal, -Vec3<T>::unit_y()));
    CHECK_FALSE(raycast(cone, at_origin, ray(Vec3<T>{T(-3), T(1.4), T(0.5)}, Vec3<T>{T(3), T(1.4), T(0.5)})));
    // Hull: a tetrahedron with a face down at y = -h/4 of its height.
    const ConvexPolyhedron<T> tetra = make_tetrahedron(T(1));
    T bottom = T(0);
    for (const Vec3<T>& v : tetra.vertices()) bottom = std::min(bottom, v.y);
    auto t = raycast(Shape<T>(tetra), at_origin, ray(Vec3<T>{T(0), T(-3), T(0)}, Vec3<T>{T(0), T(3), T(0)}));
    REQUIRE(t);
    CHECK(near(t->point.y, bottom, T(1e-5)));
    CHECK(near(t->normal, -Vec3<T>::unit_y(), T(1e-5)));
}

TEST_CASE_TEMPLATE("rays respect the pose, the length and a start inside", T, float, double) {
    const Shape<T> box = Box<T>(T(0.5), T(0.5), T(0.5));
    const Transform<T> pose{{T(10), T(2), T(0)}, Quat<T>::from_axis_angle(Vec3<T>::unit_y(), ScalarTraits<T>::pi / 4)};
    // Along x at the box's height: a turned cube's edge faces the ray at 10 - sqrt(0.5).
    auto h = raycast(box, pose, Ray<T>{{T(0), T(2), T(0)}, Vec3<T>::unit_x(), T(20)});
    REQUIRE(h);
    CHECK(near(h->distance, T(10) - std::sqrt(T(0.5)), T(1e-5)));
    CHECK_FALSE(raycast(box, pose, Ray<T>{{T(0), T(2), T(0)}, Vec3<T>::unit_x(), T(9)}));  // too short
    auto inside = raycast(box, pose, Ray<T>{{T(10), T(2.1), T(0)}, Vec3<T>::unit_y(), T(5)});
    REQUIRE(inside);
    CHECK(inside->distance == T(0));
    CHECK(near(inside->normal, -Vec3<T>::unit_y()));
    CHECK(contains_point(box, pose, Vec3<T>{T(10.6), T(2), T(0)}));   // within the turned cube's corner
    CHECK_FALSE(contains_point(box, pose, Vec3<T>{T(10.5), T(2), T(0.5)}));
}

TEST_CASE_TEMPLATE("random rays agree with the support function: the hit is on the surface", T, float, double) {
    scenes::Random rng(41);
    const Shape<T> shapes[] = {Sphere<T>(T(0.7)), Box<T>(T(0.5), T(0.3), T(0.8)), Capsule<T>(T(0.3), T(0.5)), Cylinder<T>(T(0.4), T(0.6)),
                               Cone<T>(T(0.5), T(1.2)), make_regular_prism(7, T(0.6), T(0.4))};
    int hits = 0;
    for (const Shape<T>& shape : shapes) {
        for (int k = 0; k < 500; ++k) {
            const Vec3<T> from = rng.direction<T>() * T(4);
            const Vec3<T> aim = rng.in_box(Vec3<T>{T(0.5), T(0.5), T(0.5)});
            const auto hit = raycast(shape, Transform<T>{}, ray(from, aim));
            if (!hit) continue;
            ++hits;
            // On the surface: the support along the normal reaches the hit point's plane.
            CHECK(near(dot(support(shape, hit->normal), hit->normal), dot(hit->point, hit->normal), T(2e-3)));
            CHECK(contains_point(shape, Transform<T>{}, hit->point + hit->normal * T(-1e-3)));
            CHECK_FALSE(contains_point(shape, Transform<T>{}, hit->point - normalized(aim - from) * T(1e-3)));
        }
    }
    CHECK(hits > 1500);
}

TEST_CASE_TEMPLATE("the world's ray casts find the nearest body and every body in order", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const BodyId ground = scenes::add_ground(w);
    std::vector<BodyId> boxes;
    for (int i = 0; i < 4; ++i) boxes.push_back(scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(2) * T(i + 1), T(0.5), T(0)}));
    const Ray<T> along{{T(0), T(0.5), T(0)}, Vec3<T>::unit_x(), T(100)};
    const auto first = w.raycast(along);
    REQUIRE(first);
    CHECK(first->body == boxes[0]);
    CHECK(near(first->hit.distance, T(1.5)));
    const auto all = w.raycast_all(along);
    REQUIRE(all.size() == 4);
    for (int i = 0; i < 4; ++i) CHECK(all[i].body == boxes[i]);
    const auto down = w.raycast(Ray<T>{{T(-5), T(10), T(0)}, -Vec3<T>::unit_y(), T(100)});
    REQUIRE(down);
    CHECK(down->body == ground);
    CHECK(near(down->hit.distance, T(10)));
    CHECK(w.query_point(Vec3<T>{T(4.2), T(0.7), T(0.1)}) == std::vector<BodyId>{boxes[1]});
    CHECK(w.query_point(Vec3<T>{T(5), T(0.5), T(0)}).empty());
    CHECK(w.query_aabb(Aabb<T>{{T(3.8), T(0.1), T(-0.2)}, {T(6.2), T(0.2), T(0.2)}}).size() == 2);  // two boxes
    CHECK(w.query_aabb(Aabb<T>{{T(3.8), T(-0.1), T(-0.2)}, {T(6.2), T(0.2), T(0.2)}}).size() == 3);  // and the ground
    CHECK_THROWS_AS(w.raycast(Ray<T>{{}, Vec3<T>{T(1), T(1), T(0)}, T(1)}), InvalidArgument);
}

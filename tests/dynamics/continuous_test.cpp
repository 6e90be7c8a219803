// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Continuous detection by speculative contacts: a body's broad-phase box and its contact margin
// grow with the distance it can travel in a step, so the contact that stops it exists before it
// reaches the wall, and the speculative row lets it close the gap but not cross it.
#include "support/approx.hpp"
#include "support/sim.hpp"

using namespace xeno;

TEST_CASE_TEMPLATE("a small box fired at 300 m/s never passes through a thin wall", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const T angle : {T(0), T(0.3), T(-0.7)}) {
        World<T> w(C::settings());
        scenes::add_ground(w);
        BodyDef<T> wall;
        wall.type = BodyType::static_body;
        wall.position = {T(10), T(2), T(0)};
        const BodyId wall_id = w.create_body(Box<T>(T(0.05), T(2), T(3)), wall);
        BodyDef<T> bullet;
        bullet.fast = true;  // no speed cap
        bullet.position = {T(0), T(1.5), T(0)};
        bullet.orientation = Quat<T>::from_axis_angle(Vec3<T>{T(0), T(1), T(1)}, angle);
        bullet.linear_velocity = {T(300) * std::cos(angle), T(0), T(300) * std::sin(angle) * T(0.1)};
        bullet.angular_velocity = {T(0), T(40) * angle, T(0)};
        const BodyId id = w.create_body(Box<T>(T(0.05), T(0.05), T(0.05)), bullet);
        T furthest = T(0);
        test::simulate(w, T(1), [&](int) { furthest = std::max(furthest, w.body(id).position().x); });
        CAPTURE(angle);
        CHECK(furthest < T(10) - T(0.05));  // never past the wall's near face
        CHECK(w.body(id).position().x < T(10));
        CHECK(w.contains(wall_id));
    }
}

TEST_CASE_TEMPLATE("without the fast flag the speed cap applies", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    WorldSettings<T> s = C::settings();
    s.gravity = Vec3<T>::zero();
    s.max_linear_speed = T(100);
    World<T> w(s);
    BodyDef<T> d;
    d.linear_velocity = {T(300), T(0), T(0)};
    const BodyId slow = w.create_body(Sphere<T>(T(0.1)), d);
    d.fast = true;
    d.position = {T(0), T(5), T(0)};
    const BodyId fast = w.create_body(Sphere<T>(T(0.1)), d);
    test::simulate(w, T(0.5));
    CHECK(test::near(w.body(slow).linear_velocity().x, T(100), T(1e-4)));
    CHECK(test::near(w.body(fast).linear_velocity().x, T(300), T(1e-4)));
}

TEST_CASE_TEMPLATE("regression: a fast body of every convex kind landing flat at its speed cap stops on the surface", C,
                   XENO_TEST_CONFIGS) {
    // One biased sweep a substep left a share of the approach uneven between a face's points, a
    // share of the speed: at 10⁵ m/s (float) a cone went 4 cm into the floor and hopped 6 cm; at
    // 10⁶ it sank 55 cm and was thrown 4.8 m up; a double box at 10⁸ m/s slid off at 91 m/s, and
    // at the old double cap of 10³⁰ every kind but the sphere and capsule sank through. A body
    // dropped flat on a face stops there: no bounce (restitution 0), no slide, no spin.
    using T = typename C::T;
    const T cap = detail::max_fast_speed<T>();
    std::vector<Vec3<T>> prism;  // a 12-gon prism as a hull, lying on one of its 12-gon faces
    for (int i = 0; i < 12; ++i) {
        const T angle = T(i) * T(2) * ScalarTraits<T>::pi / T(12);
        for (const T y : {T(-0.4), T(0.4)}) prism.push_back({T(0.5) * std::cos(angle), y, T(0.5) * std::sin(angle)});
    }
    const std::pair<Shape<T>, T> kinds[] = {
        {Sphere<T>(T(0.5)), T(0.5)},          {Box<T>(T(0.5), T(0.5), T(0.5)), T(0.5)},
        {Capsule<T>(T(0.3), T(0.5)), T(0.8)}, {Cylinder<T>(T(0.5), T(0.5)), T(0.5)},
        {Cone<T>(T(0.5), T(1)), T(0.25)},     {make_convex_hull(prism).polyhedron, T(0.4)},
    };
    for (const T speed : {cap / T(10), cap}) {
        for (const auto& [shape, rest_height] : kinds) {
            World<T> w(C::settings());
            BodyDef<T> ground;
            ground.type = BodyType::static_body;
            ground.position = {T(0), T(-1), T(0)};
            w.create_body(Box<T>(T(1000), T(1), T(1000)), ground);
            BodyDef<T> def;
            def.fast = true;
            def.position = {T(0), T(10), T(0)};
            def.linear_velocity = {T(0), -speed, T(0)};
            const BodyId id = w.create_body(shape, def);
            T lowest = def.position.y, highest_after = T(0);
            test::simulate(w, T(1), [&](int step) {
                const T y = w.body(id).position().y;
                lowest = std::min(lowest, y);
                if (step > 0) highest_after = std::max(highest_after, y);
            });
            const Body<T>& b = w.body(id);
            CAPTURE(speed);
            const std::string kind = shape_name(shape);
            CAPTURE(kind);
            CHECK(lowest > rest_height - T(0.005));
            CHECK(highest_after < rest_height + T(0.005));
            CHECK(std::abs(b.position().y - rest_height) < T(0.002));
            CHECK(std::hypot(b.position().x, b.position().z) < T(0.01));
            CHECK(length(b.linear_velocity()) < T(1e-3));
            CHECK(length(b.angular_velocity()) < T(1e-2));
        }
    }
}

TEST_CASE_TEMPLATE("fast bodies are held below 1e6 m/s in float and 1e10 m/s in double", T, float, double) {
    // Beyond the cap a step's travel leaves what the impact sweeps were measured to stop
    // (docs/solver.md, "Very fast impacts: more biased sweeps").
    const T cap = std::is_same_v<T, float> ? T(1e6) : T(1e10);
    World<T> w;
    BodyDef<T> def;
    def.fast = true;
    def.linear_velocity = {T(100) * cap, T(0), T(0)};
    const BodyId id = w.create_body(Sphere<T>(T(0.5)), def);
    w.step(T(1) / T(60));
    CHECK(w.body(id).linear_velocity().x == doctest::Approx(cap));
}

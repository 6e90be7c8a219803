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

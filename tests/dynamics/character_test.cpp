// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The character controller of examples/scenes/character.hpp, which uses only the public API
// (shape casts, queries, move_kinematic): it walks up a step and not up a wall, slides along a
// wall it walks into at 45° with the speed's component along it, rides a kinematic platform, and
// never ends a step inside anything. Default settings, float and double.
#include "scenes/character.hpp"
#include "support/sim.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace xeno;

namespace {

/// Walks for `seconds`, checking after every step that the capsule overlaps nothing but what it
/// stands on within the skin (the casts keep it a skin's width away).
template <class T>
int walk(World<T>& w, scenes::CharacterController<T>& hero, const Vec3<T>& velocity, T seconds) {
    int overlaps = 0;
    test::simulate(w, seconds, [&](int) {
        const Body<T>& b = w.body(hero.body());
        QueryFilter<T> others;
        others.ignore_body = hero.body();
        const Capsule<T> slimmer(T(0.3) - T(0.002), T(0.5));  // 2 mm inside the capsule
        overlaps += static_cast<int>(w.overlap_shape(slimmer, b.transform(), others).size());
        hero.update(velocity, w.settings().fixed_time_step);
    });
    return overlaps;
}

template <class T>
void static_box(World<T>& w, const Vec3<T>& half, const Vec3<T>& centre) {
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = centre;
    w.create_body(Box<T>(half), d);
}

}  // namespace

TEST_CASE_TEMPLATE("a character walks up a 0.25 m step but not up a 0.6 m one", T, float, double) {
    World<T> w;
    scenes::add_ground(w);
    static_box(w, Vec3<T>{T(2), T(0.125), T(2)}, Vec3<T>{T(4), T(0.125), T(0)});  // top at 0.25, from x = 2
    static_box(w, Vec3<T>{T(2), T(0.3), T(2)}, Vec3<T>{T(4), T(0.3), T(10)});     // top at 0.6, from x = 2
    scenes::CharacterController<T> low(w, Vec3<T>{T(0), T(0), T(0)});
    scenes::CharacterController<T> high(w, Vec3<T>{T(0), T(0), T(10)});
    low.update(Vec3<T>::zero(), w.settings().fixed_time_step);
    high.update(Vec3<T>::zero(), w.settings().fixed_time_step);
    w.step(w.settings().fixed_time_step);
    test::simulate(w, T(2.5), [&](int) {
        low.update(Vec3<T>{T(1.5), T(0), T(0)}, w.settings().fixed_time_step);
        high.update(Vec3<T>{T(1.5), T(0), T(0)}, w.settings().fixed_time_step);
    });
    CHECK(low.on_ground());
    CHECK(std::abs(low.feet().y - T(0.25)) < T(0.02));           // on the step
    CHECK(low.feet().x == doctest::Approx(3.75).epsilon(0.05));  // 1.5 m/s for 2.5 s, hardly slowed
    CHECK(high.on_ground());
    CHECK(std::abs(high.feet().y) < T(0.02));                    // still on the ground
    CHECK(std::abs(high.feet().x - (T(2) - T(0.3))) < T(0.03));  // stopped a radius (and a skin) short of it
}

TEST_CASE_TEMPLATE("a character walking into a wall at 45 degrees slides along it at v cos 45", T, float, double) {
    World<T> w;
    scenes::add_ground(w);
    static_box(w, Vec3<T>{T(10), T(1), T(0.25)}, Vec3<T>{T(0), T(1), T(-1.25)});  // the wall's face at z = -1
    scenes::CharacterController<T> hero(w, Vec3<T>{T(0), T(0), T(0)});
    hero.update(Vec3<T>::zero(), w.settings().fixed_time_step);
    w.step(w.settings().fixed_time_step);
    const T speed = T(2);
    const Vec3<T> diagonal = Vec3<T>{T(1), T(0), T(-1)} * (speed / std::sqrt(T(2)));
    // It reaches the wall (0.7 m away at 1.41 m/s across) after about 0.5 s; then 1.5 s along it.
    CHECK(walk(w, hero, diagonal, T(2)) == 0);
    const Vec3<T> feet = hero.feet();
    CHECK(feet.z > T(-1) + T(0.3) - T(0.005));  // against the wall, not in it
    CHECK(feet.z < T(-1) + T(0.3) + T(0.02));
    CHECK(feet.x == doctest::Approx(2.0 * 1.41421356 * 1.0).epsilon(0.03));  // x at v cos 45° all along: 2 s × 1.414 m/s
}

TEST_CASE_TEMPLATE("a character standing on a kinematic platform rides it, and never ends a step inside anything", T, float,
                   double) {
    World<T> w;
    scenes::add_ground(w);
    BodyDef<T> pd;
    pd.type = BodyType::kinematic;
    pd.position = {T(0), T(0.125), T(0)};
    const BodyId platform = w.create_body(Box<T>(T(2), T(0.125), T(2)), pd);
    scenes::CharacterController<T> hero(w, Vec3<T>{T(0), T(0.25), T(0)});
    const T dt = w.settings().fixed_time_step;
    int overlaps = 0;
    hero.update(Vec3<T>::zero(), dt);
    w.step(dt);
    REQUIRE(hero.on_ground());
    CHECK(hero.ground() == platform);
    const Vec3<T> start = hero.feet();
    for (int i = 1; i <= 120; ++i) {  // 1 m/s along x and 0.25 m/s up, for 2 s
        w.move_kinematic(platform, Vec3<T>{T(i) * dt, T(0.125) + T(0.25) * T(i) * dt, T(0)}, Quat<T>::identity(), dt);
        hero.update(Vec3<T>::zero(), dt);
        w.step(dt);
        QueryFilter<T> others;
        others.ignore_body = hero.body();
        overlaps +=
            static_cast<int>(w.overlap_shape(Capsule<T>(T(0.298), T(0.5)), w.body(hero.body()).transform(), others).size());
    }
    const Vec3<T> moved = hero.feet() - start;
    CHECK(std::abs(moved.x - T(2)) < T(0.05));
    CHECK(std::abs(moved.y - T(0.5)) < T(0.05));
    CHECK(hero.on_ground());
    CHECK(overlaps == 0);
}

TEST_CASE_TEMPLATE("a character walks on through a loose crate and pushes it ahead", T, float, double) {
    World<T> w;
    scenes::add_ground(w);
    const BodyId crate = scenes::add_box(w, Vec3<T>{T(0.2), T(0.2), T(0.2)}, Vec3<T>{T(1.5), T(0.2), T(0)});
    scenes::CharacterController<T> hero(w, Vec3<T>{T(0), T(0), T(0)});
    hero.update(Vec3<T>::zero(), w.settings().fixed_time_step);
    w.step(w.settings().fixed_time_step);
    CHECK(walk(w, hero, Vec3<T>{T(1.5), T(0), T(0)}, T(2)) == 0);  // contacts push the crate: never 2 mm into it
    // Kinematic: the crate's weight does not slow it (3 m in 2 s), and the crate went ahead of it.
    CHECK(hero.feet().x == doctest::Approx(3.0).epsilon(0.02));
    CHECK(hero.on_ground());
    const Vec3<T> c = w.body(crate).position();
    CHECK(c.x > T(2.5));
    CHECK(std::isfinite(c.x + c.y + c.z));
}

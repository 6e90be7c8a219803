// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Helpers for dynamics tests: worlds without sleeping, stepping for a time, measuring.
#pragma once

#include "scenes/scene.hpp"

#include <xeno/dynamics/world.hpp>

#include <cmath>
#include <functional>

namespace xeno::test {

/// Default settings with sleeping off: what holds a stack up must be the solver (issue 6).
template <class T>
WorldSettings<T> awake_settings() {
    WorldSettings<T> s;
    s.allow_sleeping = false;
    return s;
}

/// A test configuration: the scalar and the settings. Dynamics tests run in the defaults a user
/// gets (sleeping on) as well as with sleeping off (the solver alone), through one test template
/// instantiated for every XENO_TEST_CONFIGS entry; a test reads `using T = typename C::T;` and
/// builds its world from `C::settings()`.
template <class Scalar, bool Sleeping>
struct Config {
    using T = Scalar;
    static constexpr bool sleeping = Sleeping;
    static WorldSettings<T> settings() {
        WorldSettings<T> s;  // the defaults
        s.allow_sleeping = Sleeping;
        return s;
    }
    /// The same without gravity (collisions and free motion).
    static WorldSettings<T> weightless() {
        WorldSettings<T> s = settings();
        s.gravity = Vec3<T>::zero();
        return s;
    }
};

}  // namespace xeno::test

/// Every scalar with the default settings and with sleeping off.
#define XENO_TEST_CONFIGS                                                                                \
    xeno::test::Config<float, true>, xeno::test::Config<double, true>, xeno::test::Config<float, false>, \
        xeno::test::Config<double, false>

namespace xeno::test {

/// Steps `seconds` at the settings' fixed step, calling `each(step_index)` after every step.
template <class T>
void simulate(World<T>& world, T seconds, const std::function<void(int)>& each = {}) {
    const int steps = static_cast<int>(std::lround(seconds / world.settings().fixed_time_step));
    for (int i = 0; i < steps; ++i) {
        world.step(world.settings().fixed_time_step);
        if (each) each(i);
    }
}

/// Total kinetic energy of the world's bodies (J).
template <class T>
T kinetic_energy(const World<T>& world) {
    T e = T(0);
    world.for_each_body([&](BodyId, const Body<T>& b) { e += b.kinetic_energy(); });
    return e;
}

/// Angle (radians) by which q turned the body's y axis away from vertical... (yaw about y).
template <class T>
T yaw(const Quat<T>& q) {
    const Vec3<T> x = rotate(q, Vec3<T>::unit_x());
    return std::atan2(-x.z, x.x);
}

}  // namespace xeno::test

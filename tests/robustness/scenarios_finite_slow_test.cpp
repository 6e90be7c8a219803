// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Sane input never produces NaN (docs/conventions.md, "Errors"): every scene of the registry, in
// float and double, stepped 5 s at 60 Hz, with every body checked after every step: finite
// position, orientation and velocities, and an orientation of unit length within 1e-3.
#include "scenes/all.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>

using namespace xeno;

namespace {

/// The first body whose state is not finite or whose orientation is not unit, described; empty
/// when every body is fine.
template <class T>
std::string first_bad_body(const World<T>& world) {
    std::string bad;
    world.for_each_body([&](BodyId id, const Body<T>& b) {
        if (!bad.empty()) return;
        const Quat<T>& q = b.orientation();
        const bool finite =
            is_finite(b.position()) && is_finite(q) && is_finite(b.linear_velocity()) && is_finite(b.angular_velocity());
        const T unit_error = std::abs(std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z) - T(1));
        if (finite && unit_error <= T(1e-3)) return;
        std::ostringstream os;
        os << "body " << id.index << ": position " << b.position().x << ' ' << b.position().y << ' ' << b.position().z
           << ", |q| - 1 = " << unit_error << ", v " << b.linear_velocity().x << ' ' << b.linear_velocity().y << ' '
           << b.linear_velocity().z << ", w " << b.angular_velocity().x << ' ' << b.angular_velocity().y << ' '
           << b.angular_velocity().z;
        bad = os.str();
    });
    return bad;
}

}  // namespace

TEST_CASE_TEMPLATE("every scene stays finite with unit orientations after every step of 5 s", T, float, double) {
    for (const auto& entry : scenes::scene_list()) {
        const std::string& name = entry.first;  // not a structured binding: CAPTURE takes it into a lambda
        CAPTURE(name);
        World<T> world;
        const scenes::Scene scene = scenes::build<T>(name, world);
        const T dt = world.settings().fixed_time_step;
        std::string bad;
        int step = 0;
        for (; step < 300 && bad.empty(); ++step) {
            if (scene.before_step) scene.before_step(static_cast<double>(dt));
            world.step(dt);
            bad = first_bad_body(world);
        }
        CAPTURE(step);
        CHECK_MESSAGE(bad.empty(), bad);
        CHECK(world.body_count() > 0);
    }
}

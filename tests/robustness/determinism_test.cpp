// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Determinism within one process: the same scene built and stepped twice gives bitwise-identical
// body states after every step (hash of the raw bytes, state_hash.hpp). Across processes and
// compilers: xeno_determinism, compare_runs.cmake and scripts/test.sh (docs/robustness.md).
#include "robustness/state_hash.hpp"
#include "scenes/all.hpp"

#include <doctest/doctest.h>

#include <set>
#include <string>
#include <vector>

using namespace xeno;

namespace {

/// The state hash after each of `steps` steps of the named scene, built in a fresh world.
template <class T>
std::vector<std::uint64_t> per_step_hashes(const std::string& scene, int steps) {
    World<T> world;
    scenes::build<T>(scene, world);
    std::vector<std::uint64_t> hashes;
    hashes.reserve(static_cast<std::size_t>(steps));
    for (int i = 0; i < steps; ++i) {
        world.step(world.settings().fixed_time_step);
        hashes.push_back(test::state_hash(world));
    }
    return hashes;
}

template <class T>
void check_stepped_twice(const std::string& scene, int steps) {
    CAPTURE(scene);
    const std::vector<std::uint64_t> first = per_step_hashes<T>(scene, steps);
    const std::vector<std::uint64_t> second = per_step_hashes<T>(scene, steps);
    REQUIRE(first.size() == second.size());
    int first_difference = -1;
    for (std::size_t i = 0; i < first.size() && first_difference < 0; ++i)
        if (first[i] != second[i]) first_difference = static_cast<int>(i);
    CHECK(first_difference == -1);
    // The scene really moves: the hash changes from step to step (until bodies come to rest).
    CHECK(std::set<std::uint64_t>(first.begin(), first.end()).size() > 10);
}

}  // namespace

TEST_CASE_TEMPLATE("a scene stepped twice in one process gives identical state hashes after every step", T, float, double) {
    check_stepped_twice<T>("mixed-pile", 120);  // 2 s, every shape kind
    check_stepped_twice<T>("pyramid", 120);     // 2 s, 210 boxes
    check_stepped_twice<T>("rain", 180);        // 3 s, 120 impacts
}

TEST_CASE_TEMPLATE("the state hash sees a one-ulp change of one body", T, float, double) {
    World<T> world;
    scenes::build<T>("column", world);
    const std::uint64_t before = test::state_hash(world);
    BodyId last;
    world.for_each_body([&](BodyId id, const Body<T>&) { last = id; });
    Body<T>& b = world.body(last);
    Vec3<T> v = b.linear_velocity();
    v.x = std::nextafter(v.x, T(1));
    b.set_linear_velocity(v);
    CHECK(test::state_hash(world) != before);
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The crowd at the default settings (docs/robustness.md, "Crowds"): 3,000 unit spheres
// at one point overlap in 4,498,500 pairs; a step collides and solves at most max_contact_pairs
// of them and stays finite. (Its time and memory: bench/crowd_bench.cpp.)
#include <xeno/xeno.hpp>

#include <doctest/doctest.h>

#include <memory>

using namespace xeno;

TEST_CASE_TEMPLATE("3,000 spheres spawned at one point: default settings keep each step to the contact budget", T, float,
                   double) {
    World<T> w;
    const auto sphere = std::make_shared<const Shape<T>>(Sphere<T>(T(0.5)));
    BodyDef<T> d;
    d.position = {T(0), T(20), T(0)};
    const std::size_t n = 3000;
    for (std::size_t i = 0; i < n; ++i) w.create_body(sphere, d);
    for (int step = 0; step < 2; ++step) {
        w.step(T(1) / T(60));
        const StepStats& st = w.last_step_stats();
        CHECK(st.broad_pairs == n * (n - 1) / 2);
        CHECK(st.broad_pairs - st.dropped_pairs <= std::size_t(w.settings().max_contact_pairs));
        CHECK(w.contacts().size() <= std::size_t(w.settings().max_contact_pairs));
    }
    w.for_each_body([](BodyId, const Body<T>& b) {
        REQUIRE(is_finite(b.position()));
        REQUIRE(is_finite(b.linear_velocity()));
    });
}

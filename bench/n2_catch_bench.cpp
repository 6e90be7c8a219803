// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Catch2 statistics for a few detection passes of the N² benchmark (n2_detection.hpp): warm
// sweep-and-prune and tree passes (the broad phase kept between samples, as a world keeps it from
// one step to the next), a cold sweep-and-prune pass, and the thesis's brute force at 500 boxes.
// The full table, with multi-second brute-force passes that Catch2's sampling would repeat a
// hundred times, is the standalone program xeno_n2_bench.
//
//   xeno_n2_catch_bench "[n2]"     (add --benchmark-samples 20 for a quicker run)
#define CATCH_CONFIG_ENABLE_BENCHMARKING
#include <catch2/catch.hpp>

#include "n2_detection.hpp"

#include <string>

using namespace xeno;
using namespace xeno::bench;

TEST_CASE("one detection pass on the N² benchmark scene", "[n2][bench]") {
    for (const std::size_t n : {std::size_t(1000), std::size_t(10000)}) {
        const Scene<double> scene = make_box_scene<double>(n);
        Detector<double> sap(Strategy::sap), tree(Strategy::tree);
        sap.pass(scene);
        tree.pass(scene);
        BENCHMARK("sap warm, " + std::to_string(n) + " boxes") { return sap.pass(scene).contacts; };
        BENCHMARK("tree warm, " + std::to_string(n) + " boxes") { return tree.pass(scene).contacts; };
        BENCHMARK("sap cold, " + std::to_string(n) + " boxes") { return Detector<double>(Strategy::sap).pass(scene).contacts; };
    }
    const Scene<double> small = make_box_scene<double>(500);
    BENCHMARK("brute (MPR on every pair), 500 boxes") { return Detector<double>(Strategy::brute).pass(small).contacts; };
    BENCHMARK("brute_bounds, 500 boxes") { return Detector<double>(Strategy::brute_bounds).pass(small).contacts; };
}

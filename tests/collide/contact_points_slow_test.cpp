// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The 100,000-pair versions of contact_points_test.cpp's contract check and least_depth_test.cpp's
// depth check, float and double, against references computed from the support functions alone
// (support_reference.hpp):
//   contract: collide()'s contact points over every shape pair with sizes 0.1 … 10 m (up to
//             100:1), each on or inside its own shape within the depth (+ 1e-4 of the pair's size);
//   depth:    collide()'s depth ÷ the least depth over all directions (a dense search), per pair
//             kind, sizes 0.5 … 10 m.
//   build/tests/xeno_slow_tests -tc='*100,000*' -s
#include "collide/contact_points_checks.hpp"

#include <doctest/doctest.h>

using namespace xeno;

namespace {
#if defined(XENO_SANITIZE)
constexpr int kSlowPairs = 2'000;
#else
constexpr int kSlowPairs = 100'000;
#endif
}  // namespace

TEST_CASE_TEMPLATE("100,000 random pairs: contact points on or inside their own shapes within the depth", T, float, double) {
    const test::ContractResult r = test::check_contract<T>(71, kSlowPairs, 0.1, 10.0);
    MESSAGE(r.hits << " overlapping pairs, " << r.violations << " violations; worst (outside − depth) / size " << r.worst_excess
                   << " (" << r.worst_pair << "), worst |pa − pb − depth n| / size " << r.worst_offset);
    CHECK(r.hits > kSlowPairs / 4);
    CHECK(r.violations == 0);
    CHECK(r.worst_offset <= 1e-4);
}

// Issue 12, section 3: on the pairs left to MPR the depth is within 1 % of the least depth over
// all directions, by the least-depth expansion (epa.hpp); sizes 0.5 … 10 m (up to 20:1). Measured
// on 100,000 pairs (61,859 overlapping): p99 1.0072 (float) and 1.0070 (double), max 1.043 and
// 1.018 (a face normal kept within its 1e-4-of-the-size slack); before the expansion MPR gave p99
// 1.87 and max 2.80 on 2,000 of them. The goals of the issue are asserted: p99 ≤ 1.05, max ≤ 1.5.
TEST_CASE_TEMPLATE("100,000 random pairs: depth within 5 % of the least depth at the 99th percentile, 50 % at worst", T, float,
                   double) {
    const test::DepthResult r = test::check_depth<T>(72, kSlowPairs, 0.5, 10.0);
    MESSAGE("depth / least depth:\n"
            << test::depth_table(r) << "shallow pairs: worst (depth - least) / size " << r.worst_shallow
            << "; below the reference: " << r.below << " (lowest ratio " << r.lowest << ")");
    CHECK(r.all.size() > static_cast<std::size_t>(kSlowPairs / 3));
    CHECK(r.below <= static_cast<int>(r.all.size() / 100));  // the dense search may stay a little high
    CHECK(test::quantile_of(r.all, 0.99) <= 1.0102);
    CHECK(test::quantile_of(r.all, 0.99) <= 1.05);
    CHECK(test::quantile_of(r.all, 1.0) <= 1.5);
    CHECK(r.worst_shallow <= 2e-4);
}

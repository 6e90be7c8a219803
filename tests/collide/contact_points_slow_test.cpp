// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The 100,000-pair version of contact_points_test.cpp's randomised contract check, float and
// double: collide()'s contact points over every shape pair with sizes 0.1 … 10 m (up to 100:1),
// each point on or inside its own shape within the depth (+ 1e-4 of the pair's size) by a
// distance computed from the shape's support function alone (support_reference.hpp):
//   build/tests/xeno_slow_tests -tc='*100,000*' -s
#include "collide/contact_points_checks.hpp"

#include <doctest/doctest.h>

using namespace xeno;

namespace {
#if defined(XENO_SANITIZE)
constexpr int kPairs = 2'000;
#else
constexpr int kPairs = 100'000;
#endif
}  // namespace

TEST_CASE_TEMPLATE("100,000 random pairs: contact points on or inside their own shapes within the depth", T, float, double) {
    const test::ContractResult r = test::check_contract<T>(71, kPairs, 0.1, 10.0);
    MESSAGE(r.hits << " overlapping pairs, " << r.violations << " violations; worst (outside − depth) / size " << r.worst_excess << " ("
                   << r.worst_pair << "), worst |pa − pb − depth n| / size " << r.worst_offset);
    CHECK(r.hits > kPairs / 4);
    CHECK(r.violations == 0);
    CHECK(r.worst_offset <= 1e-4);
}

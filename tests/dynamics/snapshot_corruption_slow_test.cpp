// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Every byte of a small snapshot changed four ways (sign or top exponent bit, lowest bit, all
// bits, zero <-> one): each buffer is rejected with InvalidArgument or restores a world that steps
// ten steps with finite state and creates a body without overwriting a living one.
#include "dynamics/snapshot_corruption.hpp"

using namespace xeno;
using namespace xeno::test;

TEST_CASE_TEMPLATE("every single-byte corruption of a snapshot, four values each, is rejected or behaves", T, float, double) {
#ifdef XENO_SANITIZE
    const std::size_t stride = 4;  // a quarter of the bytes under sanitizers
#else
    const std::size_t stride = 1;
#endif
    const auto [rejected, accepted] = sweep_corruptions<T>(0, stride, 4);
    MESSAGE(rejected << " rejected, " << accepted << " accepted");
    CHECK(rejected > 0);
    CHECK(accepted > 0);
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <xeno/math/scalar.hpp>

using namespace xeno;

TEST_CASE_TEMPLATE("scalar traits hold the constants of each precision", T, float, double) {
    CHECK(ScalarTraits<T>::epsilon == std::numeric_limits<T>::epsilon());
    CHECK(std::abs(ScalarTraits<T>::pi - T(3.14159265358979)) < T(1e-6));
    CHECK(ScalarTraits<T>::relative_tolerance > ScalarTraits<T>::epsilon);
    CHECK(ScalarTraits<T>::geometric_tolerance < T(1e-4));
    CHECK(approx_equal(T(1), T(1) + ScalarTraits<T>::epsilon));
    CHECK_FALSE(approx_equal(T(1), T(1.01)));
    CHECK(approx_equal(T(1e6), T(1e6) * (T(1) + T(10) * ScalarTraits<T>::epsilon)));
    CHECK(approx_equal(T(0), T(1e-20)));
    CHECK(clamp(T(5), T(0), T(1)) == T(1));
    CHECK(clamp(T(-5), T(0), T(1)) == T(0));
    CHECK(clamp(T(0.5), T(0), T(1)) == T(0.5));
    CHECK(square(T(3)) == T(9));
    CHECK(std::abs(degrees(radians(T(90))) - T(90)) < T(1e-4));
    CHECK(std::abs(radians(T(180)) - ScalarTraits<T>::pi) < T(1e-6));
}

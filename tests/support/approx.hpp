// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Approximate comparisons for the math types, with tolerances that follow the scalar type, and
// doctest printing for them.
#pragma once

#include <xeno/math/aabb.hpp>
#include <xeno/math/io.hpp>
#include <xeno/math/mat4.hpp>

#include <doctest/doctest.h>

#include <sstream>
#include <string>

namespace xeno::test {

/// A tolerance suited to a few dozen operations in T: 1e-4 for float, 1e-10 for double.
template <class T>
constexpr T tol() {
    return std::is_same_v<T, float> ? T(1e-4) : T(1e-10);
}

template <class T>
bool near(T a, T b, T eps = tol<T>()) {
    return std::abs(a - b) <= eps * (T(1) + std::max(std::abs(a), std::abs(b)));
}
template <class T>
bool near(const Vec3<T>& a, const Vec3<T>& b, T eps = tol<T>()) {
    return near(a.x, b.x, eps) && near(a.y, b.y, eps) && near(a.z, b.z, eps);
}
template <class T>
bool near(const Mat3<T>& a, const Mat3<T>& b, T eps = tol<T>()) {
    return near(a[0], b[0], eps) && near(a[1], b[1], eps) && near(a[2], b[2], eps);
}
/// Same rotation: q and -q are equal.
template <class T>
bool same_rotation(const Quat<T>& a, const Quat<T>& b, T eps = tol<T>()) {
    return std::abs(std::abs(dot(a, b)) - T(1)) <= eps;
}

}  // namespace xeno::test

namespace doctest {
template <class T>
struct StringMaker<xeno::Vec3<T>> {
    static String convert(const xeno::Vec3<T>& v) {
        std::ostringstream os;
        os.precision(9);
        os << v;
        return os.str().c_str();
    }
};
template <class T>
struct StringMaker<xeno::Quat<T>> {
    static String convert(const xeno::Quat<T>& q) {
        std::ostringstream os;
        os.precision(9);
        os << q;
        return os.str().c_str();
    }
};
}  // namespace doctest

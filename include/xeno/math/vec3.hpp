// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Vec3<T>: a 3-vector of the scalar T, used for points, directions, velocities and forces alike.
// Plain public x, y, z; free functions for products (dot, cross) like linalg; everything
// constexpr where the standard library allows. Conversions between precisions are explicit.
#pragma once

#include "scalar.hpp"

#include <cmath>
#include <optional>

namespace xeno {

/// A 3-vector of scalar T (float or double).
template <class T>
struct Vec3 {
    static_assert(std::is_floating_point_v<T>, "Vec3 needs float or double");
    using scalar_type = T;

    T x{}, y{}, z{};

    constexpr Vec3() = default;
    constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    /// Explicit conversion from the other precision.
    template <class U, class = std::enable_if_t<!std::is_same_v<T, U>>>
    constexpr explicit Vec3(const Vec3<U>& v) : x(static_cast<T>(v.x)), y(static_cast<T>(v.y)), z(static_cast<T>(v.z)) {}

    static constexpr Vec3 zero() { return {T(0), T(0), T(0)}; }
    static constexpr Vec3 one() { return {T(1), T(1), T(1)}; }
    static constexpr Vec3 unit_x() { return {T(1), T(0), T(0)}; }
    static constexpr Vec3 unit_y() { return {T(0), T(1), T(0)}; }
    static constexpr Vec3 unit_z() { return {T(0), T(0), T(1)}; }
    /// The unit vector along axis 0 (x), 1 (y) or 2 (z).
    static constexpr Vec3 axis(int i) { return i == 0 ? unit_x() : (i == 1 ? unit_y() : unit_z()); }

    /// Component by index: 0 = x, 1 = y, 2 = z.
    constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr const T& operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }

    /// The same vector in precision U.
    template <class U>
    constexpr Vec3<U> cast() const {
        return {static_cast<U>(x), static_cast<U>(y), static_cast<U>(z)};
    }

    constexpr Vec3& operator+=(const Vec3& b) {
        x += b.x;
        y += b.y;
        z += b.z;
        return *this;
    }
    constexpr Vec3& operator-=(const Vec3& b) {
        x -= b.x;
        y -= b.y;
        z -= b.z;
        return *this;
    }
    constexpr Vec3& operator*=(T s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr Vec3& operator/=(T s) {
        x /= s;
        y /= s;
        z /= s;
        return *this;
    }

    /// Scales to unit length in place; a zero vector is left unchanged (see normalized_or).
    void normalize();
};

template <class T>
constexpr Vec3<T> operator+(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
constexpr Vec3<T> operator-(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
constexpr Vec3<T> operator-(const Vec3<T>& a) {
    return {-a.x, -a.y, -a.z};
}
template <class T>
constexpr Vec3<T> operator*(const Vec3<T>& a, T s) {
    return {a.x * s, a.y * s, a.z * s};
}
template <class T>
constexpr Vec3<T> operator*(T s, const Vec3<T>& a) {
    return {a.x * s, a.y * s, a.z * s};
}
template <class T>
constexpr Vec3<T> operator/(const Vec3<T>& a, T s) {
    return {a.x / s, a.y / s, a.z / s};
}
template <class T>
constexpr bool operator==(const Vec3<T>& a, const Vec3<T>& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}
template <class T>
constexpr bool operator!=(const Vec3<T>& a, const Vec3<T>& b) {
    return !(a == b);
}

/// Component-wise product.
template <class T>
constexpr Vec3<T> hadamard(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <class T>
constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
/// Right-handed cross product.
template <class T>
constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// a · (b × c): six times the signed volume of the tetrahedron (0, a, b, c).
template <class T>
constexpr T triple(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
    return dot(a, cross(b, c));
}
template <class T>
constexpr T length_squared(const Vec3<T>& a) {
    return dot(a, a);
}
namespace detail {
/// Each component halved `times` times (scalar.hpp's detail::halved).
template <class T>
Vec3<T> halved(const Vec3<T>& v, int times) {
    return {halved(v.x, times), halved(v.y, times), halved(v.z, times)};
}
}  // namespace detail
template <class T>
T length(const Vec3<T>& a) {
    return std::sqrt(dot(a, a));
}
template <class T>
T distance(const Vec3<T>& a, const Vec3<T>& b) {
    return length(a - b);
}
template <class T>
constexpr Vec3<T> min(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
template <class T>
constexpr Vec3<T> max(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
template <class T>
Vec3<T> abs(const Vec3<T>& a) {
    return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}
template <class T>
constexpr T min_component(const Vec3<T>& a) {
    return a.x < a.y ? (a.x < a.z ? a.x : a.z) : (a.y < a.z ? a.y : a.z);
}
template <class T>
constexpr T max_component(const Vec3<T>& a) {
    return a.x > a.y ? (a.x > a.z ? a.x : a.z) : (a.y > a.z ? a.y : a.z);
}
/// Index (0, 1, 2) of the largest component.
template <class T>
constexpr int max_axis(const Vec3<T>& a) {
    return a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
}
template <class T>
constexpr Vec3<T> lerp(const Vec3<T>& a, const Vec3<T>& b, T t) {
    return a + (b - a) * t;
}
/// True when every component is finite (no NaN, no infinity).
template <class T>
bool is_finite(const Vec3<T>& a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

/// The unit vector along a; a must not be zero (for that case use normalized_or).
template <class T>
Vec3<T> normalized(const Vec3<T>& a) {
    return a / length(a);
}

/// The unit vector along a, or nothing when |a|² is zero or not finite.
template <class T>
std::optional<Vec3<T>> try_normalized(const Vec3<T>& a) {
    const T len_sq = length_squared(a);
    if (!(len_sq > std::numeric_limits<T>::min()) || !std::isfinite(len_sq)) return std::nullopt;
    return a / std::sqrt(len_sq);
}

/// The unit vector along a, or fallback when a is too short to have a direction.
template <class T>
Vec3<T> normalized_or(const Vec3<T>& a, const Vec3<T>& fallback) {
    const std::optional<Vec3<T>> n = try_normalized(a);
    return n ? *n : fallback;
}

template <class T>
void Vec3<T>::normalize() {
    if (const std::optional<Vec3> n = try_normalized(*this)) *this = *n;
}

/// A unit vector perpendicular to the unit vector n, continuous in n except near one pole and
/// deterministic: the solver builds friction tangents with it (Frisvad, "Building an Orthonormal
/// Basis from a 3D Unit Vector Without Normalization", JGT 2012, with Pixar's sign fix).
template <class T>
Vec3<T> any_perpendicular(const Vec3<T>& n) {
    const T sign = n.z >= T(0) ? T(1) : T(-1);
    const T a = T(-1) / (sign + n.z);
    const T b = n.x * n.y * a;
    return {T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x};
}

namespace f32 {
using Vec3 = xeno::Vec3<float>;
}
namespace f64 {
using Vec3 = xeno::Vec3<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Mat3<T>: a 3×3 matrix stored as three rows, for rotations and inertia tensors.
// M * v transforms a column vector ("transform"); transpose(M) * v is the "transposed transform"
// the thesis uses to take world directions into a rotation's local frame (3.2.2.3).
#pragma once

#include "vec3.hpp"

#include <algorithm>
#include <optional>

namespace xeno {

/// A 3×3 matrix of scalar T, row-major: row[i][j] is row i, column j.
template <class T>
struct Mat3 {
    using scalar_type = T;

    Vec3<T> row[3]{};

    constexpr Mat3() = default;
    constexpr Mat3(const Vec3<T>& r0, const Vec3<T>& r1, const Vec3<T>& r2) : row{r0, r1, r2} {}
    /// Explicit conversion from the other precision.
    template <class U, class = std::enable_if_t<!std::is_same_v<T, U>>>
    constexpr explicit Mat3(const Mat3<U>& m) : row{Vec3<T>(m.row[0]), Vec3<T>(m.row[1]), Vec3<T>(m.row[2])} {}

    static constexpr Mat3 zero() { return {}; }
    static constexpr Mat3 identity() { return diagonal({T(1), T(1), T(1)}); }
    /// diag(d.x, d.y, d.z).
    static constexpr Mat3 diagonal(const Vec3<T>& d) { return {{d.x, T(0), T(0)}, {T(0), d.y, T(0)}, {T(0), T(0), d.z}}; }
    /// The matrix with the given columns.
    static constexpr Mat3 from_columns(const Vec3<T>& c0, const Vec3<T>& c1, const Vec3<T>& c2) {
        return {{c0.x, c1.x, c2.x}, {c0.y, c1.y, c2.y}, {c0.z, c1.z, c2.z}};
    }

    constexpr Vec3<T>& operator[](int i) { return row[i]; }
    constexpr const Vec3<T>& operator[](int i) const { return row[i]; }
    constexpr Vec3<T> column(int j) const { return {row[0][j], row[1][j], row[2][j]}; }
    constexpr Vec3<T> diagonal_vector() const { return {row[0].x, row[1].y, row[2].z}; }
};

template <class T>
constexpr Mat3<T> operator+(const Mat3<T>& a, const Mat3<T>& b) {
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
template <class T>
constexpr Mat3<T> operator-(const Mat3<T>& a, const Mat3<T>& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <class T>
constexpr Mat3<T> operator*(const Mat3<T>& a, T s) {
    return {a[0] * s, a[1] * s, a[2] * s};
}
template <class T>
constexpr Mat3<T> operator*(T s, const Mat3<T>& a) {
    return a * s;
}
template <class T>
constexpr bool operator==(const Mat3<T>& a, const Mat3<T>& b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/// M v: transforms the column vector v.
template <class T>
constexpr Vec3<T> operator*(const Mat3<T>& m, const Vec3<T>& v) {
    return {dot(m[0], v), dot(m[1], v), dot(m[2], v)};
}
template <class T>
constexpr Vec3<T> transform(const Mat3<T>& m, const Vec3<T>& v) {
    return m * v;
}
/// Mᵀ v without forming the transpose: the inverse transform when M is a rotation.
template <class T>
constexpr Vec3<T> transposed_transform(const Mat3<T>& m, const Vec3<T>& v) {
    return m[0] * v.x + m[1] * v.y + m[2] * v.z;
}

template <class T>
constexpr Mat3<T> transpose(const Mat3<T>& m) {
    return {m.column(0), m.column(1), m.column(2)};
}

/// Matrix product A B.
template <class T>
constexpr Mat3<T> operator*(const Mat3<T>& a, const Mat3<T>& b) {
    return {transposed_transform(b, a[0]), transposed_transform(b, a[1]), transposed_transform(b, a[2])};
}

template <class T>
constexpr T determinant(const Mat3<T>& m) {
    return triple(m[0], m[1], m[2]);
}

template <class T>
constexpr T trace(const Mat3<T>& m) {
    return m[0].x + m[1].y + m[2].z;
}

/// The inverse, or nothing when |det| is below a relative threshold (a singular or nearly
/// singular matrix is reported, never divided by zero). The matrix is scaled by its largest
/// entry first, so large or tiny entries (an inertia of 1e15 kg·m² in float) neither overflow
/// nor underflow the determinant.
template <class T>
std::optional<Mat3<T>> try_inverse(const Mat3<T>& m) {
    T largest = T(0);
    for (int i = 0; i < 3; ++i) largest = std::max(largest, max_component(abs(m[i])));
    if (!(largest > T(0)) || !std::isfinite(largest)) return std::nullopt;
    const Mat3<T> n = m * (T(1) / largest);
    // Columns of the adjugate's transpose are the cross products of the rows.
    const Vec3<T> c0 = cross(n[1], n[2]);
    const Vec3<T> c1 = cross(n[2], n[0]);
    const Vec3<T> c2 = cross(n[0], n[1]);
    const T det = dot(n[0], c0);
    const T scale = length(n[0]) * length(n[1]) * length(n[2]);
    if (!(std::abs(det) > ScalarTraits<T>::epsilon * scale) || !std::isfinite(det)) return std::nullopt;
    return Mat3<T>::from_columns(c0, c1, c2) * (T(1) / (det * largest));
}

/// The inverse of m with each row scaled by its own largest component first, for a matrix whose
/// rows differ by many orders of magnitude (an inertia stiff about one axis, diag(167, 1e25, 167)
/// in float), whose determinant scaled by the largest entry underflows in try_inverse. nullopt
/// when singular after the scaling.
template <class T>
std::optional<Mat3<T>> try_inverse_by_rows(const Mat3<T>& m) {
    T s[3];
    Mat3<T> n;
    for (int i = 0; i < 3; ++i) {
        s[i] = max_component(abs(m[i]));
        if (!(s[i] > T(0)) || !std::isfinite(s[i])) return std::nullopt;
        n[i] = m[i] / s[i];
    }
    const Vec3<T> c0 = cross(n[1], n[2]), c1 = cross(n[2], n[0]), c2 = cross(n[0], n[1]);
    const T det = dot(n[0], c0);
    const T scale = length(n[0]) * length(n[1]) * length(n[2]);
    if (!(std::abs(det) > ScalarTraits<T>::epsilon * scale) || !std::isfinite(det)) return std::nullopt;
    // m = S n, so m⁻¹ = n⁻¹ S⁻¹: column j of n⁻¹ (c_j / det) divided by s_j.
    return Mat3<T>::from_columns(c0 / (det * s[0]), c1 / (det * s[1]), c2 / (det * s[2]));
}

/// u vᵀ.
template <class T>
constexpr Mat3<T> outer(const Vec3<T>& u, const Vec3<T>& v) {
    return {v * u.x, v * u.y, v * u.z};
}

/// The cross-product matrix: skew(a) v = a × v.
template <class T>
constexpr Mat3<T> skew(const Vec3<T>& a) {
    return {{T(0), -a.z, a.y}, {a.z, T(0), -a.x}, {-a.y, a.x, T(0)}};
}

template <class T>
bool is_finite(const Mat3<T>& m) {
    return is_finite(m[0]) && is_finite(m[1]) && is_finite(m[2]);
}

namespace f32 {
using Mat3 = xeno::Mat3<float>;
}
namespace f64 {
using Mat3 = xeno::Mat3<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Quat<T>: a unit quaternion (w, x, y, z) for orientations, Hamilton product (docs/conventions.md,
// "Frames"). q * p applies p first, then q; rotate(q, v) = q (0, v) q*. Euler angles follow one
// convention: yaw about y, then pitch about the new x, then roll about the newest z (intrinsic
// Y-X'-Z'', the y-up form of aircraft angles): q = q_y(yaw) q_x(pitch) q_z(roll). At pitch = ±90°
// yaw and roll act about the same axis (gimbal lock); to_euler then reports roll = 0 and folds it
// into yaw, which gives the same rotation.
#pragma once

#include "mat3.hpp"

namespace xeno {

/// Yaw (about y), pitch (about x), roll (about z) in radians; see the file comment for the order.
template <class T>
struct EulerAngles {
    T yaw{}, pitch{}, roll{};
};

/// A quaternion w + x i + y j + z k; orientations are unit quaternions.
template <class T>
struct Quat {
    using scalar_type = T;

    T w{1}, x{}, y{}, z{};

    constexpr Quat() = default;
    constexpr Quat(T w_, T x_, T y_, T z_) : w(w_), x(x_), y(y_), z(z_) {}
    /// Explicit conversion from the other precision.
    template <class U, class = std::enable_if_t<!std::is_same_v<T, U>>>
    constexpr explicit Quat(const Quat<U>& q)
        : w(static_cast<T>(q.w)), x(static_cast<T>(q.x)), y(static_cast<T>(q.y)), z(static_cast<T>(q.z)) {}

    static constexpr Quat identity() { return {T(1), T(0), T(0), T(0)}; }
    /// Rotation by angle (radians, right-handed) about axis; axis need not be unit but not zero.
    static Quat from_axis_angle(const Vec3<T>& axis, T angle);
    /// The quaternion of a rotation matrix (Shepperd's method: stable for every rotation).
    static Quat from_matrix(const Mat3<T>& m);
    static Quat from_euler(const EulerAngles<T>& e);
    /// The shortest rotation taking unit vector from onto unit vector to.
    static Quat from_to(const Vec3<T>& from, const Vec3<T>& to);

    /// The vector part (x, y, z).
    constexpr Vec3<T> vec() const { return {x, y, z}; }
    template <class U>
    constexpr Quat<U> cast() const {
        return Quat<U>(*this);
    }
};

template <class T>
constexpr Quat<T> operator+(const Quat<T>& a, const Quat<T>& b) {
    return {a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
constexpr Quat<T> operator-(const Quat<T>& a, const Quat<T>& b) {
    return {a.w - b.w, a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
constexpr Quat<T> operator-(const Quat<T>& a) {
    return {-a.w, -a.x, -a.y, -a.z};
}
template <class T>
constexpr Quat<T> operator*(const Quat<T>& a, T s) {
    return {a.w * s, a.x * s, a.y * s, a.z * s};
}
template <class T>
constexpr Quat<T> operator*(T s, const Quat<T>& a) {
    return a * s;
}
template <class T>
constexpr bool operator==(const Quat<T>& a, const Quat<T>& b) {
    return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z;
}
template <class T>
constexpr bool operator!=(const Quat<T>& a, const Quat<T>& b) {
    return !(a == b);
}

/// Hamilton product: (a b) applies b first, then a.
template <class T>
constexpr Quat<T> operator*(const Quat<T>& a, const Quat<T>& b) {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

template <class T>
constexpr T dot(const Quat<T>& a, const Quat<T>& b) {
    return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
constexpr T length_squared(const Quat<T>& q) {
    return dot(q, q);
}
template <class T>
T length(const Quat<T>& q) {
    return std::sqrt(dot(q, q));
}
template <class T>
constexpr Quat<T> conjugate(const Quat<T>& q) {
    return {q.w, -q.x, -q.y, -q.z};
}
/// q⁻¹ = q* / |q|²; for a unit quaternion that is the conjugate. q must not be zero.
template <class T>
constexpr Quat<T> inverse(const Quat<T>& q) {
    return conjugate(q) * (T(1) / length_squared(q));
}
template <class T>
bool is_finite(const Quat<T>& q) {
    return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

/// q scaled to unit length; a zero (or non-finite) quaternion gives the identity. A quaternion
/// whose squared length would under- or overflow (components of 1e-20 or 1e20 in float) is first
/// divided by its largest component, so every finite non-zero q keeps its direction.
template <class T>
Quat<T> normalized(const Quat<T>& q) {
    const T len_sq = length_squared(q);
    if (len_sq >= T(1e-8) && len_sq <= T(1e8)) return q * (T(1) / std::sqrt(len_sq));  // the usual case
    if (!is_finite(q)) return Quat<T>::identity();
    const T largest = std::max(std::max(std::abs(q.w), std::abs(q.x)), std::max(std::abs(q.y), std::abs(q.z)));
    if (largest == T(0)) return Quat<T>::identity();
    const Quat<T> s{q.w / largest, q.x / largest, q.y / largest, q.z / largest};  // in [-1, 1], one of them ±1
    return s * (T(1) / length(s));
}

/// v rotated by the unit quaternion q: q (0, v) q*, as v + 2w (u × v) + 2 u × (u × v), u = q.vec().
template <class T>
constexpr Vec3<T> rotate(const Quat<T>& q, const Vec3<T>& v) {
    const Vec3<T> u = q.vec();
    const Vec3<T> t = T(2) * cross(u, v);
    return v + q.w * t + cross(u, t);
}

/// v rotated by the inverse of the unit quaternion q (world to local for an orientation q).
template <class T>
constexpr Vec3<T> inverse_rotate(const Quat<T>& q, const Vec3<T>& v) {
    return rotate(conjugate(q), v);
}

/// The rotation matrix of the unit quaternion q: to_matrix(q) v == rotate(q, v).
template <class T>
constexpr Mat3<T> to_matrix(const Quat<T>& q) {
    const T xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
    const T xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
    const T wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    return {{T(1) - T(2) * (yy + zz), T(2) * (xy - wz), T(2) * (xz + wy)},
            {T(2) * (xy + wz), T(1) - T(2) * (xx + zz), T(2) * (yz - wx)},
            {T(2) * (xz - wy), T(2) * (yz + wx), T(1) - T(2) * (xx + yy)}};
}

/// The Euler angles of the unit quaternion q (convention in the file comment). Near pitch ±90°
/// roll is reported as 0 and the whole turn about the vertical goes into yaw.
template <class T>
EulerAngles<T> to_euler(const Quat<T>& q) {
    // R = Ry(yaw) Rx(pitch) Rz(roll) gives R12 = -sin(pitch), R02/R22 = tan(yaw), R10/R11 = tan(roll).
    const Mat3<T> r = to_matrix(q);
    const T sin_pitch = clamp(-r[1].z, T(-1), T(1));
    EulerAngles<T> e;
    e.pitch = std::asin(sin_pitch);
    if (std::abs(sin_pitch) < T(1) - T(64) * ScalarTraits<T>::epsilon) {
        e.yaw = std::atan2(r[0].z, r[2].z);
        e.roll = std::atan2(r[1].x, r[1].y);
    } else {
        // Gimbal lock: with roll = 0, R00 = cos(yaw) and R20 = -sin(yaw).
        e.yaw = std::atan2(-r[2].x, r[0].x);
        e.roll = T(0);
    }
    return e;
}

/// Spherical linear interpolation along the shorter arc: t = 0 gives a, t = 1 gives b (or -b,
/// the same rotation), at a constant angular speed in between. Nearly parallel inputs use a
/// normalised linear blend, which is exact to round-off there and never divides by sin(0).
template <class T>
Quat<T> slerp(const Quat<T>& a, Quat<T> b, T t) {
    T cos_theta = dot(a, b);
    if (cos_theta < T(0)) {  // q and -q are the same rotation: take the short way round
        b = -b;
        cos_theta = -cos_theta;
    }
    if (cos_theta > T(1) - T(16) * ScalarTraits<T>::epsilon) return normalized(a * (T(1) - t) + b * t);
    const T theta = std::acos(clamp(cos_theta, T(-1), T(1)));
    const T inv_sin = T(1) / std::sin(theta);
    return a * (std::sin((T(1) - t) * theta) * inv_sin) + b * (std::sin(t * theta) * inv_sin);
}

/// The angle in radians (0 … π) of the rotation taking a to b.
template <class T>
T angle_between(const Quat<T>& a, const Quat<T>& b) {
    return T(2) * std::acos(clamp(std::abs(dot(a, b)), T(0), T(1)));
}

/// Orientation q advanced by the world-space angular velocity omega (rad/s) over dt seconds.
/// Up to a turn θ of 1/8 rad: q + dt/2 (0, omega) q, renormalised (first order, as the thesis's
/// integrator, 2.4), which turns by 2 atan(θ/2), short of θ by θ³/12. Beyond it (only spin that
/// leaves a round surface in place turns that far in a substep: detail::SpinCap) the rotation by θ
/// itself, where the first order turned a ball spinning at 300 rad/s 3 % short a substep: θ less
/// whole turns (std::fmod is exact), the half-angle's cosine and sine by their series at θ/2^k ≤
/// 1/8, doubled k ≤ 6 times by squaring the quaternion — arithmetic only, so the bits do not
/// depend on the standard library's std::sin.
template <class T>
Quat<T> integrate(const Quat<T>& q, const Vec3<T>& omega, T dt) {
    Vec3<T> turn = omega * dt;
    T angle_sq = length_squared(turn);
    if (!(angle_sq > T(1) / T(64)) || !std::isfinite(angle_sq)) {
        const Quat<T> spin{T(0), omega.x, omega.y, omega.z};
        return normalized(q + (spin * q) * (T(0.5) * dt));
    }
    const T angle = std::sqrt(angle_sq), full_turn = T(2) * ScalarTraits<T>::pi;
    if (angle > full_turn) {
        const T rest = std::fmod(angle, full_turn);
        turn *= rest / angle;
        angle_sq = rest * rest;
    }
    T scale = T(0.5);  // the half-angle's vector: turn × scale
    int doublings = 0;
    for (; angle_sq > T(1) / T(64); ++doublings) {
        scale *= T(0.5);
        angle_sq *= T(0.25);
    }
    // (half-angle)² ≤ 1/256: the first term the series leave out is below 3e-19.
    const T x = angle_sq * T(0.25);
    const T cosine = T(1) - x / T(2) * (T(1) - x / T(12) * (T(1) - x / T(30) * (T(1) - x / T(56))));
    const T sine_over = T(1) - x / T(6) * (T(1) - x / T(20) * (T(1) - x / T(42) * (T(1) - x / T(72))));
    const Vec3<T> v = turn * (scale * sine_over);
    Quat<T> r{cosine, v.x, v.y, v.z};
    for (int i = 0; i < doublings; ++i) r = r * r;
    return normalized(r * q);
}

/// The angle (rad) integrate() turns an orientation by for the turn ω dt: 2 atan(θ/2) up to
/// θ = 1/8 rad (the first-order step), θ itself beyond. What a point carried by a turning body
/// really travels in a substep follows from it (detail::chord_slip): a chord taken at θ instead
/// left a joint's anchor θ³/12 of its lever ahead each substep, which the joint's position
/// correction took back by spinning the body up (a ball whirled on a joint at 30 rad/s doubled
/// its energy in 30 s).
template <class T>
T integrated_angle(const Vec3<T>& turn) {
    const T angle_sq = length_squared(turn);
    const T angle = std::sqrt(angle_sq);
    return angle_sq > T(1) / T(64) ? angle : T(2) * std::atan(angle / T(2));
}

template <class T>
Quat<T> Quat<T>::from_axis_angle(const Vec3<T>& axis, T angle) {
    const Vec3<T> n = normalized_or(axis, Vec3<T>::unit_x());
    const T s = std::sin(T(0.5) * angle);
    return {std::cos(T(0.5) * angle), n.x * s, n.y * s, n.z * s};
}

template <class T>
Quat<T> Quat<T>::from_matrix(const Mat3<T>& m) {
    // Shepperd: build from the largest of w², x², y², z² so the divisor is never small.
    const T tr = trace(m);
    Quat q;
    if (tr >= m[0].x && tr >= m[1].y && tr >= m[2].z) {
        const T s = std::sqrt(T(1) + tr) * T(2);  // 4w
        q = {T(0.25) * s, (m[2].y - m[1].z) / s, (m[0].z - m[2].x) / s, (m[1].x - m[0].y) / s};
    } else if (m[0].x >= m[1].y && m[0].x >= m[2].z) {
        const T s = std::sqrt(T(1) + m[0].x - m[1].y - m[2].z) * T(2);  // 4x
        q = {(m[2].y - m[1].z) / s, T(0.25) * s, (m[0].y + m[1].x) / s, (m[0].z + m[2].x) / s};
    } else if (m[1].y >= m[2].z) {
        const T s = std::sqrt(T(1) + m[1].y - m[0].x - m[2].z) * T(2);  // 4y
        q = {(m[0].z - m[2].x) / s, (m[0].y + m[1].x) / s, T(0.25) * s, (m[1].z + m[2].y) / s};
    } else {
        const T s = std::sqrt(T(1) + m[2].z - m[0].x - m[1].y) * T(2);  // 4z
        q = {(m[1].x - m[0].y) / s, (m[0].z + m[2].x) / s, (m[1].z + m[2].y) / s, T(0.25) * s};
    }
    if (q.w < T(0)) q = -q;  // canonical sign: w >= 0
    return normalized(q);
}

template <class T>
Quat<T> Quat<T>::from_euler(const EulerAngles<T>& e) {
    return from_axis_angle(Vec3<T>::unit_y(), e.yaw) * from_axis_angle(Vec3<T>::unit_x(), e.pitch) *
           from_axis_angle(Vec3<T>::unit_z(), e.roll);
}

template <class T>
Quat<T> Quat<T>::from_to(const Vec3<T>& from, const Vec3<T>& to) {
    const T c = dot(from, to);
    if (c < T(-1) + T(16) * ScalarTraits<T>::epsilon)  // opposite: half a turn about any perpendicular
        return from_axis_angle(any_perpendicular(from), ScalarTraits<T>::pi);
    const Vec3<T> axis = cross(from, to);
    return normalized(Quat{T(1) + c, axis.x, axis.y, axis.z});
}

namespace f32 {
using Quat = xeno::Quat<float>;
using EulerAngles = xeno::EulerAngles<float>;
}  // namespace f32
namespace f64 {
using Quat = xeno::Quat<double>;
using EulerAngles = xeno::EulerAngles<double>;
}  // namespace f64

}  // namespace xeno

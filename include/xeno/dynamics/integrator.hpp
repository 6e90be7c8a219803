// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Semi-implicit (symplectic) Euler, the thesis's Newton–Störmer–Verlet (2.4, Quadro 21): first
// velocities from forces over the (sub)step h, then, after the contact solve, positions from the
// new velocities. The gyroscopic term ω × Iω is integrated implicitly with one Newton step in the
// body frame by the implicit midpoint rule (after Catto, "Numerical Methods", GDC 2015, who uses
// implicit Euler): an explicit term makes a free spinning body gain energy and wander; the
// midpoint rule keeps the magnitude of its angular momentum. Orientations advance by
// q ← q + h/2 (0, ω) q, renormalised.
#pragma once

#include "solver_body.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace xeno {
namespace detail {

/// Which turns leave a body's surface where it was: a sphere's about any axis through its centre,
/// a capsule's, cylinder's or cone's about its own axis (local y through the centre of mass).
enum class SpinSymmetry : std::uint8_t { none, axis_y, all };

/// The spin caps of one body (rad/s). More than a fraction of a turn per step would carry a
/// body's corners past what the step's contacts saw, and the orientation update would no longer
/// follow the spin, so the spin that moves the surface is capped at `max_rotation_per_step` a step
/// (`tumble`). Spin that leaves the surface in place (SpinSymmetry) only has to keep the surface
/// within the body's speed cap (`roll` = that cap over the radius, never below `tumble`). Before,
/// every spin had the tumbling cap: a 5 cm ball rolling down 30° reached 2.4 m/s in 3 s, not
/// 10.5 m/s, because friction held its contact point to the 47 rad/s its spin was capped at.
template <class T>
struct SpinCap {
    T tumble = ScalarTraits<T>::infinity;
    T roll = ScalarTraits<T>::infinity;  ///< ≥ tumble
    SpinSymmetry symmetry = SpinSymmetry::none;
};

/// The per-step constants of one dynamic body that velocity integration needs.
template <class T>
struct BodyIntegration {
    Vec3<T> acceleration{};                  ///< m/s²: gravity × scale + force / mass
    Vec3<T> angular_impulse_rate{};          ///< rad/s²: I_world⁻¹ torque
    const Mat3<T>* inertia_local = nullptr;  ///< kg·m², body frame (gyroscopic term; the body's own)
    Quat<T> orientation0{};                  ///< orientation at the start of the step
    T linear_damping{}, angular_damping{};
    bool gyroscopic = false;                  ///< false for isotropic inertia, where ω × Iω = 0
    SpinCap<T> spin_cap{};                    ///< the spin caps of integrate_position, applied first
    T max_speed = ScalarTraits<T>::infinity;  ///< m/s: the speed cap of integrate_position
    bool dynamic = true;                      ///< false for kinematic bodies, whose velocity is the user's
};

template <class T>
Vec3<T> capped_length(const Vec3<T>& v, T limit);

/// ω within `cap` for a body turned by `turn` from `orientation0`: the part about the symmetry
/// axis within cap.roll, the rest within cap.tumble. A spin within cap.tumble is returned as it is
/// (the same bits).
template <class T>
Vec3<T> capped_spin(const Vec3<T>& w, const SpinCap<T>& cap, const Quat<T>& turn, const Quat<T>& orientation0) {
    if (cap.symmetry == SpinSymmetry::all) return capped_length(w, cap.roll);
    const T length_sq = length_squared(w);
    if (cap.symmetry == SpinSymmetry::none || !(length_sq > cap.tumble * cap.tumble)) return capped_length(w, cap.tumble);
    const Vec3<T> u = capped_length(w, cap.roll);  // finite (even when w overflowed), so the split is
    const Vec3<T> axis = rotate(turn * orientation0, Vec3<T>::unit_y());
    const T along = dot(u, axis);
    return capped_length(u - axis * along, cap.tumble) + axis * std::clamp(along, -cap.roll, cap.roll);
}

/// m x, or where a component overflows, ±inf with the sign of m (x / s) s (s the largest |x_i|):
/// an infinite component, never inf − inf = NaN.
template <class T>
Vec3<T> product_without_nan(const Mat3<T>& m, const Vec3<T>& x) {
    const Vec3<T> y = m * x;
    if (is_finite(y)) return y;
    const T s = std::max(std::max(std::abs(x.x), std::abs(x.y)), std::abs(x.z));
    return (m * (x / s)) * s;
}

/// v += h a, ω += h I⁻¹τ, then the implicit gyroscopic correction and damping.
template <class T>
void integrate_velocity(SolverBody<T>& body, const BodyIntegration<T>& in, T h) {
    body.v += in.acceleration * h;
    // A force accepted with a larger mass may overflow f/m now: cap the speed before the contact
    // rows see an infinite velocity (integrate_position caps finite speeds).
    if (!is_finite(body.v)) body.v = detail::capped_length(body.v, in.max_speed);
    body.w += in.angular_impulse_rate * h;
    // A spin far above the cap (a huge torque or set_angular_velocity) would overflow the
    // gyroscopic term and the contact rows before integrate_position caps it: cap it here.
    body.w = capped_spin(body.w, in.spin_cap, body.dq, in.orientation0);
    if (in.gyroscopic) {
        // Implicit midpoint in the body frame: I (ω' − ω) + h ω_m × I ω_m = 0 with
        // ω_m = (ω + ω')/2. Dotting with I ω_m shows |I ω'| = |I ω|: the magnitude of the
        // angular momentum is kept exactly (implicit Euler, one step of which Catto suggests,
        // loses about 2 % in 10 s on a tumbling box). Two Newton steps from ω' = ω, with
        // J = I + h/2 (skew(ω_m) I − skew(I ω_m)).
        const Quat<T> q = body.dq * in.orientation0;
        const Vec3<T> w0 = inverse_rotate(q, body.w);
        const Mat3<T>& inertia = *in.inertia_local;
        const Vec3<T> l0 = inertia * w0;
        Vec3<T> w1 = w0;
        for (int newton = 0; newton < 2; ++newton) {
            const Vec3<T> wm = (w0 + w1) * T(0.5);
            const Vec3<T> lm = inertia * wm;
            const Vec3<T> f = inertia * w1 - l0 + cross(wm, lm) * h;
            const Mat3<T> j = inertia + (skew(wm) * inertia - skew(lm)) * (T(0.5) * h);
            const std::optional<Mat3<T>> j_inv = try_inverse(j);
            if (!j_inv) break;
            w1 -= *j_inv * f;
        }
        // Only the change goes back to the world frame. q is a product of two rounded unit
        // quaternions, on average a little long in float (|q|² − 1 ≈ +9e-8), and the round trip
        // rotate(q, inverse_rotate(q, ω)) scales ω by |q|⁴: a box tumbling freely gained 0.14 %
        // of its energy in 10 s at 8 substeps (0.77 % at 32), a straight line. On the change
        // alone the scale is that much of a small correction.
        body.w += rotate(q, w1 - w0);
    }
    body.v *= T(1) / (T(1) + h * in.linear_damping);
    body.w *= T(1) / (T(1) + h * in.angular_damping);
}

/// v scaled down to length `limit` when it is longer (limit > 0). The length is taken after
/// dividing by the largest component, so a finite v of any size (1e20 in float, whose square
/// overflows) keeps its direction; an infinite component counts as the direction of v.
template <class T>
Vec3<T> capped_length(const Vec3<T>& v, T limit) {
    const T length_sq = length_squared(v);
    if (std::isfinite(length_sq)) return length_sq > limit * limit ? v * (limit / std::sqrt(length_sq)) : v;
    Vec3<T> u = v;
    if (!is_finite(v)) {  // an overflowed velocity: keep the signs of the infinite components
        for (int i = 0; i < 3; ++i) u[i] = std::isinf(v[i]) ? std::copysign(T(1), v[i]) : T(0);
    } else {
        const T largest = std::max(std::max(std::abs(v.x), std::abs(v.y)), std::abs(v.z));
        u = v / largest;                             // components in [-1, 1], |u| in [1, √3]
        if (largest * length(u) <= limit) return v;  // only for a limit beyond √(max) (fast bodies)
    }
    return u * (limit / length(u));
}

/// Δx += h v, Δq ← Δq + h/2 (0, ω) Δq, with the speed caps against tunnelling.
template <class T>
void integrate_position(SolverBody<T>& body, const BodyIntegration<T>& in, T h) {
    body.v = detail::capped_length(body.v, in.max_speed);
    body.w = capped_spin(body.w, in.spin_cap, body.dq, in.orientation0);
    body.dp += body.v * h;
    body.dq = integrate(body.dq, body.w, h);
}

}  // namespace detail
}  // namespace xeno

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

namespace xeno {
namespace detail {

/// The per-step constants of one dynamic body that velocity integration needs.
template <class T>
struct BodyIntegration {
    Vec3<T> acceleration{};                  ///< m/s²: gravity × scale + force / mass
    Vec3<T> angular_impulse_rate{};          ///< rad/s²: I_world⁻¹ torque
    const Mat3<T>* inertia_local = nullptr;  ///< kg·m², body frame (gyroscopic term; the body's own)
    Quat<T> orientation0{};                  ///< orientation at the start of the step
    T linear_damping{}, angular_damping{};
    bool gyroscopic = false;                  ///< false for isotropic inertia, where ω × Iω = 0
    T max_spin = ScalarTraits<T>::infinity;   ///< rad/s: the spin cap of integrate_position, applied first
    T max_speed = ScalarTraits<T>::infinity;  ///< m/s: the speed cap of integrate_position
    bool dynamic = true;                      ///< false for kinematic bodies, whose velocity is the user's
};

template <class T>
Vec3<T> capped_length(const Vec3<T>& v, T limit);

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
    body.w = detail::capped_length(body.w, in.max_spin);
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
        body.w = rotate(q, w1);
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
void integrate_position(SolverBody<T>& body, T h, T max_speed, T max_rotation) {
    body.v = detail::capped_length(body.v, max_speed);
    const T turn_sq = length_squared(body.w) * h * h;
    if (!std::isfinite(turn_sq)) body.w = detail::capped_length(body.w, max_rotation / h);
    else if (turn_sq > max_rotation * max_rotation) body.w *= max_rotation / std::sqrt(turn_sq);
    body.dp += body.v * h;
    body.dq = integrate(body.dq, body.w, h);
}

}  // namespace detail
}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The solver's per-body state for one step: the compact array that steps 4–9 of World::step touch
// (docs/style.md, "The step reads top to bottom"), like Box2D's b2BodyState. It holds the
// velocities and the displacement since the step began, so contact separations can be updated every
// substep without running collision again: s = s0 + n · (Δx_B − Δx_A + R(Δq_B) r_B − R(Δq_A) r_A)
// (Box2D v3, contact_solver.c). Inverse mass and world inverse inertia are frozen for the step
// (Box3D). Slot 0 is a static stand-in: zero velocity, zero inverse mass, so static bodies need no
// branch.
#pragma once

#include "../math/quat.hpp"

#include <limits>

namespace xeno {
namespace detail {

/// Hot per-body solver state, world frame: what every substep reads and writes. 13 numbers (52
/// bytes in float, 104 in double) so that four bodies' states sit in about three cache lines and
/// a group of SIMD lanes gathers them with a few transposes (wide_contact_solver.hpp, which also
/// relies on this order); the masses, read only when rows are prepared, live in SolverMass.
template <class T>
struct SolverBody {
    Vec3<T> v{};                       ///< m/s
    Vec3<T> w{};                       ///< rad/s
    Vec3<T> dp{};                      ///< m, position change since the step began
    Quat<T> dq = Quat<T>::identity();  ///< rotation since the step began (world)

    /// Velocity of the material point at offset r.
    Vec3<T> velocity_at(const Vec3<T>& r) const { return v + cross(w, r); }
};
static_assert(sizeof(SolverBody<float>) == 13 * sizeof(float), "the hot state is 13 packed numbers");
static_assert(sizeof(SolverBody<double>) == 13 * sizeof(double), "the hot state is 13 packed numbers");

/// A solver body's inverse mass and world inverse inertia, frozen for the step (Box3D). Joint rows
/// carry a copy of their two bodies'; contact rows fold them into their Jacobians.
template <class T>
struct SolverMass {
    T inv_mass{};            ///< 1/kg, 0 for static and kinematic
    Mat3<T> inv_inertia{};   ///< world
    bool spins_far = false;  ///< turns more than a quarter of a radian in the step (levers_turn_far)
};

/// Applies an impulse P (N·s) at offset r from the centre of mass: Δv = P/m, Δω = I⁻¹ (r × P).
template <class T>
void apply_impulse(SolverBody<T>& body, const SolverMass<T>& mass, const Vec3<T>& r, const Vec3<T>& p) {
    body.v += p * mass.inv_mass;
    body.w += mass.inv_inertia * cross(r, p);
}

/// Soft-constraint coefficients for a spring–damper of frequency `hertz` and damping ratio zeta
/// integrated implicitly over h (Catto, "Soft Constraints", GDC 2011; Box2D's b2MakeSoft). With
/// ω = 2π hertz: bias_rate = ω/(2ζ + hω), mass_scale = hω(2ζ + hω)/(1 + hω(2ζ + hω)),
/// impulse_scale = 1/(1 + hω(2ζ + hω)). hertz = 0 gives a rigid row without bias.
template <class T>
struct Softness {
    T bias_rate = T(0);  ///< 1/s: fraction of the position error turned into velocity per second
    T mass_scale = T(1);
    T impulse_scale = T(0);

    static Softness make(T hertz, T zeta, T h) {
        if (hertz == T(0)) return {};
        const T omega = T(2) * ScalarTraits<T>::pi * hertz;
        const T a1 = T(2) * zeta + h * omega;
        const T a2 = h * omega * a1;
        // Any finite ratio ζ ≥ 0 is accepted, and one near the top of T's range overflows a1 or a2
        // (a2 · a3 was then ∞ · 0, NaN, and the step was discarded: bodies froze). The limit as
        // ζ → ∞: a rigid velocity row that corrects no position error.
        if (!(a2 <= std::numeric_limits<T>::max())) return {T(0), T(1), T(0)};
        const T a3 = T(1) / (T(1) + a2);
        return {omega / a1, a2 * a3, a3};
    }
};

}  // namespace detail
}  // namespace xeno

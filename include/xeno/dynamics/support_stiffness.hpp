// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// How fast a body rings on its supports. A soft contact point of effective mass m_i is a spring
// of stiffness m_i ω² along its Jacobian J_i = (n, r_i × n) (docs/solver-design.md, "Soft step"),
// so a body resting on static ground is a mass on springs: its modes there have frequencies
// ω √λ, λ the eigenvalues of M⁻¹K with K = Σ m_i J_iᵀ J_i and M the body's 6 × 6 mass matrix.
// The fastest mode is the one one sweep per substep must damp. Measured by this file's
// support_stiffness: a unit box on one face has λ = 1.5 (it rocks on its corners at √1.5 ω;
// bouncing straight up and down is λ = 1), a box in a corner 3 (it rocks about the edge it sits
// in), the stacked tables of `compound-stack` 6.8 on their sixteen leg points. World lowers such
// bodies' static contact frequency to bring λ back to 1.5 (World::share_support_stiffness).
#pragma once

#include "solver_body.hpp"

#include <cmath>
#include <cstddef>

namespace xeno {
namespace detail {

/// λ above which a body's static contacts are softened: a box on one face, which every stack
/// test passes with.
inline constexpr double support_stiffness_limit = 1.5;

/// And the most ωh a body held by two or more manifolds may ring at on its fastest mode, h the
/// substep: at the default 8 substeps a table's legs at λ = 1.5 (ωh = 1.44) trembled at 4 mm/s;
/// at 0.8 it stands still (docs/solver.md, "Support stiffness").
inline constexpr double support_omega_h_limit = 0.8;

/// One contact point holding a body, as the body sees it.
template <class T>
struct SupportRow {
    Vec3<T> linear;   ///< n
    Vec3<T> angular;  ///< r × n, r from the body's centre of mass to the point
    T mass;           ///< the point's effective normal mass, kg
};

/// The largest eigenvalue of M⁻¹K for the rows holding one body (see the top of this file), by
/// power iteration on impulses p: x = M⁻¹p, p' = Kx; the Rayleigh quotient xᵀKx / xᵀMx =
/// x·p' / x·p approaches λ from below as (λ₂/λ₁)^2k, within 3e-5 of it for a box on a face after
/// the fixed 24 iterations (a fixed count: the same bits on every run). The start holds every
/// row at a different weight, so no mode is missed by symmetry. 0 if the rows do not load the
/// body (zero or non-finite).
template <class T>
T support_stiffness(const SupportRow<T>* rows, std::size_t count, const SolverMass<T>& mass) {
    Vec3<T> force{}, torque{};
    for (std::size_t i = 0; i < count; ++i) {
        const T weight = T(1) + T(0.37) * static_cast<T>(i);
        force += rows[i].linear * weight;
        torque += rows[i].angular * weight;
    }
    T lambda = T(0);
    for (int iteration = 0; iteration < 24; ++iteration) {
        const Vec3<T> v = force * mass.inv_mass, w = mass.inv_inertia * torque;
        Vec3<T> next_force{}, next_torque{};
        for (std::size_t i = 0; i < count; ++i) {
            const T stretch = rows[i].mass * (dot(rows[i].linear, v) + dot(rows[i].angular, w));
            next_force += rows[i].linear * stretch;
            next_torque += rows[i].angular * stretch;
        }
        const T work = dot(v, force) + dot(w, torque);
        const T size = std::sqrt(dot(next_force, next_force) + dot(next_torque, next_torque));
        if (!(work > T(0)) || !(size > T(0)) || !std::isfinite(size)) return T(0);
        lambda = (dot(v, next_force) + dot(w, next_torque)) / work;
        force = next_force / size;
        torque = next_torque / size;
    }
    return lambda;
}

}  // namespace detail
}  // namespace xeno

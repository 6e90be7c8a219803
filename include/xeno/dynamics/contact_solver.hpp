// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Sequential impulses on contacts (Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005;
// "Fast and Simple Physics using Sequential Impulses", GDC 2006; docs/solver-design.md, "Sequential
// impulses"), in the phases World::step calls: prepare → (per substep: warm_start → solve(bias) →
// relax) → restitution → store. Per contact point one normal row; per manifold one two-axis
// friction row at the centre of the patch and one twist row about the normal (Box3D's central
// friction; docs/solver-design.md, "Central friction"): order-independent, so a symmetric box
// sliding straight stays straight.
//
// Normal row, with the current separation s updated from the bodies' displacement this step:
//   s > 0 (speculative)  bias = s/h: the bodies may close the gap this substep, not more;
//   s ≤ 0, soft step     Δλ = −m_n (μs (v_n + max(β s, −v_push))) − γs λ   (soft spring–damper);
//   s ≤ 0, baumgarte     bias = max(β/h · min(s + slop, 0), −v_push), rigid row;
//   relax pass           bias 0, rigid: removes the bias velocity before positions are final, so
//                        overlap recovery adds no kinetic energy.
// Then λ_total = max(λ_total + Δλ, 0) on the accumulated impulse (never the increment).
// Friction: |λ_t| ≤ µ Σ λ_n on the 2-vector (a disc, not a square); twist: |λ_τ| ≤ µ Σ ℓ_i λ_n,i.
// Restitution: after the substeps, rows that approached faster than the threshold before the
// step and carried impulse get the target v_n = −e v_n⁻ (velocity captured before gravity was
// added, so restitution adds no energy).
#pragma once

#include "settings.hpp"
#include "solver_body.hpp"

#include <array>
#include <vector>

namespace xeno {
namespace detail {

/// One contact point's row, world frame, rebuilt every step.
template <class T>
struct ContactConstraintPoint {
    Vec3<T> r_a{}, r_b{};          ///< m, from each centre of mass to the contact point
    T adjusted_separation{};       ///< m: s0 − n·(r_b − r_a), so s = n·(Δ of the anchors) + this
    T normal_mass{};               ///< kg: 1 / (n row's effective inverse mass)
    T normal_impulse{};            ///< N·s per substep, accumulated
    T max_normal_impulse{};        ///< N·s, the largest this step
    T step_impulse{};              ///< N·s, summed over the substeps (events)
    T relative_velocity{};         ///< m/s along n before the step (restitution)
};

/// One manifold's rows.
template <class T>
struct ContactConstraint {
    std::uint32_t a = 0, b = 0;    ///< solver body indices (0: static stand-in)
    std::uint32_t manifold = 0;    ///< index of the manifold it came from
    Vec3<T> normal{}, t1{}, t2{};  ///< unit, world: normal A → B and two tangents
    T friction{}, restitution{};
    Softness<T> softness{};
    int count = 0;
    std::array<ContactConstraintPoint<T>, 4> points{};
    // Central friction and twist.
    Vec3<T> rc_a{}, rc_b{};        ///< m, centres of mass to the patch centre
    T k11{}, k12{}, k22{};         ///< inverse of the 2×2 tangent effective-mass matrix
    T friction_1{}, friction_2{};  ///< N·s per substep along t1, t2
    T twist_mass{}, twist_impulse{}, twist_lever{};  ///< kg·m², N·m·s, m (mean lever of the points)
};

/// What one solver pass needs to know.
template <class T>
struct SolvePass {
    T inv_h{};         ///< 1/s, the (sub)step rate
    bool use_bias{};   ///< false in the relax pass
    SolverMode mode{};
    T baumgarte{};
    T linear_slop{};
    T max_push_out_speed{};
};


template <class T>
void apply_contact_impulses(const ContactConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b) {
    for (int i = 0; i < c.count; ++i) {
        const ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
        const Vec3<T> impulse = c.normal * p.normal_impulse;
        a.apply(p.r_a, -impulse);
        b.apply(p.r_b, impulse);
    }
    const Vec3<T> friction = c.t1 * c.friction_1 + c.t2 * c.friction_2;
    a.apply(c.rc_a, -friction);
    b.apply(c.rc_b, friction);
    const Vec3<T> twist = c.normal * c.twist_impulse;
    a.w -= a.inv_inertia * twist;
    b.w += b.inv_inertia * twist;
}


/// Applies last step's impulses (warm start) to the bodies.
template <class T>
void warm_start(const std::vector<ContactConstraint<T>>& constraints, std::vector<SolverBody<T>>& bodies) {
    for (const ContactConstraint<T>& c : constraints) detail::apply_contact_impulses(c, bodies[c.a], bodies[c.b]);
    bodies[0] = SolverBody<T>{};  // the static stand-in stays at rest
}

/// One Gauss–Seidel sweep over every contact row (normal rows first, then friction and twist).
template <class T>
void solve_contacts(std::vector<ContactConstraint<T>>& constraints, std::vector<SolverBody<T>>& bodies, const SolvePass<T>& pass) {
    for (ContactConstraint<T>& c : constraints) {
        SolverBody<T>& a = bodies[c.a];
        SolverBody<T>& b = bodies[c.b];
        T total_normal = T(0), total_twist_bound = T(0);
        for (int i = 0; i < c.count; ++i) {
            ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
            // Current separation from the displacement of both anchors this step.
            const Vec3<T> d = (b.dp - a.dp) + (rotate(b.dq, p.r_b) - rotate(a.dq, p.r_a));
            const T s = dot(d, c.normal) + p.adjusted_separation;
            T bias = T(0), mass_scale = T(1), impulse_scale = T(0);
            if (s > T(0)) {
                bias = s * pass.inv_h;  // speculative: close the gap, no further
            } else if (pass.use_bias) {
                if (pass.mode == SolverMode::soft_step) {
                    bias = std::max(c.softness.bias_rate * s, -pass.max_push_out_speed);
                    mass_scale = c.softness.mass_scale;
                    impulse_scale = c.softness.impulse_scale;
                } else {
                    bias = std::max(pass.baumgarte * pass.inv_h * std::min(s + pass.linear_slop, T(0)), -pass.max_push_out_speed);
                }
            }
            const T vn = dot(b.velocity_at(p.r_b) - a.velocity_at(p.r_a), c.normal);
            const T delta = -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
            const T updated = std::max(p.normal_impulse + delta, T(0));
            const T applied = updated - p.normal_impulse;
            p.normal_impulse = updated;
            p.max_normal_impulse = std::max(p.max_normal_impulse, updated);
            const Vec3<T> impulse = c.normal * applied;
            a.apply(p.r_a, -impulse);
            b.apply(p.r_b, impulse);
            total_normal += updated;
        }
        total_twist_bound = c.friction * c.twist_lever * total_normal;

        // Central friction: a 2-D row at the patch centre, clamped to the Coulomb disc.
        const Vec3<T> dv = b.velocity_at(c.rc_b) - a.velocity_at(c.rc_a);
        const T v1 = dot(dv, c.t1), v2 = dot(dv, c.t2);
        T f1 = c.friction_1 - (c.k11 * v1 + c.k12 * v2);
        T f2 = c.friction_2 - (c.k12 * v1 + c.k22 * v2);
        const T bound = c.friction * total_normal;
        const T magnitude_sq = f1 * f1 + f2 * f2;
        if (magnitude_sq > bound * bound) {
            const T scale = bound / std::sqrt(magnitude_sq);
            f1 *= scale;
            f2 *= scale;
        }
        const Vec3<T> friction = c.t1 * (f1 - c.friction_1) + c.t2 * (f2 - c.friction_2);
        c.friction_1 = f1;
        c.friction_2 = f2;
        a.apply(c.rc_a, -friction);
        b.apply(c.rc_b, friction);

        // Twist friction about the normal.
        if (c.twist_mass > T(0)) {
            const T wn = dot(b.w - a.w, c.normal);
            const T updated = clamp(c.twist_impulse - c.twist_mass * wn, -total_twist_bound, total_twist_bound);
            const Vec3<T> twist = c.normal * (updated - c.twist_impulse);
            c.twist_impulse = updated;
            a.w -= a.inv_inertia * twist;
            b.w += b.inv_inertia * twist;
        }
    }
    bodies[0] = SolverBody<T>{};
}

/// Adds each row's substep impulse to its step total (after every substep).
template <class T>
void accumulate_step_impulses(std::vector<ContactConstraint<T>>& constraints) {
    for (ContactConstraint<T>& c : constraints)
        for (int i = 0; i < c.count; ++i) {
            ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
            p.step_impulse += p.normal_impulse;
        }
}

/// The restitution pass after the substeps (see the file comment). A few sweeps: one
/// Gauss–Seidel sweep over a face's four points leaves the face short of the target speed
/// (measured: a flat box bounced to 96 % of e v), and only bouncing rows take part.
template <class T>
void apply_restitution(std::vector<ContactConstraint<T>>& constraints, std::vector<SolverBody<T>>& bodies, T threshold) {
    constexpr int sweeps = 4;
    for (int sweep = 0; sweep < sweeps; ++sweep)
    for (ContactConstraint<T>& c : constraints) {
        if (c.restitution == T(0)) continue;
        SolverBody<T>& a = bodies[c.a];
        SolverBody<T>& b = bodies[c.b];
        for (int i = 0; i < c.count; ++i) {
            ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
            if (p.relative_velocity > -threshold || p.max_normal_impulse == T(0)) continue;
            const T vn = dot(b.velocity_at(p.r_b) - a.velocity_at(p.r_a), c.normal);
            const T delta = -p.normal_mass * (vn + c.restitution * p.relative_velocity);
            const T updated = std::max(p.normal_impulse + delta, T(0));
            const Vec3<T> impulse = c.normal * (updated - p.normal_impulse);
            p.step_impulse += updated - p.normal_impulse;
            p.normal_impulse = updated;
            p.max_normal_impulse = std::max(p.max_normal_impulse, updated);
            a.apply(p.r_a, -impulse);
            b.apply(p.r_b, impulse);
        }
    }
    bodies[0] = SolverBody<T>{};
}


}  // namespace detail
}  // namespace xeno

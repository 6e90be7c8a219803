// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The contact rows of contact_solver.hpp solved W manifolds at a time (docs/solver.md, "Wide
// rows"; Box2D v3 and Box3D's contact_solver.c do the same with their wide constraints). Rows are
// coloured (constraint_graph.hpp) and packed colour by colour into groups of W lanes, one
// manifold per lane; a group gathers its bodies' velocities and step displacements into lanes,
// runs the normal, central-friction and twist rows in SIMD, and scatters the velocities back.
// Nothing in one colour shares a moving body, so the lanes are independent and a row gets the
// same bits whatever W it ran in; the overflow rows run through the same code one at a time.
//
// Per lane the lever arms are precomputed once per step (r × n for each point, rc × t for
// friction), and each body's world inverse inertia is copied into the lane as its 6 distinct
// numbers, so the solve reads no masses from the bodies. The images I⁻¹ (r × n) are formed in
// the sweep instead of stored: they do not depend on the impulses, so they run beside the
// Gauss–Seidel chain, and storing them (42 numbers a lane) made a group 25 % larger, which cost
// more than the products once the rows outgrow the cache (docs/solver.md, "Wide rows").
#pragma once

#include "../math/wide.hpp"
#include "../task_system.hpp"
#include "constraint_graph.hpp"
#include "contact_solver.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace xeno {
namespace detail {

/// One point slot of W manifolds.
template <class V>
struct WidePoint {
    WideVec3<V> r_a, r_b;    ///< m, centres of mass to the point
    WideVec3<V> rn_a, rn_b;  ///< r × n
    V adjusted_separation, normal_mass, normal_impulse, max_normal_impulse, step_impulse;
    V approach;  ///< m/s, v_n under gravity and applied forces alone, up to the impact (take_approach_wide)
    V landing;   ///< m/s, v_n on reaching the surface from the impact substep's start (ContactConstraintPoint::relative_velocity)
};

/// A symmetric 3 × 3 matrix in lanes (a world inverse inertia): its upper triangle.
template <class V>
struct WideSym3 {
    V xx, xy, xz, yy, yz, zz;
    friend WideVec3<V> operator*(const WideSym3& m, const WideVec3<V>& v) {
        return {m.xx * v.x + m.xy * v.y + m.xz * v.z, m.xy * v.x + m.yy * v.y + m.yz * v.z, m.xz * v.x + m.yz * v.y + m.zz * v.z};
    }
};

/// W manifolds side by side. Lanes beyond the colour's rows are padding: both bodies the static
/// stand-in, no points, every number zero.
template <class T, int W>
struct WideContact {
    using V = Wide<T, W>;
    std::uint32_t a[W], b[W];  ///< solver bodies (0: static stand-in)
    std::uint32_t row[W];      ///< index into the scalar rows (padding: ~0)
    int max_count;             ///< points of the fullest lane
    int min_count;             ///< points of the emptiest lane that holds a manifold
    bool rolls;                ///< some lane has a rounded side (round_a or round_b > 0)
    bool bounces;              ///< some lane has a restitution (its points' approach speeds are kept)
    bool turns;                ///< some lane has a side whose levers turn or that slips (its WideTurn)
    bool slips;                ///< some lane has a chord_slip (in its WideTurn)
    V count;                   ///< points per lane
    WideVec3<V> normal, t1, t2;
    V inv_mass_a, inv_mass_b, friction;
    V normal_acceleration;                     ///< m/s², ContactConstraint::normal_acceleration
    WideSym3<V> inv_inertia_a, inv_inertia_b;  ///< world, frozen for the step
    V bias_rate, mass_scale, impulse_scale;    ///< the lane's softness
    WidePoint<V> points[4];
    WideVec3<V> a1, a2, b1, b2;  ///< rc × t1, rc × t2 for A and B
    V k11, k12, k22, friction_1, friction_2;
    V twist_mass, twist_impulse, twist_friction;  ///< twist_friction: µ × the patch's mean radius
    V round_a, round_b;                           ///< radii of the rounded surfaces (ContactConstraint)
};

/// What a group that turns levers (turned_moment) needs besides its own numbers, kept beside the
/// groups: held in each group, it made every group 6 % longer (2.2 KB in float), turning or not.
template <class V>
struct WideTurn {
    V turn_a, turn_b;        ///< 1 where the lane's side turns its levers, else 0
    WideVec3<V> rc_a, rc_b;  ///< m, the levers to the patch centres at the start of the step
    V slip_1, slip_2;        ///< m/s, ContactConstraint::slip_1, slip_2
};

/// Turning levers. A row's levers are fixed in world space for the step, while its bodies turn
/// through the substeps. For most bodies that is a small error, but a body that spins fast turns
/// a point near its spin axis, and not on it, far enough that the rows held still a point that
/// had moved: the apex of a top spun at 300 rad/s and tilted 0.1 rad slid 0.2 m in 2 s
/// (docs/solver.md, "A fast top: turning levers"). The sides marked to turn (ContactConstraint::
/// turns_a, turns_b) take their levers turned by the body's rotation so far, Δq r, as the joints
/// do; the others, and a round side, whose contact point stays where it touches, keep theirs.
/// Lane by lane (a select), so a lane's numbers do not depend on the lanes beside it.
/// `lanes` holds 1 where the side turns: the moment of the turned lever there, the fixed one
/// elsewhere.
template <class T, int W>
XENO_WIDE_INLINE WideVec3<Wide<T, W>> turned_moment(const Wide<T, W>& lanes, const WideVec3<Wide<T, W>>& fixed,
                                                    const WideQuat<Wide<T, W>>& dq, const WideVec3<Wide<T, W>>& lever,
                                                    const WideVec3<Wide<T, W>>& direction) {
    return select(lanes > Wide<T, W>::splat(T(0)), cross(rotate(dq, lever), direction), fixed);
}

/// The turned value in the routines compiled for groups that turn levers, else the stored one,
/// read where it is used (Turning false is the code, and the bytes read, of fixed levers alone:
/// a copy of the stored moments held in registers made the box pyramid's solve 11 % slower).
template <bool Turning, class X>
XENO_WIDE_INLINE const X& pick(const X& turned, const X& fixed) {
    if constexpr (Turning) return turned;
    else return fixed;
}

/// The velocities (and, for the biased rows, the step displacement) of W bodies in lanes.
template <class V>
struct WideBody {
    WideVec3<V> v, w, dp;
    WideQuat<V> dq;
};

/// A point's moments r × n of both sides with turned levers (turned_moment), into rn_a, rn_b.
template <class T, int W>
XENO_WIDE_INLINE void turned_point_moments(const WideContact<T, W>& c, const WideTurn<Wide<T, W>>& t,
                                           const WidePoint<Wide<T, W>>& p, const WideBody<Wide<T, W>>& A,
                                           const WideBody<Wide<T, W>>& B, WideVec3<Wide<T, W>>& rn_a,
                                           WideVec3<Wide<T, W>>& rn_b) {
    rn_a = turned_moment(t.turn_a, p.rn_a, A.dq, p.r_a, c.normal);
    rn_b = turned_moment(t.turn_b, p.rn_b, B.dq, p.r_b, c.normal);
}

/// The friction rows' moments rc × t1, rc × t2 of both sides with turned levers (turned_moment).
template <class V>
struct FrictionMoments {
    WideVec3<V> a1, a2, b1, b2;
};
template <class T, int W>
XENO_WIDE_INLINE FrictionMoments<Wide<T, W>> friction_moments(const WideContact<T, W>& c, const WideTurn<Wide<T, W>>& t,
                                                              const WideBody<Wide<T, W>>& A, const WideBody<Wide<T, W>>& B) {
    return {turned_moment(t.turn_a, c.a1, A.dq, t.rc_a, c.t1), turned_moment(t.turn_a, c.a2, A.dq, t.rc_a, c.t2),
            turned_moment(t.turn_b, c.b1, B.dq, t.rc_b, c.t1), turned_moment(t.turn_b, c.b2, B.dq, t.rc_b, c.t2)};
}

/// The solver body's first 13 numbers, v, w, dp and dq in that order, are read and written as
/// one record (load_transposed): the layout this relies on.
template <class T>
constexpr bool solver_body_is_a_record() {
    return std::is_standard_layout_v<SolverBody<T>> && offsetof(SolverBody<T>, v) == 0 &&
           offsetof(SolverBody<T>, w) == 3 * sizeof(T) && offsetof(SolverBody<T>, dp) == 6 * sizeof(T) &&
           offsetof(SolverBody<T>, dq) == 9 * sizeof(T) && sizeof(Vec3<T>) == 3 * sizeof(T) && sizeof(Quat<T>) == 4 * sizeof(T) &&
           offsetof(Quat<T>, w) == 0;
}

template <class T, int W>
XENO_WIDE_INLINE WideBody<Wide<T, W>> gather(const std::vector<SolverBody<T>>& bodies, const std::uint32_t (&index)[W],
                                             bool displacement) {
    static_assert(solver_body_is_a_record<T>());
    using V = Wide<T, W>;
    const T* src[W];
    for (int l = 0; l < W; ++l) src[l] = reinterpret_cast<const T*>(&bodies[index[l]]);
    V rows[13];
    load_transposed(src, displacement ? 13 : 6, rows);
    WideBody<V> g;
    g.v = {rows[0], rows[1], rows[2]};
    g.w = {rows[3], rows[4], rows[5]};
    if (displacement) {
        g.dp = {rows[6], rows[7], rows[8]};
        g.dq = {rows[9], {rows[10], rows[11], rows[12]}};
    }
    return g;
}

/// Writes the lanes' velocities back; the static stand-in (padding and static sides) is written
/// to a scratch record instead.
template <class T, int W>
XENO_WIDE_INLINE void scatter(const WideBody<Wide<T, W>>& g, std::vector<SolverBody<T>>& bodies,
                              const std::uint32_t (&index)[W]) {
    T sink[W][6];
    T* dst[W];
    for (int l = 0; l < W; ++l) dst[l] = index[l] == 0 ? sink[l] : reinterpret_cast<T*>(&bodies[index[l]]);
    const Wide<T, W> rows[6] = {g.v.x, g.v.y, g.v.z, g.w.x, g.w.y, g.w.z};
    store_transposed(rows, 6, dst);
}

/// Applies an impulse along the lanes' directions to both bodies where `m` holds (every lane
/// when `masked` is false): A gets −(lin × λ) / −(ang_a λ), B gets +(lin × λ) / +(ang_b λ).
template <class V>
XENO_WIDE_INLINE void apply_wide(WideBody<V>& A, WideBody<V>& B, bool masked, const typename V::Mask& m, const WideVec3<V>& lin,
                                 const V& lambda, const V& inv_mass_a, const V& inv_mass_b, const WideVec3<V>& ang_a,
                                 const WideVec3<V>& ang_b) {
    const WideVec3<V> va = A.v - lin * (lambda * inv_mass_a), wa = A.w - ang_a * lambda;
    const WideVec3<V> vb = B.v + lin * (lambda * inv_mass_b), wb = B.w + ang_b * lambda;
    A.v = masked ? select(m, va, A.v) : va;
    A.w = masked ? select(m, wa, A.w) : wa;
    B.v = masked ? select(m, vb, B.v) : vb;
    B.w = masked ? select(m, wb, B.w) : wb;
}

/// Warm start: last step's impulses applied to both bodies. Applying impulses needs no velocity,
/// so the angular impulses are summed first (points, then friction, then twist: the order of
/// apply_contact_impulses) and each body's inverse inertia applied once.
template <bool Turning, class T, int W>
void warm_start_group(const WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, std::vector<SolverBody<T>>& bodies) {
    using V = Wide<T, W>;
    WideBody<V> A = gather<T, W>(bodies, c.a, Turning), B = gather<T, W>(bodies, c.b, Turning);
    const V zero = V::splat(T(0));
    V push = zero;
    WideVec3<V> turn_a{zero, zero, zero}, turn_b{zero, zero, zero};
    for (int i = 0; i < c.max_count; ++i) {
        const WidePoint<V>& p = c.points[i];
        // A lane's empty slots keep every sum's bits (a select, not an add of zero).
        const bool masked = i >= c.min_count;
        const typename V::Mask active = V::splat(T(i)) < c.count;
        const V pushed = push + p.normal_impulse;
        WideVec3<V> turned_a, turned_b;
        if constexpr (Turning) turned_point_moments(c, *t, p, A, B, turned_a, turned_b);
        const WideVec3<V>& rn_a = pick<Turning>(turned_a, p.rn_a);
        const WideVec3<V>& rn_b = pick<Turning>(turned_b, p.rn_b);
        const WideVec3<V> ta = turn_a + rn_a * p.normal_impulse, tb = turn_b + rn_b * p.normal_impulse;
        push = masked ? select(active, pushed, push) : pushed;
        turn_a = masked ? select(active, ta, turn_a) : ta;
        turn_b = masked ? select(active, tb, turn_b) : tb;
    }
    // Padding lanes need no mask: they write to the static stand-in, which scatter skips.
    const WideVec3<V> f = c.normal * push + (c.t1 * c.friction_1 + c.t2 * c.friction_2);
    FrictionMoments<V> m;
    if constexpr (Turning) m = friction_moments(c, *t, A, B);
    const WideVec3<V>&a1 = pick<Turning>(m.a1, c.a1), &a2 = pick<Turning>(m.a2, c.a2);
    const WideVec3<V>&b1 = pick<Turning>(m.b1, c.b1), &b2 = pick<Turning>(m.b2, c.b2);
    turn_a = turn_a + (a1 * c.friction_1 + a2 * c.friction_2) + c.normal * c.twist_impulse;
    turn_b = turn_b + (b1 * c.friction_1 + b2 * c.friction_2) + c.normal * c.twist_impulse;
    A.v = A.v - f * c.inv_mass_a;
    A.w = A.w - c.inv_inertia_a * turn_a;
    B.v = B.v + f * c.inv_mass_b;
    B.w = B.w + c.inv_inertia_b * turn_b;
    scatter<T, W>(A, bodies, c.a);
    scatter<T, W>(B, bodies, c.b);
}
/// The warm start of a group with fixed levers; of any group, `t` its WideTurn where it turns
/// levers (c.turns). WideContactRows calls warm_start_fixed alone while no group turns (as
/// solve_fixed).
template <class T, int W>
void warm_start_fixed(const WideContact<T, W>& c, std::vector<SolverBody<T>>& bodies) {
    warm_start_group<false>(c, static_cast<const WideTurn<Wide<T, W>>*>(nullptr), bodies);
}
template <class T, int W>
void warm_start_wide(const WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, std::vector<SolverBody<T>>& bodies) {
    if (c.turns) warm_start_group<true>(c, t, bodies);
    else warm_start_fixed(c, bodies);
}

/// Restitution's approach speed at the impact: each point's v_n at the start of the step plus
/// what gravity and the applied forces add to it in each substep, until the point first carries
/// impulse (docs/solver-design.md, "Restitution"). Not the bodies' own v_n at the impact: that
/// holds the impulses of the other contacts too, and in a row of touching balls the second contact
/// took as its approach the speed the first impact had just given the ball between them, and
/// bounced it again (a ball striking three with e = 1 left them 3 times the energy it brought).
/// The landing speed V kept for the rebound (set_rebounds) is taken from the point's gap s and
/// approach v at the start of the substep in which it first carries impulse, by the energy the
/// substeps' integrator keeps, ½V² = ½v² − a s + ½ a h v (a the normal acceleration): the
/// approach with that substep's whole gain, v + a h, was up to g h off, depending on where in
/// its substep the impact fell.
template <class T, int W>
void take_approach_wide(WideContact<T, W>& c, const std::vector<SolverBody<T>>& bodies, T h) {
    using V = Wide<T, W>;
    const V zero = V::splat(T(0)), two = V::splat(T(2)), gain = c.normal_acceleration * V::splat(h);
    const WideBody<V> A = gather<T, W>(bodies, c.a, true), B = gather<T, W>(bodies, c.b, true);
    const WideVec3<V> n_b = rotate(conjugate(B.dq), c.normal), n_a = rotate(conjugate(A.dq), c.normal);  // as solve_wide
    const V moved = c.rolls ? dot(B.dp - A.dp, c.normal) + rolling_rise(c, n_a, n_b) : dot(B.dp - A.dp, c.normal);
    for (int i = 0; i < c.max_count; ++i) {
        WidePoint<V>& p = c.points[i];
        const V gap = max(moved + (dot(n_b, p.r_b) - dot(n_a, p.r_a)) + p.adjusted_separation, zero);
        const V v = p.approach, half = V::splat(T(0.5));
        const V energy = half * v * v - c.normal_acceleration * gap + half * gain * v;
        const V landing = select(v + gain < zero, zero - sqrt(max(two * energy, zero)), v + gain);
        const typename V::Mask struck = p.max_normal_impulse > zero;  // kept from the substep it first carried impulse
        p.landing = select(struck, p.landing, landing);
        p.approach = select(struck, p.approach, p.approach + gain);
    }
}

/// A rounded surface of radius ρ (a sphere, a capsule, a cylinder's side) is a core swept by a
/// ball: its contact point is the core's point plus ρ towards the other body, and only the core's
/// point turns with the body. An anchor fixed in the body turns whole, so a ball rolling through
/// an angle θ in a step saw its anchor rise ρ (1 − cos θ) off the ground and sank that much into
/// it (4.8 mm for a 0.5 m ball at 10 m/s, and it lost 1.6 % of its speed in 2 s). The part of the
/// anchor along the ball's radius is taken back out: ρ (n · R(Δq) n − 1) for each side, ≤ 0, and
/// 0 for a flat side (ρ = 0) or a body that has not turned (docs/solver.md, "Rolling").
template <class T, int W>
XENO_WIDE_INLINE Wide<T, W> rolling_rise(const WideContact<T, W>& c, const WideVec3<Wide<T, W>>& n_a,
                                         const WideVec3<Wide<T, W>>& n_b) {
    const Wide<T, W> one = Wide<T, W>::splat(T(1));
    return c.round_b * (dot(n_b, c.normal) - one) + c.round_a * (dot(n_a, c.normal) - one);
}

/// One Gauss–Seidel sweep over the normal rows of W manifolds, points 0 … 3 in turn; point i of a
/// lane is solved where i < limit (c.count: all of the lane's points; 0: none, the lane keeps its
/// values). `masked_all` false lets the points every lane has skip that test. Returns Σ |Δλ| per
/// lane.
template <bool Turning, class T, int W>
XENO_WIDE_INLINE Wide<T, W> sweep_normal_rows(WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, WideBody<Wide<T, W>>& A,
                                              WideBody<Wide<T, W>>& B, const WideVec3<Wide<T, W>>& n_a,
                                              const WideVec3<Wide<T, W>>& n_b, const Wide<T, W>& moved, const SolvePass<T>& pass,
                                              const Wide<T, W>& limit, bool masked_all) {
    using V = Wide<T, W>;
    const V zero = V::splat(T(0)), one = V::splat(T(1)), inv_h = V::splat(pass.inv_h);
    const V max_push = V::splat(pass.max_push_out_speed);
    V pushed = zero;
    for (int i = 0; i < c.max_count; ++i) {
        WidePoint<V>& p = c.points[i];
        // Points every real lane has need no mask (padding lanes are never written back).
        const bool masked = masked_all || i >= c.min_count;
        const typename V::Mask active = V::splat(T(i)) < limit;
        const V s = moved + (dot(n_b, p.r_b) - dot(n_a, p.r_a)) + p.adjusted_separation;
        V bias = zero, mass_scale = one, impulse_scale = zero;
        if (pass.use_bias && pass.mode == SolverMode::soft_step) {
            bias = max(c.bias_rate * s, zero - max_push);
            mass_scale = c.mass_scale;
            impulse_scale = c.impulse_scale;
        } else if (pass.use_bias) {
            bias = max(V::splat(pass.baumgarte * pass.inv_h) * min(s + V::splat(pass.linear_slop), zero), zero - max_push);
        }
        const typename V::Mask speculative = s > zero;  // close the gap, no further
        bias = select(speculative, s * inv_h, bias);
        mass_scale = select(speculative, one, mass_scale);
        impulse_scale = select(speculative, zero, impulse_scale);

        WideVec3<V> turned_a, turned_b;
        if constexpr (Turning) turned_point_moments(c, *t, p, A, B, turned_a, turned_b);
        const WideVec3<V>& rn_a = pick<Turning>(turned_a, p.rn_a);
        const WideVec3<V>& rn_b = pick<Turning>(turned_b, p.rn_b);
        const V vn = dot(B.v - A.v, c.normal) + dot(B.w, rn_b) - dot(A.w, rn_a);
        const V delta = zero - p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
        const V clamped = max(p.normal_impulse + delta, zero);
        const V updated = masked ? select(active, clamped, p.normal_impulse) : clamped;
        const V applied = updated - p.normal_impulse;
        p.normal_impulse = updated;
        p.max_normal_impulse = max(p.max_normal_impulse, updated);
        apply_wide(A, B, masked, active, c.normal, applied, c.inv_mass_a, c.inv_mass_b, c.inv_inertia_a * rn_a,
                   c.inv_inertia_b * rn_b);
        pushed = pushed + abs(applied);
    }
    return pushed;
}

/// The sum of each lane's normal impulses (the friction rows' bound is µ times it).
template <class T, int W>
XENO_WIDE_INLINE Wide<T, W> total_normal_impulse(const WideContact<T, W>& c) {
    using V = Wide<T, W>;
    V total = V::splat(T(0));
    for (int i = 0; i < c.max_count; ++i) {
        const V lambda = c.points[i].normal_impulse;
        total = total + (i >= c.min_count ? select(V::splat(T(i)) < c.count, lambda, V::splat(T(0))) : lambda);
    }
    return total;
}

/// The central friction row and the twist row of W manifolds, bounded by µ × `total`; where
/// `masked`, only the lanes in `active` change.
template <bool Turning, class T, int W>
XENO_WIDE_INLINE void solve_friction_rows(WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, WideBody<Wide<T, W>>& A,
                                          WideBody<Wide<T, W>>& B, const Wide<T, W>& total, bool masked,
                                          const typename Wide<T, W>::Mask& active) {
    using V = Wide<T, W>;
    const V zero = V::splat(T(0)), one = V::splat(T(1));
    // Central friction: a 2-D row at the patch centre, clamped to the Coulomb disc.
    const WideVec3<V> dv = B.v - A.v;
    FrictionMoments<V> m;
    if constexpr (Turning) m = friction_moments(c, *t, A, B);
    const WideVec3<V>&a1 = pick<Turning>(m.a1, c.a1), &a2 = pick<Turning>(m.a2, c.a2);
    const WideVec3<V>&b1 = pick<Turning>(m.b1, c.b1), &b2 = pick<Turning>(m.b2, c.b2);
    V v1 = dot(dv, c.t1) + dot(B.w, b1) - dot(A.w, a1);
    V v2 = dot(dv, c.t2) + dot(B.w, b2) - dot(A.w, a2);
    if constexpr (Turning) {
        if (c.slips) v1 = v1 + t->slip_1, v2 = v2 + t->slip_2;
    }
    V f1 = c.friction_1 - (c.k11 * v1 + c.k12 * v2);
    V f2 = c.friction_2 - (c.k12 * v1 + c.k22 * v2);
    const V bound = c.friction * total;
    const typename V::Mask outside = f1 * f1 + f2 * f2 > bound * bound;
    // Sliding: the impulse goes to the disc's rim along the sliding velocity, not along K⁻¹ v
    // (sliding_friction_step in contact_solver.hpp says why).
    const V mean_mass = (c.k11 + c.k22) * V::splat(T(0.5));
    const V g1 = c.friction_1 - mean_mass * v1, g2 = c.friction_2 - mean_mass * v2;
    const V slide_sq = g1 * g1 + g2 * g2;
    const V scale = bound / sqrt(select(outside, select(slide_sq > zero, slide_sq, one), one));
    f1 = select(outside, g1 * scale, f1);
    f2 = select(outside, g2 * scale, f2);
    if (masked) f1 = select(active, f1, c.friction_1), f2 = select(active, f2, c.friction_2);
    const V d1 = f1 - c.friction_1, d2 = f2 - c.friction_2;
    c.friction_1 = f1;
    c.friction_2 = f2;
    const WideVec3<V> f = c.t1 * d1 + c.t2 * d2;
    apply_wide(A, B, masked, active, f, one, c.inv_mass_a, c.inv_mass_b, c.inv_inertia_a * (a1 * d1 + a2 * d2),
               c.inv_inertia_b * (b1 * d1 + b2 * d2));

    // Twist friction about the normal.
    const typename V::Mask twisting = c.twist_mass > zero;
    const V bound_twist = c.twist_friction * total;
    const V wn = dot(B.w - A.w, c.normal);
    const V twist = min(max(c.twist_impulse - c.twist_mass * wn, zero - bound_twist), bound_twist);
    const V d_twist = twist - c.twist_impulse;
    const V kept = masked ? select(active, select(twisting, twist, c.twist_impulse), c.twist_impulse)
                          : select(twisting, twist, c.twist_impulse);
    const WideVec3<V> wa = select(twisting, A.w - (c.inv_inertia_a * c.normal) * d_twist, A.w);
    const WideVec3<V> wb = select(twisting, B.w + (c.inv_inertia_b * c.normal) * d_twist, B.w);
    c.twist_impulse = kept;
    A.w = masked ? select(active, wa, A.w) : wa;
    B.w = masked ? select(active, wb, B.w) : wb;
}

/// Where a pass marks the bodies its impacts struck (solve_group) for the impact passes across
/// manifolds (WideContactRows::solve): solver body k is marked when a row of it took an impact
/// and it holds another row (`shared[k]`); `any` says that some body was.
struct ImpactMarks {
    const std::uint8_t* shared = nullptr;
    std::uint8_t* marked = nullptr;
    std::atomic<bool>* any = nullptr;
};

/// Marks the moving bodies of the lanes in `lanes` (a bit per lane) that hold another row. A
/// colour's lanes share no moving body, so no two workers write one byte.
template <int W>
void mark_impacts(const std::uint32_t (&a)[W], const std::uint32_t (&b)[W], unsigned lanes, const ImpactMarks& m) {
    for (int l = 0; l < W; ++l) {
        if (((lanes >> l) & 1u) == 0) continue;
        for (const std::uint32_t k : {a[l], b[l]})
            if (k != 0 && m.shared[k] != 0) {
                m.marked[k] = 1;
                m.any->store(true, std::memory_order_relaxed);
            }
    }
}

/// A group's bodies in lanes and what its separations need (solve_group).
template <class V>
struct GroupFrame {
    WideBody<V> A, B;
    WideVec3<V> n_a, n_b;  ///< the normal in each body's frame at the step's start
    V moved;               ///< how far the bodies moved apart along the normal this step
};

template <class T, int W>
XENO_WIDE_INLINE GroupFrame<Wide<T, W>> group_frame(const WideContact<T, W>& c, const std::vector<SolverBody<T>>& bodies) {
    using V = Wide<T, W>;
    GroupFrame<V> f;
    f.A = gather<T, W>(bodies, c.a, true);
    f.B = gather<T, W>(bodies, c.b, true);
    // The current separation of a point is s0 + n · (Δx_B + R(Δq_B) r_B − Δx_A − R(Δq_A) r_A)
    // (contact_solver.hpp). n is the manifold's, so n · R(Δq) r = (R(Δq)ᵀ n) · r: two rotations
    // per manifold instead of two per point.
    f.n_b = rotate(conjugate(f.B.dq), c.normal);
    f.n_a = rotate(conjugate(f.A.dq), c.normal);
    // (A group of flat sides only skips the term: 3 % of a box pyramid's step.)
    const V apart = dot(f.B.dp - f.A.dp, c.normal);
    f.moved = c.rolls ? apart + rolling_rise(c, f.n_a, f.n_b) : apart;
    return f;
}

/// One Gauss–Seidel pass over W manifolds: the rows described in contact_solver.hpp. `marks`
/// (or null) collects the bodies of its impacts.
template <bool Turning, class T, int W>
XENO_WIDE_INLINE void solve_group(WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, std::vector<SolverBody<T>>& bodies,
                                  const SolvePass<T>& pass, const ImpactMarks* marks) {
    using V = Wide<T, W>;
    const V zero = V::splat(T(0));
    GroupFrame<V> g = group_frame(c, bodies);
    WideBody<V>&A = g.A, &B = g.B;
    const WideVec3<V>&n_a = g.n_a, &n_b = g.n_b;
    const V& moved = g.moved;
    const V pushed = sweep_normal_rows<Turning>(c, t, A, B, n_a, n_b, moved, pass, c.count, false);
    // A pass that changes the bodies' speed by more than kImpactSpeed is an impact, and one sweep
    // settles it poorly. The normal rows do not share the impulse evenly over a face: the first
    // point takes the most and the body turns (a 0.5 m cube dropped flat from 0.5 m left the
    // floor turning at 0.5 rad/s, and with e = 1 it left its first bounce 0.19 m/s sideways and
    // tipped by the ninth): such lanes take kImpactSweeps more sweeps of the normal rows. Then the
    // friction row puts µ × the impact's impulse at the patch centre, a moment the normal rows
    // have not answered: a cube landing flat at 2 m/s while sliding at 4 (µ 0.6) left the floor
    // pivoting on its front edge at 2 rad/s and rolled up onto it, where µ < 1 holds it flat. So
    // they take kFrictionRounds more sweeps of both. (Friction inside the first sweeps instead
    // answered the normal rows' uneven first shares, and a box dropped straight slid off.) The
    // other lanes keep their values, so a lane's numbers do not depend on the lanes beside it
    // (the same bits at every width). Resting contacts change by g h a pass.
    constexpr T kImpactSpeed = T(0.2);  // m/s
    constexpr int kImpactSweeps = 3, kFrictionRounds = 4;
    const V speed_change = pushed * (c.inv_mass_a + c.inv_mass_b);
    const typename V::Mask impact = speed_change > V::splat(kImpactSpeed);
    const bool struck = bits(impact) != 0;
    // Bodies struck harder than kHardImpactSpeed get the passes across their manifolds
    // (WideContactRows::solve_impacts): at the threshold of every impact, a pile of 1,000 boxes
    // dropped on the floor solved in 2.9 ms a step instead of 1.7; at 1 m/s, 2.4 ms.
    constexpr T kHardImpactSpeed = T(1);  // m/s
    if (struck && marks != nullptr) {
        const typename V::Mask hard = speed_change > V::splat(kHardImpactSpeed);
        if (bits(hard) != 0) mark_impacts<W>(c.a, c.b, bits(hard), *marks);
    }
    if (struck)
        for (int k = 0; k < kImpactSweeps; ++k)
            sweep_normal_rows<Turning>(c, t, A, B, n_a, n_b, moved, pass, select(impact, c.count, zero), true);
    solve_friction_rows<Turning>(c, t, A, B, total_normal_impulse(c), false, impact);  // every lane (unmasked)
    if (struck)
        for (int k = 0; k < kFrictionRounds; ++k) {
            sweep_normal_rows<Turning>(c, t, A, B, n_a, n_b, moved, pass, select(impact, c.count, zero), true);
            solve_friction_rows<Turning>(c, t, A, B, total_normal_impulse(c), true, impact);
        }
    if (pass.last_of_substep)
        for (int i = 0; i < c.max_count; ++i) c.points[i].step_impulse = c.points[i].step_impulse + c.points[i].normal_impulse;
    scatter<T, W>(A, bodies, c.a);
    scatter<T, W>(B, bodies, c.b);
}
/// The lanes of a group whose bodies are marked (ImpactMarks).
template <class T, int W>
typename Wide<T, W>::Mask marked_lanes(const WideContact<T, W>& c, const std::uint8_t* marked) {
    Wide<T, W> m = Wide<T, W>::splat(T(0));
    for (int l = 0; l < W; ++l)
        if (marked[c.a[l]] != 0 || marked[c.b[l]] != 0) m.set(l, T(1));
    return m > Wide<T, W>::splat(T(0));
}

/// Another sweep of the normal rows of the lanes in `lanes`, and of their friction rows where
/// `friction`; the other lanes keep their values. A pass that ends with a step's total adds what
/// this one changed.
template <bool Turning, class T, int W>
void solve_lanes(WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, std::vector<SolverBody<T>>& bodies,
                 const SolvePass<T>& pass, const typename Wide<T, W>::Mask& lanes, bool friction) {
    using V = Wide<T, W>;
    GroupFrame<V> g = group_frame(c, bodies);
    V before[4];
    for (int i = 0; i < c.max_count; ++i) before[i] = c.points[i].normal_impulse;
    sweep_normal_rows<Turning>(c, t, g.A, g.B, g.n_a, g.n_b, g.moved, pass, select(lanes, c.count, V::splat(T(0))), true);
    if (friction) solve_friction_rows<Turning>(c, t, g.A, g.B, total_normal_impulse(c), true, lanes);
    if (pass.last_of_substep)
        for (int i = 0; i < c.max_count; ++i)
            c.points[i].step_impulse = c.points[i].step_impulse + (c.points[i].normal_impulse - before[i]);
    scatter<T, W>(g.A, bodies, c.a);
    scatter<T, W>(g.B, bodies, c.b);
}

template <class T, int W>
XENO_WIDE_NOINLINE void solve_turning(WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, std::vector<SolverBody<T>>& bodies,
                                      const SolvePass<T>& pass, const ImpactMarks* marks) {
    solve_group<true>(c, t, bodies, pass, marks);
}
/// One pass over a group, `t` its WideTurn where it turns levers (c.turns). WideContactRows
/// calls solve_fixed alone while no group turns levers, nearly always: a branch to the turning
/// code at each group made the box pyramid's solve, which never takes it, 6–14 % slower.
template <class T, int W>
void solve_fixed(WideContact<T, W>& c, std::vector<SolverBody<T>>& bodies, const SolvePass<T>& pass, const ImpactMarks* marks) {
    solve_group<false>(c, static_cast<const WideTurn<Wide<T, W>>*>(nullptr), bodies, pass, marks);
}
template <class T, int W>
void solve_wide(WideContact<T, W>& c, const WideTurn<Wide<T, W>>* t, std::vector<SolverBody<T>>& bodies, const SolvePass<T>& pass,
                const ImpactMarks* marks) {
    if (c.turns) solve_turning(c, t, bodies, pass, marks);
    else solve_fixed(c, bodies, pass, marks);
}

/// Lane `l` of `dst` set to the upper triangle of `m` (a world inverse inertia, symmetric up to
/// the rounding of R I⁻¹ Rᵀ).
template <class V, class T>
void put_sym(WideSym3<V>& dst, int l, const Mat3<T>& m) {
    dst.xx.set(l, m.row[0].x), dst.xy.set(l, m.row[0].y), dst.xz.set(l, m.row[0].z);
    dst.yy.set(l, m.row[1].y), dst.yz.set(l, m.row[1].z), dst.zz.set(l, m.row[2].z);
}

/// Fills lane `l` of a group from the scalar row and the bodies' frozen masses.
template <class T, int W>
void pack_lane(WideContact<T, W>& c, int l, std::uint32_t row, const ContactConstraint<T>& k,
               const std::vector<SolverMass<T>>& masses) {
    const SolverMass<T>& sa = masses[k.a];
    const SolverMass<T>& sb = masses[k.b];
    auto put = [l](WideVec3<Wide<T, W>>& dst, const Vec3<T>& v) { dst.x.set(l, v.x), dst.y.set(l, v.y), dst.z.set(l, v.z); };
    c.a[l] = k.a, c.b[l] = k.b, c.row[l] = row;
    c.max_count = std::max(c.max_count, k.count);
    c.min_count = std::min(c.min_count, k.count);
    c.count.set(l, static_cast<T>(k.count));
    put(c.normal, k.normal), put(c.t1, k.t1), put(c.t2, k.t2);
    c.inv_mass_a.set(l, sa.inv_mass), c.inv_mass_b.set(l, sb.inv_mass), c.friction.set(l, k.friction);
    c.normal_acceleration.set(l, k.normal_acceleration);
    put_sym(c.inv_inertia_a, l, sa.inv_inertia), put_sym(c.inv_inertia_b, l, sb.inv_inertia);
    c.bias_rate.set(l, k.softness.bias_rate), c.mass_scale.set(l, k.softness.mass_scale),
        c.impulse_scale.set(l, k.softness.impulse_scale);
    for (int i = 0; i < k.count; ++i) {
        const ContactConstraintPoint<T>& q = k.points[static_cast<std::size_t>(i)];
        WidePoint<Wide<T, W>>& p = c.points[i];
        const Vec3<T> rn_a = cross(q.r_a, k.normal), rn_b = cross(q.r_b, k.normal);
        put(p.r_a, q.r_a), put(p.r_b, q.r_b), put(p.rn_a, rn_a), put(p.rn_b, rn_b);
        p.adjusted_separation.set(l, q.adjusted_separation), p.normal_mass.set(l, q.normal_mass);
        p.normal_impulse.set(l, q.normal_impulse), p.max_normal_impulse.set(l, q.max_normal_impulse),
            p.step_impulse.set(l, q.step_impulse);
        p.approach.set(l, q.relative_velocity), p.landing.set(l, q.relative_velocity);
    }
    const Vec3<T> a1 = cross(k.rc_a, k.t1), a2 = cross(k.rc_a, k.t2), b1 = cross(k.rc_b, k.t1), b2 = cross(k.rc_b, k.t2);
    put(c.a1, a1), put(c.a2, a2), put(c.b1, b1), put(c.b2, b2);
    c.k11.set(l, k.k11), c.k12.set(l, k.k12), c.k22.set(l, k.k22), c.friction_1.set(l, k.friction_1),
        c.friction_2.set(l, k.friction_2);
    c.twist_mass.set(l, k.twist_mass), c.twist_impulse.set(l, k.twist_impulse),
        c.twist_friction.set(l, k.friction * k.twist_lever);
    c.round_a.set(l, k.round_a), c.round_b.set(l, k.round_b);
    c.rolls = c.rolls || k.round_a > T(0) || k.round_b > T(0);
    c.bounces = c.bounces || k.restitution > T(0);
    c.slips = c.slips || k.slips;
}

/// Fills lane `l` of the WideTurn of a group that turns levers.
template <class V, class T>
void pack_turn(WideTurn<V>& t, int l, const ContactConstraint<T>& k) {
    t.turn_a.set(l, k.turns_a ? T(1) : T(0)), t.turn_b.set(l, k.turns_b ? T(1) : T(0));
    t.rc_a.x.set(l, k.rc_a.x), t.rc_a.y.set(l, k.rc_a.y), t.rc_a.z.set(l, k.rc_a.z);
    t.rc_b.x.set(l, k.rc_b.x), t.rc_b.y.set(l, k.rc_b.y), t.rc_b.z.set(l, k.rc_b.z);
    t.slip_1.set(l, k.slip_1), t.slip_2.set(l, k.slip_2);
}

/// Copies lane `l`'s impulses back into its scalar row (for restitution, events and the next
/// step's warm start).
template <class T, int W>
void unpack_lane(const WideContact<T, W>& c, int l, ContactConstraint<T>& k) {
    for (int i = 0; i < k.count; ++i) {
        const WidePoint<Wide<T, W>>& p = c.points[i];
        ContactConstraintPoint<T>& q = k.points[static_cast<std::size_t>(i)];
        q.normal_impulse = p.normal_impulse.get(l);
        q.max_normal_impulse = p.max_normal_impulse.get(l);
        q.step_impulse = p.step_impulse.get(l);
        q.relative_velocity = p.landing.get(l);
    }
    k.friction_1 = c.friction_1.get(l);
    k.friction_2 = c.friction_2.get(l);
    k.twist_impulse = c.twist_impulse.get(l);
}

/// The step's contact rows in colour order, W lanes per group, and the overflow one at a time.
template <class T>
class WideContactRows {
public:
    static constexpr int width = native_width<T>();
    using Group = WideContact<T, width>;
    // An overflow row is a group of one row, its other lanes padding as a colour's last group's
    // may be: a lane's numbers do not depend on its neighbours, so the bits are those of a
    // one-lane row, and the kernels are compiled for one width only (width 1 as well cost
    // hello_world 6 % of its code and about 5 % of its -O2 compile; docs/benchmarks.md).
    using Single = Group;

    /// Colours and packs `rows` (their bodies' masses frozen in `masses`); the packing of the
    /// groups runs through `tasks` (task_system.hpp). `turning`: some row turns its levers
    /// (ContactConstraint::turns_a, turns_b); its group's WideTurn is then kept at its index.
    void build(const std::vector<ContactConstraint<T>>& rows, const std::vector<SolverMass<T>>& masses, bool turning,
               TaskSystem* tasks) {
        colouring_.build(
            rows.size(), masses.size(), [&](std::size_t i) { return rows[i].a; }, [&](std::size_t i) { return rows[i].b; });
        group_begin_.assign(ConstraintColouring::colours + 1, 0u);
        for (int colour = 0; colour < ConstraintColouring::colours; ++colour) {
            const auto c = static_cast<std::size_t>(colour);
            group_begin_[c + 1] =
                group_begin_[c] + (static_cast<std::uint32_t>(colouring_.colour_size(colour)) + width - 1) / width;
        }
        groups_.resize(group_begin_.back());
        turning_ = turning;
        if (turning) group_turns_.resize(groups_.size());
        parallel_for(tasks, static_cast<std::uint32_t>(groups_.size()), pack_range, [&](std::uint32_t first, std::uint32_t last) {
            for (std::uint32_t g = first; g < last; ++g) {
                // The colour of group g, and the rows it packs: W consecutive rows of that colour.
                const auto colour = static_cast<std::size_t>(std::upper_bound(group_begin_.begin(), group_begin_.end(), g) -
                                                             group_begin_.begin() - 1);
                const std::uint32_t begin = colouring_.colour_begin[colour] + (g - group_begin_[colour]) * width;
                const std::uint32_t end = std::min(begin + width, colouring_.colour_begin[colour + 1]);
                start_group(groups_[g], rows, begin, end);
                if (groups_[g].turns) group_turns_[g] = WideTurn<typename Group::V>{};  // padding lanes turn nothing
                for (std::uint32_t i = begin; i < end; ++i) {
                    const std::uint32_t row = colouring_.order[i];
                    pack_lane(groups_[g], static_cast<int>(i - begin), row, rows[row], masses);
                    if (groups_[g].turns) pack_turn(group_turns_[g], static_cast<int>(i - begin), rows[row]);
                }
            }
        });
        shared_.assign(masses.size(), std::uint8_t{0});
        marked_.assign(masses.size(), std::uint8_t{0});
        for (const ContactConstraint<T>& row : rows)
            for (const std::uint32_t k : {row.a, row.b}) shared_[k] = static_cast<std::uint8_t>(std::min(shared_[k] + 1, 2));
        for (std::uint8_t& n : shared_) n = n >= 2 ? std::uint8_t{1} : std::uint8_t{0};
        shared_[0] = 0;  // the static stand-in
        overflow_.clear();
        single_turns_.clear();
        for (const std::uint32_t row : colouring_.overflow) {
            overflow_.push_back(empty<width>());
            overflow_.back().turns = rows[row].turns_a || rows[row].turns_b || rows[row].slips;
            pack_lane(overflow_.back(), 0, row, rows[row], masses);
            if (turning) pack_turn(single_turns_.emplace_back(), 0, rows[row]);
        }
    }

    /// The overflow rows one by one, then each colour's groups through `tasks` (a colour's groups
    /// share no moving body, so they may run at once; the colours run one after another).
    void warm_start(std::vector<SolverBody<T>>& bodies, TaskSystem* tasks) const {
        if (!turning_) {
            for (const Single& c : overflow_) warm_start_fixed(c, bodies);
            for_each_colour(tasks, [&](std::uint32_t g) { warm_start_fixed(groups_[g], bodies); });
        } else {
            for (std::size_t i = 0; i < overflow_.size(); ++i) warm_start_wide(overflow_[i], &single_turns_[i], bodies);
            for_each_colour(tasks, [&](std::uint32_t g) { warm_start_wide(groups_[g], &group_turns_[g], bodies); });
        }
        bodies[0] = SolverBody<T>{};
    }
    void solve(std::vector<SolverBody<T>>& bodies, const SolvePass<T>& pass, TaskSystem* tasks) {
        impact_.flag.store(false, std::memory_order_relaxed);
        const ImpactMarks marks{shared_.data(), marked_.data(), &impact_.flag};
        if (!turning_) {
            for (Single& c : overflow_) solve_fixed(c, bodies, pass, &marks);
            for_each_colour(tasks, [&](std::uint32_t g) { solve_fixed(groups_[g], bodies, pass, &marks); });
        } else {
            for (std::size_t i = 0; i < overflow_.size(); ++i) solve_wide(overflow_[i], &single_turns_[i], bodies, pass, &marks);
            for_each_colour(tasks, [&](std::uint32_t g) { solve_wide(groups_[g], &group_turns_[g], bodies, pass, &marks); });
        }
        if (impact_.flag.load(std::memory_order_relaxed)) solve_impacts(bodies, pass, tasks);
        bodies[0] = SolverBody<T>{};
    }
    /// take_approach_wide for the groups that bounce, once a substep (before its impulses).
    void take_approach(const std::vector<SolverBody<T>>& bodies, T h, TaskSystem* tasks) {
        for (Single& c : overflow_)
            if (c.bounces) take_approach_wide(c, bodies, h);
        parallel_for(tasks, static_cast<std::uint32_t>(groups_.size()), pack_range, [&](std::uint32_t first, std::uint32_t last) {
            for (std::uint32_t g = first; g < last; ++g)
                if (groups_[g].bounces) take_approach_wide(groups_[g], bodies, h);
        });
    }
    /// Copies the impulses back into the scalar rows.
    void unpack(std::vector<ContactConstraint<T>>& rows, TaskSystem* tasks) const {
        for (const Single& c : overflow_) unpack_lane(c, 0, rows[c.row[0]]);
        parallel_for(tasks, static_cast<std::uint32_t>(groups_.size()), pack_range, [&](std::uint32_t first, std::uint32_t last) {
            for (std::uint32_t g = first; g < last; ++g)
                for (int l = 0; l < width; ++l)
                    if (groups_[g].row[l] != ~0u) unpack_lane(groups_[g], l, rows[groups_[g].row[l]]);
        });
    }

    std::size_t overflow_rows() const { return overflow_.size(); }
    std::size_t colours_used() const {
        std::size_t used = 0;
        for (int c = 0; c < ConstraintColouring::colours; ++c) used += colouring_.colour_size(c) > 0 ? 1 : 0;
        return used;
    }

private:
    /// A body struck through one of its manifolds while it holds others (a box landing across
    /// the seam of two floor tiles, a compound's parts): the impact sweeps of solve_group settle
    /// each manifold alone, and the first one solved took most of the impulse and turned the
    /// body (a 1 x 0.4 x 1 m box dropped 2 m across two tiles left spinning at 0.3 rad/s, and
    /// with e = 1 it tumbled at 9 rad/s by its third bounce). So the rows of the bodies marked
    /// by this pass take kImpactPasses more sweeps of their own, colour by colour: the normal
    /// rows each time, the friction rows in the last (their uneven first shares had the friction
    /// rows push the plate off sideways at 0.24 m/s with µ 0.6; friction in every one of these
    /// sweeps kept a 7-sided prism resting across a heightfield's ridge from ever settling).
    void solve_impacts(std::vector<SolverBody<T>>& bodies, const SolvePass<T>& pass, TaskSystem* tasks) {
        constexpr int kImpactPasses = 3;
        bool friction = false;
        const auto run = [&](Group& c, const WideTurn<typename Group::V>* t) {
            const typename Group::V::Mask lanes = marked_lanes(c, marked_.data());
            if (bits(lanes) == 0) return;
            if (c.turns) solve_lanes<true>(c, t, bodies, pass, lanes, friction);
            else solve_lanes<false>(c, static_cast<const WideTurn<typename Group::V>*>(nullptr), bodies, pass, lanes, friction);
        };
        for (int k = 0; k < kImpactPasses; ++k) {
            friction = k + 1 == kImpactPasses;
            for (std::size_t i = 0; i < overflow_.size(); ++i) run(overflow_[i], turning_ ? &single_turns_[i] : nullptr);
            for_each_colour(tasks, [&](std::uint32_t g) { run(groups_[g], turning_ ? &group_turns_[g] : nullptr); });
        }
        std::fill(marked_.begin(), marked_.end(), std::uint8_t{0});
    }

    /// Fewest groups a worker is handed: a group's solve takes about 0.1 µs (float, 4 lanes) and
    /// handing out a range a few µs, so smaller colours run on the stepping thread alone.
    static constexpr std::uint32_t solve_range = 32, pack_range = 64;

    template <class F>
    void for_each_colour(TaskSystem* tasks, const F& f) const {
        for (std::size_t colour = 0; colour + 1 < group_begin_.size(); ++colour) {
            const std::uint32_t first = group_begin_[colour];
            parallel_for(tasks, group_begin_[colour + 1] - first, solve_range, [&](std::uint32_t begin, std::uint32_t end) {
                for (std::uint32_t g = first + begin; g < first + end; ++g) f(g);
            });
        }
    }

    /// Readies a group for pack_lane, which writes every number of its lane but the point slots
    /// beyond the lane's count. A full group zeroes only those (they are read, masked, up to the
    /// fullest lane's count); a group with padding lanes is zeroed whole. Zeroing every group
    /// first wrote its 2.1 KB (in float and in double) twice: the packing is bound by memory.
    /// It also says whether the group turns levers (turned_moment), before its lanes are packed:
    /// pack_lane writes the turning numbers of a group that turns only.
    void start_group(Group& c, const std::vector<ContactConstraint<T>>& rows, std::uint32_t begin, std::uint32_t end) const {
        int fewest = 4, most = 0;
        bool turns = false;
        for (std::uint32_t i = begin; i < end; ++i) {
            const ContactConstraint<T>& row = rows[colouring_.order[i]];
            fewest = std::min(fewest, row.count);
            most = std::max(most, row.count);
            turns = turns || row.turns_a || row.turns_b || row.slips;
        }
        if (end - begin < static_cast<std::uint32_t>(width)) {
            c = empty<width>();
        } else {
            for (int i = fewest; i < most; ++i) c.points[i] = WidePoint<typename Group::V>{};
            c.max_count = 0;
            c.min_count = 4;
            c.rolls = false;
            c.bounces = false;
            c.slips = false;
        }
        c.turns = turns;
    }

    template <int W>
    static WideContact<T, W> empty() {
        WideContact<T, W> c{};
        for (int l = 0; l < W; ++l) c.a[l] = 0, c.b[l] = 0, c.row[l] = ~0u;
        c.max_count = 0;
        c.min_count = 4;
        return c;
    }

    ConstraintColouring colouring_;
    std::vector<std::uint32_t> group_begin_;  ///< colours + 1 offsets into groups_
    std::vector<Group> groups_;
    std::vector<Single> overflow_;
    bool turning_ = false;  ///< some group turns levers (build); then the two lists below are filled
    std::vector<WideTurn<typename Group::V>> group_turns_;    ///< by group
    std::vector<WideTurn<typename Single::V>> single_turns_;  ///< by overflow row
    std::vector<std::uint8_t> shared_;                        ///< by solver body: it holds two rows or more (ImpactMarks)
    std::vector<std::uint8_t> marked_;                        ///< by solver body: struck in this pass (ImpactMarks)
    /// Some body was marked in this pass. A copy of the rows (a copied World) starts unset.
    struct Flag {
        std::atomic<bool> flag{false};
        Flag() = default;
        Flag(const Flag&) noexcept {}
        Flag& operator=(const Flag&) noexcept { return *this; }
    } impact_;
};

}  // namespace detail
}  // namespace xeno

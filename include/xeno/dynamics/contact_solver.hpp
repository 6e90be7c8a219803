// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Sequential impulses on contacts (Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005;
// "Fast and Simple Physics using Sequential Impulses", GDC 2006; docs/solver-design.md, "Sequential
// impulses"), in the phases World::step calls: prepare → (per substep: warm_start → solve(bias) →
// relax) → restitution → store. This file holds the rows and their rules; the warm start, solve
// and relax passes run W manifolds at a time in wide_contact_solver.hpp. Per contact point one
// normal row; per manifold one two-axis friction row at the centre of the patch and one twist row
// about the normal (Box3D's central friction; docs/solver-design.md, "Central friction"):
// order-independent, so a symmetric box sliding straight stays straight.
//
// Normal row, with the current separation s updated from the bodies' displacement this step:
//   s > 0 (speculative)  bias = s/h: the bodies may close the gap this substep, not more;
//   s ≤ 0, soft step     Δλ = −m_n (μs (v_n + max(β s, −v_push))) − γs λ   (soft spring–damper);
//   s ≤ 0, baumgarte     bias = max(β/h · min(s + slop, 0), −v_push), rigid row;
//   relax pass           bias 0, rigid: removes the bias velocity before positions are final, so
//                        overlap recovery adds no kinetic energy.
// Then λ_total = max(λ_total + Δλ, 0) on the accumulated impulse (never the increment).
// Friction: |λ_t| ≤ µ Σ λ_n on the 2-vector (a disc, not a square); twist: |λ_τ| ≤ µ ℓ Σ λ_n, with ℓ
// the patch's mean radius (contact/patch.hpp).
// Restitution: after the substeps, rows that approached faster than the threshold and carried
// impulse get the target v_n = −e v_n⁻, v_n⁻ the approach at the impact under gravity and applied
// forces alone (wide_contact_solver.hpp; docs/solver-design.md, "Restitution"), and friction at the
// patch centre up to µ times the impulse the rebound adds.
#pragma once

#include "settings.hpp"
#include "solver_body.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace xeno {
namespace detail {

/// One contact point's row, world frame, rebuilt every step.
template <class T>
struct ContactConstraintPoint {
    Vec3<T> r_a{}, r_b{};     ///< m, from each centre of mass to its anchor of the point
    T adjusted_separation{};  ///< m: s0 − n·(r_b − r_a), so s = n·(Δ of the anchors) + this
    T normal_mass{};          ///< kg: 1 / (n row's effective inverse mass)
    T normal_impulse{};       ///< N·s per substep, accumulated
    T max_normal_impulse{};   ///< N·s, the largest this step
    T step_impulse{};         ///< N·s, summed over the substeps (events)
    T relative_velocity{};    ///< m/s along n on reaching the surface (restitution; prepare sets the step's start)
    T rebound{};              ///< m/s along n, restitution's target where the point is at the step's end
};

/// One manifold's rows.
template <class T>
struct ContactConstraint {
    std::uint32_t a = 0, b = 0;    ///< solver body indices (0: static stand-in)
    std::uint32_t manifold = 0;    ///< index of the manifold it came from
    Vec3<T> normal{}, t1{}, t2{};  ///< unit, world: normal A → B and two tangents
    T friction{}, restitution{};
    /// m/s²: n · (a_B − a_A), the bodies' accelerations from gravity and applied forces: what the
    /// substeps before an impact add to its approach speed (take_approach_wide).
    T normal_acceleration{};
    Softness<T> softness{};
    int count = 0;
    /// Each side's levers turn with its body in the sweeps (wide_contact_solver.hpp, "Turning
    /// levers"): a flat or pointed side whose fixed levers would be off by more than
    /// levers_turn_far allows. Beside `count`, which the packing reads in the same cache line.
    bool turns_a = false, turns_b = false;
    /// slip_1, slip_2 are not zero (chord_slip): the row needs its group's WideTurn.
    bool slips = false;
    std::array<ContactConstraintPoint<T>, 4> points{};
    // Central friction and twist.
    Vec3<T> rc_a{}, rc_b{};                          ///< m, centres of mass to the patch centre
    T k11{}, k12{}, k22{};                           ///< inverse of the 2×2 tangent effective-mass matrix
    T friction_1{}, friction_2{};                    ///< N·s per substep along t1, t2
    T twist_mass{}, twist_impulse{}, twist_lever{};  ///< kg·m², N·m·s, m (the patch's mean radius, World::twist_lever)
    T slip_1{}, slip_2{};                            ///< m/s along t1, t2: chord_slip of B less A's
    /// m: the radius of each side's rounded surface at the contact (a sphere, a capsule, a
    /// cylinder's side; 0 for flat faces and edges). Such a surface rolls: its contact point stays
    /// at the bottom instead of turning with the body (rolling_rise in wide_contact_solver.hpp).
    T round_a{}, round_b{};
    /// N·s: the normal impulse restitution added, summed over the points (apply_restitution);
    /// µ times it bounds the friction of the rebound (bounce_friction).
    T bounce_impulse{};
};

/// Whether the levers of one side of `c` (B's if `side_b`), fixed for the step, turn far enough
/// with a body turning at `w` to be worth turning in the sweeps (turned_moment): the body turns
/// more than a quarter of a radian in the step, and the fixed levers would be off at its end by
/// more than 5 mm/s of point speed (a lever r turns by about step ω × r, which moves the point by
/// ω × (step ω × r), at most step |ω| |ω × r|, over the side's levers to its points and to its
/// patch centre). A top or a wheel spinning fast turns its levers; a body at rest or tumbling
/// slowly keeps them, and the bits and the cost of fixed levers: turning them for every body
/// turning by more than 5 mm/s of error made the solve of 4,000 dropped boxes 30 % slower.
template <class T>
constexpr T kFarTurn = T(0.25);  ///< rad in a step: SolverMass::spins_far
template <class T>
bool levers_turn_far(const ContactConstraint<T>& c, const Vec3<T>& w, T step, bool side_b) {
    constexpr T kTurnSpeed = T(0.005);  // m/s
    if (!(length_squared(w) * step * step > kFarTurn<T> * kFarTurn<T>)) return false;
    T reach = length_squared(cross(w, side_b ? c.rc_b : c.rc_a));
    for (int i = 0; i < c.count; ++i) {
        const ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
        reach = std::max(reach, length_squared(cross(w, side_b ? p.r_b : p.r_a)));
    }
    return step * length(w) * std::sqrt(reach) > kTurnSpeed;
}

/// A body turning at w carries a point at lever r along the chord of its turn, at
/// (R(w h) − 1) r / h on average over a substep h, not at w × r, the tangent at the substep's
/// start that the friction row's lever gives. The difference, about h |w|² r / 2 towards the
/// axis, is what the friction row adds to its relative velocity, and a side that has it turns its
/// levers through the substeps (turns_a, turns_b): a body held by friction then follows the turn
/// and stays on its circle. With fixed levers it moved along the tangent each step, an explicit
/// Euler step of the circle: a box on a turntable at 1 rad/s spiralled out by step² ω² r / 2 a
/// step, 8 mm/s at 1 m, and at 2 rad/s slid off in 4 s (docs/solver.md, "Riding a turning body").
/// Turning levers alone left an eighth of that (substep² instead of step²), and every step
/// asked the first substep's friction for the whole turn of the step's velocity. The chord
/// slip of R(w h) r is that of r turned by R(w h), as both turn about w; the row keeps the one of
/// the step's start, off by the angle of one step. A dynamic body's w is the step's start too:
/// its change over the step changes the slip by a term of the next order.
///
/// By Rodrigues' formula, with u = w / |w| and φ the angle the integrator turns the body by in
/// h (integrated_angle: 2 atan(θ/2) for θ = |w| h up to 1/8 rad), (R − 1) r = sin φ u × r +
/// (1 − cos φ) u × (u × r), so the slip is ((sin φ − θ) u × r + 2 sin²(φ/2) u × (u × r)) / h:
/// each term small and computed as such. Subtracting r from R r, as this did until the slip was
/// given to dynamic bodies, lost the slip's last digits in float (1e-7 r / h, 5 % of it at 1 m
/// and 1 rad/s).
///
/// A joint's point rows take it too (World::turn_joint_inertias): they hold the anchors' motion
/// along the chord, which the position update makes. They took only the pull towards the axis
/// for a while, taken at θ: the anchor then ran ahead of its partner by the rest, about θ³/4 of
/// the lever a substep, and the rows' position correction pulled it back by spinning the body
/// up, as its inertia about its own centre is the smaller: a ball whirled on a joint at 20 rad/s
/// gained 22 % of its energy in a minute, and at 30 rad/s ran away to the speed cap. (The first
/// reason for the pull, a gyroscope on a ball joint whose axle sank, is in docs/solver.md.)
template <class T>
Vec3<T> chord_slip(const Vec3<T>& w, const Vec3<T>& r, T h) {
    const T speed = length(w);
    if (!(speed > T(0))) return {};
    const T theta = speed * h;
    const T turn = integrated_angle(w * h);
    const Vec3<T> u = w / speed;
    const T half_sine = std::sin(turn / T(2));
    return cross(u, r) * ((std::sin(turn) - theta) / h) + cross(u, cross(u, r)) * (T(2) * half_sine * half_sine / h);
}

/// m/s: the chord slip (chord_slip) below which a side's levers stay fixed and its row takes no
/// slip: a drift of a tenth of a millimetre a second at the 8 substeps of the defaults. A box in
/// a pile, turning at a thousandth of a radian a second, stays far below it and keeps the cheaper
/// rows of fixed levers.
template <class T>
constexpr T kChordSlip = T(1e-5);

/// Sliding friction opposes the sliding velocity (the most dissipative impulse on Coulomb's disc).
/// The friction row's 2×2 mass K holds each body's tipping terms (c × t)·I⁻¹·(c × t), which
/// differ along the two tangents when the inertia differs across the contact face; a sticking
/// row needs them (its impulse must stop the patch centre), but a sliding body's normal rows
/// stop the tipping, and the accumulated impulse f − K⁻¹ v, clamped radially to the disc, came to
/// rest along K⁻¹ v: a 1 × 0.2 × 0.4 m plate launched at 45° ran off at 50°, and yawed on a 35°
/// slope it slid 0.82 m sideways in 3 s (docs/solver-design.md, "Central friction"). So when
/// f − K⁻¹ v leaves the disc the row takes f − m̄ v instead, m̄ the mean of K⁻¹'s diagonal (any
/// positive scalar keeps the step along −v), scaled to the rim: its fixed point is −µλ v / |v|,
/// and a body near sticking, v small, keeps the direction of its accumulated impulse.
/// ("sliding_friction_step" names this rule in the solver's comments.)

/// What one solver pass needs to know.
template <class T>
struct SolvePass {
    T inv_h{};        ///< 1/s, the (sub)step rate
    bool use_bias{};  ///< false in the relax pass
    SolverMode mode{};
    T baumgarte{};
    T linear_slop{};
    T max_push_out_speed{};
    bool last_of_substep{};  ///< the substep's last pass: each point's impulse is added to its step total
};

/// Coulomb friction over the rebound: the substeps bound friction by the impulse that stopped
/// the approach, and the rebound's impulse allows µ times as much again, towards no slip at the
/// patch centre. Without it a ball striking a floor obliquely kept the slip of a dead impact: at
/// 3 m/s across and 5 m/s down, µ = 0.1, e = 1, it left at 2.5 m/s instead of the 2.14 m/s of
/// Newton's and Coulomb's laws (it would have lost µ(1 + e) v_n = 1 m/s; it rolls at 5/7 of 3 m/s).
/// One row, run once, so it starts from no impulse and needs none stored.
template <class T>
void bounce_friction(const ContactConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, const SolverMass<T>& ma,
                     const SolverMass<T>& mb) {
    if (!(c.bounce_impulse > T(0))) return;  // resting, or below the threshold: no rebound
    const Vec3<T> dv = b.velocity_at(c.rc_b) - a.velocity_at(c.rc_a);
    const T v1 = dot(dv, c.t1), v2 = dot(dv, c.t2);
    T f1 = -(c.k11 * v1 + c.k12 * v2);
    T f2 = -(c.k12 * v1 + c.k22 * v2);
    const T bound = c.friction * c.bounce_impulse;
    if (f1 * f1 + f2 * f2 > bound * bound) {  // sliding: against the velocity (sliding_friction_step)
        const T speed = std::sqrt(v1 * v1 + v2 * v2);
        f1 = -bound * v1 / speed;
        f2 = -bound * v2 / speed;
    }
    const Vec3<T> impulse = c.t1 * f1 + c.t2 * f2;
    apply_impulse(a, ma, c.rc_a, -impulse);
    apply_impulse(b, mb, c.rc_b, impulse);
}

/// Each point's rebound speed (ContactConstraintPoint::rebound) where it is at the end of the
/// step, gap s ≥ 0 from the surface, h the substep, a the normal acceleration (< 0 towards each
/// other; docs/solver-design.md, "Restitution"). A substep's semi-implicit Euler (v += a h, then
/// x += v h) does not keep ½v² − a x over free flight but keeps ½v² − a x + ½ a h v exactly, so
/// that is the energy the bounce works with: the landing speed V (relative_velocity,
/// take_approach_wide) has ½V² equal to it at the impact substep's start, the rebound leaves
/// e² of it, and v_up is the speed at gap s with ½v_up² − a s + ½ a h v_up = e² ½V²:
///   v_up = (√(a²h² + 4 e²V² + 8 a s) − a h) / 2.
/// With ½v² − a x alone a ball with e = 1 came back 0.7–1.3 % lower (g h/2 slower at the ground,
/// as much less high on the way up) and, bounced from where the relax pass stopped it short of
/// the surface, up to 1.4 % higher at e = 0.5: over drops of 0.3–3 m a ball or a box bounced to
/// 0.970–1.014 of e²h, now 0.997–1.000, and with e = 1 keeps its height over 30 s to 1e-4 (8 or 4
/// substeps; 6e-4 at 1).
template <class T>
void set_rebounds(ContactConstraint<T>& c, const SolverBody<T>& a, const SolverBody<T>& b, T h) {
    const Vec3<T> n_a = rotate(conjugate(a.dq), c.normal), n_b = rotate(conjugate(b.dq), c.normal);  // as solve_wide
    const T moved =
        dot(b.dp - a.dp, c.normal) + c.round_b * (dot(n_b, c.normal) - T(1)) + c.round_a * (dot(n_a, c.normal) - T(1));
    const T e = c.restitution, accel = c.normal_acceleration;
    for (int i = 0; i < c.count; ++i) {
        ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
        const T gap = std::max(moved + dot(n_b, p.r_b) - dot(n_a, p.r_a) + p.adjusted_separation, T(0));
        const T lift = accel * h, speed = e * p.relative_velocity;
        p.rebound = (std::sqrt(std::max(lift * lift + T(4) * speed * speed + T(8) * accel * gap, T(0))) - lift) / T(2);
    }
}

/// The approach speed (m/s) from which the points of row c bounce: the setting, and never less
/// than twice what the free acceleration along the normal adds within a substep of h seconds. A
/// point at rest approaches at once that much (its first substep's pull before its first impulse,
/// take_approach_wide), give or take the round-off of resting; bounced, it left at g h or more
/// (2 cm/s at 480 Hz) every step when restitution_threshold was 0.
template <class T>
T bounce_threshold(const ContactConstraint<T>& c, T threshold, T h) {
    return std::max(threshold, T(2) * std::abs(c.normal_acceleration) * h);
}

/// Whether the restitution pass drives this point to its rebound speed: it approached faster
/// than its row's bounce_threshold and carried impulse in the substeps (ReboundEnergyCap asks
/// the same).
template <class T>
bool point_rebounds(const ContactConstraintPoint<T>& p, T threshold) {
    return !(p.relative_velocity > -threshold) && p.max_normal_impulse != T(0);
}

/// Whether the restitution pass drives any point of row c (point_rebounds).
template <class T>
bool row_rebounds(const ContactConstraint<T>& c, T threshold, T h) {
    const T gate = bounce_threshold(c, threshold, h);
    for (int i = 0; i < c.count; ++i)
        if (point_rebounds(c.points[static_cast<std::size_t>(i)], gate)) return true;
    return false;
}

/// The restitution pass after the substeps (see the file comment) over the rows in `bouncing`:
/// those with a restitution, in row order (World::prepare lists them), so that a scene without
/// bounce does not read every row. Eight sweeps of the normal rows, the friction of the rebound
/// (bounce_friction), eight sweeps again (its moment changes the points' v_n). Eight, because one
/// Gauss–Seidel sweep over a face's four points leaves the face short of the target speed
/// (measured: a flat box bounced to 96 % of e v), and four left the points' shares uneven enough
/// to turn it (a cube dropped flat with e = 1 left its second bounce turning at 0.04 rad/s and
/// tipped over on its third; eight: 1e-8 rad/s).
///
/// `joint_sweep` runs the joints' relax sweeps after each sweep of the normal rows, when some
/// point rebounds: a body a joint holds then rebounds as the joint lets it. Left to the next
/// step's joint rows, the part of the rebound the joint forbids was taken back inelastically: a
/// hinged door spinning at 2 rad/s into a post with e = 1 came back at 1.61 rad/s.
template <class T, class JointSweep>
void apply_restitution(std::vector<ContactConstraint<T>>& constraints, const std::vector<std::uint32_t>& bouncing,
                       std::vector<SolverBody<T>>& bodies, const std::vector<SolverMass<T>>& masses, T threshold, T h,
                       JointSweep&& joint_sweep) {
    constexpr int sweeps = 8;
    bool rebounds = false;
    for (const std::uint32_t row : bouncing) {
        ContactConstraint<T>& c = constraints[row];
        set_rebounds(c, bodies[c.a], bodies[c.b], h);
        rebounds = rebounds || row_rebounds(c, threshold, h);
    }
    if (!rebounds) return;
    auto normal_sweeps = [&] {
        for (int sweep = 0; sweep < sweeps; ++sweep) {
            for (const std::uint32_t row : bouncing) {
                ContactConstraint<T>& c = constraints[row];
                SolverBody<T>& a = bodies[c.a];
                SolverBody<T>& b = bodies[c.b];
                const T gate = bounce_threshold(c, threshold, h);
                for (int i = 0; i < c.count; ++i) {
                    ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
                    if (!point_rebounds(p, gate)) continue;
                    const T vn = dot(b.velocity_at(p.r_b) - a.velocity_at(p.r_a), c.normal);
                    const T delta = -p.normal_mass * (vn - p.rebound);
                    const T updated = std::max(p.normal_impulse + delta, T(0));
                    const Vec3<T> impulse = c.normal * (updated - p.normal_impulse);
                    p.step_impulse += updated - p.normal_impulse;
                    c.bounce_impulse += updated - p.normal_impulse;
                    p.normal_impulse = updated;
                    p.max_normal_impulse = std::max(p.max_normal_impulse, updated);
                    apply_impulse(a, masses[c.a], p.r_a, -impulse);
                    apply_impulse(b, masses[c.b], p.r_b, impulse);
                }
            }
            joint_sweep();
        }
    };
    normal_sweeps();
    for (const std::uint32_t row : bouncing) {
        const ContactConstraint<T>& c = constraints[row];
        bounce_friction(c, bodies[c.a], bodies[c.b], masses[c.a], masses[c.b]);
    }
    normal_sweeps();
    bodies[0] = SolverBody<T>{};
}

}  // namespace detail
}  // namespace xeno

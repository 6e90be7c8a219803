// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Joints (thesis 4.1 g): ball-and-socket, hinge (with angle limits and a motor), fixed, and
// distance, solved in the contact solver's sequential-impulse loop with warm starting and the
// same soft-step treatment (Catto, "Modeling and Solving Constraints", GDC 2009; "Solver2D",
// 2024): each substep, rows are solved with a soft position bias from the error measured on the
// bodies' current poses, then relaxed without bias. Anchors are body-local points; a joint's
// rows, world frame, with r_A, r_B the anchors rotated by the bodies' current orientations:
//   point (ball, hinge, fixed)  C = (x_B + r_B) − (x_A + r_A), three rows solved as one 3×3 block:
//                               K = (1/m_A + 1/m_B) 1 − [r_A]× I_A⁻¹ [r_A]× − [r_B]× I_B⁻¹ [r_B]×
//   hinge axis                  two rows b_i·(ω_B − ω_A) = 0 with b_1, b_2 ⟂ a_A, error
//                               C_i = b_i·(a_A × a_B): the axes stay aligned
//   hinge limit                 one row along the axis, one-sided (impulse pushes back into range)
//   hinge motor                 one row along the axis, target speed, impulse ≤ max torque · h
//   fixed orientation           three rows ω_B − ω_A = 0, error 2·vec(q_B (q_A q_rel)⁻¹)
//   distance                    one row along the line between the anchors, C = |d| − length
//   prismatic (slider)          the fixed orientation rows; two point rows b_i·d = 0 across the
//                               axis a_A (d = the anchors' separation) and, along it, a one-sided
//                               limit row and a force-limited motor row. The axis turns with A, so
//                               A's lever arm in these rows is r_A + d (Box2D's prismatic joint)
//   swing-twist (ragdoll)       the point block; a one-sided swing row about t_A × t_B keeping the
//                               angle between the twist axes t_A, t_B within the cone; a twist limit
//                               about t_A on B's reference turned onto A's plane (swing removed)
// A joint's reaction (World::joint_reaction) is its accumulated impulse of the last substep over
// that substep's length: the force and torque the joint applied to B (−them to A).
#pragma once

#include "body.hpp"
#include "integrator.hpp"
#include "solver_body.hpp"

#include <optional>

namespace xeno {

enum class JointType : std::uint8_t { ball, hinge, fixed, distance, prismatic, swing_twist };

/// A handle to a joint: slot index and generation (stale after destroy_joint).
struct JointId {
    static constexpr std::uint32_t invalid_index = ~std::uint32_t(0);
    std::uint32_t index = invalid_index;
    std::uint32_t generation = 0;
    bool valid() const { return index != invalid_index; }
    friend bool operator==(JointId a, JointId b) { return a.index == b.index && a.generation == b.generation; }
    friend bool operator!=(JointId a, JointId b) { return !(a == b); }
};

/// Everything needed to create a joint; world-frame anchor and axis at creation time. A hinge's or
/// slider's limits are checked (finite, lower <= upper) and kept even while enable_limit is off:
/// set_joint_limits may turn them on, and a snapshot holds them.
template <class T>
struct JointDef {
    JointType type = JointType::ball;
    BodyId a, b;
    Vec3<T> anchor_a{};                          ///< m, world: where the joint holds body A (and B, except distance)
    Vec3<T> anchor_b{};                          ///< m, world: distance joints only, the point on B
    Vec3<T> axis{T(0), T(1), T(0)};              ///< hinge or slider axis, world (need not be unit, must not be zero)
    bool enable_limit = false;                   ///< hinge: keep the angle within [lower, upper]; prismatic: the translation
    T lower_angle{}, upper_angle{};              ///< rad, the hinge angle of B relative to A, 0 at creation
    T lower_translation{}, upper_translation{};  ///< m, prismatic: B's anchor along the axis from A's, 0 at creation
    bool enable_motor = false;                   ///< hinge: drive the relative spin about the axis; prismatic: the slide
    T motor_speed{};                             ///< rad/s (hinge), m/s (prismatic)
    T max_motor_torque{};                        ///< N·m (hinge)
    T max_motor_force{};                         ///< N (prismatic)
    T cone_angle{};                              ///< rad, swing-twist: the largest angle between the twist axes
    T length = T(-1);                            ///< distance: m; negative means the anchors' distance at creation
    bool collide_connected = false;              ///< whether the two bodies still collide with each other

    static JointDef ball(BodyId a, BodyId b, const Vec3<T>& anchor) {
        JointDef d;
        d.type = JointType::ball;
        d.a = a, d.b = b, d.anchor_a = anchor;
        return d;
    }
    static JointDef hinge(BodyId a, BodyId b, const Vec3<T>& anchor, const Vec3<T>& axis) {
        JointDef d = ball(a, b, anchor);
        d.type = JointType::hinge;
        d.axis = axis;
        return d;
    }
    static JointDef fixed(BodyId a, BodyId b, const Vec3<T>& anchor) {
        JointDef d = ball(a, b, anchor);
        d.type = JointType::fixed;
        return d;
    }
    /// A slider: B keeps A's orientation and moves only along the axis through the anchor.
    static JointDef prismatic(BodyId a, BodyId b, const Vec3<T>& anchor, const Vec3<T>& axis) {
        JointDef d = hinge(a, b, anchor, axis);
        d.type = JointType::prismatic;
        return d;
    }
    /// A shoulder or hip: a ball joint whose twist axes (both `twist_axis` at creation) stay within
    /// cone_angle of each other and whose twist about them stays within [lower, upper] (rad).
    static JointDef swing_twist(BodyId a, BodyId b, const Vec3<T>& anchor, const Vec3<T>& twist_axis, T cone_angle, T lower_twist,
                                T upper_twist) {
        JointDef d = hinge(a, b, anchor, twist_axis);
        d.type = JointType::swing_twist;
        d.cone_angle = cone_angle;
        d.enable_limit = true;
        d.lower_angle = lower_twist, d.upper_angle = upper_twist;
        return d;
    }
    static JointDef distance(BodyId a, BodyId b, const Vec3<T>& anchor_on_a, const Vec3<T>& anchor_on_b) {
        JointDef d;
        d.type = JointType::distance;
        d.a = a, d.b = b, d.anchor_a = anchor_on_a, d.anchor_b = anchor_on_b;
        return d;
    }
};

/// What a joint did to body B over the last substep (A got the opposite): World::joint_reaction.
template <class T>
struct JointReaction {
    Vec3<T> force{};   ///< N, world, at B's anchor
    Vec3<T> torque{};  ///< N·m, world (besides the moment of the force)
};

/// A joint between two bodies: local frames, settings and accumulated impulses.
template <class T>
struct Joint {
    JointType type = JointType::ball;
    BodyId a, b;
    Vec3<T> local_anchor_a{}, local_anchor_b{};  ///< m, body frames
    Vec3<T> local_axis_a{}, local_axis_b{};      ///< unit, body frames (hinge, prismatic, swing-twist)
    Vec3<T> local_ref_a{}, local_ref_b{};        ///< unit, ⟂ axis, body frames: angle 0 when aligned
    Quat<T> relative_rotation{};                 ///< q_A⁻¹ q_B at creation (fixed)
    T length{};                                  ///< m (distance)
    bool enable_limit = false, enable_motor = false, collide_connected = false;
    /// Limits and motor: rad, rad/s and N·m for a hinge; m, m/s and N for a prismatic joint; the
    /// twist limits (rad) of a swing-twist joint.
    T lower_angle{}, upper_angle{}, motor_speed{}, max_motor_torque{};
    T cone_angle{};  ///< rad (swing-twist)
    // Accumulated impulses (per substep), kept across steps for warm starting.
    Vec3<T> linear_impulse{};   ///< N·s, point rows
    Vec3<T> angular_impulse{};  ///< N·m·s, hinge axis rows / fixed rows
    T axial_impulse{};          ///< N·m·s: limit (hinge); N·s: the distance row, the limit (prismatic)
    T motor_impulse{};          ///< N·m·s (hinge), N·s (prismatic)
    T swing_impulse{};          ///< N·m·s, >= 0: the swing-twist cone row
    std::uint32_t generation = 0;
    bool alive = false;

    /// The hinge angle (rad) of B relative to A about the axis, from the bodies' orientations.
    T hinge_angle(const Quat<T>& qa, const Quat<T>& qb) const {
        const Vec3<T> axis = rotate(qa, local_axis_a);
        const Vec3<T> ra = rotate(qa, local_ref_a), rb = rotate(qb, local_ref_b);
        return std::atan2(dot(cross(ra, rb), axis), dot(ra, rb));
    }
};

namespace detail {

/// Whether angle limits (rad) lie within [-pi, pi], the range the joint's angle is measured in.
template <class T>
bool angle_limits_ok(T lower, T upper) {
    return lower >= -ScalarTraits<T>::pi && upper <= ScalarTraits<T>::pi;
}

/// A joint's rows for one step (world frame), built in prepare and solved every substep.
template <class T>
struct JointConstraint {
    std::uint32_t joint = 0;           ///< index into the world's joints
    std::uint32_t a = 0, b = 0;        ///< solver body indices (0: static stand-in)
    SolverMass<T> mass_a{}, mass_b{};  ///< the two bodies' inverse masses and inertias, frozen for the step
    Vec3<T> r_a0{}, r_b0{};            ///< anchors at the start of the step (rotated by Δq each substep)
    Vec3<T> delta_center{};            ///< x_B − x_A at the start of the step
    /// m/s: the chord slip (chord_slip) of B's anchor less A's for the coming substep, set with
    /// the turned inertias before each pass: the point rows hold the anchors' motion along the
    /// chord of the bodies' turn, which the position update makes, not along its tangent ω × r.
    Vec3<T> slip{};
    Vec3<T> axis_a0{}, axis_b0{}, ref_a0{}, ref_b0{};  ///< hinge frames at the start of the step
    Quat<T> qa0{}, qb0{};                              ///< orientations at the start of the step
    T motor_start_speed{};                             ///< a motor's axis speed at the start of the step (World::motor_turning)
    Softness<T> softness{};
    Softness<T> limit_softness{};  ///< the contacts' frequency, damped at detail::limit_damping_ratio: a contact in angle
    /// m/s: cap on the speed at which a stretched joint is pulled together (the world's speed
    /// cap: a faster pull would be cut by the integrator anyway). Also what keeps a joint torn
    /// 1e35 m apart (a teleport, a restored snapshot) from overflowing its impulse to inf − inf.
    T max_bias_speed = ScalarTraits<T>::infinity;
    /// N·s and N·m·s: the impulses that would change the two bodies' speed (at the joint's levers)
    /// or spin by max_setting_length / 2 (detail::speed_per_impulse, spin_per_impulse). What a
    /// joint carries to the next step is capped by them (cap_joint_impulses): a weld anchored
    /// 1e5 m from its box, or a motor of "unlimited" force (FLT_MAX) against a limit, stored
    /// impulses that spun bodies until their contacts overflowed, or no snapshot restored.
    T max_linear_impulse = ScalarTraits<T>::infinity;
    T max_angular_impulse = ScalarTraits<T>::infinity;
    /// The one of them along the axis (slider, distance joint: linear; hinge, swing-twist:
    /// angular): the most a limit row holds in one substep; a motor gets half of it, so a limit
    /// can stop it.
    T max_axial_impulse = ScalarTraits<T>::infinity;
    /// m/s or rad/s: the joint's motor speed within what the integrator lets the bodies reach (the
    /// sum of their speed caps, or of their spin caps): faster, the integrator cut the motion
    /// anyway, and a float hinge motor at 1e6 rad/s spinning a paddle into the ground fed the
    /// contacts impulses no snapshot of the world would restore.
    T motor_speed{};
};

/// m: the farthest a joint's anchor may lie from its body's centre, in both precisions (float's
/// max_size). Its rows' angular terms grow with the lever squared: at 10³⁰ m in double, round-off
/// alone in a distance row spun a light box until its contacts overflowed.
template <class T>
constexpr T max_joint_lever() {
    return T(1e6);
}

/// Whether a joint's axial and motor impulses push along its axis (N·s) rather than turn about it.
inline bool linear_axis(JointType type) { return type == JointType::prismatic || type == JointType::distance; }

/// Caps the impulses joint j carries to the next step's warm start (JointConstraint::max_linear_impulse).
/// Within the caps the impulses keep their bits.
template <class T>
void cap_joint_impulses(Joint<T>& j, const JointConstraint<T>& c) {
    j.linear_impulse = capped_length(j.linear_impulse, c.max_linear_impulse);
    j.angular_impulse = capped_length(j.angular_impulse, c.max_angular_impulse);
    j.axial_impulse = clamp(j.axial_impulse, -c.max_axial_impulse, c.max_axial_impulse);
    j.motor_impulse = clamp(j.motor_impulse, -c.max_axial_impulse, c.max_axial_impulse);
    j.swing_impulse = std::min(j.swing_impulse, c.max_angular_impulse);
}

/// Halves `times` times every impulse joint j carries to the next step (Body::impulse_halvings_).
template <class T>
void halve_impulses(Joint<T>& j, int times) {
    if (times == 0) return;
    j.linear_impulse = halved(j.linear_impulse, times);
    j.angular_impulse = halved(j.angular_impulse, times);
    j.axial_impulse = halved(j.axial_impulse, times);
    j.motor_impulse = halved(j.motor_impulse, times);
    j.swing_impulse = halved(j.swing_impulse, times);
}

/// −[r]× M [r]×, the rotational part of a point row's 3×3 effective mass.
template <class T>
Mat3<T> point_mass_term(const Vec3<T>& r, const Mat3<T>& inv_inertia) {
    const Mat3<T> s = skew(r);
    return Mat3<T>::zero() - s * inv_inertia * s;
}

/// Two unit vectors perpendicular to the unit vector a (and to each other).
template <class T>
void perpendicular_pair(const Vec3<T>& a, Vec3<T>& b1, Vec3<T>& b2) {
    b1 = any_perpendicular(a);
    b2 = cross(a, b1);
}

/// A swing-twist joint's angles on the current poses: the twist axes, the swing (angle between
/// them) about `swing_normal` (t_A × t_B normalised; any perpendicular when they are parallel) and
/// the twist of B about t_A, measured on B's reference turned by the shortest arc from t_B to t_A.
template <class T>
struct SwingTwist {
    Vec3<T> twist_axis{}, swing_normal{};
    T swing{}, twist{};
};

template <class T>
SwingTwist<T> swing_twist_state(const JointConstraint<T>& c, const Quat<T>& dqa, const Quat<T>& dqb) {
    SwingTwist<T> st;
    const Vec3<T> ta = rotate(dqa, c.axis_a0), tb = rotate(dqb, c.axis_b0);
    const Vec3<T> n = cross(ta, tb);
    const T sin_swing = length(n);
    st.twist_axis = ta;
    st.swing = std::atan2(sin_swing, dot(ta, tb));
    st.swing_normal = sin_swing > T(0) ? n / sin_swing : any_perpendicular(ta);
    const Vec3<T> ra = rotate(dqa, c.ref_a0), rb = rotate(Quat<T>::from_to(tb, ta), rotate(dqb, c.ref_b0));
    st.twist = std::atan2(dot(cross(ra, rb), ta), dot(ra, rb));
    return st;
}

/// Applies the joint's accumulated impulses (warm start).
template <class T>
void warm_start_joint(const Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b) {
    const Vec3<T> ra = rotate(a.dq, c.r_a0), rb = rotate(b.dq, c.r_b0);
    Vec3<T> linear = j.linear_impulse, angular = j.angular_impulse;
    if (j.type == JointType::hinge) angular += rotate(a.dq, c.axis_a0) * (j.axial_impulse + j.motor_impulse);
    if (j.type == JointType::swing_twist) {
        const SwingTwist<T> st = swing_twist_state(c, a.dq, b.dq);
        angular += st.twist_axis * j.axial_impulse - st.swing_normal * j.swing_impulse;
    }
    Vec3<T> lever_a = ra;
    if (j.type == JointType::distance) {
        const Vec3<T> d = (b.dp - a.dp) + c.delta_center + rb - ra;
        linear = normalized_or(d, Vec3<T>::unit_y()) * j.axial_impulse;
    }
    if (j.type == JointType::prismatic) {
        lever_a = ra + (b.dp - a.dp) + c.delta_center + rb - ra;
        linear += rotate(a.dq, c.axis_a0) * (j.axial_impulse + j.motor_impulse);
    }
    apply_impulse(a, c.mass_a, lever_a, -linear);
    apply_impulse(b, c.mass_b, rb, linear);
    a.w -= c.mass_a.inv_inertia * angular;
    b.w += c.mass_b.inv_inertia * angular;
}

/// A joint row's softness in one pass: the biased pass takes the joint's, the relax pass none.
template <class T>
struct PassSoftness {
    T bias_rate, mass_scale, impulse_scale;
    PassSoftness(const Softness<T>& s, bool use_bias)
        : bias_rate(use_bias ? s.bias_rate : T(0)),
          mass_scale(use_bias ? s.mass_scale : T(1)),
          impulse_scale(use_bias ? s.impulse_scale : T(0)) {}
};

/// The three rows that hold B's orientation at A's times the one they had at creation (fixed and
/// prismatic joints), as one 3×3 block; the error is 2·vec(q_B (q_A q_rel)⁻¹).
template <class T>
void solve_orientation_lock(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b,
                            const PassSoftness<T>& s) {
    const Quat<T> qa = a.dq * c.qa0, qb = b.dq * c.qb0;
    Quat<T> err = qb * conjugate(qa * j.relative_rotation);
    if (err.w < T(0)) err = -err;
    const Vec3<T> error = err.vec() * T(2);
    if (const std::optional<Mat3<T>> k_inv = try_inverse(c.mass_a.inv_inertia + c.mass_b.inv_inertia)) {
        const Vec3<T> cdot = (b.w - a.w) + error * s.bias_rate;
        const Vec3<T> impulse = (*k_inv * cdot) * (-s.mass_scale) - j.angular_impulse * s.impulse_scale;
        j.angular_impulse += impulse;
        a.w -= c.mass_a.inv_inertia * impulse;
        b.w += c.mass_b.inv_inertia * impulse;
    }
}

/// 1 / the effective mass of a linear row along n with lever arms la (A) and lb (B); 0 if none.
template <class T>
T row_mass(const JointConstraint<T>& c, const Vec3<T>& la, const Vec3<T>& lb, const Vec3<T>& n) {
    const Vec3<T> rna = cross(la, n), rnb = cross(lb, n);
    const T k =
        c.mass_a.inv_mass + c.mass_b.inv_mass + dot(rna, c.mass_a.inv_inertia * rna) + dot(rnb, c.mass_b.inv_inertia * rnb);
    return k > T(0) ? T(1) / k : T(0);
}

/// A prismatic joint's linear rows: across the axis (two rows, soft like the point block), then
/// the motor and the limit along it (the limit last: it must hold, as a contact does).
template <class T>
void solve_slider(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, bool use_bias, T h) {
    const Vec3<T> ra = rotate(a.dq, c.r_a0), rb = rotate(b.dq, c.r_b0);
    const Vec3<T> d = (b.dp - a.dp) + c.delta_center + rb - ra;
    const Vec3<T> la = ra + d;  // the axis turns with A about A's centre
    const Vec3<T> axis = rotate(a.dq, c.axis_a0);
    const auto push = [&](const Vec3<T>& n, T lambda) {
        apply_impulse(a, c.mass_a, la, -n * lambda);
        apply_impulse(b, c.mass_b, rb, n * lambda);
    };
    const auto speed = [&](const Vec3<T>& n) { return dot(b.velocity_at(rb) - a.velocity_at(la), n); };
    const PassSoftness<T> soft(c.softness, use_bias);
    Vec3<T> b1, b2;
    perpendicular_pair(axis, b1, b2);
    Vec3<T> across = Vec3<T>::zero();
    for (const Vec3<T>& n : {b1, b2}) {
        const T m = row_mass(c, la, rb, n);
        const T accumulated = dot(n, j.linear_impulse);
        const T bias = clamp(soft.bias_rate * dot(n, d), -c.max_bias_speed, c.max_bias_speed);
        const T delta = -soft.mass_scale * m * (speed(n) + bias) - soft.impulse_scale * accumulated;
        across += n * (accumulated + delta);
        push(n, delta);
    }
    j.linear_impulse = across;
    const T axial_mass = row_mass(c, la, rb, axis);
    if (j.enable_motor) {
        const T limit = std::min(j.max_motor_torque * h, c.max_axial_impulse / T(2));  // N (max_motor_force) · s
        const T updated = clamp(j.motor_impulse - axial_mass * (speed(axis) - c.motor_speed), -limit, limit);
        push(axis, updated - j.motor_impulse);
        j.motor_impulse = updated;
    }
    if (j.enable_limit) {  // one-sided at the nearer end, speculative above it (as the hinge limit)
        const T s_now = dot(d, axis);
        const T to_lower = s_now - j.lower_angle, to_upper = j.upper_angle - s_now;
        const bool at_lower = to_lower <= to_upper;
        const T sign = at_lower ? T(1) : T(-1);
        const T gap = at_lower ? to_lower : to_upper;
        T bias = T(0), ms = T(1), is = T(0);
        if (gap > T(0)) {
            bias = gap / h;
        } else if (use_bias) {
            bias = std::max(c.limit_softness.bias_rate * gap, -c.max_bias_speed);  // as the point rows' pull
            ms = c.limit_softness.mass_scale;
            is = c.limit_softness.impulse_scale;
        }
        const T current = j.axial_impulse * sign;
        const T updated =
            clamp(current - axial_mass * ms * (sign * speed(axis) + bias) - is * current, T(0), c.max_axial_impulse);
        push(axis, sign * (updated - current));
        j.axial_impulse = sign * updated;
    }
}

/// One angular limit row about a unit axis (B relative to A): keeps `angle` within [lower,
/// upper] with a one-sided impulse at the nearer end, speculative while the gap is open (it
/// stops the bodies where they would reach the stop within the substep), soft like a contact once
/// past it. `accumulated` is the row's signed impulse along the axis.
template <class T>
void solve_angular_limit(const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, const Vec3<T>& axis, T angle, T lower,
                         T upper, T& accumulated, bool use_bias, T h) {
    const T kk = dot(axis, (c.mass_a.inv_inertia + c.mass_b.inv_inertia) * axis);
    const T axial_mass = kk > T(0) ? T(1) / kk : T(0);
    const T to_lower = angle - lower, to_upper = upper - angle;
    const bool at_lower = to_lower <= to_upper;
    const T sign = at_lower ? T(1) : T(-1);  // the row's direction along the axis
    const T gap = at_lower ? to_lower : to_upper;
    T bias = T(0), ms = T(1), is = T(0);
    if (gap > T(0)) {
        bias = gap * (T(1) / h);
    } else if (use_bias) {
        bias = std::max(c.limit_softness.bias_rate * gap, -c.max_bias_speed);  // as the point rows' pull
        ms = c.limit_softness.mass_scale;
        is = c.limit_softness.impulse_scale;
    }
    // The accumulated impulse of the active side stays >= 0 along sign · axis.
    const T current = accumulated * sign;
    const T cdot = sign * dot(b.w - a.w, axis);
    const T updated = clamp(current - axial_mass * ms * (cdot + bias) - is * current, T(0), c.max_axial_impulse);
    const Vec3<T> impulse = axis * (sign * (updated - current));
    accumulated = sign * updated;
    a.w -= c.mass_a.inv_inertia * impulse;
    b.w += c.mass_b.inv_inertia * impulse;
}

/// A swing-twist joint's limits after its point block: the twist, then the cone (the swing is
/// an angle >= 0 about the normal, limited above only; its impulse is stored as a magnitude).
template <class T>
void solve_swing_twist_limits(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, bool use_bias, T h) {
    const SwingTwist<T> st = swing_twist_state(c, a.dq, b.dq);
    solve_angular_limit(c, a, b, st.twist_axis, st.twist, j.lower_angle, j.upper_angle, j.axial_impulse, use_bias, h);
    // A swing never exceeds pi, so a cone of pi limits nothing; its row would still see a gap
    // closing to zero at 180° and stop a rod swinging through it dead (2 rad/s to 0 in a step).
    if (j.cone_angle >= ScalarTraits<T>::pi) return;
    T along = -j.swing_impulse;  // pushes back: along −normal
    solve_angular_limit(c, a, b, st.swing_normal, st.swing, -ScalarTraits<T>::max, j.cone_angle, along, use_bias, h);
    j.swing_impulse = -along;
}

/// A distance joint's one row along the line between its anchors (ra, rb: the anchors' levers).
template <class T>
void solve_distance(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, const Vec3<T>& ra,
                    const Vec3<T>& rb, const PassSoftness<T>& s) {
    const Vec3<T> d = (b.dp - a.dp) + c.delta_center + rb - ra;
    const T len = length(d);
    // (A length that overflows still has a direction: capped_length scales before squaring.)
    const Vec3<T> n = !std::isfinite(len) ? detail::capped_length(d, T(1)) : len > T(0) ? d / len : Vec3<T>::unit_y();
    const Vec3<T> rna = cross(ra, n), rnb = cross(rb, n);
    const T k =
        c.mass_a.inv_mass + c.mass_b.inv_mass + dot(rna, c.mass_a.inv_inertia * rna) + dot(rnb, c.mass_b.inv_inertia * rnb);
    if (!(k > T(0))) return;
    const T bias = s.bias_rate > T(0) ? clamp(s.bias_rate * (len - j.length), -c.max_bias_speed, c.max_bias_speed) : T(0);
    const T cdot = dot(b.velocity_at(rb) - a.velocity_at(ra), n) + bias;
    const T delta = -s.mass_scale * cdot / k - s.impulse_scale * j.axial_impulse;
    j.axial_impulse += delta;
    apply_impulse(a, c.mass_a, ra, -n * delta);
    apply_impulse(b, c.mass_b, rb, n * delta);
}

/// The point rows of a ball, hinge or fixed joint, as one 3×3 block: the anchors meet.
template <class T>
void solve_point_block(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, const Vec3<T>& ra,
                       const Vec3<T>& rb, const PassSoftness<T>& s) {
    const Mat3<T> k = Mat3<T>::identity() * (c.mass_a.inv_mass + c.mass_b.inv_mass) +
                      detail::point_mass_term(ra, c.mass_a.inv_inertia) + detail::point_mass_term(rb, c.mass_b.inv_inertia);
    const std::optional<Mat3<T>> k_inv = try_inverse(k);
    if (!k_inv) return;
    const Vec3<T> separation = (b.dp - a.dp) + c.delta_center + rb - ra;
    const Vec3<T> bias = s.bias_rate > T(0) ? detail::capped_length(separation * s.bias_rate, c.max_bias_speed) : Vec3<T>::zero();
    const Vec3<T> cdot = b.velocity_at(rb) - a.velocity_at(ra) + c.slip + bias;
    const Vec3<T> impulse = (*k_inv * cdot) * (-s.mass_scale) - j.linear_impulse * s.impulse_scale;
    j.linear_impulse += impulse;
    apply_impulse(a, c.mass_a, ra, -impulse);
    apply_impulse(b, c.mass_b, rb, impulse);
}

/// A hinge's rows after its point block: two that keep the axes aligned, the motor about the
/// axis, and the limit last (a one-sided row at whichever end is nearer, speculative above it,
/// as contacts).
template <class T>
void solve_hinge_axis(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, const PassSoftness<T>& s,
                      bool use_bias, T h) {
    const Mat3<T> inv_i = c.mass_a.inv_inertia + c.mass_b.inv_inertia;
    const Vec3<T> axis = rotate(a.dq, c.axis_a0);
    Vec3<T> b1, b2;
    detail::perpendicular_pair(axis, b1, b2);
    const Vec3<T> error = cross(axis, rotate(b.dq, c.axis_b0));
    const Vec3<T> dw = b.w - a.w;
    const T c1 = dot(b1, dw) + s.bias_rate * dot(b1, error), c2 = dot(b2, dw) + s.bias_rate * dot(b2, error);
    const T k11 = dot(b1, inv_i * b1), k12 = dot(b1, inv_i * b2), k22 = dot(b2, inv_i * b2);
    const T det = k11 * k22 - k12 * k12;
    if (det > T(0)) {
        const T p1 = dot(b1, j.angular_impulse), p2 = dot(b2, j.angular_impulse);
        const T l1 = -s.mass_scale * (k22 * c1 - k12 * c2) / det - s.impulse_scale * p1;
        const T l2 = -s.mass_scale * (k11 * c2 - k12 * c1) / det - s.impulse_scale * p2;
        const Vec3<T> impulse = b1 * l1 + b2 * l2;
        j.angular_impulse = b1 * (p1 + l1) + b2 * (p2 + l2);
        a.w -= c.mass_a.inv_inertia * impulse;
        b.w += c.mass_b.inv_inertia * impulse;
    }
    const T kk = dot(axis, inv_i * axis);
    const T axial_mass = kk > T(0) ? T(1) / kk : T(0);
    // Motor: drive the relative spin towards the target speed, torque-limited.
    if (j.enable_motor) {
        const T cdot = dot(b.w - a.w, axis) - c.motor_speed;
        const T limit = std::min(j.max_motor_torque * h, c.max_axial_impulse / T(2));
        const T updated = clamp(j.motor_impulse - axial_mass * cdot, -limit, limit);
        const Vec3<T> impulse = axis * (updated - j.motor_impulse);
        j.motor_impulse = updated;
        a.w -= c.mass_a.inv_inertia * impulse;
        b.w += c.mass_b.inv_inertia * impulse;
    }
    if (j.enable_limit) {
        const T angle = j.hinge_angle(a.dq * c.qa0, b.dq * c.qb0);
        solve_angular_limit(c, a, b, axis, angle, j.lower_angle, j.upper_angle, j.axial_impulse, use_bias, h);
    }
}

/// One pass over a joint's rows; use_bias false in the relax pass. h: the substep. The point
/// block goes first and the angular rows after it, the limit last of all, so that what must hold
/// (the stop) is solved last, as contact normals are.
template <class T>
void solve_joint(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, bool use_bias, T h) {
    const Vec3<T> ra = rotate(a.dq, c.r_a0), rb = rotate(b.dq, c.r_b0);
    const PassSoftness<T> s(c.softness, use_bias);
    if (j.type == JointType::distance) {
        solve_distance(j, c, a, b, ra, rb, s);
    } else if (j.type == JointType::prismatic) {
        solve_orientation_lock(j, c, a, b, s);
        solve_slider(j, c, a, b, use_bias, h);
    } else {
        solve_point_block(j, c, a, b, ra, rb, s);
        if (j.type == JointType::fixed) solve_orientation_lock(j, c, a, b, s);
        else if (j.type == JointType::swing_twist) solve_swing_twist_limits(j, c, a, b, use_bias, h);
        else if (j.type == JointType::hinge) solve_hinge_axis(j, c, a, b, s, use_bias, h);
    }
}

}  // namespace detail

namespace f32 {
using JointDef = xeno::JointDef<float>;
using Joint = xeno::Joint<float>;
}  // namespace f32
namespace f64 {
using JointDef = xeno::JointDef<double>;
using Joint = xeno::Joint<double>;
}  // namespace f64

}  // namespace xeno

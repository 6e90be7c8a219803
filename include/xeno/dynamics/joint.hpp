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
#pragma once

#include "body.hpp"
#include "integrator.hpp"
#include "solver_body.hpp"

#include <optional>

namespace xeno {

enum class JointType : std::uint8_t { ball, hinge, fixed, distance };

/// A handle to a joint: slot index and generation (stale after destroy_joint).
struct JointId {
    static constexpr std::uint32_t invalid_index = ~std::uint32_t(0);
    std::uint32_t index = invalid_index;
    std::uint32_t generation = 0;
    bool valid() const { return index != invalid_index; }
    friend bool operator==(JointId a, JointId b) { return a.index == b.index && a.generation == b.generation; }
    friend bool operator!=(JointId a, JointId b) { return !(a == b); }
};

/// Everything needed to create a joint; world-frame anchor and axis at creation time.
template <class T>
struct JointDef {
    JointType type = JointType::ball;
    BodyId a, b;
    Vec3<T> anchor_a{};              ///< m, world: where the joint holds body A (and B, except distance)
    Vec3<T> anchor_b{};              ///< m, world: distance joints only, the point on B
    Vec3<T> axis{T(0), T(1), T(0)};  ///< hinge axis, world (need not be unit, must not be zero)
    bool enable_limit = false;       ///< hinge: keep the angle within [lower, upper]
    T lower_angle{}, upper_angle{};  ///< rad, the hinge angle of B relative to A, 0 at creation
    bool enable_motor = false;       ///< hinge: drive the relative spin about the axis
    T motor_speed{};                 ///< rad/s
    T max_motor_torque{};            ///< N·m
    T length = T(-1);                ///< distance: m; negative means the anchors' distance at creation
    bool collide_connected = false;  ///< whether the two bodies still collide with each other

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
    static JointDef distance(BodyId a, BodyId b, const Vec3<T>& anchor_on_a, const Vec3<T>& anchor_on_b) {
        JointDef d;
        d.type = JointType::distance;
        d.a = a, d.b = b, d.anchor_a = anchor_on_a, d.anchor_b = anchor_on_b;
        return d;
    }
};

/// A joint between two bodies: local frames, settings and accumulated impulses.
template <class T>
struct Joint {
    JointType type = JointType::ball;
    BodyId a, b;
    Vec3<T> local_anchor_a{}, local_anchor_b{};  ///< m, body frames
    Vec3<T> local_axis_a{}, local_axis_b{};      ///< unit, body frames (hinge)
    Vec3<T> local_ref_a{}, local_ref_b{};        ///< unit, ⟂ axis, body frames: angle 0 when aligned
    Quat<T> relative_rotation{};                 ///< q_A⁻¹ q_B at creation (fixed)
    T length{};                                  ///< m (distance)
    bool enable_limit = false, enable_motor = false, collide_connected = false;
    T lower_angle{}, upper_angle{}, motor_speed{}, max_motor_torque{};
    // Accumulated impulses (per substep), kept across steps for warm starting.
    Vec3<T> linear_impulse{};   ///< N·s, point rows
    Vec3<T> angular_impulse{};  ///< N·m·s, hinge axis rows / fixed rows
    T axial_impulse{};          ///< N·m·s: limit (hinge) or the distance row's N·s
    T motor_impulse{};          ///< N·m·s
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

/// A joint's rows for one step (world frame), built in prepare and solved every substep.
template <class T>
struct JointConstraint {
    std::uint32_t joint = 0;                           ///< index into the world's joints
    std::uint32_t a = 0, b = 0;                        ///< solver body indices (0: static stand-in)
    SolverMass<T> mass_a{}, mass_b{};                  ///< the two bodies' inverse masses and inertias, frozen for the step
    Vec3<T> r_a0{}, r_b0{};                            ///< anchors at the start of the step (rotated by Δq each substep)
    Vec3<T> delta_center{};                            ///< x_B − x_A at the start of the step
    Vec3<T> axis_a0{}, axis_b0{}, ref_a0{}, ref_b0{};  ///< hinge frames at the start of the step
    Quat<T> qa0{}, qb0{};                              ///< orientations at the start of the step
    Softness<T> softness{};
    Softness<T> limit_softness{};  ///< the contacts' (heavily damped): a limit is a contact in angle
    /// m/s: cap on the speed at which a stretched joint is pulled together (the world's speed
    /// cap: a faster pull would be cut by the integrator anyway). Also what keeps a joint torn
    /// 1e35 m apart (a teleport, a restored snapshot) from overflowing its impulse to inf − inf.
    T max_bias_speed = ScalarTraits<T>::infinity;
};

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

/// Applies the joint's accumulated impulses (warm start).
template <class T>
void warm_start_joint(const Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b) {
    const Vec3<T> ra = rotate(a.dq, c.r_a0), rb = rotate(b.dq, c.r_b0);
    Vec3<T> linear = j.linear_impulse, angular = j.angular_impulse;
    if (j.type == JointType::hinge) angular += rotate(a.dq, c.axis_a0) * (j.axial_impulse + j.motor_impulse);
    if (j.type == JointType::distance) {
        const Vec3<T> d = (b.dp - a.dp) + c.delta_center + rb - ra;
        linear = normalized_or(d, Vec3<T>::unit_y()) * j.axial_impulse;
    }
    apply_impulse(a, c.mass_a, ra, -linear);
    apply_impulse(b, c.mass_b, rb, linear);
    a.w -= c.mass_a.inv_inertia * angular;
    b.w += c.mass_b.inv_inertia * angular;
}

/// One pass over a joint's rows; use_bias false in the relax pass. h: the substep. The point
/// block goes first and the angular rows after it, the limit last of all, so that what must hold
/// (the stop) is solved last, as contact normals are.
template <class T>
void solve_joint(Joint<T>& j, const JointConstraint<T>& c, SolverBody<T>& a, SolverBody<T>& b, bool use_bias, T h) {
    const T inv_h = T(1) / h;
    const Vec3<T> ra = rotate(a.dq, c.r_a0), rb = rotate(b.dq, c.r_b0);
    const T bias_rate = use_bias ? c.softness.bias_rate : T(0);
    const T mass_scale = use_bias ? c.softness.mass_scale : T(1);
    const T impulse_scale = use_bias ? c.softness.impulse_scale : T(0);
    const Mat3<T> inv_i = c.mass_a.inv_inertia + c.mass_b.inv_inertia;

    if (j.type == JointType::distance) {
        const Vec3<T> d = (b.dp - a.dp) + c.delta_center + rb - ra;
        const T len = length(d);
        // (A length that overflows still has a direction: capped_length scales before squaring.)
        const Vec3<T> n = !std::isfinite(len) ? detail::capped_length(d, T(1)) : len > T(0) ? d / len : Vec3<T>::unit_y();
        const Vec3<T> rna = cross(ra, n), rnb = cross(rb, n);
        const T k =
            c.mass_a.inv_mass + c.mass_b.inv_mass + dot(rna, c.mass_a.inv_inertia * rna) + dot(rnb, c.mass_b.inv_inertia * rnb);
        if (k > T(0)) {
            const T bias = bias_rate > T(0) ? clamp(bias_rate * (len - j.length), -c.max_bias_speed, c.max_bias_speed) : T(0);
            const T cdot = dot(b.velocity_at(rb) - a.velocity_at(ra), n) + bias;
            const T delta = -mass_scale * cdot / k - impulse_scale * j.axial_impulse;
            j.axial_impulse += delta;
            apply_impulse(a, c.mass_a, ra, -n * delta);
            apply_impulse(b, c.mass_b, rb, n * delta);
        }
        return;
    }

    // The point rows (ball, hinge, fixed), as one 3×3 block.
    const Mat3<T> k = Mat3<T>::identity() * (c.mass_a.inv_mass + c.mass_b.inv_mass) +
                      detail::point_mass_term(ra, c.mass_a.inv_inertia) + detail::point_mass_term(rb, c.mass_b.inv_inertia);
    if (const std::optional<Mat3<T>> k_inv = try_inverse(k)) {
        const Vec3<T> separation = (b.dp - a.dp) + c.delta_center + rb - ra;
        const Vec3<T> bias = bias_rate > T(0) ? detail::capped_length(separation * bias_rate, c.max_bias_speed) : Vec3<T>::zero();
        const Vec3<T> cdot = b.velocity_at(rb) - a.velocity_at(ra) + bias;
        const Vec3<T> impulse = (*k_inv * cdot) * (-mass_scale) - j.linear_impulse * impulse_scale;
        j.linear_impulse += impulse;
        apply_impulse(a, c.mass_a, ra, -impulse);
        apply_impulse(b, c.mass_b, rb, impulse);
    }

    if (j.type == JointType::fixed) {
        const Quat<T> qa = a.dq * c.qa0, qb = b.dq * c.qb0;
        Quat<T> err = qb * conjugate(qa * j.relative_rotation);
        if (err.w < T(0)) err = -err;
        const Vec3<T> error = err.vec() * T(2);
        if (const std::optional<Mat3<T>> k_inv = try_inverse(inv_i)) {
            const Vec3<T> cdot = (b.w - a.w) + error * bias_rate;
            const Vec3<T> impulse = (*k_inv * cdot) * (-mass_scale) - j.angular_impulse * impulse_scale;
            j.angular_impulse += impulse;
            a.w -= c.mass_a.inv_inertia * impulse;
            b.w += c.mass_b.inv_inertia * impulse;
        }
        return;
    }
    if (j.type != JointType::hinge) return;

    const Vec3<T> axis = rotate(a.dq, c.axis_a0);
    // Keep the axes aligned: two rows perpendicular to A's axis.
    Vec3<T> b1, b2;
    detail::perpendicular_pair(axis, b1, b2);
    const Vec3<T> error = cross(axis, rotate(b.dq, c.axis_b0));
    const Vec3<T> dw = b.w - a.w;
    const T c1 = dot(b1, dw) + bias_rate * dot(b1, error), c2 = dot(b2, dw) + bias_rate * dot(b2, error);
    const T k11 = dot(b1, inv_i * b1), k12 = dot(b1, inv_i * b2), k22 = dot(b2, inv_i * b2);
    const T det = k11 * k22 - k12 * k12;
    if (det > T(0)) {
        const T p1 = dot(b1, j.angular_impulse), p2 = dot(b2, j.angular_impulse);
        const T l1 = -mass_scale * (k22 * c1 - k12 * c2) / det - impulse_scale * p1;
        const T l2 = -mass_scale * (k11 * c2 - k12 * c1) / det - impulse_scale * p2;
        const Vec3<T> impulse = b1 * l1 + b2 * l2;
        j.angular_impulse = b1 * (p1 + l1) + b2 * (p2 + l2);
        a.w -= c.mass_a.inv_inertia * impulse;
        b.w += c.mass_b.inv_inertia * impulse;
    }
    const T kk = dot(axis, inv_i * axis);
    const T axial_mass = kk > T(0) ? T(1) / kk : T(0);
    // Motor: drive the relative spin towards the target speed, torque-limited.
    if (j.enable_motor) {
        const T cdot = dot(b.w - a.w, axis) - j.motor_speed;
        const T limit = j.max_motor_torque * h;
        const T updated = clamp(j.motor_impulse - axial_mass * cdot, -limit, limit);
        const Vec3<T> impulse = axis * (updated - j.motor_impulse);
        j.motor_impulse = updated;
        a.w -= c.mass_a.inv_inertia * impulse;
        b.w += c.mass_b.inv_inertia * impulse;
    }
    // Limit: a one-sided row at whichever end is nearer (speculative above it, as contacts).
    if (j.enable_limit) {
        const Quat<T> qa = a.dq * c.qa0, qb = b.dq * c.qb0;
        const T angle = j.hinge_angle(qa, qb);
        const T to_lower = angle - j.lower_angle, to_upper = j.upper_angle - angle;
        const bool at_lower = to_lower <= to_upper;
        const T sign = at_lower ? T(1) : T(-1);  // the row's direction along the axis
        const T s = at_lower ? to_lower : to_upper;
        T bias = T(0), ms = T(1), is = T(0);
        if (s > T(0)) {
            bias = s * inv_h;
        } else if (use_bias) {
            bias = c.limit_softness.bias_rate * s;
            ms = c.limit_softness.mass_scale;
            is = c.limit_softness.impulse_scale;
        }
        // The accumulated impulse of the active side stays >= 0 along sign · axis.
        const T current = j.axial_impulse * sign;
        const T cdot = sign * dot(b.w - a.w, axis);
        const T updated = std::max(current - axial_mass * ms * (cdot + bias) - is * current, T(0));
        const Vec3<T> impulse = axis * (sign * (updated - current));
        j.axial_impulse = sign * updated;
        a.w -= c.mass_a.inv_inertia * impulse;
        b.w += c.mass_b.inv_inertia * impulse;
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

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// World's joints: creating and destroying them, their limits and motors, the reaction force and
// torque of each after a step, and the rows prepared for the solver each step (the rows
// themselves are in joint.hpp). Included at the end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

/// A hinge's or slider's axis (and a reference across it), limits and motor from its definition,
/// checked (InvalidArgument naming `where`). Both store their limits and motor in the same fields:
/// radians, rad/s and N·m for a hinge, metres, m/s and N for a slider.
template <class T>
void World<T>::set_axis_limit_motor(Joint<T>& j, const JointDef<T>& def, const Body<T>& a, const Body<T>& b, const char* where) {
    detail::require_finite_xyz(def.axis, where, "axis");
    // Scaled by its largest component first: |axis|² of a finite axis can underflow (1e-20) or
    // overflow (1e20 in float), and such an axis was refused as zero.
    const T largest = max_component(abs(def.axis));
    const std::optional<Vec3<T>> axis = largest > T(0) ? try_normalized(def.axis / largest) : std::nullopt;
    if (!axis)
        detail::report_invalid(where, "the joint axis must be non-zero; its length", static_cast<double>(length(def.axis)));
    j.local_axis_a = a.local_vector(*axis);
    j.local_axis_b = b.local_vector(*axis);
    const Vec3<T> ref = any_perpendicular(*axis);
    j.local_ref_a = a.local_vector(ref);
    j.local_ref_b = b.local_vector(ref);
    const bool slider = def.type == JointType::prismatic;
    const T lower = slider ? def.lower_translation : def.lower_angle;
    const T upper = slider ? def.upper_translation : def.upper_angle;
    check_limits(def.type, lower, upper, where);  // kept, and restored from snapshots, even while the limit is off
    if (def.type == JointType::swing_twist) {
        if (!(def.cone_angle >= T(0) && def.cone_angle <= ScalarTraits<T>::pi))
            detail::report_invalid(where, "cone_angle must be within [0, pi] rad", static_cast<double>(def.cone_angle));
        j.cone_angle = def.cone_angle;
    }
    const T max_motor = slider ? def.max_motor_force : def.max_motor_torque;
    // A motor speed within the range a speed setting takes (1e6 in float): faster, the motor's
    // rows lose every digit of the bodies' motion across the axis to round-off.
    detail::require_at_most(def.motor_speed, detail::max_setting_length<T>(), where, "motor_speed", " m/s or rad/s");
    detail::require_non_negative(max_motor, where, slider ? "max_motor_force" : "max_motor_torque");
    j.enable_limit = def.enable_limit || def.type == JointType::swing_twist;  // a swing-twist joint is its limits
    j.lower_angle = lower;
    j.upper_angle = upper;
    j.enable_motor = def.enable_motor;
    j.motor_speed = def.motor_speed;
    j.max_motor_torque = max_motor;
}

template <class T>
void World<T>::check_limits(JointType type, T lower, T upper, const char* where) {
    detail::require_finite(lower, where, "lower limit");
    detail::require_finite(upper, where, "upper limit");
    if (lower > upper)
        detail::report_invalid(where, "the lower limit must be <= the upper; lower - upper", static_cast<double>(lower - upper));
    // An angle is measured in (-pi, pi] (Joint::hinge_angle), so a limit beyond pi is never
    // reached where the user meant it: [-4, 4] let an arm turn freely, and [0, 3.5] read the
    // angle past pi as -3.1 and threw the arm forwards every turn (1 rad/s became 9.2).
    if (!detail::linear_axis(type) && !detail::angle_limits_ok(lower, upper))
        detail::report_invalid(where, "angle limits must be within [-pi, pi] rad; the larger magnitude",
                               static_cast<double>(std::max(-lower, upper)));
}

/// The joint `def` describes between bodies a and b (checked here: finite anchors within
/// max_joint_lever of their bodies, the axis, limits and motor, a distance's length), not yet in
/// a slot.
template <class T>
Joint<T> World<T>::make_joint(const JointDef<T>& def, const Body<T>& a, const Body<T>& b, const char* where) {
    detail::require_finite_xyz(def.anchor_a, where, "anchor_a");
    detail::require_finite_xyz(def.anchor_b, where, "anchor_b");
    Joint<T> j;
    j.type = def.type;
    j.a = def.a;
    j.b = def.b;
    j.collide_connected = def.collide_connected;
    j.local_anchor_a = a.local_point(def.anchor_a);
    j.local_anchor_b = b.local_point(def.type == JointType::distance ? def.anchor_b : def.anchor_a);
    // An anchor farther than max_joint_lever from its body (10⁶ m) is a lever the solver cannot
    // use: a float distance joint anchored 1e15 m out froze both bodies in mid-air, and in double
    // one anchored 1e30 m out on a light box spun it until its contacts overflowed to inf.
    detail::require_at_most(length(j.local_anchor_a), detail::max_joint_lever<T>(), where, "anchor_a's distance from body a",
                            " m");
    detail::require_at_most(length(j.local_anchor_b), detail::max_joint_lever<T>(), where, "anchor_b's distance from body b",
                            " m");
    if (def.type == JointType::hinge || def.type == JointType::prismatic || def.type == JointType::swing_twist)
        set_axis_limit_motor(j, def, a, b, where);
    j.relative_rotation = conjugate(a.orientation_) * b.orientation_;
    if (def.type == JointType::distance) {
        detail::require_finite(def.length, where, "length");
        j.length = def.length < T(0) ? distance(def.anchor_a, def.anchor_b) : def.length;
        // The distance between the anchors can overflow though both are finite (1e30 apart in
        // float); the world's own snapshot then refused the infinite length.
        detail::require_at_most(j.length, ScalarTraits<T>::max_size, where, "length (given, or the anchors' distance)");
    }
    return j;
}

template <class T>
JointId World<T>::create_joint(const JointDef<T>& def) {
    const char* where = "World::create_joint";
    require_outside_filter(where);
    const std::uint32_t ia = checked(def.a, where), ib = checked(def.b, where);
    if (ia == ib) detail::report_invalid(where, "a joint needs two different bodies; body index", static_cast<double>(ia));
    if (def.type != JointType::ball && def.type != JointType::hinge && def.type != JointType::fixed &&
        def.type != JointType::distance && def.type != JointType::prismatic && def.type != JointType::swing_twist)
        detail::report_invalid(where, "type must be ball, hinge, fixed, distance, prismatic or swing_twist; type",
                               static_cast<double>(static_cast<std::uint8_t>(def.type)));
    const Body<T>& a = bodies_[ia];
    const Body<T>& b = bodies_[ib];
    if (a.type_ == BodyType::static_body && b.type_ == BodyType::static_body)
        detail::report_invalid(where, "a joint between two static bodies does nothing; body index", static_cast<double>(ib));
    Joint<T> j = make_joint(def, a, b, where);
    std::uint32_t slot;
    if (!free_joints_.empty()) {
        slot = free_joints_.back();
        free_joints_.pop_back();
        j.generation = joints_[slot].generation;
        joints_[slot] = j;
    } else {
        slot = static_cast<std::uint32_t>(joints_.size());
        joints_.push_back(j);
    }
    joints_[slot].alive = true;
    bind_joints();
    bodies_[ia].wake();
    bodies_[ib].wake();
    rebuild_joint_pairs();
    return {slot, joints_[slot].generation};
}

template <class T>
void World<T>::destroy_joint(JointId id) {
    require_outside_filter("World::destroy_joint");
    const std::uint32_t slot = checked(id, "World::destroy_joint");
    Joint<T>& j = joints_[slot];
    if (contains(j.a)) bodies_[j.a.index].wake();
    if (contains(j.b)) bodies_[j.b.index].wake();
    j.alive = false;
    ++j.generation;
    free_joints_.push_back(slot);
    rebuild_joint_pairs();
}

template <class T>
void World<T>::set_hinge_motor(JointId id, bool enable, T speed, T max_torque) {
    const char* where = "World::set_hinge_motor";
    require_outside_filter(where);
    if (joints_[checked(id, where)].type != JointType::hinge)
        detail::report_invalid(where, "the joint is not a hinge; its type", static_cast<double>(joints_[id.index].type));
    set_joint_motor(id, enable, speed, max_torque);
}

template <class T>
void World<T>::set_joint_motor(JointId id, bool enable, T speed, T max) {
    const char* where = "World::set_joint_motor";
    require_outside_filter(where);
    Joint<T>& j = joints_[checked(id, where)];
    if (j.type != JointType::hinge && j.type != JointType::prismatic)
        detail::report_invalid(where, "only hinges and sliders have a motor; joint type", static_cast<double>(j.type));
    detail::require_at_most(speed, detail::max_setting_length<T>(), where, "speed", " m/s or rad/s");
    detail::require_non_negative(max, where, "max torque or force");
    j.enable_motor = enable;
    j.motor_speed = speed;
    j.max_motor_torque = max;
    // The motor's warm start: every substep re-applies it, so one left behind by a motor switched
    // off held a hinged arm level for ever (as set_joint_limits clears the limit's).
    if (!enable) j.motor_impulse = T(0);
    bodies_[j.a.index].wake();
    bodies_[j.b.index].wake();
}

template <class T>
void World<T>::set_joint_limits(JointId id, bool enable, T lower, T upper) {
    const char* where = "World::set_joint_limits";
    require_outside_filter(where);
    Joint<T>& j = joints_[checked(id, where)];
    if (j.type != JointType::hinge && j.type != JointType::prismatic && j.type != JointType::swing_twist)
        detail::report_invalid(where, "only hinges, sliders and swing-twist joints have limits; joint type",
                               static_cast<double>(j.type));
    check_limits(j.type, lower, upper, where);
    if (j.type == JointType::swing_twist && !enable)
        detail::report_invalid(where, "a swing-twist joint's twist limit cannot be disabled (use a ball joint); enable", 0.0);
    j.enable_limit = enable;
    j.lower_angle = lower;
    j.upper_angle = upper;
    if (!enable) j.axial_impulse = T(0);  // the limit's warm start
    bodies_[j.a.index].wake();
    bodies_[j.b.index].wake();
}

// The accumulated impulses are the last substep's (each substep warm-starts from them and adds
// its corrections), so impulse / substep is the mean force of that substep.
template <class T>
JointReaction<T> World<T>::joint_reaction(JointId id) const {
    const Joint<T>& j = joints_[checked(id, "World::joint_reaction")];
    if (!(last_substep_ > T(0)) || !joint_active(j)) return {};
    const Body<T>& a = bodies_[j.a.index];
    const Body<T>& b = bodies_[j.b.index];
    const Vec3<T> axis = rotate(a.orientation_, j.local_axis_a);
    Vec3<T> linear = j.linear_impulse, angular = j.angular_impulse;
    if (j.type == JointType::distance) {
        const Vec3<T> d = b.world_point(j.local_anchor_b) - a.world_point(j.local_anchor_a);
        linear = normalized_or(d, Vec3<T>::unit_y()) * j.axial_impulse;
    }
    if (j.type == JointType::hinge) angular += axis * (j.axial_impulse + j.motor_impulse);
    if (j.type == JointType::prismatic) linear += axis * (j.axial_impulse + j.motor_impulse);
    if (j.type == JointType::swing_twist) {
        const Vec3<T> tb = rotate(b.orientation_, j.local_axis_b);
        const Vec3<T> n = cross(axis, tb);
        const T sin_swing = length(n);
        angular += axis * j.axial_impulse - (sin_swing > T(0) ? n / sin_swing : any_perpendicular(axis)) * j.swing_impulse;
    }
    return {linear / last_substep_, angular / last_substep_};
}

template <class T>
void World<T>::rebuild_joint_pairs() {
    unconnected_pairs_.clear();
    for (const Joint<T>& j : joints_)
        if (j.alive && !j.collide_connected) unconnected_pairs_.push_back(pair_key(j.a.index, j.b.index));
    std::sort(unconnected_pairs_.begin(), unconnected_pairs_.end());
}

template <class T>
void World<T>::prepare_joints(T h) {
    joint_rows_.clear();
    using detail::Softness;
    const Softness<T> soft = Softness<T>::make(std::min(settings_.joint_hertz, T(0.25) / h), settings_.joint_damping_ratio, h);
    const Softness<T> limit_soft =
        Softness<T>::make(detail::capped_contact_hertz(settings_, h), T(detail::limit_damping_ratio), h);
    for (std::uint32_t i = 0; i < joints_.size(); ++i) {
        Joint<T>& j = joints_[i];
        if (!joint_active(j)) continue;
        detail::JointConstraint<T> c;
        c.joint = i;
        c.a = solver_index_[j.a.index];
        c.b = solver_index_[j.b.index];
        if (c.a == 0 && c.b == 0) continue;  // both asleep or static
        c.mass_a = solver_masses_[c.a];
        c.mass_b = solver_masses_[c.b];
        const Body<T>& a = bodies_[j.a.index];
        const Body<T>& b = bodies_[j.b.index];
        c.r_a0 = rotate(a.orientation_, j.local_anchor_a);
        c.r_b0 = rotate(b.orientation_, j.local_anchor_b);
        c.delta_center = b.position_ - a.position_;
        c.axis_a0 = rotate(a.orientation_, j.local_axis_a);
        c.axis_b0 = rotate(b.orientation_, j.local_axis_b);
        c.ref_a0 = rotate(a.orientation_, j.local_ref_a);
        c.ref_b0 = rotate(b.orientation_, j.local_ref_b);
        c.qa0 = a.orientation_;
        c.qb0 = b.orientation_;
        if (j.enable_motor) c.motor_start_speed = motor_axis_speed(j, c.axis_a0);
        c.softness = settings_.solver == SolverMode::soft_step ? soft : detail::Softness<T>::make(T(0.25) / h, T(1), h);
        c.limit_softness = settings_.solver == SolverMode::soft_step ? limit_soft : c.softness;
        c.max_bias_speed = settings_.max_linear_speed;
        // A velocity change of half the largest speed setting (10⁶ m/s in float, 10³⁰ in double)
        // per substep: at max_size's 10⁵⁰ in double, a weld and a distance joint fighting spun a
        // body fast enough that its contacts' impulses overflowed to inf.
        const auto cap = [](T response) {
            return response > T(0) ? T(0.5) * detail::max_setting_length<T>() / response : ScalarTraits<T>::infinity;
        };
        // At the joint's own levers (a slider's on A is r_A + d, d the anchors' separation):
        // anchored 1e30 m out on a 0.24 kg box (double), a row at the bounding radius's cap spun
        // the box so fast that its contacts overflowed to inf.
        const T lever_a = length(c.r_a0) + (j.type == JointType::prismatic ? length(c.delta_center + c.r_b0 - c.r_a0) : T(0));
        const T spin_a = detail::spin_per_impulse(a), spin_b = detail::spin_per_impulse(b);
        c.max_linear_impulse =
            cap(detail::speed_per_impulse(a, spin_a, lever_a) + detail::speed_per_impulse(b, spin_b, length(c.r_b0)));
        c.max_angular_impulse = cap(spin_a + spin_b);
        c.max_axial_impulse = detail::linear_axis(j.type) ? c.max_linear_impulse : c.max_angular_impulse;
        const auto speed_cap = [&](std::uint32_t k) {  // a static stand-in (0) does not move
            return k == 0 ? T(0) : j.type == JointType::prismatic ? integration_[k].max_speed : integration_[k].spin_cap.roll;
        };
        c.motor_speed = clamp(j.motor_speed, -(speed_cap(c.a) + speed_cap(c.b)), speed_cap(c.a) + speed_cap(c.b));
        if (!settings_.warm_starting) {
            j.linear_impulse = j.angular_impulse = Vec3<T>::zero();
            j.axial_impulse = j.motor_impulse = j.swing_impulse = T(0);
        }
        joint_rows_.push_back(c);
    }
}

/// The joints' part of each stage of the step (World::solve calls it through joint_stage_).
template <class T>
void World<T>::run_joint_stage(JointStage stage, T h) {
    switch (stage) {
        case JointStage::prepare: prepare_joints(h); return;
        case JointStage::turn_inertias: turn_joint_inertias(h); return;
        case JointStage::warm_start:
            for (const detail::JointConstraint<T>& c : joint_rows_)
                detail::warm_start_joint(joints_[c.joint], c, solver_bodies_[c.a], solver_bodies_[c.b]);
            return;
        case JointStage::solve:
        case JointStage::relax:  // the solve with its bias, and the relax sweeps without
            for (int sweep = 0; sweep < settings_.joint_iterations; ++sweep)
                for (const detail::JointConstraint<T>& c : joint_rows_)
                    detail::solve_joint(joints_[c.joint], c, solver_bodies_[c.a], solver_bodies_[c.b], stage == JointStage::solve,
                                        h);
            return;
        case JointStage::cap:
            for (const detail::JointConstraint<T>& c : joint_rows_) detail::cap_joint_impulses(joints_[c.joint], c);
            return;
    }
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Islands and sleeping (world.hpp, step): islands touched by an awake body wake; the sleep
// clocks run on slow bodies and on bodies resting near where their clock started; an island whose
// every body has slept long enough falls asleep, unless it slides, drifts or is driven by a
// motor. Included at the end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

/// Per slot of an active body, in island_sleep_time_ (scratch until update_sleep): the speed of
/// the fastest point of its group at the start of the step, where a group is the active bodies
/// joined by contacts with points (speculative ones too) and by joints. A body at rest beside a sleeper
/// can be struck within the step and leave at up to twice the striker's speed (an elastic hit
/// on a lighter body), which its own velocity before the solve does not show: a box resting
/// 1 cm from a sleeper and struck at 10 m/s was driven 7 cm into it, the sleeper not woken.
/// Linear in bodies, contacts and joints (a union–find in island_parent_, rebuilt after).
template <class T>
void World<T>::measure_group_speeds() {
    std::vector<std::uint32_t>& parent = island_parent_;
    parent.resize(bodies_.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto both_active = [&](std::uint32_t a, std::uint32_t b) { return active(bodies_[a]) && active(bodies_[b]); };
    for (const Contact<T>& c : contacts_)
        if (!c.sensor && c.manifold.count > 0 && both_active(c.a.index, c.b.index))
            parent[island_root(c.a.index)] = island_root(c.b.index);
    for (const Joint<T>& j : joints_)
        if (joint_active(j) && both_active(j.a.index, j.b.index)) parent[island_root(j.a.index)] = island_root(j.b.index);
    std::vector<T>& speed = island_sleep_time_;
    speed.assign(bodies_.size(), T(0));
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
        const Body<T>& b = bodies_[i];
        if (!b.alive_ || !active(b)) continue;
        // Velocities only: what gravity adds over the step (in travel_speed) is what a resting body's
        // support takes away, and counted here every awake body at rest in a pile reached 5 mm
        // further (2 g dt²): it woke its sleeping neighbours, which woke it, and of the 64 boxes
        // of the sleeping-pile scene 48 never slept. A pair's own approach under gravity is
        // closes_within_step's.
        const T point_speed =
            std::min(length(b.linear_velocity_), speed_limit(b)) + length(b.angular_velocity_) * b.bounding_radius();
        T& fastest = speed[island_root(i)];
        fastest = std::max(fastest, point_speed);
    }
    for (std::uint32_t i = 0; i < bodies_.size(); ++i)
        if (bodies_[i].alive_ && active(bodies_[i])) speed[i] = speed[island_root(i)];
}

/// Whether some point of the contact is within the slop of touching at the bodies' poses now:
/// close enough that one body, awake, wakes the other (closes_within_step).
template <class T>
bool World<T>::within_slop(const Contact<T>& c) const {
    const Body<T>& a = bodies_[c.a.index];
    const Body<T>& b = bodies_[c.b.index];
    for (int i = 0; i < c.manifold.count; ++i) {
        const ContactPoint<T>& cp = c.manifold.points[static_cast<std::size_t>(i)];
        if (dot(b.world_point(cp.local_b) - a.world_point(cp.local_a), c.manifold.normal) <= settings_.linear_slop) return true;
    }
    return false;
}

/// Islands: dynamic bodies joined by joints and by (non-sensor) contacts with points that touch, lie
/// within the slop, or are not coming apart, as a union–find over body slots in island_parent_
/// (linear in bodies, contacts and joints). Such a contact can wake a sleeper from an awake body
/// (wake_touched_islands), so its two bodies share one sleep clock: apart, they took turns waking
/// each other for ever. Two boxes resting 2 mm apart, one dropped a little later, did; so did
/// boxes at rest 7-9 mm apart in a pile, where the closing test counts the awake one's fall under
/// gravity (2.7 mm a step at 60 Hz) and the fastest point of its group: a 400-box dropped pile
/// slept after 19 s in float instead of 8 s. A contact coming apart (faster than a thousandth of
/// the sleep speed at every point) joins nothing beyond the slop: a ball drifting away from a box
/// at rest lets the box sleep.
template <class T>
void World<T>::build_islands() {
    std::vector<std::uint32_t>& parent = island_parent_;
    parent.resize(bodies_.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto dynamic = [&](std::uint32_t slot) { return bodies_[slot].type_ == BodyType::dynamic; };
    const T apart = T(1e-3) * settings_.sleep_linear_speed;
    for (const Contact<T>& c : contacts_)
        if (!c.sensor && c.manifold.count > 0 && dynamic(c.a.index) && dynamic(c.b.index) &&
            (c.touching || within_slop(c) || !separating(c, apart)))
            parent[island_root(c.a.index)] = island_root(c.b.index);
    for (const Joint<T>& j : joints_)
        if (joint_active(j) && dynamic(j.a.index) && dynamic(j.b.index)) parent[island_root(j.a.index)] = island_root(j.b.index);
}

/// The root of a slot in a union–find over body slots, halving the path as it goes: islands
/// (island_root, after build_islands) and the bodies that hold each other (keep_drifting_islands_awake).
template <class T>
std::uint32_t World<T>::union_root(std::vector<std::uint32_t>& parent, std::uint32_t slot) {
    while (parent[slot] != slot) slot = parent[slot] = parent[parent[slot]];
    return slot;
}

template <class T>
void World<T>::wake_touched_islands(T dt) {
    // Islands of dynamic bodies joined by touching contacts and joints (union–find, linear in
    // bodies and contacts). A sleeping island wakes as a whole, before the solver runs, when an
    // active body touches one of its bodies, has a contact with it that can close within this
    // step (speculative points count) or is jointed to it: an awake body is never solved against
    // a sleeping one, which would act as an immovable wall and eat the impact.
    // (Nothing active, nothing wakes: a world asleep skips the islands; so does a world with no
    // body asleep, where there is nothing to wake: 0.47 ms of the 5,050-box pyramid's step with
    // sleeping off.)
    const auto asleep = [](const Body<T>& b) { return b.type_ == BodyType::dynamic && !b.awake_ && b.enabled_; };
    bool any_active = false, any_asleep = false;
    for (const Body<T>& b : bodies_) {
        if (!b.alive_) continue;
        any_active = any_active || active(b);
        any_asleep = any_asleep || asleep(b);
        if (any_active && any_asleep) break;
    }
    if (!any_active || !any_asleep) return;
    measure_group_speeds();
    const std::vector<T>& group_speed = island_sleep_time_;
    build_islands();
    auto find = [&](std::uint32_t slot) { return island_root(slot); };
    auto sleeping = [&](std::uint32_t slot) { return asleep(bodies_[slot]); };

    std::vector<std::uint8_t>& wake = island_flag_;
    wake.assign(bodies_.size(), 0);
    bool any = false;
    auto reach = [&](std::uint32_t from, std::uint32_t to) {
        if (active(bodies_[from]) && sleeping(to)) wake[find(to)] = 1, any = true;
    };
    for (const Contact<T>& c : contacts_) {
        if (c.sensor || c.manifold.count == 0) continue;  // sensors never push
        const bool a_to_b = active(bodies_[c.a.index]) && sleeping(c.b.index);
        const bool b_to_a = active(bodies_[c.b.index]) && sleeping(c.a.index);
        if (!a_to_b && !b_to_a) continue;
        if (!c.touching && !closes_within_step(c, dt, group_speed[a_to_b ? c.a.index : c.b.index])) continue;
        reach(c.a.index, c.b.index);
        reach(c.b.index, c.a.index);
    }
    for (const Joint<T>& j : joints_) {
        if (!joint_active(j)) continue;
        reach(j.a.index, j.b.index);
        reach(j.b.index, j.a.index);
    }
    if (!any) return;
    for (std::uint32_t i = 0; i < bodies_.size(); ++i)
        if (bodies_[i].alive_ && sleeping(i) && wake[find(i)]) bodies_[i].wake();
}

// True when the pair slides: its friction was at the Coulomb bound in the last solve and its
// surfaces still slip, faster than a tenth of the sleep speed, at the patch centre. A body that
// speeds up slowly from rest (a box on a ramp a little steeper than its friction angle: 0.04
// m/s² at 0.2° past it) stays under the sleep speeds for the whole sleep time, and sleeping
// would stop it for good. Friction at the bound alone does not tell: a domino that slid until
// it leans on the next rests with its friction at the bound and slips at 1e-7 m/s. A pair that
// slides only for a moment (a pile settling) delays its island's sleep by that moment, as the
// island's clocks keep running. The bound is met to round-off when the row clamps (the solver
// scales the impulse onto it); 1e-3 below it counts.
template <class T>
bool World<T>::sliding(const Contact<T>& c) const {
    const Manifold<T>& m = c.manifold;
    const Body<T>& a = bodies_[c.a.index];
    const Body<T>& b = bodies_[c.b.index];
    T load = T(0);
    Vec3<T> centre{};
    for (int i = 0; i < m.count; ++i) {
        load += m.points[static_cast<std::size_t>(i)].normal_impulse;
        centre += a.world_point(m.points[static_cast<std::size_t>(i)].local_a);
    }
    const T bound = T(0.999) * c.friction * load;
    if (!(load > T(0)) || length_squared(m.friction_impulse) < bound * bound) return false;
    centre = centre / static_cast<T>(m.count);
    const Vec3<T> v = b.velocity_at(centre) - a.velocity_at(centre);
    const T slow_slip = settings_.sleep_linear_speed / T(10);
    return length_squared(v - m.normal * dot(v, m.normal)) > slow_slip * slow_slip;
}

template <class T>
void World<T>::update_sleep(T dt) {
    if (!settings_.allow_sleeping) return;
    if (std::none_of(bodies_.begin(), bodies_.end(), &World::awake_dynamic)) return;  // no clock to run
    build_islands();
    run_sleep_clocks(dt);
    keep_moving_islands_awake();
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
        Body<T>& b = bodies_[i];
        if (!awake_dynamic(b) || !clock_done(island_sleep_time_[island_root(i)])) continue;
        b.awake_ = false;
        b.linear_velocity_ = Vec3<T>::zero();
        b.angular_velocity_ = Vec3<T>::zero();
    }
}

/// Each awake dynamic body's sleep clock, and in island_sleep_time_ (by island root) the least
/// clock of each island. A body's clock runs while it is slow or stays within `reach` of its pose
/// when the clock started (Body::distance_from_rest); an island sleeps when all its clocks passed
/// sleep_time and none refuses to sleep or touches a moving kinematic body.
template <class T>
void World<T>::run_sleep_clocks(T dt) {
    const T lin_sq = settings_.sleep_linear_speed * settings_.sleep_linear_speed;
    const T ang_sq = settings_.sleep_angular_speed * settings_.sleep_angular_speed;
    const T reach = settings_.sleep_linear_speed * settings_.sleep_time;
    island_sleep_time_.assign(bodies_.size(), ScalarTraits<T>::infinity);
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
        Body<T>& b = bodies_[i];
        if (!awake_dynamic(b)) continue;
        const bool slow = length_squared(b.linear_velocity_) < lin_sq && length_squared(b.angular_velocity_) < ang_sq;
        // Near its rest pose but faster than the sleep speeds, the clock runs at a quarter rate,
        // so such a body sleeps after 4 × sleep_time: one still settling (a rock rocking onto a
        // face, at 5 cm/s and 0.24 rad/s when it slept at full rate) gets time to come to rest.
        // A stopped clock (re)starts from a new rest pose when the body is slow or has left the
        // old one; a fast body is not judged against a pose set this step, where every body is
        // (with sleep_time <= dt / 4 a box thrown at 10 m/s slept in mid-air after one step).
        const bool near = b.distance_from_rest() <= reach;
        const bool fresh = b.sleep_time_ == T(0) && (slow || !near);
        if (fresh) b.rest_position_ = b.position_, b.rest_orientation_ = b.orientation_;
        const T rate = slow ? T(1) : near && !fresh ? T(0.25) : T(0);
        b.sleep_time_ = (rate > T(0) && b.allow_sleep_) ? b.sleep_time_ + rate * dt : T(0);
        const std::uint32_t root = island_root(i);
        island_sleep_time_[root] = std::min(island_sleep_time_[root], b.sleep_time_);
    }
}

/// An island that slides (World::sliding), or touches or is jointed to a moving kinematic body,
/// stays awake: its least clock is set back to 0. The slide is looked at only where an awake
/// island would otherwise sleep now, rarely a step.
template <class T>
void World<T>::keep_moving_islands_awake() {
    std::vector<T>& island_min = island_sleep_time_;
    const auto would_sleep = [&](std::uint32_t i) {
        const Body<T>& b = bodies_[i];
        return b.type_ == BodyType::dynamic && b.awake_ && clock_done(island_min[island_root(i)]);
    };
    // A moving kinematic body touching an island or jointed to it keeps it awake: asleep, a box
    // hung on a joint from a slowly moving kinematic body stopped, was woken by the joint the next
    // step and fell asleep again 19 times in 10 s, ending 1.2 cm behind where it hung awake.
    const auto driven_by_kinematic = [&](std::uint32_t a, std::uint32_t b) {
        for (const auto& [k, d] : {std::pair{a, b}, std::pair{b, a}}) {
            const Body<T>& kin = bodies_[k];
            if (kin.type_ == BodyType::kinematic && bodies_[d].type_ == BodyType::dynamic &&
                (length_squared(kin.linear_velocity_) > T(0) || length_squared(kin.angular_velocity_) > T(0)))
                island_min[island_root(d)] = T(0);
        }
    };
    for (const Contact<T>& c : contacts_) {
        if (!c.touching) continue;
        if ((would_sleep(c.a.index) || would_sleep(c.b.index)) && sliding(c))
            for (const std::uint32_t i : {c.a.index, c.b.index})
                if (bodies_[i].type_ == BodyType::dynamic) island_min[island_root(i)] = T(0);
        driven_by_kinematic(c.a.index, c.b.index);
    }
    for (const Joint<T>& j : joints_)
        if (joint_active(j)) driven_by_kinematic(j.a.index, j.b.index);
    for (const detail::JointConstraint<T>& row : joint_rows_) {  // this step's joints between awake bodies
        const Joint<T>& j = joints_[row.joint];
        if (motor_turning(j, row.motor_start_speed) && (would_sleep(j.a.index) || would_sleep(j.b.index)))
            for (const std::uint32_t i : {j.a.index, j.b.index})
                if (bodies_[i].type_ == BodyType::dynamic) island_min[island_root(i)] = T(0);
    }
    keep_drifting_islands_awake();
}

/// The relative speed of a hinge's (rad/s) or a slider's (m/s) bodies about or along its axis
/// (A's axis in world space).
template <class T>
T World<T>::motor_axis_speed(const Joint<T>& j, const Vec3<T>& axis) const {
    const Body<T>& a = bodies_[j.a.index];
    const Body<T>& b = bodies_[j.b.index];
    return j.type == JointType::hinge ? dot(b.angular_velocity_ - a.angular_velocity_, axis)
                                      : dot(b.linear_velocity_ - a.linear_velocity_, axis);
}

/// Whether a joint's motor drives its bodies: enabled, with a speed and a torque (or force), and
/// moving at half its speed or more, or still gaining on it (since `start_speed`, the step's
/// start) by 1 % or more of what its torque alone gives in a step. A motor slower than the sleep
/// speeds (a hinge at 0.02 rad/s) stopped after sleep_time, and so did a heavy wheel spun up by a
/// small torque (2 N·m on 19.6 kg·m², 0.1 rad/s²) before it reached them; a stalled motor (held
/// by a limit or a load above its torque) gains nothing and lets its island sleep.
template <class T>
bool World<T>::motor_turning(const Joint<T>& j, T start_speed) const {
    if (!joint_active(j) || !j.enable_motor || j.motor_speed == T(0) || !(j.max_motor_torque > T(0))) return false;
    const Body<T>& a = bodies_[j.a.index];
    const Body<T>& b = bodies_[j.b.index];
    const Vec3<T> axis = rotate(a.orientation_, j.local_axis_a);
    const T speed = motor_axis_speed(j, axis);
    if (speed * j.motor_speed >= T(0.5) * j.motor_speed * j.motor_speed) return true;
    const T response = j.type == JointType::hinge ? dot(axis, (a.inverse_inertia_world() + b.inverse_inertia_world()) * axis)
                                                  : a.inverse_mass_ + b.inverse_mass_;
    const T dt = last_substep_ * substeps_per_step();
    const T gained = j.motor_speed > T(0) ? speed - start_speed : start_speed - speed;
    return gained > T(0.01) * j.max_motor_torque * dt * response;
}

/// An island in free flight, held by no static or kinematic body through a contact or a joint,
/// keeps its momentum: it stays awake while any of its bodies moves at all. Sleeping stops a
/// body, and only a contact or a joint may take its momentum: in zero gravity a 100 kg ball
/// struck by a 1 kg ball drifted off at 4 cm/s, under the sleep speed, and stopped 0.5 s later,
/// turning the pair's momentum from +2 to −2 kg·m/s. (Under gravity no island floats that slowly
/// for sleep_time, bar one whose gravity_scale is 0.) The island's clock is set back as the
/// sliding rule above does; an island at rest in free flight still sleeps.
template <class T>
void World<T>::keep_drifting_islands_awake() {
    std::vector<T>& island_min = island_sleep_time_;
    const auto would_sleep = [&](std::uint32_t i) {
        const Body<T>& b = bodies_[i];
        return b.alive_ && b.type_ == BodyType::dynamic && b.awake_ && clock_done(island_min[island_root(i)]);
    };
    bool any = false;  // nearly every step nothing is about to sleep
    for (std::uint32_t i = 0; i < bodies_.size() && !any; ++i) any = would_sleep(i);
    if (!any) return;
    // Held is judged over the bodies joined by joints and by contacts that touch, or lie within
    // the slop and are not coming apart: an island joins a body near it (build_islands), which
    // shares its clock but takes no force from it, and a ball drifting off at 5 mm/s, 2 mm from
    // a box resting on the floor (gravity 0), froze with the box.
    std::vector<std::uint32_t>& parent = drift_parent_;
    parent.resize(bodies_.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&](std::uint32_t slot) { return union_root(parent, slot); };
    const auto dynamic = [&](std::uint32_t slot) { return bodies_[slot].type_ == BodyType::dynamic; };
    const T apart = T(1e-3) * settings_.sleep_linear_speed;
    std::vector<std::uint8_t> holds(contacts_.size(), 0);  // rarely built: only when a body is about to sleep
    for (std::size_t k = 0; k < contacts_.size(); ++k) {
        const Contact<T>& c = contacts_[k];
        holds[k] = !c.sensor && c.manifold.count > 0 && (c.touching || (within_slop(c) && !separating(c, apart)));
        if (holds[k] && dynamic(c.a.index) && dynamic(c.b.index)) parent[root(c.a.index)] = root(c.b.index);
    }
    for (const Joint<T>& j : joints_)
        if (joint_active(j) && dynamic(j.a.index) && dynamic(j.b.index)) parent[root(j.a.index)] = root(j.b.index);
    std::vector<std::uint8_t>& held = island_flag_;  // scratch here: wake_touched_islands is done with it
    held.assign(bodies_.size(), 0);
    const auto hold = [&](std::uint32_t a, std::uint32_t b) {  // a body of one side held by the other
        if (!dynamic(a)) held[root(b)] = 1;
        if (!dynamic(b)) held[root(a)] = 1;
    };
    for (std::size_t k = 0; k < contacts_.size(); ++k)
        if (holds[k]) hold(contacts_[k].a.index, contacts_[k].b.index);
    for (const Joint<T>& j : joints_)
        if (joint_active(j)) hold(j.a.index, j.b.index);
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
        const Body<T>& b = bodies_[i];
        if (would_sleep(i) && !held[root(i)] &&
            (length_squared(b.linear_velocity_) > T(0) || length_squared(b.angular_velocity_) > T(0)))
            island_min[island_root(i)] = T(0);
    }
}

/// Whether every point of the contact opens faster than `speed` (m/s) along the normal.
template <class T>
bool World<T>::separating(const Contact<T>& c, T speed) const {
    const Body<T>& a = bodies_[c.a.index];
    const Body<T>& b = bodies_[c.b.index];
    for (int i = 0; i < c.manifold.count; ++i) {
        const ContactPoint<T>& cp = c.manifold.points[static_cast<std::size_t>(i)];
        const Vec3<T> pa = a.world_point(cp.local_a), pb = b.world_point(cp.local_b);
        if (!(dot(b.velocity_at(pb) - a.velocity_at(pa), c.manifold.normal) > speed)) return false;
    }
    return true;
}

}  // namespace xeno

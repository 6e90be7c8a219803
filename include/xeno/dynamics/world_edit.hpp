// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Changing a body after creation, by ID: its pose and velocity, shape, type, collision filter,
// sensor and `fast` flags, whether it takes part in the simulation at all, whether it sleeps, and
// a kinematic body's next pose. Each call checks everything first and changes nothing when it
// rejects (InvalidArgument), then keeps what the world derives from the body true: the broad-phase
// and query boxes, the contacts (ended, with events, where the change makes them meaningless) and
// the islands (it wakes what the change can move; a sleeping body is never left resting on
// something that changed under it). The narrow phase re-reads layer, mask, sensor and type every
// step, so those changes need no more than a wake. Included at the end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

template <class T>
void World<T>::require_centred(const Shape<T>& shape, const char* where) {
    const Vec3<T> centre = interior_point(shape);
    if (length(centre) > T(1e-4) * bounding_radius(shape))
        detail::report_invalid(where,
                               "the shape's centre of mass must be its local origin (make_convex_hull and "
                               "ConvexPolyhedron::recentered() re-centre); distance (m)",
                               static_cast<double>(length(centre)));
}

/// The body's boxes after its pose, shape, type or enabled flag changed: the broad phase's (fat by
/// the speculative distance; empty while disabled, so it pairs with nothing) and its place in the
/// query tree of its type (none while disabled). The tree of the body's type has room for every
/// slot up to it (create_body and set_type reserve it first), so nothing here allocates or throws.
template <class T>
void World<T>::place_in_broad_phase(std::uint32_t slot) {
    Body<T>& b = bodies_[slot];
    b.moved_ = true;
    AabbTree<T>& mine = query_tree_of(slot);
    for (AabbTree<T>& tree : query_trees_)
        if (&tree != &mine && tree.contains(slot)) tree.remove(slot);
    if (!b.enabled_) {
        bounds_[slot] = Aabb<T>{};
        if (mine.contains(slot)) mine.remove(slot);
    } else {
        const Aabb<T> box = b.world_bounds();
        bounds_[slot] = box.expanded(settings_.speculative_distance);
        if (mine.contains(slot)) mine.move(slot, box);
        else mine.insert(slot, box);
    }
    refresh_query_tree();
}

/// Wakes every body whose box comes within the speculative distance of this one's. A change to
/// a body (moved into a pile, turned solid, made static) must reach sleepers it has no contact
/// with yet: two inactive bodies are not collided, so they would never find out.
template <class T>
void World<T>::wake_overlapping(std::uint32_t slot) {
    const Body<T>& b = bodies_[slot];
    if (!b.enabled_) return;
    const Aabb<T> box = b.world_bounds().expanded(settings_.speculative_distance);
    query_trees_[1].query(box, [&](std::uint32_t other) {
        if (other != slot) bodies_[other].wake();
    });
}

template <class T>
void World<T>::set_transform(BodyId id, const Vec3<T>& position, const Quat<T>& orientation) {
    const char* where = "World::set_transform";
    require_outside_filter(where);
    const std::uint32_t slot = checked(id, where);
    detail::require_finite_xyz(position, where, "position");
    detail::require_orientation(orientation, where, "orientation");
    Body<T>& b = bodies_[slot];
    wake_overlapping(slot);  // where it was
    b.position_ = position;
    b.orientation_ = normalized(orientation);
    b.wake();
    previous_pose_[slot] = b.transform();
    place_in_broad_phase(slot);
    wake_neighbours_of(slot);
    wake_overlapping(slot);  // where it is
}

template <class T>
void World<T>::set_velocity(BodyId id, const Vec3<T>& linear, const Vec3<T>& angular) {
    const char* where = "World::set_velocity";
    require_outside_filter(where);
    Body<T>& b = bodies_[checked(id, where)];
    detail::require_finite_xyz(linear, where, "linear");
    detail::require_finite_xyz(angular, where, "angular");
    if (b.type_ == BodyType::static_body) return;
    b.linear_velocity_ = linear;
    b.angular_velocity_ = angular;
    b.wake();
}

// The velocities that carry the body from its pose to the target in dt. The integrator turns a
// body by 2·atan(h|ω|/2) per substep of length h (Δq ← normalise(Δq + h/2 (0, ω) Δq), about a
// fixed axis), so |ω| = (2/h)·tan(θ/2n) over n substeps lands on the target's angle θ to
// rounding; the rate it reports is within (θ/n)²/12 of θ/dt.
template <class T>
void World<T>::move_kinematic(BodyId id, const Vec3<T>& position, const Quat<T>& orientation, T dt) {
    const char* where = "World::move_kinematic";
    require_outside_filter(where);
    const std::uint32_t slot = checked(id, where);
    Body<T>& b = bodies_[slot];
    if (b.type_ != BodyType::kinematic)
        detail::report_invalid(where, "only kinematic bodies are moved to a target; body type", static_cast<double>(b.type_));
    detail::require_finite_xyz(position, where, "position");
    detail::require_orientation(orientation, where, "orientation");
    detail::require_positive(dt, where, "dt");
    detail::require_at_most(dt, detail::max_time_step<T>(), where, "dt", " s");
    const Vec3<T> v = (position - b.position_) / dt;
    Quat<T> turn = normalized(orientation) * conjugate(b.orientation_);
    if (turn.w < T(0)) turn = {-turn.w, -turn.x, -turn.y, -turn.z};  // the shorter way round (Quat is w, x, y, z)
    const Vec3<T> axis_sin{turn.x, turn.y, turn.z};                  // axis · sin(θ/2)
    const T sin_half = length(axis_sin);
    Vec3<T> w = Vec3<T>::zero();
    if (sin_half > T(0)) {
        const T n = substeps_per_step();
        const T angle = T(2) * std::atan2(sin_half, turn.w);
        const T h = dt / n;
        w = axis_sin * ((T(2) / h) * std::tan(angle / (T(2) * n)) / sin_half);
    }
    if (!is_finite(v) || !is_finite(w))
        detail::report_invalid(where, "the velocity to reach the target overflows; distance (m)",
                               static_cast<double>(distance(position, b.position_)));
    b.linear_velocity_ = v;
    b.angular_velocity_ = w;
    b.wake();
}

template <class T>
void World<T>::set_shape(BodyId id, std::shared_ptr<const Shape<T>> shape, MassUpdate mass) {
    const char* where = "World::set_shape";
    require_outside_filter(where);
    if (!shape) detail::report_invalid(where, "shape must not be null", 0.0);
    detail::require_moved_in(*shape, where);
    require_centred(*shape, where);
    set_shape_impl(checked(id, where), std::move(shape), nullptr, mass, where);
}

template <class T>
void World<T>::set_shape(BodyId id, std::shared_ptr<const Compound<T>> compound, MassUpdate mass) {
    const char* where = "World::set_shape";
    require_outside_filter(where);
    if (!compound) detail::report_invalid(where, "compound must not be null", 0.0);
    detail::require_moved_in(*compound, where);
    set_shape_impl(checked(id, where), nullptr, std::move(compound), mass, where);
}

// Contacts are per pair of parts and their points are in the parts' frames: none survives a new
// shape, so all end (with events) and the next step finds the new ones.
template <class T>
void World<T>::set_shape_impl(std::uint32_t slot, std::shared_ptr<const Shape<T>> shape,
                              std::shared_ptr<const Compound<T>> compound, MassUpdate mass, const char* where) {
    if (mass != MassUpdate::recompute && mass != MassUpdate::keep)
        detail::report_invalid(where, "mass must be MassUpdate::recompute or MassUpdate::keep; mass",
                               static_cast<double>(static_cast<std::uint8_t>(mass)));
    Body<T>& b = bodies_[slot];
    MassProperties<T> m{};
    // Kept, the mass stays and the inertia is the new shape's at that mass: the old inertia kept
    // with a new shape (a 5 cm ball's on a 10 m box) gave the solver's rows almost no effective
    // mass, and the box fell through the floor.
    const bool dynamic = b.type_ == BodyType::dynamic;
    const T kept = mass == MassUpdate::keep ? T(1) / b.inverse_mass_ : T(0);
    if (dynamic) m = dynamic_mass(shape.get(), compound.get(), b.density_, kept, where);
    wake_overlapping(slot);
    end_contacts_of(slot);
    b.set_geometry(std::move(shape), std::move(compound), nullptr);  // a mesh body given a convex shape becomes a convex body
    if (dynamic) b.set_mass_properties(m);
    b.wake();
    place_in_broad_phase(slot);
    wake_overlapping(slot);
}

template <class T>
void World<T>::set_density(BodyId id, T density) {
    const char* where = "World::set_density";
    require_outside_filter(where);
    Body<T>& b = bodies_[checked(id, where)];
    detail::require_positive(density, where, "density");
    if (b.type_ == BodyType::dynamic) b.set_mass_properties(dynamic_mass(b.convex_shape(), b.compound(), density, T(0), where));
    b.density_ = density;
}

// Static and kinematic bodies have no mass, force or torque; a static body no velocity either. A
// body that becomes dynamic gets density × its shape's mass. Its contacts stay (the narrow phase
// drops those that no longer have a dynamic side, with events); the island it leaves or joins
// wakes, so nothing sleeps on a body that started or stopped moving.
template <class T>
void World<T>::set_type(BodyId id, BodyType type) {
    const char* where = "World::set_type";
    require_outside_filter(where);
    const std::uint32_t slot = checked(id, where);
    Body<T>& b = bodies_[slot];
    if (type != BodyType::static_body && type != BodyType::kinematic && type != BodyType::dynamic)
        detail::report_invalid(where, "type must be static_body, kinematic or dynamic; type",
                               static_cast<double>(static_cast<std::uint8_t>(type)));
    if (type == b.type_) return;
    if (type == BodyType::static_body)  // as create_joint: a joint between two static bodies does nothing
        for (const Joint<T>& j : joints_)
            if (j.alive && (j.a.index == slot || j.b.index == slot) &&
                bodies_[j.a.index == slot ? j.b.index : j.a.index].type_ == BodyType::static_body)
                detail::report_invalid(where, "a body jointed to a static body cannot become static; body index",
                                       static_cast<double>(slot));
    if (type == BodyType::dynamic && b.mesh())
        detail::report_invalid(where, "a mesh or heightfield body cannot become dynamic (it has no volume to weigh); triangles",
                               static_cast<double>(triangle_count(*b.mesh())));
    MassProperties<T> m{};
    if (type == BodyType::dynamic) {
        if (!(b.density_ > T(0) && std::isfinite(b.density_)))
            detail::report_invalid(where, "a body becoming dynamic needs a density > 0 (set_density); density",
                                   static_cast<double>(b.density_));
        m = dynamic_mass(b.convex_shape(), b.compound(), b.density_, T(0), where);
    }
    query_tree_for(type).reserve(bodies_.size());  // may throw: before anything changes
    wake_neighbours_of(slot);
    b.type_ = type;
    b.force_ = b.torque_ = Vec3<T>::zero();
    b.sleep_time_ = T(0);
    if (type == BodyType::dynamic) {
        b.set_mass_properties(m);
    } else {
        b.inverse_mass_ = T(0);
        b.inertia_local_ = Mat3<T>::zero();
        b.isotropic_ = true;
    }
    if (type == BodyType::static_body) b.linear_velocity_ = b.angular_velocity_ = Vec3<T>::zero();
    b.wake();
    place_in_broad_phase(slot);
    wake_overlapping(slot);
}

template <class T>
void World<T>::set_collision_filter(BodyId id, std::uint32_t layer, std::uint32_t mask) {
    const char* where = "World::set_collision_filter";
    require_outside_filter(where);
    const std::uint32_t slot = checked(id, where);
    Body<T>& b = bodies_[slot];
    b.layer_ = layer;
    b.mask_ = mask;
    b.wake();
    wake_neighbours_of(slot);
    wake_overlapping(slot);
}

template <class T>
void World<T>::set_sensor(BodyId id, bool sensor) {
    const char* where = "World::set_sensor";
    require_outside_filter(where);
    const std::uint32_t slot = checked(id, where);
    Body<T>& b = bodies_[slot];
    // A touching pair that turns from solid to sensor (or back) ends, and begins again as the
    // other kind at the next step: an event that only flipped its sensor flag was never a
    // `began` to a listener waiting for sensor overlaps, nor an `ended` to one counting contacts.
    if (b.sensor_ != sensor) end_contacts_of(slot);
    b.sensor_ = sensor;
    b.wake();
    wake_neighbours_of(slot);
    wake_overlapping(slot);
}

template <class T>
void World<T>::set_fast(BodyId id, bool fast) {
    const char* where = "World::set_fast";
    require_outside_filter(where);
    Body<T>& b = bodies_[checked(id, where)];
    b.fast_ = fast;
    b.wake();
}

// A disabled body keeps its state (pose, velocity, mass, user data) but is out of the world: no
// box in the broad phase or the query trees, no contacts (they end, with events), no integration,
// and its joints do nothing until it is enabled again, when it wakes where it was.
template <class T>
void World<T>::set_enabled(BodyId id, bool enabled) {
    const char* where = "World::set_enabled";
    require_outside_filter(where);
    const std::uint32_t slot = checked(id, where);
    Body<T>& b = bodies_[slot];
    if (b.enabled_ == enabled) return;
    if (!enabled) {
        wake_overlapping(slot);
        end_contacts_of(slot);  // wakes its joint partners too
    }
    b.enabled_ = enabled;
    b.wake();
    place_in_broad_phase(slot);
    wake_overlapping(slot);
}

// Awake: the body, and at the next step whatever it touches. Asleep: its whole island (every
// dynamic body joined to it by touching contacts and joints), velocities zeroed as when it falls
// asleep by itself. An island put to sleep next to a moving body wakes again at the next step,
// as any sleeper does. Static and kinematic bodies do not sleep; for them this does nothing.
template <class T>
void World<T>::set_awake(BodyId id, bool awake) {
    const char* where = "World::set_awake";
    require_outside_filter(where);
    const std::uint32_t slot = checked(id, where);
    Body<T>& b = bodies_[slot];
    if (b.type_ != BodyType::dynamic || !b.enabled_) return;
    if (awake) {
        b.wake();
        return;
    }
    build_islands();
    const std::uint32_t root = island_root(slot);
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
        Body<T>& other = bodies_[i];
        if (!other.alive_ || !other.enabled_ || other.type_ != BodyType::dynamic || island_root(i) != root) continue;
        other.awake_ = false;
        other.sleep_time_ = T(0);
        other.linear_velocity_ = other.angular_velocity_ = Vec3<T>::zero();
    }
}

}  // namespace xeno

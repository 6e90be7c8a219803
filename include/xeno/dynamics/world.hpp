// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// World<T>: the thesis's PhysicsSystem (3.2.2.6) templated on the scalar. It owns the bodies
// (reached through BodyId handles that cannot dangle), their contacts and the solver's scratch.
// step(dt) advances one fixed step and reads top to bottom, one named phase per call:
//    1. check dt; body bounds for the broad phase
//    2. broad phase      fattened world boxes → sorted pairs (sweep and prune by default)
//    3. narrow phase     per pair: contact manifold by MPR + face clipping, matched to last step's
//                        points so their impulses warm-start; pairs that left lose their contact
//    4. wake             islands touched by an awake body wake up
//    5. prepare          solver bodies and contact rows (anchors, effective masses, softness,
//                        restitution speeds, carried by gravity to each impact)
//    6. substeps         integrate velocities → warm start → solve with bias → integrate positions
//                        → relax (docs/solver-design.md, "Substeps"; baumgarte mode: one substep
//                        and N iterations)
//    7. restitution      one pass after the substeps
//    8. finish           impulses stored in the manifolds, poses and velocities written back
//    9. sleep, events    islands of slow bodies fall asleep; the query trees follow the bodies
//                        that moved; contact events are reported
// This file declares World and defines its creation, update and step; each phase's code is in a
// header of its own, included at the end: world_broad.hpp (1, 2 and the query trees of 9),
// world_narrow.hpp (3), world_sleep.hpp (4 and the sleep of 9), world_solve.hpp (5–8) and
// world_events.hpp (the events of 9).
// With set_workers(n) or set_task_system(&jobs), the phases' independent work (per body, per pair,
// per row, per colour's groups) runs on several threads with the same result (docs/parallel.md).
// update(seconds) runs whole steps from an accumulator (thesis Quadro 22) and leaves the remainder
// as an interpolation factor for rendering. Between steps, bodies change by ID (world_edit.hpp)
// and the world answers queries (world_query.hpp).
#pragma once

#include "../broadphase/brute_force.hpp"
#include "../broadphase/aabb_tree.hpp"
#include "../broadphase/sweep_and_prune.hpp"
#include "../collide/collide.hpp"
#include "../collide/early_out.hpp"
#include "../collide/mesh_collide.hpp"
#include "../collide/raycast.hpp"
#include "../collide/shape_cast.hpp"
#include "../contact/manifold.hpp"
#include "../contact/patch.hpp"
#include "../task_system.hpp"
#include "body.hpp"
#include "contact_solver.hpp"
#include "wide_contact_solver.hpp"
#include "integrator.hpp"
#include "joint.hpp"
#include "query_filter.hpp"
#include "rebound_energy.hpp"
#include "support_stiffness.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <iterator>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace xeno {

/// A touching (or nearly touching) pair and its persistent manifold; A has the lower slot.
template <class T>
struct Contact {
    BodyId a, b;
    std::uint32_t child_a = 0, child_b = 0;  ///< the touching parts (compound bodies; 0 otherwise)
    Manifold<T> manifold;
    T friction{}, restitution{};  ///< combined from the two materials
    bool touching = false;        ///< some point overlaps, or pushed during the last step
    bool was_touching = false;    ///< touching at the end of the previous step (events)
    bool sensor = false;          ///< one body is a sensor: reported, never solved
    // Where the narrow phase last made this manifold: while no contact point has moved, and cannot
    // move within the step, more than a tenth of linear_slop relative to A, the next step
    // re-measures the points instead of colliding the shapes again (docs/collision.md, "Reusing a
    // manifold").
    Vec3<T> made_offset{};                    ///< m, B's centre of mass in A's body frame
    Quat<T> made_turn = Quat<T>::identity();  ///< B's orientation relative to A's
    Vec3<T> made_normal{};                    ///< unit, the normal in A's body frame
    // The twist-friction lever of the polygon the points span (contact/patch.hpp; a round face
    // resting whole uses 2r/3 instead: World::twist_lever), computed from the points' anchors on
    // A and kept while they stay: a manifold re-measured step after step (a stack at rest) does
    // not integrate its patch again. The key is a digest of those anchors, 0 before the first
    // solve.
    T twist_lever{};  ///< m
    std::uint64_t twist_lever_key = 0;
};

enum class ContactEventKind { began, persisted, ended };

/// A change in contact reported after a step: two bodies began to touch (or a sensor began to
/// overlap), still touch, or stopped touching. Delivered after the step, when the world is
/// consistent; the handles may be stale by the time a listener sees them if an earlier listener
/// call destroyed the body (check World::contains).
template <class T>
struct ContactEvent {
    ContactEventKind kind = ContactEventKind::began;
    BodyId a, b;
    bool sensor = false;              ///< one of the bodies is a sensor (overlap, no response)
    Vec3<T> normal{};                 ///< unit, world, from A to B
    int count = 0;                    ///< contact points (0 for ended events)
    std::array<Vec3<T>, 4> points{};  ///< m, world: the middle of each contact point pair
    T impulse{};                      ///< N·s: total normal impulse over the step (0 for sensors)
    /// The touching parts, as in Contact: a compound's part index, 0 for a convex body. A pair of
    /// bodies touching through several parts has a contact, and so events, for each part pair
    /// (as Box2D's events are per shape pair): a dumbbell on the floor begins twice, and when one
    /// end lifts that end's contact ends while the other's persists.
    std::uint32_t child_a = 0, child_b = 0;
};

/// The contacts of one body (World::contacts_of): const Contact<T>& in the order of contacts().
template <class T>
class ContactRange {
public:
    class iterator {
    public:
        iterator(const Contact<T>* contacts, const std::uint32_t* at) : contacts_(contacts), at_(at) {}
        const Contact<T>& operator*() const { return contacts_[*at_]; }
        const Contact<T>* operator->() const { return &contacts_[*at_]; }
        iterator& operator++() {
            ++at_;
            return *this;
        }
        bool operator==(const iterator& o) const { return at_ == o.at_; }
        bool operator!=(const iterator& o) const { return at_ != o.at_; }

    private:
        const Contact<T>* contacts_;
        const std::uint32_t* at_;
    };
    ContactRange(const Contact<T>* contacts, const std::uint32_t* first, const std::uint32_t* last)
        : contacts_(contacts), first_(first), last_(last) {}
    iterator begin() const { return {contacts_, first_}; }
    iterator end() const { return {contacts_, last_}; }
    std::size_t size() const { return static_cast<std::size_t>(last_ - first_); }
    bool empty() const { return first_ == last_; }

private:
    const Contact<T>* contacts_;
    const std::uint32_t *first_, *last_;
};

/// A ray hit on a body of the world.
template <class T>
struct WorldRayHit {
    BodyId body;
    RayHit<T> hit;
};

/// A shape cast's hit on a body of the world.
template <class T>
struct WorldShapeCastHit {
    BodyId body;
    ShapeCastHit<T> hit;
};

/// Counters of the last step, for benchmarks and tests.
struct StepStats {
    std::size_t broad_pairs = 0;      ///< pairs whose boxes overlapped
    std::size_t apart_pairs = 0;      ///< of those, convex pairs the early-out found apart (no narrow phase)
    std::size_t reused_contacts = 0;  ///< manifolds re-measured instead of made again (the pair barely moved)
    std::size_t dropped_pairs = 0;    ///< of those, left out: more than settings.max_contact_pairs (a crowd)
    std::size_t contacts = 0;         ///< manifolds with at least one point
    std::size_t contact_points = 0;   ///< rows solved
    std::size_t awake_bodies = 0;
    std::size_t colours = 0;            ///< colours the solved manifolds took (docs/solver.md, "Colours")
    std::size_t overflow_contacts = 0;  ///< manifolds no colour could take, solved one at a time
    /// Wall-clock seconds of each stage (steady_clock), to see where a step's time goes and what
    /// stays serial with several workers (docs/parallel.md).
    struct Times {
        double bounds = 0, broad = 0, narrow = 0, wake = 0, prepare = 0, solve = 0, finish = 0, sleep = 0, queries = 0,
               events = 0;
    } seconds;
};

/// A rigid-body world of scalar T.
template <class T>
class World {
public:
    using scalar_type = T;

    explicit World(const WorldSettings<T>& settings = {}) : settings_(settings) { detail::validate(settings_); }
    // Copies take everything but the worker pool (a copy gets one of its own), moves everything.
    // Declared here and defined after the class, not left implicit, so that compiled mode
    // (compiled.hpp) compiles them once with the rest of World instead of in every user file.
    World(const World&);
    World(World&&);
    World& operator=(const World&);
    World& operator=(World&&) noexcept;
    ~World();

    const WorldSettings<T>& settings() const { return settings_; }
    /// Replaces the settings (checked, InvalidArgument on bad values). A new gravity, or sleeping
    /// turned off, wakes every sleeping body: a sleeper is not integrated, so it would hang on in
    /// the old gravity (as Body::set_gravity_scale wakes its body).
    void set_settings(const WorldSettings<T>& s) {
        require_outside_filter("World::set_settings");
        detail::validate(s);
        const bool wake_all = !(s.gravity == settings_.gravity) || (settings_.allow_sleeping && !s.allow_sleeping);
        settings_ = s;
        if (wake_all)
            for (Body<T>& b : bodies_)
                if (b.alive_ && b.type_ == BodyType::dynamic) b.wake();
    }
    void set_gravity(const Vec3<T>& g) {
        WorldSettings<T> s = settings_;
        s.gravity = g;
        set_settings(s);
    }

    /// Creates a body of the given (shared) shape. Checks the definition at the door: finite
    /// pose and velocities, non-zero orientation (normalised), positive density or mass for
    /// dynamic bodies (a number for the others), a shape whose centre of mass is its local origin.
    BodyId create_body(std::shared_ptr<const Shape<T>> shape, const BodyDef<T>& def = {});
    /// Convenience: the shape is copied into a new shared shape.
    BodyId create_body(const Shape<T>& shape, const BodyDef<T>& def = {});
    /// A compound body (several convex parts); the compound is already centred on its centre of
    /// mass, so def.position is where that centre goes.
    BodyId create_body(std::shared_ptr<const Compound<T>> compound, const BodyDef<T>& def = {});
    BodyId create_body(const Compound<T>& compound, const BodyDef<T>& def = {});
    /// A body of level geometry, a triangle mesh or a heightfield (docs/meshes.md), placed by
    /// def.position and def.orientation (the mesh's own frame: a mesh has no centre of mass).
    /// Static or kinematic only: a dynamic definition is rejected (InvalidArgument), so the
    /// definition has no default here.
    BodyId create_body(std::shared_ptr<const MeshShape<T>> mesh, const BodyDef<T>& def);
    BodyId create_body(const TriangleMesh<T>& mesh, const BodyDef<T>& def);
    BodyId create_body(const HeightField<T>& field, const BodyDef<T>& def);
    /// Removes the body and every contact it had; bodies resting on it wake up. The handle
    /// (and every copy of it) becomes stale.
    void destroy_body(BodyId id);
    /// True while the handle refers to a living body.
    bool contains(BodyId id) const {
        return id.index < bodies_.size() && bodies_[id.index].alive_ && bodies_[id.index].generation_ == id.generation;
    }
    /// The body of a handle; a stale or invalid handle is reported (InvalidArgument). The
    /// reference stays valid while the body lives, whatever else is created or destroyed
    /// (bodies are kept in stable storage); it ends with destroy_body(id), restore_snapshot and
    /// the world itself.
    Body<T>& body(BodyId id) { return bodies_[checked(id, "World::body")]; }
    const Body<T>& body(BodyId id) const { return bodies_[checked(id, "World::body")]; }
    /// Moves a body (teleport), waking it and the bodies it touched.
    // Changing a body by ID (world_edit.hpp). Each checks its input first (InvalidArgument, nothing
    // changed), keeps boxes, contacts and islands true, and wakes what the change can move.
    /// Teleports the body (no velocity implied; contacts re-found at the next step).
    void set_transform(BodyId id, const Vec3<T>& position, const Quat<T>& orientation);
    /// Linear (m/s) and angular (rad/s, world) velocity; ignored for static bodies.
    void set_velocity(BodyId id, const Vec3<T>& linear, const Vec3<T>& angular);
    /// A kinematic body's velocities set so that the next step of length dt ends at this pose
    /// (to rounding, within the speed caps); they stay until changed, so call it every step.
    void move_kinematic(BodyId id, const Vec3<T>& position, const Quat<T>& orientation, T dt);
    /// A new shape (or compound); a dynamic body's mass is recomputed from its density, or kept.
    /// Every contact of the body ends (with events); the next step finds the new ones.
    void set_shape(BodyId id, std::shared_ptr<const Shape<T>> shape, MassUpdate mass = MassUpdate::recompute);
    void set_shape(BodyId id, const Shape<T>& shape, MassUpdate mass = MassUpdate::recompute) {
        set_shape(id, std::make_shared<const Shape<T>>(shape), mass);
    }
    void set_shape(BodyId id, std::shared_ptr<const Compound<T>> compound, MassUpdate mass = MassUpdate::recompute);
    void set_shape(BodyId id, const Compound<T>& compound, MassUpdate mass = MassUpdate::recompute) {
        set_shape(id, std::make_shared<const Compound<T>>(compound), mass);
    }
    /// kg/m³ (> 0): a dynamic body's mass becomes density × its shape's; kept for the others.
    void set_density(BodyId id, T density);
    /// static ↔ kinematic ↔ dynamic. Becoming dynamic: mass from the body's density. Static: at rest.
    void set_type(BodyId id, BodyType type);
    /// The layer bits and the mask of layers it collides with (both sides must agree).
    void set_collision_filter(BodyId id, std::uint32_t layer, std::uint32_t mask);
    void set_sensor(BodyId id, bool sensor);
    void set_fast(BodyId id, bool fast);
    /// Out of the simulation (no contacts, no motion, joints inert, not found by queries) without
    /// being destroyed; enabled again where it was.
    void set_enabled(BodyId id, bool enabled);
    /// Wakes the body, or puts its whole island to sleep (dynamic bodies; others are unaffected).
    void set_awake(BodyId id, bool awake);

    std::size_t body_count() const { return bodies_.size() - free_slots_.size(); }
    /// Reserves room for this many bodies and contacts, so growing to them allocates once (the
    /// query tree of static bodies grows as static bodies are created). At most 2^32 − 2 bodies
    /// and 2^30 contacts (InvalidArgument); std::bad_alloc when memory runs out.
    void reserve(std::size_t bodies, std::size_t contacts = 0);
    /// Calls f(BodyId, const Body<T>&) for every living body, in slot order.
    template <class F>
    void for_each_body(F&& f) const {
        for (std::uint32_t i = 0; i < bodies_.size(); ++i)
            if (bodies_[i].alive_) f(BodyId{i, bodies_[i].generation_}, bodies_[i]);
    }
    /// Joins two bodies (see JointDef). Checks at the door: living, distinct bodies, not both
    /// static, finite anchors, a non-zero hinge or slider axis, lower <= upper, max torque or force >= 0.
    JointId create_joint(const JointDef<T>& def);
    /// Removes a joint; its handle becomes stale. Destroying a body removes its joints.
    void destroy_joint(JointId id);
    bool contains(JointId id) const {
        return id.index < joints_.size() && joints_[id.index].alive && joints_[id.index].generation == id.generation;
    }
    /// The joint of a handle; a stale or invalid handle is reported (InvalidArgument).
    const Joint<T>& joint(JointId id) const { return joints_[checked(id, "World::joint")]; }
    /// The current hinge angle (rad) of a hinge joint; another kind of joint is reported
    /// (InvalidArgument), as it has no hinge axis (a ball joint read 0).
    T hinge_angle(JointId id) const {
        const Joint<T>& j = joint(id);
        if (j.type != JointType::hinge)
            detail::report_invalid("World::hinge_angle", "only a hinge has a hinge angle; joint type",
                                   static_cast<double>(j.type));
        return j.hinge_angle(bodies_[j.a.index].orientation_, bodies_[j.b.index].orientation_);
    }
    /// The translation (m) of a slider's anchor on B from its anchor on A, along A's axis; another
    /// kind of joint is reported (InvalidArgument).
    T slider_translation(JointId id) const {
        const Joint<T>& j = joint(id);
        if (j.type != JointType::prismatic)
            detail::report_invalid("World::slider_translation", "only a slider has a translation; joint type",
                                   static_cast<double>(j.type));
        const Body<T>& a = bodies_[j.a.index];
        const Body<T>& b = bodies_[j.b.index];
        return dot(b.world_point(j.local_anchor_b) - a.world_point(j.local_anchor_a), a.world_vector(j.local_axis_a));
    }
    /// Sets a hinge's motor (enable, target speed rad/s, max torque N·m); wakes the bodies.
    void set_hinge_motor(JointId id, bool enable, T speed, T max_torque);
    /// A hinge's or slider's motor: target speed (rad/s or m/s) and max torque (N·m) or force (N).
    void set_joint_motor(JointId id, bool enable, T speed, T max);
    /// A hinge's (rad) or slider's (m) limits, lower <= upper; disabling drops the limit's impulse.
    void set_joint_limits(JointId id, bool enable, T lower, T upper);
    /// The force (N, world) and torque (N·m) the joint applied to body B over the last substep of
    /// the last step (A got the opposite); zero before the first step and while the joint is inert.
    JointReaction<T> joint_reaction(JointId id) const;

    /// Every contact (including speculative ones) after the last step, sorted by body pair.
    const std::vector<Contact<T>>& contacts() const { return contacts_; }
    /// The contacts of one body (touching or speculative: check Contact::touching), in the order of
    /// contacts(), found in time proportional to their number (an index rebuilt with the
    /// contacts). The range is valid until the world next changes; a stale handle is reported.
    ContactRange<T> contacts_of(BodyId id) const {
        const std::uint32_t slot = checked(id, "World::contacts_of");
        if (slot + std::size_t(1) >= contact_start_.size()) return {contacts_.data(), nullptr, nullptr};  // created since
        const std::uint32_t* list = contact_list_.data();
        return {contacts_.data(), list + (slot == 0 ? 0 : contact_start_[slot - 1]), list + contact_start_[slot]};
    }
    const StepStats& last_step_stats() const { return stats_; }
    /// Contact events of the last step (began, persisted, ended), sorted by body pair.
    const std::vector<ContactEvent<T>>& contact_events() const { return events_; }
    /// Called after every step once per event of contact_events(), in that order. The listener
    /// may change the world (create or destroy bodies and joints, teleport, change settings,
    /// restore a snapshot): the events are delivered from a copy, and a handle in a later event
    /// may be stale by then (check contains()). It may replace or clear itself: the call in
    /// progress finishes on the listener it started with (kept alive until it returns), and the
    /// remaining events of the step go to the new listener (none when cleared). It may not step
    /// the world: step() and update() from inside it are rejected (InvalidArgument). Pass {} to
    /// remove it.
    void set_contact_listener(std::function<void(World&, const ContactEvent<T>&)> listener) {
        require_outside_filter("World::set_contact_listener");
        listener_ = listener ? std::make_shared<const Listener>(std::move(listener)) : nullptr;
    }
    // Queries (dynamics/world_query.hpp). They walk the world's query trees, bounding-volume
    // trees of every body's current box (static bodies in one) kept up to date by every change, so
    // a short ray or a small box costs O(log n) whatever the world's size; the exact test is the
    // shape's own. They keep no scratch in the world (each traversal stack is the call's own), so
    // several threads may query between steps (tests/robustness/parallel_test.cpp, run under
    // ThreadSanitizer). A filter
    // (QueryFilter: layer mask, ignore static / sensors / one body, a callback) chooses the
    // bodies; the default sees all. Results do not depend on the tree: equal distances go to the
    // lower slot, lists come in slot order (tested against a scan of every body).

    /// The nearest body the ray hits within its length, if any (every shape type, solid: a ray
    /// starting inside a body hits it at distance 0). The ray is checked and its direction
    /// normalised as Ray says (unit within 1e-3, max_distance > 0; InvalidArgument otherwise), so
    /// distances are metres.
    std::optional<WorldRayHit<T>> raycast(const Ray<T>& ray, const QueryFilter<T>& filter = {}) const;
    /// A body the ray hits, the first one found, not necessarily the nearest: a line-of-sight test
    /// that stops at the first hit.
    std::optional<WorldRayHit<T>> raycast_any(const Ray<T>& ray, const QueryFilter<T>& filter = {}) const;
    /// Every body the ray hits, nearest first.
    std::vector<WorldRayHit<T>> raycast_all(const Ray<T>& ray, const QueryFilter<T>& filter = {}) const;
    /// The bodies whose shape contains the point (surface included). A mesh or heightfield body
    /// has no inside: it is never reported.
    std::vector<BodyId> query_point(const Vec3<T>& point, const QueryFilter<T>& filter = {}) const;
    /// The bodies whose tight bounding box overlaps the box (touching counts). The box must be
    /// finite with min <= max on every axis (InvalidArgument otherwise).
    std::vector<BodyId> query_aabb(const Aabb<T>& box, const QueryFilter<T>& filter = {}) const;
    /// The bodies a sphere overlaps (intersect(): touching is not overlapping). radius within the
    /// size range of T (as a Sphere's).
    std::vector<BodyId> overlap_sphere(const Vec3<T>& center, T radius, const QueryFilter<T>& filter = {}) const;
    /// The bodies a convex shape at a pose overlaps (intersect(): touching is not overlapping).
    std::vector<BodyId> overlap_shape(const Shape<T>& shape, const Transform<T>& pose, const QueryFilter<T>& filter = {}) const;
    /// The first body a shape swept from `pose` along `translation` (m, world) touches: the body
    /// and where (fraction of the translation, normal from the shape to the body, point on the
    /// body); bodies it overlaps at the start come first, with fraction 0. Ties go to the lower slot.
    std::optional<WorldShapeCastHit<T>> shape_cast(const Shape<T>& shape, const Transform<T>& pose, const Vec3<T>& translation,
                                                   const QueryFilter<T>& filter = {}) const;
    /// The same for a compound swept from `pose` (its centre-of-mass frame, as a body's
    /// transform): the first touch of any of its parts.
    std::optional<WorldShapeCastHit<T>> shape_cast(const Compound<T>& compound, const Transform<T>& pose,
                                                   const Vec3<T>& translation, const QueryFilter<T>& filter = {}) const;

    /// A user veto on pairs: called during step() for every pair whose boxes overlap (and that
    /// layers and masks allow); returning false means the two never touch. Pass {} to remove it.
    /// The filter must not change the world: it runs while the step walks the bodies and their
    /// contacts, so every mutating World call made from inside it (create_body, destroy_body,
    /// set_transform, create_joint, destroy_joint, set_hinge_motor, set_settings, set_gravity,
    /// reserve, set_contact_filter, set_contact_listener, step, update, restore_snapshot) is
    /// rejected with InvalidArgument and changes nothing. Reading the world is fine. Body
    /// setters are not checked (they touch no table the step walks) but the filter should not
    /// call them either: decide from the bodies as they are, and change the world after step().
    void set_contact_filter(std::function<bool(BodyId, BodyId)> filter) {
        require_outside_filter("World::set_contact_filter");
        filter_ = std::move(filter);
    }

    /// Advances exactly one step of dt seconds (dt finite and > 0, else InvalidArgument).
    void step(T dt);

    /// Steps on `workers` threads (the caller and workers − 1 of a ThreadPool the world owns); 1,
    /// the default, steps on the caller alone. Any count gives the same bits (docs/parallel.md).
    /// InvalidArgument unless 1 <= workers <= ThreadPool::max_workers.
    void set_workers(unsigned workers) {
        require_outside_callbacks("World::set_workers");
        if (workers < 1 || workers > ThreadPool::max_workers)
            detail::report_invalid("World::set_workers", "workers must be between 1 and 256", static_cast<double>(workers));
        tasks_.own(workers);
    }
    /// Steps through the game's own job system (not owned; it must outlive its use, or be
    /// replaced first). nullptr steps on the caller alone. Drops a pool from set_workers.
    void set_task_system(TaskSystem* tasks) {
        require_outside_callbacks("World::set_task_system");
        tasks_.use(tasks);
    }
    /// Threads a step may use: 1 without a task system.
    unsigned workers() const { return tasks_.get() != nullptr ? tasks_.get()->workers() : 1u; }
    /// Advances by `seconds` of real time in fixed steps of settings().fixed_time_step, at most
    /// max_steps_per_update per call (time beyond is dropped so a slow frame cannot snowball).
    /// Returns the number of steps taken.
    int update(T seconds);
    /// Fraction (0 … 1) of a step left in the accumulator after update(): render at
    /// interpolated_transform() to hide the fixed step. It is the accumulator in steps, so it
    /// exceeds 1 while steps are owed: after a listener threw out of update(), or after
    /// set_settings made fixed_time_step smaller (the next update() steps them, up to
    /// max_steps_per_update); interpolated_transform clamps it. At most max_steps_per_update + 1:
    /// the next update() drops what is owed beyond (a fixed step set to the smallest subnormal
    /// made the quotient inf).
    T interpolation_factor() const {
        return std::min(accumulator_ / settings_.fixed_time_step, static_cast<T>(settings_.max_steps_per_update) + T(1));
    }
    /// The body's pose blended between the last two steps by interpolation_factor().
    Transform<T> interpolated_transform(BodyId id) const;

private:
    friend struct SnapshotAccess<T>;
    using Listener = std::function<void(World&, const ContactEvent<T>&)>;
    /// Sets a flag for the lifetime of the object, clearing it on the way out (also by exception).
    struct FlagScope {
        bool& flag;
        explicit FlagScope(bool& f) : flag(f) { flag = true; }
        ~FlagScope() { flag = false; }
        FlagScope(const FlagScope&) = delete;
        FlagScope& operator=(const FlagScope&) = delete;
    };
    /// The door of every mutating call: rejected while the contact filter runs, or a query
    /// filter's `accept` on this thread.
    void require_outside_filter(const char* where) const {
        if (callbacks_.in_filter)
            detail::report_invalid(std::string("xeno: ") + where +
                                   ": the world may not be changed from inside the contact filter (change it after step())");
        if (accepting_world() == this)
            detail::report_invalid(
                std::string("xeno: ") + where +
                ": the world may not be changed from inside a query filter's accept (change it after the query)");
    }
    /// The world whose query filter's `accept` runs on this thread, if any. Per thread, as queries
    /// may run on several at once (docs/parallel.md). A query walks the world's trees and bodies
    /// around the callback: an accept that destroyed the body it was shown crashed raycast_all.
    static const World*& accepting_world() {
        static thread_local const World* world = nullptr;
        return world;
    }
    struct AcceptScope {
        const World* outer;
        explicit AcceptScope(const World* world) : outer(accepting_world()) { accepting_world() = world; }
        ~AcceptScope() { accepting_world() = outer; }
        AcceptScope(const AcceptScope&) = delete;
        AcceptScope& operator=(const AcceptScope&) = delete;
    };
    /// step() and update(): rejected inside the filter and inside the contact listener.
    void require_outside_callbacks(const char* where) const {
        require_outside_filter(where);
        if (callbacks_.in_listener)
            detail::report_invalid(std::string("xeno: ") + where +
                                   ": the world may not be stepped from inside the contact listener (step after it returns)");
    }
    /// The user filter's verdict on a pair (true without a filter), with mutations locked out.
    bool filter_allows(std::uint32_t a, std::uint32_t b) {
        if (!filter_) return true;
        const FlagScope scope(callbacks_.in_filter);
        return filter_(id_of(a), id_of(b));
    }
    std::uint32_t checked(BodyId id, const char* where) const {
        if (!id.valid()) detail::report_invalid(where, "invalid body handle (default-constructed BodyId), index", -1.0);
        if (!contains(id))
            detail::report_invalid(where, "stale body handle: that body was destroyed; index", static_cast<double>(id.index));
        return id.index;
    }
    std::uint32_t checked(JointId id, const char* where) const {
        if (!id.valid()) detail::report_invalid(where, "invalid joint handle (default-constructed JointId), index", -1.0);
        if (!contains(id))
            detail::report_invalid(where, "stale joint handle: that joint was destroyed; index", static_cast<double>(id.index));
        return id.index;
    }
    static std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
        return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
    }
    void rebuild_joint_pairs();
    Joint<T> make_joint(const JointDef<T>& def, const Body<T>& a, const Body<T>& b, const char* where);
    void set_axis_limit_motor(Joint<T>& j, const JointDef<T>& def, const Body<T>& a, const Body<T>& b, const char* where);
    static void check_limits(JointType type, T lower, T upper, const char* where);
    static MassProperties<T> unit_mass(const Shape<T>* shape, const Compound<T>* compound) {
        return shape ? mass_properties(*shape, T(1)) : compound->unit_mass_properties();
    }
    static MassProperties<T> dynamic_mass(const Shape<T>* shape, const Compound<T>* compound, T density, T mass,
                                          const char* where);
    BodyId create_body_impl(std::shared_ptr<const Shape<T>> shape, std::shared_ptr<const Compound<T>> compound,
                            const BodyDef<T>& def, std::shared_ptr<const MeshShape<T>> mesh = nullptr);
    /// The contacts of one pair into `next`, matched to last step's contacts_[old_begin, old_end).
    void collide_pair(const ProxyPair& pair, T margin, T dt, std::size_t old_begin, std::size_t old_end,
                      std::vector<Contact<T>>& next);
    /// What collide_parts did: the parts are apart, or their manifold was made or re-measured.
    enum class PartsContact : std::uint8_t { apart, made, reused };
    PartsContact collide_parts(const ProxyPair& pair, std::uint32_t ca, std::uint32_t cb, T margin, T dt, const Contact<T>* had,
                               Contact<T>& out) const;
    bool reuse_contact(const ProxyPair& pair, T margin, T dt, const Contact<T>& had, Contact<T>& out) const;
    /// How a contact stands to its moving body's path this step (World::path_of).
    struct PathContact {
        enum Kind : std::uint8_t { none, turns, beside } kind = none;  ///< none: no row, or not a static pair
        T distance{};       ///< m: how far the body moves before the contact turns it (0: now)
        Vec3<T> normal{};   ///< unit, world: the static surface's normal there, towards the body
        Vec3<T> surface{};  ///< m, world: a point of that surface
    };
    PathContact path_of(std::uint32_t m, T dt) const;
    bool drop_out_of_reach(T dt);
    bool out_of_reach(std::uint32_t m) const;
    bool jointed(std::uint32_t slot) const;
    /// A mesh pair's manifolds (mesh_collide.hpp), each with the convex side's part.
    struct MeshManifolds {
        std::vector<MeshContact<T>> contacts;
        std::vector<std::uint32_t> parts;
    };
    void mesh_manifolds(const ProxyPair& pair, T margin, T dt, MeshManifolds& out) const;
    SpeculativeSweep<T> speculative_sweep(const Body<T>& a, std::uint32_t ca, const Body<T>& b, std::uint32_t cb, T dt,
                                          bool any_speed = false) const;
    T turning_radius(const Body<T>& body, std::uint32_t child) const;
    /// The contacts of a pair with a mesh side from its manifolds, matched to last step's by the
    /// convex part and the normal.
    void merge_mesh_pair(const ProxyPair& pair, T margin, std::size_t old_begin, std::size_t old_end, const MeshManifolds& fresh,
                         std::vector<Contact<T>>& next);
    /// A ball's speculative manifold made where the parts first touch (see the definition), or `now`.
    ContactManifold<T> at_first_touch(const Body<T>& a, std::uint32_t ca, const Transform<T>& pose_a, const Body<T>& b,
                                      std::uint32_t cb, const Transform<T>& pose_b, const ContactManifold<T>& now, T margin,
                                      T dt) const;
    /// `out` from a fresh manifold of parts ca and cb, its points matched to `had` (or nullptr).
    void make_contact(const ProxyPair& pair, std::uint32_t ca, std::uint32_t cb, T margin, const Contact<T>* had,
                      const ContactManifold<T>& fresh, Contact<T>& out) const;
    /// How far apart a pair's contacts may begin: the speculative distance plus what the two can
    /// travel in the step.
    T pair_margin(const Body<T>& a, const Body<T>& b, T dt) const {
        return settings_.speculative_distance + (travel_speed(a, dt) + travel_speed(b, dt)) * dt;
    }
    /// dropped: not wanted; apart: rejected by the early-out (its contacts end); kept: both asleep;
    /// remeasured: a mesh pair that barely moved (its contacts re-measured into remeasured_).
    enum class PairKind : std::uint8_t { dropped, apart, kept, collided, parts, mesh, remeasured };
    /// Where the merge takes a run of contacts from (narrow_phase): last step's list, the mesh
    /// pairs' re-measured contacts, the workers' contacts of collided pairs, or the contacts of
    /// compound and mesh pairs made during the merge.
    enum class ContactSource : std::uint8_t { last_step, remeasured, job, side };
    const std::vector<Contact<T>>& contact_source(ContactSource from) const {
        switch (from) {
            case ContactSource::last_step: return contacts_;
            case ContactSource::remeasured: return remeasured_;
            case ContactSource::job: return job_contacts_;
            case ContactSource::side: break;
        }
        return side_contacts_;
    }
    /// Contacts source[begin, begin + count) go to next_contacts_[to …]; `kept`: a sleeping
    /// pair's, whose was_touching is set from touching.
    struct PlacedRun {
        ContactSource from;
        bool kept;
        std::uint32_t begin, count, to;
    };
    void copy_placed_runs(std::uint32_t count);
    bool remeasure_mesh_pair(const ProxyPair& pair, T margin, T dt, std::size_t old_begin, std::size_t old_end);
    /// The mesh narrow phase's three parts, bound by the first mesh body (see joint_stage_).
    struct MeshStage {
        bool (World::*remeasure)(const ProxyPair&, T, T, std::size_t, std::size_t) = nullptr;
        void (World::*manifolds)(const ProxyPair&, T, T, MeshManifolds&) const = nullptr;
        void (World::*merge)(const ProxyPair&, T, std::size_t, std::size_t, const MeshManifolds&,
                             std::vector<Contact<T>>&) = nullptr;
    };
    void bind_mesh_pairs() { mesh_stage_ = {&World::remeasure_mesh_pair, &World::mesh_manifolds, &World::merge_mesh_pair}; }
    /// B's centre of mass in A's body frame, and B's orientation relative to A's: the pose a
    /// contact's manifold is made at (Contact::made_offset, made_turn).
    static Vec3<T> offset_in_a(const Body<T>& a, const Body<T>& b) {
        return inverse_rotate(a.orientation(), b.position() - a.position());
    }
    static Quat<T> turn_from_a(const Body<T>& a, const Body<T>& b) { return conjugate(a.orientation()) * b.orientation(); }
    void reject_apart_pairs(T dt);
    /// What the narrow phase does with a broad-phase pair, and its contacts of last step.
    struct PairWork {
        std::uint32_t old_begin, old_end;  ///< in contacts_
        std::uint32_t remeasured_begin;    ///< kind remeasured: its contacts in remeasured_, from here
        PairKind kind;
    };
    void prepare_joints(T h);
    void turn_joint_inertias(T h);
    // Joints and mesh pairs are stages a world binds when it first needs them: the step reaches
    // them through the member pointers joint_stage_ and mesh_stage_, which the first create_joint
    // (or a snapshot holding joints) and the first mesh or heightfield body set. A program that
    // never makes either never instantiates their code: 17 % of a stepping World's object code and
    // 8-14 % of its -O2 compile (docs/benchmarks.md, "Paying for joints and meshes only when they
    // are used").
    enum class JointStage : std::uint8_t { prepare, turn_inertias, warm_start, solve, relax, cap };
    void run_joint_stage(JointStage stage, T h);
    void bind_joints() { joint_stage_ = &World::run_joint_stage; }
    void joint_stage(JointStage stage, T h) {
        if (joint_stage_) (this->*joint_stage_)(stage, h);
    }
    BodyId id_of(std::uint32_t slot) const { return {slot, bodies_[slot].generation_}; }
    /// A living, enabled, awake dynamic body: one whose sleep clock runs (update_sleep).
    static bool awake_dynamic(const Body<T>& b) { return b.alive_ && b.enabled_ && b.type_ == BodyType::dynamic && b.awake_; }
    /// An awake dynamic body, or a kinematic body with a velocity: something that can push.
    static bool active(const Body<T>& b) {
        if (!b.enabled_) return false;
        if (b.type_ == BodyType::dynamic) return b.awake_;
        return b.type_ == BodyType::kinematic &&
               (length_squared(b.linear_velocity_) > T(0) || length_squared(b.angular_velocity_) > T(0));
    }
    /// A joint acts while it lives and both its bodies are enabled (set_enabled).
    bool joint_active(const Joint<T>& j) const { return j.alive && bodies_[j.a.index].enabled_ && bodies_[j.b.index].enabled_; }
    /// The speed cap of the integrator: the settings' for most bodies, detail::max_fast_speed for
    /// fast ones (1e6 m/s in float, 1e10 in double).
    T speed_limit(const Body<T>& b) const { return b.fast_ ? detail::max_fast_speed<T>() : settings_.max_linear_speed; }
    detail::SpinCap<T> spin_cap(const Body<T>& b, T dt) const;
    /// m/s²: what gravity and the applied force do to b's velocity (zero unless dynamic and awake).
    Vec3<T> free_acceleration(const Body<T>& b) const {
        if (b.type_ != BodyType::dynamic || !b.awake_) return Vec3<T>::zero();
        return settings_.gravity * b.gravity_scale_ + b.force_ * b.inverse_mass_;
    }
    /// How fast the body can travel this step (its speed within the cap; a velocity whose length
    /// overflows is capped like any other), for boxes and margins that must stay finite.
    /// The fastest b can move over a step of dt: its speed plus what gravity and its force add
    /// (without them, a ball at rest 3 cm over a floor under g = 1000, or under g at dt = 0.2 s,
    /// fell more than the contact margin in its first step and through the floor).
    T travel_speed(const Body<T>& b, T dt) const {
        return std::min(length(b.linear_velocity_) + length(free_acceleration(b)) * dt, speed_limit(b));
    }
    detail::BodyIntegration<T> integration_constants(const Body<T>& b, const detail::SolverMass<T>& s, T h) const;
    void keep_poses_and_update_bounds(T dt);
    void scale_lighter_impulses();
    void narrow_phase(T dt);
    void classify_pairs(T dt);
    void collide_on_workers(T dt);
    void merge_contacts(T dt);
    void wake_touched_islands(T dt);
    void measure_group_speeds();
    bool closes_within_step(const Contact<T>& c, T dt, T struck_speed) const;
    bool within_slop(const Contact<T>& c) const;
    bool separating(const Contact<T>& c, T speed) const;
    void prepare(T dt);
    void solve_substep(int sub, T h, detail::SolvePass<T>& pass);
    void prepare_solver_bodies(T h);
    void prepare_contact_rows(T h);
    void contact_row(std::uint32_t m, const detail::Softness<T>& soft, const detail::Softness<T>& soft_static, T step,
                     detail::ContactConstraint<T>& c);
    static T twist_lever(Contact<T>& contact, T face_a, T face_b);
    void share_support_stiffness(T static_hertz, T h);
    /// Fewest items a worker is handed per stage (task_system.hpp): about a few µs of work each.
    static constexpr std::uint32_t bounds_range = 256, row_range = 64, integrate_range = 256, finish_range = 256;
    static constexpr std::uint32_t copy_range = 256;      ///< runs of contacts copied into place (narrow phase)
    static constexpr std::uint32_t early_out_range = 64;  ///< groups of W pairs given MPR's first test (narrow phase)
    void order_solver_bodies_in_space();
    void solve(T dt);
    void thin_crowded_pairs();
    void build_islands();
    std::uint32_t island_root(std::uint32_t slot) { return union_root(island_parent_, slot); }
    static std::uint32_t union_root(std::vector<std::uint32_t>& parent, std::uint32_t slot);
    void finish();
    void discard_overflowed_solve();
    void update_sleep(T dt);
    void run_sleep_clocks(T dt);
    /// An island's least clock has run its sleep_time (a clock of 0 has not started: with a
    /// sleep_time of 0 every island slept at once, thrown bodies in mid-air included).
    bool clock_done(T clock) const { return clock > T(0) && clock >= settings_.sleep_time; }
    /// The substeps a step is solved in: the setting in soft-step mode, one in baumgarte mode.
    T substeps_per_step() const { return static_cast<T>(settings_.solver == SolverMode::soft_step ? settings_.substeps : 1); }
    void keep_moving_islands_awake();
    void keep_drifting_islands_awake();
    T motor_axis_speed(const Joint<T>& j, const Vec3<T>& axis) const;
    bool motor_turning(const Joint<T>& j, T start_speed) const;
    bool sliding(const Contact<T>& c) const;
    void update_query_tree();
    void rebuild_query_tree();
    /// A tree grown by edits queries several times slower than a built one (measured 5x at
    /// 10,000 bodies): rebuilt once the edits since its last build reach half its size, which
    /// costs O(log n) per edit amortised. Never allocates: reserve() made the room.
    void refresh_query_tree() {
        for (AabbTree<T>& tree : query_trees_)
            if (due_for_rebuild(tree)) tree.rebuild();
    }
    /// Whether the tree is rebuilt once `coming` more of its leaves have moved.
    static bool due_for_rebuild(const AabbTree<T>& tree, std::size_t coming = 0) {
        return 2 * (tree.edits_since_build() + coming) >= tree.size();
    }
    AabbTree<T>& query_tree_for(BodyType type) { return query_trees_[type == BodyType::static_body ? 0 : 1]; }
    AabbTree<T>& query_tree_of(std::uint32_t slot) { return query_tree_for(bodies_[slot].type_); }
    void report_events();
    std::size_t collect_events();
    void sort_events(std::size_t recorded);
    bool makes_event(const Contact<T>& c) const;
    ContactEvent<T> event_of(const Contact<T>& c) const;
    /// Contacts a block of the parallel event collection holds (its blocks are fixed, so the
    /// events land in the same places however the blocks are handed out).
    static constexpr std::uint32_t event_block = 256;
    // Query helpers (world_query.hpp).
    bool seen_by(const QueryFilter<T>& filter, std::uint32_t slot) const {
        if (!filter.accept) return filter.passes(id_of(slot), bodies_[slot]);
        const AcceptScope scope(this);
        return filter.passes(id_of(slot), bodies_[slot]);
    }
    std::optional<RayHit<T>> nearest_hit(std::uint32_t slot, const Ray<T>& ray) const;
    template <class Exact>
    std::vector<BodyId> overlapping(const Aabb<T>& box, const QueryFilter<T>& filter, Exact&& exact) const;
    void wake_neighbours_of(std::uint32_t slot);
    void end_contacts_of(std::uint32_t slot);
    void set_shape_impl(std::uint32_t slot, std::shared_ptr<const Shape<T>> shape, std::shared_ptr<const Compound<T>> compound,
                        MassUpdate mass, const char* where);
    void wake_overlapping(std::uint32_t slot);
    void place_in_broad_phase(std::uint32_t slot);
    static void require_centred(const Shape<T>& shape, const char* where);
    void index_contacts(std::size_t slots);
    bool seam_ghost(const Contact<T>& contact) const;
    Vec3<T> highest_point(std::uint32_t slot, const Vec3<T>& d, std::uint32_t near) const;
    void end_contact(const Contact<T>& c) {
        if (c.touching)
            events_pending_.push_back(
                {ContactEventKind::ended, c.a, c.b, c.sensor, c.manifold.normal, 0, {}, T(0), c.child_a, c.child_b});
    }

    /// Which of this world's callbacks is running. That belongs to the running call, not to the
    /// world's state: a copy starts outside every callback and an assigned-to world keeps its own
    /// (a copy made inside the filter was locked for good; a world assigned to inside the listener
    /// could step from it). Assigning to a world from inside its contact filter is rejected
    /// before any member changes, the step walking its tables (it read freed memory): the first
    /// member, so its assignment runs first. (From a move assignment, noexcept, the report ends
    /// the program.)
    struct CallbackState {
        bool in_filter = false;    ///< the contact filter is running: mutating calls are rejected
        bool in_listener = false;  ///< the contact listener is running: step() and update() are rejected
        CallbackState() = default;
        CallbackState(const CallbackState&) noexcept {}
        CallbackState& operator=(const CallbackState&) {
            if (in_filter)
                detail::report_invalid(
                    "xeno: World::operator=: the world may not be changed from inside the contact filter (change it after "
                    "step())");
            return *this;
        }
        ~CallbackState() = default;
    };
    CallbackState callbacks_;
    WorldSettings<T> settings_;
    std::deque<Body<T>> bodies_;  ///< a deque: references stay valid as it grows
    std::vector<std::uint32_t> free_slots_;
    std::vector<Aabb<T>> bounds_;  ///< per slot; empty for free slots
    // Per slot: bounds_ (and the early-out bound) were placed while the body slept, with the
    // speculative distance bounds_margin_. Asleep and not moved, it would get the same box again.
    std::vector<std::uint8_t> bounds_asleep_;
    /// By slot: a static or kinematic body changed since the last step (moved_), whose touching
    /// bodies keep_poses_and_update_bounds wakes. Zero between steps.
    std::vector<std::uint8_t> retouched_;
    T bounds_margin_ = T(-1);
    std::vector<Transform<T>> previous_pose_;  ///< per slot: pose before the last step
    SweepAndPrune<T> sweep_;
    AabbTree<T> tree_;
    /// Each living body's current world box (tight; the tree fattens it), for queries: [0] static
    /// bodies, [1] the others. Apart, as Box2D v3 keeps them: a level's large static boxes among
    /// small moving ones made rays at 100,000 bodies twice as slow (world_query.hpp).
    AabbTree<T> query_trees_[2];
    std::vector<ProxyPair> pairs_;
    std::vector<Contact<T>> contacts_;                  ///< sorted by (a.index, b.index)
    std::vector<detail::SolverBody<T>> solver_bodies_;  ///< slot 0: static stand-in
    std::vector<detail::SolverMass<T>> solver_masses_;  ///< per solver body
    std::vector<std::uint32_t> solver_index_;           ///< per slot: index into solver_bodies_ (0: none)
    std::vector<std::uint32_t> solver_slot_;            ///< per solver body: its slot
    std::vector<std::uint32_t> solver_order_;           ///< prepare: the slots of the solver bodies, in order
    std::vector<std::uint32_t> solver_cells_;           ///< prepare, several workers: bodies per cell along the axis, then starts
    std::vector<std::uint32_t> solver_sorted_;          ///< prepare, several workers: solver_order_ by cell
                                                        ///< as pairs so comparisons do not read the bodies' deque
    std::vector<detail::BodyIntegration<T>> integration_;  ///< per solver body: the step's constants
    std::vector<detail::ContactConstraint<T>> constraints_;
    detail::WideContactRows<T> wide_rows_;  ///< constraints_ coloured and packed in SIMD lanes
    std::vector<Joint<T>> joints_;
    std::vector<std::uint32_t> free_joints_;
    std::vector<detail::JointConstraint<T>> joint_rows_;
    void (World::*joint_stage_)(JointStage, T) = nullptr;  ///< run_joint_stage once a joint was made
    std::vector<std::uint64_t> unconnected_pairs_;         ///< sorted keys of jointed pairs that do not collide
    StepStats stats_;
    std::vector<ContactEvent<T>> events_, events_pending_;
    std::vector<std::uint32_t> event_block_start_;  ///< scratch: where each block's events begin (collect_events)
    std::vector<ContactEvent<T>> merged_events_;    ///< scratch: the events with the recorded ones merged in (sort_events)
    std::vector<std::uint8_t> leaves_fat_box_;      ///< scratch: 1 = leaves its query leaf's box (update_query_tree)
    std::shared_ptr<const Listener> listener_;      ///< shared: a running listener outlives its replacement
    std::function<bool(BodyId, BodyId)> filter_;
    T accumulator_{};
    T last_substep_{};      ///< s: the last step's substep, for joint_reaction
    T fastest_approach_{};  ///< m/s: the step's fastest approach of a contact point (prepare), for the impact sweeps
    // Scratch kept between steps so a settled step allocates nothing.
    std::vector<Contact<T>> next_contacts_;  ///< narrow phase output, swapped with contacts_
    std::vector<PairWork> pair_work_;        ///< per broad-phase pair (narrow phase)
    EarlyOut<T> early_out_;                  ///< each convex body's rounded box in the world (keep_poses_and_update_bounds)
    std::vector<std::uint32_t> early_jobs_;  ///< pairs of kind collided, for the early-out
    MeshStage mesh_stage_;                   ///< set by the first mesh body (bind_mesh_pairs)
    MeshManifolds mesh_manifolds_;           ///< one worker: a mesh pair's manifolds (narrow phase)
    std::vector<std::uint32_t> mesh_jobs_;   ///< several workers: the pairs of kind mesh, in pair order
    std::vector<MeshManifolds> mesh_job_manifolds_;  ///< several workers: the manifolds of each of mesh_jobs_
    std::vector<std::uint8_t> old_taken_;            ///< last step's contacts of a mesh pair already matched (pass 3)
    std::vector<std::uint32_t> vetoed_bodies_;       ///< merge: the bodies of pairs the filter now vetoes, to wake
    std::vector<PathContact> path_;                  ///< per contact: path_of (drop_out_of_reach)
    std::vector<std::uint8_t> dropped_;              ///< per contact: 1 = out of reach (drop_out_of_reach)
    std::vector<std::uint32_t> row_contacts_;        ///< per contact row: its contact (prepare)
    std::vector<std::uint32_t> bouncing_rows_;       ///< the rows with a restitution, in row order (prepare)
    detail::ReboundEnergyCap<T> rebound_cap_;        ///< solve: a bounce gives back no more than it took
    std::vector<std::uint32_t> collide_jobs_;        ///< several workers: the pairs of kind collided, in pair order
    std::vector<Contact<T>> job_contacts_;           ///< several workers: the contact of each of collide_jobs_
    std::vector<Contact<T>> side_contacts_;          ///< several workers: compound and mesh pairs' contacts (merge)
    std::vector<PlacedRun> placed_runs_;             ///< several workers: where the merge puts each run of contacts
    std::vector<PartsContact> job_results_;          ///< several workers: what collide_parts did for each of collide_jobs_
    std::vector<Contact<T>> remeasured_;             ///< the re-measured contacts of mesh pairs, in pair order
    std::vector<std::uint32_t> contact_start_;       ///< per slot: the end of its run in contact_list_ (index_contacts)
    std::vector<std::uint32_t> contact_list_;        ///< contact indices grouped by body slot
    std::vector<std::uint32_t> island_parent_;       ///< union–find parents per slot (wake, sleep)
    std::vector<std::uint32_t> drift_parent_;        ///< union–find parents per slot: bodies that hold each other (sleep)
    std::vector<std::uint8_t> island_flag_;          ///< per island root: wake it, or (falling asleep) held
    std::vector<T> island_sleep_time_;               ///< per island root: the least sleep clock (first: group speeds)
    std::vector<std::uint32_t> pair_degree_;         ///< per slot: broad-phase pairs (crowd thinning)
    std::vector<std::uint64_t> crowd_histogram_;     ///< pairs by crowd size (crowd thinning)
    std::vector<ContactEvent<T>> delivered_events_;  ///< the listener's copy of events_
    // Per solver body, for share_support_stiffness: where its rows on static or kinematic bodies
    // start in support_rows_, how many manifolds hold it there, and its share of the frequency.
    std::vector<std::uint32_t> support_begin_, support_fill_, support_manifolds_;
    std::vector<detail::SupportRow<T>> support_rows_;
    std::vector<T> support_share_;
    detail::WorldTasks tasks_;  ///< where a step's parallel stages run (set_workers, set_task_system)
};

template <class T>
World<T>::World(const World&) = default;
template <class T>
World<T>::World(World&&) = default;
template <class T>
World<T>& World<T>::operator=(const World&) = default;
template <class T>
World<T>& World<T>::operator=(World&&) noexcept = default;
template <class T>
World<T>::~World() = default;

// The copying overloads of create_body live out of the class for the same reason: compiled mode
// compiles their make_shared (control block, deleter, the shape variant's copy) once.
template <class T>
BodyId World<T>::create_body(const Shape<T>& shape, const BodyDef<T>& def) {
    return create_body(std::make_shared<const Shape<T>>(shape), def);
}

template <class T>
BodyId World<T>::create_body(const Compound<T>& compound, const BodyDef<T>& def) {
    return create_body(std::make_shared<const Compound<T>>(compound), def);
}

template <class T>
BodyId World<T>::create_body(const TriangleMesh<T>& mesh, const BodyDef<T>& def) {
    return create_body(std::make_shared<const MeshShape<T>>(mesh), def);
}

template <class T>
BodyId World<T>::create_body(const HeightField<T>& field, const BodyDef<T>& def) {
    return create_body(std::make_shared<const MeshShape<T>>(field), def);
}

namespace detail {

// A shape's own constructor checks it, but a moved-from mesh, compound or hull is a valid object
// with nothing in it: a moved-from mesh crashed create_body (its bounds read an empty tree), and
// an empty compound or hull was accepted and left a world whose own snapshot did not restore.
// (The convex shape's check, detail::require_moved_in(Shape), is in shape.hpp.)
template <class T>
void require_moved_in(const Compound<T>& compound, const char* where) {
    if (compound.children().empty()) report_invalid(where, "a compound needs a part (a moved-from compound?); parts", 0.0);
    for (const CompoundChild<T>& child : compound.children()) require_moved_in(child.shape, where);
}
template <class T>
void require_moved_in(const MeshShape<T>& mesh, const char* where) {
    const bool empty = std::visit(
        [](const auto& m) {
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, HeightField<T>>) return m.empty();
            else return m.vertices().empty() || m.size() == 0;
        },
        mesh);
    if (empty) report_invalid(where, "a mesh or heightfield needs its triangles (a moved-from one?); triangles", 0.0);
}

}  // namespace detail

template <class T>
BodyId World<T>::create_body(std::shared_ptr<const Shape<T>> shape, const BodyDef<T>& def) {
    require_outside_filter("World::create_body");
    if (!shape) detail::report_invalid("World::create_body", "shape must not be null", 0.0);
    detail::require_moved_in(*shape, "World::create_body");
    return create_body_impl(std::move(shape), nullptr, def);
}

template <class T>
BodyId World<T>::create_body(std::shared_ptr<const Compound<T>> compound, const BodyDef<T>& def) {
    require_outside_filter("World::create_body");
    if (!compound) detail::report_invalid("World::create_body", "compound must not be null", 0.0);
    detail::require_moved_in(*compound, "World::create_body");
    return create_body_impl(nullptr, std::move(compound), def);
}

template <class T>
BodyId World<T>::create_body(std::shared_ptr<const MeshShape<T>> mesh, const BodyDef<T>& def) {
    require_outside_filter("World::create_body");
    if (!mesh) detail::report_invalid("World::create_body", "mesh must not be null", 0.0);
    detail::require_moved_in(*mesh, "World::create_body");
    const BodyId id = create_body_impl(nullptr, nullptr, def, std::move(mesh));
    bind_mesh_pairs();
    return id;
}

template <class T>
BodyId World<T>::create_body_impl(std::shared_ptr<const Shape<T>> shape, std::shared_ptr<const Compound<T>> compound,
                                  const BodyDef<T>& def, std::shared_ptr<const MeshShape<T>> mesh) {
    const char* where = "World::create_body";
    if (mesh && def.type == BodyType::dynamic)
        detail::report_invalid(where,
                               "a mesh or heightfield body must be static or kinematic (it has no volume to weigh); triangles",
                               static_cast<double>(triangle_count(*mesh)));
    detail::require_finite_xyz(def.position, where, "position");
    detail::require_orientation(def.orientation, where, "orientation");
    detail::require_finite_xyz(def.linear_velocity, where, "linear_velocity");
    detail::require_finite_xyz(def.angular_velocity, where, "angular_velocity");
    detail::validate(def.material, where);
    detail::require_non_negative(def.linear_damping, where, "linear_damping");
    detail::require_non_negative(def.angular_damping, where, "angular_damping");
    detail::require_at_most(def.gravity_scale, ScalarTraits<T>::max_size, where, "gravity_scale");
    if (shape) require_centred(*shape, where);

    // Every check comes before the first change: a rejected body leaves the world as it was.
    if (def.type != BodyType::static_body && def.type != BodyType::kinematic && def.type != BodyType::dynamic)
        detail::report_invalid(where, "type must be static_body, kinematic or dynamic; type",
                               static_cast<double>(static_cast<std::uint8_t>(def.type)));

    // Mass properties before a slot is taken, so a rejected body leaves no trace.
    MassProperties<T> mass;
    if (def.type == BodyType::dynamic) {
        detail::require_non_negative(def.mass, where, "mass");
        detail::require_positive(def.density, where, "density");
        mass = dynamic_mass(shape.get(), compound.get(), def.density, def.mass, where);
    } else if (std::isnan(def.density)) {  // kept for set_type, which checks it; a snapshot must hold a number
        detail::report_invalid(where, "density must be a number (kept for when the body becomes dynamic)",
                               static_cast<double>(def.density));
    }
    if (free_slots_.empty()) {  // grow the tables first, so an allocation failure changes nothing
        const auto make_room = [](auto& table) {
            if (table.size() == table.capacity()) table.reserve(std::max<std::size_t>(8, 2 * table.size()));
        };
        make_room(bounds_), make_room(previous_pose_), make_room(solver_index_);
    }
    // The insert below cannot fail half-way. Only the tree of the body's type: room for every body
    // in both trees cost 132 bytes a body (float) that a world of moving bodies never used.
    query_tree_for(def.type).reserve(bodies_.size() + 1);

    std::uint32_t slot;
    if (!free_slots_.empty()) {
        slot = free_slots_.back();
        free_slots_.pop_back();
    } else {
        slot = static_cast<std::uint32_t>(bodies_.size());
        bodies_.emplace_back();  // the only one that may throw (the deque), so it goes first
        bounds_.emplace_back();
        previous_pose_.emplace_back();
        solver_index_.push_back(0);
    }
    Body<T>& b = bodies_[slot];
    const std::uint32_t generation = b.generation_;
    b = Body<T>{};
    b.generation_ = generation;
    b.alive_ = true;
    b.set_geometry(std::move(shape), std::move(compound), std::move(mesh));
    b.type_ = def.type;
    b.position_ = def.position;
    b.orientation_ = normalized(def.orientation);
    b.material_ = def.material;
    b.linear_damping_ = def.linear_damping;
    b.angular_damping_ = def.angular_damping;
    b.gravity_scale_ = def.gravity_scale;
    b.fast_ = def.fast;
    b.sensor_ = def.sensor;
    b.allow_sleep_ = def.allow_sleep;
    b.layer_ = def.layer;
    b.mask_ = def.mask;
    b.user_data_ = def.user_data;
    if (def.type != BodyType::static_body) {
        b.linear_velocity_ = def.linear_velocity;
        b.angular_velocity_ = def.angular_velocity;
    }
    b.density_ = def.density;
    if (def.type == BodyType::dynamic) {
        b.set_mass_properties(mass);
        b.impulse_halvings_ = 0;  // from no mass, but it has no contact or joint yet
        if (def.mass > T(0)) b.density_ = def.mass / unit_mass(b.convex_shape(), b.compound()).mass;
    }
    b.moved_ = true;
    bounds_[slot] = b.world_bounds();
    query_tree_of(slot).insert(slot, bounds_[slot]);
    refresh_query_tree();
    previous_pose_[slot] = b.transform();
    // A static or kinematic body placed over sleepers (a trigger spawned over a settled pile):
    // two inactive bodies are never collided, so without this the overlap was never found. A new
    // dynamic body is awake and finds them itself.
    if (def.type != BodyType::dynamic) wake_overlapping(slot);
    return {slot, b.generation_};
}

/// Mass properties of a dynamic body of this shape (or compound): `mass` > 0 sets the mass (the
/// inertia scaled to it), else density × the shape's. Checked as set_mass_properties checks them,
/// and that they stay within the range of T; reports naming `where` and changes nothing.
template <class T>
MassProperties<T> World<T>::dynamic_mass(const Shape<T>* shape, const Compound<T>* compound, T density, T mass,
                                         const char* where) {
    MassProperties<T> m = unit_mass(shape, compound);
    if (mass <= T(0)) {
        m.mass *= density;
        m.inertia = m.inertia * density;
    } else {
        m.inertia = m.inertia * (mass / m.mass);
        m.mass = mass;
    }
    m.center = Vec3<T>::zero();
    // Density (or mass) times the shape's volume and inertia can leave the range of T.
    if (!(std::isfinite(m.mass) && m.mass > T(0) && is_finite(m.inertia) && m.inertia[0].x > T(0) && m.inertia[1].y > T(0) &&
          m.inertia[2].z > T(0)))
        detail::report_invalid(
            where, "mass and inertia (density or mass times the shape's) must be finite and > 0 in this precision; mass",
            static_cast<double>(m.mass));
    detail::check_mass_properties(m, shape ? bounding_radius(*shape) : compound->bounding_radius(), where);
    return m;
}

template <class T>
void World<T>::reserve(std::size_t bodies, std::size_t contacts) {
    require_outside_filter("World::reserve");
    // Beyond what a BodyId can index or a world can hold, the containers threw std::length_error
    // (reserve(SIZE_MAX)); a count within these and beyond memory is std::bad_alloc, as for any container.
    if (bodies > std::size_t(std::numeric_limits<std::uint32_t>::max() - 1))
        detail::report_invalid("World::reserve", "bodies must be at most 2^32 - 2 (a BodyId's index); bodies",
                               static_cast<double>(bodies));
    if (contacts > std::size_t(detail::SettingsLimits::max_contact_pairs))
        detail::report_invalid("World::reserve", "contacts must be at most 2^30 (max_contact_pairs' limit); contacts",
                               static_cast<double>(contacts));
    bounds_.reserve(bodies);
    query_tree_for(BodyType::dynamic).reserve(bodies);
    previous_pose_.reserve(bodies);
    solver_index_.reserve(bodies);
    contacts_.reserve(contacts);
}

template <class T>
void World<T>::destroy_body(BodyId id) {
    require_outside_filter("World::destroy_body");
    const std::uint32_t slot = checked(id, "World::destroy_body");
    end_contacts_of(slot);
    for (std::uint32_t i = 0; i < joints_.size(); ++i)
        if (joints_[i].alive && (joints_[i].a.index == slot || joints_[i].b.index == slot))
            destroy_joint({i, joints_[i].generation});
    Body<T>& b = bodies_[slot];
    b.alive_ = false;
    b.set_geometry(nullptr, nullptr, nullptr);
    ++b.generation_;
    bounds_[slot] = Aabb<T>{};
    query_tree_of(slot).remove(slot);
    free_slots_.push_back(slot);
}

/// Ends every contact of a body (reported after the next step, as the narrow phase reports
/// them), waking the bodies on the other side: what destroying, disabling or reshaping it does.
template <class T>
void World<T>::end_contacts_of(std::uint32_t slot) {
    wake_neighbours_of(slot);
    contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(),
                                   [&](const Contact<T>& c) {
                                       const bool gone = c.a.index == slot || c.b.index == slot;
                                       if (gone) end_contact(c);
                                       return gone;
                                   }),
                    contacts_.end());
    index_contacts(contact_start_.empty() ? 0 : contact_start_.size() - 1);  // its own size: allocates nothing
}

/// Wakes the bodies a body touches and the ones jointed to it: whatever moves, reshapes or
/// retypes it must reach sleepers resting on it or hanging from it (a bob asleep on a ball joint
/// stayed 1.41 m from its static anchor after the anchor was moved 1 m).
template <class T>
void World<T>::wake_neighbours_of(std::uint32_t slot) {
    for (const Contact<T>& c : contacts_of(id_of(slot))) {
        const BodyId other = c.a.index == slot ? c.b : c.a;
        if (contains(other)) bodies_[other.index].wake();
    }
    for (const Joint<T>& j : joints_)
        if (j.alive && (j.a.index == slot || j.b.index == slot)) bodies_[j.a.index == slot ? j.b.index : j.a.index].wake();
}

template <class T>
Transform<T> World<T>::interpolated_transform(BodyId id) const {
    const std::uint32_t slot = checked(id, "World::interpolated_transform");
    const Body<T>& b = bodies_[slot];
    const T f = clamp(interpolation_factor(), T(0), T(1));
    const Transform<T>& p = previous_pose_[slot];
    return {lerp(p.position, b.position_, f), slerp(p.orientation, b.orientation_, f)};
}

template <class T>
int World<T>::update(T seconds) {
    require_outside_callbacks("World::update");
    detail::require_non_negative(seconds, "World::update", "seconds");
    accumulator_ += seconds;
    // Too far behind, the frames beyond max_steps_per_update are dropped first: trimmed after the
    // loop, a listener that threw left the whole frame (update(1000) left an interpolation factor
    // of 59,994, and the next update(0) ran 8 steps nobody asked for).
    const T most = settings_.fixed_time_step * static_cast<T>(settings_.max_steps_per_update);
    if (accumulator_ >= most + settings_.fixed_time_step)
        accumulator_ = most + std::fmod(accumulator_, settings_.fixed_time_step);
    int steps = 0;
    // The step's time leaves the accumulator before the step: a listener that restores a
    // snapshot replaces the accumulator (subtracting afterwards left it at -dt, and the world's
    // own snapshot was rejected), and one that throws leaves the step counted. The settings are
    // read afresh each time, as a listener may change them.
    while (accumulator_ >= settings_.fixed_time_step && steps < settings_.max_steps_per_update) {
        const T dt = settings_.fixed_time_step;
        accumulator_ -= dt;
        ++steps;
        step(dt);
    }
    if (accumulator_ >= settings_.fixed_time_step)  // dropped: too far behind
        accumulator_ = std::fmod(accumulator_, settings_.fixed_time_step);
    return steps;
}

template <class T>
void World<T>::step(T dt) {
    require_outside_callbacks("World::step");
    detail::require_positive(dt, "World::step", "dt");
    detail::require_at_most(dt, detail::max_time_step<T>(), "World::step", "dt", " s");
    stats_ = {};
    using clock = std::chrono::steady_clock;
    clock::time_point mark = clock::now();
    auto lap = [&](double& seconds) {
        const clock::time_point now = clock::now();
        seconds = std::chrono::duration<double>(now - mark).count();
        mark = now;
    };
    keep_poses_and_update_bounds(dt);
    lap(stats_.seconds.bounds);
    switch (settings_.broad_phase) {
        case BroadPhaseKind::brute_force: brute_force_pairs(bounds_, pairs_); break;
        case BroadPhaseKind::sweep_and_prune: sweep_.find_pairs(bounds_, pairs_, tasks_.get()); break;
        case BroadPhaseKind::aabb_tree: tree_.find_pairs(bounds_, pairs_); break;
    }
    stats_.broad_pairs = pairs_.size();
    thin_crowded_pairs();
    lap(stats_.seconds.broad);
    narrow_phase(dt);
    lap(stats_.seconds.narrow);
    wake_touched_islands(dt);
    lap(stats_.seconds.wake);
    prepare(dt);
    lap(stats_.seconds.prepare);
    solve(dt);
    lap(stats_.seconds.solve);
    finish();
    lap(stats_.seconds.finish);
    update_sleep(dt);
    lap(stats_.seconds.sleep);
    update_query_tree();
    lap(stats_.seconds.queries);
    report_events();
    lap(stats_.seconds.events);
}

namespace f32 {
using World = xeno::World<float>;
using Contact = xeno::Contact<float>;
using ContactEvent = xeno::ContactEvent<float>;
using WorldRayHit = xeno::WorldRayHit<float>;
using WorldShapeCastHit = xeno::WorldShapeCastHit<float>;
}  // namespace f32
namespace f64 {
using World = xeno::World<double>;
using Contact = xeno::Contact<double>;
using ContactEvent = xeno::ContactEvent<double>;
using WorldRayHit = xeno::WorldRayHit<double>;
using WorldShapeCastHit = xeno::WorldShapeCastHit<double>;
}  // namespace f64

}  // namespace xeno

#include "world_broad.hpp"
#include "world_narrow.hpp"
#include "world_events.hpp"
#include "world_sleep.hpp"
#include "world_solve.hpp"
#include "world_edit.hpp"
#include "world_joints.hpp"
#include "world_query.hpp"

namespace xeno {

#ifdef XENO_COMPILED_LIB
// Compiled mode (compiled.hpp): float and double are compiled once, in src/xeno_compiled.cpp.
extern template class World<float>;
extern template class World<double>;
#endif

}  // namespace xeno

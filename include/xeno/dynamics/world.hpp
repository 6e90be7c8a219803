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
    /// The door of every mutating call: rejected while the contact filter runs.
    void require_outside_filter(const char* where) const {
        if (callbacks_.in_filter)
            detail::report_invalid(std::string("xeno: ") + where +
                                   ": the world may not be changed from inside the contact filter (change it after step())");
    }
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
    bool seen_by(const QueryFilter<T>& filter, std::uint32_t slot) const { return filter.passes(id_of(slot), bodies_[slot]); }
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
template <class T>
void require_moved_in(const Shape<T>& shape, const char* where) {
    if (const auto* hull = std::get_if<ConvexPolyhedron<T>>(&shape); hull && hull->vertices().size() < 4)
        report_invalid(where, "a convex hull needs at least 4 vertices (a moved-from hull?); vertices",
                       static_cast<double>(hull->vertices().size()));
}
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

/// Bounds a step's work when more pairs overlap than max_contact_pairs (thousands of bodies
/// spawned at one point: n²/2 pairs, once 39 s and gigabytes for a step). Pairs with a static or
/// kinematic side are always kept (what holds a crowd up; a body has few of them) and use up the
/// budget first. Among pairs of two dynamic bodies, a pair's crowd is the larger pair count of
/// its bodies: pairs of crowd ≤ k are all kept, a pair of crowd c > k with probability k / c,
/// decided by a hash of the two slots (deterministic, the same pairs every step until the crowd
/// thins out). So every crowded body keeps about k partners and the crowd pushes itself apart,
/// while bodies elsewhere keep all of theirs. k is the largest quota whose expected total fits
/// the budget; a hard cap takes care of the rest.
template <class T>
void World<T>::thin_crowded_pairs() {
    const std::uint64_t budget = static_cast<std::uint64_t>(settings_.max_contact_pairs);
    if (pairs_.size() <= budget) return;
    auto both_dynamic = [&](const ProxyPair& p) {
        return bodies_[p.a].type_ == BodyType::dynamic && bodies_[p.b].type_ == BodyType::dynamic;
    };
    std::vector<std::uint32_t>& degree = pair_degree_;
    degree.assign(bodies_.size(), 0u);
    std::uint64_t fixed = 0;  // pairs with a static or kinematic side
    for (const ProxyPair& p : pairs_) {
        if (!both_dynamic(p)) {
            ++fixed;
            continue;
        }
        ++degree[p.a];
        ++degree[p.b];
    }
    const std::uint64_t room = budget > fixed ? budget - fixed : 0;
    if (pairs_.size() - fixed <= room) return;
    auto crowd = [&](const ProxyPair& p) { return std::max(degree[p.a], degree[p.b]); };
    std::vector<std::uint64_t>& histogram = crowd_histogram_;  // pairs of two dynamic bodies by crowd
    histogram.assign(*std::max_element(degree.begin(), degree.end()) + std::size_t(1), 0u);
    for (const ProxyPair& p : pairs_)
        if (both_dynamic(p)) ++histogram[crowd(p)];
    auto expected = [&](std::uint64_t k) {  // pairs kept for quota k (floored per crowd size)
        std::uint64_t sum = 0;
        for (std::uint64_t c = 1; c < histogram.size(); ++c) sum += c <= k ? histogram[c] : histogram[c] * k / c;
        return sum;
    };
    std::uint64_t low = 0, high = histogram.size() - 1;  // expected(low) ≤ room < expected(high)
    while (high - low > 1) {
        const std::uint64_t mid = low + (high - low) / 2;
        (expected(mid) <= room ? low : high) = mid;
    }
    const std::uint64_t quota = low;
    // Pairs of crowd ≤ quota are all kept: they are counted exactly in expected(quota) ≤ room.
    // The hard cap applies to the drawn ones only (a draw may keep more than its expectation),
    // so a pair away from the crowd is never dropped for where it happens to sit in the list.
    std::uint64_t sure = 0;
    for (std::uint64_t c = 1; c <= quota && c < histogram.size(); ++c) sure += histogram[c];
    const std::uint64_t draw_room = room - sure;
    std::uint64_t drawn = 0;
    const auto dropped = std::remove_if(pairs_.begin(), pairs_.end(), [&](const ProxyPair& p) {
        if (!both_dynamic(p)) return false;
        const std::uint64_t c = crowd(p);
        if (c <= quota) return false;
        const bool keep = drawn < draw_room && detail::mix_pair(p.a, p.b) % c < quota;
        drawn += keep ? 1 : 0;
        return !keep;
    });
    stats_.dropped_pairs = static_cast<std::size_t>(pairs_.end() - dropped);
    pairs_.erase(dropped, pairs_.end());
}

// A contact reports an event when it touches or has just stopped touching, except a pair with no
// active body (both asleep, or asleep on a static body): it is not re-collided, its contact is
// unchanged, so "persisted" is not repeated every step.
template <class T>
bool World<T>::makes_event(const Contact<T>& c) const {
    if (!c.touching && !c.was_touching) return false;
    return !(c.touching && c.was_touching && !active(bodies_[c.a.index]) && !active(bodies_[c.b.index]));
}

template <class T>
ContactEvent<T> World<T>::event_of(const Contact<T>& c) const {
    ContactEvent<T> e;
    e.kind = !c.touching ? ContactEventKind::ended : (c.was_touching ? ContactEventKind::persisted : ContactEventKind::began);
    e.a = c.a;
    e.b = c.b;
    e.sensor = c.sensor;
    e.normal = c.manifold.normal;
    e.child_a = c.child_a;
    e.child_b = c.child_b;
    if (c.touching) {
        const Body<T>& a = bodies_[c.a.index];
        const Body<T>& b = bodies_[c.b.index];
        e.count = c.manifold.count;
        for (int i = 0; i < c.manifold.count; ++i) {
            const ContactPoint<T>& p = c.manifold.points[static_cast<std::size_t>(i)];
            e.points[static_cast<std::size_t>(i)] = (a.world_point(p.local_a) + b.world_point(p.local_b)) * T(0.5);
            e.impulse += p.step_impulse;
        }
    }
    return e;
}

// The step's events: the ended events recorded since the last report first, then one per contact
// that makes one, in contact order. On several workers the contacts are cut into fixed blocks,
// each block's events counted and then written into their places in parallel (a 5,050-box
// pyramid makes 15,000 events a step, which took 0.6 ms in float and 1.4 ms in double on one
// thread); the list keeps last step's elements and overwrites them, so only a grown tail is
// cleared first.
template <class T>
std::size_t World<T>::collect_events() {
    const std::size_t recorded = events_pending_.size();
    const std::uint32_t contacts = static_cast<std::uint32_t>(contacts_.size());
    if (workers() <= 1 || contacts < 2 * event_block) {
        events_.swap(events_pending_);
        events_pending_.clear();
        events_.reserve(events_.size() + contacts_.size());
        for (const Contact<T>& c : contacts_)
            if (makes_event(c)) events_.push_back(event_of(c));
        return recorded;
    }
    const std::uint32_t blocks = (contacts + event_block - 1) / event_block;
    const auto block_end = [&](std::uint32_t k) { return std::min(contacts, (k + 1) * event_block); };
    event_block_start_.resize(blocks + std::size_t(1));
    parallel_for(tasks_.get(), blocks, 1u, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t k = begin; k < end; ++k) {
            std::uint32_t count = 0;
            for (std::uint32_t i = k * event_block; i < block_end(k); ++i) count += makes_event(contacts_[i]) ? 1u : 0u;
            event_block_start_[k + 1] = count;
        }
    });
    event_block_start_[0] = static_cast<std::uint32_t>(recorded);
    for (std::uint32_t k = 0; k < blocks; ++k) event_block_start_[k + 1] += event_block_start_[k];
    events_.resize(event_block_start_[blocks]);
    std::copy(events_pending_.begin(), events_pending_.end(), events_.begin());
    events_pending_.clear();
    parallel_for(tasks_.get(), blocks, 1u, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t k = begin; k < end; ++k) {
            std::uint32_t to = event_block_start_[k];
            for (std::uint32_t i = k * event_block; i < block_end(k); ++i)
                if (makes_event(contacts_[i])) events_[to++] = event_of(contacts_[i]);
        }
    });
    return recorded;
}

// The events in pair order. The contacts are in pair order, so their events usually are too, and
// only the ended events recorded between steps (the first `recorded`, few) need a place: they are
// sorted and merged in, O(n), where sorting the whole list took 1 ms a step on the 5,050-box
// pyramid whenever a body had been destroyed. An ended event recorded between steps comes before
// the same pair's event of the step (a slot reused). Only a contact list whose events are not
// strictly increasing (a mesh pair's several contacts) sorts everything, stably: std::sort put a
// reused slot's `began` before the old body's `ended` in any world holding a compound.
template <class T>
void World<T>::sort_events(std::size_t recorded) {
    const auto before = [](const ContactEvent<T>& x, const ContactEvent<T>& y) {
        if (x.a.index != y.a.index) return x.a.index < y.a.index;
        if (x.b.index != y.b.index) return x.b.index < y.b.index;
        return x.child_a != y.child_a ? x.child_a < y.child_a : x.child_b < y.child_b;
    };
    const auto out_of_order = [&](const ContactEvent<T>& x, const ContactEvent<T>& y) { return !before(x, y); };
    const auto steps_events = events_.begin() + static_cast<std::ptrdiff_t>(recorded);
    if (std::adjacent_find(steps_events, events_.end(), out_of_order) != events_.end()) {
        std::stable_sort(events_.begin(), events_.end(), before);
        return;
    }
    if (recorded == 0) return;
    const bool in_order = std::adjacent_find(events_.begin(), steps_events, out_of_order) == steps_events &&
                          (steps_events == events_.end() || before(*(steps_events - 1), *steps_events));
    if (in_order) return;
    std::stable_sort(events_.begin(), steps_events, before);  // in the order they were recorded
    std::vector<ContactEvent<T>>& merged = merged_events_;
    merged.clear();
    std::merge(events_.begin(), steps_events, steps_events, events_.end(), std::back_inserter(merged), before);
    events_.swap(merged);
}

template <class T>
void World<T>::report_events() {
    sort_events(collect_events());
    if (listener_) {
        // The listener may change the world (and so events_; restore_snapshot replaces every
        // member): it is handed a copy held in a local vector, whose buffer is the world's scratch
        // taken out for the call and given back after, so a settled step allocates nothing. Each
        // call holds the listener alive even if it replaces or clears itself.
        std::vector<ContactEvent<T>> delivering;
        delivering.swap(delivered_events_);
        delivering = events_;
        {
            const FlagScope scope(callbacks_.in_listener);
            for (const ContactEvent<T>& e : delivering) {
                if (!listener_) break;  // cleared from inside
                const std::shared_ptr<const Listener> current = listener_;
                (*current)(*this, e);
            }
        }
        delivered_events_.swap(delivering);
    }
}

template <class T>
void World<T>::keep_poses_and_update_bounds(T dt) {
    // Fattened by the speculative distance and by the distance the body can travel this step,
    // so contacts exist before the bodies meet. The early-out's bound of each convex body is
    // placed here too: once per body, not per pair.
    // (After bodies were added or a snapshot restored, every body's bound is placed again.)
    // Each body's pose before the step is kept here as well, in the same parallel pass (the
    // query tree compares against it after the step, interpolated_transform blends from it).
    const bool all = early_out_.size() != bodies_.size() || settings_.speculative_distance != bounds_margin_;
    if (all) early_out_.resize(bodies_.size()), bounds_asleep_.assign(bodies_.size(), 0);
    if (retouched_.size() != bodies_.size()) retouched_.assign(bodies_.size(), 0);
    std::atomic<bool> any_retouched{false}, any_lighter{false};
    bounds_margin_ = settings_.speculative_distance;
    const auto place_bound = [&](std::uint32_t i, const Body<T>& b) {
        if (b.mesh() || b.compound()) early_out_.clear(i);
        else early_out_.set(i, *b.convex_shape(), b.transform());
    };
    parallel_for(
        tasks_.get(), static_cast<std::uint32_t>(bodies_.size()), bounds_range, [&](std::uint32_t begin, std::uint32_t end) {
            for (std::uint32_t i = begin; i < end; ++i) {
                Body<T>& b = bodies_[i];
                if (!b.alive_) continue;
                previous_pose_[i] = b.transform();
                if (b.impulse_halvings_ != 0) any_lighter.store(true, std::memory_order_relaxed);
                if (!b.enabled_) continue;  // a disabled body's box stays empty
                if (b.type_ == BodyType::static_body && !b.moved_) {
                    if (all) place_bound(i, b);
                    continue;
                }
                if (b.type_ != BodyType::dynamic && b.moved_) {
                    retouched_[i] = 1;
                    any_retouched.store(true, std::memory_order_relaxed);
                }
                // A sleeper that has not moved gets the box it got last step: skip it.
                // (Whatever moves or reshapes a body sets moved_, create_body included.)
                const bool asleep = b.type_ == BodyType::dynamic && !b.awake_ && length_squared(b.linear_velocity_) == T(0);
                if (asleep && bounds_asleep_[i] && !b.moved_) continue;
                const T reach = settings_.speculative_distance + travel_speed(b, dt) * dt;
                bounds_[i] = b.world_bounds().expanded(reach);
                place_bound(i, b);
                bounds_asleep_[i] = asleep ? 1 : 0;
                b.moved_ = false;
            }
        });
    // A static or kinematic body changed between steps wakes what rests on it: a material made
    // slippery (Body::set_material, which cannot reach the world) left a box asleep on a
    // frictionless ramp. (The world's own edits wake these at once as well.)
    if (any_retouched.load(std::memory_order_relaxed))
        for (std::uint32_t i = 0; i < bodies_.size(); ++i)
            if (retouched_[i] != 0) retouched_[i] = 0, wake_neighbours_of(i);
    if (any_lighter.load(std::memory_order_relaxed)) scale_lighter_impulses();
}

// A body made lighter (Body::set_mass_properties) would get from its contacts' and joints'
// cached impulses a warm start sized for its old mass: each is halved as many times as the
// lighter side asks (Body::impulse_halvings_), exactly (powers of two), before the narrow phase
// carries them over. Once per step in which some body's mass fell, over every contact and joint.
template <class T>
void World<T>::scale_lighter_impulses() {
    const auto halvings = [&](BodyId a, BodyId b) {
        return std::max(bodies_[a.index].impulse_halvings_, bodies_[b.index].impulse_halvings_);
    };
    for (Contact<T>& c : contacts_) detail::halve_impulses(c.manifold, halvings(c.a, c.b));
    for (Joint<T>& j : joints_)
        if (j.alive) detail::halve_impulses(j, halvings(j.a, j.b));
    for (Body<T>& b : bodies_) b.impulse_halvings_ = 0;
}

// The queries' tree holds each body's current box: after the step, every body whose pose changed
// gets its new one. First the bodies whose new box leaves their leaf's fat box are marked and
// counted, in parallel, so that the stepping thread reads a byte per body of a resting stack, not
// each body's box (that was 0.7 ms of the 5,050-box pyramid's step); then it moves the marked
// leaves. When they will bring the tree to its rebuild (refresh_query_tree), they only take their
// new boxes, without reinsertion: the rebuild reads only the leaves, so the tree is the same.
template <class T>
void World<T>::update_query_tree() {
    AabbTree<T>& tree = query_trees_[1];
    const auto moved = [&](std::uint32_t i) {
        const Body<T>& b = bodies_[i];
        if (!b.alive_ || !b.enabled_ || b.type_ == BodyType::static_body) return false;
        return !(b.position_ == previous_pose_[i].position && b.orientation_ == previous_pose_[i].orientation);
    };
    const auto n = static_cast<std::uint32_t>(bodies_.size());
    leaves_fat_box_.resize(n);
    std::atomic<std::size_t> leaving{0};
    parallel_for(tasks_.get(), n, bounds_range, [&](std::uint32_t begin, std::uint32_t end) {
        std::size_t count = 0;
        for (std::uint32_t i = begin; i < end; ++i) {
            leaves_fat_box_[i] = moved(i) && tree.would_reinsert(i, bodies_[i].world_bounds()) ? 1 : 0;
            count += leaves_fat_box_[i];
        }
        leaving.fetch_add(count, std::memory_order_relaxed);
    });
    const bool rebuilding = due_for_rebuild(tree, leaving.load());
    for (std::uint32_t i = 0; i < n; ++i) {
        if (leaves_fat_box_[i] == 0) continue;
        if (rebuilding) tree.move_before_rebuild(i, bodies_[i].world_bounds());
        else tree.move(i, bodies_[i].world_bounds());
    }
    refresh_query_tree();
}

// From scratch (a restored snapshot): every living body, then one balanced build.
template <class T>
void World<T>::rebuild_query_tree() {
    for (AabbTree<T>& tree : query_trees_) tree.clear();
    for (std::uint32_t i = 0; i < bodies_.size(); ++i)  // room up to each body's slot in its type's tree (create_body)
        if (bodies_[i].alive_) query_tree_of(i).reserve(i + std::size_t(1));
    for (std::uint32_t i = 0; i < bodies_.size(); ++i)
        if (bodies_[i].alive_ && bodies_[i].enabled_) query_tree_of(i).insert(i, bodies_[i].world_bounds());
    for (AabbTree<T>& tree : query_trees_) tree.rebuild();
}

// Three passes so that the costly middle one can run on several threads with the same result:
// (1) in pair order, which pairs are wanted (the user's filter runs here, on the stepping
// thread), which need the narrow phase, and last step's contacts of each pair (a merge-join, both
// lists sorted by body pair); (2) each pair without a compound side, independently, through the
// task system: its manifold, matched to last step's points; (3) in pair order, the new contact
// list and the events of contacts that ended. A pair with a compound side collides in pass 3 (it
// may give a contact per pair of parts). With one worker pass 2 is skipped and pass 3 collides
// every pair itself: the same calls on the same inputs, without a contact per pair kept apart.
template <class T>
void World<T>::narrow_phase(T dt) {
    classify_pairs(dt);
    reject_apart_pairs(dt);
    collide_on_workers(dt);
    merge_contacts(dt);
    contacts_.swap(next_contacts_);
    index_contacts(bodies_.size());
    if (drop_out_of_reach(dt)) index_contacts(bodies_.size());
    stats_.contacts = contacts_.size();
}

/// Removes the contacts out of reach (World::out_of_reach) from contacts_, as if the narrow
/// phase had found none: a contact kept without a row merged its stale points into the next
/// step's manifold (a box sliding at 10 m/s across tiles stopped dead at a seam). Reports an
/// `ended` event for one that touched at the end of the last step. True if it removed any.
template <class T>
bool World<T>::drop_out_of_reach(T dt) {
    path_.resize(contacts_.size());
    std::atomic<bool> beside{false};
    parallel_for(tasks_.get(), static_cast<std::uint32_t>(contacts_.size()), row_range,
                 [&](std::uint32_t begin, std::uint32_t end) {
                     bool any = false;
                     for (std::uint32_t m = begin; m < end; ++m) {
                         path_[m] = path_of(m, dt);
                         any = any || path_[m].kind == PathContact::beside;
                     }
                     if (any) beside.store(true, std::memory_order_relaxed);
                 });
    if (!beside.load()) return false;
    // Decided for every contact before any is removed: each decision reads the body's others.
    dropped_.assign(contacts_.size(), 0);
    bool any = false;
    for (std::uint32_t m = 0; m < contacts_.size(); ++m)
        if (out_of_reach(m)) dropped_[m] = 1, any = true;
    if (!any) return false;
    std::size_t kept = 0;
    for (std::size_t m = 0; m < contacts_.size(); ++m) {
        const Contact<T>& c = contacts_[m];
        if (!dropped_[m]) {
            if (kept != m) contacts_[kept] = c;
            ++kept;
        } else if (c.was_touching) {
            events_pending_.push_back(
                {ContactEventKind::ended, c.a, c.b, c.sensor, c.manifold.normal, 0, {}, T(0), c.child_a, c.child_b});
        }
    }
    contacts_.resize(kept);
    return true;
}

/// Pass 1 of narrow_phase, in pair order: each pair's kind (PairWork) and its contacts of last
/// step; the collided pairs listed for the early-out, the mesh pairs for the workers.
template <class T>
void World<T>::classify_pairs(T dt) {
    const bool parallel = workers() > 1;
    pair_work_.resize(pairs_.size());
    early_jobs_.clear();
    remeasured_.clear();
    mesh_jobs_.clear();
    std::size_t old = 0;
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
        const ProxyPair& pair = pairs_[k];
        PairWork& work = pair_work_[k];
        while (old < contacts_.size() &&
               (contacts_[old].a.index < pair.a || (contacts_[old].a.index == pair.a && contacts_[old].b.index < pair.b)))
            ++old;
        work.old_begin = static_cast<std::uint32_t>(old);
        while (old < contacts_.size() && contacts_[old].a.index == pair.a && contacts_[old].b.index == pair.b) ++old;
        work.old_end = static_cast<std::uint32_t>(old);
        const Body<T>& a = bodies_[pair.a];
        const Body<T>& b = bodies_[pair.b];
        // (A free slot's box is empty and pairs with nothing; checked anyway, so a broad phase
        // can never hand a destroyed body to the narrow phase.)
        const bool wanted = a.alive_ && b.alive_ && a.enabled_ && b.enabled_ &&
                            (a.type_ == BodyType::dynamic || b.type_ == BodyType::dynamic) && (a.layer_ & b.mask_) &&
                            (b.layer_ & a.mask_) &&
                            !std::binary_search(unconnected_pairs_.begin(), unconnected_pairs_.end(), pair_key(pair.a, pair.b)) &&
                            filter_allows(pair.a, pair.b);
        // Both asleep (or asleep on static): the contacts stay as they were.
        work.kind = !wanted                        ? PairKind::dropped
                    : !active(a) && !active(b)     ? PairKind::kept
                    : a.mesh() || b.mesh()         ? PairKind::mesh
                    : a.compound() || b.compound() ? PairKind::parts
                                                   : PairKind::collided;
        work.remeasured_begin = static_cast<std::uint32_t>(remeasured_.size());
        if (work.kind == PairKind::mesh &&
            (this->*mesh_stage_.remeasure)(pair, pair_margin(a, b, dt), dt, work.old_begin, work.old_end))
            work.kind = PairKind::remeasured;
        if (work.kind == PairKind::collided) early_jobs_.push_back(static_cast<std::uint32_t>(k));
        if (parallel && work.kind == PairKind::mesh) mesh_jobs_.push_back(static_cast<std::uint32_t>(k));
    }
}

/// Pass 2 of narrow_phase, several workers only: the collided pairs the early-out left and the
/// mesh pairs' manifolds, each pair on its own, through the task system.
template <class T>
void World<T>::collide_on_workers(T dt) {
    if (workers() <= 1) return;  // merge_contacts collides each pair in its place
    collide_jobs_.clear();
    for (const std::uint32_t k : early_jobs_)
        if (pair_work_[k].kind == PairKind::collided) collide_jobs_.push_back(k);
    job_contacts_.resize(collide_jobs_.size());
    job_results_.resize(collide_jobs_.size());
    parallel_for(
        tasks_.get(), static_cast<std::uint32_t>(collide_jobs_.size()), 16u, [&](std::uint32_t begin, std::uint32_t end) {
            for (std::uint32_t j = begin; j < end; ++j) {
                const std::uint32_t k = collide_jobs_[j];
                const PairWork& work = pair_work_[k];
                const Contact<T>* had = work.old_begin < work.old_end && contacts_[work.old_begin].child_a == 0 &&
                                                contacts_[work.old_begin].child_b == 0
                                            ? &contacts_[work.old_begin]
                                            : nullptr;
                job_contacts_[j].manifold.count = 0;
                job_results_[j] = collide_parts(pairs_[k], 0, 0, pair_margin(bodies_[pairs_[k].a], bodies_[pairs_[k].b], dt), dt,
                                                had, job_contacts_[j]);
            }
        });
    if (mesh_job_manifolds_.size() < mesh_jobs_.size()) mesh_job_manifolds_.resize(mesh_jobs_.size());
    parallel_for(tasks_.get(), static_cast<std::uint32_t>(mesh_jobs_.size()), 1u, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t j = begin; j < end; ++j) {
            const ProxyPair& pair = pairs_[mesh_jobs_[j]];
            (this->*mesh_stage_.manifolds)(pair, pair_margin(bodies_[pair.a], bodies_[pair.b], dt), dt, mesh_job_manifolds_[j]);
        }
    });
}

/// Pass 3 of narrow_phase, the merge, in pair order: ended contacts reported, each pair's
/// contacts into next_contacts_. On one worker they are copied (or made) there at once. On
/// several, this pass only says where each run of contacts goes (compound and mesh pairs are made
/// into side_contacts_ first), and the runs are copied in parallel afterwards: a serial copy of
/// every contact (280 bytes in float, on two workers half of them just written by the other core)
/// was the largest serial part of the narrow phase (docs/parallel.md).
template <class T>
void World<T>::merge_contacts(T dt) {
    const bool parallel = workers() > 1;
    std::vector<Contact<T>>& next = next_contacts_;
    std::vector<Contact<T>>& made = parallel ? side_contacts_ : next;  // where compound and mesh pairs append
    made.clear();
    placed_runs_.clear();
    if (!parallel) next.reserve(pairs_.size());  // most pairs give one contact: no copies while growing (a crowd's first step)
    std::uint32_t placed = 0;
    const auto place = [&](ContactSource from, std::size_t begin, std::size_t count, bool kept) {
        if (count == 0) return;
        if (parallel) {
            placed_runs_.push_back({from, kept, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(count), placed});
            placed += static_cast<std::uint32_t>(count);
            return;
        }
        const std::vector<Contact<T>>& source = contact_source(from);
        for (std::size_t i = begin; i < begin + count; ++i) {
            next.push_back(source[i]);
            if (kept) next.back().was_touching = next.back().touching;
        }
    };
    std::size_t old = 0, job = 0, mesh_job = 0;
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
        const PairWork& work = pair_work_[k];
        while (old < work.old_begin) end_contact(contacts_[old++]);  // no pair this step: ended
        if (work.kind == PairKind::kept) {
            place(ContactSource::last_step, old, work.old_end - old, true);
            old = work.old_end;
        } else if (work.kind == PairKind::parts || (work.kind == PairKind::collided && !parallel)) {
            const std::size_t before = made.size();
            collide_pair(pairs_[k], pair_margin(bodies_[pairs_[k].a], bodies_[pairs_[k].b], dt), dt, old, work.old_end, made);
            if (parallel) place(ContactSource::side, before, made.size() - before, false);
            old = work.old_end;
        } else if (work.kind == PairKind::mesh) {
            const T margin = pair_margin(bodies_[pairs_[k].a], bodies_[pairs_[k].b], dt);
            if (!parallel) (this->*mesh_stage_.manifolds)(pairs_[k], margin, dt, mesh_manifolds_);
            const std::size_t before = made.size();
            (this->*mesh_stage_.merge)(pairs_[k], margin, old, work.old_end,
                                       parallel ? mesh_job_manifolds_[mesh_job++] : mesh_manifolds_, made);
            if (parallel) place(ContactSource::side, before, made.size() - before, false);
            old = work.old_end;
        } else if (work.kind == PairKind::remeasured) {
            const std::uint32_t count = work.old_end - work.old_begin;
            place(ContactSource::remeasured, work.remeasured_begin, count, false);
            stats_.reused_contacts += count;
            old = work.old_end;
        } else if (work.kind == PairKind::collided) {
            // Pass 2's contact took over last step's contact of parts (0, 0), if there was one.
            if (job_results_[job] == PartsContact::reused) ++stats_.reused_contacts;
            const Contact<T>& fresh = job_contacts_[job++];
            const bool had = old < work.old_end && contacts_[old].child_a == 0 && contacts_[old].child_b == 0;
            if (had && fresh.manifold.count == 0) end_contact(contacts_[old]);
            if (had) ++old;
            if (fresh.manifold.count > 0) place(ContactSource::job, job - 1, 1, false);
        }
        // A pair the contact filter now vetoes: a sleeper it held wakes, or it hung in the air.
        const bool vetoed = work.kind == PairKind::dropped;
        for (; old < work.old_end; ++old) {  // dropped, or parts that no longer exist
            if (vetoed && contacts_[old].touching) vetoed_bodies_.insert(vetoed_bodies_.end(), {pairs_[k].a, pairs_[k].b});
            end_contact(contacts_[old]);
        }
    }
    if (parallel) copy_placed_runs(placed);
    while (old < contacts_.size()) end_contact(contacts_[old++]);
    // Woken after every pair is collided: a woken body's margin grows by what gravity adds over
    // the step (travel_speed), and one worker collides pairs here, in the merge, where several
    // collided them before it; waking in the loop gave later pairs of the body a larger margin
    // on one worker only, and other bits.
    for (const std::uint32_t i : vetoed_bodies_)
        if (bodies_[i].type_ == BodyType::dynamic && bodies_[i].alive_) bodies_[i].wake();
    vetoed_bodies_.clear();
}

/// Several workers: every run the merge placed (narrow_phase) copied into next_contacts_, which
/// holds `count` contacts after it. The runs do not overlap, so they are copied in parallel; the
/// list is resized, not cleared, so the slots it already had are not cleared first.
template <class T>
void World<T>::copy_placed_runs(std::uint32_t count) {
    next_contacts_.resize(count);
    parallel_for(tasks_.get(), static_cast<std::uint32_t>(placed_runs_.size()), copy_range,
                 [&](std::uint32_t begin, std::uint32_t end) {
                     for (std::uint32_t r = begin; r < end; ++r) {
                         const PlacedRun& run = placed_runs_[r];
                         const std::vector<Contact<T>>& source = contact_source(run.from);
                         for (std::uint32_t i = 0; i < run.count; ++i) {
                             Contact<T>& c = next_contacts_[run.to + i];
                             c = source[run.begin + i];
                             if (run.kept) c.was_touching = c.touching;
                         }
                     }
                 });
}

// MPR's first test for W pairs at a time (early_out.hpp): a convex pair apart by more than its
// margin becomes PairKind::apart, so its contacts end as they would after a narrow phase that
// found nothing, without the narrow phase. It only rejects pairs the narrow phase would reject.
// Each group of W pairs only reads the bounds and marks its own pairs, so the groups run on the
// workers (one worker: in order on the caller, the same calls).
template <class T>
void World<T>::reject_apart_pairs(T dt) {
    constexpr int W = EarlyOut<T>::width;
    constexpr std::size_t kAhead = 16;  // second bodies come at random: keep a few misses in flight
    const std::size_t jobs = early_jobs_.size();
    const std::uint32_t* job = early_jobs_.data();
    const ProxyPair* pairs = pairs_.data();
    PairWork* work = pair_work_.data();
    std::atomic<std::size_t> apart_count{0};
    const auto groups = static_cast<std::uint32_t>((jobs + W - 1) / W);
    parallel_for(tasks_.get(), groups, early_out_range, [&](std::uint32_t begin, std::uint32_t end) {
        std::size_t found = 0;
        const std::size_t stop = std::min(std::size_t(end) * W, jobs);
        std::size_t j = std::size_t(begin) * W;
        for (; j + W <= stop; j += W) {
            std::uint32_t a[W], b[W];
            T margin[W];
            for (int l = 0; l < W; ++l) {
                const std::size_t m = j + static_cast<std::size_t>(l);
                if (m + kAhead < jobs) early_out_.prefetch(pairs[job[m + kAhead]].b);
                const ProxyPair& pair = pairs[job[m]];
                a[l] = pair.a, b[l] = pair.b, margin[l] = pair_margin(bodies_[pair.a], bodies_[pair.b], dt);
            }
            const unsigned apart = early_out_.template apart_pairs<W>(a, b, margin);
            for (int l = 0; l < W; ++l)
                if ((apart >> l) & 1u) work[job[j + static_cast<std::size_t>(l)]].kind = PairKind::apart, ++found;
        }
        for (; j < stop; ++j) {  // the last few, one at a time
            const ProxyPair& pair = pairs[job[j]];
            if (early_out_.apart(pair.a, pair.b, pair_margin(bodies_[pair.a], bodies_[pair.b], dt)))
                work[job[j]].kind = PairKind::apart, ++found;
        }
        apart_count.fetch_add(found, std::memory_order_relaxed);
    });
    stats_.apart_pairs = apart_count.load(std::memory_order_relaxed);
}

// A counting sort of the contacts by body slot (each contact listed under both bodies), in
// contacts_ order: counts, prefix sums, then a forward fill that leaves contact_start_[i] at the
// end of slot i's run, which begins where slot i - 1's ends. Slots past `slots` (bodies created
// since the last step) have no contacts. At a fixed size it allocates nothing.
template <class T>
void World<T>::index_contacts(std::size_t slots) {
    contact_start_.assign(slots + 1, 0u);
    for (const Contact<T>& c : contacts_) {
        ++contact_start_[c.a.index + std::size_t(1)];
        ++contact_start_[c.b.index + std::size_t(1)];
    }
    for (std::size_t i = 1; i <= slots; ++i) contact_start_[i] += contact_start_[i - 1];
    contact_list_.resize(2 * contacts_.size());
    for (std::uint32_t k = 0; k < contacts_.size(); ++k) {
        contact_list_[contact_start_[contacts_[k].a.index]++] = k;
        contact_list_[contact_start_[contacts_[k].b.index]++] = k;
    }
}

template <class T>
void World<T>::collide_pair(const ProxyPair& pair, T margin, T dt, std::size_t old_begin, std::size_t old_end,
                            std::vector<Contact<T>>& next) {
    const Body<T>& a = bodies_[pair.a];
    const Body<T>& b = bodies_[pair.b];
    std::size_t old = old_begin;
    for (std::uint32_t ca = 0; ca < a.child_count(); ++ca) {
        for (std::uint32_t cb = 0; cb < b.child_count(); ++cb) {
            // Last step's contact of these two parts, if any (both lists are in part order).
            while (old < old_end &&
                   (contacts_[old].child_a < ca || (contacts_[old].child_a == ca && contacts_[old].child_b < cb)))
                end_contact(contacts_[old++]);
            const bool had = old < old_end && contacts_[old].child_a == ca && contacts_[old].child_b == cb;
            // Made in its place in `next` (reserved for a contact a pair: no copy of the contact).
            next.emplace_back();
            const PartsContact result = collide_parts(pair, ca, cb, margin, dt, had ? &contacts_[old] : nullptr, next.back());
            if (result == PartsContact::reused) ++stats_.reused_contacts;
            if (result == PartsContact::apart) {
                next.pop_back();
                if (had) end_contact(contacts_[old]);  // apart: the contact ends
            }
            if (had) ++old;
        }
    }
    for (; old < old_end; ++old) end_contact(contacts_[old]);
}

/// The contact of parts ca and cb of a pair into `out`, its points matched to `had` (last step's
/// contact of those parts, or nullptr), or re-measured from `had` when the pair barely moved;
/// apart when they are apart (out is left as it was).
template <class T>
typename World<T>::PartsContact World<T>::collide_parts(const ProxyPair& pair, std::uint32_t ca, std::uint32_t cb, T margin, T dt,
                                                        const Contact<T>* had, Contact<T>& out) const {
    const Body<T>& a = bodies_[pair.a];
    const Body<T>& b = bodies_[pair.b];
    const Transform<T> pose_a = a.child_transform(ca), pose_b = b.child_transform(cb);
    if (a.compound() || b.compound()) {  // parts whose boxes are apart need no narrow phase
        if (!overlaps(world_bounds(a.child_shape(ca), pose_a).expanded(margin), world_bounds(b.child_shape(cb), pose_b)))
            return PartsContact::apart;
    }
    if (had && reuse_contact(pair, margin, dt, *had, out)) return PartsContact::reused;
    const ContactManifold<T> now =
        generate_contacts(a.child_shape(ca), pose_a, b.child_shape(cb), pose_b, margin, settings_.linear_slop);
    if (now.count == 0) return PartsContact::apart;
    make_contact(pair, ca, cb, margin, had, at_first_touch(a, ca, pose_a, b, cb, pose_b, now, margin, dt), out);
    return PartsContact::made;
}

/// m: how far the surface of the body's part `child` can swing as the body turns: the bounding
/// radius, or for a ball only its centre's offset from the body's centre (a ball turns without
/// moving its surface: a ball rolling at 10 m/s past a floor's corner, never nearer than 2 cm,
/// was not swept for turning by more than speculative_distance, kept a manifold with the corner
/// and was thrown up at 3-4 m/s).
template <class T>
T World<T>::turning_radius(const Body<T>& body, std::uint32_t child) const {
    return detail::is_sphere(body, child) ? length(body.child_transform(child).position - body.position_)
                                          : body.bounding_radius();
}

// Speculative contacts out of reach (docs/collision.md). A pair's margin grows with both bodies'
// travel, so a fast body has speculative manifolds with everything within its travel: the tiles
// beside the one it lands on, the border of a mesh platform, each along the normal of the
// closest features now, tilted towards the body. Solved with the face it lands on, they pushed
// it sideways, and their friction spun it: a box dropped at 60 m/s across the seam of four 1 m
// static tiles went through them, a ball at 1,000 m/s near the border of a 4 m mesh platform was
// thrown 24 m up. When a part moves more than half its bounding radius in the step (against a
// static body: at any speed, `any_speed`) and turns its surface by no more than
// speculative_distance, a manifold whose every point is farther than speculative_distance is
// beside the path unless the part, swept along the pair's relative translation (plus
// speculative_distance), meets the other part or triangle: a mesh drops such triangles
// (collide_mesh), a convex pair with a static body is removed after the narrow phase when
// nothing can turn the body towards it (drop_out_of_reach). Pairs of moving bodies keep theirs.
template <class T>
SpeculativeSweep<T> World<T>::speculative_sweep(const Body<T>& a, std::uint32_t ca, const Body<T>& b, std::uint32_t cb, T dt,
                                                bool any_speed) const {
    // Each velocity held to its body's cap, as pair_margin holds it (a kinematic body may be set
    // to any finite speed; the solver caps it).
    const auto capped = [&](const Body<T>& body) {
        const T speed = length(body.linear_velocity_);
        return speed > speed_limit(body) ? body.linear_velocity_ * (speed_limit(body) / speed) : body.linear_velocity_;
    };
    const Vec3<T> move = (capped(a) - capped(b)) * dt;
    const T radius = xeno::bounding_radius(a.child_shape(ca)), distance = length(move);
    if (!is_finite(move)) return {};
    const T turn =
        (length(a.angular_velocity_) * turning_radius(a, ca) + length(b.angular_velocity_) * turning_radius(b, cb)) * dt;
    const T near = settings_.speculative_distance;
    if (!(distance > T(0.5) * radius || (any_speed && distance > T(0))) || !(turn <= near)) return {};
    return {move * ((distance + near) / distance), near, settings_.linear_slop};
}

/// How contact m, between a static body and a moving one, stands to the moving body's path in
/// the step: it may turn the body (a point within speculative_distance, a solver row now; or
/// the part, swept along its translation in the step plus speculative_distance, meets the static
/// part: at that distance, with the surface it meets there), or it is beside the path (every
/// point farther than speculative_distance and the sweep misses: speculative_sweep). Against a
/// static body at any speed: separate static boxes laid side by side (a floor of tiles) gave a
/// body sliding over them manifolds with the neighbours beside its path, whose separating axis
/// pointed along the motion (docs/meshes.md, "Separate bodies edge to edge"). Mesh pairs cull
/// their triangles in collide_mesh, and their manifolds may turn the body; sensors and pairs of
/// moving bodies are `none`.
template <class T>
typename World<T>::PathContact World<T>::path_of(std::uint32_t m, T dt) const {
    const Contact<T>& c = contacts_[m];
    const Body<T>& a = bodies_[c.a.index];
    const Body<T>& b = bodies_[c.b.index];
    PathContact out;
    const bool a_static = a.type_ == BodyType::static_body;
    if (c.sensor || c.manifold.count == 0 || a_static == (b.type_ == BodyType::static_body) || seam_ghost(c)) return out;
    const Vec3<T> towards_mover = a_static ? c.manifold.normal : -c.manifold.normal;
    out.kind = PathContact::turns;
    out.normal = towards_mover;
    const ContactPoint<T>& first = c.manifold.points[0];
    out.surface = (a_static ? b.world_point(first.local_b) : a.world_point(first.local_a)) + towards_mover * first.depth;
    if (a.mesh() || b.mesh()) return out;  // a mesh's manifolds turn the body now; it dropped its triangles beside the path
    for (int i = 0; i < c.manifold.count; ++i)
        if (!(c.manifold.points[static_cast<std::size_t>(i)].depth < -settings_.speculative_distance)) return out;
    const SpeculativeSweep<T> sweep = speculative_sweep(a, c.child_a, b, c.child_b, dt, true);
    if (!sweep.active()) return out;
    const std::optional<ShapeCastHit<T>> hit =
        xeno::shape_cast(a.child_shape(c.child_a), a.child_transform(c.child_a), sweep.move, b.child_shape(c.child_b),
                         b.child_transform(c.child_b));
    if (!hit) {
        out.kind = PathContact::beside;
        return out;
    }
    // The hit's normal runs from the swept part A to B, and its point is on B where the moved A
    // touches it: moved back by A's share of the move when A is the static one.
    out.distance = hit->fraction * length(sweep.move);
    out.normal = a_static ? hit->normal : -hit->normal;
    out.surface = a_static ? hit->point - sweep.move * hit->fraction : hit->point;
    return out;
}

/// Whether contact m gets no row as out of reach (docs/collision.md, "Speculative contacts out
/// of reach"): beside the path of its moving body (path_of), and that body cannot be turned
/// towards it within the step. It can when a joint holds it (a flail swung into a post went
/// through it), or when the static part rises by more than linear_slop above the surface that
/// first turns the body this step (the nearest along its path of its contacts that may turn
/// it): a ball falling at 70 m/s onto a 45° ramp beside a wall was turned by the ramp into the
/// wall, whose manifold was beside its straight path, and went through it in 4 of 10 drops. The
/// tiles beside the one a body lands on, flush with its top, stay out of reach.
template <class T>
bool World<T>::out_of_reach(std::uint32_t m) const {
    if (path_[m].kind != PathContact::beside) return false;
    const Contact<T>& c = contacts_[m];
    const bool a_static = bodies_[c.a.index].type_ == BodyType::static_body;
    const std::uint32_t mover = a_static ? c.b.index : c.a.index, fixed = a_static ? c.a.index : c.b.index;
    if (jointed(mover)) return false;
    const T slop = settings_.linear_slop;
    const std::uint32_t end = contact_start_[mover], begin = mover == 0 ? 0 : contact_start_[mover - 1];
    T first = ScalarTraits<T>::infinity;
    for (std::uint32_t k = begin; k < end; ++k) {
        const PathContact& turn = path_[contact_list_[k]];
        if (turn.kind == PathContact::turns) first = std::min(first, turn.distance);
    }
    for (std::uint32_t k = begin; k < end; ++k) {
        const PathContact& turn = path_[contact_list_[k]];
        if (turn.kind != PathContact::turns || !(turn.distance <= first + slop)) continue;
        if (dot(highest_point(fixed, turn.normal, mover) - turn.surface, turn.normal) > slop) return false;
    }
    return true;
}

/// Whether a living joint holds the body in `slot`.
template <class T>
bool World<T>::jointed(std::uint32_t slot) const {
    for (const Joint<T>& j : joints_)
        if (j.alive && (j.a.index == slot || j.b.index == slot)) return true;
    return false;
}

/// Speculative contacts of a ball meet where the parts will touch, not where they are closest
/// now. A ball and a part apart by more than the slop and moving towards each other by more than
/// their gap within two steps are swept along their relative translation (shape_cast; turning is
/// left out) to the first touch, collided there, and the manifold found there is moved back by each body's
/// travel: its normal and points are those of the impact, its depths the gaps along that normal
/// now. The manifold of closest features instead holds a normal that turns as the bodies close:
/// two balls meeting off-centre at 10 m/s left at 62° instead of 72° (a quarter of a diameter
/// apart at the start of the step), and the ball struck took 50 % too much momentum. Without
/// a touch within two steps (they pass, or the sweep starts overlapping) `now` is kept.
template <class T>
ContactManifold<T> World<T>::at_first_touch(const Body<T>& a, std::uint32_t ca, const Transform<T>& pose_a, const Body<T>& b,
                                            std::uint32_t cb, const Transform<T>& pose_b, const ContactManifold<T>& now, T margin,
                                            T dt) const {
    // A ball on one side: the sweep is exact for it, whichever way it turns. Between other
    // shapes a ragdoll, swept the same way whenever its limbs turned slowly, landed further past
    // its cones (median of 20 runs 1.42° against 1.17°, worst 5.0° against 3.4°): left for later.
    if (!detail::is_sphere(a, ca) && !detail::is_sphere(b, cb)) return now;
    T deepest = -ScalarTraits<T>::infinity;
    for (int i = 0; i < now.count; ++i) deepest = std::max(deepest, now.points[static_cast<std::size_t>(i)].depth);
    // Two steps ahead: the relax pass after a step's last substep already answers a touch due in
    // the next substep (the gap it would close then), with the normal of this step's manifold.
    const T horizon = T(2) * dt;
    const Vec3<T> travel_a = a.linear_velocity_ * horizon, travel_b = b.linear_velocity_ * horizon;
    const Vec3<T> relative = travel_a - travel_b;
    const T gap = -deepest;
    // A travel beyond the largest T (a body at half of it for 2 dt) is no sweep: shape_cast would
    // refuse it and throw out of the step, half done (with workers, out of a worker).
    if (!is_finite(relative)) return now;
    if (!(gap > settings_.linear_slop) || !(length_squared(relative) > gap * gap)) return now;
    // The sweep leaves turning out: only while turning moves the surfaces by less than a quarter
    // of the gap (a ball turns without moving its surface; what it strikes may spin).
    const auto turning = [&](const Body<T>& body, std::uint32_t child) {
        return length(body.angular_velocity_) * turning_radius(body, child) * horizon;
    };
    if (!(turning(a, ca) + turning(b, cb) <= T(0.25) * gap)) return now;
    const std::optional<ShapeCastHit<T>> hit = xeno::shape_cast(a.child_shape(ca), pose_a, relative, b.child_shape(cb), pose_b);
    if (!hit || hit->initially_overlapping) return now;
    const Vec3<T> shift_a = travel_a * hit->fraction, shift_b = travel_b * hit->fraction;
    ContactManifold<T> touch =
        generate_contacts(a.child_shape(ca), {pose_a.position + shift_a, pose_a.orientation}, b.child_shape(cb),
                          {pose_b.position + shift_b, pose_b.orientation}, margin, settings_.linear_slop);
    if (touch.count == 0) return now;
    for (int i = 0; i < touch.count; ++i) {
        ManifoldPoint<T>& p = touch.points[static_cast<std::size_t>(i)];
        p.point_a -= shift_a;
        p.point_b -= shift_b;
        p.depth = dot(p.point_a - p.point_b, touch.normal);
    }
    return touch;
}

template <class T>
void World<T>::make_contact(const ProxyPair& pair, std::uint32_t ca, std::uint32_t cb, T margin, const Contact<T>* had,
                            const ContactManifold<T>& fresh, Contact<T>& out) const {
    const Body<T>& a = bodies_[pair.a];
    const Body<T>& b = bodies_[pair.b];
    Contact<T>& c = out;
    c = had ? *had : Contact<T>{};
    c.was_touching = had && had->touching;
    c.a = id_of(pair.a);
    c.b = id_of(pair.b);
    c.child_a = ca;
    c.child_b = cb;
    c.friction = combined_friction(a.material_, b.material_);
    c.restitution = combined_restitution(a.material_, b.material_);
    c.sensor = a.sensor_ || b.sensor_;
    // A sphere touches by one point, never by a patch the thesis's gradual merge could build: its
    // old points are only where its surface was. On a rolling ball they rise along a cycloid
    // without sliding, so the merge's slide test kept them within the margin (at 5 m/s three
    // points up to 6 cm off the ground), which lifted the friction patch's centre and let the
    // ball spin 2.5 % faster than it rolled. (A capsule rolls on its side, where it gets two
    // points, replaced whole; its ends keep the merge, on which a ragdoll's limbs settle.)
    const bool sphere = detail::is_sphere(a, ca) || detail::is_sphere(b, cb);
    if (fresh.count == 1 && had && c.manifold.count > 0 && !sphere)
        c.manifold.merge_single(fresh.points[0], fresh.normal, a.transform(), b.transform(), settings_.contact_match_distance,
                                margin);
    else c.manifold.replace(fresh, a.transform(), b.transform(), settings_.contact_match_distance);
    c.touching = c.manifold.touching();
    for (int i = 0; i < c.manifold.count; ++i) c.manifold.points[static_cast<std::size_t>(i)].step_impulse = T(0);
    c.made_offset = offset_in_a(a, b);
    c.made_turn = turn_from_a(a, b);
    c.made_normal = a.transform().inverse_apply_direction(c.manifold.normal);
}

// A resting pair moves by round-off from step to step, and colliding it again gives the same
// points: Jolt's body-pair cache, Bullet's persistent manifold refreshed from its anchors. B's
// motion relative to A since the manifold was made moves any of its anchors by at most
// |Δ offset| + θ · (the anchor's distance from B's centre), θ the relative rotation (2 |Δq| for
// small angles); while that, plus how far the anchors can move in this step at the bodies'
// velocities, stays within a tenth of linear_slop, every point is re-measured from its two
// anchors along the normal carried in A's frame. That is exact for a face of A under
// anything of B (a box on a box: the anchors on B are its corners, the plane of A's face turns
// with A) and off by the bound for a face of B or an edge pair.
template <class T>
bool World<T>::reuse_contact(const ProxyPair& pair, T margin, T dt, const Contact<T>& had, Contact<T>& out) const {
    if (!settings_.reuse_contacts || had.manifold.count == 0) return false;
    const Body<T>& a = bodies_[pair.a];
    const Body<T>& b = bodies_[pair.b];
    Quat<T> turn = turn_from_a(a, b);
    if (dot(turn, had.made_turn) < T(0)) turn = -turn;  // q and −q are one rotation
    T lever_a = T(0), lever_b = T(0);
    for (int i = 0; i < had.manifold.count; ++i) {
        lever_a = std::max(lever_a, length_squared(had.manifold.points[static_cast<std::size_t>(i)].local_a));
        lever_b = std::max(lever_b, length_squared(had.manifold.points[static_cast<std::size_t>(i)].local_b));
    }
    lever_a = std::sqrt(lever_a), lever_b = std::sqrt(lever_b);
    const T moved = length(offset_in_a(a, b) - had.made_offset) + T(2) * length(turn - had.made_turn) * lever_b;
    // ... and how far they can move during this step: a body just set spinning or pushed is
    // collided again at once, so the speculative points of its new motion are there.
    const T moving = (length(b.linear_velocity_ - a.linear_velocity_) + length(a.angular_velocity_) * lever_a +
                      length(b.angular_velocity_) * lever_b) *
                     dt;
    if (!(moved + moving <= T(0.1) * settings_.linear_slop)) return false;
    const Transform<T> pose_a = a.transform(), pose_b = b.transform();
    const Vec3<T> n = pose_a.apply_direction(had.made_normal);
    // A round surface rolls under a contact point that stays put; its anchor turns with it. Held
    // there, a rolling ball's normal force sat up to the bound ahead of its centre and rolled it on
    // (pushed by 1e-4 of its weight, a ball gained 3.9 times the speed the push gives in 2 s, a
    // cylinder 3.2 times), so a round part's anchor is put back where it touches along the normal
    // and the other anchor beside it, on its own plane. Every point is measured before `out` is
    // written (a 280-byte contact copied once: through a temporary it was copied twice, 1 % of a
    // box pyramid's step), so `out` is untouched when the pair must be collided again.
    struct Measured {
        Vec3<T> on_a, on_b;
        T separation;
        bool round;
    };
    std::array<Measured, 4> measured;
    for (int i = 0; i < had.manifold.count; ++i) {
        const ContactPoint<T>& p = had.manifold.points[static_cast<std::size_t>(i)];
        Measured& m = measured[static_cast<std::size_t>(i)];
        m.on_a = pose_a.apply(p.local_a), m.on_b = pose_b.apply(p.local_b);
        const bool round_a = detail::rolling_point(a, had.child_a, n, m.on_a);
        const bool round_b = detail::rolling_point(b, had.child_b, -n, m.on_b);
        m.separation = dot(m.on_b - m.on_a, n);
        if (m.separation > margin) return false;  // beyond the margin: colliding again drops it
        m.round = round_a || round_b;
        if (m.round) {
            if (!round_a) m.on_a = m.on_b - n * m.separation;
            if (!round_b) m.on_b = m.on_a + n * m.separation;
        }
    }
    out = had;
    out.was_touching = had.touching;
    out.friction = combined_friction(a.material_, b.material_);
    out.restitution = combined_restitution(a.material_, b.material_);
    out.sensor = a.sensor_ || b.sensor_;
    out.manifold.normal = n;
    for (int i = 0; i < out.manifold.count; ++i) {
        ContactPoint<T>& p = out.manifold.points[static_cast<std::size_t>(i)];
        const Measured& m = measured[static_cast<std::size_t>(i)];
        if (m.round) {
            p.local_a = pose_a.inverse_apply(m.on_a);
            p.local_b = pose_b.inverse_apply(m.on_b);
        }
        p.depth = -m.separation;
        p.step_impulse = T(0);
    }
    out.touching = out.manifold.touching();
    return true;
}

// A convex body resting on level geometry: when every contact of the pair can be re-measured
// (reuse_contact), the triangles near the body are the same as when they were made, and the
// pair skips the mesh narrow phase; its contacts wait in remeasured_ for the merge. A pair
// without contacts is always collided.
template <class T>
bool World<T>::remeasure_mesh_pair(const ProxyPair& pair, T margin, T dt, std::size_t old_begin, std::size_t old_end) {
    if (old_begin == old_end) return false;
    const std::size_t begin = remeasured_.size();
    remeasured_.resize(begin + (old_end - old_begin));
    for (std::size_t o = old_begin; o < old_end; ++o)
        if (!reuse_contact(pair, margin, dt, contacts_[o], remeasured_[begin + (o - old_begin)])) {
            remeasured_.resize(begin);
            return false;
        }
    return true;
}

// Read-only, so pass 2 of the narrow phase runs it for several mesh pairs at once.
template <class T>
void World<T>::mesh_manifolds(const ProxyPair& pair, T margin, T dt, MeshManifolds& out) const {
    const Body<T>& a = bodies_[pair.a];
    const Body<T>& b = bodies_[pair.b];
    const Body<T>& mesh = a.mesh() ? a : b;
    const Body<T>& other = a.mesh() ? b : a;
    out.contacts.clear();
    out.parts.clear();
    // A joint turns the body's path within the step (a flail swung into a post): no triangle is
    // beside its path. Asked only of a body fast enough to sweep (jointed() reads every joint).
    bool held = false, asked = false;
    for (std::uint32_t part = 0; part < other.child_count(); ++part) {
        SpeculativeSweep<T> sweep = speculative_sweep(other, part, mesh, 0, dt);
        if (sweep.active() && !asked) held = jointed(a.mesh() ? pair.b : pair.a), asked = true;
        if (held) sweep = {};
        collide_mesh(*mesh.mesh(), mesh.transform(), other.child_shape(part), other.child_transform(part), margin,
                     settings_.linear_slop, out.contacts, sweep);
        out.parts.resize(out.contacts.size(), part);
    }
}

// A convex part against a mesh may give several manifolds (one per normal it leans on, none of
// them tied to one triangle): each takes over last step's contact of the same part whose normal
// agrees best (within about 8°), so warm starting carries across triangle borders. The mesh
// side's part number is the triangle of the deepest point.
template <class T>
void World<T>::merge_mesh_pair(const ProxyPair& pair, T margin, std::size_t old_begin, std::size_t old_end,
                               const MeshManifolds& fresh_list, std::vector<Contact<T>>& next) {
    const bool mesh_is_a = bodies_[pair.a].mesh() != nullptr;
    old_taken_.assign(old_end - old_begin, 0);
    for (std::size_t i = 0; i < fresh_list.contacts.size(); ++i) {
        const MeshContact<T>& m = fresh_list.contacts[i];
        const std::uint32_t part = fresh_list.parts[i];
        ContactManifold<T> fresh = m.manifold;
        if (!mesh_is_a) {  // the normal goes from A to B
            fresh.normal = -fresh.normal;
            for (int p = 0; p < fresh.count; ++p)
                std::swap(fresh.points[static_cast<std::size_t>(p)].point_a, fresh.points[static_cast<std::size_t>(p)].point_b);
        }
        std::size_t match = old_end;
        T best = T(0.99);
        for (std::size_t o = old_begin; o < old_end; ++o) {
            const Contact<T>& old = contacts_[o];
            if (old_taken_[o - old_begin] || (mesh_is_a ? old.child_b : old.child_a) != part) continue;
            const T agree = dot(old.manifold.normal, fresh.normal);
            if (agree > best) best = agree, match = o;
        }
        if (match != old_end) old_taken_[match - old_begin] = 1;
        next.emplace_back();
        make_contact(pair, mesh_is_a ? m.triangle : part, mesh_is_a ? part : m.triangle, margin,
                     match != old_end ? &contacts_[match] : nullptr, fresh, next.back());
    }
    for (std::size_t o = old_begin; o < old_end; ++o)
        if (!old_taken_[o - old_begin]) end_contact(contacts_[o]);
}

template <class T>
bool World<T>::closes_within_step(const Contact<T>& c, T dt, T struck_speed) const {
    // A point closes when its gap is within what the bodies' relative velocity (and the
    // acceleration of gravity and forces over the step) can cover in dt, or what the active body
    // could cover at twice struck_speed (measure_group_speeds), or within the slop.
    // Conservative on purpose: a wrong "yes" only wakes an island early; a wrong "no" would let
    // the solver treat the sleeper as a wall and swallow the impact (issue 12).
    const Body<T>& a = bodies_[c.a.index];
    const Body<T>& b = bodies_[c.b.index];
    const Vec3<T> relative_acceleration = free_acceleration(b) - free_acceleration(a);
    const T struck_reach = T(2) * struck_speed * dt;
    for (int i = 0; i < c.manifold.count; ++i) {
        const ContactPoint<T>& cp = c.manifold.points[static_cast<std::size_t>(i)];
        const Vec3<T> pa = a.world_point(cp.local_a), pb = b.world_point(cp.local_b);
        const Vec3<T> mid = (pa + pb) * T(0.5);
        const Vec3<T> va = a.linear_velocity_ + cross(a.angular_velocity_, mid - a.position_);
        const Vec3<T> vb = b.linear_velocity_ + cross(b.angular_velocity_, mid - b.position_);
        const T gap = dot(pb - pa, c.manifold.normal);
        const T approach = -dot(vb - va, c.manifold.normal) * dt - dot(relative_acceleration, c.manifold.normal) * dt * dt;
        if (gap <= std::max({approach, struck_reach, T(0)}) + settings_.linear_slop) return true;
    }
    return false;
}

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

/// Islands: dynamic bodies joined by touching (non-sensor) contacts and by joints, as a
/// union–find over body slots in island_parent_ (linear in bodies, contacts and joints). A contact
/// within the slop of touching joins too: either body awake wakes the other (closes_within_step),
/// so apart they would take turns waking each other for ever (two boxes resting 2 mm apart, one
/// dropped a little later than the other, did); joined they share one sleep clock.
template <class T>
void World<T>::build_islands() {
    std::vector<std::uint32_t>& parent = island_parent_;
    parent.resize(bodies_.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto dynamic = [&](std::uint32_t slot) { return bodies_[slot].type_ == BodyType::dynamic; };
    for (const Contact<T>& c : contacts_)
        if (!c.sensor && c.manifold.count > 0 && dynamic(c.a.index) && dynamic(c.b.index) && (c.touching || within_slop(c)))
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

/// On several workers, the solver bodies in order along the axis their centres spread most on: the
/// world hands out bodies, and each colour's rows, in solver order (constraint_graph.hpp), so each
/// worker keeps to one slab of space and the bodies it writes stay in its core's cache across
/// colours and substeps. In slot order a pile dropped in layers has every body written by both
/// workers in every sweep, which made two workers no faster than one (docs/parallel.md). The order
/// only places bodies in memory: rows of one colour share no body, so the result is the same bits
/// in any order, and a counting sort over as many cells along the axis as there are bodies (slot
/// order within a cell) places them as well as an exact sort, in O(n) (sorting the exact places
/// took 0.22 ms a step for 4,000 bodies). One worker keeps slot order and skips it.
template <class T>
void World<T>::order_solver_bodies_in_space() {
    const TaskSystem* tasks = tasks_.get();
    const std::size_t n = solver_order_.size();
    if (tasks == nullptr || tasks->workers() <= 1 || n < 2) return;
    Vec3<T> lo = bodies_[solver_order_[0]].position_, hi = lo;
    for (const std::uint32_t i : solver_order_) lo = min(lo, bodies_[i].position_), hi = max(hi, bodies_[i].position_);
    const Vec3<T> extent = hi - lo;
    const int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
    // All in one place, or too far apart to measure in T: slot order.
    if (!(extent[axis] > T(0) && extent[axis] < ScalarTraits<T>::infinity)) return;
    const T cells_per_metre = static_cast<T>(n) / extent[axis];
    const auto cell_of = [&](std::uint32_t slot) -> std::size_t {
        const T t = (bodies_[slot].position_[axis] - lo[axis]) * cells_per_metre;  // NaN (0 · ∞) goes to cell 0
        return t >= static_cast<T>(n) ? n - 1 : (t > T(0) ? static_cast<std::size_t>(t) : 0);
    };
    solver_cells_.assign(n + 1, 0);
    for (const std::uint32_t i : solver_order_) ++solver_cells_[cell_of(i) + 1];
    for (std::size_t c = 1; c <= n; ++c) solver_cells_[c] += solver_cells_[c - 1];
    solver_sorted_.resize(n);
    for (const std::uint32_t i : solver_order_) solver_sorted_[solver_cells_[cell_of(i)]++] = i;
    solver_order_.swap(solver_sorted_);
}

template <class T>
void World<T>::prepare(T dt) {
    const T h = dt / substeps_per_step();
    last_substep_ = h;
    prepare_solver_bodies(h);
    joint_stage(JointStage::prepare, h);
    prepare_contact_rows(h);
}

/// The solver bodies: every awake dynamic or kinematic body, in space order; slot 0 stands for
/// static ones. h: the substep.
template <class T>
void World<T>::prepare_solver_bodies(T h) {
    solver_bodies_.assign(1, detail::SolverBody<T>{});
    solver_masses_.assign(1, detail::SolverMass<T>{});
    solver_slot_.assign(1, 0);
    integration_.assign(1, detail::BodyIntegration<T>{});
    std::fill(solver_index_.begin(), solver_index_.end(), 0u);
    solver_order_.clear();
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
        const Body<T>& b = bodies_[i];
        if (b.alive_ && b.enabled_ && b.type_ != BodyType::static_body && b.awake_) solver_order_.push_back(i);
    }
    order_solver_bodies_in_space();
    // Solver body k + 1 from solver_order_[k], each independently, so in parallel.
    const auto count = static_cast<std::uint32_t>(solver_order_.size());
    const T step = h * substeps_per_step();
    solver_bodies_.resize(count + std::size_t(1));
    solver_masses_.resize(count + std::size_t(1));
    solver_slot_.resize(count + std::size_t(1));
    integration_.resize(count + std::size_t(1));
    parallel_for(tasks_.get(), count, integrate_range, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t k = begin; k < end; ++k) {
            const std::uint32_t i = solver_order_[k];
            const Body<T>& b = bodies_[i];
            solver_index_[i] = k + 1;
            detail::SolverMass<T>& m = solver_masses_[k + 1];
            m.inv_mass = b.inverse_mass_;
            m.inv_inertia = b.type_ == BodyType::dynamic ? b.inverse_inertia_world() : Mat3<T>::zero();
            solver_slot_[k + 1] = i;
            integration_[k + 1] = integration_constants(b, m, h);
            // Velocities enter the solver within the integrator's caps: any finite velocity is
            // accepted at the door, and a kinematic body at 1e308 m/s made every row it touched
            // NaN (found by the world fuzzer).
            detail::SolverBody<T>& s = solver_bodies_[k + 1];
            s.v = detail::capped_length(b.linear_velocity_, integration_[k + 1].max_speed);
            s.w = detail::capped_spin(b.angular_velocity_, integration_[k + 1].spin_cap, Quat<T>::identity(), b.orientation_);
            m.spins_far = length_squared(s.w) * step * step > detail::kFarTurn<T> * detail::kFarTurn<T>;
        }
    });
    stats_.awake_bodies = count;
}

/// The contact rows of the touching contacts with a body in the solver, coloured and packed into
/// lanes. h: the substep.
template <class T>
void World<T>::prepare_contact_rows(T h) {
    const T contact_hertz = detail::capped_contact_hertz(settings_, h);
    using detail::Softness;
    const Softness<T> soft = Softness<T>::make(contact_hertz, settings_.contact_damping_ratio, h);
    const T static_hertz = std::min(contact_hertz * settings_.static_contact_hertz_scale, T(0.25) / h);
    const Softness<T> soft_static = Softness<T>::make(static_hertz, settings_.static_contact_damping_ratio, h);
    const T step = h * substeps_per_step();
    // Which contacts get a row (in contact order), then the rows, independently of each other.
    row_contacts_.clear();
    bouncing_rows_.clear();
    for (std::uint32_t m = 0; m < contacts_.size(); ++m) {
        const Contact<T>& contact = contacts_[m];
        if (contact.sensor || contact.manifold.count == 0) continue;
        const std::uint32_t ia = solver_index_[contact.a.index], ib = solver_index_[contact.b.index];
        if (ia == 0 && ib == 0) continue;  // both asleep or static
        // A sleeper left asleep by wake_touched_islands cannot be reached this step; solving
        // against it as a static stand-in would stop the mover dead (issue 12), so skip the row.
        if ((ia == 0 && bodies_[contact.a.index].type_ == BodyType::dynamic) ||
            (ib == 0 && bodies_[contact.b.index].type_ == BodyType::dynamic))
            continue;
        if (seam_ghost(contact)) continue;
        if (contact.restitution != T(0)) bouncing_rows_.push_back(static_cast<std::uint32_t>(row_contacts_.size()));
        row_contacts_.push_back(m);
        stats_.contact_points += static_cast<std::size_t>(contact.manifold.count);
    }
    constraints_.resize(row_contacts_.size());
    std::atomic<bool> turning{false};  // some row turns its levers (contact_row)
    std::atomic<bool> impact{false};   // some point approaches faster than the impact sweeps' threshold
    parallel_for(
        tasks_.get(), static_cast<std::uint32_t>(row_contacts_.size()), row_range, [&](std::uint32_t begin, std::uint32_t end) {
            bool turns = false, fast = false;
            for (std::uint32_t r = begin; r < end; ++r) {
                const detail::ContactConstraint<T>& c = constraints_[r];
                contact_row(row_contacts_[r], soft, soft_static, step, constraints_[r]);
                turns = turns || c.turns_a || c.turns_b || c.slips;
                for (int i = 0; i < c.count; ++i)
                    fast = fast || c.points[static_cast<std::size_t>(i)].relative_velocity < -T(detail::impact_sweep_speed);
            }
            if (turns) turning.store(true, std::memory_order_relaxed);
            if (fast) impact.store(true, std::memory_order_relaxed);
        });
    // The fastest approach, found again in row order only when some point is past the threshold
    // (a rare step): a maximum, so the same whichever worker saw it first.
    fastest_approach_ = T(0);
    if (impact.load())
        for (const detail::ContactConstraint<T>& c : constraints_)
            for (int i = 0; i < c.count; ++i)
                fastest_approach_ = std::max(fastest_approach_, -c.points[static_cast<std::size_t>(i)].relative_velocity);
    share_support_stiffness(static_hertz, h);
    wide_rows_.build(constraints_, solver_masses_, turning.load(), tasks_.get());
    stats_.colours = wide_rows_.colours_used();
    stats_.overflow_contacts = wide_rows_.overflow_rows();
}

// The seam between two separate static bodies laid edge to edge (box tiles of a floor): a body
// sliding on one towards the seam gets a contact with the side face of the next, square to the
// face it slides on and against its motion, whose points on the body all lie in that face's
// plane. That side face is covered by the first body; only Box2D's chain shapes or Jolt's
// enhanced internal edge removal (off by default) know it. Such a contact gets no row while the body
// touches the first body's face there (docs/meshes.md, "Separate bodies edge to edge"): a 0.5 m
// cube at 5 m/s across 1 m tiles stopped after 0.65 m of 2.12 and hopped 11 cm. The second body
// must itself end within linear_slop of that plane: a wall or a step keeps its row even against
// a body thinner than linear_slop (a 3 mm plate, a 4 mm ball, whose every point is near the
// plane; without this test they went through a 2 cm static wall at 3-6 m/s).
template <class T>
bool World<T>::seam_ghost(const Contact<T>& c) const {
    const bool a_static = bodies_[c.a.index].type_ == BodyType::static_body;
    if (a_static == (bodies_[c.b.index].type_ == BodyType::static_body)) return false;
    const std::uint32_t mover = a_static ? c.b.index : c.a.index;
    const Body<T>& body = bodies_[mover];
    if (body.type_ != BodyType::dynamic || c.manifold.count == 0) return false;
    const T slop = settings_.linear_slop;
    // The contact's normal from the static side to the mover, its points on the mover.
    const auto from_static = [&](const Contact<T>& k) { return k.a.index == mover ? -k.manifold.normal : k.manifold.normal; };
    const auto on_mover = [&](const Contact<T>& k, int i) {
        const ContactPoint<T>& p = k.manifold.points[static_cast<std::size_t>(i)];
        return k.a.index == mover ? body.world_point(p.local_a) : body.world_point(p.local_b);
    };
    T deepest = -ScalarTraits<T>::infinity;
    for (int i = 0; i < c.manifold.count; ++i) deepest = std::max(deepest, c.manifold.points[static_cast<std::size_t>(i)].depth);
    if (!(deepest <= slop)) return false;  // a real overlap
    const Vec3<T> n = from_static(c);
    const std::uint32_t obstacle = a_static ? c.a.index : c.b.index;
    const std::uint32_t end = contact_start_[mover], begin = mover == 0 ? 0 : contact_start_[mover - 1];
    for (std::uint32_t k = begin; k < end; ++k) {
        const Contact<T>& face = contacts_[contact_list_[k]];
        if (&face == &c || face.sensor || face.manifold.count == 0) continue;  // a trigger holds nothing up
        const std::uint32_t other = face.a.index == mover ? face.b.index : face.a.index;
        if (bodies_[other].type_ != BodyType::static_body) continue;
        const Vec3<T> n1 = from_static(face);
        if (!(std::abs(dot(n1, n)) < T(0.1))) continue;  // a side face square to the face it slides on
        T face_depth = -ScalarTraits<T>::infinity;
        for (int i = 0; i < face.manifold.count; ++i)
            face_depth = std::max(face_depth, face.manifold.points[static_cast<std::size_t>(i)].depth);
        if (!(face_depth >= -slop)) continue;  // not resting on that face
        // A point of the face's plane: a point on the mover lies `depth` below it along n1.
        const Vec3<T> on_face = on_mover(face, 0) + n1 * face.manifold.points[0].depth;
        bool in_plane = true;
        for (int i = 0; i < c.manifold.count && in_plane; ++i) in_plane = std::abs(dot(on_mover(c, i) - on_face, n1)) <= slop;
        if (in_plane && dot(highest_point(obstacle, n1, mover) - on_face, n1) <= slop) return true;
    }
    return false;
}

/// The point of a body's geometry farthest along the world direction d, near the body in slot
/// `near`: its shape's support point; for a compound, the highest of its parts' support points;
/// for a mesh, the highest vertex of its triangles under `near`'s broad-phase box (a post or a
/// hill elsewhere in a terrain chunk is not in the way), or the corner of its own bounding box
/// (not bounds_, the broad phase's, which the speculative margin makes 2 cm taller: no floor of
/// mesh or compound tiles had a seam then).
template <class T>
Vec3<T> World<T>::highest_point(std::uint32_t slot, const Vec3<T>& d, std::uint32_t near) const {
    const Body<T>& b = bodies_[slot];
    if (const Shape<T>* shape = b.convex_shape()) return b.world_point(support(*shape, b.local_vector(d)));
    const auto higher = [&](Vec3<T>& best, const Vec3<T>& p) {
        if (dot(p, d) > dot(best, d)) best = p;
    };
    if (b.compound()) {
        const auto part_top = [&](std::uint32_t i) {
            const Transform<T> pose = b.child_transform(i);
            return pose.apply(support(b.child_shape(i), inverse_rotate(pose.orientation, d)));
        };
        Vec3<T> best = part_top(0);
        for (std::uint32_t i = 1; i < b.child_count(); ++i) higher(best, part_top(i));
        return best;
    }
    const Aabb<T> own = b.world_bounds();
    Vec3<T> best{d.x >= T(0) ? own.max.x : own.min.x, d.y >= T(0) ? own.max.y : own.min.y, d.z >= T(0) ? own.max.z : own.min.z};
    if (const MeshShape<T>* mesh = b.mesh()) {
        const Transform<T> pose = b.transform(), back = inverse(pose);
        const Aabb<T>& there = bounds_[near];
        const Mat3<T> r = to_matrix(back.orientation);
        const Aabb<T> local =
            Aabb<T>::from_center(back.apply(there.center()), Mat3<T>{abs(r[0]), abs(r[1]), abs(r[2])} * there.half_extents());
        bool any = false;
        Vec3<T> top{};
        for_each_triangle(*mesh, local, [&](std::uint32_t, const MeshTriangle<T>& t) {
            for (const Vec3<T>& v : t.v) {
                const Vec3<T> p = pose.apply(v);
                if (!any) top = p, any = true;
                else higher(top, p);
            }
        });
        if (any) best = top;
    }
    return best;
}

/// Every contact point is a spring of stiffness m_eff·ω² (m_eff its normal_mass), so a body on
/// static or kinematic ground rings on its supports at ω√λ (support_stiffness.hpp): a box on one
/// face at √1.5 ω, a table on four legs at √6.8 ω, beyond what one sweep per substep damps; it
/// vibrated and walked across the floor (docs/solver.md, "Support stiffness"). A body held by two
/// or more manifolds there gets ω·√(limit/λ) on each of those rows when its λ is above the limit:
/// support_stiffness_limit (1.5, a box on its face), and no more than ωh = support_omega_h_limit
/// (0.8) on that fastest mode. One manifold is one flat patch, which stays near 1.5 (a cube 1.5,
/// a thin square slab 12/7) and is not measured.
template <class T>
void World<T>::share_support_stiffness(T static_hertz, T h) {
    if (settings_.solver != SolverMode::soft_step) return;
    // The dynamic side of a row whose other side is static or kinematic, else 0. Read from the
    // solver bodies' integration constants (a flag per solver body, as the rows index them),
    // not from the bodies and contacts (a cache miss each: 3 % of the 5,050-box pyramid's step).
    // Slot 0 stands for static bodies (a row never has a sleeping dynamic one there: prepare
    // skips those), and its constants are a default's, which say dynamic.
    const auto moves = [&](std::uint32_t slot) { return slot != 0 && integration_[slot].dynamic; };
    const auto supported = [&](const detail::ContactConstraint<T>& c) -> std::uint32_t {
        const bool a_moves = moves(c.a);
        if (a_moves == moves(c.b)) return 0;
        return a_moves ? c.a : c.b;
    };
    // Each body's support rows side by side: support_begin_[b] … support_begin_[b + 1].
    const std::size_t n = solver_bodies_.size();
    support_begin_.assign(n + 1, 0);
    support_manifolds_.assign(n, 0);
    for (const detail::ContactConstraint<T>& c : constraints_)
        if (const std::uint32_t body = supported(c)) {
            support_begin_[body + 1] += static_cast<std::uint32_t>(c.count);
            ++support_manifolds_[body];
        }
    for (std::size_t b = 1; b <= n; ++b) support_begin_[b] += support_begin_[b - 1];
    support_rows_.resize(support_begin_[n]);
    support_fill_.assign(support_begin_.begin(), support_begin_.end() - 1);
    for (const detail::ContactConstraint<T>& c : constraints_)
        if (const std::uint32_t body = supported(c); body != 0 && support_manifolds_[body] >= 2)  // the rest are not measured
            for (int i = 0; i < c.count; ++i) {
                const detail::ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
                const Vec3<T>& r = body == c.a ? p.r_a : p.r_b;
                support_rows_[support_fill_[body]++] = {c.normal, cross(r, c.normal), p.normal_mass};
            }
    support_share_.assign(n, T(1));
    const T wh = T(2) * ScalarTraits<T>::pi * static_hertz * h;  // of one static row
    const T limit = std::min(T(detail::support_stiffness_limit),
                             T(detail::support_omega_h_limit * detail::support_omega_h_limit) / (wh * wh));
    for (std::size_t b = 1; b < n; ++b) {
        if (support_manifolds_[b] < 2) continue;
        const T lambda = detail::support_stiffness(support_rows_.data() + support_begin_[b],
                                                   support_begin_[b + 1] - support_begin_[b], solver_masses_[b]);
        if (lambda > limit) support_share_[b] = std::sqrt(limit / lambda);
    }
    for (detail::ContactConstraint<T>& c : constraints_) {
        const std::uint32_t body = supported(c);
        if (body == 0 || !(support_share_[body] < T(1))) continue;
        c.softness = detail::Softness<T>::make(static_hertz * support_share_[body], settings_.static_contact_damping_ratio, h);
    }
}

/// Writes c, the contact row of contacts_[m] (prepare): anchors, effective masses, softness and
/// the approach speed for restitution (at the start of the step; the substeps add gravity's share
/// up to the impact), from the bodies' state at the start of the step. Every number of c is
/// written in place, the unused point slots zeroed: a row built by value was zeroed whole and
/// then copied into constraints_ (352 bytes in float, 696 in double; 1 % of a pyramid's step).
template <class T>
void World<T>::contact_row(std::uint32_t m, const detail::Softness<T>& soft, const detail::Softness<T>& soft_static, T step,
                           detail::ContactConstraint<T>& c) {
    Contact<T>& contact = contacts_[m];
    const Body<T>& a = bodies_[contact.a.index];
    const Body<T>& b = bodies_[contact.b.index];
    c.a = solver_index_[contact.a.index];
    c.b = solver_index_[contact.b.index];
    const detail::SolverMass<T>& sa = solver_masses_[c.a];
    const detail::SolverMass<T>& sb = solver_masses_[c.b];
    const detail::SolverBody<T>& va = solver_bodies_[c.a];
    const detail::SolverBody<T>& vb = solver_bodies_[c.b];
    c.manifold = m;
    c.normal = contact.manifold.normal;
    c.t1 = any_perpendicular(c.normal);
    c.t2 = cross(c.normal, c.t1);
    c.friction = contact.friction;
    c.restitution = contact.restitution;
    c.normal_acceleration = dot(free_acceleration(b) - free_acceleration(a), c.normal);
    c.softness = (a.type_ == BodyType::dynamic && b.type_ == BodyType::dynamic) ? soft : soft_static;
    if (settings_.solver == SolverMode::baumgarte) c.softness = detail::Softness<T>{};
    c.count = contact.manifold.count;
    const Vec3<T> xa = a.position_, xb = b.position_;
    Vec3<T> centre_a{}, centre_b{};
    for (int i = 0; i < c.count; ++i) {
        const ContactPoint<T>& cp = contact.manifold.points[static_cast<std::size_t>(i)];
        detail::ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
        const Vec3<T> pa = a.world_point(cp.local_a), pb = b.world_point(cp.local_b);
        centre_a += pa;
        centre_b += pb;
        // Each body's lever to its own anchor. For points of closest features pb − pa lies along
        // n and the levers' n-moments equal those of the midpoint; for points of a first touch
        // (at_first_touch) the anchors are apart across n by the travel still to come, and a
        // common point would put a lever across n on a ball struck through its centre.
        p.r_a = pa - xa;
        p.r_b = pb - xb;
        const T separation = dot(pb - pa, c.normal);
        p.adjusted_separation = separation - dot(p.r_b - p.r_a, c.normal);
        const Vec3<T> rna = cross(p.r_a, c.normal), rnb = cross(p.r_b, c.normal);
        const T k = sa.inv_mass + sb.inv_mass + dot(rna, sa.inv_inertia * rna) + dot(rnb, sb.inv_inertia * rnb);
        p.normal_mass = k > T(0) ? T(1) / k : T(0);
        p.normal_impulse = settings_.warm_starting ? cp.normal_impulse : T(0);
        p.max_normal_impulse = T(0);
        p.step_impulse = T(0);
        p.relative_velocity = dot(vb.velocity_at(p.r_b) - va.velocity_at(p.r_a), c.normal);
        p.rebound = T(0);
    }
    for (int i = c.count; i < 4; ++i) c.points[static_cast<std::size_t>(i)] = detail::ContactConstraintPoint<T>{};
    // Friction and twist act at each body's own patch centre too: at the midpoint, a ball that
    // lands from a step away was turned about a lever half that step longer than its radius (at
    // 5 m/s and 60 Hz, 8 % more spin than the friction's impulse gives, and it left the bounce
    // rolling about a point below the floor).
    c.rc_a = centre_a / static_cast<T>(c.count) - xa;
    c.rc_b = centre_b / static_cast<T>(c.count) - xb;
    // The 2×2 tangent effective mass K and its inverse.
    const Vec3<T> a1 = cross(c.rc_a, c.t1), a2 = cross(c.rc_a, c.t2), b1 = cross(c.rc_b, c.t1), b2 = cross(c.rc_b, c.t2);
    const T base = sa.inv_mass + sb.inv_mass;
    const T k11 = base + dot(a1, sa.inv_inertia * a1) + dot(b1, sb.inv_inertia * b1);
    const T k12 = dot(a1, sa.inv_inertia * a2) + dot(b1, sb.inv_inertia * b2);
    const T k22 = base + dot(a2, sa.inv_inertia * a2) + dot(b2, sb.inv_inertia * b2);
    const T det = k11 * k22 - k12 * k12;
    c.k11 = c.k12 = c.k22 = T(0);
    if (det > T(0)) {
        c.k11 = k22 / det;
        c.k12 = -k12 / det;
        c.k22 = k11 / det;
    }
    const T kt = dot(c.normal, (sa.inv_inertia + sb.inv_inertia) * c.normal);
    c.twist_mass = kt > T(0) ? T(1) / kt : T(0);
    const detail::Roundness<T> round_a = detail::roundness(a, contact.child_a, c.normal);
    const detail::Roundness<T> round_b = detail::roundness(b, contact.child_b, c.normal);
    c.round_a = round_a.rolling;
    c.round_b = round_b.rolling;
    // A turning side's flat surface carries its contact round with it (a round one turns under
    // a contact that stays put): its levers turn, and the row takes its chord slip, a kinematic
    // turntable's or a dynamic disc's on a hinge alike. Only where the two bodies turn together
    // (within a tenth), as a rider does with what carries it: bodies tumbling against each other
    // or on the ground took the turning rows too, and dropped piles stepped 15-20 % slower.
    const T h = step / substeps_per_step();
    const T spin_sq = std::max(length_squared(va.w), length_squared(vb.w));
    const bool together = length_squared(vb.w - va.w) <= T(0.01) * spin_sq;
    const Vec3<T> slip_a = together && c.round_a == T(0) ? detail::chord_slip(va.w, c.rc_a, h) : Vec3<T>{};
    const Vec3<T> slip_b = together && c.round_b == T(0) ? detail::chord_slip(vb.w, c.rc_b, h) : Vec3<T>{};
    const bool carries_a = length_squared(slip_a) > detail::kChordSlip<T> * detail::kChordSlip<T>;
    const bool carries_b = length_squared(slip_b) > detail::kChordSlip<T> * detail::kChordSlip<T>;
    c.turns_a = carries_a || (sa.spins_far && c.round_a == T(0) && detail::levers_turn_far(c, va.w, step, false));
    c.turns_b = carries_b || (sb.spins_far && c.round_b == T(0) && detail::levers_turn_far(c, vb.w, step, true));
    Vec3<T> slip{};
    if (carries_b) slip += slip_b;
    if (carries_a) slip -= slip_a;
    c.slip_1 = dot(slip, c.t1);
    c.slip_2 = dot(slip, c.t2);
    c.slips = c.slip_1 != T(0) || c.slip_2 != T(0);
    c.twist_lever = twist_lever(contact, round_a.face, round_b.face);
    c.friction_1 = c.friction_2 = c.twist_impulse = T(0);
    if (settings_.warm_starting) {
        c.friction_1 = dot(contact.manifold.friction_impulse, c.t1);
        c.friction_2 = dot(contact.manifold.friction_impulse, c.t2);
        c.twist_impulse = contact.manifold.twist_impulse;
    }
    c.bounce_impulse = T(0);
}

/// m: the lever ℓ of a manifold's twist friction, µ ℓ Σλ_n, under a uniform pressure over its
/// patch (contact/patch.hpp): the polygon its points' anchors on A span, kept in the contact
/// while they stay, or the whole of a round face (a cylinder's cap, a cone's base, of radius
/// face_a or face_b) when the points lie on that face's rim: four points kept of the rim's
/// polygon span a square of 0.81 times the disc's lever.
template <class T>
T World<T>::twist_lever(Contact<T>& contact, T face_a, T face_b) {
    const Manifold<T>& m = contact.manifold;
    std::array<Vec3<T>, 4> anchors{};
    for (std::size_t i = 0; i < static_cast<std::size_t>(m.count); ++i) anchors[i] = m.points[i].local_a;
    const T face = face_a > T(0) && face_b > T(0) ? std::min(face_a, face_b) : std::max(face_a, face_b);
    if (m.count >= 3 && face > T(0)) {
        Vec3<T> centre{};
        for (std::size_t i = 0; i < static_cast<std::size_t>(m.count); ++i) centre += anchors[i];
        centre /= static_cast<T>(m.count);
        bool on_rim = true;
        for (std::size_t i = 0; i < static_cast<std::size_t>(m.count); ++i)
            on_rim = on_rim && length_squared(anchors[i] - centre) >= T(0.81) * face * face;
        if (on_rim) return T(2) / T(3) * face;
    }
    const std::uint64_t key = detail::patch_key(anchors, m.count);
    if (key != contact.twist_lever_key) {
        contact.twist_lever = detail::patch_twist_lever(anchors, m.count);
        contact.twist_lever_key = key;
    }
    return contact.twist_lever;
}

/// The spin caps of `b` over steps of dt (detail::SpinCap): the surface of a sphere, capsule,
/// cylinder or cone stays in place as it turns about its centre or axis, so only that spin may
/// exceed max_rotation_per_step, up to the speed cap at its rim.
template <class T>
detail::SpinCap<T> World<T>::spin_cap(const Body<T>& b, T dt) const {
    detail::SpinCap<T> cap;
    cap.tumble = settings_.max_rotation_per_step / dt;
    cap.roll = cap.tumble;
    const Shape<T>* shape = b.convex_shape();
    if (!shape) return cap;
    const auto rim = [&](detail::SpinSymmetry symmetry, T radius) {
        cap.symmetry = symmetry;
        cap.roll = std::max(cap.tumble, speed_limit(b) / radius);
    };
    if (const auto* sphere = std::get_if<Sphere<T>>(shape)) rim(detail::SpinSymmetry::all, sphere->radius());
    else if (const auto* capsule = std::get_if<Capsule<T>>(shape)) rim(detail::SpinSymmetry::axis_y, capsule->radius());
    else if (const auto* cylinder = std::get_if<Cylinder<T>>(shape)) rim(detail::SpinSymmetry::axis_y, cylinder->radius());
    else if (const auto* cone = std::get_if<Cone<T>>(shape)) rim(detail::SpinSymmetry::axis_y, cone->radius());
    return cap;
}

/// What integrating body `b` (solver state `s`) over substeps of h needs, constant for the step:
/// read once here rather than from the body every substep.
template <class T>
detail::BodyIntegration<T> World<T>::integration_constants(const Body<T>& b, const detail::SolverMass<T>& s, T h) const {
    detail::BodyIntegration<T> in;
    in.dynamic = b.type_ == BodyType::dynamic;
    in.acceleration = free_acceleration(b);  // solver bodies are awake
    // A torque accepted in one orientation may overflow I⁻¹τ in another: then ±inf per component
    // (never inf − inf), which integrate_velocity's caps bring back to a finite spin.
    in.angular_impulse_rate = detail::product_without_nan(s.inv_inertia, b.torque_);
    in.inertia_local = &b.inertia_local_;
    in.orientation0 = b.orientation_;
    in.gyroscopic = !b.isotropic_;
    in.linear_damping = b.linear_damping_;
    in.angular_damping = b.angular_damping_;
    in.spin_cap = spin_cap(b, h * substeps_per_step());
    in.max_speed = speed_limit(b);
    return in;
}

// A joint's bodies turn through the substeps, and a body's world inertia turns with it (Δq:
// R I₀⁻¹ Rᵀ); only an anisotropic one's changes. Frozen at the step's start, a disc spinning at
// 200 rad/s on a ball joint, precessing at 0.74 rad/s, met its joint's torque with the inertia of
// an axis up to 0.7° behind, which fed its spin 0.35 % a second at any substep count.
// Each row also takes its anchors' chord pull for the coming substep h (detail::chord_pull): the
// position update carries an anchor along the chord of its body's turn, not along the tangent
// ω × r the row holds, and where ω is not square to the lever the chord's pull towards the axis
// has a part off the lever, which the relax pass turned into a steady loss: that disc's axle, at
// 0.3 m, sank 16° in 4 s (about 3° a second at any spin), now 3.5° (docs/solver.md, "A gyroscope
// on a ball joint").
template <class T>
void World<T>::turn_joint_inertias(T h) {
    const auto turned = [&](std::uint32_t k) {
        const Mat3<T> r = to_matrix(solver_bodies_[k].dq);
        return r * solver_masses_[k].inv_inertia * transpose(r);
    };
    const auto pull = [&](std::uint32_t k, const Vec3<T>& r0) {
        const detail::SolverBody<T>& s = solver_bodies_[k];
        return k == 0 ? Vec3<T>{} : detail::chord_pull(s.w, rotate(s.dq, r0), h);
    };
    for (detail::JointConstraint<T>& c : joint_rows_) {
        c.pull = pull(c.b, c.r_b0) - pull(c.a, c.r_a0);
        if (c.a != 0 && integration_[c.a].gyroscopic) c.mass_a.inv_inertia = turned(c.a);
        if (c.b != 0 && integration_[c.b].gyroscopic) c.mass_b.inv_inertia = turned(c.b);
    }
}

template <class T>
void World<T>::solve(T dt) {
    const bool soft = settings_.solver == SolverMode::soft_step;
    const int substeps = soft ? settings_.substeps : 1;
    const T h = dt / static_cast<T>(substeps);
    detail::SolvePass<T> pass{
        T(1) / h, true, settings_.solver, settings_.baumgarte, settings_.linear_slop, settings_.max_push_out_speed};
    for (int sub = 0; sub < substeps; ++sub) solve_substep(sub, h, pass);
    wide_rows_.unpack(constraints_, tasks_.get());
    rebound_cap_.before(constraints_, bouncing_rows_, joint_rows_, solver_bodies_, integration_, settings_.restitution_threshold);
    detail::apply_restitution(constraints_, bouncing_rows_, solver_bodies_, solver_masses_, settings_.restitution_threshold, h);
    rebound_cap_.after(
        constraints_, solver_bodies_, solver_masses_, integration_,
        [&](std::uint32_t k) {
            const Body<T>& b = bodies_[solver_slot_[k]];
            return std::make_pair(b.linear_velocity_, b.angular_velocity_);
        },
        h);
    joint_stage(JointStage::cap, h);
}

/// Substep `sub` of solve (h long): gravity and forces, warm start, the biased sweeps, the
/// position update, then the relax sweeps.
template <class T>
void World<T>::solve_substep(int sub, T h, detail::SolvePass<T>& pass) {
    const bool soft = settings_.solver == SolverMode::soft_step;
    const auto movers = static_cast<std::uint32_t>(solver_bodies_.size() - 1);
    parallel_for(tasks_.get(), movers, integrate_range, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t i = begin + 1; i <= end; ++i)
            if (integration_[i].dynamic)
                detail::integrate_velocity(solver_bodies_[i], integration_[i], h);  // kinematic: the user's
    });
    joint_stage(JointStage::turn_inertias, h);
    if (!bouncing_rows_.empty()) wide_rows_.take_approach(solver_bodies_, h, tasks_.get());
    // Without warm_starting a step starts from zero impulses (prepare), but each later substep
    // still starts from the one before, as Box2D v3 does: the accumulated impulses are the ones
    // the rows clamp and the events sum, so left unapplied they clamped the wrong totals (a row
    // could pull) and a resting box reported (n + 1) / 2 times its weight over n substeps.
    if (settings_.warm_starting || sub > 0) {
        joint_stage(JointStage::warm_start, h);
        wide_rows_.warm_start(solver_bodies_, tasks_.get());
    }
    // The first substep relaxes longer: its warm start applies the last step's impulses, and
    // where a load vanished between steps (a support released, a body removed) one sweep a
    // substep sheds them too slowly along a stack; the bodies it held are pushed apart and fly
    // off at a steady speed (docs/solver.md, "Releasing a load").
    const int relax = soft && sub == 0 ? settings_.first_relax_iterations : settings_.relax_iterations;
    pass.use_bias = true;
    // More sweeps in a step that brings a very fast impact (settings.hpp, detail::biased_sweeps).
    const int sweeps = detail::biased_sweeps(settings_.velocity_iterations, fastest_approach_);
    for (int it = 0; it < sweeps; ++it) {
        // The substep's last pass adds each point's impulse to its step total (for events
        // and restitution), inside the solve so that each worker does it for its own rows.
        pass.last_of_substep = relax == 0 && it + 1 == sweeps;
        // Joints after contacts: a limb's limit then answers the impulse its landing just took
        // (before them, a ragdoll landed 4.5° past a cone at 8 substeps; docs/solver.md).
        wide_rows_.solve(solver_bodies_, pass, tasks_.get());
        joint_stage(JointStage::solve, h);
    }
    parallel_for(tasks_.get(), movers, integrate_range, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t i = begin + 1; i <= end; ++i) detail::integrate_position(solver_bodies_[i], integration_[i], h);
    });
    joint_stage(JointStage::turn_inertias, h);
    pass.use_bias = false;
    // Joints relax in the last relax_iterations of these sweeps only: the first substep's extra
    // sweeps are for stored contact impulses (with the joints in all of them, a door still
    // swung at 0.024 rad/s off its stop; in the first of them, a ragdoll landed 4.0° past a cone).
    const int joints_from = relax - settings_.relax_iterations;
    for (int it = 0; it < relax; ++it) {
        pass.last_of_substep = it + 1 == relax;
        if (it >= joints_from) joint_stage(JointStage::relax, h);
        wide_rows_.solve(solver_bodies_, pass, tasks_.get());
    }
    solver_bodies_[0] = detail::SolverBody<T>{};
}

template <class T>
void World<T>::finish() {
    discard_overflowed_solve();
    parallel_for(tasks_.get(), static_cast<std::uint32_t>(constraints_.size()), finish_range,
                 [&](std::uint32_t begin, std::uint32_t end) {
                     for (std::uint32_t r = begin; r < end; ++r) {
                         const detail::ContactConstraint<T>& c = constraints_[r];
                         Manifold<T>& m = contacts_[c.manifold].manifold;
                         for (int i = 0; i < c.count; ++i) {
                             const detail::ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
                             m.points[static_cast<std::size_t>(i)].normal_impulse = p.normal_impulse;
                             m.points[static_cast<std::size_t>(i)].max_normal_impulse = p.max_normal_impulse;
                             m.points[static_cast<std::size_t>(i)].step_impulse = p.step_impulse;
                             // A speculative contact that pushed this step touched: the impact happens in the
                             // step that stops the bodies, before they overlap.
                             if (p.step_impulse > T(0)) contacts_[c.manifold].touching = true;
                         }
                         m.friction_impulse = c.t1 * c.friction_1 + c.t2 * c.friction_2;
                         m.twist_impulse = c.twist_impulse;
                     }
                 });
    const auto movers = static_cast<std::uint32_t>(solver_bodies_.size() - 1);
    parallel_for(tasks_.get(), movers, finish_range, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t i = begin + 1; i <= end; ++i) {
            Body<T>& b = bodies_[solver_slot_[i]];
            const detail::SolverBody<T>& s = solver_bodies_[i];
            b.position_ += s.dp;
            b.orientation_ = normalized(s.dq * b.orientation_);
            b.linear_velocity_ = s.v;
            b.angular_velocity_ = s.w;
            b.force_ = Vec3<T>::zero();
            b.torque_ = Vec3<T>::zero();
        }
    });
}

/// The last line of defence against the range of T (docs/robustness.md, "Range of T"): inputs
/// that are each accepted (a fast body at 10³⁰ m/s, a shape 10²⁵ m across, a restitution of 1)
/// can still multiply past the largest T in a contact or joint row, and one inf − inf spreads
/// NaN through an island. A body whose solver state is not finite after the step keeps its
/// start-of-step velocity and does not move this step; the impulses of the rows that
/// touched it are dropped, so that next step's warm start does not bring the overflow back.
/// Never taken by a step whose values stay within the documented range.
template <class T>
void World<T>::discard_overflowed_solve() {
    bool overflowed = false;
    for (std::size_t i = 1; i < solver_bodies_.size(); ++i) {
        detail::SolverBody<T>& s = solver_bodies_[i];
        if (is_finite(s.v) && is_finite(s.w) && is_finite(s.dp) && is_finite(s.dq)) continue;
        const Body<T>& b = bodies_[solver_slot_[i]];
        s.v = b.linear_velocity_;  // finite: checked where it entered
        s.w = b.angular_velocity_;
        s.dp = Vec3<T>::zero();
        s.dq = Quat<T>::identity();
        overflowed = true;
    }
    if (!overflowed) return;
    for (detail::ContactConstraint<T>& c : constraints_) {
        bool finite = std::isfinite(c.friction_1) && std::isfinite(c.friction_2) && std::isfinite(c.twist_impulse);
        for (int i = 0; i < c.count; ++i) finite = finite && std::isfinite(c.points[static_cast<std::size_t>(i)].step_impulse);
        if (finite) continue;
        for (int i = 0; i < c.count; ++i) {
            detail::ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
            p.normal_impulse = p.max_normal_impulse = p.step_impulse = T(0);
        }
        c.friction_1 = c.friction_2 = c.twist_impulse = T(0);
    }
    for (Joint<T>& j : joints_) {
        if (is_finite(j.linear_impulse) && is_finite(j.angular_impulse) && std::isfinite(j.axial_impulse) &&
            std::isfinite(j.motor_impulse) && std::isfinite(j.swing_impulse))
            continue;
        j.linear_impulse = j.angular_impulse = Vec3<T>::zero();
        j.axial_impulse = j.motor_impulse = j.swing_impulse = T(0);
    }
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

/// An island that slides (World::sliding) or touches a moving kinematic body stays awake: its
/// least clock is set back to 0. The slide is looked at only where an awake island would
/// otherwise sleep now, rarely a step.
template <class T>
void World<T>::keep_moving_islands_awake() {
    std::vector<T>& island_min = island_sleep_time_;
    const auto would_sleep = [&](std::uint32_t i) {
        const Body<T>& b = bodies_[i];
        return b.type_ == BodyType::dynamic && b.awake_ && clock_done(island_min[island_root(i)]);
    };
    for (const Contact<T>& c : contacts_) {
        if (!c.touching) continue;
        if ((would_sleep(c.a.index) || would_sleep(c.b.index)) && sliding(c))
            for (const std::uint32_t i : {c.a.index, c.b.index})
                if (bodies_[i].type_ == BodyType::dynamic) island_min[island_root(i)] = T(0);
        for (const auto& [k, d] : {std::pair{c.a.index, c.b.index}, std::pair{c.b.index, c.a.index}}) {
            const Body<T>& kin = bodies_[k];
            if (kin.type_ == BodyType::kinematic &&
                (length_squared(kin.linear_velocity_) > T(0) || length_squared(kin.angular_velocity_) > T(0)))
                island_min[island_root(d)] = T(0);
        }
    }
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
    // the slop and are not coming apart: an island joins a body within the slop (build_islands),
    // which shares its clock but takes no force from it, and a ball drifting off at 5 mm/s, 2 mm
    // from a box resting on the floor (gravity 0), froze with the box.
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

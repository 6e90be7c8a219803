// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The solve of a step (world.hpp, step): solver bodies in order, contact rows prepared (anchors,
// effective masses, softness, restitution, support stiffness, twist levers), the substeps
// (integrate, warm start, solve, relax), restitution, and the results written back. Included at
// the end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

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
// Each row also takes its anchors' chord slip for the coming substep h (detail::chord_slip): the
// position update carries an anchor along the chord of its body's turn, not along the tangent
// ω × r the row holds. Where ω is not square to the lever the chord's pull towards the axis has
// a part off the lever, which the relax pass turned into a steady loss: that disc's axle, at
// 0.3 m, sank 16° in 4 s (about 3° a second at any spin), now 3.2° (docs/solver.md, "A gyroscope
// on a ball joint"). The chord's shortening along the tangent counts too: without it a body
// whirled round a joint spun itself up (chord_slip).
template <class T>
void World<T>::turn_joint_inertias(T h) {
    const auto turned = [&](std::uint32_t k) {
        const Mat3<T> r = to_matrix(solver_bodies_[k].dq);
        return r * solver_masses_[k].inv_inertia * transpose(r);
    };
    const auto slip = [&](std::uint32_t k, const Vec3<T>& r0) {
        const detail::SolverBody<T>& s = solver_bodies_[k];
        return k == 0 ? Vec3<T>{} : detail::chord_slip(s.w, rotate(s.dq, r0), h);
    };
    for (detail::JointConstraint<T>& c : joint_rows_) {
        c.slip = slip(c.b, c.r_b0) - slip(c.a, c.r_a0);
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
    rebound_cap_.before(constraints_, bouncing_rows_, joint_rows_, solver_bodies_, integration_, settings_.restitution_threshold,
                        h);
    detail::apply_restitution(constraints_, bouncing_rows_, solver_bodies_, solver_masses_, settings_.restitution_threshold, h,
                              [&] { joint_stage(JointStage::relax, h); });
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

}  // namespace xeno

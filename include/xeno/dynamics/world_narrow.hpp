// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The narrow phase of a step (world.hpp, step): which broad-phase pairs are wanted, each pair
// collided (MPR, clipping, closed forms, meshes) or its resting manifold re-measured, speculative
// contacts out of reach dropped, and the new contacts merged in pair order with last step's
// impulses carried over. Included at the end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

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

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The step's first stages (world.hpp, step): each body's pose kept and its fattened box and
// early-out bound placed; the impulses of bodies made lighter halved; crowds thinned when more
// pairs overlap than max_contact_pairs; and, after the step, the query tree moved with the bodies.
// Included at the end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

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

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Manifold<T>: the persistent contact between two bodies, at most four points kept across steps
// so that their impulses warm-start the solver (thesis 3.2.2.7, Quadros 15–16; Bullet's
// btPersistentManifold). Pair convention, used everywhere: bodies A and B, the normal points from
// A to B, depth is positive when they overlap.
//
// Two ways to refresh it each step (docs/solver-design.md, "Contact manifolds"):
//   whole    the narrow phase clipped two supporting faces and returned up to four points at
//            once (polytopes, cylinder caps, cone bases, capsule and cylinder sides): the points
//            are replaced, and each new point inherits the impulse of the old point whose body-
//            local anchor lies within the match distance (each old point donates once);
//   gradual  the narrow phase returned one point (rounded ends, rims, edges; a sphere's one point
//            replaces its manifold instead: World::make_contact says why): the thesis
//            way. Old points are re-measured from their body-local anchors and dropped when they
//            separated beyond the margin or slid apart tangentially (Quadro 16); the new point
//            updates a close old one or is added; with five, the deepest stays and the four that
//            span the largest area are kept (Quadro 15).
#pragma once

#include "../collide/face_clip.hpp"

#include <array>
#include <cstdint>

namespace xeno {

/// One persistent contact point: anchors on both bodies and its accumulated impulses.
template <class T>
struct ContactPoint {
    Vec3<T> local_a{};       ///< m, A's body frame: the contact on A
    Vec3<T> local_b{};       ///< m, B's body frame: the contact on B
    T depth{};               ///< m along the normal, > 0 overlapping, < 0 speculative gap
    T normal_impulse{};      ///< N·s per solver substep, accumulated (warm start)
    T max_normal_impulse{};  ///< N·s, the largest of the last step (restitution gate)
    T step_impulse{};        ///< N·s, total normal impulse applied over the last step (events)
};

/// The persistent contact of one body pair.
template <class T>
struct Manifold {
    static constexpr int capacity = 4;
    Vec3<T> normal{};                                ///< unit, world, from A to B
    std::array<ContactPoint<T>, capacity> points{};  ///< the first `count` are valid
    int count = 0;
    Vec3<T> friction_impulse{};  ///< N·s per substep, world, central friction (re-projected each step)
    T twist_impulse{};           ///< N·m·s per substep about the normal

    /// Replaces the points by a freshly clipped manifold, matching impulses by anchor distance.
    void replace(const ContactManifold<T>& fresh, const Transform<T>& pose_a, const Transform<T>& pose_b, T match_distance);
    /// Merges a single fresh point the thesis way (see the file comment). margin: separation
    /// beyond which old points are dropped.
    void merge_single(const ManifoldPoint<T>& fresh, const Vec3<T>& normal_world, const Transform<T>& pose_a,
                      const Transform<T>& pose_b, T match_distance, T margin);
    /// True when some point overlaps (depth > 0): the bodies touch.
    bool touching() const {
        for (int i = 0; i < count; ++i)
            if (points[static_cast<std::size_t>(i)].depth > T(0)) return true;
        return false;
    }
};

namespace detail {

/// Index of the old point whose anchors are closest to p within match_distance, or -1.
template <class T>
int closest_old_point(const Manifold<T>& old, const ContactPoint<T>& p, T match_distance, std::uint32_t taken) {
    int best = -1;
    T best_distance = match_distance * match_distance;
    for (int i = 0; i < old.count; ++i) {
        if (taken & (1u << i)) continue;
        const ContactPoint<T>& o = old.points[static_cast<std::size_t>(i)];
        const T d = std::max(length_squared(o.local_a - p.local_a), length_squared(o.local_b - p.local_b));
        if (d <= best_distance) {
            best_distance = d;
            best = i;
        }
    }
    return best;
}

template <class T>
ContactPoint<T> to_contact_point(const ManifoldPoint<T>& m, const Transform<T>& pose_a, const Transform<T>& pose_b) {
    ContactPoint<T> c;
    c.local_a = pose_a.inverse_apply(m.point_a);
    c.local_b = pose_b.inverse_apply(m.point_b);
    c.depth = m.depth;
    return c;
}

}  // namespace detail

template <class T>
void Manifold<T>::replace(const ContactManifold<T>& fresh, const Transform<T>& pose_a, const Transform<T>& pose_b,
                          T match_distance) {
    const Manifold old = *this;
    std::uint32_t taken = 0;
    normal = fresh.normal;
    count = fresh.count;
    for (int i = 0; i < fresh.count; ++i) {
        ContactPoint<T> p = detail::to_contact_point(fresh.points[static_cast<std::size_t>(i)], pose_a, pose_b);
        const int match = detail::closest_old_point(old, p, match_distance, taken);
        if (match >= 0) {
            taken |= 1u << match;
            p.normal_impulse = old.points[static_cast<std::size_t>(match)].normal_impulse;
            p.max_normal_impulse = old.points[static_cast<std::size_t>(match)].max_normal_impulse;
        }
        points[static_cast<std::size_t>(i)] = p;
    }
    if (taken == 0) {  // nothing carried over: the friction and twist guesses are stale too
        friction_impulse = Vec3<T>::zero();
        twist_impulse = T(0);
    }
}

template <class T>
void Manifold<T>::merge_single(const ManifoldPoint<T>& fresh, const Vec3<T>& normal_world, const Transform<T>& pose_a,
                               const Transform<T>& pose_b, T match_distance, T margin) {
    normal = normal_world;
    // Re-measure the old points from their anchors (Quadro 16): drop those that separated beyond
    // the margin or slid apart along the surface.
    int kept = 0;
    for (int i = 0; i < count; ++i) {
        ContactPoint<T> p = points[static_cast<std::size_t>(i)];
        const Vec3<T> gap = pose_b.apply(p.local_b) - pose_a.apply(p.local_a);
        const T separation = dot(gap, normal);
        const Vec3<T> slide = gap - normal * separation;
        // Asked as "within", so that a point made of NaN (never from finite input) is dropped too.
        if (!(separation <= margin && length_squared(slide) <= match_distance * match_distance)) continue;
        p.depth = -separation;
        points[static_cast<std::size_t>(kept++)] = p;
    }
    count = kept;
    ContactPoint<T> p = detail::to_contact_point(fresh, pose_a, pose_b);
    // A new point near an old one updates it, keeping its impulse (Quadro 15).
    const int match = detail::closest_old_point(*this, p, match_distance, 0);
    if (match >= 0) {
        p.normal_impulse = points[static_cast<std::size_t>(match)].normal_impulse;
        p.max_normal_impulse = points[static_cast<std::size_t>(match)].max_normal_impulse;
        points[static_cast<std::size_t>(match)] = p;
        return;
    }
    if (count < capacity) {
        points[static_cast<std::size_t>(count++)] = p;
        return;
    }
    // Five candidates: keep the deepest, drop the one whose removal leaves the largest area.
    std::array<ContactPoint<T>, capacity + 1> all;
    for (int i = 0; i < capacity; ++i) all[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(i)];
    all[capacity] = p;
    int deepest = 0;
    for (int i = 1; i <= capacity; ++i)
        if (all[static_cast<std::size_t>(i)].depth > all[static_cast<std::size_t>(deepest)].depth) deepest = i;
    // Without a finite area (NaN anchors) the newest point goes, or the first when it is the
    // deepest: left at -1, drop kept all five and wrote the fifth past the array, over `count`.
    int drop = deepest == capacity ? 0 : capacity;
    T best_area = -T(1);
    for (int skip = 0; skip <= capacity; ++skip) {
        if (skip == deepest) continue;
        Vec3<T> q[capacity];
        int k = 0;
        for (int i = 0; i <= capacity; ++i)
            if (i != skip) q[k++] = all[static_cast<std::size_t>(i)].local_a;
        // Twice the area of the quadrilateral's two diagonals' parallelogram, any vertex order.
        const T area = std::max({length(cross(q[0] - q[1], q[2] - q[3])), length(cross(q[0] - q[2], q[1] - q[3])),
                                 length(cross(q[0] - q[3], q[1] - q[2]))});
        if (area > best_area) {
            best_area = area;
            drop = skip;
        }
    }
    int k = 0;
    for (int i = 0; i <= capacity; ++i)
        if (i != drop) points[static_cast<std::size_t>(k++)] = all[static_cast<std::size_t>(i)];
}

namespace detail {
/// Halves `times` times every impulse the manifold carries to the next step (Body::impulse_halvings_).
template <class T>
void halve_impulses(Manifold<T>& m, int times) {
    if (times == 0) return;
    for (ContactPoint<T>& p : m.points) {
        p.normal_impulse = halved(p.normal_impulse, times);
        p.max_normal_impulse = halved(p.max_normal_impulse, times);
        p.step_impulse = halved(p.step_impulse, times);
    }
    m.friction_impulse = halved(m.friction_impulse, times);
    m.twist_impulse = halved(m.twist_impulse, times);
}
}  // namespace detail

namespace f32 {
using Manifold = xeno::Manifold<float>;
using ContactPoint = xeno::ContactPoint<float>;
}  // namespace f32
namespace f64 {
using Manifold = xeno::Manifold<double>;
using ContactPoint = xeno::ContactPoint<double>;
}  // namespace f64

}  // namespace xeno

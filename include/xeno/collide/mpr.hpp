// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Minkowski Portal Refinement (XenoCollide): Snethen, "XenoCollide: Complex Collision Made
// Simple", Game Programming Gems 7 (2008); the seed thesis 2.2.1 and Apêndice A; degenerate cases
// as catalogued in docs/collision.md, "Degenerate cases". Templated on the two shape types: every
// support call is a direct, inlinable call (no virtual dispatch per support evaluation).
//
// D = A ⊖ B contains the origin iff A and B overlap. With v0 inside D, the origin is in D iff the
// ray from v0 through the origin reaches the origin before leaving D.
//   Phase 0  v0 = interior(A) − interior(B) (centres of mass: inside, whatever the local origins);
//            when v0 ≈ 0 (centres coincide) it is nudged a tiny step against the axis of least
//            support, so the ray runs along the likely separating direction.
//   Phase 1  portal discovery: a triangle (v1, v2, v3) of support points that the ray crosses.
//   Phase 2  refinement: while the origin is beyond the portal, replace a portal vertex by the
//            support point v4 along the portal normal, keeping the ray inside the new triangle.
//            The origin is inside D (hit) once it is on v0's side of a portal. Miss as soon as a
//            support plane separates the origin (v·n ≤ 0) or the portal reaches the boundary of D
//            with the origin still outside.
//   Phase 3  (penetration query) refine until the support plane is within a tolerance of the
//            portal; the portal's normal is the contact normal (A → B), the depth is the support
//            distance along it, and the contact points are the barycentric combination of the
//            portal's witnesses at the projection of the origin onto the portal.
// Touching without overlap (depth 0) is a miss. Every loop is capped (kMaxIterations); tolerances
// are fractions of the pair's size; every normalisation is guarded, so finite input gives finite
// output. A non-finite pose is rejected (InvalidArgument) before the query runs.
#pragma once

#include "../error.hpp"
#include "minkowski.hpp"

#include <algorithm>
#include <utility>

namespace xeno {

/// Result of a penetration query. When hit is false the other fields are meaningless.
template <class T>
struct Penetration {
    bool hit = false;
    Vec3<T> normal{};  ///< unit, world frame, from A to B
    /// world. collide(): on A's support plane along the normal and on or inside A within the
    /// depth (on A's surface where the two support features overlap), with
    /// point_a − point_b = depth · normal (contact_points.hpp). mpr_penetration(): the point of A
    /// where the centre line leaves A ⊖ B.
    Vec3<T> point_a{};
    Vec3<T> point_b{};   ///< world, the same for B (on B's support plane along −normal)
    T depth{};           ///< metres, > 0 when hit; moving B by depth · normal makes them touch
    int iterations = 0;  ///< support evaluations used (instrumentation)
};

/// True when the shapes overlap by more than touching. Stops as soon as the answer is known.
template <class A, class B>
bool mpr_intersect(const A& a, const Transform<typename A::scalar_type>& pose_a, const B& b,
                   const Transform<typename A::scalar_type>& pose_b);

/// Normal, contact points and depth when the shapes overlap (hit), else hit = false.
template <class A, class B>
Penetration<typename A::scalar_type> mpr_penetration(const A& a, const Transform<typename A::scalar_type>& pose_a, const B& b,
                                                     const Transform<typename A::scalar_type>& pose_b);

namespace detail {

/// Iteration cap for each MPR phase; a polytope pair needs fewer than 10 (docs/collision.md,
/// "Iteration counts").
constexpr int kMprMaxIterations = 64;

template <class T>
void require_finite_pose(const Transform<T>& pose, const char* where, const char* name) {
    // Every query checks its poses: the common, valid case returns before any message is built
    // (building the names allocates, which made intersect() slower than collide()).
    const Vec3<T>& p = pose.position;
    const Quat<T>& q = pose.orientation;
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(q.w) && std::isfinite(q.x) &&
        std::isfinite(q.y) && std::isfinite(q.z) && std::abs(length_squared(q) - T(1)) <= T(1e-3))
        return;
    require_finite_xyz(pose.position, where, (std::string(name) + ".position").c_str());
    require_orientation(pose.orientation, where, (std::string(name) + ".orientation").c_str());
    // rotate() assumes a unit quaternion: any other scales and shears the shape.
    if (!(std::abs(length_squared(pose.orientation) - T(1)) <= T(1e-3)))
        report_invalid(where,
                       (std::string(name) + ".orientation must be a unit quaternion (within 1e-3; normalise it), |q|^2").c_str(),
                       static_cast<double>(length_squared(pose.orientation)));
}

enum class PortalStatus { miss, hit_on_ray, found };

/// Phases 0 and 1. On hit_on_ray the origin lies on the segment v0–v1 and v1 alone is the contact.
template <class A, class B>
PortalStatus discover_portal(const MinkowskiDifference<A, B>& md, SupportPoint<typename A::scalar_type> (&v)[4],
                             int& iterations) {
    using T = typename A::scalar_type;
    const T scale = md.scale();
    const T eps = ScalarTraits<T>::epsilon;

    // Phase 0: the interior point; nudge it off the origin when the centres coincide.
    v[0] = md.interior();
    if (length_squared(v[0].v) <= square(T(16) * eps * scale)) {
        // Aim the ray along the axis of A with the smallest support distance of D: the likely
        // direction of least penetration.
        Vec3<T> best_axis = Vec3<T>::unit_x();
        T best = ScalarTraits<T>::infinity;
        for (int i = 0; i < 6; ++i) {
            const Vec3<T> axis = Vec3<T>::axis(i % 3) * (i < 3 ? T(1) : T(-1));
            const T h = dot(md.support(axis).v, axis);
            ++iterations;
            if (h < best) {
                best = h;
                best_axis = axis;
            }
        }
        const Vec3<T> nudge = best_axis * (T(1e-5) * scale);
        v[0].v -= nudge;
        v[0].a -= nudge;
    }

    // Phase 1: v1 along the ray from v0 through the origin.
    v[1] = md.support(-v[0].v);
    ++iterations;
    if (dot(v[1].v, v[0].v) >= T(0)) return PortalStatus::miss;  // a support plane separates

    Vec3<T> n = cross(v[1].v, v[0].v);
    // v1 collinear with the ray: the origin lies on the segment v0–v1 (relative test: |v0 × v1|
    // against |v0||v1|, so it works at any scale).
    if (length_squared(n) <= square(T(16) * eps) * length_squared(v[0].v) * length_squared(v[1].v))
        return PortalStatus::hit_on_ray;

    v[2] = md.support(n);
    ++iterations;
    if (dot(v[2].v, n) <= T(0)) return PortalStatus::miss;

    n = cross(v[1].v - v[0].v, v[2].v - v[0].v);
    if (dot(n, v[0].v) > T(0)) {  // orient so the origin is on the + side
        std::swap(v[1], v[2]);
        n = -n;
    }
    for (int k = 0; k < kMprMaxIterations; ++k) {
        v[3] = md.support(n);
        ++iterations;
        if (dot(v[3].v, n) <= T(0)) return PortalStatus::miss;
        // Origin outside the plane (v0, v1, v3): drop v2.
        if (dot(cross(v[1].v, v[3].v), v[0].v) < T(0)) {
            v[2] = v[3];
            n = cross(v[1].v - v[0].v, v[3].v - v[0].v);
            continue;
        }
        // Origin outside the plane (v0, v3, v2): drop v1.
        if (dot(cross(v[3].v, v[2].v), v[0].v) < T(0)) {
            v[1] = v[3];
            n = cross(v[3].v - v[0].v, v[2].v - v[0].v);
            continue;
        }
        return PortalStatus::found;
    }
    return PortalStatus::miss;  // cap reached: a flat D that never yields a portal
}

/// Replaces one portal vertex by v4 so that the ray v0 → origin still crosses the portal.
template <class T>
void choose_new_portal(SupportPoint<T> (&v)[4], const SupportPoint<T>& v4) {
    const Vec3<T> c = cross(v4.v, v[0].v);
    if (dot(v[1].v, c) > T(0)) {
        if (dot(v[2].v, c) > T(0)) v[1] = v4;
        else v[3] = v4;
    } else {
        if (dot(v[3].v, c) > T(0)) v[2] = v4;
        else v[1] = v4;
    }
}

/// The contact, in A's frame, from a converged portal (v1, v2, v3) with unit normal n. The points
/// are where the centre line leaves D; their difference is along that line, not exactly along n.
template <class T>
Penetration<T> contact_from_portal(const SupportPoint<T> (&v)[4], const Vec3<T>& n, T depth) {
    // Barycentric weights of the point where the ray v0 → origin crosses the portal: for a line
    // through 0 along v0 they are proportional to the triple products below, and MPR keeps that
    // crossing inside the portal, so they are non-negative up to round-off (clamped). The
    // witnesses are then the points of A and B whose difference is that crossing point: where the
    // centre line leaves D, a unique point even when the portal lies on a flat face of D.
    // (Projecting the origin perpendicularly onto the portal, as some implementations do, can
    // land outside the triangle on oblique portals and bend the points off the contact.)
    T w1 = triple(v[0].v, v[2].v, v[3].v);
    T w2 = triple(v[0].v, v[3].v, v[1].v);
    T w3 = triple(v[0].v, v[1].v, v[2].v);
    if (w1 + w2 + w3 < T(0)) {
        w1 = -w1;
        w2 = -w2;
        w3 = -w3;
    }
    w1 = std::max(w1, T(0));
    w2 = std::max(w2, T(0));
    w3 = std::max(w3, T(0));
    const T sum = w1 + w2 + w3;
    Vec3<T> pa, pb;
    if (sum > T(0)) {
        pa = (v[1].a * w1 + v[2].a * w2 + v[3].a * w3) / sum;
        pb = (v[1].b() * w1 + v[2].b() * w2 + v[3].b() * w3) / sum;
    } else {  // a sliver portal: its vertices are within round-off of each other
        pa = v[1].a;
        pb = v[1].b();
    }
    Penetration<T> out;
    out.hit = true;
    out.normal = n;
    out.point_a = pa;
    out.point_b = pb;
    out.depth = depth;
    return out;
}

/// Phases 2 and 3; with stop_at_hit, returns as soon as the origin is known to be inside. The
/// result is in A's local frame. On a penetration hit, `simplex` (when given, 4 entries) receives
/// the tetrahedron v0 and portal the answer came from: points of D around the origin, where the
/// least-depth expansion (epa.hpp) starts.
template <class A, class B>
Penetration<typename A::scalar_type> mpr(const MinkowskiDifference<A, B>& md, bool stop_at_hit,
                                         Vec3<typename A::scalar_type>* simplex = nullptr) {
    using T = typename A::scalar_type;
    Penetration<T> result;
    SupportPoint<T> v[4];
    int iterations = 0;
    const PortalStatus status = discover_portal(md, v, iterations);
    if (status == PortalStatus::miss) {
        result.iterations = iterations;
        return result;
    }
    if (status == PortalStatus::hit_on_ray) {
        // The support along the ray is the contact: normal along the ray, exact depth for it.
        const Vec3<T> n = normalized_or(-v[0].v, Vec3<T>::unit_y());
        const T depth = dot(v[1].v, n);
        if (!(depth > T(0))) {
            result.iterations = iterations;
            return result;
        }
        SupportPoint<T> on_ray[4] = {v[0], v[1], v[1], v[1]};
        result = contact_from_portal(on_ray, n, depth);
        if (simplex)  // flat: the expansion does not start from it
            for (int i = 0; i < 4; ++i) simplex[i] = on_ray[i].v;
        result.iterations = iterations;
        return result;
    }

    auto keep = [simplex](const SupportPoint<T>(&tetrahedron)[4]) {
        if (simplex)
            for (int i = 0; i < 4; ++i) simplex[i] = tetrahedron[i].v;
    };
    const T scale = md.scale();
    // Convergence within 1e-7 of the pair's size in double (1e-5 in float), the smaller shape's
    // when the two differ (MinkowskiDifference::tolerance_scale), never below round-off at the
    // pair's coordinates: on a curved surface the portal must shrink to about sqrt(8 R tau) before
    // it is that flat, and below 1e-7 its triangles turn to slivers in double's round-off before
    // they get there (measured: with 1e-9, 0.5 % of near-touching sphere pairs never converged).
    const T tolerance = std::max(std::max(ScalarTraits<T>::geometric_tolerance, T(1e-7)) * md.tolerance_scale(), md.round_off());
    const T tiny_normal_sq = square(T(16) * ScalarTraits<T>::epsilon * scale * scale);
    bool hit = false;
    Vec3<T> last_good_n{};
    // The best portal seen once the origin is inside: the support distance along any direction
    // bounds the penetration depth from above, so when the loop ends without converging (the
    // cap, a collapsed or flipped portal: round-off on curved shapes, where the portal shrinks
    // towards a point and slivers of it can flip), the portal with the smallest one is still a
    // true, nearly minimal answer. (Regression: two resting spheres whose portal degenerated after
    // 40 iterations and never converged reported the last portal's 25 cm instead of 0.04 mm.)
    SupportPoint<T> best[4];
    Vec3<T> best_n{};
    T best_ratio = ScalarTraits<T>::infinity;  // support distance² / |n|², i.e. depth²
    // The portal normal n is left unnormalised inside the loop (every test below is homogeneous
    // in n or compares squares): one square root at the end instead of one per iteration.
    for (int k = 0; k < kMprMaxIterations; ++k) {
        const Vec3<T> n = cross(v[2].v - v[1].v, v[3].v - v[1].v);
        const T n_sq = length_squared(n);
        if (!(n_sq > tiny_normal_sq)) break;               // the portal collapsed to a segment or a point
        const bool origin_inside = dot(n, v[1].v) > T(0);  // false after a hit: a sliver flipped
        last_good_n = n;
        if (!hit && origin_inside) {  // origin strictly inside the tetrahedron
            hit = true;
            if (stop_at_hit) break;
        }
        const SupportPoint<T> v4 = md.support(n);
        ++iterations;
        const T support_distance = dot(v4.v, n);        // times |n|
        if (!hit && !(support_distance > T(0))) break;  // a support plane separates the origin
        if (origin_inside && support_distance > T(0) && support_distance * support_distance < best_ratio * n_sq) {
            best_ratio = support_distance * support_distance / n_sq;
            std::copy(v, v + 4, best);
            best_n = n;
        }
        // Converged: the support plane is within tolerance of the portal (all three vertices,
        // which are equal in exact arithmetic, as libccd does for safety in float).
        const T progress = std::min(std::min(dot(v4.v - v[1].v, n), dot(v4.v - v[2].v, n)), dot(v4.v - v[3].v, n));
        if (progress <= T(0) || progress * progress <= tolerance * tolerance * n_sq) {
            if (hit) {
                const T inv_length = T(1) / std::sqrt(n_sq);
                result = contact_from_portal(v, n * inv_length, std::max(support_distance * inv_length, T(0)));
                result.hit = support_distance > T(0);
                keep(v);
            }
            result.iterations = iterations;
            return result;
        }
        choose_new_portal(v, v4);
    }
    // Stopped early (boolean hit), cap reached, or a collapsed portal: report the last good portal
    // if the origin was found inside, else a miss.
    if (hit) {
        if (stop_at_hit) {
            result.hit = true;
        } else {
            // The last portal is normally within round-off of converging (and keeps A–B
            // symmetry); the best one replaces it when the last went wrong.
            const Vec3<T> n = normalized_or(last_good_n, -v[0].v);
            const T depth = dot(v[1].v, n);
            const T best_depth = std::sqrt(best_ratio);
            if (best_ratio < ScalarTraits<T>::infinity && !(depth > T(0) && depth <= T(1.5) * best_depth + tolerance)) {
                result = contact_from_portal(best, normalized_or(best_n, -v[0].v), best_depth);
                keep(best);
            } else {
                keep(v);
                result = contact_from_portal(v, n, std::max(depth, T(0)));
                result.hit = depth > T(0);
            }
        }
    }
    result.iterations = iterations;
    return result;
}

}  // namespace detail

template <class A, class B>
bool mpr_intersect(const A& a, const Transform<typename A::scalar_type>& pose_a, const B& b,
                   const Transform<typename A::scalar_type>& pose_b) {
    detail::require_finite_pose(pose_a, "mpr_intersect", "pose_a");
    detail::require_finite_pose(pose_b, "mpr_intersect", "pose_b");
    return detail::mpr(MinkowskiDifference<A, B>(a, pose_a, b, pose_b), true).hit;
}

template <class A, class B>
Penetration<typename A::scalar_type> mpr_penetration(const A& a, const Transform<typename A::scalar_type>& pose_a, const B& b,
                                                     const Transform<typename A::scalar_type>& pose_b) {
    detail::require_finite_pose(pose_a, "mpr_penetration", "pose_a");
    detail::require_finite_pose(pose_b, "mpr_penetration", "pose_b");
    Penetration<typename A::scalar_type> p = detail::mpr(MinkowskiDifference<A, B>(a, pose_a, b, pose_b), false);
    if (p.hit) {
        p.normal = pose_a.apply_direction(p.normal);
        p.point_a = pose_a.apply(p.point_a);
        p.point_b = pose_a.apply(p.point_b);
    }
    return p;
}

namespace f32 {
using Penetration = xeno::Penetration<float>;
}
namespace f64 {
using Penetration = xeno::Penetration<double>;
}

}  // namespace xeno

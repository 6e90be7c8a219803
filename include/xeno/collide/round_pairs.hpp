// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Closed-form contacts for round shapes: spheres and capsules against each other and against
// boxes, exact to rounding, where MPR stops at a portal within a tolerance and on curved surfaces
// reports depths up to twice the minimum (issue 12). A sphere is a point and a capsule a segment
// (its core) swept by a ball, so A ⊖ B = (core_A ⊖ core_B) ⊕ ball(r_A + r_B): while the cores are
// apart, the minimum depth is the radius sum minus their distance, along the line through their
// closest points (Ericson, "Real-Time Collision Detection", 4.5.1 and 5.1.9). Two reductions cover
// every pair, each as a segment against a box, in the box's frame:
//   round – round  A's core (0, ±h_A, 0) is a flat box of half extents (0, h_A, 0), radius r_A + r_B;
//   round – box    the box itself against the round shape's core, radius r.
// One routine then answers all of them (the segment may be a point, the box may be flat):
//   1. closest points: |segment(t) − box|² is convex and piecewise quadratic in t, breaking where a
//      coordinate crosses a face plane; each piece's minimum is in closed form. In the box's frame a
//      nearly parallel capsule pair keeps its accuracy, where the general segment–segment formula
//      divides by 1 − cos² of their angle;
//   2. cores apart (by more than a rounding fraction of the size): the normal runs from the box's
//      closest point to the segment's, depth = radius − distance;
//   3. cores touching or crossing. Two round shapes: core_A ⊖ core_B is flat, so the origin is on its
//      boundary and depth = r_A + r_B along any normal perpendicular to both cores. A segment in a
//      box: box ⊖ segment is a polytope whose faces are normal to the box's axes and to the cross
//      products of those axes with the segment, so the least overlap over these ≤ 6 axes is the
//      exact depth of the segment (separating axes, as box_box.hpp); faces win ties.
// Points come `depth` apart along the normal (point_a = point_b + depth · normal, as collide()
// reports every pair): point_b on B's surface, point_a on or inside A. Manifolds hold one point,
// except a segment along a box face (the two ends of the segment clipped to the face) and two
// nearly parallel capsules (B's ends clipped to A's extent, plus the closest point when the axes
// cross between them), so a capsule rests on a floor or on another capsule without rocking.
#pragma once

#include "../shape/box.hpp"
#include "../shape/capsule.hpp"
#include "../shape/sphere.hpp"
#include "face_clip.hpp"
#include "minkowski.hpp"

#include <algorithm>
#include <type_traits>

namespace xeno {

namespace detail {

template <class S>
struct IsRound : std::false_type {};
template <class T>
struct IsRound<Sphere<T>> : std::true_type {};
template <class T>
struct IsRound<Capsule<T>> : std::true_type {};

/// True for the pairs answered here: two round shapes (sphere, capsule), or one and a box, in
/// either order.
template <class A, class B>
constexpr bool is_round_pair = (IsRound<A>::value && (IsRound<B>::value || std::is_same_v<B, Box<typename A::scalar_type>>)) ||
                               (IsRound<B>::value && std::is_same_v<A, Box<typename A::scalar_type>>);

/// Half length of a round shape's core segment along its local y (a sphere's core is a point).
template <class T>
T core_half_length(const Sphere<T>&) {
    return T(0);
}
template <class T>
T core_half_length(const Capsule<T>& c) {
    return c.half_height();
}

/// p minus its nearest point in the box |x_i| <= e_i: zero inside, else the offset from the box.
template <class T>
Vec3<T> outside_box(const Vec3<T>& p, const Vec3<T>& e) {
    return p - Vec3<T>{clamp(p.x, -e.x, e.x), clamp(p.y, -e.y, e.y), clamp(p.z, -e.z, e.z)};
}

/// The t in [−1, 1] whose point c + t·u is nearest to the box |x_i| <= e_i (u and any e_i may be
/// zero). f(t) = |outside_box(c + t·u)|² is convex and quadratic between the t where a coordinate
/// crosses ±e_i: each piece is minimised in closed form and the least kept (the first on ties). A
/// piece on which f is constant answers its middle, so a segment parallel to a face gives the
/// middle of the part above it.
template <class T>
T closest_to_box(const Vec3<T>& c, const Vec3<T>& u, const Vec3<T>& e) {
    T cuts[8];
    int count = 0;
    cuts[count++] = T(-1);
    cuts[count++] = T(1);
    for (int i = 0; i < 3; ++i) {
        if (u[i] == T(0)) continue;
        const T low = (-e[i] - c[i]) / u[i], high = (e[i] - c[i]) / u[i];
        if (low > T(-1) && low < T(1)) cuts[count++] = low;
        if (high > T(-1) && high < T(1)) cuts[count++] = high;
    }
    std::sort(cuts, cuts + count);
    T best_t = T(0), best = ScalarTraits<T>::infinity;
    for (int k = 0; k + 1 < count; ++k) {
        const T t0 = cuts[k], t1 = cuts[k + 1];
        if (!(t1 > t0)) continue;
        const T mid = T(0.5) * (t0 + t1);
        // On this piece each coordinate stays above e_i, below −e_i or between: f is the sum over
        // the outside ones of (c_i ∓ e_i + t·u_i)², least at t = −Σ u_i (c_i ∓ e_i) / Σ u_i².
        T a = T(0), b = T(0);
        for (int i = 0; i < 3; ++i) {
            const T p = c[i] + mid * u[i];
            if (p > e[i]) {
                a += u[i] * u[i];
                b += u[i] * (c[i] - e[i]);
            } else if (p < -e[i]) {
                a += u[i] * u[i];
                b += u[i] * (c[i] + e[i]);
            }
        }
        const T t = a > T(0) ? clamp(-b / a, t0, t1) : mid;
        const T f = length_squared(outside_box(c + u * t, e));
        if (f < best) {
            best = f;
            best_t = t;
        }
    }
    return best_t;
}

/// The part [t0, t1] of the segment c + t·u (t in [−1, 1]) within the side planes of the box's
/// faces normal to axis k (|x_j| <= e_j for j != k). False when no part is.
template <class T>
bool clip_to_face(const Vec3<T>& c, const Vec3<T>& u, const Vec3<T>& e, int k, T& t0, T& t1) {
    t0 = T(-1);
    t1 = T(1);
    for (int j = 0; j < 3; ++j) {
        if (j == k) continue;
        if (u[j] == T(0)) {
            if (std::abs(c[j]) > e[j]) return false;  // parallel to the side plane, beyond it
            continue;
        }
        T low = (-e[j] - c[j]) / u[j], high = (e[j] - c[j]) / u[j];
        if (low > high) std::swap(low, high);
        t0 = std::max(t0, low);
        t1 = std::min(t1, high);
    }
    return t0 <= t1;
}

/// Where a segment c + t·u (t in [−1, 1]) meets a box, in the box's frame.
template <class T>
struct CoreContact {
    Vec3<T> normal{};  ///< unit, from the box to the segment
    T gap{};           ///< metres along normal: > 0 the cores are that far apart, <= 0 the segment is that deep in the box
    T t{};             ///< the segment's contact point is c + t·u
    int face = -1;     ///< 0–2 when the normal is ± that box axis and the contact on that face, else −1
};

/// Below this distance (a rounding fraction of the pair's size) two cores touch: their offset has
/// no reliable direction.
template <class T>
T touching_distance(T scale) {
    return T(16) * ScalarTraits<T>::epsilon * scale;
}

/// A round shape's core (segment c ± u) against a box of half extents e > 0, in the box's frame.
/// Step 1 of both core contacts: the segment c ± u's parameter t closest to the box of half
/// extents e (≥ 0), and the offset from the box to that point. Sets out.gap and out.normal and
/// returns true when the two are apart by more than touching_distance.
template <class T>
bool core_apart(const Vec3<T>& c, const Vec3<T>& u, const Vec3<T>& e, T scale, CoreContact<T>& out, Vec3<T>& offset) {
    out.t = closest_to_box(c, u, e);
    offset = outside_box(c + u * out.t, e);
    const T distance = length(offset);
    if (!(distance > touching_distance(scale))) return false;
    out.gap = distance;
    out.normal = offset / distance;
    return true;
}

template <class T>
CoreContact<T> core_box_contact(const Vec3<T>& c, const Vec3<T>& u, const Vec3<T>& e, T scale) {
    CoreContact<T> out;
    Vec3<T> offset;
    if (core_apart(c, u, e, scale, out, offset)) {
        // Outside along one axis only: the closest point is on a face, the normal exactly its axis.
        const int outside = (offset.x != T(0) ? 1 : 0) + (offset.y != T(0) ? 1 : 0) + (offset.z != T(0) ? 1 : 0);
        if (outside == 1) {
            out.face = offset.x != T(0) ? 0 : (offset.y != T(0) ? 1 : 2);
            out.normal = Vec3<T>::axis(out.face) * (offset[out.face] > T(0) ? T(1) : T(-1));
        }
        return out;
    }
    // The core cuts into the box: least overlap over the faces of box ⊖ segment. Along a unit axis
    // m the overlap is Σ e_i |m_i| + |u·m| − |c·m|; for the edge axes u·m = 0.
    const T slack = T(64) * ScalarTraits<T>::epsilon * scale;
    T best_face = ScalarTraits<T>::infinity;
    for (int k = 0; k < 3; ++k) {
        const T overlap = e[k] + std::abs(u[k]) - std::abs(c[k]);
        if (overlap < best_face) {
            best_face = overlap;
            out.face = k;
            out.normal = Vec3<T>::axis(k) * (c[k] >= T(0) ? T(1) : T(-1));
        }
    }
    int edge = -1;
    T best_edge = best_face - slack;  // an edge axis only when clearly shallower than every face
    const T u_length = length(u);
    for (int i = 0; i < 3; ++i) {
        const Vec3<T> axis = cross(Vec3<T>::axis(i), u);
        const T len = length(axis);
        if (!(len > T(1e-6) * u_length)) continue;  // a point, or parallel to box axis i: faces cover it
        const Vec3<T> m = axis / len;
        const T overlap = dot(e, abs(m)) - std::abs(dot(c, m));
        if (overlap < best_edge) {
            best_edge = overlap;
            edge = i;
            out.normal = dot(c, m) >= T(0) ? m : -m;
        }
    }
    if (edge >= 0) {
        // The box's edge along axis `edge` that supports the normal, and the segment's point
        // nearest to it (that edge is a flat box around its midpoint).
        out.gap = -best_edge;
        out.face = -1;
        Vec3<T> midpoint{std::copysign(e.x, out.normal.x), std::copysign(e.y, out.normal.y), std::copysign(e.z, out.normal.z)};
        midpoint[edge] = T(0);
        Vec3<T> extent = Vec3<T>::zero();
        extent[edge] = e[edge];
        out.t = closest_to_box(c - midpoint, u, extent);
        return out;
    }
    // A face: the deepest point of the segment's part within the face; the middle on ties.
    out.gap = -best_face;
    T t0, t1;
    if (clip_to_face(c, u, e, out.face, t0, t1)) {
        const int k = out.face;
        const T h0 = out.normal[k] * (c[k] + t0 * u[k]), h1 = out.normal[k] * (c[k] + t1 * u[k]);
        out.t = std::abs(h0 - h1) <= slack ? T(0.5) * (t0 + t1) : (h0 < h1 ? t0 : t1);
    }  // an empty clip (rounding at a side plane) keeps the closest point of step 1
    return out;
}

/// Two round cores, in A's frame: A's core (0, ±half_a, 0) against B's segment c ± u.
template <class T>
CoreContact<T> core_core_contact(T half_a, const Vec3<T>& c, const Vec3<T>& u, T scale) {
    const Vec3<T> e{T(0), half_a, T(0)};
    CoreContact<T> out;
    Vec3<T> offset;
    if (core_apart(c, u, e, scale, out, offset)) return out;
    // The cores touch or cross (coincident centres, crossing axes, overlapping parallel axes):
    // depth is the radius sum along any normal perpendicular to both. Take their common normal when
    // they cross, else the way from A's axis to B's centre, else x; pointing towards B's centre.
    out.gap = T(0);
    const Vec3<T> across{u.z, T(0), -u.x};  // y × u
    const Vec3<T> n = length_squared(across) > T(1e-12) * length_squared(u)
                          ? normalized(across)
                          : normalized_or(Vec3<T>{c.x, T(0), c.z}, Vec3<T>::unit_x());
    out.normal = dot(n, c) >= T(0) ? n : -n;
    return out;
}

/// A round pair as a segment against a box, in the box's frame (A's, or B's when B is the box).
template <class T>
struct CorePair {
    Vec3<T> c{}, u{};    ///< metres: the segment c ± u (the round shape's core; B's for two round shapes)
    Vec3<T> e{};         ///< metres: half extents of the box (A's core as a flat box for two round shapes)
    T radius_box{};      ///< metres: radius swept around the box (0 for a real box)
    T radius_segment{};  ///< metres: radius swept around the segment
    bool round_round = false;
    bool b_is_box = false;  ///< the frame is B's: directions and sides swap when answering in A's frame
    CoreContact<T> contact{};
    T radius() const { return radius_box + radius_segment; }
    T depth() const { return radius() - contact.gap; }
    Vec3<T> segment_point(T t) const { return c + u * t; }
};

/// The reduction of a round pair (the contact not yet computed).
template <class A, class B>
CorePair<typename A::scalar_type> core_pair(const MinkowskiDifference<A, B>& md) {
    using T = typename A::scalar_type;
    CorePair<T> p;
    const Vec3<T> b_centre = md.to_a(Vec3<T>::zero());
    if constexpr (std::is_same_v<A, Box<T>>) {
        p.e = md.shape_a().half_extents();
        p.c = b_centre;
        p.u = md.direction_to_a(Vec3<T>{T(0), core_half_length(md.shape_b()), T(0)});
        p.radius_segment = md.shape_b().radius();
    } else if constexpr (std::is_same_v<B, Box<T>>) {
        p.b_is_box = true;
        p.e = md.shape_b().half_extents();
        p.c = md.direction_to_b(-b_centre);
        p.u = md.direction_to_b(Vec3<T>{T(0), core_half_length(md.shape_a()), T(0)});
        p.radius_segment = md.shape_a().radius();
    } else {
        p.round_round = true;
        p.e = {T(0), core_half_length(md.shape_a()), T(0)};
        p.radius_box = md.shape_a().radius();
        p.c = b_centre;
        p.u = md.direction_to_a(Vec3<T>{T(0), core_half_length(md.shape_b()), T(0)});
        p.radius_segment = md.shape_b().radius();
    }
    return p;
}

/// The reduction of a round pair with its contact.
template <class A, class B>
CorePair<typename A::scalar_type> core_pair_contact(const MinkowskiDifference<A, B>& md) {
    CorePair<typename A::scalar_type> p = core_pair(md);
    p.contact = p.round_round ? core_core_contact(p.e.y, p.c, p.u, md.scale()) : core_box_contact(p.c, p.u, p.e, md.scale());
    return p;
}

/// True when a round pair overlaps: the same answer as round_contact's depth > 0 (cores within
/// touching distance, or apart by less than the radius sum), without the normal and points.
template <class A, class B>
bool round_intersect(const MinkowskiDifference<A, B>& md) {
    using T = typename A::scalar_type;
    const CorePair<T> p = core_pair(md);
    const T distance = length(outside_box(p.segment_point(closest_to_box(p.c, p.u, p.e)), p.e));
    return distance <= touching_distance(md.scale()) || p.radius() - distance > T(0);
}

/// One contact in A's frame from the segment's point at t and its depth along the pair's normal:
/// the segment's surface point, and the box side's point `depth` beyond it along the normal.
template <class A, class B>
void core_points(const MinkowskiDifference<A, B>& md, const CorePair<typename A::scalar_type>& p, typename A::scalar_type t,
                 typename A::scalar_type depth, Vec3<typename A::scalar_type>& point_a, Vec3<typename A::scalar_type>& point_b) {
    using T = typename A::scalar_type;
    const Vec3<T>& n = p.contact.normal;
    const Vec3<T> on_segment = p.segment_point(t) - n * p.radius_segment;
    const Vec3<T> on_box = on_segment + n * depth;
    if (p.b_is_box) {
        point_a = md.to_a(on_segment);
        point_b = md.to_a(on_box);
    } else {
        point_a = on_box;
        point_b = on_segment;
    }
}

/// The pair's normal in A's frame, from A to B.
template <class A, class B>
Vec3<typename A::scalar_type> core_normal(const MinkowskiDifference<A, B>& md, const CorePair<typename A::scalar_type>& p) {
    return p.b_is_box ? -md.direction_to_a(p.contact.normal) : p.contact.normal;
}

/// The contact of a round pair in A's frame, as refined_contact gives it: unit normal n from A to
/// B, overlap h (exact; h > −margin when within reach), single-contact points h apart along n.
/// False when the shapes are farther apart than md's margin.
template <class A, class B>
bool round_contact(const MinkowskiDifference<A, B>& md, Vec3<typename A::scalar_type>& n, typename A::scalar_type& h,
                   Vec3<typename A::scalar_type>& point_a, Vec3<typename A::scalar_type>& point_b) {
    const auto p = core_pair_contact(md);
    h = p.depth();
    if (!(h > -md.margin())) return false;
    n = core_normal(md, p);
    core_points(md, p, p.contact.t, h, point_a, point_b);
    return true;
}

/// The manifold of a round pair with speculative points up to md's margin (see the file comment).
template <class A, class B>
ContactManifold<typename A::scalar_type> round_manifold(const MinkowskiDifference<A, B>& md) {
    using T = typename A::scalar_type;
    const T margin = md.margin();
    const CorePair<T> p = core_pair_contact(md);
    ContactManifold<T> out;
    const T h = p.depth();
    if (!(h > -margin)) return out;
    const CoreContact<T>& cc = p.contact;
    // Candidates: the segment's parameter and the depth there along the normal.
    T ts[3], depths[3];
    int count = 0;
    auto keep = [&](T t, T depth) {
        if (depth > -margin) {
            ts[count] = t;
            depths[count] = depth;
            ++count;
        }
    };
    // Shorter clipped parts count as one point: a thousandth of the round shape's own size, never
    // of the pair's (a 400 m ground made capsules shorter than 0.57 m touch it by one point, which
    // rocked them end to end as they rolled and let them spin 7 % faster than they rolled).
    const T u_length = length(p.u);
    const T short_span = std::max(T(1e-3) * (u_length + p.radius_segment), touching_distance(md.scale()));
    if (p.round_round) {
        // Nearly parallel capsules side by side (within about 6°, as Capsule::support_face): B's
        // ends within A's extent, each at its own distance from A's core.
        const Vec3<T>& u = p.u;
        const bool parallel = p.e.y > T(0) && u_length > T(0) && u.x * u.x + u.z * u.z <= T(0.01) * length_squared(u);
        if (parallel && std::abs(cc.normal.y) <= T(0.1)) {
            T t0 = (-p.e.y - p.c.y) / u.y, t1 = (p.e.y - p.c.y) / u.y;
            if (t0 > t1) std::swap(t0, t1);
            t0 = std::max(t0, T(-1));
            t1 = std::min(t1, T(1));
            if ((t1 - t0) * u_length > short_span) {
                keep(t0, p.radius() - length(outside_box(p.segment_point(t0), p.e)));
                keep(t1, p.radius() - length(outside_box(p.segment_point(t1), p.e)));
                // Axes crossing between the ends: the closest point is deeper than both. It joins
                // them, or stands for the end it nearly coincides with.
                if (count == 2 && h > std::max(depths[0], depths[1]) + touching_distance(md.scale())) {
                    const int near_end = std::abs(cc.t - ts[0]) <= std::abs(cc.t - ts[1]) ? 0 : 1;
                    if (std::abs(cc.t - ts[near_end]) * u_length <= short_span) {
                        ts[near_end] = cc.t;
                        depths[near_end] = h;
                    } else {
                        keep(cc.t, h);
                    }
                }
            }
        }
    } else if (cc.face >= 0 && u_length > T(0)) {
        // A segment along a box face: the ends of its part within the face, each at its own height.
        T t0, t1;
        if (clip_to_face(p.c, p.u, p.e, cc.face, t0, t1) && (t1 - t0) * u_length > short_span) {
            const int k = cc.face;
            keep(t0, p.radius() - (cc.normal[k] * (p.c[k] + t0 * p.u[k]) - p.e[k]));
            keep(t1, p.radius() - (cc.normal[k] * (p.c[k] + t1 * p.u[k]) - p.e[k]));
        }
    }
    if (count < 2) {  // one point: the exact closest (or deepest) one
        count = 0;
        keep(cc.t, h);
    }
    out.normal = md.direction_to_world(core_normal(md, p));
    out.count = count;
    for (int i = 0; i < count; ++i) {
        Vec3<T> point_a, point_b;
        core_points(md, p, ts[i], depths[i], point_a, point_b);
        out.points[static_cast<std::size_t>(i)] = {md.point_to_world(point_a), md.point_to_world(point_b), depths[i]};
    }
    return out;
}

}  // namespace detail

}  // namespace xeno

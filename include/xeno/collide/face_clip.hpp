// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A whole contact manifold in one step, from one contact normal (docs/collision.md,
// "Contact manifolds by clipping"; after Box3D's b3BuildFaceAContact and Jolt's
// ManifoldBetweenTwoFaces):
//   1. each shape gives its supporting face along the normal (A along n, B along −n): a polygon
//      for a box or hull face, a cylinder cap or a cone base; a segment for a capsule's or a
//      cylinder's side; a point for a sphere or a rounded end;
//   2. the better aligned polygon is the reference face (A's on ties, so the choice is stable) and
//      the normal snaps to it; the other feature is the incident one;
//   3. the incident feature is clipped by the side planes of the reference face (Sutherland–
//      Hodgman); two segments clip each other's extent along the first;
//   4. every clipped point within the speculative margin of the reference plane becomes a contact
//      (incident point and its projection on the reference plane); depth = −separation;
//   5. more than four are reduced to four: the deepest, the farthest from it, the one making the
//      largest triangle, the one adding the most area (Box3D's b3ReduceManifoldPoints order).
// A point feature, or a clip that leaves nothing (edges crossing), gives one contact at the
// supplied fallback points. Everything here runs in A's local frame.
#pragma once

#include "../shape/support_face.hpp"
#include "minkowski.hpp"

#include <array>
#include <new>
#include <type_traits>

namespace xeno {

/// One contact of a manifold. Depth > 0 overlaps; depth < 0 is a speculative contact that far apart.
template <class T>
struct ManifoldPoint {
    Vec3<T> point_a{};  ///< world, on (or for speculative points, nearest to) A
    Vec3<T> point_b{};  ///< world, on B
    T depth{};          ///< metres along the manifold normal: > 0 overlap, < 0 gap
};

/// Up to four contacts sharing one normal, from A to B.
template <class T>
struct ContactManifold {
    static constexpr int capacity = 4;
    Vec3<T> normal{};                                 ///< unit, world, from A to B
    std::array<ManifoldPoint<T>, capacity> points{};  ///< the first `count` are valid
    int count = 0;
};

namespace detail {

/// N slots of a trivially copyable V that start unset, for scratch whose slots are each set
/// before they are read (a count says how many). Vec3 zeroes itself, and zeroing the two clip
/// polygons (436 bytes each in float) and the 36 candidate points (1 KB) of every manifold took
/// about 13 % of build_manifold's time in a pile of boxes.
template <class V, std::size_t N>
class Slots {
public:
    static_assert(std::is_trivially_copyable_v<V> && std::is_trivially_destructible_v<V>, "plain values only");
    Slots() {}  // leaves the slots unset: the point of the type
    /// Slot i takes v (its lifetime starts here).
    void set(std::size_t i, const V& v) { ::new (static_cast<void*>(&slot_[i])) V(v); }
    /// A slot that was set.
    V& operator[](std::size_t i) { return slot_[i]; }
    const V& operator[](std::size_t i) const { return slot_[i]; }

private:
    union {
        V slot_[N];
    };
};

template <class T>
struct ClipPolygon {
    static constexpr int capacity = 2 * SupportFace<T>::capacity + 4;
    Slots<Vec3<T>, capacity> p;  ///< the first `count` are set
    int count = 0;
    void push(const Vec3<T>& v) {
        if (count < capacity) p.set(static_cast<std::size_t>(count++), v);
    }
};

/// Candidate contact points of a clip (the first `count` set).
template <class T>
using ClipPoints = Slots<ManifoldPoint<T>, ClipPolygon<T>::capacity>;

/// Writes to `out` (not `in`) the part of the polygon `in` (or segment, or point) on the inner
/// side of the plane dot(x − origin, side) <= 0. Callers clip back and forth between two
/// polygons: a polygon is 436 bytes in float, and making one and copying it for every plane
/// (zeroed, as every Vec3 is) took a fifth of the clipping's time in a pile of boxes.
template <class T>
void clip_by_plane(const ClipPolygon<T>& in, const Vec3<T>& origin, const Vec3<T>& side, ClipPolygon<T>& out) {
    out.count = 0;
    if (in.count == 1) {
        if (dot(in.p[0] - origin, side) <= T(0)) out.push(in.p[0]);
        return;
    }
    // A segment is a polygon of two vertices whose closing edge retraces it; visiting only its one
    // edge keeps each clipped end once.
    const int edges = in.count == 2 ? 1 : in.count;
    for (int i = 0; i < edges; ++i) {
        const Vec3<T>& a = in.p[static_cast<std::size_t>(i)];
        const Vec3<T>& b = in.p[static_cast<std::size_t>((i + 1) % in.count)];
        const T da = dot(a - origin, side), db = dot(b - origin, side);
        if (da <= T(0)) out.push(a);
        if ((da < T(0)) != (db < T(0)) && da != db) out.push(a + (b - a) * (da / (da - db)));
        if (in.count == 2 && db <= T(0)) out.push(b);
    }
}

/// Reduces candidate contacts to at most four that keep the deepest and span the largest area.
/// `first`, if given, is kept in place of the deepest (a caller that knows better among ties).
template <class T>
int reduce_to_four(ClipPoints<T>& pts, int count, const Vec3<T>& normal, int first = -1) {
    if (count <= 4) return count;
    auto mid = [](const ManifoldPoint<T>& m) { return (m.point_a + m.point_b) * T(0.5); };
    int chosen[4];
    // 1. The deepest.
    chosen[0] = 0;
    for (int i = 1; i < count; ++i)
        if (pts[static_cast<std::size_t>(i)].depth > pts[static_cast<std::size_t>(chosen[0])].depth) chosen[0] = i;
    if (first >= 0) chosen[0] = first;
    const Vec3<T> p0 = mid(pts[static_cast<std::size_t>(chosen[0])]);
    // 2. The farthest from it.
    chosen[1] = chosen[0] == 0 ? 1 : 0;
    T best = -T(1);
    for (int i = 0; i < count; ++i) {
        const T d = length_squared(mid(pts[static_cast<std::size_t>(i)]) - p0);
        if (i != chosen[0] && d > best) {
            best = d;
            chosen[1] = i;
        }
    }
    const Vec3<T> p1 = mid(pts[static_cast<std::size_t>(chosen[1])]);
    // 3. The largest triangle with those two (signed, so 4. can look on the other side).
    chosen[2] = -1;
    T best_area = T(0);
    T signed_area = T(0);
    for (int i = 0; i < count; ++i) {
        if (i == chosen[0] || i == chosen[1]) continue;
        const T area = dot(cross(p1 - p0, mid(pts[static_cast<std::size_t>(i)]) - p0), normal);
        if (chosen[2] < 0 || std::abs(area) > best_area) {
            best_area = std::abs(area);
            signed_area = area;
            chosen[2] = i;
        }
    }
    const Vec3<T> p2 = mid(pts[static_cast<std::size_t>(chosen[2])]);
    // 4. The point adding the most area on the far side of one of the triangle's edges.
    chosen[3] = -1;
    best_area = T(0);
    const Vec3<T> tri[3] = {p0, p1, p2};
    for (int i = 0; i < count; ++i) {
        if (i == chosen[0] || i == chosen[1] || i == chosen[2]) continue;
        const Vec3<T> q = mid(pts[static_cast<std::size_t>(i)]);
        for (int e = 0; e < 3; ++e) {
            // Area outside edge e, with the triangle's winding taken from its signed area.
            const T area = -dot(cross(tri[(e + 1) % 3] - tri[e], q - tri[e]), normal) * (signed_area >= T(0) ? T(1) : T(-1));
            if (area > best_area) {
                best_area = area;
                chosen[3] = i;
            }
        }
    }
    const int kept = chosen[3] < 0 ? 3 : 4;
    std::array<ManifoldPoint<T>, 4> picked;
    for (int k = 0; k < kept; ++k) picked[static_cast<std::size_t>(k)] = pts[static_cast<std::size_t>(chosen[k])];
    for (int k = 0; k < kept; ++k) pts[static_cast<std::size_t>(k)] = picked[static_cast<std::size_t>(k)];
    return kept;
}

}  // namespace detail

/// The manifold of A and B for the unit normal n (A's frame, from A to B). fallback_a/_b are the
/// single-contact points (A's frame) used for point features and empty clips, with depth
/// fallback_depth along n. Points deeper than -margin (metres) are kept.
template <class A, class B>
ContactManifold<typename A::scalar_type> build_manifold(const MinkowskiDifference<A, B>& md,
                                                        const Vec3<typename A::scalar_type>& n,
                                                        const Vec3<typename A::scalar_type>& fallback_a,
                                                        const Vec3<typename A::scalar_type>& fallback_b,
                                                        typename A::scalar_type fallback_depth, typename A::scalar_type margin) {
    using T = typename A::scalar_type;
    const SupportFace<T> face_a = md.shape_a().support_face(n);
    SupportFace<T> face_b = md.shape_b().support_face(md.direction_to_b(-n));
    for (int i = 0; i < face_b.count; ++i) face_b.vertex[static_cast<std::size_t>(i)] = md.to_a(face_b[i]);
    face_b.normal = md.direction_to_a(face_b.normal);

    ContactManifold<T> out;
    auto single = [&]() {
        out.normal = md.direction_to_world(n);
        out.count = 1;
        out.points[0] = {md.point_to_world(fallback_a), md.point_to_world(fallback_b), fallback_depth};
        return out;
    };

    // Reference: the better aligned polygon (A on ties); a segment pair uses A's segment. A
    // feature only counts when it faces along n (within about 2.5°): otherwise the contact is an
    // edge or a rim, and clipping a face that does not face the partner would invent points.
    const T aligned = T(0.999);
    const bool a_polygon = face_a.count >= 3 && dot(face_a.normal, n) >= aligned;
    const bool b_polygon = face_b.count >= 3 && dot(face_b.normal, -n) >= aligned;
    bool reference_is_a;
    if (a_polygon && b_polygon) reference_is_a = dot(face_a.normal, n) + T(0.01) >= dot(face_b.normal, -n);
    else if (a_polygon || b_polygon) reference_is_a = a_polygon;
    else if (face_a.count == 2 && face_b.count == 2 && std::abs(dot(face_a.normal, n)) >= aligned &&
             std::abs(dot(face_b.normal, n)) >= aligned)
        reference_is_a = true;
    else return single();  // a point feature: the single contact is exact

    const SupportFace<T>& ref = reference_is_a ? face_a : face_b;
    const SupportFace<T>& inc = reference_is_a ? face_b : face_a;
    detail::ClipPolygon<T> polygons[2];  // the incident feature, clipped back and forth (clip_by_plane)
    int current = 0;
    for (int i = 0; i < inc.count; ++i) polygons[0].push(inc[i]);
    const auto clip = [&](const Vec3<T>& origin, const Vec3<T>& side) {
        detail::clip_by_plane(polygons[current], origin, side, polygons[1 - current]);
        current = 1 - current;
    };

    Vec3<T> ref_normal;  // outward normal of the reference feature, on the reference body
    if (ref.count >= 3) {
        ref_normal = ref.normal;
        for (int i = 0; i < ref.count && polygons[current].count > 0; ++i) {
            const Vec3<T>& r0 = ref[i];
            const Vec3<T>& r1 = ref[(i + 1) % ref.count];
            clip(r0, cross(r1 - r0, ref_normal));
        }
    } else {
        // Segment against segment: keep B's segment within A's segment's extent, and measure
        // along the contact normal.
        ref_normal = n;
        const Vec3<T> axis = ref[1] - ref[0];
        clip(ref[0], -axis);
        if (polygons[current].count > 0) clip(ref[1], axis);
    }
    const detail::ClipPolygon<T>& poly = polygons[current];
    if (poly.count == 0) return single();

    // The manifold normal is the reference normal, pointing from A to B.
    const Vec3<T> normal = reference_is_a ? ref_normal : -ref_normal;
    detail::ClipPoints<T> pts;
    int count = 0;
    for (int i = 0; i < poly.count; ++i) {
        const Vec3<T>& p = poly.p[static_cast<std::size_t>(i)];
        // Separation of the incident point from the reference plane (or line), > 0 outside.
        Vec3<T> on_ref;
        if (ref.count >= 3) {
            on_ref = p - ref_normal * dot(p - ref[0], ref_normal);
        } else {
            // A segment too short for its length squared (a capsule of subnormal half height) is
            // its point: dividing by that 0 gave the manifold NaN anchors.
            const Vec3<T> axis = ref[1] - ref[0];
            const T axis_sq = length_squared(axis);
            on_ref = axis_sq > T(0) ? ref[0] + axis * clamp(dot(p - ref[0], axis) / axis_sq, T(0), T(1)) : ref[0];
        }
        const T separation = dot(p - on_ref, ref_normal);
        if (separation > margin) continue;
        const Vec3<T> pa = reference_is_a ? on_ref : p;
        const Vec3<T> pb = reference_is_a ? p : on_ref;
        pts.set(static_cast<std::size_t>(count++), {pa, pb, -separation});
    }
    if (count == 0) return single();
    count = detail::reduce_to_four(pts, count, normal);
    out.normal = md.direction_to_world(normal);
    out.count = count;
    for (int i = 0; i < count; ++i) {
        const ManifoldPoint<T>& m = pts[static_cast<std::size_t>(i)];
        out.points[static_cast<std::size_t>(i)] = {md.point_to_world(m.point_a), md.point_to_world(m.point_b), m.depth};
    }
    return out;
}

namespace f32 {
using ContactManifold = xeno::ContactManifold<float>;
using ManifoldPoint = xeno::ManifoldPoint<float>;
}  // namespace f32
namespace f64 {
using ContactManifold = xeno::ContactManifold<double>;
using ManifoldPoint = xeno::ManifoldPoint<double>;
}  // namespace f64

}  // namespace xeno

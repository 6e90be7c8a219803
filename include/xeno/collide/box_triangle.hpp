// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A box against one triangle of a mesh by separating axes in closed form, the mesh's fast path
// for the most common body (docs/meshes.md, "Boxes on triangles"). Both are polytopes, so the
// least-overlap axis among 13 candidates is the exact least-depth normal: the triangle's normal,
// the box's three face normals, and the nine cross products of a triangle edge with a box axis
// (the set of Akenine-Möller's triangle–box overlap test, "Fast 3D triangle-box overlap testing",
// JGT 2001, and of Eberly's "method of separating axes"). Each axis costs three projected
// vertices against one projected box; the whole test takes a quarter to a third of the time of
// MPR with its least-depth expansion (xeno_mesh_bench: 318 ns against 1.1-1.3 us a pair).
// Faces win ties as in box_box.hpp: the triangle's normal first, a box face only when clearly
// shallower, an edge pair only when shallower by a slack, so a box resting on a triangle gets the
// triangle's exact normal.
#pragma once

#include "../shape/box.hpp"
#include "../shape/triangle.hpp"
#include "contact_points.hpp"
#include "minkowski.hpp"

#include <algorithm>
#include <cmath>

namespace xeno {

namespace detail {

/// How far the triangle and the box overlap along one unit axis: the lesser of the two pushes
/// that would part them (the box along +axis or along −axis), and the direction of that push,
/// from the triangle to the box. Negative: apart by that much.
template <class T>
struct AxisOverlap {
    T overlap;
    Vec3<T> normal;
};

/// The overlap along `axis` (unit, the box's frame) of triangle v (in the box's frame, so the
/// box is centred at the origin with its faces square to the axes) and the box of half-extents e.
template <class T>
AxisOverlap<T> overlap_along(const Vec3<T> (&v)[3], const Vec3<T>& e, const Vec3<T>& axis) {
    const T p0 = dot(v[0], axis), p1 = dot(v[1], axis), p2 = dot(v[2], axis);
    const T low = std::min({p0, p1, p2}), high = std::max({p0, p1, p2});
    const T radius = e.x * std::abs(axis.x) + e.y * std::abs(axis.y) + e.z * std::abs(axis.z);
    const T up = high + radius;   // the box pushed along +axis clears the triangle
    const T down = radius - low;  // along −axis
    if (up <= down) return {up, axis};
    return {down, -axis};
}

/// The least-overlap axis of a triangle (A) and a box (B), A's frame: normal n from the triangle
/// to the box, overlap h (< 0: apart by −h, at most the margin) and the fallback single-contact
/// points build_manifold needs for point features (h apart along n). Returns false as soon as an
/// axis parts them by more than the margin (then n, h and the points are not set). The axes are
/// tried in the box's frame, where its face normals are the unit axes and an edge pair's axis is
/// a triangle edge with two components swapped (Akenine-Möller's form).
template <class T>
bool box_triangle_axis(const MinkowskiDifference<Triangle<T>, Box<T>>& md, Vec3<T>& n, T& h, Vec3<T>& point_a, Vec3<T>& point_b) {
    const T margin = md.margin();
    const MeshTriangle<T>& t = md.shape_a().triangle();
    const Vec3<T>& e = md.shape_b().half_extents();
    const Vec3<T> centre = md.to_a(Vec3<T>::zero());
    Vec3<T> v[3];
    for (int i = 0; i < 3; ++i) v[i] = md.direction_to_b(t.v[i] - centre);  // the triangle in the box's frame

    AxisOverlap<T> best = overlap_along(v, e, md.direction_to_b(t.normal));
    if (best.overlap < -margin) return false;
    bool triangle_face = true;
    for (int j = 0; j < 3; ++j) {
        const AxisOverlap<T> o = overlap_along(v, e, Vec3<T>::axis(j));
        if (o.overlap < -margin) return false;
        if (o.overlap < best.overlap - T(1e-4) * e[j]) best = o, triangle_face = false;  // only if clearly shallower
    }
    // Edge pairs. A cross product of nearly parallel edges is mostly round-off (relative error
    // ε / sin θ), so pairs within √ε of parallel are left to the face axes: the sliver of the
    // Minkowski difference they stand for is at most that thin (√ε × the size: 0.3 mm per metre
    // in float), and the two errors balance there.
    const T parallel = std::sqrt(ScalarTraits<T>::epsilon);
    const T slack = T(1e-3) * min_component(e);
    AxisOverlap<T> edge{best.overlap - slack, {}};
    int best_edge = -1;
    for (int k = 0; k < 3; ++k) {
        const Vec3<T> d = v[(k + 1) % 3] - v[k];
        const T edge_length = length(d);
        const Vec3<T> axes[3] = {{T(0), d.z, -d.y}, {-d.z, T(0), d.x}, {d.y, -d.x, T(0)}};  // d × x, d × y, d × z
        for (int j = 0; j < 3; ++j) {
            const T len = length(axes[j]);
            if (!(len > parallel * edge_length)) continue;
            const AxisOverlap<T> o = overlap_along(v, e, axes[j] / len);
            if (o.overlap < -margin) return false;
            if (o.overlap < edge.overlap) edge = o, best_edge = 3 * k + j;
        }
    }
    if (best_edge >= 0) {
        h = edge.overlap;
        // The triangle's feature along the normal: edge k, or the corner opposite when it
        // reaches farther (a degenerate segment); the box's edge along axis j through its
        // support point against the normal. Closest points in the box's frame, then to A's.
        const int k = best_edge / 3, j = best_edge % 3;
        Vec3<T> a0 = v[k], a1 = v[(k + 1) % 3];
        const Vec3<T>& opposite = v[(k + 2) % 3];
        if (dot(opposite - a0, edge.normal) > T(0)) a0 = a1 = opposite;
        Vec3<T> b0 = md.shape_b().support(-edge.normal), b1 = b0;
        b0[j] = -e[j];
        b1[j] = e[j];
        Vec3<T> ca, cb;
        closest_points_of_segments(a0, a1, b0, b1, ca, cb);
        n = md.direction_to_a(edge.normal);
        const Vec3<T> middle = md.to_a((ca + cb) * T(0.5));
        point_a = middle + n * (T(0.5) * h);
        point_b = middle - n * (T(0.5) * h);
        return true;
    }
    h = best.overlap;
    if (triangle_face) {  // the box's deepest corner and its projection on the triangle's plane
        n = t.normal * (dot(best.normal, md.direction_to_b(t.normal)) >= T(0) ? T(1) : T(-1));  // the exact normal
        point_b = md.to_a(md.shape_b().support(-best.normal));
        point_a = point_b + n * h;
    } else {  // the triangle's deepest corner and its projection on the box's face
        n = md.direction_to_a(best.normal);
        point_a = md.shape_a().support(n);
        point_b = point_a - n * h;
    }
    return true;
}

}  // namespace detail

}  // namespace xeno

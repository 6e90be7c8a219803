// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Box against box by separating axes in closed form, the fast path of the narrow phase for the
// most common pair (docs/collision.md, "Box against box": only 15 axes, each with a closed-form
// overlap, so cheaper than MPR and exact). Gottschalk, Lin & Manocha, "OBBTree"
// (SIGGRAPH 1996), in the form of Ericson, "Real-Time Collision Detection" 4.4.1: in A's frame,
// with R the rotation of B and t the offset of B, each axis's overlap is the sum of the two
// projected radii minus the projected centre distance. The 6 face axes are tried first; one of the
// 9 edge-edge axes wins only if it is shallower by a slack, so resting boxes keep face normals.
// For an edge-edge axis the contact is the pair of closest points of the two support edges.
#pragma once

#include "../shape/box.hpp"
#include "contact_points.hpp"
#include "minkowski.hpp"

namespace xeno {

namespace detail {

/// The points of an edge-edge contact along n with overlap h: the closest points of A's edge
/// along its axis i through its support point along n and B's edge along its axis j through its
/// support point along -n, put h apart along n around their middle, as for the other pairs.
template <class T>
void edge_contact_points(const MinkowskiDifference<Box<T>, Box<T>>& md, const Vec3<T>& n, T h, int i, int j, Vec3<T>& point_a,
                         Vec3<T>& point_b) {
    const Vec3<T>& a = md.shape_a().half_extents();
    const Vec3<T>& b = md.shape_b().half_extents();
    Vec3<T> pa = md.shape_a().support(n), pb_local = md.shape_b().support(md.direction_to_b(-n));
    Vec3<T> qa = pa, qb_local = pb_local;
    pa[i] = -a[i];
    qa[i] = a[i];
    pb_local[j] = -b[j];
    qb_local[j] = b[j];
    closest_points_of_segments(pa, qa, md.to_a(pb_local), md.to_a(qb_local), point_a, point_b);
    const Vec3<T> middle = (point_a + point_b) * T(0.5);
    point_a = middle + n * (T(0.5) * h);
    point_b = middle - n * (T(0.5) * h);
}

/// The single-contact points of a face contact along n with overlap h, `face` the reference face's
/// axis (0–2: A's, 3–5: B's).
template <bool OnSurfaces, class T>
void face_contact_points(const MinkowskiDifference<Box<T>, Box<T>>& md, const Vec3<T>& n, T h, int face, Vec3<T>& point_a,
                         Vec3<T>& point_b) {
    if constexpr (OnSurfaces) {
        // collide(): the incident box's deepest corner when it is its only deepest point and lies
        // over the reference face (then it and its projection are on both surfaces: the common
        // case, and cheap); else the middle of where the two support features overlap across n,
        // lifted onto both surfaces (contact_points.hpp). The corner alone can be metres outside
        // a small box when the other is large. An incident edge or face (within the tolerance
        // place_contact_points uses) has no one deepest corner: which corner the support picked
        // depended on which box was A, and collide(B, A) put the point 0.7 m from collide(A, B)'s
        // for a box resting flat on a larger one.
        const T tau = std::max(ScalarTraits<T>::geometric_tolerance, T(1e-7)) * md.scale();
        auto over_face = [](const Vec3<T>& p, const Vec3<T>& half, int axis) {
            for (int k = 0; k < 3; ++k)
                if (k != axis && std::abs(p[k]) > half[k]) return false;
            return true;
        };
        if (face < 3) {
            const Vec3<T> d = md.direction_to_b(-n);
            const Vec3<T> corner_b = md.to_a(md.shape_b().support(d));
            if (support_feature(md.shape_b(), d, tau).count == 1 && over_face(corner_b, md.shape_a().half_extents(), face)) {
                point_b = corner_b;
                point_a = corner_b + n * h;
                return;
            }
        } else {
            const Vec3<T> corner_a = md.shape_a().support(n);
            const Vec3<T> t = md.to_a(Vec3<T>::zero());
            if (support_feature(md.shape_a(), n, tau).count == 1 &&
                over_face(transposed_transform(md.rotation_b(), corner_a - t), md.shape_b().half_extents(), face - 3)) {
                point_a = corner_a;
                point_b = corner_a - n * h;
                return;
            }
        }
        place_contact_points(md, n, h, static_cast<const Vec3<T>*>(nullptr), point_a, point_b);
        return;
    }
    // The manifold's fallback (face contacts get their points from clipping): B's deepest vertex
    // and its projection.
    point_b = md.to_a(md.shape_b().support(md.direction_to_b(-n)));
    point_a = point_b + n * h;
}

/// The least-overlap axis of two boxes (A's frame): normal n from A to B, overlap h (< 0 means
/// separated by −h, at most the margin), and single-contact points (on both surfaces for edge
/// contacts, and for face contacts too with OnSurfaces, collide()'s contract).
/// Returns false as soon as an axis separates them by more than the margin (then n, h, points
/// are not set).
template <bool OnSurfaces = false, class T>
bool box_box_axis(const MinkowskiDifference<Box<T>, Box<T>>& md, Vec3<T>& n, T& h, Vec3<T>& point_a, Vec3<T>& point_b) {
    const T margin = md.margin();
    const Vec3<T>& a = md.shape_a().half_extents();
    const Vec3<T>& b = md.shape_b().half_extents();
    const Mat3<T>& r = md.rotation_b();
    const Vec3<T> t = md.to_a(Vec3<T>::zero());
    // |R| for the face axes; plus a little for the edge axes, so that near-parallel edges (cross
    // product ~ 0) cannot win by round-off. With the little in the face axes too, every face
    // overlap grew by 16 ε (Σ b): boxes sharing a face, touching without overlap, were a hit.
    const T eps = T(16) * ScalarTraits<T>::epsilon;
    Mat3<T> abs_r, abs_r_edge;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) abs_r[i][j] = std::abs(r[i][j]), abs_r_edge[i][j] = abs_r[i][j] + eps;

    int best_axis = 0;  // 0–2: A's faces, 3–5: B's faces, 6–14: edge pairs
    T best = ScalarTraits<T>::infinity;
    for (int i = 0; i < 3; ++i) {
        const T overlap = a[i] + dot(abs_r[i], b) - std::abs(t[i]) + margin;
        if (overlap < T(0)) return false;  // separated along A's face axis
        if (overlap < best) {
            best = overlap;
            best_axis = i;
        }
    }
    const Vec3<T> t_in_b = transposed_transform(r, t);
    for (int j = 0; j < 3; ++j) {
        const T overlap = dot(abs_r.column(j), a) + b[j] - std::abs(t_in_b[j]) + margin;
        if (overlap < T(0)) return false;
        if (overlap < best - T(1e-4) * (a[j % 3] + b[j])) {  // B's face only if clearly shallower
            best = overlap;
            best_axis = 3 + j;
        }
    }
    const T slack = T(1e-3) * std::min(min_component(a), min_component(b));
    int best_edge = -1;
    T best_edge_overlap = best - slack;
    Vec3<T> best_edge_axis;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const Vec3<T> axis = cross(Vec3<T>::axis(i), r.column(j));
            const T len = length(axis);
            if (len < T(1e-5)) continue;  // parallel edges: the face axes cover them
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const T ra = a[i1] * abs_r_edge[i2][j] + a[i2] * abs_r_edge[i1][j];
            const T rb = b[j1] * abs_r_edge[i][j2] + b[j2] * abs_r_edge[i][j1];
            const T overlap = (ra + rb - std::abs(dot(t, axis))) / len + margin;
            if (overlap < T(0)) return false;
            if (overlap < best_edge_overlap) {
                best_edge_overlap = overlap;
                best_edge = 3 * i + j;
                best_edge_axis = axis / len;
            }
        }
    }
    if (best_edge >= 0) {
        n = dot(best_edge_axis, t) >= T(0) ? best_edge_axis : -best_edge_axis;
        h = best_edge_overlap - margin;
        edge_contact_points(md, n, h, best_edge / 3, best_edge % 3, point_a, point_b);
        return true;
    }
    h = best - margin;
    if (best_axis < 3) {
        n = Vec3<T>::axis(best_axis) * (t[best_axis] >= T(0) ? T(1) : T(-1));
    } else {
        const int j = best_axis - 3;
        n = r.column(j) * (t_in_b[j] >= T(0) ? T(1) : T(-1));
    }
    face_contact_points<OnSurfaces>(md, n, h, best_axis, point_a, point_b);
    return true;
}

}  // namespace detail

}  // namespace xeno

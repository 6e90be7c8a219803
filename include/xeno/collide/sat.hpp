// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Separating-axis test for polytopes (boxes and convex polyhedra): the exact minimum penetration
// depth and its axis. D = A ⊖ B is the polytope whose face normals are A's face normals, B's face
// normals negated, and cross products of an edge of A with an edge of B; the minimum of D's support
// function over those axes is the distance from the origin to D's boundary (Gottschalk's SAT; see
// Ericson, "Real-Time Collision Detection", 4.4 and 5.2.1). Negative means separated by that much.
// Used as the reference that MPR's depth is measured against, and by the narrow phase for box–box.
#pragma once

#include "../shape/box.hpp"
#include "../shape/convex_polyhedron.hpp"
#include "minkowski.hpp"

#include <vector>

namespace xeno {

/// Minimum of D's support function over the separating axes: depth (m, > 0 overlap) along axis
/// (unit, world, from A to B).
template <class T>
struct SeparatingAxis {
    T depth{};       ///< metres: positive = penetration depth, negative = separation
    Vec3<T> axis{};  ///< unit, world frame, from A to B
};

namespace detail {

template <class T>
void polytope_axes(const Box<T>&, std::vector<Vec3<T>>& faces, std::vector<Vec3<T>>& edges) {
    for (int i = 0; i < 3; ++i) {
        faces.push_back(Vec3<T>::axis(i));
        faces.push_back(-Vec3<T>::axis(i));
        edges.push_back(Vec3<T>::axis(i));
    }
}

template <class T>
void polytope_axes(const ConvexPolyhedron<T>& p, std::vector<Vec3<T>>& faces, std::vector<Vec3<T>>& edges) {
    for (const auto& f : p.faces()) faces.push_back(f.normal);
    for (const auto& e : p.edges()) edges.push_back(p.vertices()[e.second] - p.vertices()[e.first]);
}

}  // namespace detail

/// Exact minimum penetration (or separation) of two placed polytopes by brute force over all
/// candidate axes: O(faces + edges_A × edges_B) support evaluations.
template <class A, class B>
SeparatingAxis<typename A::scalar_type> separating_axis(const A& a, const Transform<typename A::scalar_type>& pose_a, const B& b,
                                                        const Transform<typename A::scalar_type>& pose_b) {
    using T = typename A::scalar_type;
    const MinkowskiDifference<A, B> md(a, pose_a, b, pose_b);
    std::vector<Vec3<T>> faces_a, edges_a, faces_b, edges_b;
    detail::polytope_axes(a, faces_a, edges_a);
    detail::polytope_axes(b, faces_b, edges_b);
    SeparatingAxis<T> best{ScalarTraits<T>::infinity, Vec3<T>::unit_y()};
    auto consider = [&](const Vec3<T>& axis) {
        const T h = dot(md.support(axis).v, axis);
        if (h < best.depth) best = {h, axis};
    };
    for (const Vec3<T>& n : faces_a) consider(n);
    for (const Vec3<T>& n : faces_b) consider(-md.direction_to_a(n));
    const T eps = ScalarTraits<T>::relative_tolerance;
    for (const Vec3<T>& ea : edges_a)
        for (const Vec3<T>& eb_local : edges_b) {
            const Vec3<T> eb = md.direction_to_a(eb_local);
            const Vec3<T> c = cross(ea, eb);
            const T c_sq = length_squared(c);
            if (c_sq <= eps * eps * length_squared(ea) * length_squared(eb)) continue;  // parallel edges
            const Vec3<T> n = c / std::sqrt(c_sq);
            consider(n);
            consider(-n);
        }
    best.axis = md.direction_to_world(best.axis);
    return best;
}

namespace f32 {
using SeparatingAxis = xeno::SeparatingAxis<float>;
}
namespace f64 {
using SeparatingAxis = xeno::SeparatingAxis<double>;
}

}  // namespace xeno

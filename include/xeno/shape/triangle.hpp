// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Triangle<T>: one triangle of a mesh or heightfield as a convex shape the narrow phase can take
// (a flat hull of three points: MPR needs only supports, and the Minkowski difference of a
// triangle and a convex body has volume, so the portal search works unchanged). Vertices are in
// the mesh's local frame, counter-clockwise seen from the front (the side the normal points to).
//
// MPR starts from a point inside A ⊖ B, by default the difference of the two centres. For a large
// triangle and a small body the ray from the centroid runs almost parallel to the triangle and can
// leave through the body's side; the triangle's interior point is therefore set per query to the
// point of the triangle closest to the body's centre (any point of a flat shape will do: the body
// has volume, so the difference is still strictly inside A ⊖ B), which makes the ray leave
// through the face or the edge the body actually touches (docs/meshes.md, "Triangles in MPR").
#pragma once

#include "../math/aabb.hpp"
#include "support_face.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace xeno {

/// A triangle of a mesh with what edge handling needs (docs/meshes.md, "Internal edges"): its
/// unit normal (front side), which of its edges are active (edge i runs from v[i] to
/// v[(i + 1) % 3]; bit i set: a contact normal from that edge may be kept; clear: the neighbour
/// across it is coplanar or concave and such a normal is replaced by the face normal), and for
/// each active edge how far such a normal may turn from the face's: the cosine of the fold, the
/// angle between this face's normal and the neighbour's (−1 at a border, where any turn is real).
template <class T>
struct MeshTriangle {
    Vec3<T> v[3];
    Vec3<T> normal{};
    std::uint8_t active_edges = 7;
    T fold_cos[3] = {T(-1), T(-1), T(-1)};
};

namespace detail {

/// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection 5.1.5).
template <class T>
Vec3<T> closest_point_on_triangle(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
    const Vec3<T> ab = b - a, ac = c - a, ap = p - a;
    const T d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= T(0) && d2 <= T(0)) return a;
    const Vec3<T> bp = p - b;
    const T d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= T(0) && d4 <= d3) return b;
    const T vc = d1 * d4 - d3 * d2;
    if (vc <= T(0) && d1 >= T(0) && d3 <= T(0)) return a + ab * (d1 / (d1 - d3));
    const Vec3<T> cp = p - c;
    const T d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= T(0) && d5 <= d6) return c;
    const T vb = d5 * d2 - d1 * d6;
    if (vb <= T(0) && d2 >= T(0) && d6 <= T(0)) return a + ac * (d2 / (d2 - d6));
    const T va = d3 * d6 - d5 * d4;
    if (va <= T(0) && (d4 - d3) >= T(0) && (d5 - d6) >= T(0)) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const T denom = T(1) / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace detail

/// A triangle as a convex shape for the narrow phase (see the file comment).
template <class T>
class Triangle {
public:
    using scalar_type = T;

    /// The triangle of `t`, with `inside` (a point of the triangle) as MPR's interior point.
    Triangle(const MeshTriangle<T>& t, const Vec3<T>& inside) : tri_(t), inside_(inside) {
        const Vec3<T> centre = (t.v[0] + t.v[1] + t.v[2]) / T(3);
        for (const Vec3<T>& v : t.v) radius_ = std::max(radius_, length(v - centre));
        radius_ += length(inside - centre);  // a sphere about `inside` that holds the triangle
    }

    const MeshTriangle<T>& triangle() const { return tri_; }
    const Vec3<T>& vertex(int i) const { return tri_.v[i]; }
    const Vec3<T>& normal() const { return tri_.normal; }

    /// The vertex farthest along d (the lowest index on ties, so the answer is deterministic).
    Vec3<T> support(const Vec3<T>& d) const { return tri_.v[support_index(d)]; }
    int support_index(const Vec3<T>& d) const {
        int best = 0;
        T best_dot = dot(tri_.v[0], d);
        for (int i = 1; i < 3; ++i) {
            const T x = dot(tri_.v[i], d);
            if (x > best_dot) best_dot = x, best = i;
        }
        return best;
    }
    /// The triangle itself (wound counter-clockwise seen along d) when d is within 45° of ±normal;
    /// otherwise the supporting edge when both its ends are within a thousandth of the size of the
    /// support plane, else the supporting vertex.
    SupportFace<T> support_face(const Vec3<T>& d) const {
        SupportFace<T> face;
        const T along = dot(d, tri_.normal);
        if (along * along >= T(0.5) * length_squared(d)) {
            const bool front = along >= T(0);
            face.normal = front ? tri_.normal : -tri_.normal;
            for (int k = 0; k < 3; ++k) face.push(tri_.v[front ? k : 2 - k]);
            return face;
        }
        face.normal = normalized_or(d, tri_.normal);
        const int top = support_index(d);
        const int next = (top + 1) % 3, prev = (top + 2) % 3;
        const int second = dot(tri_.v[next], d) >= dot(tri_.v[prev], d) ? next : prev;
        face.push(tri_.v[top]);
        if (dot(tri_.v[top] - tri_.v[second], face.normal) <= T(1e-3) * radius_) face.push(tri_.v[second]);
        return face;
    }
    /// ±normal when d is within 45° of it (the face the narrow phase tries as a contact normal).
    std::optional<Vec3<T>> flat_normal(const Vec3<T>& d) const {
        const T along = dot(d, tri_.normal);
        if (along * along < T(0.5) * length_squared(d)) return std::nullopt;
        return along >= T(0) ? tri_.normal : -tri_.normal;
    }
    Aabb<T> local_bounds() const {
        Aabb<T> box;
        for (const Vec3<T>& v : tri_.v) box.merge(v);
        return box;
    }
    T bounding_radius() const { return radius_; }
    Vec3<T> interior_point() const { return inside_; }
    /// Flat: no box of volume fits inside, so the interior point stays where the query put it.
    Vec3<T> inner_half_extents() const { return Vec3<T>::zero(); }

private:
    MeshTriangle<T> tri_;
    Vec3<T> inside_;
    T radius_ = T(0);
};

namespace f32 {
using MeshTriangle = xeno::MeshTriangle<float>;
using Triangle = xeno::Triangle<float>;
}  // namespace f32
namespace f64 {
using MeshTriangle = xeno::MeshTriangle<double>;
using Triangle = xeno::Triangle<double>;
}  // namespace f64

}  // namespace xeno

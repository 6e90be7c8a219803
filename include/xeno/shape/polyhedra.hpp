// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Builders for common convex polyhedra, each centred on its centre of mass: box, the thesis's
// triangular prism (3.2.2.4), regular tetrahedron and regular n-sided prism. Sizes are in metres
// and must be finite and > 0 (InvalidArgument otherwise). Prism axes follow docs/conventions.md:
// local y.
#pragma once

#include "../math/quat.hpp"
#include "convex_polyhedron.hpp"

namespace xeno {

/// A box as a polyhedron (8 vertices, 6 quads), for code that wants the general polytope path.
template <class T>
ConvexPolyhedron<T> make_box_polyhedron(const Vec3<T>& half_extents) {
    detail::require_positive(half_extents.x, "make_box_polyhedron", "half_extents.x");
    detail::require_positive(half_extents.y, "make_box_polyhedron", "half_extents.y");
    detail::require_positive(half_extents.z, "make_box_polyhedron", "half_extents.z");
    std::vector<Vec3<T>> v;
    for (int i = 0; i < 8; ++i)  // bit 0: x, bit 1: y, bit 2: z; set bit = + side
        v.push_back({(i & 1) ? half_extents.x : -half_extents.x, (i & 2) ? half_extents.y : -half_extents.y,
                     (i & 4) ? half_extents.z : -half_extents.z});
    return ConvexPolyhedron<T>(std::move(v),
                               {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}});
}

/// A right prism whose cross-section (in x-y) is the isosceles triangle with base 2·half_width
/// and the given height, extruded ±half_depth along z; re-centred on its centroid.
template <class T>
ConvexPolyhedron<T> make_triangular_prism(T half_width, T height, T half_depth) {
    detail::require_positive(half_width, "make_triangular_prism", "half_width");
    detail::require_positive(height, "make_triangular_prism", "height");
    detail::require_positive(half_depth, "make_triangular_prism", "half_depth");
    const T c = height / T(3);  // centroid of the triangle above its base
    std::vector<Vec3<T>> v{{-half_width, -c, -half_depth}, {half_width, -c, -half_depth}, {T(0), height - c, -half_depth},
                           {-half_width, -c, half_depth},  {half_width, -c, half_depth},  {T(0), height - c, half_depth}};
    return ConvexPolyhedron<T>(std::move(v), {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}});
}

/// A regular tetrahedron with the given edge length, centred, one face down (normal -y).
template <class T>
ConvexPolyhedron<T> make_tetrahedron(T edge) {
    detail::require_positive(edge, "make_tetrahedron", "edge");
    // Vertices of alternate corners of a cube of side edge/√2 are a regular tetrahedron; rotate so
    // that one face is horizontal.
    const T s = edge / (T(2) * std::sqrt(T(2)));
    const Vec3<T> corners[4] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
    const Quat<T> tilt = Quat<T>::from_to(normalized(Vec3<T>{T(1), T(1), T(1)}), Vec3<T>::unit_y());
    std::vector<Vec3<T>> v;
    for (const Vec3<T>& p : corners) v.push_back(rotate(tilt, p));
    return ConvexPolyhedron<T>(std::move(v), {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
}

/// A regular prism with n >= 3 sides (circumradius `radius`), height 2·half_height along y.
template <class T>
ConvexPolyhedron<T> make_regular_prism(int sides, T radius, T half_height) {
    if (sides < 3) detail::report_invalid("make_regular_prism", "sides must be >= 3", sides);
    detail::require_positive(radius, "make_regular_prism", "radius");
    detail::require_positive(half_height, "make_regular_prism", "half_height");
    const std::uint32_t n = static_cast<std::uint32_t>(sides);
    std::vector<Vec3<T>> v;
    for (std::uint32_t k = 0; k < n; ++k) {
        const T angle = T(2) * ScalarTraits<T>::pi * static_cast<T>(k) / static_cast<T>(n);
        const T x = radius * std::cos(angle), z = radius * std::sin(angle);
        v.push_back({x, -half_height, z});
        v.push_back({x, half_height, z});
    }
    std::vector<std::vector<std::uint32_t>> faces(2);
    for (std::uint32_t k = 0; k < n; ++k) {
        faces[0].push_back(2 * k);                // bottom, counter-clockwise from -y: increasing angle
        faces[1].push_back(2 * (n - 1 - k) + 1);  // top, counter-clockwise from +y: decreasing angle
        const std::uint32_t next = (k + 1) % n;
        faces.push_back({2 * k, 2 * k + 1, 2 * next + 1, 2 * next});
    }
    return ConvexPolyhedron<T>(std::move(v), faces);
}

}  // namespace xeno

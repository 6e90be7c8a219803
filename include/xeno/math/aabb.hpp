// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Aabb<T>: an axis-aligned box [min, max], the bounding volume of the broad phase. The default
// value is empty (min = +inf, max = -inf), so merging points into it grows it from nothing.
#pragma once

#include "vec3.hpp"

namespace xeno {

/// An axis-aligned bounding box; empty when min > max on some axis.
template <class T>
struct Aabb {
    using scalar_type = T;

    Vec3<T> min{ScalarTraits<T>::infinity, ScalarTraits<T>::infinity, ScalarTraits<T>::infinity};
    Vec3<T> max{-ScalarTraits<T>::infinity, -ScalarTraits<T>::infinity, -ScalarTraits<T>::infinity};

    /// The box [centre - half_extents, centre + half_extents].
    static constexpr Aabb from_center(const Vec3<T>& centre, const Vec3<T>& half_extents) {
        return {centre - half_extents, centre + half_extents};
    }

    constexpr bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    // Halved first: the same bits as (min + max) / 2 wherever that does not overflow, and finite
    // for boxes far out near the largest T.
    constexpr Vec3<T> center() const { return min * T(0.5) + max * T(0.5); }
    constexpr Vec3<T> half_extents() const { return (max - min) * T(0.5); }
    /// Area of the six faces (the cost measure of AABB trees).
    constexpr T surface_area() const {
        const Vec3<T> d = max - min;
        return T(2) * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
    constexpr void merge(const Vec3<T>& p) {
        min = xeno::min(min, p);
        max = xeno::max(max, p);
    }
    constexpr void merge(const Aabb& b) {
        min = xeno::min(min, b.min);
        max = xeno::max(max, b.max);
    }
    /// The box grown by margin on every side.
    constexpr Aabb expanded(T margin) const {
        const Vec3<T> m{margin, margin, margin};
        return {min - m, max + m};
    }
    constexpr bool contains(const Vec3<T>& p) const {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
    }
    constexpr bool contains(const Aabb& b) const {
        return b.min.x >= min.x && b.max.x <= max.x && b.min.y >= min.y && b.max.y <= max.y && b.min.z >= min.z &&
               b.max.z <= max.z;
    }
};

/// True when the boxes share at least a point (touching counts).
template <class T>
constexpr bool overlaps(const Aabb<T>& a, const Aabb<T>& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y && a.min.z <= b.max.z &&
           b.min.z <= a.max.z;
}

/// The smallest box holding both.
template <class T>
constexpr Aabb<T> merged(const Aabb<T>& a, const Aabb<T>& b) {
    return {min(a.min, b.min), max(a.max, b.max)};
}

namespace f32 {
using Aabb = xeno::Aabb<float>;
}
namespace f64 {
using Aabb = xeno::Aabb<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Cylinder<T>: radius r, half height h, axis along local y, centred. Support (docs/collision.md,
// "Support functions"): (r·dx/σ, sign(dy)·h, r·dz/σ) with σ = |(dx, dz)|; on the axis (σ = 0) the
// cap centre. The supporting face is a cap, approximated by a regular 12-gon inscribed in the rim,
// when d is closer to the axis than to the side; else the side line (two points).
#pragma once

#include "../error.hpp"
#include "../math/aabb.hpp"
#include "mass_properties.hpp"
#include "support_face.hpp"

#include <optional>

namespace xeno {

/// A solid circular cylinder along local y, centred on its centre of mass.
template <class T>
class Cylinder {
public:
    using scalar_type = T;
    /// Vertices of the polygon that stands for a cap in support_face().
    static constexpr int cap_segments = 12;

    /// radius and half_height in metres, finite and within [ScalarTraits<T>::min_size, max_size].
    Cylinder(T radius, T half_height) : radius_(radius), half_height_(half_height) {
        detail::require_size(radius, "Cylinder", "radius");
        detail::require_size(half_height, "Cylinder", "half_height");
    }

    T radius() const { return radius_; }
    T half_height() const { return half_height_; }
    Vec3<T> support(const Vec3<T>& d) const {
        const T y = d.y >= T(0) ? half_height_ : -half_height_;
        const T sigma = std::sqrt(d.x * d.x + d.z * d.z);
        if (!(sigma > ScalarTraits<T>::epsilon * std::abs(d.y))) return {T(0), y, T(0)};
        return {radius_ * d.x / sigma, y, radius_ * d.z / sigma};
    }
    SupportFace<T> support_face(const Vec3<T>& d) const {
        SupportFace<T> face;
        const T sigma = std::sqrt(d.x * d.x + d.z * d.z);
        if (std::abs(d.y) >= sigma) {
            const T sign = d.y >= T(0) ? T(1) : T(-1);
            face.normal = {T(0), sign, T(0)};
            for (int k = 0; k < cap_segments; ++k) {
                // Counter-clockwise seen from +y is decreasing angle in the (x, z) plane.
                const T angle = T(2) * ScalarTraits<T>::pi * static_cast<T>(sign > T(0) ? cap_segments - k : k) /
                                static_cast<T>(cap_segments);
                face.push({radius_ * std::cos(angle), sign * half_height_, radius_ * std::sin(angle)});
            }
        } else {
            const Vec3<T> side{d.x / sigma, T(0), d.z / sigma};
            face.normal = side;
            face.push(side * radius_ + Vec3<T>{T(0), half_height_, T(0)});
            face.push(side * radius_ - Vec3<T>{T(0), half_height_, T(0)});
        }
        return face;
    }
    /// The outward normal of support_face(d) when that face is a polygon (3 or more vertices),
    /// else nothing: the narrow phase tries it as a contact normal without building the face.
    std::optional<Vec3<T>> flat_normal(const Vec3<T>& d) const {
        if (std::abs(d.y) >= std::sqrt(d.x * d.x + d.z * d.z)) return Vec3<T>{T(0), d.y >= T(0) ? T(1) : T(-1), T(0)};
        return std::nullopt;
    }
    Aabb<T> local_bounds() const { return Aabb<T>::from_center(Vec3<T>::zero(), {radius_, half_height_, radius_}); }
    T bounding_radius() const { return std::sqrt(radius_ * radius_ + half_height_ * half_height_); }
    Vec3<T> interior_point() const { return Vec3<T>::zero(); }
    /// Half extents of a box centred on interior_point() that lies strictly inside the shape:
    /// the narrow phase moves its interior point within it toward a much smaller partner.
    Vec3<T> inner_half_extents() const { return {T(0.6) * radius_, T(0.9) * half_height_, T(0.6) * radius_}; }
    T volume() const { return ScalarTraits<T>::pi * radius_ * radius_ * T(2) * half_height_; }
    /// Density 1: Iy = V r²/2, Ix = Iz = V (3r² + H²)/12 with H = 2h.
    MassProperties<T> unit_mass_properties() const {
        const T v = volume(), r2 = radius_ * radius_, height = T(2) * half_height_;
        const T transverse = v * (T(3) * r2 + height * height) / T(12);
        return {v, Vec3<T>::zero(), Mat3<T>::diagonal({transverse, v * r2 / T(2), transverse})};
    }

private:
    T radius_;       ///< metres
    T half_height_;  ///< metres
};

namespace f32 {
using Cylinder = xeno::Cylinder<float>;
}
namespace f64 {
using Cylinder = xeno::Cylinder<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Sphere<T>: a ball of radius r centred on the local origin. Support r·d/|d|; a zero direction
// returns the top point (0, r, 0) so the answer is always on the surface.
#pragma once

#include "../error.hpp"
#include "../math/aabb.hpp"
#include "mass_properties.hpp"
#include "support_face.hpp"

#include <optional>

namespace xeno {

/// A sphere centred on its centre of mass.
template <class T>
class Sphere {
public:
    using scalar_type = T;

    /// radius in metres, finite and within [ScalarTraits<T>::min_size, max_size].
    explicit Sphere(T radius) : radius_(radius) { detail::require_size(radius, "Sphere", "radius"); }

    T radius() const { return radius_; }
    Vec3<T> support(const Vec3<T>& d) const { return normalized_or(d, Vec3<T>::unit_y()) * radius_; }
    /// A sphere has no flat part: the single support point, normal along d.
    SupportFace<T> support_face(const Vec3<T>& d) const {
        SupportFace<T> face;
        face.normal = normalized_or(d, Vec3<T>::unit_y());
        face.push(face.normal * radius_);
        return face;
    }
    /// The outward normal of support_face(d) when that face is a polygon (3 or more vertices),
    /// else nothing: the narrow phase tries it as a contact normal without building the face.
    std::optional<Vec3<T>> flat_normal(const Vec3<T>&) const { return std::nullopt; }
    Aabb<T> local_bounds() const { return Aabb<T>::from_center(Vec3<T>::zero(), Vec3<T>::one() * radius_); }
    T bounding_radius() const { return radius_; }
    Vec3<T> interior_point() const { return Vec3<T>::zero(); }
    /// Half extents of a box centred on interior_point() that lies strictly inside the shape:
    /// the narrow phase moves its interior point within it toward a much smaller partner.
    Vec3<T> inner_half_extents() const { return Vec3<T>::one() * (T(0.5) * radius_); }
    T volume() const { return T(4) / T(3) * ScalarTraits<T>::pi * radius_ * radius_ * radius_; }
    /// Density 1: I = 2/5 V r².
    MassProperties<T> unit_mass_properties() const {
        return {volume(), Vec3<T>::zero(), Mat3<T>::identity() * (T(0.4) * volume() * radius_ * radius_)};
    }

private:
    T radius_;  ///< metres
};

namespace f32 {
using Sphere = xeno::Sphere<float>;
}
namespace f64 {
using Sphere = xeno::Sphere<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Capsule<T>: the segment from (0, -h, 0) to (0, h, 0) on the local y axis swept by a sphere of
// radius r (docs/conventions.md, "Units and axes": h is the segment's half-length, caps excluded).
// Support: the segment end along d plus r·d/|d|. The supporting face of a direction nearly
// perpendicular to the axis is the side line (two points), so a capsule lying flat gets a two-point
// manifold at once.
#pragma once

#include "../error.hpp"
#include "../math/aabb.hpp"
#include "mass_properties.hpp"
#include "support_face.hpp"

#include <optional>

namespace xeno {

/// A capsule along local y, centred on its centre of mass.
template <class T>
class Capsule {
public:
    using scalar_type = T;

    /// radius within [ScalarTraits<T>::min_size, max_size] and half_height in [0, max_size] (0 is
    /// a sphere), both finite, in metres.
    Capsule(T radius, T half_height) : radius_(radius), half_height_(half_height) {
        detail::require_size(radius, "Capsule", "radius");
        detail::require_non_negative(half_height, "Capsule", "half_height");
        if (half_height > ScalarTraits<T>::max_size) detail::require_size(half_height, "Capsule", "half_height");
    }

    T radius() const { return radius_; }
    T half_height() const { return half_height_; }
    Vec3<T> support(const Vec3<T>& d) const {
        const Vec3<T> n = normalized_or(d, Vec3<T>::unit_y());
        return Vec3<T>{T(0), n.y >= T(0) ? half_height_ : -half_height_, T(0)} + n * radius_;
    }
    /// The side line when d is within about 6° of perpendicular to the axis, else the cap point.
    SupportFace<T> support_face(const Vec3<T>& d) const {
        SupportFace<T> face;
        face.normal = normalized_or(d, Vec3<T>::unit_y());
        if (std::abs(face.normal.y) < T(0.1) && half_height_ > T(0)) {
            const Vec3<T> side = normalized_or(Vec3<T>{face.normal.x, T(0), face.normal.z}, Vec3<T>::unit_x()) * radius_;
            face.push(side + Vec3<T>{T(0), half_height_, T(0)});
            face.push(side - Vec3<T>{T(0), half_height_, T(0)});
        } else {
            face.push(support(d));
        }
        return face;
    }
    /// The outward normal of support_face(d) when that face is a polygon (3 or more vertices),
    /// else nothing: the narrow phase tries it as a contact normal without building the face.
    std::optional<Vec3<T>> flat_normal(const Vec3<T>&) const { return std::nullopt; }
    Aabb<T> local_bounds() const {
        return Aabb<T>::from_center(Vec3<T>::zero(), Vec3<T>{radius_, half_height_ + radius_, radius_});
    }
    T bounding_radius() const { return half_height_ + radius_; }
    Vec3<T> interior_point() const { return Vec3<T>::zero(); }
    /// Half extents of a box centred on interior_point() that lies strictly inside the shape:
    /// the narrow phase moves its interior point within it toward a much smaller partner.
    Vec3<T> inner_half_extents() const { return {T(0.5) * radius_, half_height_ + T(0.5) * radius_, T(0.5) * radius_}; }
    T volume() const {
        const T pi = ScalarTraits<T>::pi;
        return pi * radius_ * radius_ * (T(2) * half_height_ + T(4) / T(3) * radius_);
    }
    /// Density 1: cylinder of length 2h plus two hemispheres (each 83/320 m r² about its own
    /// centre, which sits 3r/8 beyond the segment end).
    MassProperties<T> unit_mass_properties() const {
        const T pi = ScalarTraits<T>::pi, r = radius_, h = half_height_, r2 = r * r;
        const T cylinder = pi * r2 * T(2) * h;
        const T hemisphere = T(2) / T(3) * pi * r2 * r;
        const T axial = cylinder * r2 / T(2) + T(2) * hemisphere * T(0.4) * r2;
        const T lever = h + T(3) / T(8) * r;
        const T transverse =
            cylinder * (T(3) * r2 + T(4) * h * h) / T(12) + T(2) * hemisphere * (T(83) / T(320) * r2 + lever * lever);
        return {volume(), Vec3<T>::zero(), Mat3<T>::diagonal({transverse, axial, transverse})};
    }

private:
    T radius_;       ///< metres
    T half_height_;  ///< metres, half the segment length
};

namespace f32 {
using Capsule = xeno::Capsule<float>;
}
namespace f64 {
using Capsule = xeno::Capsule<double>;
}

}  // namespace xeno

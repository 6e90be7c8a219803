// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Cone<T>: base radius r, full height H, axis along local y, apex up. The local origin is the
// centre of mass (docs/conventions.md, "Frames"), a quarter of the height above the base: base at
// y = -H/4, apex at y = 3H/4. Support (docs/collision.md, "Support functions", after Bullet's
// coneLocalSupport): the apex when d is within the apex's normal cone (dy > |d| sin α, sin
// α = r/√(r² + H²)), else the rim point along d. The supporting face is the base (a 12-gon), the
// side line from apex to rim, or the apex alone.
#pragma once

#include "../error.hpp"
#include "../math/aabb.hpp"
#include "mass_properties.hpp"
#include "support_face.hpp"

#include <optional>

namespace xeno {

/// A solid right circular cone along local y, apex up, centred on its centre of mass.
template <class T>
class Cone {
public:
    using scalar_type = T;
    /// Vertices of the polygon that stands for the base in support_face().
    static constexpr int base_segments = 12;

    /// radius (of the base) and height in metres, finite and within
    /// [ScalarTraits<T>::min_size, max_size].
    Cone(T radius, T height) : radius_(radius), height_(height) {
        detail::require_size(radius, "Cone", "radius");
        detail::require_size(height, "Cone", "height");
        sin_alpha_ = radius_ / std::sqrt(radius_ * radius_ + height_ * height_);
    }

    T radius() const { return radius_; }
    T height() const { return height_; }
    Vec3<T> apex() const { return {T(0), T(0.75) * height_, T(0)}; }
    T base_y() const { return T(-0.25) * height_; }

    Vec3<T> support(const Vec3<T>& d) const {
        if (d.y > length(d) * sin_alpha_) return apex();
        const T sigma = std::sqrt(d.x * d.x + d.z * d.z);
        if (!(sigma > ScalarTraits<T>::epsilon * std::abs(d.y))) return {T(0), base_y(), T(0)};
        return {radius_ * d.x / sigma, base_y(), radius_ * d.z / sigma};
    }
    SupportFace<T> support_face(const Vec3<T>& d) const;
    /// The outward normal of support_face(d) when that face is a polygon (3 or more vertices),
    /// else nothing: the narrow phase tries it as a contact normal without building the face.
    std::optional<Vec3<T>> flat_normal(const Vec3<T>& d) const {
        if (base_faces(normalized_or(d, Vec3<T>::unit_y()))) return Vec3<T>{T(0), T(-1), T(0)};
        return std::nullopt;
    }
    Aabb<T> local_bounds() const { return {{-radius_, base_y(), -radius_}, {radius_, T(0.75) * height_, radius_}}; }
    T bounding_radius() const { return std::max(T(0.75) * height_, std::sqrt(radius_ * radius_ + base_y() * base_y())); }
    Vec3<T> interior_point() const { return Vec3<T>::zero(); }
    /// Half extents of a box centred on interior_point() that lies strictly inside the shape:
    /// the narrow phase moves its interior point within it toward a much smaller partner.
    Vec3<T> inner_half_extents() const { return {T(0.35) * radius_, T(0.2) * height_, T(0.35) * radius_}; }
    T volume() const { return ScalarTraits<T>::pi * radius_ * radius_ * height_ / T(3); }
    /// Density 1, about the centre of mass: Iy = 3/10 V r², Ix = Iz = V (3/20 r² + 3/80 H²).
    MassProperties<T> unit_mass_properties() const {
        const T v = volume(), r2 = radius_ * radius_, h2 = height_ * height_;
        const T transverse = v * (T(3) / T(20) * r2 + T(3) / T(80) * h2);
        return {v, Vec3<T>::zero(), Mat3<T>::diagonal({transverse, T(0.3) * v * r2, transverse})};
    }

private:
    T radius_;     ///< metres, base radius
    T height_;     ///< metres, base to apex
    T sin_alpha_;  ///< sine of the half-angle at the apex

    /// True when the base is better aligned with the unit direction n than the side is.
    bool base_faces(const Vec3<T>& n) const {
        const T sigma = std::sqrt(n.x * n.x + n.z * n.z);
        const T slant = std::sqrt(radius_ * radius_ + height_ * height_);
        return -n.y >= (height_ * sigma + radius_ * n.y) / slant;
    }
};

template <class T>
SupportFace<T> Cone<T>::support_face(const Vec3<T>& d) const {
    SupportFace<T> face;
    const Vec3<T> n = normalized_or(d, Vec3<T>::unit_y());
    const T sigma = std::sqrt(n.x * n.x + n.z * n.z);
    const T slant = std::sqrt(radius_ * radius_ + height_ * height_);
    // Alignment of d with the side normal in d's azimuth plane, against the base normal (-y).
    const T side_alignment = (height_ * sigma + radius_ * n.y) / slant;
    if (base_faces(n)) {
        face.normal = {T(0), T(-1), T(0)};
        for (int k = 0; k < base_segments; ++k) {
            // Counter-clockwise seen from -y is increasing angle in the (x, z) plane.
            const T angle = T(2) * ScalarTraits<T>::pi * static_cast<T>(k) / static_cast<T>(base_segments);
            face.push({radius_ * std::cos(angle), base_y(), radius_ * std::sin(angle)});
        }
    } else if (sigma > T(1e-3) && side_alignment > T(0.995)) {
        const Vec3<T> radial{n.x / sigma, T(0), n.z / sigma};
        face.normal = (radial * height_ + Vec3<T>::unit_y() * radius_) / slant;
        face.push(apex());
        face.push(radial * radius_ + Vec3<T>{T(0), base_y(), T(0)});
    } else {
        face.normal = n;
        face.push(support(d));
    }
    return face;
}

namespace f32 {
using Cone = xeno::Cone<float>;
}
namespace f64 {
using Cone = xeno::Cone<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Box<T>: a rectangular box centred on its centre of mass, given by half extents along the local
// x, y and z axes. Support by sign selection (docs/collision.md, "Support functions"), exact and
// branch-free: std::copysign instead of a comparison, because the signs of random directions defeat
// branch prediction (measured: one MPR miss 88 → 64 ns). A zero component takes the sign of the
// zero (+0 gives +, −0 gives −), so the answer is deterministic.
#pragma once

#include "../error.hpp"
#include "../math/aabb.hpp"
#include "mass_properties.hpp"
#include "support_face.hpp"

#include <cmath>
#include <optional>

namespace xeno {

/// An oriented box; local frame centred on the box, faces perpendicular to the axes.
template <class T>
class Box {
public:
    using scalar_type = T;

    /// A box with the given half extents (metres); each must be finite and within
    /// [ScalarTraits<T>::min_size, max_size].
    explicit Box(const Vec3<T>& half_extents) : half_extents_(half_extents) {
        detail::require_size(half_extents.x, "Box", "half_extents.x");
        detail::require_size(half_extents.y, "Box", "half_extents.y");
        detail::require_size(half_extents.z, "Box", "half_extents.z");
        bounding_radius_ = length(half_extents);
    }
    /// A box with half extents (hx, hy, hz).
    Box(T hx, T hy, T hz) : Box(Vec3<T>{hx, hy, hz}) {}

    const Vec3<T>& half_extents() const { return half_extents_; }

    /// The farthest point along d (local frame); d need not be unit.
    Vec3<T> support(const Vec3<T>& d) const {
        return {std::copysign(half_extents_.x, d.x), std::copysign(half_extents_.y, d.y), std::copysign(half_extents_.z, d.z)};
    }
    /// The face whose outward normal is most aligned with d: four corners, counter-clockwise.
    SupportFace<T> support_face(const Vec3<T>& d) const;
    /// The outward normal of support_face(d) when that face is a polygon (3 or more vertices),
    /// else nothing: the narrow phase tries it as a contact normal without building the face.
    std::optional<Vec3<T>> flat_normal(const Vec3<T>& d) const {
        const int axis = max_axis(abs(d));
        return Vec3<T>::axis(axis) * (d[axis] >= T(0) ? T(1) : T(-1));
    }
    Aabb<T> local_bounds() const { return {-half_extents_, half_extents_}; }
    /// Radius of the smallest sphere about the centre holding the box: its half diagonal (kept:
    /// every narrow-phase query asks for it twice).
    T bounding_radius() const { return bounding_radius_; }
    /// A point strictly inside: the centre.
    Vec3<T> interior_point() const { return Vec3<T>::zero(); }
    /// Half extents of a box centred on interior_point() that lies strictly inside the shape:
    /// the narrow phase moves its interior point within it toward a much smaller partner.
    Vec3<T> inner_half_extents() const { return half_extents_ - Vec3<T>::one() * (T(0.1) * min_component(half_extents_)); }
    T volume() const { return T(8) * half_extents_.x * half_extents_.y * half_extents_.z; }
    /// Density 1: I = V/3 · diag(hy² + hz², hx² + hz², hx² + hy²).
    MassProperties<T> unit_mass_properties() const {
        const Vec3<T> h2 = hadamard(half_extents_, half_extents_);
        return {volume(), Vec3<T>::zero(), Mat3<T>::diagonal(Vec3<T>{h2.y + h2.z, h2.x + h2.z, h2.x + h2.y} * (volume() / T(3)))};
    }

private:
    Vec3<T> half_extents_;  ///< metres, each > 0
    T bounding_radius_;     ///< metres, |half_extents_|
};

template <class T>
SupportFace<T> Box<T>::support_face(const Vec3<T>& d) const {
    const Vec3<T> a = abs(d);
    const int axis = max_axis(a);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const T sign = d[axis] >= T(0) ? T(1) : T(-1);
    SupportFace<T> face;
    face.normal = Vec3<T>::axis(axis) * sign;
    // Corners in the (u, v) plane; (u, v, axis) is right-handed, so this order is
    // counter-clockwise seen from +axis; reversed for the -axis face.
    const T cu[4] = {T(1), T(-1), T(-1), T(1)};
    const T cv[4] = {T(1), T(1), T(-1), T(-1)};
    for (int k = 0; k < 4; ++k) {
        const int i = sign > T(0) ? k : 3 - k;
        Vec3<T> p;
        p[axis] = sign * half_extents_[axis];
        p[u] = cu[i] * half_extents_[u];
        p[v] = cv[i] * half_extents_[v];
        face.push(p);
    }
    return face;
}

namespace f32 {
using Box = xeno::Box<float>;
}
namespace f64 {
using Box = xeno::Box<double>;
}

}  // namespace xeno

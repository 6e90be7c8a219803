// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Shape<T>: one type that holds any convex shape (a std::variant), so worlds and tools can store
// mixed shapes. Pairs with a closed form are dispatched by one std::visit over both shapes; the
// pairs MPR answers see both through collide/shape_ref.hpp, one compiled copy whose support call
// switches on the kind (docs/style.md, "Static dispatch").
#pragma once

#include "box.hpp"
#include "capsule.hpp"
#include "cone.hpp"
#include "convex_polyhedron.hpp"
#include "cylinder.hpp"
#include "sphere.hpp"
#include "../math/transform.hpp"

#include <variant>

namespace xeno {

/// Any convex shape of scalar T.
template <class T>
using Shape = std::variant<Sphere<T>, Box<T>, Capsule<T>, Cylinder<T>, Cone<T>, ConvexPolyhedron<T>>;

/// Short lower-case name of the held shape ("sphere", "box", "capsule", "cylinder", "cone", "hull").
template <class T>
const char* shape_name(const Shape<T>& s) {
    constexpr const char* names[] = {"sphere", "box", "capsule", "cylinder", "cone", "hull"};
    return names[s.index()];
}

template <class T>
Vec3<T> support(const Shape<T>& s, const Vec3<T>& d) {
    return std::visit([&](const auto& shape) { return shape.support(d); }, s);
}
template <class T>
SupportFace<T> support_face(const Shape<T>& s, const Vec3<T>& d) {
    return std::visit([&](const auto& shape) { return shape.support_face(d); }, s);
}
template <class T>
Aabb<T> local_bounds(const Shape<T>& s) {
    return std::visit([](const auto& shape) { return shape.local_bounds(); }, s);
}
template <class T>
T bounding_radius(const Shape<T>& s) {
    return std::visit([](const auto& shape) { return shape.bounding_radius(); }, s);
}
template <class T>
Vec3<T> interior_point(const Shape<T>& s) {
    return std::visit([](const auto& shape) { return shape.interior_point(); }, s);
}
template <class T>
T volume(const Shape<T>& s) {
    return std::visit([](const auto& shape) { return shape.volume(); }, s);
}
namespace detail {
/// A moved-from hull is a valid object without vertices, whose support reads nothing: every
/// entry that takes a shape (create_body, set_shape, collide, intersect, raycast, shape_cast,
/// the world's shape queries, a compound's children) rejects it (InvalidArgument) instead of
/// crashing.
template <class T>
void require_moved_in(const Shape<T>& shape, const char* where) {
    if (const auto* hull = std::get_if<ConvexPolyhedron<T>>(&shape); hull && hull->vertices().size() < 4)
        report_invalid(where, "a convex hull needs at least 4 vertices (a moved-from hull?); vertices",
                       static_cast<double>(hull->vertices().size()));
}
}  // namespace detail

/// Mass properties of any shape at density (kg/m³); density must be finite and > 0.
template <class T>
MassProperties<T> mass_properties(const Shape<T>& s, T density) {
    detail::require_moved_in(s, "mass_properties");
    return std::visit([&](const auto& shape) { return mass_properties(shape, density); }, s);
}

/// The world-space bounding box of shape s placed by t: exact for spheres, boxes, capsules and
/// cylinders; for cones and hulls the rotated local box (never smaller than the shape).
template <class T>
Aabb<T> world_bounds(const Shape<T>& s, const Transform<T>& t) {
    const Mat3<T> r = to_matrix(t.orientation);
    return std::visit(
        [&](const auto& shape) {
            using S = std::decay_t<decltype(shape)>;
            if constexpr (std::is_same_v<S, Sphere<T>>) {
                return Aabb<T>::from_center(t.position, Vec3<T>::one() * shape.radius());
            } else if constexpr (std::is_same_v<S, Capsule<T>>) {
                const Vec3<T> axis = r.column(1) * shape.half_height();
                return Aabb<T>::from_center(t.position, abs(axis) + Vec3<T>::one() * shape.radius());
            } else if constexpr (std::is_same_v<S, Cylinder<T>>) {
                // Along world axis i: h |a_i| + r sqrt(1 - a_i²), a = the cylinder's axis.
                const Vec3<T> a = r.column(1);
                Vec3<T> half;
                for (int i = 0; i < 3; ++i)
                    half[i] =
                        shape.half_height() * std::abs(a[i]) + shape.radius() * std::sqrt(std::max(T(0), T(1) - a[i] * a[i]));
                return Aabb<T>::from_center(t.position, half);
            } else {
                const Aabb<T> local = shape.local_bounds();
                const Mat3<T> abs_r{abs(r[0]), abs(r[1]), abs(r[2])};
                return Aabb<T>::from_center(t.apply(local.center()), abs_r * local.half_extents());
            }
        },
        s);
}

namespace f32 {
using Shape = xeno::Shape<float>;
}
namespace f64 {
using Shape = xeno::Shape<double>;
}

}  // namespace xeno

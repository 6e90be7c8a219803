// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Closed-form contacts of a sphere with a cylinder or a cone. A sphere is its centre swept by a
// ball, so while the centre is outside the solid the least depth is the radius minus the distance
// from the centre to the solid's nearest point, along the line between them (Ericson, "Real-Time
// Collision Detection", 5.1); inside, it is the radius plus the distance to the nearest face.
// Both solids turn about their axis (local y), so the nearest point is found in the half-plane
// through the axis and the centre, where the solid is a rectangle (cylinder) or a triangle
// (cone), and turned back. MPR stopped at a portal within its tolerance, which on the rim's
// curve left the normal up to 6.5° off and the point on the solid up to 2 mm outside it.
#pragma once

#include "../shape/cone.hpp"
#include "../shape/cylinder.hpp"
#include "round_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace xeno {

namespace detail {

template <class S>
struct IsTurnedSolid : std::false_type {};
template <class T>
struct IsTurnedSolid<Cylinder<T>> : std::true_type {};
template <class T>
struct IsTurnedSolid<Cone<T>> : std::true_type {};

/// True for a sphere with a cylinder or a cone, in either order.
template <class A, class B>
constexpr bool is_sphere_solid_pair = (std::is_same_v<A, Sphere<typename A::scalar_type>> && IsTurnedSolid<B>::value) ||
                                      (std::is_same_v<B, Sphere<typename A::scalar_type>> && IsTurnedSolid<A>::value);

/// The nearest point of a solid's surface to a point p (all in the solid's frame): the point, the
/// outward unit normal there, and p's signed distance along it (negative inside).
template <class T>
struct SurfacePoint {
    Vec3<T> point{}, normal{};
    T distance{};
};

/// The unit vector from the axis towards p in the plane y = 0; +x for a point on the axis (any
/// direction is as near there, and this one is the same every time).
template <class T>
Vec3<T> radial_direction(const Vec3<T>& p, T rho) {
    return rho > T(0) ? Vec3<T>{p.x / rho, T(0), p.z / rho} : Vec3<T>::unit_x();
}

/// p outside by more than `touching`: the point at radius `r` and height `y` of p's half-plane
/// (r == rho keeps p's own x and z), and the normal from it to p.
template <class T>
SurfacePoint<T> nearest_from_outside(const Vec3<T>& p, T rho, T r, T y) {
    const T scale = rho > T(0) ? r / rho : T(0);
    SurfacePoint<T> out;
    out.point = {p.x * scale, y, p.z * scale};
    const Vec3<T> d = p - out.point;
    out.distance = length(d);
    out.normal = d / out.distance;
    return out;
}

template <class T>
SurfacePoint<T> nearest_surface_point(const Cylinder<T>& cylinder, const Vec3<T>& p, T touching) {
    const T r = cylinder.radius(), h = cylinder.half_height();
    const T rho = std::sqrt(p.x * p.x + p.z * p.z);
    const T side = rho - r, cap = std::abs(p.y) - h;  // > 0 outside that surface
    if (side > touching || cap > touching) return nearest_from_outside(p, rho, std::min(rho, r), clamp(p.y, -h, h));
    const T up = p.y >= T(0) ? T(1) : T(-1);
    if (cap >= side) return {{p.x, up * h, p.z}, {T(0), up, T(0)}, cap};
    const Vec3<T> out = radial_direction(p, rho);
    return {out * r + Vec3<T>{T(0), p.y, T(0)}, out, side};
}

template <class T>
SurfacePoint<T> nearest_surface_point(const Cone<T>& cone, const Vec3<T>& p, T touching) {
    // The half-plane's triangle: the base's centre (0, yb), its rim (r, yb) and the apex (0, ya).
    const T r = cone.radius(), height = cone.height(), yb = cone.base_y();
    const T slant = std::sqrt(r * r + height * height);
    const T rho = std::sqrt(p.x * p.x + p.z * p.z);
    const T below = yb - p.y;                                        // > 0 outside the base
    const T beyond = ((rho - r) * height + (p.y - yb) * r) / slant;  // > 0 outside the side
    if (below > touching || beyond > touching) {
        // The nearer of the base's segment and the side's (from the rim towards the apex).
        const T base_r = clamp(rho, T(0), r);
        const T base_sq = (rho - base_r) * (rho - base_r) + below * below;
        const T t = clamp(((rho - r) * -r + (p.y - yb) * height) / (slant * slant), T(0), T(1));
        const T side_r = r - t * r, side_y = yb + t * height;
        const T side_sq = (rho - side_r) * (rho - side_r) + (p.y - side_y) * (p.y - side_y);
        return base_sq <= side_sq ? nearest_from_outside(p, rho, base_r, yb) : nearest_from_outside(p, rho, side_r, side_y);
    }
    if (below >= beyond) return {{p.x, yb, p.z}, {T(0), T(-1), T(0)}, below};
    const Vec3<T> out = radial_direction(p, rho);
    const Vec3<T> normal = out * (height / slant) + Vec3<T>{T(0), r / slant, T(0)};
    return {p - normal * beyond, normal, beyond};
}

/// The solid's surface point nearest the sphere's centre, in the solid's frame (md's A or B).
template <class A, class B>
SurfacePoint<typename A::scalar_type> sphere_solid_nearest(const MinkowskiDifference<A, B>& md) {
    using T = typename A::scalar_type;
    const T touching = touching_distance(md.scale());
    const Vec3<T> b_centre = md.to_a(Vec3<T>::zero());
    if constexpr (IsTurnedSolid<A>::value) return nearest_surface_point(md.shape_a(), b_centre, touching);
    else return nearest_surface_point(md.shape_b(), md.direction_to_b(-b_centre), touching);
}

template <class A, class B>
typename A::scalar_type sphere_radius(const MinkowskiDifference<A, B>& md) {
    if constexpr (IsTurnedSolid<A>::value) return md.shape_b().radius();
    else return md.shape_a().radius();
}

/// True when the sphere and the solid overlap (depth > 0), as sphere_solid_contact's depth says.
template <class A, class B>
bool sphere_solid_intersect(const MinkowskiDifference<A, B>& md) {
    return sphere_radius(md) - sphere_solid_nearest(md).distance > typename A::scalar_type(0);
}

/// The contact in A's frame, as refined_contact gives it: unit normal n from A to B, the exact
/// overlap h (> −margin within reach), point_b on B's surface and point_a = point_b + h n on A's.
/// False when farther apart than md's margin.
template <class A, class B>
bool sphere_solid_contact(const MinkowskiDifference<A, B>& md, Vec3<typename A::scalar_type>& n, typename A::scalar_type& h,
                          Vec3<typename A::scalar_type>& point_a, Vec3<typename A::scalar_type>& point_b) {
    const auto nearest = sphere_solid_nearest(md);
    h = sphere_radius(md) - nearest.distance;
    if (!(h > -md.margin())) return false;
    if constexpr (IsTurnedSolid<A>::value) {
        n = nearest.normal;
        point_a = nearest.point;
        point_b = point_a - n * h;
    } else {
        n = -md.direction_to_a(nearest.normal);
        point_b = md.to_a(nearest.point);
        point_a = point_b + n * h;
    }
    return true;
}

/// The manifold: the one contact, speculative up to md's margin.
template <class A, class B>
ContactManifold<typename A::scalar_type> sphere_solid_manifold(const MinkowskiDifference<A, B>& md) {
    using T = typename A::scalar_type;
    ContactManifold<T> out;
    Vec3<T> n, point_a, point_b;
    T h;
    if (!sphere_solid_contact(md, n, h, point_a, point_b)) return out;
    out.normal = md.direction_to_world(n);
    out.count = 1;
    out.points[0] = {md.point_to_world(point_a), md.point_to_world(point_b), h};
    return out;
}

}  // namespace detail

}  // namespace xeno

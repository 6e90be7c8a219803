// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Ray casts and point tests against every shape, in closed form in the shape's local frame: a
// quadratic for the round surfaces (sphere, capsule side and ends, cylinder side, cone side; the
// first three in a form that does not cancel for far rays, see enter_round), a
// plane for flat ones (cylinder caps, cone base) and slab clipping for boxes and polyhedra
// (Cyrus–Beck: the ray enters at the last entering face plane and leaves at the first leaving
// one). Shapes are solid: a ray that starts inside one hits it at distance 0, with the normal
// facing back along the ray.
#pragma once

#include "../shape/shape.hpp"
#include "mpr.hpp"  // detail::require_finite_pose

#include <algorithm>
#include <cmath>
#include <optional>

namespace xeno {

/// A ray from origin along the unit direction, at most max_distance long (metres). The ray casts
/// (raycast(shape, pose, ray), raycast(box, ray), a mesh's or heightfield's, the world's) take a
/// finite origin, a direction of length 1 within 1e-3, which they normalise first (so distances
/// are metres), and a max_distance > 0 (ScalarTraits<T>::max or +∞ for no limit); anything else
/// is an InvalidArgument (detail::checked_ray).
template <class T>
struct Ray {
    Vec3<T> origin{};
    Vec3<T> direction{T(0), T(-1), T(0)};   ///< unit (within 1e-3)
    T max_distance = ScalarTraits<T>::max;  ///< m, > 0
};

/// Where a ray meets a shape.
template <class T>
struct RayHit {
    T distance{};      ///< m along the ray, 0 … max_distance
    T fraction{};      ///< distance / max_distance, 0 … 1 (0 when max_distance is ScalarTraits<T>::max or more)
    Vec3<T> point{};   ///< world
    Vec3<T> normal{};  ///< unit, world, the surface normal at the hit (facing the ray's origin)
};

namespace detail {

/// RayHit::fraction of a hit `distance` along a ray reaching `max_distance`.
template <class T>
T ray_fraction(T distance, T max_distance) {
    return max_distance < ScalarTraits<T>::max ? distance / max_distance : T(0);
}

/// The ray as the ray casts use it, or an InvalidArgument from `where` (Ray). A NaN or zero
/// direction, a NaN or infinite origin and a max_distance of 0 were silent misses or a fraction
/// of 0/0 in raycast(shape, pose, ray). The skip up to a far shape (ray_skip) and the distances
/// assume a unit direction: with one 1e-4 too long, a sphere 10 km away was hit on its far side.
/// A direction unit to T's rounding (|d|² within 4ε of 1, as normalized() gives) is kept as it
/// is: the skip's slack covers that, and the results stay bit for bit what they were.
template <class T>
Ray<T> checked_ray(const Ray<T>& ray, const char* where) {
    require_finite_xyz(ray.origin, where, "ray.origin");
    const T length_d = length(ray.direction);
    if (!is_finite(ray.direction) || !(std::abs(length_d - T(1)) <= T(1e-3)))
        report_invalid(where, "ray direction must be a unit vector; its length", static_cast<double>(length_d));
    if (!(ray.max_distance > T(0))) report_invalid(where, "ray max_distance must be > 0", static_cast<double>(ray.max_distance));
    Ray<T> out = ray;
    if (std::abs(length_squared(ray.direction) - T(1)) > T(4) * ScalarTraits<T>::epsilon)
        out.direction = ray.direction / length_d;
    return out;
}

/// Local-frame hit: distance and outward normal.
template <class T>
struct LocalHit {
    T t;
    Vec3<T> n;
};

/// Keeps the nearer of two candidate hits.
template <class T>
void keep_nearer(std::optional<LocalHit<T>>& best, T t, const Vec3<T>& n) {
    if (!best || t < best->t) best = LocalHit<T>{t, n};
}

/// Entry and exit of a ray (o + t d) into a convex set bounded by planes n·x <= offset.
template <class T, class Planes>
std::optional<LocalHit<T>> clip_by_planes(const Vec3<T>& o, const Vec3<T>& d, T max_t, const Planes& planes) {
    T enter = T(0), exit = max_t;
    Vec3<T> normal = -d;  // starting inside
    for (const auto& [n, offset] : planes) {
        const T dist = offset - dot(n, o);  // >= 0 on the inner side
        const T speed = dot(n, d);
        if (speed == T(0)) {
            if (dist < T(0)) return std::nullopt;  // parallel and outside
            continue;
        }
        const T t = dist / speed;
        if (speed < T(0)) {  // entering through this plane
            if (t > enter) {
                enter = t;
                normal = n;
            }
        } else if (t < exit) {
            exit = t;
        }
        if (enter > exit) return std::nullopt;
    }
    return LocalHit<T>{enter, normal};
}

/// The entering distance t in [0, max_t] of a ray o + t d (|d|² = a > 0) into the round set of
/// points within r of a point or an axis through the local origin, where m is the origin's offset
/// across it (o for a sphere; o's part across the axis for a cylinder, and d likewise), and the
/// offset across it at the hit (for the normal). The textbook discriminant b² − a c cancels when
/// the ray starts far away (|m| ≫ r: from 1 km a float unit sphere was hit 1 cm off, from 10⁸ m a
/// capsule was missed); here the origin is first moved to the ray's closest approach,
/// t_c = −m·d / a, and the half chord √((r² − |q|²) / a) comes from the small vector
/// q = m + t_c d (the stable form of Haines et al., "Precision Improvements for Ray/Sphere
/// Intersection", Ray Tracing Gems, 2019). A ray that starts inside does not enter.
template <class T>
struct RoundHit {
    T t;
    Vec3<T> offset;  ///< from the centre (or axis) to the hit point
};

template <class T>
std::optional<RoundHit<T>> enter_round(const Vec3<T>& m, const Vec3<T>& d, T a, T r, T max_t) {
    if (!(a > T(0))) return std::nullopt;
    const T t_closest = -dot(m, d) / a;
    const Vec3<T> q = m + d * t_closest;
    const T q_length = length(q);
    const T h_sq = (r - q_length) * (r + q_length);  // r² − |q|²
    if (h_sq < T(0)) return std::nullopt;
    const T half_chord = std::sqrt(h_sq / a);
    // The entry t_c − half chord cancels when the ray starts near the surface and runs nearly
    // along the axis (t_c ≈ half chord, both ~1/√a); the product of the roots, |m|² − r² over a,
    // divided by the exit root gives it without cancelling.
    const T m_length = length(m);
    const T t0 = t_closest > T(0) ? (m_length - r) * (m_length + r) / (a * (t_closest + half_chord)) : t_closest - half_chord;
    if (t0 >= T(0) && t0 <= max_t) return RoundHit<T>{t0, q - d * half_chord};
    return std::nullopt;
}

template <class T>
std::optional<LocalHit<T>> ray_sphere(const Vec3<T>& o, const Vec3<T>& d, T max_t, const Vec3<T>& centre, T r) {
    const Vec3<T> m = o - centre;
    if (length_squared(m) <= r * r) return LocalHit<T>{T(0), -d};
    if (const std::optional<RoundHit<T>> hit = enter_round(m, d, length_squared(d), r, max_t))
        return LocalHit<T>{hit->t, normalized_or(hit->offset, -d)};
    return std::nullopt;
}

/// The side of an infinite y-axis cylinder of radius r, restricted to y_low <= y <= y_high.
template <class T>
std::optional<LocalHit<T>> ray_cylinder_side(const Vec3<T>& o, const Vec3<T>& d, T max_t, T r, T y_low, T y_high) {
    const Vec3<T> across{d.x, T(0), d.z};
    const T a = length_squared(across);
    // Only a ray exactly parallel to the axis misses the side: one within √ε of it (3.4e-4 rad in
    // float) was skipped, and missed a long thin pole it entered through the side.
    if (!(a > T(0))) return std::nullopt;
    if (const std::optional<RoundHit<T>> hit = enter_round(Vec3<T>{o.x, T(0), o.z}, across, a, r, max_t)) {
        const T y = o.y + d.y * hit->t;
        if (y >= y_low && y <= y_high) return LocalHit<T>{hit->t, normalized_or(hit->offset, -d)};
    }
    return std::nullopt;
}

/// A disc of radius r in the plane y = y0 facing `side` (+1 up, -1 down).
template <class T>
std::optional<LocalHit<T>> ray_disc(const Vec3<T>& o, const Vec3<T>& d, T max_t, T r, T y0, T side) {
    if (d.y * side >= T(0)) return std::nullopt;  // moving away from the face
    const T t = (y0 - o.y) / d.y;
    if (t < T(0) || t > max_t) return std::nullopt;
    const Vec3<T> p = o + d * t;
    if (p.x * p.x + p.z * p.z > r * r) return std::nullopt;
    return LocalHit<T>{t, {T(0), side, T(0)}};
}

template <class T>
bool contains_local(const Shape<T>& shape, const Vec3<T>& p) {
    return std::visit(
        [&](const auto& s) -> bool {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, Sphere<T>>) {
                return length_squared(p) <= s.radius() * s.radius();
            } else if constexpr (std::is_same_v<S, Box<T>>) {
                const Vec3<T> a = abs(p);
                const Vec3<T>& h = s.half_extents();
                return a.x <= h.x && a.y <= h.y && a.z <= h.z;
            } else if constexpr (std::is_same_v<S, Capsule<T>>) {
                const Vec3<T> axis{T(0), clamp(p.y, -s.half_height(), s.half_height()), T(0)};
                return length_squared(p - axis) <= s.radius() * s.radius();
            } else if constexpr (std::is_same_v<S, Cylinder<T>>) {
                return std::abs(p.y) <= s.half_height() && p.x * p.x + p.z * p.z <= s.radius() * s.radius();
            } else if constexpr (std::is_same_v<S, Cone<T>>) {
                const T top = s.apex().y, bottom = s.base_y();
                if (p.y < bottom || p.y > top) return false;
                const T rr = s.radius() * (top - p.y) / s.height();
                return p.x * p.x + p.z * p.z <= rr * rr;
            } else {
                for (const auto& f : s.faces())
                    if (dot(f.normal, p) > f.offset) return false;
                return true;
            }
        },
        shape);
}

template <class T>
std::optional<LocalHit<T>> raycast_local(const Shape<T>& shape, const Vec3<T>& o, const Vec3<T>& d, T max_t) {
    if (contains_local(shape, o)) return LocalHit<T>{T(0), -d};
    return std::visit(
        [&](const auto& s) -> std::optional<LocalHit<T>> {
            using S = std::decay_t<decltype(s)>;
            std::optional<LocalHit<T>> best;
            if constexpr (std::is_same_v<S, Sphere<T>>) {
                best = ray_sphere(o, d, max_t, Vec3<T>::zero(), s.radius());
            } else if constexpr (std::is_same_v<S, Box<T>>) {
                const Vec3<T>& h = s.half_extents();
                const std::pair<Vec3<T>, T> planes[6] = {{Vec3<T>::unit_x(), h.x}, {-Vec3<T>::unit_x(), h.x},
                                                         {Vec3<T>::unit_y(), h.y}, {-Vec3<T>::unit_y(), h.y},
                                                         {Vec3<T>::unit_z(), h.z}, {-Vec3<T>::unit_z(), h.z}};
                best = clip_by_planes(o, d, max_t, planes);
            } else if constexpr (std::is_same_v<S, Capsule<T>>) {
                const T h = s.half_height(), r = s.radius();
                if (auto side = ray_cylinder_side(o, d, max_t, r, -h, h)) keep_nearer(best, side->t, side->n);
                for (const T y : {h, -h})
                    if (auto cap = ray_sphere(o, d, max_t, Vec3<T>{T(0), y, T(0)}, r)) {
                        // On the cap's own half: the normal (the hit's offset from the cap's
                        // centre, exact even for far rays) points away from the segment.
                        if (y > T(0) ? cap->n.y >= T(0) : cap->n.y <= T(0)) keep_nearer(best, cap->t, cap->n);
                    }
            } else if constexpr (std::is_same_v<S, Cylinder<T>>) {
                const T h = s.half_height(), r = s.radius();
                if (auto side = ray_cylinder_side(o, d, max_t, r, -h, h)) keep_nearer(best, side->t, side->n);
                if (auto top = ray_disc(o, d, max_t, r, h, T(1))) keep_nearer(best, top->t, top->n);
                if (auto bottom = ray_disc(o, d, max_t, r, -h, T(-1))) keep_nearer(best, bottom->t, bottom->n);
            } else if constexpr (std::is_same_v<S, Cone<T>>) {
                // Side: x² + z² = k² (apex_y - y)², k = r / H, for base_y <= y <= apex_y.
                const T apex = s.apex().y, k = s.radius() / s.height();
                const Vec3<T> q{o.x, o.y - apex, o.z};  // apex at the origin
                const T k2 = k * k;
                const T a = d.x * d.x + d.z * d.z - k2 * d.y * d.y;
                const T b = q.x * d.x + q.z * d.z - k2 * q.y * d.y;
                const T c = q.x * q.x + q.z * q.z - k2 * q.y * q.y;
                const T disc = b * b - a * c;
                if (disc >= T(0)) {
                    // Both roots without cancellation, sum / a and c / sum: a ray along a line of
                    // the side (a = 0) meets it at the one root c / sum = -c / 2b. Skipping |a| <= ε
                    // missed such a ray's way in, and it left through the base from inside: the
                    // cone was missed whole.
                    const T sum = -(b + std::copysign(std::sqrt(disc), b));
                    const T roots[2] = {a != T(0) ? sum / a : -T(1), sum != T(0) ? c / sum : -T(1)};
                    for (const T t : roots) {
                        if (!(t >= T(0)) || t > max_t) continue;
                        const Vec3<T> p = o + d * t;
                        if (p.y < s.base_y() || p.y > apex) continue;  // the other nappe or past the base
                        const T rho = std::sqrt(p.x * p.x + p.z * p.z);
                        const Vec3<T> radial = rho > T(0) ? Vec3<T>{p.x / rho, T(0), p.z / rho} : Vec3<T>::zero();
                        keep_nearer(best, t, normalized_or(radial * s.height() + Vec3<T>::unit_y() * s.radius(), -d));
                    }
                }
                if (auto base = ray_disc(o, d, max_t, s.radius(), s.base_y(), T(-1))) keep_nearer(best, base->t, base->n);
            } else {
                std::vector<std::pair<Vec3<T>, T>> planes;
                planes.reserve(s.faces().size());
                for (const auto& f : s.faces()) planes.emplace_back(f.normal, f.offset);
                best = clip_by_planes(o, d, max_t, planes);
            }
            return best;
        },
        shape);
}

/// How far a ray may skip ahead before it can meet a shape within `reach` of `centre`: a ray that
/// passes the centre more than 2 reach ahead of its origin starts again reach (and the rounding
/// of the new start) short of that point, as no point of the shape lies nearer the origin along
/// the ray, so the shape's local quadratics and planes see small numbers. Without it the cone's
/// side, whose quadratic is the textbook one, was hit 362 m off its surface from 10⁶ m in float,
/// and a ray from near the end of the range of T (3·10³⁸ in float) overflowed the shape's frame
/// and hit shapes it passes far from, at an infinite distance. Infinity when the shape lies
/// beyond the range of T.
template <class T>
T ray_skip(const Vec3<T>& centre, T reach, const Ray<T>& ray) {
    const Vec3<T> to = centre - ray.origin;
    if (!is_finite(to)) return ScalarTraits<T>::infinity;
    T along = dot(to, ray.direction);
    if (!std::isfinite(along)) {  // the products overflowed: scale by the largest component first
        const T scale = std::max({std::abs(to.x), std::abs(to.y), std::abs(to.z)});
        along = dot(to / scale, ray.direction) * scale;
        if (!std::isfinite(along)) return ScalarTraits<T>::infinity;
    }
    // Short of the shape by its reach and by what rounding the new start can move it (a few ulps
    // of the origin's and the skip's size), so the start never lands on or past the shape.
    const T eps4 = T(4) * ScalarTraits<T>::epsilon;
    const T slack = eps4 * std::max({std::abs(ray.origin.x), std::abs(ray.origin.y), std::abs(ray.origin.z)}) + eps4 * along;
    return along > T(2) * (reach + slack) ? along - (reach + slack) : T(0);
}

/// A ray moved up to a shape by ray_skip: the distance skipped, the new start (world), and that
/// start and the direction in the frame of `pose`.
template <class T>
struct SkippedRay {
    T skip;
    Vec3<T> start, origin, direction;
};

/// The ray moved up to a shape placed by `pose` within `reach` of `centre` (world), or nothing
/// when the shape lies beyond max_distance or the ray passes it farther than the range of T.
/// One skip leaves the start a few ulps of the origin short (10¹⁹ m from 10²⁶ m in float), which
/// the round shapes' quadratics squared past the range of T: from 10²⁶ m (float) or 10²⁰⁰ m
/// (double) a unit sphere was missed. So the ray skips again from where it landed, each time
/// a factor of about 1/(8ε) closer, until it is within about twice the reach (or the rounding of
/// the centre's own coordinates); a ray from nearer than about reach / (8ε) skips once, as before.
template <class T>
std::optional<SkippedRay<T>> skip_to(const Transform<T>& pose, const Vec3<T>& centre, T reach, const Ray<T>& ray) {
    T skip = T(0);
    Vec3<T> start = ray.origin;
    for (int i = 0; i < 64; ++i) {  // 21 skips cross double's whole range
        const T step = ray_skip(centre, reach, Ray<T>{start, ray.direction, ray.max_distance});
        if (!(skip + step <= ray.max_distance)) return std::nullopt;
        if (!(step > T(0))) break;
        start = start + ray.direction * step;
        skip += step;
    }
    const Vec3<T> origin = pose.inverse_apply(start);
    if (!is_finite(origin)) return std::nullopt;
    return SkippedRay<T>{skip, start, origin, pose.inverse_apply_direction(ray.direction)};
}

}  // namespace detail

namespace detail {

/// raycast(shape, pose, ray) on a checked ray (checked_ray) and pose.
template <class T>
std::optional<RayHit<T>> raycast_checked(const Shape<T>& shape, const Transform<T>& pose, const Ray<T>& ray) {
    const std::optional<detail::SkippedRay<T>> s = detail::skip_to(pose, pose.position, bounding_radius(shape), ray);
    if (!s) return std::nullopt;
    const std::optional<detail::LocalHit<T>> hit =
        detail::raycast_local(shape, s->origin, s->direction, ray.max_distance - s->skip);
    if (!hit) return std::nullopt;
    RayHit<T> out;
    out.distance = s->skip + hit->t;
    out.fraction = detail::ray_fraction(out.distance, ray.max_distance);
    out.point = s->start + ray.direction * hit->t;
    out.normal = pose.apply_direction(hit->n);
    return out;
}

}  // namespace detail

/// The first point where the ray meets the shape placed by pose, if it does within max_distance.
/// A ray starting inside the shape hits at distance 0 (fraction 0), with the normal facing back
/// along the ray. The ray and pose are checked as the world's ray casts check them (Ray;
/// InvalidArgument), and the direction is normalised first. A ray from far away is first moved up
/// to the shape along itself (detail::skip_to).
template <class T>
std::optional<RayHit<T>> raycast(const Shape<T>& shape, const Transform<T>& pose, const Ray<T>& ray) {
    detail::require_moved_in(shape, "raycast");
    detail::require_finite_pose(pose, "raycast", "pose");
    return detail::raycast_checked(shape, pose, detail::checked_ray(ray, "raycast"));
}

/// True when the world point lies inside (or on) the shape placed by pose.
template <class T>
bool contains_point(const Shape<T>& shape, const Transform<T>& pose, const Vec3<T>& point) {
    return detail::contains_local(shape, pose.inverse_apply(point));
}

namespace detail {
/// raycast(box, ray) on a checked ray (checked_ray).
template <class T>
std::optional<T> raycast_box(const Aabb<T>& box, const Ray<T>& ray) {
    // Empty (min > max: Aabb{} is +inf … −inf) or with a NaN bound: nothing to hit. Every ray
    // entered Aabb{} at 0, its slabs' infinities swapped into a range that holds everything.
    if (!(box.min.x <= box.max.x && box.min.y <= box.max.y && box.min.z <= box.max.z)) return std::nullopt;
    T enter = T(0), exit = ray.max_distance;
    for (int i = 0; i < 3; ++i) {
        const T o = ray.origin[i], d = ray.direction[i];
        if (d == T(0)) {
            if (o < box.min[i] || o > box.max[i]) return std::nullopt;
            continue;
        }
        T t0 = (box.min[i] - o) / d, t1 = (box.max[i] - o) / d;
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        exit = std::min(exit, t1);
        if (enter > exit) return std::nullopt;
    }
    return enter;
}
}  // namespace detail

/// Entry distance of a ray into a box (slab test), if it enters within max_distance; 0 from
/// inside. An empty box (or one with a NaN bound) is never hit. The ray is checked as
/// raycast(shape, pose, ray) checks it (InvalidArgument).
template <class T>
std::optional<T> raycast(const Aabb<T>& box, const Ray<T>& ray) {
    return detail::raycast_box(box, detail::checked_ray(ray, "raycast(box, ray)"));
}

namespace f32 {
using Ray = xeno::Ray<float>;
using RayHit = xeno::RayHit<float>;
}  // namespace f32
namespace f64 {
using Ray = xeno::Ray<double>;
using RayHit = xeno::RayHit<double>;
}  // namespace f64

#ifdef XENO_COMPILED_LIB
// Compiled mode (compiled.hpp): float and double are compiled once, in src/xeno_compiled.cpp.
extern template std::optional<RayHit<float>> raycast<float>(const Shape<float>&, const Transform<float>&, const Ray<float>&);
extern template std::optional<RayHit<double>> raycast<double>(const Shape<double>&, const Transform<double>&, const Ray<double>&);
#endif

}  // namespace xeno

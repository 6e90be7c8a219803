// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The narrow phase as the rest of xeno calls it, for any two Shape<T>: one std::visit per pair
// selects the instantiation for the two concrete shape types (static dispatch). Spheres and
// capsules, with each other or with a box, are answered exactly in closed form by round_pairs.hpp
// (all three queries, their own manifolds); the other pairs as follows:
//   intersect()          the boolean MPR test, stopping at the first portal that holds the origin
//                        (two boxes: the separating-axis test of box_box.hpp);
//   collide()            MPR penetration (for two boxes: the closed-form separating-axis test of
//                        box_box.hpp, exact and cheaper). MPR's normal is where the centre line
//                        leaves A ⊖ B, not the direction of least penetration: the least-depth
//                        expansion (epa.hpp) brings the depth within 1 % of the least one
//                        (docs/collision.md, "Least depth"), then normal refinement snaps a
//                        resting contact to a face (docs/collision.md, "Normal refinement"). The
//                        supporting faces of both shapes along that normal are
//                        tried as axes (one support call each) and the axis with the smallest depth
//                        wins, faces preferred within a small slack, so a resting contact gets the
//                        exact face normal;
//   generate_contacts()  the same on shapes inflated by a speculative margin, then a whole
//                        manifold by face clipping (face_clip.hpp): what the world uses per pair.
#pragma once

#include "../shape/shape.hpp"
#include "box_box.hpp"
#include "contact_points.hpp"
#include "epa.hpp"
#include "face_clip.hpp"
#include "mpr.hpp"
#include "round_pairs.hpp"
#include "sphere_solid.hpp"
#include "shape_ref.hpp"

#include <algorithm>
#include <optional>
#include <tuple>
#include <utility>

namespace xeno {

namespace detail {

/// Tries the supporting faces of A along n and of B along −n as contact normals; keeps the one with
/// the least depth h (faces win ties within `slack`). n is A-frame, unit; h is D's support distance
/// along n minus the margin (the true overlap along n).
template <class A, class B>
void refine_normal(const MinkowskiDifference<A, B>& md, Vec3<typename A::scalar_type>& n, typename A::scalar_type& h) {
    using T = typename A::scalar_type;
    // A ten-thousandth of the smaller shape, above round-off at the pair's size: of the pair's
    // size, a 10 cm hull on the edge of a 400 m box took the box's face up to 5.7 cm deeper than
    // the least depth (4 mm), and was pushed out that far.
    const T slack = std::max(T(1e-4) * md.smaller_scale(), md.round_off());
    auto depth_along = [&](const Vec3<T>& axis) { return dot(md.support(axis).v, axis) - md.margin(); };
    const Vec3<T> mpr_normal = n;
    bool have_face = false;
    if (const std::optional<Vec3<T>> face_a = md.flat_normal_a(mpr_normal)) {
        const T h_face = depth_along(*face_a);
        if (h_face <= h + slack) {
            n = *face_a;
            h = h_face;
            have_face = true;
        }
    }
    if (const std::optional<Vec3<T>> face_b = md.flat_normal_b(-mpr_normal)) {
        const Vec3<T> axis = -*face_b;
        const T h_face = depth_along(axis);
        // B's face replaces A's only when clearly better, so the choice does not flicker.
        if (have_face ? h_face < h - slack : h_face <= h + slack) {
            n = axis;
            h = h_face;
        }
    }
}

/// MPR + refinement on a Minkowski difference (possibly inflated by a margin), all in A's frame.
/// On a hit gives the normal, the overlap h along it (h > −margin means within reach) and
/// single-contact points h apart along n: with OnSurfaces, by collide()'s contract
/// (contact_points.hpp: each on its own body's surface where the support features overlap);
/// otherwise at the centre line's exit, the cheaper fallback build_manifold needs for point
/// features (a template flag, so generate_contacts does not instantiate the contract's code).
/// The least-depth expansion runs when MPR's overlap exceeds `expand_above` (metres; by default
/// always).
template <bool OnSurfaces = false, class A, class B>
bool refined_contact(const MinkowskiDifference<A, B>& md, Vec3<typename A::scalar_type>& n, typename A::scalar_type& h,
                     Vec3<typename A::scalar_type>& point_a, Vec3<typename A::scalar_type>& point_b,
                     typename A::scalar_type expand_above = -ScalarTraits<typename A::scalar_type>::infinity) {
    using T = typename A::scalar_type;
    if constexpr (is_round_pair<A, B>) {
        // Spheres and capsules, with each other or a box: exact in closed form (round_pairs.hpp).
        return round_contact(md, n, h, point_a, point_b);
    }
    if constexpr (is_sphere_solid_pair<A, B>) {
        // A sphere with a cylinder or a cone: exact in closed form (sphere_solid.hpp).
        return sphere_solid_contact(md, n, h, point_a, point_b);
    }
    if constexpr (std::is_same_v<A, Box<T>> && std::is_same_v<B, Box<T>>) {
        // Two boxes: the exact separating axis in closed form is cheaper than MPR and exact.
        return box_box_axis<OnSurfaces>(md, n, h, point_a, point_b) && h > -md.margin();
    }
    Vec3<T> simplex[4];
    const Penetration<T> p = mpr(md, false, simplex);
    if (!p.hit) return false;
    n = p.normal;
    T support_distance = p.depth;  // of D, margin included
    if (support_distance - md.margin() > expand_above) expand_to_least_depth(md, simplex, n, support_distance);
    h = support_distance - md.margin();
    refine_normal(md, n, h);
    if (!(h > -md.margin())) return false;
    if constexpr (OnSurfaces) {
        // collide()'s contract: the points from the support features along the final normal
        // (contact_points.hpp), with a point inside both shapes as the fallback.
        const Vec3<T> inside = point_inside_both(md, p);
        place_contact_points(md, n, h, &inside, point_a, point_b);
        return true;
    }
    // The manifold's fallback points (build_manifold clips faces and uses these only for point
    // features): remove the margin's inflation from A's witness, place them h apart along n.
    const Vec3<T> middle = (p.point_a - p.normal * md.margin() + p.point_b) * T(0.5);
    point_a = middle + n * (T(0.5) * h);
    point_b = middle - n * (T(0.5) * h);
    return true;
}

/// Pairs that go through MPR (not closed-form: round pairs, a sphere with a cylinder or a cone,
/// two boxes).
template <class A, class B>
constexpr bool answered_by_mpr =
    !is_round_pair<A, B> && !is_sphere_solid_pair<A, B> &&
    !(std::is_same_v<A, Box<typename A::scalar_type>> && std::is_same_v<B, Box<typename A::scalar_type>>);

/// Whether collide() and intersect() should run a pair as (B, A) and flip the answer. MPR and the
/// least-depth expansion stop within tolerances along paths that depend on the order, so a pair
/// that has two nearly equal directions of least depth could otherwise get a different one each
/// way round; the round pairs' closed forms work in one shape's frame, so their round-off depends
/// on the order, and where the normal is free (coincident centres, a ball's centre on a capsule's
/// axis) they would pick a different one each way round. One canonical order (by shape kind, then
/// pose, then size; ties keep the given order) makes collide(A, B) and collide(B, A) agree
/// exactly. Two boxes keep the given order: their separating axes are exact to rounding either
/// way, and in the first box's frame a face normal of an unrotated first box comes out exact (a
/// box resting on an unrotated floor gets the normal (0, 1, 0), not a rounding of it).
template <class T>
bool query_order_swapped(const Shape<T>& a, const Transform<T>& pose_a, const Shape<T>& b, const Transform<T>& pose_b) {
    if (std::holds_alternative<Box<T>>(a) && std::holds_alternative<Box<T>>(b)) return false;
    const auto key = [](const Shape<T>& s, const Transform<T>& p) {
        return std::make_tuple(s.index(), p.position.x, p.position.y, p.position.z, p.orientation.w, p.orientation.x,
                               p.orientation.y, p.orientation.z, bounding_radius(s));
    };
    return key(b, pose_b) < key(a, pose_a);
}

/// collide() for two spheres in the world frame: no pair frame (a rotation matrix and the general
/// round-pair reduction cost 2–3 times the rest of the query). nullopt when the centres are within
/// touching distance, where the normal is free and the general reduction (round_pairs.hpp) picks
/// it. intersect() asks this too, so the two agree exactly.
template <class T>
std::optional<Penetration<T>> sphere_pair(const Sphere<T>& a, const Transform<T>& pose_a, const Sphere<T>& b,
                                          const Transform<T>& pose_b) {
    const T distance = length(pose_b.position - pose_a.position);
    if (!(distance > touching_distance(a.bounding_radius() + b.bounding_radius()))) return std::nullopt;
    Penetration<T> out;
    const T depth = a.radius() + b.radius() - distance;
    if (!(depth > T(0))) return out;
    out.hit = true;
    out.normal = (pose_b.position - pose_a.position) / distance;
    out.depth = depth;
    out.point_b = pose_b.position - out.normal * b.radius();  // on B, depth from A's support plane
    out.point_a = out.point_b + out.normal * depth;
    return out;
}

/// collide() for one concrete pair in the given order, world frame.
template <class A, class B>
Penetration<typename A::scalar_type> collide_pair(const A& a, const Transform<typename A::scalar_type>& pose_a, const B& b,
                                                  const Transform<typename A::scalar_type>& pose_b) {
    using T = typename A::scalar_type;
    if constexpr (std::is_same_v<A, Sphere<T>> && std::is_same_v<B, Sphere<T>>) {
        if (const std::optional<Penetration<T>> p = sphere_pair(a, pose_a, b, pose_b)) return *p;
    }
    const MinkowskiDifference<A, B> md(a, pose_a, b, pose_b);
    Penetration<T> out;
    Vec3<T> n, pa, pb;
    T h;
    if (!refined_contact<true>(md, n, h, pa, pb) || !(h > T(0))) return out;
    out.hit = true;
    out.normal = pose_a.apply_direction(n);
    out.depth = h;
    out.point_a = pose_a.apply(pa);
    out.point_b = pose_a.apply(pb);
    return out;
}

/// generate_contacts() for one Minkowski difference (inflated by the margin), A's frame.
template <class A, class B>
ContactManifold<typename A::scalar_type> manifold_of(const MinkowskiDifference<A, B>& md,
                                                     typename A::scalar_type exact_depth_above) {
    using T = typename A::scalar_type;
    if constexpr (is_round_pair<A, B>) {
        return round_manifold(md);  // their own manifolds
    } else if constexpr (is_sphere_solid_pair<A, B>) {
        return sphere_solid_manifold(md);
    } else {
        Vec3<T> n, pa, pb;
        T h;
        if (!refined_contact(md, n, h, pa, pb, exact_depth_above)) return ContactManifold<T>{};
        return build_manifold(md, n, pa, pb, h, md.margin());
    }
}

/// The same contact seen from the other body.
template <class T>
Penetration<T> flipped(Penetration<T> p) {
    p.normal = -p.normal;
    std::swap(p.point_a, p.point_b);
    return p;
}

/// intersect() in the given order.
template <class T>
bool intersect_in_order(const Shape<T>& a, const Transform<T>& pose_a, const Shape<T>& b, const Transform<T>& pose_b) {
    const std::optional<bool> closed_form = std::visit(
        [&](const auto& sa, const auto& sb) -> std::optional<bool> {
            using SA = std::decay_t<decltype(sa)>;
            using SB = std::decay_t<decltype(sb)>;
            // Closed-form pairs: cheaper than MPR, and always the same answer as collide().hit.
            if constexpr (std::is_same_v<SA, Sphere<T>> && std::is_same_v<SB, Sphere<T>>) {
                const std::optional<Penetration<T>> p = sphere_pair(sa, pose_a, sb, pose_b);
                return p ? p->hit : true;  // centres within touching distance: a hit (round_intersect)
            } else if constexpr (is_round_pair<SA, SB>) {
                return round_intersect(MinkowskiDifference<SA, SB>(sa, pose_a, sb, pose_b));
            } else if constexpr (is_sphere_solid_pair<SA, SB>) {
                return sphere_solid_intersect(MinkowskiDifference<SA, SB>(sa, pose_a, sb, pose_b));
            } else if constexpr (!answered_by_mpr<SA, SB>) {  // two boxes
                const MinkowskiDifference<SA, SB> md(sa, pose_a, sb, pose_b);
                Vec3<T> n, pa, pb;
                T h;
                return refined_contact(md, n, h, pa, pb) && h > T(0);
            } else {
                return std::nullopt;
            }
        },
        a, b);
    if (closed_form) return *closed_form;
    // MPR pairs, compiled once for every kind (shape_ref.hpp); the poses were checked by the
    // caller (MPR directly, not mpr_intersect, which checks them again).
    using AnyPair = MinkowskiDifference<ShapeRef<T>, ShapeRef<T>>;
    const ShapeRef<T> any_a(a), any_b(b);
    return mpr(AnyPair(any_a, pose_a, any_b, pose_b), true).hit;
}

/// collide() in the given order.
template <class T>
Penetration<T> collide_in_order(const Shape<T>& a, const Transform<T>& pose_a, const Shape<T>& b, const Transform<T>& pose_b) {
    const std::optional<Penetration<T>> closed_form = std::visit(
        [&](const auto& sa, const auto& sb) -> std::optional<Penetration<T>> {
            using SA = std::decay_t<decltype(sa)>;
            using SB = std::decay_t<decltype(sb)>;
            if constexpr (answered_by_mpr<SA, SB>) return std::nullopt;
            else return collide_pair(sa, pose_a, sb, pose_b);
        },
        a, b);
    if (closed_form) return *closed_form;
    const ShapeRef<T> any_a(a), any_b(b);
    return collide_pair(any_a, pose_a, any_b, pose_b);
}

/// Whether B's position less A's is finite. Two finite poses near ±max of T are farther apart
/// than T holds, and no shape (at most max_size across) spans that: two boxes at ±FLT_MAX had
/// their offset overflow to inf, which the separating-axis test read as an overlap of depth inf.
template <class T>
bool offset_is_finite(const Transform<T>& pose_a, const Transform<T>& pose_b) {
    return is_finite(pose_b.position - pose_a.position);
}

}  // namespace detail

/// True when the shapes overlap (touching is not overlapping). Poses must be finite (InvalidArgument).
/// Runs in collide()'s order, so the two agree, whichever order they are given the shapes in.
template <class T>
bool intersect(const Shape<T>& a, const Transform<T>& pose_a, const Shape<T>& b, const Transform<T>& pose_b) {
    detail::require_moved_in(a, "intersect");
    detail::require_moved_in(b, "intersect");
    detail::require_finite_pose(pose_a, "intersect", "pose_a");
    detail::require_finite_pose(pose_b, "intersect", "pose_b");
    if (!detail::offset_is_finite(pose_a, pose_b)) return false;
    if (detail::query_order_swapped(a, pose_a, b, pose_b)) return detail::intersect_in_order(b, pose_b, a, pose_a);
    return detail::intersect_in_order(a, pose_a, b, pose_b);
}

/// Penetration of two shapes with the refined normal: hit, unit normal A → B (world), the overlap
/// depth along it (> 0) and a point on each body. Poses must be finite (InvalidArgument).
/// collide(b, pose_b, a, pose_a) gives the same answer with the normal negated and the points
/// swapped, bit for bit, for every pair of kinds but two boxes, which agree to rounding
/// (detail::query_order_swapped says why).
template <class T>
Penetration<T> collide(const Shape<T>& a, const Transform<T>& pose_a, const Shape<T>& b, const Transform<T>& pose_b) {
    detail::require_moved_in(a, "collide");
    detail::require_moved_in(b, "collide");
    detail::require_finite_pose(pose_a, "collide", "pose_a");
    detail::require_finite_pose(pose_b, "collide", "pose_b");
    if (!detail::offset_is_finite(pose_a, pose_b)) return {};
    if (detail::query_order_swapped(a, pose_a, b, pose_b)) return detail::flipped(detail::collide_in_order(b, pose_b, a, pose_a));
    return detail::collide_in_order(a, pose_a, b, pose_b);
}

/// The contact manifold the world uses: up to four points with one normal (A → B), including
/// speculative points up to `margin` metres apart. count == 0 when the shapes are farther apart.
/// Poses are assumed finite (the world checks them at the door). On pairs answered by MPR the
/// least-depth expansion runs when the overlap exceeds `exact_depth_above` metres (by default
/// always; the world passes its linear_slop: shallower overlaps are within round-off of MPR's
/// answer and cost nothing to leave, docs/collision.md, "Least depth").
template <class T>
ContactManifold<T> generate_contacts(const Shape<T>& a, const Transform<T>& pose_a, const Shape<T>& b, const Transform<T>& pose_b,
                                     T margin, T exact_depth_above = -ScalarTraits<T>::infinity) {
    const std::optional<ContactManifold<T>> closed_form = std::visit(
        [&](const auto& sa, const auto& sb) -> std::optional<ContactManifold<T>> {
            using SA = std::decay_t<decltype(sa)>;
            using SB = std::decay_t<decltype(sb)>;
            if constexpr (detail::answered_by_mpr<SA, SB>) return std::nullopt;
            else return detail::manifold_of(MinkowskiDifference<SA, SB>(sa, pose_a, sb, pose_b, margin), exact_depth_above);
        },
        a, b);
    if (closed_form) return *closed_form;
    const detail::ShapeRef<T> any_a(a), any_b(b);
    return detail::manifold_of(
        MinkowskiDifference<detail::ShapeRef<T>, detail::ShapeRef<T>>(any_a, pose_a, any_b, pose_b, margin), exact_depth_above);
}

#ifdef XENO_COMPILED_LIB
// Compiled mode (compiled.hpp): float and double are compiled once, in src/xeno_compiled.cpp.
#define XENO_DETAIL_EXTERN_COLLIDE(T)                                                                                      \
    extern template bool intersect<T>(const Shape<T>&, const Transform<T>&, const Shape<T>&, const Transform<T>&);         \
    extern template Penetration<T> collide<T>(const Shape<T>&, const Transform<T>&, const Shape<T>&, const Transform<T>&); \
    extern template ContactManifold<T> generate_contacts<T>(const Shape<T>&, const Transform<T>&, const Shape<T>&,         \
                                                            const Transform<T>&, T, T);
XENO_DETAIL_EXTERN_COLLIDE(float)
XENO_DETAIL_EXTERN_COLLIDE(double)
#undef XENO_DETAIL_EXTERN_COLLIDE
#endif

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// World's queries: ray casts (nearest, any, all) and overlaps (point, box, sphere, any convex
// shape), each through the query trees (World::query_trees_: AabbTrees of every living body's
// current world box, static bodies in one, the others in the other) and a QueryFilter. The trees
// only decide which bodies are tried; the exact
// test is the shape's own (raycast, contains_point, intersect), the same one a scan of every body
// would make, so the answers equal that scan's bit for bit (tests/dynamics/query_test.cpp).
// Cost: a ray visits the boxes along it, nearest first, and the nearest-hit search stops looking
// beyond its best hit; an overlap visits the boxes that overlap the query's box. Included at the
// end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

/// The body's nearest hit over its parts (one for a convex body), in the ray's own length.
template <class T>
std::optional<RayHit<T>> World<T>::nearest_hit(std::uint32_t slot, const Ray<T>& ray) const {
    const Body<T>& b = bodies_[slot];
    std::optional<RayHit<T>> nearest;
    if (b.mesh()) {
        if (const auto hit = xeno::raycast(*b.mesh(), b.transform(), ray)) nearest = hit->first;
    }
    for (std::uint32_t k = 0; k < b.child_count(); ++k)
        if (const std::optional<RayHit<T>> hit = detail::raycast_checked(b.child_shape(k), b.child_transform(k), ray))
            if (!nearest || hit->distance < nearest->distance) nearest = hit;
    return nearest;
}

template <class T>
std::optional<WorldRayHit<T>> World<T>::raycast(const Ray<T>& unchecked, const QueryFilter<T>& filter) const {
    const Ray<T> ray = detail::checked_ray(unchecked, "World::raycast");
    std::optional<WorldRayHit<T>> best;
    auto visit = [&](std::uint32_t slot, T reach) {
        if (!seen_by(filter, slot)) return reach;
        const std::optional<RayHit<T>> hit = nearest_hit(slot, ray);
        if (!hit || hit->distance > reach) return reach;
        // Equal distances go to the lower slot, whatever order the trees visit them in.
        if (!best || hit->distance < best->hit.distance || (hit->distance == best->hit.distance && slot < best->body.index))
            best = WorldRayHit<T>{id_of(slot), *hit};
        return best->hit.distance;  // from now on only boxes that start no farther matter
    };
    for (const AabbTree<T>& tree : query_trees_)
        tree.query_segment(ray.origin, ray.direction, best ? best->hit.distance : ray.max_distance, visit);
    return best;
}

template <class T>
std::optional<WorldRayHit<T>> World<T>::raycast_any(const Ray<T>& unchecked, const QueryFilter<T>& filter) const {
    const Ray<T> ray = detail::checked_ray(unchecked, "World::raycast_any");
    std::optional<WorldRayHit<T>> found;
    for (const AabbTree<T>& tree : query_trees_) {
        tree.query_segment(ray.origin, ray.direction, ray.max_distance, [&](std::uint32_t slot, T reach) {
            if (!seen_by(filter, slot)) return reach;
            const std::optional<RayHit<T>> hit = nearest_hit(slot, ray);
            if (!hit) return reach;
            found = WorldRayHit<T>{id_of(slot), *hit};
            return T(-1);  // stop
        });
        if (found) break;
    }
    return found;
}

template <class T>
std::vector<WorldRayHit<T>> World<T>::raycast_all(const Ray<T>& unchecked, const QueryFilter<T>& filter) const {
    const Ray<T> ray = detail::checked_ray(unchecked, "World::raycast_all");
    std::vector<WorldRayHit<T>> hits;
    for (const AabbTree<T>& tree : query_trees_)
        tree.query_segment(ray.origin, ray.direction, ray.max_distance, [&](std::uint32_t slot, T reach) {
            if (seen_by(filter, slot))
                if (const std::optional<RayHit<T>> hit = nearest_hit(slot, ray)) hits.push_back({id_of(slot), *hit});
            return reach;
        });
    std::sort(hits.begin(), hits.end(), [](const WorldRayHit<T>& x, const WorldRayHit<T>& y) {
        return x.hit.distance != y.hit.distance ? x.hit.distance < y.hit.distance : x.body.index < y.body.index;
    });
    return hits;
}

/// The bodies whose tree box overlaps `box`, that the filter lets through and for which
/// exact(slot) holds, in slot order.
template <class T>
template <class Exact>
std::vector<BodyId> World<T>::overlapping(const Aabb<T>& box, const QueryFilter<T>& filter, Exact&& exact) const {
    std::vector<BodyId> out;
    for (const AabbTree<T>& tree : query_trees_)
        tree.query(box, [&](std::uint32_t slot) {
            if (seen_by(filter, slot) && exact(slot)) out.push_back(id_of(slot));
        });
    std::sort(out.begin(), out.end(), [](BodyId x, BodyId y) { return x.index < y.index; });
    return out;
}

template <class T>
std::vector<BodyId> World<T>::query_point(const Vec3<T>& point, const QueryFilter<T>& filter) const {
    detail::require_finite_xyz(point, "World::query_point", "point");
    return overlapping(Aabb<T>{point, point}, filter, [&](std::uint32_t slot) {
        const Body<T>& b = bodies_[slot];
        for (std::uint32_t k = 0; k < b.child_count(); ++k)
            if (contains_point(b.child_shape(k), b.child_transform(k), point)) return true;
        return false;
    });
}

template <class T>
std::vector<BodyId> World<T>::query_aabb(const Aabb<T>& box, const QueryFilter<T>& filter) const {
    detail::require_finite_xyz(box.min, "World::query_aabb", "box.min");
    detail::require_finite_xyz(box.max, "World::query_aabb", "box.max");
    // Corners given the wrong way round overlap nothing: a swapped box would find no body and say
    // nothing (Box2D asserts the same).
    const Vec3<T> inverted = box.min - box.max;
    if (max_component(inverted) > T(0))
        detail::report_invalid("World::query_aabb", "box.min must not exceed box.max on any axis; largest min - max (m)",
                               static_cast<double>(max_component(inverted)));
    return overlapping(box, filter, [&](std::uint32_t slot) { return overlaps(bodies_[slot].world_bounds(), box); });
}

template <class T>
std::vector<BodyId> World<T>::overlap_sphere(const Vec3<T>& center, T radius, const QueryFilter<T>& filter) const {
    detail::require_finite_xyz(center, "World::overlap_sphere", "center");
    detail::require_size(radius, "World::overlap_sphere", "radius");  // Sphere's check, under this call's name
    return overlap_shape(Sphere<T>(radius), Transform<T>{center, Quat<T>{}}, filter);
}

template <class T>
std::vector<BodyId> World<T>::overlap_shape(const Shape<T>& shape, const Transform<T>& pose, const QueryFilter<T>& filter) const {
    detail::require_moved_in(shape, "World::overlap_shape");
    detail::require_finite_pose(pose, "World::overlap_shape", "pose");
    const Aabb<T> box = world_bounds(shape, pose);
    return overlapping(box, filter, [&](std::uint32_t slot) {
        const Body<T>& b = bodies_[slot];
        if (b.mesh() && intersect_mesh(*b.mesh(), b.transform(), shape, pose)) return true;
        for (std::uint32_t k = 0; k < b.child_count(); ++k)
            if (intersect(shape, pose, b.child_shape(k), b.child_transform(k))) return true;
        return false;
    });
}

// The bodies whose boxes the swept box (the shape's box at the start and at the end, merged)
// overlaps are cast against part by part; the nearest hit wins. A sweep through a crowd tries
// every body in its box: keep long casts for sparse places (or split them).
template <class T>
std::optional<WorldShapeCastHit<T>> World<T>::shape_cast(const Shape<T>& shape, const Transform<T>& pose,
                                                         const Vec3<T>& translation, const QueryFilter<T>& filter) const {
    detail::require_moved_in(shape, "World::shape_cast");
    detail::require_finite_pose(pose, "World::shape_cast", "pose");
    detail::require_finite_xyz(translation, "World::shape_cast", "translation");
    Aabb<T> swept = world_bounds(shape, pose);
    swept.merge(world_bounds(shape, Transform<T>{pose.position + translation, pose.orientation}));
    std::optional<WorldShapeCastHit<T>> best;
    for (const AabbTree<T>& tree : query_trees_)
        tree.query(swept, [&](std::uint32_t slot) {
            if (!seen_by(filter, slot)) return;
            const Body<T>& b = bodies_[slot];
            for (std::uint32_t k = 0; k < b.child_count() + (b.mesh() ? 1u : 0u); ++k) {
                const std::optional<ShapeCastHit<T>> hit =
                    b.mesh() ? xeno::shape_cast(shape, pose, translation, *b.mesh(), b.transform())
                             : xeno::shape_cast(shape, pose, translation, b.child_shape(k), b.child_transform(k));
                if (!hit) continue;
                if (!best || hit->fraction < best->hit.fraction ||
                    (hit->fraction == best->hit.fraction && slot < best->body.index))
                    best = WorldShapeCastHit<T>{id_of(slot), *hit};
            }
        });
    return best;
}

template <class T>
std::optional<WorldShapeCastHit<T>> World<T>::shape_cast(const Compound<T>& compound, const Transform<T>& pose,
                                                         const Vec3<T>& translation, const QueryFilter<T>& filter) const {
    detail::require_finite_pose(pose, "World::shape_cast", "pose");
    std::optional<WorldShapeCastHit<T>> best;
    for (const CompoundChild<T>& child : compound.children()) {
        const std::optional<WorldShapeCastHit<T>> hit = shape_cast(child.shape, pose * child.local, translation, filter);
        if (hit && (!best || hit->hit.fraction < best->hit.fraction ||
                    (hit->hit.fraction == best->hit.fraction && hit->body.index < best->body.index)))
            best = hit;
    }
    return best;
}

}  // namespace xeno

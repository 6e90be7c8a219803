// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// MeshShape<T>: the level geometry a static or kinematic body can be made of, a TriangleMesh or a
// HeightField (docs/meshes.md). Both answer the same three questions, so the world treats them
// alike through these few functions: their local box, the triangles under a box, and ray casts.
#pragma once

#include "height_field.hpp"
#include "triangle_mesh.hpp"

#include <variant>

namespace xeno {

/// A triangle mesh or a heightfield.
template <class T>
using MeshShape = std::variant<TriangleMesh<T>, HeightField<T>>;

template <class T>
Aabb<T> local_bounds(const MeshShape<T>& m) {
    return std::visit([](const auto& mesh) { return mesh.local_bounds(); }, m);
}

/// "mesh" or "heightfield".
template <class T>
const char* shape_name(const MeshShape<T>& m) {
    return m.index() == 0 ? "mesh" : "heightfield";
}

/// Triangles of the mesh (a heightfield's holes included in the count).
template <class T>
std::size_t triangle_count(const MeshShape<T>& m) {
    return std::visit([](const auto& mesh) { return mesh.size(); }, m);
}

/// World box of mesh m placed by t: its local box rotated (never smaller than the mesh).
template <class T>
Aabb<T> world_bounds(const MeshShape<T>& m, const Transform<T>& t) {
    const Aabb<T> local = local_bounds(m);
    const Mat3<T> r = to_matrix(t.orientation);
    const Mat3<T> abs_r{abs(r[0]), abs(r[1]), abs(r[2])};
    return Aabb<T>::from_center(t.apply(local.center()), abs_r * local.half_extents());
}

/// Calls f(k, triangle) for each triangle (local frame) whose box overlaps `local_box` and that
/// keep(triangle) accepts (keep may see the triangle without its edges' data).
template <class T, class F, class Keep = detail::KeepAll>
void for_each_triangle(const MeshShape<T>& m, const Aabb<T>& local_box, F&& f, Keep keep = {}) {
    std::visit([&](const auto& mesh) { mesh.for_each_triangle(local_box, f, keep); }, m);
}

/// The nearest hit of a world ray on mesh m placed by `pose` (either side of a triangle), with
/// the index of the triangle hit. The ray and pose are checked and the direction normalised as by
/// raycast(shape, pose, ray).
template <class T>
std::optional<std::pair<RayHit<T>, std::uint32_t>> raycast(const MeshShape<T>& m, const Transform<T>& pose,
                                                           const Ray<T>& unchecked) {
    detail::require_finite_pose(pose, "raycast", "pose");
    const Ray<T> ray = detail::checked_ray(unchecked, "raycast");
    // A ray from far away first moves up to the mesh's bounding sphere, as for convex shapes.
    const Aabb<T> bounds = local_bounds(m);
    const auto s = detail::skip_to(pose, pose.apply(bounds.center()), length(bounds.half_extents()), ray);
    if (!s) return std::nullopt;
    const Ray<T> local{s->origin, s->direction, ray.max_distance - s->skip};
    auto hit = std::visit([&](const auto& mesh) { return mesh.raycast(local); }, m);
    if (!hit) return hit;
    hit->first.distance += s->skip;
    hit->first.point = pose.apply(hit->first.point);
    hit->first.normal = pose.apply_direction(hit->first.normal);
    hit->first.fraction = ray.max_distance < ScalarTraits<T>::max ? hit->first.distance / ray.max_distance : T(0);
    return hit;
}

namespace f32 {
using MeshShape = xeno::MeshShape<float>;
}
namespace f64 {
using MeshShape = xeno::MeshShape<double>;
}

}  // namespace xeno

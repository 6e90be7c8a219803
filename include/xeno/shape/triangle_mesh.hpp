// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// TriangleMesh<T>: static level geometry made of indexed triangles (docs/meshes.md). Built once:
//   1. checked at the door (finite vertices within the size range, indices in range);
//   2. degenerate triangles (zero area, or slivers thinner than a millionth of their longest
//      edge) and duplicates (the same three corners, either winding) dropped and counted;
//   3. adjacency: corners welded by exact position, triangles sharing an edge found by sorting
//      edge keys, and each edge marked active or not (triangle.hpp, "active_edges");
//   4. a bounding-volume hierarchy by median splits of the triangles' centres along the longest
//      axis, leaves of up to four triangles: O(n log n); the build time and bytes per triangle
//      of a million-triangle mesh are measured by xeno_mesh_bench (docs/benchmarks.md, "Meshes").
// Bodies made of a mesh are static or kinematic (a mesh has no volume to give a mass).
#pragma once

#include "../collide/raycast.hpp"
#include "../error.hpp"
#include "../math/scalar.hpp"
#include "triangle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace xeno {

namespace detail {

/// Whether the edge from p shared with a neighbour whose third corner is w is active for a
/// triangle of unit normal n: only convex edges bent by more than about 2° are (a coplanar or
/// concave neighbour covers every contact the edge could give, so its normals would be ghosts).
template <class T>
bool edge_is_active(const Vec3<T>& n, const Vec3<T>& p, const Vec3<T>& q, const Vec3<T>& w) {
    const Vec3<T> e = q - p, r = w - p;
    const Vec3<T> across = r - e * (dot(r, e) / length_squared(e));  // from the edge to w, in w's plane
    const T rise = dot(r, n);
    return rise < -T(0.035) * length(across);  // sin 2°: the neighbour falls away
}

/// Unit normal of (a, b, c) wound counter-clockwise, or zero for a degenerate triangle.
template <class T>
Vec3<T> triangle_normal(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
    const Vec3<T> n = cross(b - a, c - a);
    const T len = length(n);
    const T longest = std::max({length(b - a), length(c - b), length(a - c)});
    if (!(len > T(1e-6) * longest * longest)) return Vec3<T>::zero();
    return n / len;
}

/// The default triangle filter of for_each_triangle: every triangle.
struct KeepAll {
    template <class Triangle>
    bool operator()(const Triangle&) const {
        return true;
    }
};

/// A node of a mesh's hierarchy: a leaf holds triangles [first, first + count); an inner node
/// (count == 0) has its children at its own index + 1 and at `first`.
template <class T>
struct BvhNode {
    Aabb<T> box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

}  // namespace detail

/// Indexed triangles with a hierarchy for box and ray queries (see the file comment).
template <class T>
class TriangleMesh {
public:
    using scalar_type = T;
    using Indices = std::array<std::uint32_t, 3>;

    /// Triangles wound counter-clockwise seen from their front (normals by the right-hand rule).
    /// InvalidArgument for a non-finite or out-of-range vertex, an index past the vertices, or no
    /// triangle left once degenerate ones are dropped.
    TriangleMesh(std::vector<Vec3<T>> vertices, const std::vector<Indices>& triangles);

    std::size_t size() const { return tris_.size(); }
    const std::vector<Vec3<T>>& vertices() const { return vertices_; }
    /// Triangles dropped at build (degenerate or duplicate).
    std::size_t dropped_triangles() const { return dropped_; }
    Aabb<T> local_bounds() const { return nodes_.empty() ? Aabb<T>{} : nodes_.front().box; }  // empty: moved from
    /// Triangle k of the hierarchy's order (0 … size() - 1; source_index(k) is its number in the
    /// constructor's list, the number queries and contacts report).
    MeshTriangle<T> triangle(std::uint32_t k) const {
        const Indices& t = tris_[k];
        MeshTriangle<T> out{{vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]}, {}, active_[k], {}};
        out.normal = detail::triangle_normal(out.v[0], out.v[1], out.v[2]);
        for (int e = 0; e < 3; ++e) out.fold_cos[e] = fold_cos_[k][static_cast<std::size_t>(e)];
        return out;
    }
    /// The index the triangle had in the constructor's list.
    std::uint32_t source_index(std::uint32_t k) const { return source_[k]; }
    /// Calls f(source index, triangle) for every triangle whose box overlaps `box` (local frame),
    /// in a fixed order.
    template <class F, class Keep = detail::KeepAll>
    void for_each_triangle(const Aabb<T>& box, F&& f, Keep keep = {}) const;
    /// The nearest hit of a ray (local frame) on either side of any triangle, with the triangle. The
    /// ray is checked as raycast(shape, pose, ray) checks it (InvalidArgument).
    std::optional<std::pair<RayHit<T>, std::uint32_t>> raycast(const Ray<T>& ray) const;
    /// Bytes held, for the benchmark's memory per triangle.
    std::size_t memory_bytes() const {
        return vertices_.capacity() * sizeof(Vec3<T>) + tris_.capacity() * sizeof(Indices) + active_.capacity() +
               fold_cos_.capacity() * sizeof(std::array<T, 3>) + source_.capacity() * sizeof(std::uint32_t) +
               nodes_.capacity() * sizeof(detail::BvhNode<T>);
    }

private:
    void drop_bad_triangles(const std::vector<Indices>& triangles);
    void mark_edges();
    void build_hierarchy();
    std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::vector<std::uint32_t>& order,
                        const std::vector<Aabb<T>>& boxes, const std::vector<Vec3<T>>& centres);

    std::vector<Vec3<T>> vertices_;
    std::vector<Indices> tris_;
    std::vector<std::uint8_t> active_;
    std::vector<std::array<T, 3>> fold_cos_;  ///< per edge: MeshTriangle::fold_cos
    std::vector<std::uint32_t> source_;
    std::vector<detail::BvhNode<T>> nodes_;
    std::size_t dropped_ = 0;
};

template <class T>
TriangleMesh<T>::TriangleMesh(std::vector<Vec3<T>> vertices, const std::vector<Indices>& triangles)
    : vertices_(std::move(vertices)) {
    const char* where = "TriangleMesh";
    // Indices are 32-bit: every vertex and triangle must have a number below 2³² − 1.
    if (vertices_.size() >= 0xffffffffu || triangles.size() >= 0xffffffffu)
        detail::report_invalid(where, "takes fewer than 2^32 - 1 vertices and triangles; count",
                               static_cast<double>(std::max(vertices_.size(), triangles.size())));
    const T limit = ScalarTraits<T>::max_size;
    for (std::size_t i = 0; i < vertices_.size(); ++i) {
        const Vec3<T>& v = vertices_[i];
        if (!(std::abs(v.x) <= limit && std::abs(v.y) <= limit && std::abs(v.z) <= limit))  // NaN too; the message only then
            detail::require_within_xyz(v, limit, where, ("vertex " + std::to_string(i)).c_str(), " m");
    }
    for (std::size_t k = 0; k < triangles.size(); ++k)
        for (std::uint32_t index : triangles[k])
            if (index >= vertices_.size())
                detail::report_invalid(where,
                                       ("triangle " + std::to_string(k) + " has a vertex index past the vertices; index").c_str(),
                                       static_cast<double>(index));
    drop_bad_triangles(triangles);
    if (tris_.empty())
        detail::report_invalid(where, "needs at least one triangle that is not degenerate; triangles given",
                               static_cast<double>(triangles.size()));
    mark_edges();
    build_hierarchy();
}

template <class T>
void TriangleMesh<T>::drop_bad_triangles(const std::vector<Indices>& triangles) {
    // Weld corners by exact position so duplicates and neighbours are found whatever the indexing.
    std::vector<std::uint32_t> order(vertices_.size()), weld(vertices_.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto key = [&](std::uint32_t i) { return std::make_tuple(vertices_[i].x, vertices_[i].y, vertices_[i].z, i); };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    for (std::size_t i = 0; i < order.size(); ++i)
        weld[order[i]] = i > 0 && vertices_[order[i]] == vertices_[order[i - 1]] ? weld[order[i - 1]] : order[i];
    std::vector<std::pair<Indices, std::uint32_t>> sorted;  // corner set (welded, ascending), source index
    for (std::uint32_t k = 0; k < triangles.size(); ++k) {
        Indices t{weld[triangles[k][0]], weld[triangles[k][1]], weld[triangles[k][2]]};
        if (detail::triangle_normal(vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]) == Vec3<T>::zero()) continue;
        std::sort(t.begin(), t.end());
        sorted.push_back({t, k});
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) {
        if (i > 0 && sorted[i].first == sorted[i - 1].first) continue;  // a duplicate: the first one given stays
        const Indices& t = triangles[sorted[i].second];
        tris_.push_back({weld[t[0]], weld[t[1]], weld[t[2]]});
        source_.push_back(sorted[i].second);
    }
    dropped_ = triangles.size() - tris_.size();
    // Back to the order given, so the hierarchy's input does not depend on the corners' values.
    std::vector<std::uint32_t> by_source(tris_.size());
    std::iota(by_source.begin(), by_source.end(), 0u);
    std::sort(by_source.begin(), by_source.end(), [&](std::uint32_t a, std::uint32_t b) { return source_[a] < source_[b]; });
    std::vector<Indices> tris(tris_.size());
    std::vector<std::uint32_t> source(tris_.size());
    for (std::size_t i = 0; i < by_source.size(); ++i) tris[i] = tris_[by_source[i]], source[i] = source_[by_source[i]];
    tris_.swap(tris);
    source_.swap(source);
}

// Each edge is keyed by its two (welded) corners; triangles with equal keys are neighbours. An
// edge with no neighbour (the mesh's border) or with more than one (not a surface there) stays
// active; with one, edge_is_active decides from the neighbour's third corner.
template <class T>
void TriangleMesh<T>::mark_edges() {
    struct EdgeRef {
        std::uint32_t lo, hi, tri, edge;
        bool operator<(const EdgeRef& o) const { return std::tie(lo, hi, tri, edge) < std::tie(o.lo, o.hi, o.tri, o.edge); }
    };
    std::vector<EdgeRef> edges;
    edges.reserve(3 * tris_.size());
    for (std::uint32_t k = 0; k < tris_.size(); ++k)
        for (std::uint32_t e = 0; e < 3; ++e) {
            const std::uint32_t p = tris_[k][e], q = tris_[k][(e + 1) % 3];
            edges.push_back({std::min(p, q), std::max(p, q), k, e});
        }
    std::sort(edges.begin(), edges.end());
    active_.assign(tris_.size(), 7);
    fold_cos_.assign(tris_.size(), {T(-1), T(-1), T(-1)});
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i + 1;
        while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
        if (j - i == 2) {
            for (int side = 0; side < 2; ++side) {
                const EdgeRef& mine = edges[i + static_cast<std::size_t>(side)];
                const EdgeRef& other = edges[i + static_cast<std::size_t>(1 - side)];
                const Indices& t = tris_[mine.tri];
                const Vec3<T>& p = vertices_[t[mine.edge]];
                const Vec3<T>& q = vertices_[t[(mine.edge + 1) % 3]];
                const Vec3<T>& w = vertices_[tris_[other.tri][(other.edge + 2) % 3]];
                const Vec3<T> n = detail::triangle_normal(vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
                fold_cos_[mine.tri][mine.edge] = dot(n, detail::triangle_normal(q, p, w));  // the neighbour runs q → p
                if (!detail::edge_is_active(n, p, q, w)) active_[mine.tri] &= static_cast<std::uint8_t>(~(1u << mine.edge));
            }
        }
        i = j;
    }
}

// The hierarchy is built on a permutation of the triangles, applied once at the end. Median
// split along the longest axis of the triangles' centres: the k smallest centres (ties by index)
// go left, a strict order, so each side's set (and so the whole tree) is the same whatever the
// standard library's nth_element does; a leaf's triangles are kept in index order.
template <class T>
void TriangleMesh<T>::build_hierarchy() {
    const std::size_t n = tris_.size();
    std::vector<Aabb<T>> boxes(n);
    std::vector<Vec3<T>> centres(n);
    for (std::size_t k = 0; k < n; ++k) {
        for (std::uint32_t v : tris_[k]) boxes[k].merge(vertices_[v]);
        centres[k] = boxes[k].center();
    }
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    nodes_.reserve(n / 2 + 2);
    build(0, static_cast<std::uint32_t>(n), order, boxes, centres);
    const auto permute = [&](auto& table) {
        std::remove_reference_t<decltype(table)> sorted(n);
        for (std::size_t i = 0; i < n; ++i) sorted[i] = table[order[i]];
        table.swap(sorted);
    };
    permute(tris_), permute(source_), permute(active_), permute(fold_cos_);
}

template <class T>
std::uint32_t TriangleMesh<T>::build(std::uint32_t begin, std::uint32_t end, std::vector<std::uint32_t>& order,
                                     const std::vector<Aabb<T>>& boxes, const std::vector<Vec3<T>>& centres) {
    const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Aabb<T> box, centre_box;
    for (std::uint32_t i = begin; i < end; ++i) {
        box.merge(boxes[order[i]]);
        centre_box.merge(centres[order[i]]);
    }
    nodes_[index].box = box;
    if (end - begin <= 4) {
        std::sort(order.begin() + begin, order.begin() + end);
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    }
    const int axis = max_axis(centre_box.max - centre_box.min);
    const std::uint32_t half = begin + (end - begin) / 2;
    std::nth_element(order.begin() + begin, order.begin() + half, order.begin() + end, [&](std::uint32_t a, std::uint32_t b) {
        return centres[a][axis] < centres[b][axis] || (centres[a][axis] == centres[b][axis] && a < b);
    });
    build(begin, half, order, boxes, centres);
    nodes_[index].first = build(half, end, order, boxes, centres);
    return index;
}

template <class T>
template <class F, class Keep>
void TriangleMesh<T>::for_each_triangle(const Aabb<T>& box, F&& f, Keep keep) const {
    if (nodes_.empty()) return;  // moved from: no triangles
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const detail::BvhNode<T>& node = nodes_[stack[--top]];
        if (!overlaps(node.box, box)) continue;
        if (node.count > 0) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                const MeshTriangle<T> t = triangle(k);
                Aabb<T> tb;
                for (const Vec3<T>& v : t.v) tb.merge(v);
                if (overlaps(tb, box) && keep(t)) f(source_[k], t);
            }
            continue;
        }
        const std::uint32_t self = static_cast<std::uint32_t>(&node - nodes_.data());
        stack[top++] = node.first;  // right, visited after the left
        stack[top++] = self + 1;
    }
}

namespace detail {

/// A ray's own frame, after Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection"
/// (JCGT 2(1), 2013): the axes permuted so that the ray's largest component is z, x and y sheared
/// so that the ray runs down the z axis from the origin, z scaled to distance along the ray. A
/// point's x, y say where it lies across the ray; each corner is placed once, the same for every
/// triangle that shares it.
template <class T>
struct RayFrame {
    using Axis = T Vec3<T>::*;
    Vec3<T> origin;
    Axis x, y, z;  ///< the world axes that become x, y, z
    T sx, sy, sz;  ///< the shear and the scale

    explicit RayFrame(const Ray<T>& ray) : origin(ray.origin) {
        const Axis axes[3] = {&Vec3<T>::x, &Vec3<T>::y, &Vec3<T>::z};
        const Vec3<T>& d = ray.direction;
        const T ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
        const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
        x = axes[(kz + 1) % 3], y = axes[(kz + 2) % 3], z = axes[kz];
        if (d.*z < T(0)) std::swap(x, y);  // keeps the winding (the paper's; no side is culled here)
        sx = d.*x / d.*z, sy = d.*y / d.*z, sz = T(1) / d.*z;
    }
    Vec3<T> apply(const Vec3<T>& p) const {
        const Vec3<T> a = p - origin;
        return {a.*x - sx * a.*z, a.*y - sy * a.*z, sz * a.*z};
    }
};

/// Which side of the edge p → q (ray frame) the ray passes, as twice the signed area of the ray's
/// point and the edge: the neighbour across the edge runs q → p and gets exactly the negative, so
/// no ray passes outside both. A float value of exactly 0 is worked out again in double (a float
/// product is exact there), as the paper does.
template <class T>
T edge_side(const Vec3<T>& p, const Vec3<T>& q) {
    const T e = p.x * q.y - p.y * q.x;
    if constexpr (std::is_same_v<T, float>)
        if (e == 0.f) return static_cast<float>(double(p.x) * double(q.y) - double(p.y) * double(q.x));
    return e;
}

/// Ray (as a RayFrame) against one triangle from either side, watertight: two triangles sharing
/// an edge or a corner leave no gap between them for rounding to let a ray through (an edge or
/// corner hit counts for both). The distance, if it hits within [0, max_distance].
template <class T>
std::optional<T> ray_triangle(const RayFrame<T>& f, T max_distance, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
    const Vec3<T> p = f.apply(a), q = f.apply(b), r = f.apply(c);
    const T u = edge_side(r, q), v = edge_side(p, r), w = edge_side(q, p);  // the weights of a, b, c
    if ((u < T(0) || v < T(0) || w < T(0)) && (u > T(0) || v > T(0) || w > T(0))) return std::nullopt;
    const T det = u + v + w;
    if (det == T(0)) return std::nullopt;  // seen edge-on
    const T t = (u * p.z + v * q.z + w * r.z) / det;
    if (!(t >= T(0) && t <= max_distance)) return std::nullopt;
    return t;
}

/// Ray against one triangle from either side: the distance, if it hits within [0, max_distance].
template <class T>
std::optional<T> ray_triangle(const Ray<T>& ray, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
    return ray_triangle(RayFrame<T>(ray), ray.max_distance, a, b, c);
}

/// A ray prepared for the hierarchy walk: slab tests by its reciprocal direction against node
/// boxes grown by `pad`, 32 ε of the farthest the mesh's box reaches from the ray's origin along
/// an axis. That is more than the slab test's rounding and ray_triangle's (each a few ε of that
/// distance), so the walk never culls a triangle the test would hit (an edge-grazing ray missed
/// the unpadded box of its triangle).
template <class T>
struct RaySlabs {
    Vec3<T> origin, inverse;
    T pad;

    RaySlabs(const Ray<T>& ray, const Aabb<T>& all) : origin(ray.origin) {
        const Vec3<T>& d = ray.direction;
        // + 0 turns −0 into +0: along an axis the ray is square to, +∞ (see slab).
        inverse = {T(1) / (d.x + T(0)), T(1) / (d.y + T(0)), T(1) / (d.z + T(0))};
        pad = T(32) * ScalarTraits<T>::epsilon * max_component(max(abs(all.min - origin), abs(all.max - origin)));
    }
    /// Whether the ray meets the grown box within [0, max_distance].
    bool meets(const Aabb<T>& box, T max_distance) const {
        T enter = T(0), exit = max_distance;
        return slab(box.min.x, box.max.x, origin.x, inverse.x, enter, exit) &&
               slab(box.min.y, box.max.y, origin.y, inverse.y, enter, exit) &&
               slab(box.min.z, box.max.z, origin.z, inverse.z, enter, exit);
    }
    /// Narrows [enter, exit] to one axis's slab; false once it is empty. A ray square to the axis
    /// (inv = +∞) gives t0 = −∞ and t1 = +∞ inside the slab, both +∞ or both −∞ outside, and
    /// 0 × ∞ = NaN on a face, which std::max and std::min with it second leave out.
    bool slab(T lo, T hi, T o, T inv, T& enter, T& exit) const {
        T t0 = (lo - pad - o) * inv, t1 = (hi + pad - o) * inv;
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        exit = std::min(exit, t1);
        return enter <= exit;
    }
};

}  // namespace detail

template <class T>
std::optional<std::pair<RayHit<T>, std::uint32_t>> TriangleMesh<T>::raycast(const Ray<T>& ray) const {
    Ray<T> r = detail::checked_ray(ray, "TriangleMesh::raycast");
    const T ray_reach = r.max_distance;       // r's shrinks to the nearest hit so far
    if (nodes_.empty()) return std::nullopt;  // moved from: no triangles
    const detail::RayFrame<T> frame(r);
    const detail::RaySlabs<T> slabs(r, nodes_[0].box);
    std::optional<std::pair<RayHit<T>, std::uint32_t>> best;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const std::uint32_t at = stack[--top];
        const detail::BvhNode<T>& node = nodes_[at];
        if (!slabs.meets(node.box, r.max_distance)) continue;
        if (node.count > 0) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                const MeshTriangle<T> t = triangle(k);
                if (const std::optional<T> d = detail::ray_triangle(frame, r.max_distance, t.v[0], t.v[1], t.v[2])) {
                    r.max_distance = *d;  // only nearer hits from now on
                    RayHit<T> hit;
                    hit.distance = *d;
                    hit.fraction = detail::ray_fraction(*d, ray_reach);
                    hit.point = r.origin + r.direction * *d;
                    hit.normal = dot(t.normal, r.direction) <= T(0) ? t.normal : -t.normal;
                    best = std::make_pair(hit, source_[k]);
                }
            }
            continue;
        }
        stack[top++] = node.first;
        stack[top++] = at + 1;
    }
    return best;
}

namespace f32 {
using TriangleMesh = xeno::TriangleMesh<float>;
}
namespace f64 {
using TriangleMesh = xeno::TriangleMesh<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// HeightField<T>: terrain as a grid of heights, without storing triangles (docs/meshes.md).
// Samples are `columns` along x by `rows` along z, `spacing` metres apart, centred on the local
// origin in x and z; the height (local y) of sample (i, j) is heights[j * columns + i]. Each cell
// (i, j), between samples i … i + 1 and j … j + 1, is two triangles split along the diagonal from
// (i, j) to (i + 1, j + 1), both facing +y; a cell can be a hole (no triangles). Triangle index
// 2 (j (columns − 1) + i) + s, s = 0 for (p00, p01, p11) and 1 for (p00, p11, p10). Active edges
// are worked out per query from the neighbouring samples, by the same rule as a TriangleMesh.
#pragma once

#include "../collide/raycast.hpp"
#include "../error.hpp"
#include "triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace xeno {

/// A grid of heights (see the file comment).
template <class T>
class HeightField {
public:
    using scalar_type = T;

    /// columns, rows >= 2, fewer than 2^31 cells; heights.size() == columns × rows, finite and
    /// within the size range; spacing finite and within [min_size, max_size]; holes empty or one
    /// flag per cell ((columns − 1) × (rows − 1), row-major, non-zero = hole); no cell (but a
    /// hole) so steep for its spacing that a triangle of it has no normal. InvalidArgument
    /// otherwise.
    HeightField(std::uint32_t columns, std::uint32_t rows, std::vector<T> heights, T spacing,
                std::vector<std::uint8_t> holes = {});

    std::uint32_t columns() const { return columns_; }
    /// True only for a moved-from field: a constructed one has its samples.
    bool empty() const { return heights_.empty(); }
    std::uint32_t rows() const { return rows_; }
    T spacing() const { return spacing_; }
    std::size_t size() const { return 2 * std::size_t(columns_ - 1) * (rows_ - 1); }
    Aabb<T> local_bounds() const { return bounds_; }
    T height(std::uint32_t i, std::uint32_t j) const { return heights_[std::size_t(j) * columns_ + i]; }
    bool hole(std::uint32_t i, std::uint32_t j) const {
        return !holes_.empty() && holes_[std::size_t(j) * (columns_ - 1) + i] != 0;
    }
    /// Local position of sample (i, j).
    Vec3<T> sample(std::uint32_t i, std::uint32_t j) const {
        return {origin_x_ + spacing_ * static_cast<T>(i), height(i, j), origin_z_ + spacing_ * static_cast<T>(j)};
    }
    /// Triangle k (see the file comment), with its active edges.
    MeshTriangle<T> triangle(std::uint32_t k) const;
    /// Calls f(k, triangle) for each triangle (not in a hole) whose box overlaps `box` (local)
    /// and that keep(triangle) accepts; keep sees the corners and normal only, so a caller's
    /// cheap rejection skips working out the edges.
    template <class F, class Keep = detail::KeepAll>
    void for_each_triangle(const Aabb<T>& box, F&& f, Keep keep = {}) const;
    /// The nearest hit of a ray (local frame) on the surface from either side, with the triangle.
    /// The ray is checked as raycast(shape, pose, ray) checks it (InvalidArgument).
    std::optional<std::pair<RayHit<T>, std::uint32_t>> raycast(const Ray<T>& ray) const;
    std::size_t memory_bytes() const { return heights_.capacity() * sizeof(T) + holes_.capacity(); }

private:
    /// Whether sample (i, j) exists and the neighbour triangle through it is there: the cell
    /// (ci, cj) it belongs to is inside the grid and not a hole.
    bool cell_present(std::int64_t ci, std::int64_t cj) const {
        return ci >= 0 && cj >= 0 && ci < std::int64_t(columns_) - 1 && cj < std::int64_t(rows_) - 1 &&
               !hole(static_cast<std::uint32_t>(ci), static_cast<std::uint32_t>(cj));
    }
    MeshTriangle<T> corners(std::uint32_t k) const;  ///< triangle k without its edges' data
    void require_normals(const char* where) const;   ///< InvalidArgument for a cell with a triangle of no normal
    void add_edges(std::uint32_t k, MeshTriangle<T>& t) const;
    /// Cell range [lo, hi] (inclusive) along one axis covering [a, b] in local coordinates.
    bool cell_range(T a, T b, T origin, std::uint32_t samples, std::uint32_t& lo, std::uint32_t& hi) const;

    std::uint32_t columns_, rows_;
    std::vector<T> heights_;
    T spacing_;
    std::vector<std::uint8_t> holes_;
    T origin_x_, origin_z_;
    Aabb<T> bounds_;
};

template <class T>
HeightField<T>::HeightField(std::uint32_t columns, std::uint32_t rows, std::vector<T> heights, T spacing,
                            std::vector<std::uint8_t> holes)
    : columns_(columns), rows_(rows), heights_(std::move(heights)), spacing_(spacing), holes_(std::move(holes)) {
    const char* where = "HeightField";
    if (columns_ < 2 || rows_ < 2)
        detail::report_invalid(where, "needs at least 2 columns and 2 rows of samples; the smaller count",
                               static_cast<double>(std::min(columns_, rows_)));
    if (heights_.size() != std::size_t(columns_) * rows_)
        detail::report_invalid(where, "needs columns × rows heights; heights given", static_cast<double>(heights_.size()));
    if (!holes_.empty() && holes_.size() != std::size_t(columns_ - 1) * (rows_ - 1))
        detail::report_invalid(where, "needs no holes or one flag per cell, (columns − 1) × (rows − 1); flags given",
                               static_cast<double>(holes_.size()));
    detail::require_size(spacing_, where, "spacing");
    for (std::size_t k = 0; k < heights_.size(); ++k)  // (the name is built for a bad height only: 0.3 s for 4097²)
        if (!(std::abs(heights_[k]) <= ScalarTraits<T>::max_size))
            detail::require_at_most(heights_[k], ScalarTraits<T>::max_size, where, ("height " + std::to_string(k)).c_str(), " m");
    if (std::size_t(columns_ - 1) * (rows_ - 1) > std::size_t(std::numeric_limits<std::uint32_t>::max() / 2))
        detail::report_invalid(where, "needs fewer than 2^31 cells (two triangles each, numbered in 32 bits); cells",
                               static_cast<double>(std::size_t(columns_ - 1) * (rows_ - 1)));
    const T width = spacing_ * static_cast<T>(columns_ - 1), depth = spacing_ * static_cast<T>(rows_ - 1);
    if (!(width <= ScalarTraits<T>::max_size && depth <= ScalarTraits<T>::max_size))
        detail::report_invalid(where, "extent (spacing × cells) must be within the size range; metres",
                               static_cast<double>(std::max(width, depth)));
    origin_x_ = -T(0.5) * width;
    origin_z_ = -T(0.5) * depth;
    const auto [low, high] = std::minmax_element(heights_.begin(), heights_.end());
    bounds_ = {{origin_x_, *low, origin_z_}, {origin_x_ + width, *high, origin_z_ + depth}};
    require_normals(where);
}

// A cell whose heights step so far over its spacing that a triangle of it has no normal
// (detail::triangle_normal: |n| > 1e-6 × the longest edge²) would be a wall with no side: rays
// hit it with a zero normal and bodies passed through it. A triangle mesh drops such triangles; a
// grid cannot, so it is rejected. Both triangles of a cell have |n| ≥ dx dz (the cell's widths as
// the samples' coordinates round) and edges no longer than √(dx² + dz² + D²), D the cell's
// height span; a cell whose span is within that bound, with room for rounding, is sound without
// measuring its triangles (every cell but a cliff a thousand spacings high), the rest are
// measured.
template <class T>
void HeightField<T>::require_normals(const char* where) const {
    T narrow_x = ScalarTraits<T>::infinity, wide_x = T(0), narrow_z = ScalarTraits<T>::infinity, wide_z = T(0);
    // Past about 2^23 samples along an axis in float, spacing × i rounds two samples onto one
    // coordinate: a cell of no width.
    for (std::uint32_t i = 0; i + 1 < columns_; ++i) {
        const T dx = sample(i + 1, 0).x - sample(i, 0).x;
        if (!(dx > T(0)))
            detail::report_invalid(where, "has two columns at one x (too many for T at this spacing); column",
                                   static_cast<double>(i));
        narrow_x = std::min(narrow_x, dx), wide_x = std::max(wide_x, dx);
    }
    for (std::uint32_t j = 0; j + 1 < rows_; ++j) {
        const T dz = sample(0, j + 1).z - sample(0, j).z;
        if (!(dz > T(0)))
            detail::report_invalid(where, "has two rows at one z (too many for T at this spacing); row", static_cast<double>(j));
        narrow_z = std::min(narrow_z, dz), wide_z = std::max(wide_z, dz);
    }
    const T room = narrow_x * narrow_z * T(0.999) / T(1e-6) - (wide_x * wide_x + wide_z * wide_z) * T(1.001);  // D² allowed
    for (std::uint32_t j = 0; j + 1 < rows_; ++j)
        for (std::uint32_t i = 0; i + 1 < columns_; ++i) {
            if (hole(i, j)) continue;
            const T a = height(i, j), b = height(i + 1, j), c = height(i, j + 1), d = height(i + 1, j + 1);
            const T span = std::max({a, b, c, d}) - std::min({a, b, c, d});
            if (span * span < room) continue;
            const std::uint32_t k = 2 * (j * (columns_ - 1) + i);
            if (length_squared(corners(k).normal) == T(0) || length_squared(corners(k + 1).normal) == T(0))
                detail::report_invalid(where, "has a cell too steep for its spacing (a triangle with no normal); cell",
                                       static_cast<double>(k / 2));
        }
}

template <class T>
MeshTriangle<T> HeightField<T>::corners(std::uint32_t k) const {
    const std::uint32_t cell = k / 2, i = cell % (columns_ - 1), j = cell / (columns_ - 1);
    MeshTriangle<T> t;
    t.v[0] = sample(i, j);
    t.v[1] = k % 2 == 0 ? sample(i, j + 1) : sample(i + 1, j + 1);
    t.v[2] = k % 2 == 0 ? sample(i + 1, j + 1) : sample(i + 1, j);
    t.normal = detail::triangle_normal(t.v[0], t.v[1], t.v[2]);
    return t;
}

template <class T>
void HeightField<T>::add_edges(std::uint32_t k, MeshTriangle<T>& t) const {
    const std::uint32_t cell = k / 2, s = k % 2;
    const std::uint32_t i = cell % (columns_ - 1), j = cell / (columns_ - 1);
    // Per edge: the neighbour's cell and its third corner (the sample across the edge).
    const std::int64_t ci = i, cj = j;
    auto across = [&](std::int64_t ni, std::int64_t nj, std::int64_t wi, std::int64_t wj) {
        return cell_present(ni, nj)
                   ? std::optional<Vec3<T>>(sample(static_cast<std::uint32_t>(wi), static_cast<std::uint32_t>(wj)))
                   : std::nullopt;
    };
    std::optional<Vec3<T>> w[3];
    if (s == 0) {                                   // p00, p01, p11
        w[0] = across(ci - 1, cj, ci - 1, cj);      // p00 → p01: the cell to the left, its (i − 1, j)
        w[1] = across(ci, cj + 1, ci + 1, cj + 2);  // p01 → p11: the cell above, its (i + 1, j + 2)
        w[2] = across(ci, cj, ci + 1, cj);          // p11 → p00: the other half, p10
    } else {                                        // p00, p11, p10
        w[0] = across(ci, cj, ci, cj + 1);          // p00 → p11: the other half, p01
        w[1] = across(ci + 1, cj, ci + 2, cj + 1);  // p11 → p10: the cell to the right, its (i + 2, j + 1)
        w[2] = across(ci, cj - 1, ci, cj - 1);      // p10 → p00: the cell below, its (i, j − 1)
    }
    t.active_edges = 0;
    for (int e = 0; e < 3; ++e) {
        const Vec3<T>& p = t.v[e];
        const Vec3<T>& q = t.v[(e + 1) % 3];
        if (w[e]) t.fold_cos[e] = dot(t.normal, detail::triangle_normal(q, p, *w[e]));  // the neighbour runs q → p
        if (!w[e] || detail::edge_is_active(t.normal, p, q, *w[e]))
            t.active_edges = static_cast<std::uint8_t>(t.active_edges | (1u << e));
    }
}

template <class T>
MeshTriangle<T> HeightField<T>::triangle(std::uint32_t k) const {
    MeshTriangle<T> t = corners(k);
    add_edges(k, t);
    return t;
}

// The last cell is clamped in integers: a count of cells converted to T may round up past it
// (in float, 2^24 + 3 rows became 2^24 + 4 cells, and a box at the far edge read heights past the
// end).
template <class T>
bool HeightField<T>::cell_range(T a, T b, T origin, std::uint32_t samples, std::uint32_t& lo, std::uint32_t& hi) const {
    const T first = std::floor((a - origin) / spacing_), last = std::floor((b - origin) / spacing_);
    const std::uint32_t cells = samples - 1;
    if (!(last >= T(0) && first < static_cast<T>(cells))) return false;
    // first < cells ≤ 2^32 (as T): a whole number the cast holds.
    lo = std::min(static_cast<std::uint32_t>(std::max(first, T(0))), cells - 1);
    hi = last < static_cast<T>(cells) ? std::min(static_cast<std::uint32_t>(last), cells - 1) : cells - 1;
    return true;
}

template <class T>
template <class F, class Keep>
void HeightField<T>::for_each_triangle(const Aabb<T>& box, F&& f, Keep keep) const {
    if (empty() || !overlaps(box, bounds_)) return;  // moved from: no triangles
    std::uint32_t i0, i1, j0, j1;
    if (!cell_range(box.min.x, box.max.x, origin_x_, columns_, i0, i1) ||
        !cell_range(box.min.z, box.max.z, origin_z_, rows_, j0, j1))
        return;
    for (std::uint32_t j = j0; j <= j1; ++j)
        for (std::uint32_t i = i0; i <= i1; ++i) {
            if (hole(i, j)) continue;
            const T low = std::min({height(i, j), height(i + 1, j), height(i, j + 1), height(i + 1, j + 1)});
            const T high = std::max({height(i, j), height(i + 1, j), height(i, j + 1), height(i + 1, j + 1)});
            if (low > box.max.y || high < box.min.y) continue;
            for (std::uint32_t k = 2 * (j * (columns_ - 1) + i), last = k + 1; k <= last; ++k) {
                MeshTriangle<T> t = corners(k);
                if (!keep(t)) continue;  // before the neighbours' normals: the costly part
                add_edges(k, t);
                f(k, t);
            }
        }
}

// Cells along the ray's path would be the fast way (a 2D DDA); the cells under the ray's box are
// simpler and exact, and rays in games are short or vertical. A long slanted ray over a large
// field visits many cells: bounded by the cells under its box.
//
// The boxes are grown by a thousandth of a spacing, and by 64 ε of the ray's reach from the
// origin (the rounding of the path's ends), so a ray down a grid line or through a sample takes
// in the cells on both sides: detail::ray_triangle is watertight only among the triangles it sees.
template <class T>
std::optional<std::pair<RayHit<T>, std::uint32_t>> HeightField<T>::raycast(const Ray<T>& ray) const {
    Ray<T> r = detail::checked_ray(ray, "HeightField::raycast");
    const T ray_reach = r.max_distance;  // r's shrinks to the nearest hit so far
    if (empty()) return std::nullopt;    // moved from: no triangles
    const T extent = length(bounds_.max - bounds_.min) + spacing_;
    const T place = std::max({std::abs(r.origin.x), std::abs(r.origin.y), std::abs(r.origin.z)});
    const T pad = spacing_ * T(1e-3) + T(64) * ScalarTraits<T>::epsilon * (place + extent);
    const std::optional<T> enter = detail::raycast_box(bounds_.expanded(pad), r);
    if (!enter) return std::nullopt;
    // Clip the ray to the field's box so its own box is finite.
    Aabb<T> path;
    path.merge(r.origin + r.direction * *enter);
    const T reach = std::min(r.max_distance, *enter + extent);
    path.merge(r.origin + r.direction * reach);
    const detail::RayFrame<T> frame(r);
    std::optional<std::pair<RayHit<T>, std::uint32_t>> best;
    path = path.expanded(pad + T(64) * ScalarTraits<T>::epsilon * *enter);
    for_each_triangle(path, [&](std::uint32_t k, const MeshTriangle<T>& t) {
        if (const std::optional<T> d = detail::ray_triangle(frame, r.max_distance, t.v[0], t.v[1], t.v[2])) {
            r.max_distance = *d;
            RayHit<T> hit;
            hit.distance = *d;
            hit.fraction = detail::ray_fraction(*d, ray_reach);
            hit.point = r.origin + r.direction * *d;
            hit.normal = dot(t.normal, r.direction) <= T(0) ? t.normal : -t.normal;
            best = std::make_pair(hit, k);
        }
    });
    return best;
}

namespace f32 {
using HeightField = xeno::HeightField<float>;
}
namespace f64 {
using HeightField = xeno::HeightField<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The lever of twist friction: how far from its centre a contact patch carries its load.
//
// A body spinning about the normal of a flat contact is braked by the friction torque
// µ ∫ p(x) |x − c| dA. With a uniform pressure p = N / A over the patch that is µ N ℓ, with ℓ the
// mean distance of the patch's area from c. The manifold only holds the patch's corners (at most
// four), and their mean distance is not ℓ: for a square it is √2 a against
// (√2 + ln(1 + √2)) a / 3 = 0.765 a, 1.85 times too much, so a box spun on the floor stopped in
// 0.56 of the time a continuum model (and the textbook) gives. Here the corners span a polygon
// and ℓ is integrated over it exactly (docs/solver-design.md, "Central friction"):
//   1 point     0 (a point resists no twist);
//   2 points    a line of uniform load: a quarter of their distance (the mean of |x| on [−L, L]
//               is L/2);
//   3–4 points  the polygon's area mean of |x − c|, triangle by triangle from c.
// A round face (a cylinder's cap, a cone's base) is a disc whose polygon of four kept points is a
// square inside it; World::twist_lever uses the disc's 2r/3 when the patch is the whole face.
#pragma once

#include "../math/vec3.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>

namespace xeno {
namespace detail {

/// ∫ |x| dA over the triangle (0, p, q) of the plane (2-D coordinates; p, q counter-clockwise
/// about 0; rp = |p|, rq = |q|). In polar coordinates about 0, with d the distance from 0 to the
/// line pq and s the coordinate along it from the foot of the perpendicular: ∫ ρ³/3 dφ with
/// ρ = d sec φ, which integrates to d/6 [r s] + d³/6 [ln(r + s)] between p and q. r + s is taken
/// as d² / (r − s) for s < 0, where it would lose its digits.
template <class T>
T triangle_first_moment(T px, T py, T rp, T qx, T qy, T rq) {
    const T ex = qx - px, ey = qy - py;
    const T len = std::sqrt(ex * ex + ey * ey);
    if (!(len > T(0))) return T(0);
    const T ux = ex / len, uy = ey / len;
    const T d = px * uy - py * ux;  // ≥ 0 for a counter-clockwise triangle
    if (!(d > T(0))) return T(0);
    const T sp = px * ux + py * uy, sq = qx * ux + qy * uy;
    const auto r_plus_s = [d](T r, T s) { return s >= T(0) ? r + s : d * d / (r - s); };
    return d / T(6) * (rq * sq - rp * sp) + d * d * d / T(6) * std::log(r_plus_s(rq, sq) / r_plus_s(rp, sp));
}

/// m: the mean distance from the patch centre of a uniformly loaded contact patch whose corners
/// are (u[i], v[i]), i < count ≤ 4, in plane coordinates about that centre (the mean of the
/// corners, so it lies inside their hull).
template <class T>
T patch_mean_radius(std::array<T, 4> u, std::array<T, 4> v, int count) {
    if (count < 2) return T(0);
    if (count == 2) return std::sqrt((u[1] - u[0]) * (u[1] - u[0]) + (v[1] - v[0]) * (v[1] - v[0])) / T(4);
    const std::size_t n = static_cast<std::size_t>(count);
    // Counter-clockwise about the centre: by half-plane (v > 0, or v = 0 and u > 0, first), then
    // by the sign of the cross product. No angles, so no libm differences in the order.
    std::array<std::size_t, 4> order{0, 1, 2, 3};
    const auto upper = [&](std::size_t i) { return v[i] > T(0) || (v[i] == T(0) && u[i] > T(0)); };
    const auto before = [&](std::size_t i, std::size_t j) {
        if (upper(i) != upper(j)) return upper(i);
        return u[i] * v[j] - v[i] * u[j] > T(0);
    };
    for (std::size_t k = 1; k < n; ++k)  // insertion sort: at most four corners
        for (std::size_t m = k; m > 0 && before(order[m], order[m - 1]); --m) std::swap(order[m], order[m - 1]);
    std::array<T, 4> r{};
    T span_sq = T(0);
    for (std::size_t i = 0; i < n; ++i) {
        r[i] = std::sqrt(u[i] * u[i] + v[i] * v[i]);
        for (std::size_t j = 0; j < i; ++j)
            span_sq = std::max(span_sq, (u[i] - u[j]) * (u[i] - u[j]) + (v[i] - v[j]) * (v[i] - v[j]));
    }
    T area = T(0), moment = T(0);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = order[k], j = order[(k + 1) % n];
        area += (u[i] * v[j] - v[i] * u[j]) / T(2);
        moment += triangle_first_moment(u[i], v[i], r[i], u[j], v[j], r[j]);
    }
    // Corners in a line (an edge resting on a face reported as three or four points): a line.
    if (!(area > T(1e-3) * span_sq)) return std::sqrt(span_sq) / T(4);
    return moment / area;
}

/// The twist lever of the patch whose corners are p[i], i < count ≤ 4, in any frame: the plane
/// is the corners' own (the normal of their largest triangle), so the lever depends on the
/// corners alone and can be kept while they stay (World::twist_lever, Contact::twist_lever_key).
template <class T>
T patch_twist_lever(const std::array<Vec3<T>, 4>& p, int count) {
    if (count < 2) return T(0);
    if (count == 2) return length(p[1] - p[0]) / T(4);
    Vec3<T> centre{};
    for (int i = 0; i < count; ++i) centre += p[static_cast<std::size_t>(i)];
    centre /= static_cast<T>(count);
    Vec3<T> normal = cross(p[1] - p[0], p[2] - p[0]);
    if (count == 4) {
        for (const Vec3<T>& other :
             {cross(p[2] - p[0], p[3] - p[0]), cross(p[1] - p[0], p[3] - p[0]), cross(p[2] - p[1], p[3] - p[1])})
            if (length_squared(other) > length_squared(normal)) normal = other;
    }
    T span_sq = T(0);
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < i; ++j)
            span_sq = std::max(span_sq, length_squared(p[static_cast<std::size_t>(i)] - p[static_cast<std::size_t>(j)]));
    // Corners in a line (an edge on a face reported as three or four points): a line.
    if (!(length(normal) > T(2e-3) * span_sq)) return std::sqrt(span_sq) / T(4);
    const Vec3<T> n = normalized(normal), t1 = any_perpendicular(n), t2 = cross(n, t1);
    std::array<T, 4> u{}, v{};
    for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
        u[i] = dot(p[i] - centre, t1);
        v[i] = dot(p[i] - centre, t2);
    }
    // The mean radius lies within the span. Three corners a few ulps apart (a mesh manifold's
    // points at one place) passed the line test above by round-off and gave −∞, and the step's
    // solve, overflowed, was discarded every step: the body froze where it was.
    const T span = std::sqrt(span_sq), lever = patch_mean_radius(u, v, count);
    return lever >= T(0) && lever <= span ? lever : span / T(4);
}

/// A 64-bit digest of the corners' bits and count, never 0 (0: no lever computed yet). Equal
/// corners give equal keys, so a lever kept under its key is the one they would give again.
template <class T>
std::uint64_t patch_key(const std::array<Vec3<T>, 4>& p, int count) {
    std::uint64_t h = 0x9e3779b97f4a7c15ull ^ static_cast<std::uint64_t>(count);
    for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i)
        for (int k = 0; k < 3; ++k) {
            const T x = p[i][k];
            std::uint64_t bits = 0;
            std::memcpy(&bits, &x, sizeof x);
            h = (h ^ bits) * 0x100000001b3ull;
            h ^= h >> 29;
        }
    return h | 1u;
}

}  // namespace detail
}  // namespace xeno

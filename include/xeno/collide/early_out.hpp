// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// EarlyOut<T>: MPR's first test, the one that rejects most pairs, run for W pairs at once in SIMD
// lanes (the thesis's extension 4.1 c; docs/collision.md, "The early-out in lanes").
//
// MPR's first support point is taken along the centre line d = c_B − c_A, and the pair is a miss
// when the support plane there separates the origin: |d|² ≥ h_A(d) + h_B(−d), h being a shape's
// support distance from its centre along d (scaled by |d|). This file asks the same question of a
// bound of each shape, a box (centre, three half-axes) swept by a ball of radius `round`, kept in
// world coordinates once per step:
//     h(d) = |u0·d| + |u1·d| + |u2·d| + round·|d|      (u_k = half extent k × world axis k)
// That is exact for boxes, spheres and capsules, an upper bound for cylinders (a capsule around
// them), cones and hulls (their local box). A pair is reported apart only when
//     |d|² (1 − 2⁻⁷) > (h_A + h_B + margin·|d|) (1 + 2⁻⁷),
// a gap of about 1.6 % of the centre distance beyond the margin, so rounding in either computation (and
// a quaternion off unit length by the 1e-3 the queries accept) can never turn a pair MPR or the
// closed-form tests would find touching into "apart": skipping the rejected pairs changes no
// result (tests/collide/early_out_test.cpp). The rest go on to the narrow phase one by one.
//
// Why world coordinates: the per-pair relative rotation MPR needs (minkowski.hpp) is what made a
// rejected pair cost 50–70 ns; here each body's axes are computed once, and the relative rotation
// only for the pairs that survive.
//
// Same bits in every width: each lane runs the same IEEE operations in the same order (wide.hpp),
// so a pair's answer does not depend on W, on the lane it landed in or on its neighbours. A body
// without a bound (a mesh, a compound, a slot not set) holds NaN, which no comparison passes: its
// pairs are never rejected.
#pragma once

#include "../math/wide.hpp"
#include "../shape/shape.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace xeno {

/// A convex shape's bound for the early-out, in its local frame: the box centre ± half swept by a
/// ball of radius round (metres).
template <class T>
struct RoundedBox {
    Vec3<T> centre{};
    Vec3<T> half{};
    T round{};
};

/// The tightest rounded box of each convex shape kind (see the file comment).
template <class T>
RoundedBox<T> rounded_box(const Shape<T>& shape) {
    return std::visit(
        [](const auto& s) -> RoundedBox<T> {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, Sphere<T>>) {
                return {Vec3<T>::zero(), Vec3<T>::zero(), s.radius()};
            } else if constexpr (std::is_same_v<S, Box<T>>) {
                return {Vec3<T>::zero(), s.half_extents(), T(0)};
            } else if constexpr (std::is_same_v<S, Capsule<T>> || std::is_same_v<S, Cylinder<T>>) {
                return {Vec3<T>::zero(), {T(0), s.half_height(), T(0)}, s.radius()};
            } else {  // cones and hulls: the local box
                const Aabb<T> box = s.local_bounds();
                return {box.center(), box.half_extents(), T(0)};
            }
        },
        shape);
}

/// Every body's rounded box in world coordinates, one record of 16 numbers per body (centre,
/// three half-axes, round, padding: a cache line in float), transposed into lanes W records at a
/// time: W consecutive bodies (brute force) or the bodies of any W pairs (a pair list). Records
/// rather than one array per number, because a pair list reaches its second bodies at random: a
/// record is one or two cache lines, thirteen arrays would be thirteen misses.
template <class T>
class EarlyOut {
public:
    /// Lanes per test on this target (wide.hpp): 4 / 8 floats, 2 / 4 doubles, 1 without SIMD.
    static constexpr int width = detail::native_width<T>();

    /// n bodies: the first ones keep their bounds, new ones have none (their pairs are never
    /// rejected until set).
    void resize(std::size_t n) {
        records_.resize(n * kRecord, std::numeric_limits<T>::quiet_NaN());
        n_ = n;
    }
    std::size_t size() const { return n_; }

    /// Body i is `shape` placed by `pose` (rotation matrix computed here, once per body).
    void set(std::size_t i, const Shape<T>& shape, const Transform<T>& pose) { set(i, rounded_box(shape), pose); }
    void set(std::size_t i, const RoundedBox<T>& box, const Transform<T>& pose) {
        const Mat3<T> r = to_matrix(pose.orientation);
        const Vec3<T> c = pose.apply(box.centre);
        const Vec3<T> u0 = r.column(0) * box.half.x, u1 = r.column(1) * box.half.y, u2 = r.column(2) * box.half.z;
        const T values[kRecord] = {c.x,  c.y,  c.z,  u0.x, u0.y,      u0.z, u1.x, u1.y,
                                   u1.z, u2.x, u2.y, u2.z, box.round, T(0), T(0), T(0)};
        std::copy(values, values + kRecord, record(i));
    }
    /// Body i has no bound: every pair with it goes on to the narrow phase.
    void clear(std::size_t i) { std::fill(record(i), record(i) + kRecord, std::numeric_limits<T>::quiet_NaN()); }

    /// Bit l set when bodies a and b + l are apart by more than margin (l < W; b + W − 1 < size()).
    template <int W>
    unsigned apart_run(std::size_t a, std::size_t b, T margin) const {
        using V = detail::Wide<T, W>;
        const T* rb[W];
        for (int l = 0; l < W; ++l) rb[l] = record(b + static_cast<std::size_t>(l));
        V va[kRecord], vb[kRecord];
        for (int k = 0; k < kRecord; ++k) va[k] = V::splat(record(a)[k]);
        detail::load_transposed(rb, kRecord, vb);
        return bits(apart_lanes(va, vb, V::splat(margin)));
    }
    /// Bit l set when bodies a[l] and b[l] are apart by more than margin[l].
    template <int W>
    unsigned apart_pairs(const std::uint32_t (&a)[W], const std::uint32_t (&b)[W], const T (&margin)[W]) const {
        using V = detail::Wide<T, W>;
        const T* ra[W];
        const T* rb[W];
        for (int l = 0; l < W; ++l) ra[l] = record(a[l]), rb[l] = record(b[l]);
        V va[kRecord], vb[kRecord];
        detail::load_transposed(ra, kRecord, va);
        detail::load_transposed(rb, kRecord, vb);
        return bits(apart_lanes(va, vb, V::loadu(margin)));
    }
    /// Asks the cache for body i's record ahead of a test (a pair list reaches its bodies at
    /// random: prefetching a few pairs ahead keeps several misses in flight).
    void prefetch(std::size_t i) const {
#if defined(__GNUC__) || defined(__clang__)
        const char* p = reinterpret_cast<const char*>(record(i));
        __builtin_prefetch(p);
        if (sizeof(T) * kRecord > 64) __builtin_prefetch(p + 64);
#else
        (void)i;
#endif
    }
    /// One pair, through the same operations (a lane of width 1).
    bool apart(std::size_t a, std::size_t b, T margin) const { return apart_run<1>(a, b, margin) != 0; }

private:
    static constexpr int kRows = 13;    // centre (3), three half-axes (9), round
    static constexpr int kRecord = 16;  // padded: whole 4 × 4 transposes
    T* record(std::size_t i) { return records_.data() + i * kRecord; }
    const T* record(std::size_t i) const { return records_.data() + i * kRecord; }

    // The test of the file comment, lane by lane.
    template <class V>
    XENO_WIDE_INLINE static typename V::Mask apart_lanes(const V (&a)[kRecord], const V (&b)[kRecord], V margin) {
        const detail::WideVec3<V> d{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const V dd = dot(d, d);
        const V reach = extent(a, d) + extent(b, d) + (a[12] + b[12] + margin) * sqrt(dd);
        return dd * V::splat(T(1) - kSlack) > reach * V::splat(T(1) + kSlack);
    }
    template <class V>
    XENO_WIDE_INLINE static V extent(const V (&r)[kRecord], const detail::WideVec3<V>& d) {
        return abs(r[3] * d.x + r[4] * d.y + r[5] * d.z) + abs(r[6] * d.x + r[7] * d.y + r[8] * d.z) +
               abs(r[9] * d.x + r[10] * d.y + r[11] * d.z);
    }
    static constexpr T kSlack = T(1) / T(128);

    std::size_t n_ = 0;
    std::vector<T> records_;
};

namespace f32 {
using EarlyOut = xeno::EarlyOut<float>;
using RoundedBox = xeno::RoundedBox<float>;
}  // namespace f32
namespace f64 {
using EarlyOut = xeno::EarlyOut<double>;
using RoundedBox = xeno::RoundedBox<double>;
}  // namespace f64

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The Minkowski difference D = A ⊖ B = {a − b} of two placed shapes, evaluated in A's local frame
// (docs/collision.md, "Working in A's frame": the relative rotation and offset are computed once
// per pair, so each support evaluation costs one matrix product for B and none for A, and the
// numbers stay near the origin even when both bodies are far from it). Each support point keeps its
// two witnesses, the points of A and of B it came from, so the narrow phase can report a point on
// each body. With D = A ⊖ B the portal normal at the end of MPR points from A to B
// (docs/conventions.md, "Contacts").
#pragma once

#include "../math/transform.hpp"
#include "../shape/convex_polyhedron.hpp"
#include "shape_ref.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>

namespace xeno {

/// A point of D = A ⊖ B with its witness on A, all in A's local frame. B's witness is a − v; it
/// is not stored, so the portal vertices MPR shuffles every iteration stay small.
template <class T>
struct SupportPoint {
    Vec3<T> v;                           ///< metres, on the boundary of D
    Vec3<T> a;                           ///< metres, the point of A it came from
    Vec3<T> b() const { return a - v; }  ///< metres, the point of B
};

/// Shapes A and B placed by rigid transforms, seen from A's local frame.
template <class A, class B>
class MinkowskiDifference {
public:
    using T = typename A::scalar_type;
    static_assert(std::is_same_v<T, typename B::scalar_type>, "both shapes must use the same scalar");

    /// margin (metres, >= 0) inflates A by a sphere of that radius, so that pairs closer than the
    /// margin overlap: the world uses it for speculative contacts (docs/collision.md, "Speculative
    /// margin").
    MinkowskiDifference(const A& a, const Transform<T>& pose_a, const B& b, const Transform<T>& pose_b, T margin = T(0))
        : a_(a), b_(b), pose_a_(pose_a), margin_(margin) {
        const Quat<T> inv_a = conjugate(pose_a.orientation);
        rotation_b_ = to_matrix(inv_a * pose_b.orientation);
        offset_b_ = rotate(inv_a, pose_b.position - pose_a.position);
    }

    /// Support of D along d (A's frame; d need not be unit): S_A(d) − S_B(−d).
    SupportPoint<T> support(const Vec3<T>& d) const {
        return combined(d, support_of(a_, d, hint_a_), support_of(b_, direction_to_b(-d), hint_b_));
    }
    /// support(d) for directions that jump about (the least-depth expansion's face normals): a
    /// polyhedron answers as on its own (support_index: a scan up to 48 vertices), not by climbing
    /// from its previous answer, which such a jump can make a long walk.
    SupportPoint<T> support_fresh(const Vec3<T>& d) const { return combined(d, a_.support(d), b_.support(direction_to_b(-d))); }
    /// The normal of A's flat supporting face along d (A's frame), if it has one.
    std::optional<Vec3<T>> flat_normal_a(const Vec3<T>& d) const { return flat_normal_of(a_, d, hint_a_); }
    /// The normal of B's flat supporting face along d (both in A's frame), if it has one.
    std::optional<Vec3<T>> flat_normal_b(const Vec3<T>& d) const {
        const std::optional<Vec3<T>> n = flat_normal_of(b_, direction_to_b(d), hint_b_);
        if (!n) return std::nullopt;
        return direction_to_a(*n);
    }

    /// A point strictly inside D: a point inside A minus a point inside B. Normally the centres of
    /// mass; when one shape is much larger (bounding radii 4:1 or more) its point moves, within a
    /// box inside it, as close as it can to the smaller shape's centre, so that the ray from v0
    /// crosses the surface the small shape actually touches instead of leaving through a far side
    /// (docs/collision.md, "Large size ratios"; Newton issue 3773).
    SupportPoint<T> interior() const {
        Vec3<T> pa = a_.interior_point();
        Vec3<T> pb = to_a(b_.interior_point());
        const T ra = a_.bounding_radius(), rb = b_.bounding_radius();
        if (ra > T(4) * rb) {
            pa = clamp_into(pb, a_.interior_point(), a_.inner_half_extents());
        } else if (rb > T(4) * ra) {
            const Vec3<T> pa_in_b = transposed_transform(rotation_b_, pa - offset_b_);
            pb = to_a(clamp_into(pa_in_b, b_.interior_point(), b_.inner_half_extents()));
        }
        return {pa - pb, pa};
    }
    /// A point of B's local frame in A's frame.
    Vec3<T> to_a(const Vec3<T>& p_b) const { return rotation_b_ * p_b + offset_b_; }
    /// A direction of B's frame in A's frame.
    Vec3<T> direction_to_a(const Vec3<T>& d_b) const { return rotation_b_ * d_b; }
    /// A direction of A's frame in B's frame.
    Vec3<T> direction_to_b(const Vec3<T>& d_a) const { return transposed_transform(rotation_b_, d_a); }
    /// A point of A's frame in the world.
    Vec3<T> point_to_world(const Vec3<T>& p) const { return pose_a_.apply(p); }
    /// A direction of A's frame in the world.
    Vec3<T> direction_to_world(const Vec3<T>& d) const { return pose_a_.apply_direction(d); }
    /// Length scale of the pair: the sum of the bounding radii (tolerances are fractions of it).
    T scale() const { return a_.bounding_radius() + b_.bounding_radius() + margin_; }
    /// Length scale of the smaller shape, for tolerances that must not grow with the larger one.
    T smaller_scale() const { return std::min(a_.bounding_radius(), b_.bounding_radius()) + margin_; }
    /// What a convergence tolerance of the pair is a fraction of: scale() for shapes of one size,
    /// twice the smaller one's for unequal shapes (a 10 cm hull at the edge of a 400 m box: as a
    /// fraction of scale(), float MPR stopped 5.7 mm short and missed overlaps that deep).
    T tolerance_scale() const { return std::min(scale(), T(2) * smaller_scale()); }
    /// Round-off of support distances at the pair's coordinates: tolerances stay above it.
    T round_off() const { return T(16) * ScalarTraits<T>::epsilon * scale(); }
    T margin() const { return margin_; }

    const A& shape_a() const { return a_; }
    /// B's local axes in A's frame (columns).
    const Mat3<T>& rotation_b() const { return rotation_b_; }
    const B& shape_b() const { return b_; }

private:
    // The support point of D along d from A's support along d and B's along −d (B's frame).
    SupportPoint<T> combined(const Vec3<T>& d, Vec3<T> pa, const Vec3<T>& pb_in_b) const {
        if (margin_ > T(0)) pa += normalized_or(d, Vec3<T>::unit_y()) * margin_;
        const Vec3<T> pb = to_a(pb_in_b);
        return {pa - pb, pa};
    }

    // Polyhedra climb from the vertex of the previous query: successive MPR directions are close,
    // so each support is a few neighbour checks (thesis 3.4, hill climbing). Other shapes answer
    // in closed form.
    template <class S>
    static Vec3<T> support_of(const S& shape, const Vec3<T>& d, std::uint32_t& hint) {
        if constexpr (detail::is_shape_ref<S>) {
            return shape.visit([&](const auto& concrete) { return support_of(concrete, d, hint); });
        } else if constexpr (std::is_same_v<S, ConvexPolyhedron<T>>) {
            hint = shape.support_index_hill_climb(d, hint == kNoHint ? shape.start_vertex(d) : hint);
            return shape.vertices()[hint];
        } else {
            (void)hint;
            return shape.support(d);
        }
    }

    template <class S>
    static std::optional<Vec3<T>> flat_normal_of(const S& shape, const Vec3<T>& d, std::uint32_t hint) {
        if constexpr (detail::is_shape_ref<S>) {
            return shape.visit([&](const auto& concrete) { return flat_normal_of(concrete, d, hint); });
        } else {
            if constexpr (std::is_same_v<S, ConvexPolyhedron<T>>) {
                if (hint != kNoHint) return shape.faces()[shape.support_face_index(d, hint)].normal;
            }
            return shape.flat_normal(d);
        }
    }

    static Vec3<T> clamp_into(const Vec3<T>& p, const Vec3<T>& centre, const Vec3<T>& half) {
        return centre + min(max(p - centre, -half), half);
    }

    const A& a_;
    const B& b_;
    Transform<T> pose_a_;
    T margin_;
    Mat3<T> rotation_b_;  ///< B's local axes in A's frame
    Vec3<T> offset_b_;    ///< B's origin in A's frame
    static constexpr std::uint32_t kNoHint = ~std::uint32_t(0);
    mutable std::uint32_t hint_a_ = kNoHint, hint_b_ = kNoHint;  ///< last support vertices of polyhedra
};

namespace f32 {
using SupportPoint = xeno::SupportPoint<float>;
}
namespace f64 {
using SupportPoint = xeno::SupportPoint<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The pairs MPR answers reach it through detail::ShapeRef (collide/shape_ref.hpp: one compiled
// copy of the narrow phase for every pair of kinds, a switch per support call). These tests hold
// that path to the per-pair instantiations it replaced, which stay callable with concrete types:
// the same bits for the world's manifolds (generate_contacts), for collide() (whose points take
// each kind's own support-feature rule, contact_points.hpp) and for a mesh triangle against every
// kind but the box (which keeps its closed form), in float and double.
#include "collide/random_pairs.hpp"

#include <xeno/collide/mesh_collide.hpp>

#include <doctest/doctest.h>

#include <cstring>

using namespace xeno;

namespace {

template <class X>
bool same_bits(const X& x, const X& y) {
    static_assert(std::is_trivially_copyable_v<X>);
    return std::memcmp(&x, &y, sizeof(X)) == 0;
}

template <class T>
bool same_manifold(const ContactManifold<T>& x, const ContactManifold<T>& y) {
    if (x.count != y.count || (x.count > 0 && !same_bits(x.normal, y.normal))) return false;
    for (int i = 0; i < x.count; ++i) {
        const ManifoldPoint<T>& p = x.points[static_cast<std::size_t>(i)];
        const ManifoldPoint<T>& q = y.points[static_cast<std::size_t>(i)];
        if (!same_bits(p.point_a, q.point_a) || !same_bits(p.point_b, q.point_b) || !same_bits(p.depth, q.depth)) return false;
    }
    return true;
}

template <class T>
bool same_penetration(const Penetration<T>& x, const Penetration<T>& y) {
    return x.hit == y.hit && (!x.hit || (same_bits(x.normal, y.normal) && same_bits(x.depth, y.depth) &&
                                         same_bits(x.point_a, y.point_a) && same_bits(x.point_b, y.point_b)));
}

/// The two queries on one pair of concrete shapes, as collide.hpp computed them per pair.
template <class T>
struct Typed {
    ContactManifold<T> manifold;
    Penetration<T> penetration;
};

template <class T, class SA, class SB>
Typed<T> typed_queries(const SA& sa, const Transform<T>& pa, const SB& sb, const Transform<T>& pb, bool swapped, T margin) {
    Typed<T> out;
    out.manifold = detail::manifold_of(MinkowskiDifference<SA, SB>(sa, pa, sb, pb, margin), T(0.005));
    out.penetration = swapped ? detail::flipped(detail::collide_pair(sb, pb, sa, pa)) : detail::collide_pair(sa, pa, sb, pb);
    return out;
}

template <class T>
void check_typed_random_pairs() {
    test::RandomPairs pairs(29, 0.05, 2.0, 10.0);
    pairs.set_touching_fraction(0.2);
    const test::ShapeMaker<T> maker(pairs);
    int compared = 0;
    for (int k = 0; k < 3000; ++k) {
        const test::PairParams p = pairs.next();
        Shape<T> sa = Sphere<T>(T(1)), sb = Sphere<T>(T(1));
        const Shape<T>& a = maker.get(p.a, sa);
        const Shape<T>& b = maker.get(p.b, sb);
        const Transform<T> pa = test::cast_pose<T>(p.pose_a), pb = test::cast_pose<T>(p.pose_b);
        const T margin = k % 2 ? T(0) : static_cast<T>(0.05 * p.scale);
        const bool swapped = detail::query_order_swapped(a, pa, b, pb);
        std::visit(
            [&](const auto& ca, const auto& cb) {
                using SA = std::decay_t<decltype(ca)>;
                using SB = std::decay_t<decltype(cb)>;
                if constexpr (detail::answered_by_mpr<SA, SB>) {
                    const Typed<T> typed = typed_queries(ca, pa, cb, pb, swapped, margin);
                    INFO("pair ", k, ": ", shape_name(a), " against ", shape_name(b));
                    CHECK(same_manifold(generate_contacts(a, pa, b, pb, margin, T(0.005)), typed.manifold));
                    CHECK(same_penetration(collide(a, pa, b, pb), typed.penetration));
                    ++compared;
                }
            },
            a, b);
    }
    CHECK(compared > 1700);  // 23 of the 36 ordered kind pairs go through MPR
}

template <class T>
void check_mesh_triangle() {
    test::RandomPairs pairs(31, 0.05, 2.0, 1.0);
    const test::ShapeMaker<T> maker(pairs);
    MeshTriangle<T> t;
    t.v[0] = {T(-2), T(0), T(-2)};
    t.v[1] = {T(0), T(0), T(2)};
    t.v[2] = {T(2), T(0), T(-2)};
    t.normal = Vec3<T>::unit_y();
    t.active_edges = 5;  // one inactive edge, so the edge correction runs too
    int touching = 0;
    for (int k = 0; k < 1500; ++k) {
        const test::PairParams p = pairs.next();
        Shape<T> scratch = Sphere<T>(T(1));
        const Shape<T>& shape = maker.get(p.a, scratch);
        if (std::holds_alternative<Box<T>>(shape)) continue;  // boxes keep box_triangle.hpp
        Transform<T> pose = test::cast_pose<T>(p.pose_a);
        pose.position.y = static_cast<T>(0.6 * p.scale * (2 * ((k * 37) % 100) / 100.0 - 0.5));
        const T margin = T(0.02);
        const ContactManifold<T> through_ref =
            detail::triangle_manifold(t, detail::ShapeRef<T>(shape), pose, pose.position, margin, T(0.005));
        const ContactManifold<T> typed = std::visit(
            [&](const auto& concrete) { return detail::triangle_manifold(t, concrete, pose, pose.position, margin, T(0.005)); },
            shape);
        INFO("pair ", k, ": triangle against ", shape_name(shape));
        CHECK(same_manifold(through_ref, typed));
        touching += typed.count > 0;
    }
    CHECK(touching > 200);
}

}  // namespace

TEST_CASE_TEMPLATE("MPR pairs through ShapeRef give the per-pair instantiations' bits (3,000 random pairs)", T, float, double) {
    check_typed_random_pairs<T>();
}

TEST_CASE_TEMPLATE("mesh triangles through ShapeRef give the per-kind instantiations' bits", T, float, double) {
    check_mesh_triangle<T>();
}

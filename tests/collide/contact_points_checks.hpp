// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The randomised check of collide()'s contact points shared by contact_points_test.cpp (a few
// thousand pairs) and contact_points_slow_test.cpp (100,000 pairs per precision), against
// references computed from the shapes' support functions alone (support_reference.hpp):
// point_a on or inside A within the depth (+ 1e-4 of the pair's size), point_b the same for B,
// and point_a − point_b = depth · normal.
#pragma once

#include "collide/random_pairs.hpp"
#include "collide/support_reference.hpp"

#include <xeno/collide/collide.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace xeno::test {

inline const char* kind_name(std::size_t k) {
    static const char* names[] = {"sphere", "box", "capsule", "cylinder", "cone", "hull"};
    return names[k];
}

inline std::string pair_name(const PairParams& p) {
    std::size_t a = p.a.kind, b = p.b.kind;
    if (a > b) std::swap(a, b);
    return std::string(kind_name(a)) + "-" + kind_name(b);
}

struct ContractResult {
    int hits = 0;
    int violations = 0;        ///< a point farther outside its shape than depth + 1e-4 · size
    double worst_excess = -1;  ///< max over hits of (distance outside − depth) / size
    double worst_offset = 0;   ///< max over hits of |point_a − point_b − depth · normal| / size
    std::string worst_pair;
};

/// Draws `count` pairs (sizes min_size … max_size, so up to (max/min)·10 between the two shapes)
/// and checks collide()'s contact points in precision T.
template <class T>
ContractResult check_contract(std::uint64_t seed, int count, double min_size, double max_size) {
    RandomPairs pairs(seed, min_size, max_size, 10.0);
    const ShapeMaker<T> make(pairs);
    Shape<T> sa = Sphere<T>(T(1)), sb = Sphere<T>(T(1));
    ContractResult r;
    for (int k = 0; k < count; ++k) {
        const PairParams p = pairs.next();
        const Shape<T>& a = make.get(p.a, sa);
        const Shape<T>& b = make.get(p.b, sb);
        const Transform<T> ta = cast_pose<T>(p.pose_a), tb = cast_pose<T>(p.pose_b);
        const Penetration<T> c = collide(a, ta, b, tb);
        if (!c.hit) continue;
        ++r.hits;
        const Shape<double> ad = widened(a), bd = widened(b);
        const Transform<double> tad = ta.template cast<double>(), tbd = tb.template cast<double>();
        const double size = bounding_radius(ad) + bounding_radius(bd);
        const double depth = static_cast<double>(c.depth);
        const Vec3<double> pa = c.point_a.template cast<double>(), pb = c.point_b.template cast<double>();
        const double excess = std::max(distance_outside(ad, tad, pa), distance_outside(bd, tbd, pb)) - depth;
        const double offset = length(pa - pb - c.normal.template cast<double>() * depth);
        if (excess > 1e-4 * size || offset > 1e-4 * size) ++r.violations;
        if (excess / size > r.worst_excess) {
            r.worst_excess = excess / size;
            r.worst_pair = pair_name(p);
        }
        r.worst_offset = std::max(r.worst_offset, offset / size);
    }
    return r;
}

}  // namespace xeno::test

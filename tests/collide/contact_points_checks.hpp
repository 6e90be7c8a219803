// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The two randomised checks of collide()'s answer shared by contact_points_test.cpp (a few
// thousand pairs) and contact_points_slow_test.cpp (100,000 pairs per precision), against
// references computed from the shapes' support functions alone (support_reference.hpp):
//   contract:  point_a on or inside A within the depth (+ 1e-4 of the pair's size), point_b the
//              same for B, and point_a − point_b = depth · normal;
//   depth:     reported depth ÷ the least depth over all directions (dense search).
#pragma once

#include "collide/random_pairs.hpp"
#include "collide/support_reference.hpp"

#include <xeno/collide/collide.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
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

inline double quantile_of(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
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

struct DepthResult {
    std::map<std::string, std::vector<double>> ratio;  ///< per pair kind: depth ÷ least depth
    std::vector<double> all;
    double worst_shallow = 0;  ///< max (depth − least) / size where the least depth is < 1e-3 of the size
    int below = 0;             ///< pairs reported shallower than the reference minimum by > 1e-4 of the size
    double lowest = 1;         ///< the smallest depth ÷ reference (below 1 where the reference search stayed high)
};

/// Reported depth against the least depth over all directions on `count` random pairs (sizes
/// min_size … max_size), in precision T; the reference is computed in double on the same
/// (rounded) shapes and poses.
template <class T>
DepthResult check_depth(std::uint64_t seed, int count, double min_size, double max_size) {
    RandomPairs pairs(seed, min_size, max_size, 10.0);
    const ShapeMaker<T> make(pairs);
    Shape<T> sa = Sphere<T>(T(1)), sb = Sphere<T>(T(1));
    DepthResult r;
    for (int k = 0; k < count; ++k) {
        const PairParams p = pairs.next();
        const Shape<T>& a = make.get(p.a, sa);
        const Shape<T>& b = make.get(p.b, sb);
        const Transform<T> ta = cast_pose<T>(p.pose_a), tb = cast_pose<T>(p.pose_b);
        const Penetration<T> c = collide(a, ta, b, tb);
        if (!c.hit) continue;
        const Shape<double> ad = widened(a), bd = widened(b);
        const Transform<double> tad = ta.template cast<double>(), tbd = tb.template cast<double>();
        const double size = bounding_radius(ad) + bounding_radius(bd);
        const double least = minimum_depth(ad, tad, bd, tbd);
        const double depth = static_cast<double>(c.depth);
        if (depth < least - 1e-4 * size) ++r.below;
        if (least > 1e-3 * size) r.lowest = std::min(r.lowest, depth / least);
        if (least > 1e-3 * size) {
            r.ratio[pair_name(p)].push_back(depth / least);
            r.all.push_back(depth / least);
        } else {
            r.worst_shallow = std::max(r.worst_shallow, (depth - least) / size);
        }
    }
    return r;
}

/// The per-kind table (median, 99 %, max of depth ÷ least depth) as text.
inline std::string depth_table(const DepthResult& r) {
    std::string out = "pair kind          pairs   median      p99      max\n";
    char line[128];
    for (const auto& [name, v] : r.ratio) {
        std::snprintf(line, sizeof line, "%-17s %6zu %8.4f %8.4f %8.4f\n", name.c_str(), v.size(), quantile_of(v, 0.5),
                      quantile_of(v, 0.99), quantile_of(v, 1.0));
        out += line;
    }
    std::snprintf(line, sizeof line, "%-17s %6zu %8.4f %8.4f %8.4f\n", "all", r.all.size(), quantile_of(r.all, 0.5),
                  quantile_of(r.all, 0.99), quantile_of(r.all, 1.0));
    out += line;
    return out;
}

}  // namespace xeno::test

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Random narrow-phase pairs for the sweep and precision tests: every shape kind (hulls of 4 to 12
// random points included), sizes log-uniform over a range, A anywhere in a box, B placed from 0 to
// 1.1 times the sum of the bounding radii away from A in a random direction (so overlaps, near
// touches and misses all occur), and optionally a share of pairs moved to within 1e-12 … 1e-4 of
// their size from touching. Pairs are drawn in double, deterministically (scenes::Random), and built in
// either precision from the same numbers: float shapes and poses are the double ones rounded,
// hulls share their vertices (rounded) and faces.
#pragma once

#include "scenes/random.hpp"

#include <xeno/collide/collide.hpp>
#include <xeno/shape/convex_hull.hpp>
#include <xeno/shape/shape.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace xeno::test {

/// One shape as numbers: kind is the Shape<T> variant index (sphere, box, capsule, cylinder,
/// cone, hull); dims are metres; hull indexes the hull pool.
struct ShapeParams {
    std::size_t kind = 0;
    Vec3<double> dims{};
    std::size_t hull = 0;
};

/// One pair of placed shapes, in double.
struct PairParams {
    ShapeParams a, b;
    Transform<double> pose_a, pose_b;
    double scale = 0;  ///< m, the sum of the two bounding radii
    double gap = 0;    ///< for near-touching pairs: m beyond touching along the offset (< 0 overlaps)
};

/// The generator. Hulls come from a pool built once (make_convex_hull is far slower than a query).
class RandomPairs {
public:
    RandomPairs(std::uint64_t seed, double min_size, double max_size, double max_position, std::size_t hull_count = 64)
        : rng_(seed), min_size_(min_size), max_size_(max_size), max_position_(max_position) {
        while (hulls_.size() < hull_count) add_hull();
    }

    const std::vector<ConvexPolyhedron<double>>& hulls() const { return hulls_; }

    PairParams next() {
        PairParams p;
        p.a = shape();
        p.b = shape();
        p.scale = radius(p.a) + radius(p.b);
        const Vec3<double> position_a = rng_.in_box(Vec3<double>::one() * max_position_);
        const Quat<double> orientation_a = rng_.rotation<double>();
        const Vec3<double> direction = rng_.direction<double>();
        const double distance = rng_.uniform(0.0, 1.1) * p.scale;
        const Quat<double> orientation_b = rng_.rotation<double>();
        p.pose_a = {position_a, orientation_a};
        p.pose_b = {position_a + direction * distance, orientation_b};
        if (rng_.uniform() < touching_fraction_) {
            // Near touching: the overlapping distances along the direction form an interval from 0
            // (centres together) to where they touch; bisection in double finds that end to
            // 2^-45 of the pair's size. Then a gap or overlap of 1e-12 … 1e-4 of the size
            // (log-uniform) is added, so both precisions meet their round-off.
            Shape<double> sa = Sphere<double>(1.0), sb = Sphere<double>(1.0);
            const Shape<double>& a = get(p.a, sa);
            const Shape<double>& b = get(p.b, sb);
            double inside = 0, outside = 1.0001 * p.scale;
            for (int i = 0; i < 45; ++i) {
                const double mid = 0.5 * (inside + outside);
                const Transform<double> pose_b{position_a + direction * mid, orientation_b};
                (intersect(a, p.pose_a, b, pose_b) ? inside : outside) = mid;
            }
            const double sign = rng_.uniform() < 0.5 ? -1.0 : 1.0;
            const double gap = sign * log_uniform(1e-12, 1e-4) * p.scale;
            p.pose_b.position = position_a + direction * (inside + gap);
            p.gap = gap;
        }
        return p;
    }
    /// The fraction of pairs placed within 1e-12 … 1e-4 of their size from touching (default none).
    void set_touching_fraction(double f) { touching_fraction_ = f; }

private:
    const Shape<double>& get(const ShapeParams& s, Shape<double>& scratch) const {
        const Vec3<double>& d = s.dims;
        switch (s.kind) {
            case 0: scratch = Sphere<double>(d.x); break;
            case 1: scratch = Box<double>(d); break;
            case 2: scratch = Capsule<double>(d.x, d.y); break;
            case 3: scratch = Cylinder<double>(d.x, d.y); break;
            case 4: scratch = Cone<double>(d.x, d.y); break;
            default: return hull_shapes_[s.hull];
        }
        return scratch;
    }
    double log_uniform(double low, double high) { return low * std::pow(high / low, rng_.uniform()); }
    /// A size: log-uniform base, each dimension 0.1 … 1 of it, clamped to the range.
    Vec3<double> dims() {
        const double base = log_uniform(min_size_, max_size_);
        Vec3<double> d;
        for (int i = 0; i < 3; ++i) d[i] = std::max(min_size_, base * log_uniform(0.1, 1.0));
        return d;
    }
    ShapeParams shape() {
        ShapeParams s;
        s.kind = rng_.index(6);
        s.dims = dims();
        if (s.kind == 5) s.hull = rng_.index(static_cast<std::uint32_t>(hulls_.size()));
        return s;
    }
    double radius(const ShapeParams& s) const {
        Shape<double> scratch = Sphere<double>(1.0);
        return bounding_radius(get(s, scratch));
    }
    /// A hull of 4 to 12 points on an ellipsoid of random size; degenerate clouds (and clouds whose
    /// faces a float polyhedron could not represent) are drawn again.
    void add_hull() {
        const Vec3<double> axes = dims();
        const int n = 4 + static_cast<int>(rng_.index(9));
        std::vector<Vec3<double>> points;
        for (int i = 0; i < n; ++i) points.push_back(hadamard(rng_.direction<double>(), axes));
        try {
            ConvexPolyhedron<double> hull = make_convex_hull(points).polyhedron;
            (void)ConvexPolyhedron<float>(rounded_vertices<float>(hull), face_lists(hull));
            hull_shapes_.emplace_back(hull);
            hulls_.push_back(std::move(hull));
        } catch (const InvalidArgument&) {
        }
    }

public:
    template <class T>
    static std::vector<Vec3<T>> rounded_vertices(const ConvexPolyhedron<double>& hull) {
        std::vector<Vec3<T>> v;
        for (const Vec3<double>& p : hull.vertices()) v.push_back(p.cast<T>());
        return v;
    }
    static std::vector<std::vector<std::uint32_t>> face_lists(const ConvexPolyhedron<double>& hull) {
        std::vector<std::vector<std::uint32_t>> faces;
        for (const auto& f : hull.faces())
            faces.emplace_back(hull.face_indices().begin() + f.first, hull.face_indices().begin() + f.first + f.count);
        return faces;
    }

private:
    scenes::Random rng_;
    double min_size_, max_size_, max_position_;
    double touching_fraction_ = 0;
    std::vector<ConvexPolyhedron<double>> hulls_;
    std::vector<Shape<double>> hull_shapes_;  // the same, as shapes
};

/// The shapes of RandomPairs in precision T: hulls built once, other shapes on demand.
template <class T>
class ShapeMaker {
public:
    explicit ShapeMaker(const RandomPairs& pairs) {
        for (const ConvexPolyhedron<double>& h : pairs.hulls())
            hulls_.emplace_back(ConvexPolyhedron<T>(RandomPairs::rounded_vertices<T>(h), RandomPairs::face_lists(h)));
    }
    /// The shape of s: a pool hull, or an implicit shape built into scratch.
    const Shape<T>& get(const ShapeParams& s, Shape<T>& scratch) const {
        const Vec3<T> d = s.dims.cast<T>();
        switch (s.kind) {
            case 0: scratch = Sphere<T>(d.x); break;
            case 1: scratch = Box<T>(d); break;
            case 2: scratch = Capsule<T>(d.x, d.y); break;
            case 3: scratch = Cylinder<T>(d.x, d.y); break;
            case 4: scratch = Cone<T>(d.x, d.y); break;
            default: return hulls_[s.hull];
        }
        return scratch;
    }

private:
    std::vector<Shape<T>> hulls_;
};

template <class T>
Transform<T> cast_pose(const Transform<double>& t) {
    return t.template cast<T>();
}

}  // namespace xeno::test

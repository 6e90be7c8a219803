// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Reference answers for the narrow-phase contract tests, computed from the shapes' support
// functions alone (no MPR, no separating-axis code, no refinement): both are maxima or minima of a
// function of a unit direction d, found by a dense sampling of the sphere (a Fibonacci lattice)
// and a compass-search polish from the best samples.
//   distance_outside(shape, pose, p) = max over unit d of d·p − h(d), where h is the shape's
//       support distance: the Euclidean distance from p to the convex shape when p is outside
//       (the maximising d points from the nearest point of the shape to p), ≤ 0 inside.
//   minimum_depth(a, pose_a, b, pose_b) = min over unit n of h_A(n) + h_B(−n): the support
//       function of A ⊖ B, whose minimum over directions is the penetration depth (the distance
//       from the origin to the boundary of A ⊖ B) when the shapes overlap.
// Everything is evaluated in double, whatever the precision of the pair under test.
#pragma once

#include <xeno/math/mat3.hpp>
#include <xeno/math/quat.hpp>
#include <xeno/shape/shape.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <vector>

namespace xeno::test {

/// The same shape in double (a float shape's numbers widened exactly), for the references.
template <class T>
Shape<double> widened(const Shape<T>& s) {
    return std::visit(
        [](const auto& x) -> Shape<double> {
            using S = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<S, Sphere<T>>) return Sphere<double>(double(x.radius()));
            else if constexpr (std::is_same_v<S, Box<T>>) return Box<double>(x.half_extents().template cast<double>());
            else if constexpr (std::is_same_v<S, Capsule<T>>) return Capsule<double>(double(x.radius()), double(x.half_height()));
            else if constexpr (std::is_same_v<S, Cylinder<T>>)
                return Cylinder<double>(double(x.radius()), double(x.half_height()));
            else if constexpr (std::is_same_v<S, Cone<T>>) return Cone<double>(double(x.radius()), double(x.height()));
            else {
                std::vector<Vec3<double>> v;
                for (const Vec3<T>& p : x.vertices()) v.push_back(p.template cast<double>());
                std::vector<std::vector<std::uint32_t>> faces;
                for (const auto& f : x.faces())
                    faces.emplace_back(x.face_indices().begin() + f.first, x.face_indices().begin() + f.first + f.count);
                return ConvexPolyhedron<double>(v, faces);
            }
        },
        s);
}

/// A shape with its pose as a rotation matrix: the searches below evaluate its support function
/// some 10,000 times per pair, and one matrix product per call is half the work of two quaternion
/// rotations.
struct PlacedShape {
    PlacedShape(const Shape<double>& s, const Transform<double>& pose)
        : shape(s), rotation(to_matrix(pose.orientation)), position(pose.position) {}
    const Shape<double>& shape;
    Mat3<double> rotation;
    Vec3<double> position;
};

/// Support distance of a placed shape along the world direction d (unit): max over the shape of
/// x·d, that is (R s(Rᵀd) + p)·d = s(Rᵀd)·Rᵀd + p·d for the support point s of the local direction.
inline double support_distance(const PlacedShape& x, const Vec3<double>& d) {
    const Vec3<double> local = transposed_transform(x.rotation, d);
    return dot(support(x.shape, local), local) + dot(x.position, d);
}

/// `samples` directions of a Fibonacci lattice on the unit sphere, computed once per count (the
/// trigonometry cost as much as the searches' support calls).
inline const std::vector<Vec3<double>>& fibonacci_lattice(int samples) {
    static std::mutex mutex;
    static std::map<int, std::vector<Vec3<double>>> cache;
    const std::lock_guard<std::mutex> lock(mutex);
    std::vector<Vec3<double>>& lattice = cache[samples];
    if (lattice.empty()) {
        const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
        for (int i = 0; i < samples; ++i) {
            const double z = 1.0 - (2.0 * i + 1.0) / samples;
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            const double phi = golden * i;
            lattice.push_back({r * std::cos(phi), z, r * std::sin(phi)});
        }
    }
    return lattice;
}

/// The compass search's 12 tangent directions as (cos, sin), in three sets turned by 0.37 of a
/// step between them so successive rounds probe between each other's directions.
inline const std::array<std::array<double, 2>, 36>& compass_directions() {
    static const std::array<std::array<double, 2>, 36> table = [] {
        std::array<std::array<double, 2>, 36> t{};
        for (int turn = 0; turn < 3; ++turn)
            for (int j = 0; j < 12; ++j) {
                const double angle = (j + 0.37 * turn) * 3.14159265358979323846 / 6;
                t[static_cast<std::size_t>(turn * 12 + j)] = {std::cos(angle), std::sin(angle)};
            }
        return t;
    }();
    return table;
}

/// The maximum of f over unit vectors: `samples` directions of a Fibonacci lattice, then a compass
/// search (12 tangent directions, step halved on failure down to 1e-9 rad) from the `starts` best.
template <class F>
double maximise_on_sphere(F&& f, int samples = 800, int starts = 6, const std::vector<Vec3<double>>& seeds = {},
                          Vec3<double>* argmax = nullptr) {
    struct Sample {
        double value;
        Vec3<double> d;
    };
    std::vector<Sample> s;
    s.reserve(static_cast<std::size_t>(samples) + seeds.size());
    for (const Vec3<double>& d : seeds) s.push_back({f(d), d});
    for (const Vec3<double>& d : fibonacci_lattice(samples)) s.push_back({f(d), d});
    const int k = std::min(starts, static_cast<int>(s.size()));
    std::partial_sort(s.begin(), s.begin() + k, s.end(), [](const Sample& x, const Sample& y) { return x.value > y.value; });
    double best = s[0].value;
    if (argmax) *argmax = s[0].d;
    // A move must gain more than round-off (relative to the spread of the samples), and each start
    // makes at most 1,000 moves: a point on a surface has f ≈ 0 ± round-off, where a walk through
    // noise could otherwise go on for ever.
    double low = best;
    for (const Sample& x : s) low = std::min(low, x.value);
    const double gain = 1e-13 * (best - low) + 1e-300;
    const double spacing = std::sqrt(4.0 * 3.14159265358979323846 / samples);
    const std::array<std::array<double, 2>, 36>& compass = compass_directions();
    for (int i = 0; i < k; ++i) {
        Vec3<double> d = s[static_cast<std::size_t>(i)].d;
        double value = s[static_cast<std::size_t>(i)].value;
        double step = spacing;
        int turn = 0;
        int moves = 0;
        while (step > 1e-9 && moves < 1000) {
            const Vec3<double> t1 = normalized(cross(d, std::abs(d.x) < 0.6 ? Vec3<double>::unit_x() : Vec3<double>::unit_y()));
            const Vec3<double> t2 = cross(d, t1);
            bool moved = false;
            for (int j = 0; j < 12; ++j) {
                const std::array<double, 2>& cs = compass[static_cast<std::size_t>((turn % 3) * 12 + j)];
                const Vec3<double> trial = normalized(d + (t1 * cs[0] + t2 * cs[1]) * step);
                const double v = f(trial);
                if (v > value + gain) {
                    value = v;
                    d = trial;
                    moved = true;
                    ++moves;
                    break;
                }
            }
            ++turn;
            if (!moved) step *= 0.5;
        }
        if (value > best) {
            best = value;
            if (argmax) *argmax = d;
        }
    }
    return best;
}

/// Distance from p to the placed convex shape (> 0 outside, ≤ 0 inside: minus the depth below the
/// nearest support plane).
inline double distance_outside(const Shape<double>& s, const Transform<double>& pose, const Vec3<double>& p, int samples = 400,
                               int starts = 3) {
    const PlacedShape x(s, pose);
    return maximise_on_sphere([&](const Vec3<double>& d) { return dot(d, p) - support_distance(x, d); }, samples, starts);
}

/// Flat-feature and edge directions of a placed shape (world frame), the separating-axis
/// candidates of polytopes: face normals go to `faces`, edge (or side-line) directions to `edges`.
inline void feature_directions(const Shape<double>& s, const Transform<double>& pose, std::vector<Vec3<double>>& faces,
                               std::vector<Vec3<double>>& edges) {
    auto world = [&](const Vec3<double>& d) { return pose.apply_direction(d); };
    std::visit(
        [&](const auto& x) {
            using S = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<S, Box<double>>) {
                for (int i = 0; i < 3; ++i) {
                    faces.push_back(world(Vec3<double>::axis(i)));
                    faces.push_back(-world(Vec3<double>::axis(i)));
                    edges.push_back(world(Vec3<double>::axis(i)));
                }
            } else if constexpr (std::is_same_v<S, ConvexPolyhedron<double>>) {
                for (const auto& f : x.faces()) faces.push_back(world(f.normal));
                for (const auto& e : x.edges()) edges.push_back(world(x.vertices()[e.second] - x.vertices()[e.first]));
            } else if constexpr (std::is_same_v<S, Cylinder<double>>) {
                faces.push_back(world(Vec3<double>::unit_y()));
                faces.push_back(-world(Vec3<double>::unit_y()));
                edges.push_back(world(Vec3<double>::unit_y()));
            } else if constexpr (std::is_same_v<S, Capsule<double>>) {
                edges.push_back(world(Vec3<double>::unit_y()));
            } else if constexpr (std::is_same_v<S, Cone<double>>) {
                faces.push_back(-world(Vec3<double>::unit_y()));
            }
        },
        s);
}

/// Penetration depth of two placed convex shapes (< 0: they are apart by at least that much).
/// Besides the sphere lattice, the search starts from the separating-axis candidates of the flat
/// features (face normals of both, cross products of their edges), where the polytope parts of
/// A ⊖ B have their faces.
inline double minimum_depth(const Shape<double>& a, const Transform<double>& pose_a, const Shape<double>& b,
                            const Transform<double>& pose_b, int samples = 2000, int starts = 16,
                            Vec3<double>* normal = nullptr) {
    std::vector<Vec3<double>> faces, edges_a, edges_b, seeds;
    feature_directions(a, pose_a, faces, edges_a);
    for (const Vec3<double>& f : faces) seeds.push_back(f);
    faces.clear();
    feature_directions(b, pose_b, faces, edges_b);
    for (const Vec3<double>& f : faces) seeds.push_back(-f);
    for (const Vec3<double>& ea : edges_a)
        for (const Vec3<double>& eb : edges_b) {
            const Vec3<double> c = cross(ea, eb);
            if (length_squared(c) <= 1e-20 * length_squared(ea) * length_squared(eb)) continue;
            seeds.push_back(normalized(c));
            seeds.push_back(-normalized(c));
        }
    const PlacedShape pa(a, pose_a), pb(b, pose_b);
    return -maximise_on_sphere([&](const Vec3<double>& n) { return -(support_distance(pa, n) + support_distance(pb, -n)); },
                               samples, starts, seeds, normal);
}

}  // namespace xeno::test

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// collide()'s contact points against references computed from the shapes' support functions
// alone (support_reference.hpp): the contract of contact_points.hpp (each point on or inside its
// own body within the depth, point_a − point_b = depth · normal) and exact points for face, edge
// and round contacts. The 100,000-pair version is in contact_points_slow_test.cpp.
#include "collide/contact_points_checks.hpp"
#include "support/approx.hpp"

#include "scenes/random.hpp"

#include <doctest/doctest.h>

#include <algorithm>

using namespace xeno;

namespace {

#if defined(XENO_SANITIZE)
constexpr int kContractPairs = 200;
#else
constexpr int kContractPairs = 2000;
#endif

// Closed-form "surface gap" of a point against a placed primitive, in double: 0 on the surface,
// < 0 inside, > 0 outside (the largest of the signed distances to the bounding planes or curved
// sides, which is zero exactly on the surface). For the exact-placement checks, where a sampled
// support search would stall at the kink of a face and read slightly inside.
template <class T>
double surface_gap(const Shape<T>& s, const Transform<T>& pose, const Vec3<T>& p_world) {
    const Vec3<double> p = pose.template cast<double>().inverse_apply(p_world.template cast<double>());
    return std::visit(
        [&](const auto& x) -> double {
            using S = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<S, Sphere<T>>) {
                return length(p) - double(x.radius());
            } else if constexpr (std::is_same_v<S, Box<T>>) {
                const Vec3<double> h = x.half_extents().template cast<double>();
                return std::max({std::abs(p.x) - h.x, std::abs(p.y) - h.y, std::abs(p.z) - h.z});
            } else if constexpr (std::is_same_v<S, Capsule<T>>) {
                const double y = std::clamp(p.y, -double(x.half_height()), double(x.half_height()));
                return length(p - Vec3<double>{0, y, 0}) - double(x.radius());
            } else if constexpr (std::is_same_v<S, Cylinder<T>>) {
                return std::max(std::sqrt(p.x * p.x + p.z * p.z) - double(x.radius()), std::abs(p.y) - double(x.half_height()));
            } else if constexpr (std::is_same_v<S, Cone<T>>) {
                const double r = x.radius(), h = x.height(), slant = std::sqrt(r * r + h * h);
                const double side = (std::sqrt(p.x * p.x + p.z * p.z) * h + (p.y - 0.75 * h) * r) / slant;
                return std::max(-0.25 * h - p.y, side);
            } else {
                return 1e30;  // not used on hulls
            }
        },
        s);
}

}  // namespace

TEST_CASE_TEMPLATE("regression: a 1 m box overlapping a 30 m box gets its contact points on the boxes, not metres away", T, float,
                   double) {
    // Before: the point on the small box was the large box's far corner moved by the depth, up to
    // 17 m from the small box (box_box.hpp placed the contact at B's support vertex).
    const Shape<T> small = Box<T>(T(0.5), T(0.5), T(0.5)), big = Box<T>(T(15), T(2), T(15));
    const Transform<T> big_pose{Vec3<T>::zero(), Quat<T>::identity()};
    scenes::Random rng(91);
    // Round-off: float coordinates of 15 m carry 1e-6 m, and the separating-axis test pads |R| by
    // 16 epsilon against parallel edges, which adds up to 6e-5 m to a float depth at this size.
    const double on_surface = std::is_same_v<T, float> ? 1e-4 : 1e-9;
    const T offset = std::is_same_v<T, float> ? T(1e-4) : T(1e-9);
    for (int k = 0; k < 200; ++k) {
        const Transform<T> small_pose{{rng.uniform(T(-14), T(14)), T(2.4), rng.uniform(T(-14), T(14))},
                                      Quat<T>::from_axis_angle(Vec3<T>::unit_y(), rng.uniform(T(0), T(3)))};
        for (const bool small_first : {true, false}) {
            const Penetration<T> p =
                small_first ? collide(small, small_pose, big, big_pose) : collide(big, big_pose, small, small_pose);
            REQUIRE(p.hit);
            CHECK(test::near(p.depth, T(0.1), T(1e-4)));
            const Vec3<T>& on_small = small_first ? p.point_a : p.point_b;
            const Vec3<T>& on_big = small_first ? p.point_b : p.point_a;
            // Face against face: both points on their surfaces (within round-off), under the small box.
            CHECK(std::abs(surface_gap(small, small_pose, on_small)) <= on_surface);
            CHECK(std::abs(surface_gap(big, big_pose, on_big)) <= on_surface);
            CHECK(length(Vec3<T>{on_small.x - small_pose.position.x, T(0), on_small.z - small_pose.position.z}) < T(0.71));
            CHECK(test::near(p.point_a - p.point_b, p.normal * p.depth, offset));
        }
    }
}

TEST_CASE_TEMPLATE("face, edge and round contacts get both points exactly on the surfaces", T, float, double) {
    const Transform<T> origin{Vec3<T>::zero(), Quat<T>::identity()};
    const Shape<T> ground = Box<T>(T(5), T(0.5), T(5));
    const double tol = std::is_same_v<T, float> ? 2e-5 : 1e-7;
    const Quat<T> flat = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 2);
    const Quat<T> edge_down = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 4);
    struct Case {
        Shape<T> shape;
        Transform<T> pose;
        T depth;
    };
    const Case cases[] = {
        {Sphere<T>(T(0.5)), {{T(1), T(0.99), T(2)}, Quat<T>::identity()}, T(0.01)},
        {Cylinder<T>(T(0.4), T(0.5)), {{T(-2), T(0.98), T(1)}, Quat<T>::identity()}, T(0.02)},  // on its cap
        {Cylinder<T>(T(0.4), T(0.5)), {{T(3), T(0.89), T(0)}, flat}, T(0.01)},                  // on its side
        {Cone<T>(T(0.5), T(1)), {{T(0), T(0.74), T(-3)}, Quat<T>::identity()}, T(0.01)},        // on its base
        {Capsule<T>(T(0.3), T(0.6)), {{T(0.5), T(0.79), T(0.5)}, flat}, T(0.01)},               // lying flat
        {Box<T>(T(0.5), T(0.5), T(0.5)), {{T(4), T(0.5) + std::sqrt(T(0.5)) - T(0.02), T(4)}, edge_down}, T(0.02)},  // on an edge
    };
    for (const Case& c : cases) {
        const Penetration<T> p = collide(ground, origin, c.shape, c.pose);
        REQUIRE(p.hit);
        CHECK(test::near(p.depth, c.depth, T(1e-4)));
        CHECK(test::near(p.normal, Vec3<T>::unit_y(), T(1e-4)));
        CHECK(std::abs(surface_gap(ground, origin, p.point_a)) <= tol);
        CHECK(std::abs(surface_gap(c.shape, c.pose, p.point_b)) <= tol);
        // Under the body, not at a corner of the ground.
        CHECK(length(Vec3<T>{p.point_b.x - c.pose.position.x, T(0), p.point_b.z - c.pose.position.z}) <=
              bounding_radius(c.shape));
        CHECK(test::near(p.point_a - p.point_b, p.normal * p.depth, T(1e-5)));
    }
}

TEST_CASE_TEMPLATE("collide() contact points lie on or inside their own shapes within the depth, sizes up to 100:1", T, float,
                   double) {
    // Every shape kind, sizes 0.1 … 10 m, so the two shapes differ by up to 100 times.
    const test::ContractResult r = test::check_contract<T>(61, kContractPairs, 0.1, 10.0);
    MESSAGE(r.hits << " overlapping pairs, " << r.violations
                   << " with a point outside its shape by more than the depth + 1e-4 of the size; "
                   << "worst (outside − depth) / size " << r.worst_excess << " (" << r.worst_pair
                   << "), worst |pa − pb − depth n| / size " << r.worst_offset);
    CHECK(r.hits > kContractPairs / 4);
    CHECK(r.violations == 0);
    CHECK(r.worst_offset <= 1e-4);
}

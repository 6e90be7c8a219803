// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// detail::support_stiffness, the fastest mode of a body on its static contact points, against
// closed forms for a box resting on one face, however the box is turned.
#include "support/approx.hpp"

#include <xeno/dynamics/support_stiffness.hpp>

#include <vector>

using namespace xeno;
using xeno::test::near;

namespace {

/// The four corner points of a box of half extents e resting on its −y face, each a row as the
/// World builds it (n, r × n, the point's effective mass), all turned by q with the box.
template <class T>
std::vector<detail::SupportRow<T>> corner_rows(const Vec3<T>& e, T mass, const Mat3<T>& inv_inertia, const Quat<T>& q) {
    std::vector<detail::SupportRow<T>> rows;
    const Vec3<T> n = rotate(q, Vec3<T>::unit_y());
    for (const T sx : {T(-1), T(1)})
        for (const T sz : {T(-1), T(1)}) {
            const Vec3<T> r = rotate(q, Vec3<T>{sx * e.x, -e.y, sz * e.z});
            const Vec3<T> rn = cross(r, n);
            rows.push_back({n, rn, T(1) / (T(1) / mass + dot(rn, inv_inertia * rn))});
        }
    return rows;
}

/// The closed form: with the box's axes as the frame the bounce (translation along n) and the
/// rocking about x and about z decouple, by symmetry. A corner point's effective mass is
/// M / (1 + 3c²/(b²+c²) + 3a²/(a²+b²)) (a box's inertia about x is M(b²+c²)/3 with half extents),
/// and the modes are 4 m/M for the bounce and 4 m/M · 3c²/(b²+c²), 4 m/M · 3a²/(a²+b²) rocking.
double box_on_face(double a, double b, double c) {
    const double rock_x = 3 * c * c / (b * b + c * c), rock_z = 3 * a * a / (a * a + b * b);
    const double share = 4 / (1 + rock_x + rock_z);  // 4 m / M
    return std::max({share, share * rock_x, share * rock_z});
}

}  // namespace

TEST_CASE_TEMPLATE("a box on one face rings fastest rocking on its corners, as the closed form says", T, float, double) {
    struct Case {
        Vec3<T> half;
        double expected;
    };
    const Case cases[] = {
        {{T(0.5), T(0.5), T(0.5)}, 1.5},                           // a cube: rocking, √1.5 ω
        {{T(0.5), T(0.05), T(0.5)}, box_on_face(0.5, 0.05, 0.5)},  // a slab: near 12/7
        {{T(0.5), T(0.2), T(0.3)}, box_on_face(0.5, 0.2, 0.3)},    // no two sides alike
        {{T(0.1), T(2), T(0.1)}, box_on_face(0.1, 2, 0.1)},        // a post on its end: the bounce
    };
    CHECK(near(cases[1].expected, 12.0 / 7.0, 0.05));
    CHECK(cases[3].expected == doctest::Approx(4 / (1 + 2 * 3 * 0.01 / 4.01)));
    const Quat<T> turns[] = {Quat<T>::identity(), Quat<T>::from_axis_angle(normalized(Vec3<T>{T(1), T(2), T(-0.5)}), T(0.9)),
                             Quat<T>::from_axis_angle(normalized(Vec3<T>{T(-0.3), T(0.1), T(1)}), T(2.7))};
    for (const Case& c : cases)
        for (const Quat<T>& q : turns) {
            // A box's inverse inertia, M(b² + c²)/3 … about its axes, turned with it.
            const T mass = T(700);
            const Vec3<T> e2{c.half.x * c.half.x, c.half.y * c.half.y, c.half.z * c.half.z};
            const Mat3<T> inv_local = Mat3<T>::diagonal(
                Vec3<T>{T(3) / (mass * (e2.y + e2.z)), T(3) / (mass * (e2.x + e2.z)), T(3) / (mass * (e2.x + e2.y))});
            const Mat3<T> rot = to_matrix(q);
            const detail::SolverMass<T> solver_mass{T(1) / mass, rot * inv_local * transpose(rot)};
            const auto rows = corner_rows(c.half, mass, solver_mass.inv_inertia, q);
            const T lambda = detail::support_stiffness(rows.data(), rows.size(), solver_mass);
            CAPTURE(c.half);
            CAPTURE(lambda);
            // 24 power iterations: the estimate is within (λ₂/λ₁)^48 of λ₁ from below, 3e-5 here.
            CHECK(double(lambda) <= c.expected * (1 + 1e-6));
            CHECK(near(double(lambda), c.expected, 1e-4));
        }
}

TEST_CASE_TEMPLATE("rows that cannot load the body give no stiffness, not a NaN", T, float, double) {
    const detail::SolverMass<T> mass{T(1), Mat3<T>::identity()};
    const detail::SupportRow<T> zero{{}, {}, T(0)};
    CHECK(detail::support_stiffness(&zero, 1, mass) == T(0));
    CHECK(detail::support_stiffness<T>(nullptr, 0, mass) == T(0));
    const detail::SupportRow<T> one{Vec3<T>::unit_y(), {}, T(1)};
    CHECK(near(detail::support_stiffness(&one, 1, mass), T(1)));  // a ball on the ground bounces at ω
}

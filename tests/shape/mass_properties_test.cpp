// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Mass properties against closed forms, and the closed forms of the round shapes against an
// independent numerical integration over thin discs along the axis.
#include "support/approx.hpp"

#include <xeno/shape/polyhedra.hpp>
#include <xeno/shape/shape.hpp>

#include <functional>

using namespace xeno;
using xeno::test::near;

namespace {

// Solid of revolution about y with radius profile r(y) on [y0, y1], density rho: Simpson's rule
// over discs. Returns {mass, centre y, Iy, Ix about the centre}.
struct Revolved {
    double mass, centre, axial, transverse;
};
Revolved integrate_revolution(const std::function<double(double)>& radius, double y0, double y1, double rho) {
    const int n = 20000;
    const double h = (y1 - y0) / n, pi = 3.14159265358979323846;
    double m = 0, my = 0, iy = 0, ix0 = 0;
    for (int i = 0; i <= n; ++i) {
        const double y = y0 + i * h, r = radius(y);
        const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        const double area = pi * r * r;
        m += w * area;
        my += w * area * y;
        iy += w * pi * r * r * r * r / 2;                    // disc about its axis
        ix0 += w * (pi * r * r * r * r / 4 + area * y * y);  // disc about x through y = 0
    }
    const double s = rho * h / 3;
    Revolved out{m * s, my / m, iy * s, 0};
    out.transverse = ix0 * s - out.mass * out.centre * out.centre;
    return out;
}

template <class T>
void check_against(const MassProperties<T>& m, const Revolved& r) {
    const T eps = std::is_same_v<T, float> ? T(1e-4) : T(1e-6);
    CHECK(near(m.mass, T(r.mass), eps));
    CHECK(near(m.center.y, T(r.centre), eps));
    CHECK(near(m.inertia[1].y, T(r.axial), eps));
    CHECK(near(m.inertia[0].x, T(r.transverse), eps));
    CHECK(near(m.inertia[2].z, T(r.transverse), eps));
    CHECK(std::abs(m.inertia[0].y) < eps * m.inertia[0].x);
}

}  // namespace

TEST_CASE_TEMPLATE("box mass properties match m/12 (b² + c²)", T, float, double) {
    const MassProperties<T> m = mass_properties(Box<T>(T(1), T(2), T(3)), T(500));
    CHECK(near(m.mass, T(500 * 48)));
    CHECK(m.center == Vec3<T>::zero());
    CHECK(near(m.inertia[0].x, T(500 * 48) / 12 * (16 + 36)));
    CHECK(near(m.inertia[1].y, T(500 * 48) / 12 * (4 + 36)));
    CHECK(near(m.inertia[2].z, T(500 * 48) / 12 * (4 + 16)));
    // The polyhedron path agrees with the closed form.
    const MassProperties<T> p = mass_properties(make_box_polyhedron(Vec3<T>{T(1), T(2), T(3)}), T(500));
    CHECK(near(p.mass, m.mass));
    CHECK(near(p.center, Vec3<T>::zero()));
    CHECK(near(p.inertia, m.inertia));
}

TEST_CASE_TEMPLATE("sphere mass properties match 2/5 m r²", T, float, double) {
    const MassProperties<T> m = mass_properties(Sphere<T>(T(0.5)), T(1000));
    const T mass = T(1000) * T(4) / T(3) * ScalarTraits<T>::pi * T(0.125);
    CHECK(near(m.mass, mass));
    CHECK(near(m.inertia, Mat3<T>::identity() * (T(0.4) * mass * T(0.25))));
    check_against(m, integrate_revolution([](double y) { return std::sqrt(std::max(0.0, 0.25 - y * y)); }, -0.5, 0.5, 1000));
}

TEST_CASE_TEMPLATE("cylinder, cone and capsule closed forms match integration over discs", T, float, double) {
    check_against(mass_properties(Cylinder<T>(T(0.3), T(0.8)), T(2)),
                  integrate_revolution([](double) { return 0.3; }, -0.8, 0.8, 2));
    // Cone: base at -H/4, apex at 3H/4, so the centre of mass comes out at 0.
    check_against(mass_properties(Cone<T>(T(0.5), T(2)), T(3)),
                  integrate_revolution([](double y) { return 0.5 * (1.5 - y) / 2.0; }, -0.5, 1.5, 3));
    const double r = 0.25, h = 0.6;
    check_against(mass_properties(Capsule<T>(T(r), T(h)), T(7)), integrate_revolution(
                                                                     [=](double y) {
                                                                         const double over = std::max(0.0, std::abs(y) - h);
                                                                         return std::sqrt(std::max(0.0, r * r - over * over));
                                                                     },
                                                                     -h - r, h + r, 7));
}

TEST_CASE_TEMPLATE("regular tetrahedron has isotropic inertia m a²/20", T, float, double) {
    const T a = T(1.5);
    const MassProperties<T> m = mass_properties(make_tetrahedron(a), T(10));
    const T mass = T(10) * a * a * a / (T(6) * std::sqrt(T(2)));
    CHECK(near(m.mass, mass));
    CHECK(near(m.center, Vec3<T>::zero()));
    CHECK(near(m.inertia, Mat3<T>::identity() * (mass * a * a / T(20))));
}

TEST_CASE_TEMPLATE("a many-sided prism converges to the cylinder", T, float, double) {
    const int n = 512;
    const MassProperties<T> prism = mass_properties(make_regular_prism(n, T(0.4), T(0.7)), T(1));
    const MassProperties<T> cylinder = mass_properties(Cylinder<T>(T(0.4), T(0.7)), T(1));
    CHECK(near(prism.mass, cylinder.mass, T(1e-3)));
    CHECK(near(prism.inertia, cylinder.inertia, T(1e-3)));
}

TEST_CASE_TEMPLATE("non-positive density is rejected", T, float, double) {
    CHECK_THROWS_AS(mass_properties(Box<T>(T(1), T(1), T(1)), T(0)), InvalidArgument);
    CHECK_THROWS_AS(mass_properties(Sphere<T>(T(1)), T(-3)), InvalidArgument);
    CHECK_THROWS_AS(mass_properties(Shape<T>(Sphere<T>(T(1))), std::numeric_limits<T>::quiet_NaN()), InvalidArgument);
}

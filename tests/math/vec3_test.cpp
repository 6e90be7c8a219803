// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
#include "support/approx.hpp"

#include <xeno/math/vec3.hpp>

using namespace xeno;
using xeno::test::near;
using xeno::test::tol;

TEST_CASE_TEMPLATE("vec3 arithmetic matches hand-computed values", T, float, double) {
    const Vec3<T> a{T(1), T(2), T(3)}, b{T(-4), T(5), T(0.5)};
    CHECK(a + b == Vec3<T>{T(-3), T(7), T(3.5)});
    CHECK(a - b == Vec3<T>{T(5), T(-3), T(2.5)});
    CHECK(-a == Vec3<T>{T(-1), T(-2), T(-3)});
    CHECK(a * T(2) == Vec3<T>{T(2), T(4), T(6)});
    CHECK(T(2) * a == a * T(2));
    CHECK(a / T(2) == Vec3<T>{T(0.5), T(1), T(1.5)});
    CHECK(dot(a, b) == T(-4 + 10 + 1.5));
    CHECK(cross(a, b) == Vec3<T>{T(2 * 0.5 - 3 * 5), T(3 * -4 - 1 * 0.5), T(1 * 5 - 2 * -4)});
    CHECK(hadamard(a, b) == Vec3<T>{T(-4), T(10), T(1.5)});
    CHECK(min(a, b) == Vec3<T>{T(-4), T(2), T(0.5)});
    CHECK(max(a, b) == Vec3<T>{T(1), T(5), T(3)});
    CHECK(min_component(b) == T(-4));
    CHECK(max_component(b) == T(5));
    CHECK(max_axis(a) == 2);
    Vec3<T> c = a;
    c += b;
    c -= b;
    c *= T(3);
    c /= T(3);
    CHECK(near(c, a));
}

TEST_CASE_TEMPLATE("vec3 components are reachable by index", T, float, double) {
    Vec3<T> v{T(7), T(8), T(9)};
    CHECK(v[0] == T(7));
    CHECK(v[1] == T(8));
    CHECK(v[2] == T(9));
    v[1] = T(-1);
    CHECK(v.y == T(-1));
    for (int i = 0; i < 3; ++i) CHECK(Vec3<T>::axis(i)[i] == T(1));
}

TEST_CASE_TEMPLATE("cross product is orthogonal and right-handed", T, float, double) {
    CHECK(cross(Vec3<T>::unit_x(), Vec3<T>::unit_y()) == Vec3<T>::unit_z());
    CHECK(cross(Vec3<T>::unit_y(), Vec3<T>::unit_z()) == Vec3<T>::unit_x());
    const Vec3<T> a{T(0.3), T(-1.2), T(2)}, b{T(4), T(0.1), T(-0.7)};
    const Vec3<T> c = cross(a, b);
    CHECK(near(dot(c, a), T(0)));
    CHECK(near(dot(c, b), T(0)));
    CHECK(near(triple(a, b, c), length_squared(c)));
}

TEST_CASE_TEMPLATE("normalise gives unit length and the safe variant handles zero", T, float, double) {
    const Vec3<T> v{T(3), T(4), T(12)};
    CHECK(near(length(v), T(13)));
    CHECK(near(length(normalized(v)), T(1)));
    CHECK(near(normalized(v), Vec3<T>{T(3) / 13, T(4) / 13, T(12) / 13}));
    CHECK_FALSE(try_normalized(Vec3<T>::zero()).has_value());
    CHECK(normalized_or(Vec3<T>::zero(), Vec3<T>::unit_y()) == Vec3<T>::unit_y());
    const T inf = std::numeric_limits<T>::infinity();
    CHECK_FALSE(try_normalized(Vec3<T>{inf, T(0), T(0)}).has_value());
    Vec3<T> z = Vec3<T>::zero();
    z.normalize();  // stays zero, no NaN
    CHECK(z == Vec3<T>::zero());
    Vec3<T> w = v;
    w.normalize();
    CHECK(near(length(w), T(1)));
    // Very small and very large vectors still normalise.
    CHECK(near(length(normalized(Vec3<T>{T(1e-18), T(0), T(1e-18)})), T(1)));
    CHECK(near(length(normalized(Vec3<T>{T(1e18), T(1e18), T(0)})), T(1)));
}

TEST_CASE_TEMPLATE("any_perpendicular is a unit vector orthogonal to n", T, float, double) {
    for (int i = 0; i < 200; ++i) {
        const T a = T(i) * T(0.37), b = T(i) * T(0.11);
        const Vec3<T> n{std::cos(a) * std::sin(b), std::cos(b), std::sin(a) * std::sin(b)};
        const Vec3<T> p = any_perpendicular(normalized(n));
        CHECK(near(length(p), T(1)));
        CHECK(std::abs(dot(p, normalized(n))) < tol<T>());
    }
    CHECK(near(length(any_perpendicular(Vec3<T>{T(0), T(0), T(-1)})), T(1)));
}

TEST_CASE("vec3 converts between precisions only explicitly") {
    const f64::Vec3 d{1.0 / 3.0, 2.0, -5.5};
    const f32::Vec3 f(d);
    CHECK(f.x == static_cast<float>(1.0 / 3.0));
    CHECK(d.cast<float>() == f);
    static_assert(!std::is_convertible_v<f64::Vec3, f32::Vec3>, "precision never changes silently");
    static_assert(std::is_constructible_v<f32::Vec3, f64::Vec3>);
}

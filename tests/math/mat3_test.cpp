// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
#include "support/approx.hpp"

#include <xeno/math/mat3.hpp>

using namespace xeno;
using xeno::test::near;

TEST_CASE_TEMPLATE("mat3 product, transpose and determinant match hand-computed values", T, float, double) {
    const Mat3<T> a{{T(1), T(2), T(3)}, {T(0), T(1), T(4)}, {T(5), T(6), T(0)}};
    const Mat3<T> b{{T(2), T(0), T(0)}, {T(1), T(1), T(0)}, {T(0), T(0), T(3)}};
    const Mat3<T> ab{{T(4), T(2), T(9)}, {T(1), T(1), T(12)}, {T(16), T(6), T(0)}};
    CHECK(a * b == ab);
    CHECK(transpose(a) == Mat3<T>{{T(1), T(0), T(5)}, {T(2), T(1), T(6)}, {T(3), T(4), T(0)}});
    CHECK(determinant(a) == T(1));
    CHECK(determinant(b) == T(6));
    CHECK(near(determinant(a * b), determinant(a) * determinant(b)));
    const Vec3<T> v{T(1), T(-1), T(2)};
    CHECK(a * v == Vec3<T>{T(5), T(7), T(-1)});
    CHECK(transform(a, v) == a * v);
    CHECK(transposed_transform(a, v) == transpose(a) * v);
    CHECK(trace(a) == T(2));
    CHECK(a.column(2) == Vec3<T>{T(3), T(4), T(0)});
    CHECK(a + b - b == a);
    CHECK(a * T(2) == T(2) * a);
}

TEST_CASE_TEMPLATE("inverse times matrix is the identity", T, float, double) {
    const Mat3<T> a{{T(1), T(2), T(3)}, {T(0), T(1), T(4)}, {T(5), T(6), T(0)}};
    const auto inv = try_inverse(a);
    REQUIRE(inv.has_value());
    CHECK(near(*inv * a, Mat3<T>::identity()));
    CHECK(near(a * *inv, Mat3<T>::identity()));
    CHECK(near((*inv)[0], Vec3<T>{T(-24), T(18), T(5)}));
}

TEST_CASE_TEMPLATE("a singular matrix is reported, not divided by zero", T, float, double) {
    const Mat3<T> rank2{{T(1), T(2), T(3)}, {T(2), T(4), T(6)}, {T(0), T(1), T(1)}};
    CHECK_FALSE(try_inverse(rank2).has_value());
    CHECK_FALSE(try_inverse(Mat3<T>::zero()).has_value());
    // Rows that are dependent up to round-off: the determinant is tiny relative to the rows.
    const Mat3<T> nearly{{T(1), T(0), T(0)}, {T(0), T(1), T(0)}, {T(1), T(1), T(1e-17)}};
    CHECK_FALSE(try_inverse(nearly).has_value());
    // Badly scaled but independent rows invert fine.
    const Mat3<T> scaled{{T(1e6), T(0), T(0)}, {T(0), T(1e6), T(0)}, {T(0), T(0), T(1e-12)}};
    CHECK(try_inverse(scaled).has_value());
    // Small but well-conditioned is fine.
    CHECK(try_inverse(Mat3<T>::identity() * T(1e-6)).has_value());
}

TEST_CASE_TEMPLATE("skew matrix reproduces the cross product, outer and diagonal", T, float, double) {
    const Vec3<T> a{T(0.5), T(-2), T(3)}, b{T(1), T(4), T(-1)};
    CHECK(near(skew(a) * b, cross(a, b)));
    CHECK(near(transpose(skew(a)), skew(a) * T(-1)));
    const Mat3<T> o = outer(a, b);
    CHECK(near(o * b, a * dot(b, b)));
    CHECK(o[1].z == a.y * b.z);
    CHECK(Mat3<T>::diagonal({T(1), T(2), T(3)}) * b == Vec3<T>{T(1), T(8), T(-3)});
    CHECK(Mat3<T>::from_columns(a, b, a).column(1) == b);
    CHECK(Mat3<T>::diagonal({T(4), T(5), T(6)}).diagonal_vector() == Vec3<T>{T(4), T(5), T(6)});
}

TEST_CASE_TEMPLATE("the inverse of a matrix with huge or tiny entries neither overflows nor underflows", T, float, double) {
    // Regression: a float inertia of 4e14 kg·m² (a 300 m cube) has a determinant of 7e43, beyond
    // float's range, and was reported singular (found by xeno_scale_sweep).
    for (const T s : {T(4e14), T(1e30), T(1e-30)}) {
        const Mat3<T> m = Mat3<T>::diagonal({T(1), T(2), T(3)}) * s;
        const auto inv = try_inverse(m);
        REQUIRE(inv.has_value());
        CAPTURE(s);
        CHECK(near(*inv * m, Mat3<T>::identity(), T(1e-5)));
    }
}

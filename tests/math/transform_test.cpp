// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
#include "support/approx.hpp"

#include "scenes/random.hpp"

#include <xeno/math/aabb.hpp>
#include <xeno/math/mat4.hpp>

using namespace xeno;
using xeno::test::near;

TEST_CASE_TEMPLATE("transform maps points and directions and its inverse undoes it", T, float, double) {
    const Transform<T> t{{T(1), T(2), T(3)}, Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 2)};
    CHECK(near(t.apply(Vec3<T>::unit_x()), Vec3<T>{T(1), T(3), T(3)}));
    CHECK(near(t.apply_direction(Vec3<T>::unit_x()), Vec3<T>::unit_y()));
    CHECK(near(t.inverse_apply(t.apply(Vec3<T>{T(4), T(5), T(6)})), Vec3<T>{T(4), T(5), T(6)}));
    CHECK(near(t.inverse_apply_direction(Vec3<T>::unit_y()), Vec3<T>::unit_x()));
    scenes::Random rng(5);
    for (int k = 0; k < 100; ++k) {
        const Transform<T> a{rng.in_box(Vec3<T>{T(5), T(5), T(5)}), rng.rotation<T>()};
        const Transform<T> b{rng.in_box(Vec3<T>{T(5), T(5), T(5)}), rng.rotation<T>()};
        const Vec3<T> p = rng.in_box(Vec3<T>{T(2), T(2), T(2)});
        CHECK(near(inverse(a).apply(a.apply(p)), p));
        CHECK(near((a * b).apply(p), a.apply(b.apply(p))));
        CHECK(near(transform_point(Mat4<T>::from_transform(a) * Mat4<T>::from_transform(b), p), a.apply(b.apply(p))));
    }
    CHECK(is_finite(t));
    CHECK_FALSE(is_finite(Transform<T>{{std::numeric_limits<T>::quiet_NaN(), T(0), T(0)}, Quat<T>::identity()}));
}

TEST_CASE_TEMPLATE("mat4 separates point and direction transforms and inverts", T, float, double) {
    const Mat3<T> r = to_matrix(Quat<T>::from_axis_angle(Vec3<T>::unit_y(), T(0.7)));
    const Vec3<T> t{T(-1), T(4), T(2)};
    const Mat4<T> m = Mat4<T>::from_rotation_translation(r, t);
    const Vec3<T> p{T(1), T(1), T(1)};
    CHECK(near(transform_point(m, p), r * p + t));
    CHECK(near(transform_direction(m, p), r * p));
    const auto inv = try_inverse(m);
    REQUIRE(inv.has_value());
    CHECK(near(transform_point(*inv, transform_point(m, p)), p));
    CHECK(near(transform_point(*inv * m, p), p));
    CHECK(m.at(3, 3) == T(1));
    CHECK(m.at(3, 0) == T(0));
    CHECK(m.at(1, 3) == T(4));
    T column_major[16];
    m.to_column_major(column_major);
    CHECK(column_major[12] == T(-1));  // translation x in the fourth column
    CHECK(column_major[15] == T(1));
    CHECK(column_major[1] == r[1].x);
    const Mat4<T> singular = Mat4<T>::from_rotation_translation(Mat3<T>::zero(), t);
    CHECK_FALSE(try_inverse(singular).has_value());
}

TEST_CASE_TEMPLATE("aabb merges, overlaps and expands", T, float, double) {
    Aabb<T> box;
    CHECK(box.empty());
    box.merge(Vec3<T>{T(1), T(2), T(3)});
    box.merge(Vec3<T>{T(-1), T(0), T(5)});
    CHECK_FALSE(box.empty());
    CHECK(box.min == Vec3<T>{T(-1), T(0), T(3)});
    CHECK(box.max == Vec3<T>{T(1), T(2), T(5)});
    CHECK(box.center() == Vec3<T>{T(0), T(1), T(4)});
    CHECK(box.half_extents() == Vec3<T>{T(1), T(1), T(1)});
    CHECK(box.surface_area() == T(24));
    const Aabb<T> other = Aabb<T>::from_center({T(2), T(1), T(4)}, {T(1), T(1), T(1)});
    CHECK(overlaps(box, other));  // touching at x = 1 counts
    CHECK_FALSE(overlaps(box, Aabb<T>::from_center({T(2.01), T(1), T(4)}, {T(1), T(1), T(1)})));
    CHECK(box.expanded(T(0.5)).contains(Vec3<T>{T(1.4), T(2.4), T(5.4)}));
    CHECK(merged(box, other).contains(box));
    CHECK(merged(box, other).contains(other));
    CHECK_FALSE(box.contains(other));
}

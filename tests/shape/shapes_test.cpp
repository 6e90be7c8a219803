// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Support functions, supporting faces and bounds of every shape, checked against brute force over
// points sampled on the surface.
#include "support/approx.hpp"

#include "scenes/random.hpp"

#include <xeno/shape/polyhedra.hpp>
#include <xeno/shape/shape.hpp>

#include <vector>

using namespace xeno;
using xeno::test::near;

namespace {

// Points on the surface of each implicit shape, for brute-force support values.
template <class T>
std::vector<Vec3<T>> surface_samples(const Shape<T>& shape, scenes::Random& rng, int n) {
    std::vector<Vec3<T>> points;
    for (int i = 0; i < n; ++i) {
        // A surface point is the support point of some direction: sample directions densely.
        points.push_back(support(shape, rng.direction<T>()));
    }
    return points;
}

template <class T>
std::vector<Shape<T>> all_shapes() {
    return {Sphere<T>(T(0.7)),
            Box<T>(T(0.5), T(1), T(0.25)),
            Capsule<T>(T(0.3), T(0.6)),
            Cylinder<T>(T(0.4), T(0.9)),
            Cone<T>(T(0.5), T(1.2)),
            make_triangular_prism(T(0.5), T(0.8), T(0.4)),
            make_regular_prism(7, T(0.6), T(0.3))};
}

}  // namespace

TEST_CASE_TEMPLATE("support is the farthest point along every direction", T, float, double) {
    scenes::Random rng(11);
    for (const Shape<T>& shape : all_shapes<T>()) {
        CAPTURE(shape_name(shape));
        const std::vector<Vec3<T>> samples = surface_samples(shape, rng, 4000);
        for (int k = 0; k < 300; ++k) {
            const Vec3<T> d = rng.direction<T>() * rng.uniform(T(0.01), T(100));
            const T value = dot(support(shape, d), d);
            T best = -ScalarTraits<T>::infinity;
            for (const Vec3<T>& p : samples) best = std::max(best, dot(p, d));
            // No sampled surface point beats the support (up to round-off).
            CHECK(value >= best - T(1e-4) * length(d));
        }
    }
}

TEST_CASE_TEMPLATE("support points lie on the analytic surface", T, float, double) {
    scenes::Random rng(12);
    const Sphere<T> sphere(T(0.7));
    const Capsule<T> capsule(T(0.3), T(0.6));
    const Cylinder<T> cylinder(T(0.4), T(0.9));
    const Cone<T> cone(T(0.5), T(1.2));
    for (int k = 0; k < 500; ++k) {
        const Vec3<T> d = rng.direction<T>();
        CHECK(near(length(sphere.support(d)), T(0.7)));
        const Vec3<T> c = capsule.support(d);
        const T along = clamp(c.y, T(-0.6), T(0.6));
        CHECK(near(length(c - Vec3<T>{T(0), along, T(0)}), T(0.3)));
        const Vec3<T> y = cylinder.support(d);
        CHECK(near(std::abs(y.y), T(0.9)));
        CHECK(std::sqrt(y.x * y.x + y.z * y.z) <= T(0.4) + T(1e-5));
        const Vec3<T> o = cone.support(d);
        const bool apex = near(o, Vec3<T>{T(0), T(0.9), T(0)});
        const bool rim = near(o.y, T(-0.3)) && near(std::sqrt(o.x * o.x + o.z * o.z), T(0.5));
        CHECK((apex || rim));
    }
}

TEST_CASE_TEMPLATE("box support selects corners by sign and ties go to plus", T, float, double) {
    const Box<T> box(T(1), T(2), T(3));
    CHECK(box.support({T(1), T(-1), T(1)}) == Vec3<T>{T(1), T(-2), T(3)});
    CHECK(box.support({T(0), T(0), T(0)}) == Vec3<T>{T(1), T(2), T(3)});
    CHECK(box.support({T(-1e-30), T(0), T(-5)}) == Vec3<T>{T(-1), T(2), T(-3)});
}

TEST_CASE_TEMPLATE("zero and huge directions give finite support points", T, float, double) {
    for (const Shape<T>& shape : all_shapes<T>()) {
        CAPTURE(shape_name(shape));
        for (const Vec3<T>& d : {Vec3<T>::zero(), Vec3<T>{T(1e-30), T(0), T(0)}, Vec3<T>{T(1e30), T(-1e30), T(1e30)},
                                 Vec3<T>{T(0), T(1e-20), T(0)}}) {
            CHECK(is_finite(support(shape, d)));
            const SupportFace<T> face = support_face(shape, d);
            CHECK(face.count >= 1);
            CHECK(is_finite(face.normal));
            for (int i = 0; i < face.count; ++i) CHECK(is_finite(face[i]));
        }
    }
}

TEST_CASE_TEMPLATE("local bounds and bounding radius hold every support point", T, float, double) {
    scenes::Random rng(13);
    for (const Shape<T>& shape : all_shapes<T>()) {
        CAPTURE(shape_name(shape));
        const Aabb<T> box = local_bounds(shape).expanded(T(1e-5));
        const T radius = bounding_radius(shape) + T(1e-5);
        T max_distance = 0;
        for (int k = 0; k < 2000; ++k) {
            const Vec3<T> p = support(shape, rng.direction<T>());
            CHECK(box.contains(p));
            max_distance = std::max(max_distance, length(p));
        }
        CHECK(max_distance <= radius);
        CHECK(max_distance >= T(0.9) * (radius - T(1e-5)));  // and they are not loose
        // Tight on each axis: the support along ±axis reaches the box.
        for (int axis = 0; axis < 3; ++axis) {
            CHECK(near(support(shape, Vec3<T>::axis(axis))[axis], local_bounds(shape).max[axis], T(1e-4)));
            CHECK(near(support(shape, -Vec3<T>::axis(axis))[axis], local_bounds(shape).min[axis], T(1e-4)));
        }
    }
}

TEST_CASE_TEMPLATE("world bounds contain the placed shape", T, float, double) {
    scenes::Random rng(14);
    for (const Shape<T>& shape : all_shapes<T>()) {
        CAPTURE(shape_name(shape));
        for (int k = 0; k < 50; ++k) {
            const Transform<T> t{rng.in_box(Vec3<T>{T(10), T(10), T(10)}), rng.rotation<T>()};
            const Aabb<T> box = world_bounds(shape, t).expanded(T(1e-4));
            for (int axis = 0; axis < 3; ++axis) {
                for (const T sign : {T(1), T(-1)}) {
                    const Vec3<T> d = Vec3<T>::axis(axis) * sign;
                    const Vec3<T> far_point = t.apply(support(shape, t.inverse_apply_direction(d)));
                    CHECK(box.contains(far_point));
                    // Exact for the shapes it claims: the face touches the support point.
                    if (shape.index() <= 3) CHECK(near(far_point[axis], sign > 0 ? box.max[axis] : box.min[axis], T(1e-3)));
                }
            }
        }
    }
}

TEST_CASE_TEMPLATE("supporting faces are the flat parts most aligned with the direction", T, float, double) {
    const Box<T> box(T(1), T(2), T(3));
    const SupportFace<T> top = box.support_face({T(0.1), T(1), T(-0.2)});
    CHECK(top.count == 4);
    CHECK(top.normal == Vec3<T>::unit_y());
    for (int i = 0; i < 4; ++i) CHECK(top[i].y == T(2));
    // Counter-clockwise from outside: Newell normal agrees with the face normal.
    Vec3<T> newell{};
    for (int i = 0; i < top.count; ++i) newell += cross(top[i], top[(i + 1) % top.count]);
    CHECK(dot(newell, top.normal) > T(0));

    const Cylinder<T> cylinder(T(0.5), T(1));
    const SupportFace<T> cap = cylinder.support_face({T(0.2), T(-1), T(0)});
    CHECK(cap.count == Cylinder<T>::cap_segments);
    CHECK(cap.normal == Vec3<T>{T(0), T(-1), T(0)});
    newell = {};
    for (int i = 0; i < cap.count; ++i) newell += cross(cap[i], cap[(i + 1) % cap.count]);
    CHECK(dot(newell, cap.normal) > T(0));
    const SupportFace<T> side = cylinder.support_face({T(1), T(0.2), T(0)});
    CHECK(side.count == 2);
    CHECK(near(side[0], Vec3<T>{T(0.5), T(1), T(0)}));
    CHECK(near(side[1], Vec3<T>{T(0.5), T(-1), T(0)}));

    const Cone<T> cone(T(0.5), T(2));
    const SupportFace<T> base = cone.support_face({T(0), T(-1), T(0.1)});
    CHECK(base.count == Cone<T>::base_segments);
    newell = {};
    for (int i = 0; i < base.count; ++i) newell += cross(base[i], base[(i + 1) % base.count]);
    CHECK(dot(newell, base.normal) > T(0));
    const Vec3<T> side_normal = normalized(Vec3<T>{T(2), T(0.5), T(0)});
    const SupportFace<T> slant = cone.support_face(side_normal);
    CHECK(slant.count == 2);
    CHECK(near(slant[0], cone.apex()));
    CHECK(cone.support_face(Vec3<T>::unit_y()).count == 1);

    const Capsule<T> capsule(T(0.3), T(1));
    CHECK(capsule.support_face({T(0), T(0), T(-1)}).count == 2);
    CHECK(capsule.support_face({T(0), T(1), T(-1)}).count == 1);
    CHECK(Sphere<T>(T(1)).support_face({T(0), T(0), T(2)}).count == 1);
    CHECK(near(Sphere<T>(T(1)).support_face({T(0), T(0), T(2)})[0], Vec3<T>::unit_z()));
}

TEST_CASE_TEMPLATE("polyhedron support face contains the support vertex and winds outward", T, float, double) {
    scenes::Random rng(15);
    const ConvexPolyhedron<T> prism = make_regular_prism(9, T(1), T(0.5));
    for (int k = 0; k < 200; ++k) {
        const Vec3<T> d = rng.direction<T>();
        const SupportFace<T> face = prism.support_face(d);
        REQUIRE(face.count >= 3);
        CHECK(dot(face.normal, d) > T(0));
        const T best = dot(prism.support(d), d);
        T face_best = -ScalarTraits<T>::infinity;
        Vec3<T> newell{};
        for (int i = 0; i < face.count; ++i) {
            face_best = std::max(face_best, dot(face[i], d));
            newell += cross(face[i], face[(i + 1) % face.count]);
        }
        CHECK(near(face_best, best));
        CHECK(dot(newell, face.normal) > T(0));
    }
}

TEST_CASE_TEMPLATE("the shape variant dispatches to the held shape", T, float, double) {
    const Shape<T> s = Capsule<T>(T(0.25), T(1));
    CHECK(std::string(shape_name(s)) == "capsule");
    CHECK(near(bounding_radius(s), T(1.25)));
    CHECK(near(support(s, Vec3<T>::unit_y()), Vec3<T>{T(0), T(1.25), T(0)}));
    CHECK(interior_point(s) == Vec3<T>::zero());
    CHECK(near(volume(s), ScalarTraits<T>::pi * T(0.0625) * (T(2) + T(1) / T(3))));
}

TEST_CASE_TEMPLATE("shapes reject non-positive and non-finite sizes", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    CHECK_THROWS_AS(Sphere<T>(T(0)), InvalidArgument);
    CHECK_THROWS_AS(Sphere<T>{nan}, InvalidArgument);
    CHECK_THROWS_AS(Box<T>(T(1), inf, T(1)), InvalidArgument);
    CHECK_THROWS_AS(Capsule<T>(T(-1), T(1)), InvalidArgument);
    CHECK_THROWS_AS(Capsule<T>(T(1), T(-1)), InvalidArgument);
    CHECK_NOTHROW(Capsule<T>(T(1), T(0)));
    CHECK_THROWS_AS(Cylinder<T>(T(1), T(0)), InvalidArgument);
    CHECK_THROWS_AS(Cone<T>(T(0), T(1)), InvalidArgument);
    CHECK_THROWS_AS(Cone<T>(T(1), nan), InvalidArgument);
    CHECK_THROWS_AS(make_regular_prism(2, T(1), T(1)), InvalidArgument);
    CHECK_THROWS_AS(make_tetrahedron(T(0)), InvalidArgument);
    CHECK_THROWS_AS(make_triangular_prism(T(1), T(-1), T(1)), InvalidArgument);
    CHECK_THROWS_AS(make_box_polyhedron(Vec3<T>{T(1), T(1), T(0)}), InvalidArgument);
}

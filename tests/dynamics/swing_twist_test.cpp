// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The swing-twist (ragdoll) joint against closed forms: a rod held out sideways falls until its
// cone stops it and then rests on it, the joint carrying the weight and the moment (L/2)·m·g·cos θ;
// a hanging rod spun about its axis stops at its twist limit; inside its limits it swings as freely
// as a ball joint. Default settings and sleeping off, float and double.
#include "support/sim.hpp"

#include <xeno/dynamics/world.hpp>

#include <doctest/doctest.h>

#include <cmath>

using namespace xeno;

namespace {

template <class T>
BodyId anchor_at(World<T>& w, const Vec3<T>& at) {
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = at;
    return w.create_body(Box<T>(T(0.05), T(0.05), T(0.05)), d);
}

/// A 1 m rod along x (a thin box) whose left end is at `end`.
template <class T>
BodyId rod_from(World<T>& w, const Vec3<T>& end, const Vec3<T>& direction) {
    BodyDef<T> d;
    d.position = end + direction * T(0.5);
    d.orientation = Quat<T>::from_to(Vec3<T>::unit_x(), direction);
    return w.create_body(Box<T>(T(0.5), T(0.05), T(0.05)), d);
}

}  // namespace

TEST_CASE_TEMPLATE("a rod held out sideways swings down to its cone and rests on it, carrying (L/2) m g cos(theta)", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const Vec3<T> pivot{T(0), T(3), T(0)};
    const BodyId wall = anchor_at(w, pivot);
    const BodyId rod = rod_from(w, pivot, Vec3<T>::unit_x());
    const T cone = radians(T(30));
    const JointId joint =
        w.create_joint(JointDef<T>::swing_twist(wall, rod, pivot, Vec3<T>::unit_x(), cone, radians(T(-10)), radians(T(10))));
    T widest = T(0);
    test::simulate(w, T(3), [&](int) {
        const Vec3<T> u = w.body(rod).world_vector(Vec3<T>::unit_x());
        widest = std::max(widest, std::atan2(length(cross(Vec3<T>::unit_x(), u)), u.x));
    });
    CHECK(widest < cone + radians(T(1)));  // never more than 1° past the cone
    const Vec3<T> u = w.body(rod).world_vector(Vec3<T>::unit_x());
    const T settled = std::atan2(-u.y, u.x);  // below the horizontal, in the x–y plane
    CHECK(std::abs(settled - cone) < radians(T(0.5)));
    CHECK(std::abs(u.z) < T(1e-3));
    // At rest on the cone: the joint holds the weight up and its torque cancels the moment of that
    // force about the rod's centre, (L/2) m g cos θ about z.
    const T weight = w.body(rod).mass() * T(9.81);
    const JointReaction<T> r = w.joint_reaction(joint);
    CHECK(r.force.y == doctest::Approx(static_cast<double>(weight)).epsilon(0.01));
    CHECK(r.torque.z == doctest::Approx(static_cast<double>(T(0.5) * weight * std::cos(cone))).epsilon(0.02));
}

TEST_CASE_TEMPLATE("a hanging rod spun about its own axis stops at its twist limits", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const Vec3<T> pivot{T(0), T(3), T(0)};
    const BodyId ceiling = anchor_at(w, pivot);
    const Vec3<T> down{T(0), T(-1), T(0)};
    const BodyId rod = rod_from(w, pivot, down);
    const T lower = radians(T(-20)), upper = radians(T(45));
    w.create_joint(JointDef<T>::swing_twist(ceiling, rod, pivot, down, radians(T(20)), lower, upper));
    // The rod's own y axis (across it) measures the twist about the vertical.
    const auto twist = [&] {
        const Vec3<T> across = w.body(rod).world_vector(Vec3<T>::unit_y());
        return std::atan2(-across.z, across.x);  // angle about +y from the x axis, as seen from above
    };
    const T start = twist();
    T most = T(0), least = T(0);
    w.body(rod).set_angular_velocity({T(0), T(4), T(0)});  // about +y: twist about the down axis is negative...
    test::simulate(w, T(1.5), [&](int) {
        const T turned = twist() - start;
        most = std::max(most, turned), least = std::min(least, turned);
    });
    // ... so +y spin runs into the lower limit (−20° about −y is +20° about +y), and the other way the upper.
    CHECK(most < -lower + radians(T(1.5)));
    CHECK(most > -lower - radians(T(1.5)));
    w.body(rod).set_angular_velocity({T(0), T(-6), T(0)});
    test::simulate(w, T(1.5), [&](int) {
        const T turned = twist() - start;
        most = std::max(most, turned), least = std::min(least, turned);
    });
    CHECK(least > -upper - radians(T(1.5)));
    CHECK(least < -upper + radians(T(1.5)));
    // The rod still hangs from the pivot.
    CHECK(distance(w.body(rod).world_point(Vec3<T>{T(-0.5), T(0), T(0)}), pivot) < T(0.005));
}

TEST_CASE_TEMPLATE("inside its limits a swing-twist joint swings like a ball joint", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    // Two pendulums released 20° out, one on a ball joint and one on a swing-twist joint with a
    // 60° cone: they swing alike (the limits never act).
    World<T> w(C::settings());
    const Vec3<T> p1{T(0), T(3), T(0)}, p2{T(5), T(3), T(0)};
    const Vec3<T> out{std::sin(radians(T(20))), -std::cos(radians(T(20))), T(0)};
    const BodyId a1 = anchor_at(w, p1), a2 = anchor_at(w, p2);
    const BodyId r1 = rod_from(w, p1, out), r2 = rod_from(w, p2, out);
    w.create_joint(JointDef<T>::ball(a1, r1, p1));
    const JointId st = w.create_joint(
        JointDef<T>::swing_twist(a2, r2, p2, Vec3<T>{T(0), T(-1), T(0)}, radians(T(60)), radians(T(-30)), radians(T(30))));
    T gap = T(0);
    test::simulate(w, T(2),
                   [&](int) { gap = std::max(gap, length((w.body(r2).position() - p2) - (w.body(r1).position() - p1))); });
    CHECK(gap < T(1e-3));
    CHECK(w.joint(st).swing_impulse == T(0));
}

TEST_CASE_TEMPLATE("regression: a cone of pi limits no swing: a rod swings through 180 degrees at its speed", T, float, double) {
    // The cone row still ran at pi, its gap (pi - swing) / h closing to zero at 180°: a rod
    // swinging sideways at 2 rad/s stopped dead there in one step.
    WorldSettings<T> s;
    s.gravity = Vec3<T>::zero();
    World<T> w(s);
    const Vec3<T> pivot{T(0), T(2), T(0)};
    const BodyId a = anchor_at(w, pivot);
    const BodyId rod = rod_from(w, pivot, Vec3<T>{T(0), T(-1), T(0)});
    w.create_joint(JointDef<T>::swing_twist(a, rod, pivot, Vec3<T>{T(0), T(-1), T(0)}, ScalarTraits<T>::pi, T(-3), T(3)));
    w.body(rod).set_angular_velocity(Vec3<T>{T(0), T(0), T(2)});
    w.body(rod).set_linear_velocity(Vec3<T>{T(1), T(0), T(0)});  // its centre, 0.5 m out, at 2 rad/s
    T slowest = T(2);
    test::simulate(w, T(3), [&](int) { slowest = std::min(slowest, length(w.body(rod).angular_velocity())); });
    CHECK(slowest > T(1.98));  // three turns' worth of 180° crossings (was 0 at the first)
}

TEST_CASE_TEMPLATE("regression: angle limits beyond pi are refused, the world unchanged", T, float, double) {
    // The hinge angle is measured in (-pi, pi]: limits of [-4, 4] let an arm turn freely, and
    // [0, 3.5] read the angle past pi as -3.1 and threw the arm on every turn (1 rad/s became 9.2).
    World<T> w;
    const Vec3<T> at{T(0), T(2), T(0)};
    const BodyId a = anchor_at(w, at);
    const BodyId b = rod_from(w, at, Vec3<T>::unit_x());
    JointDef<T> hinge = JointDef<T>::hinge(a, b, at, Vec3<T>::unit_z());
    hinge.enable_limit = true;
    hinge.lower_angle = T(0);
    hinge.upper_angle = T(3.5);
    CHECK_THROWS_AS(w.create_joint(hinge), InvalidArgument);
    hinge.lower_angle = T(-4);
    hinge.upper_angle = T(0);
    CHECK_THROWS_AS(w.create_joint(hinge), InvalidArgument);
    CHECK_THROWS_AS(w.create_joint(JointDef<T>::swing_twist(a, b, at, Vec3<T>::unit_x(), T(1), T(-3.5), T(0))), InvalidArgument);
    hinge.lower_angle = -ScalarTraits<T>::pi;
    hinge.upper_angle = ScalarTraits<T>::pi;
    const JointId j = w.create_joint(hinge);
    CHECK(j.index == 0);  // the refused ones took no slot
    CHECK_THROWS_AS(w.set_joint_limits(j, true, T(-1), T(3.2)), InvalidArgument);
    CHECK(w.joint(j).upper_angle == ScalarTraits<T>::pi);
    // A slider's limits are lengths: any ordered pair.
    JointDef<T> slider = JointDef<T>::prismatic(a, b, at, Vec3<T>::unit_x());
    slider.enable_limit = true;
    slider.lower_translation = T(-10);
    slider.upper_translation = T(10);
    CHECK_NOTHROW(w.create_joint(slider));
}

TEST_CASE_TEMPLATE("swing-twist definitions are checked", T, float, double) {
    World<T> w;
    const BodyId a = anchor_at(w, Vec3<T>{T(0), T(2), T(0)});
    const BodyId b = rod_from(w, Vec3<T>{T(0), T(2), T(0)}, Vec3<T>::unit_x());
    const Vec3<T> at{T(0), T(2), T(0)};
    CHECK_THROWS_AS(w.create_joint(JointDef<T>::swing_twist(a, b, at, Vec3<T>::unit_x(), T(-0.1), T(0), T(0))), InvalidArgument);
    CHECK_THROWS_AS(w.create_joint(JointDef<T>::swing_twist(a, b, at, Vec3<T>::unit_x(), T(4), T(0), T(0))), InvalidArgument);
    CHECK_THROWS_AS(w.create_joint(JointDef<T>::swing_twist(a, b, at, Vec3<T>::unit_x(), T(1), T(0.5), T(0))), InvalidArgument);
    CHECK_THROWS_AS(w.create_joint(JointDef<T>::swing_twist(a, b, at, Vec3<T>::zero(), T(1), T(0), T(0))), InvalidArgument);
    const JointId j = w.create_joint(JointDef<T>::swing_twist(a, b, at, Vec3<T>::unit_x(), T(1), T(-0.5), T(0.5)));
    CHECK_THROWS_AS(w.set_joint_limits(j, false, T(-1), T(1)), InvalidArgument);
    w.set_joint_limits(j, true, T(-1), T(1));
    CHECK(w.joint(j).upper_angle == T(1));
    CHECK(w.joint(j).cone_angle == T(1));
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Changing bodies after creation (world_edit.hpp), in the default settings (sleeping on) and with
// sleeping off, float and double: each change is checked against what physics says happens next
// (free fall ½gt², a stack that stays put, a box that falls through what stopped holding it,
// masses density × volume) and against the world's own bookkeeping (events, queries, snapshots).
#include "support/sim.hpp"

#include <xeno/dynamics/snapshot.hpp>
#include <xeno/dynamics/world.hpp>
#include <xeno/dynamics/world_draw.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace xeno;

namespace {

template <class T>
const Box<T> unit_box{T(0.5), T(0.5), T(0.5)};

template <class T>
BodyId add_ground(World<T>& w) {
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(0), T(-0.5), T(0)};
    return w.create_body(Box<T>(T(20), T(0.5), T(20)), d);
}

template <class T>
BodyId add_box(World<T>& w, const Vec3<T>& at, BodyType type = BodyType::dynamic) {
    BodyDef<T> d;
    d.type = type;
    d.position = at;
    return w.create_body(unit_box<T>, d);
}

/// A static plate, `half_width` each way and `half_height` thick, centred `y` above the origin.
template <class T>
BodyId add_static_plate(World<T>& w, T y, T half_width, T half_height) {
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(0), y, T(0)};
    return w.create_body(Box<T>(half_width, half_height, half_width), d);
}

/// Events of the last step between a and b (either order).
template <class T>
std::vector<ContactEventKind> events_between(const World<T>& w, BodyId a, BodyId b) {
    std::vector<ContactEventKind> kinds;
    for (const ContactEvent<T>& e : w.contact_events())
        if ((e.a == a && e.b == b) || (e.a == b && e.b == a)) kinds.push_back(e.kind);
    return kinds;
}

/// Counts the triangles drawn.
template <class T>
struct TriangleCounter : DebugDraw<T> {
    int triangles = 0;
    void draw_triangle(const Vec3<T>&, const Vec3<T>&, const Vec3<T>&, Color) override { ++triangles; }
    void draw_line(const Vec3<T>&, const Vec3<T>&, Color) override {}
    void draw_point(const Vec3<T>&, T, Color) override {}
};

/// Free fall from rest under the default gravity for t seconds, as the semi-implicit integrator
/// takes it: within 1 % of ½ g t² at 12 substeps a step.
template <class T>
T fall_after(T t) {
    return T(0.5) * T(9.81) * t * t;
}

}  // namespace

TEST_CASE_TEMPLATE("a body switched static under a resting stack holds it, switched dynamic it falls with the stack in free fall",
                   C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    BodyDef<T> plate_def;
    plate_def.type = BodyType::dynamic;
    plate_def.position = {T(0), T(5), T(0)};
    const BodyId plate = w.create_body(Box<T>(T(2), T(0.25), T(2)), plate_def);
    w.set_gravity({T(0), T(0), T(0)});  // the plate floats while the stack is built on it
    const BodyId ground = add_ground(w);
    w.set_type(plate, BodyType::static_body);
    CHECK(w.body(plate).is_static());
    CHECK(w.body(plate).inverse_mass() == T(0));
    w.set_gravity({T(0), T(-9.81), T(0)});
    std::vector<BodyId> stack;
    for (int i = 0; i < 3; ++i) stack.push_back(add_box(w, Vec3<T>{T(0), T(5.75) + T(i), T(0)}));
    test::simulate(w, T(3));
    std::vector<Vec3<T>> rest;
    for (const BodyId id : stack) rest.push_back(w.body(id).position());
    CHECK(w.body(plate).position() == Vec3<T>{T(0), T(5), T(0)});  // static: never moved
    for (std::size_t i = 0; i < stack.size(); ++i) CHECK(std::abs(rest[i].y - (T(5.75) + T(i))) < T(0.01));

    // Dynamic again: mass = density × volume (1000 kg/m³ × 4 × 0.5 × 4 m³), and the plate and
    // its stack fall together from rest.
    w.set_type(plate, BodyType::dynamic);
    CHECK(w.body(plate).mass() == doctest::Approx(8000.0).epsilon(1e-5));
    CHECK(w.body(stack[0]).awake());  // what touches it wakes now, the rest of its island at the next step
    w.step(w.settings().fixed_time_step);
    for (const BodyId id : stack) CHECK(w.body(id).awake());
    const T t = T(0.5) + w.settings().fixed_time_step;
    test::simulate(w, T(0.5));
    const T drop = T(5) - w.body(plate).position().y;
    CHECK(drop == doctest::Approx(static_cast<double>(fall_after(t))).epsilon(0.01));
    for (std::size_t i = 0; i < stack.size(); ++i)  // the stack rode down on it
        CHECK(std::abs((rest[i].y - w.body(stack[i]).position().y) - drop) < T(0.01));
    (void)ground;
}

TEST_CASE_TEMPLATE("a stack whose static support is destroyed between steps falls as one, its boxes not pushed apart", C,
                   XENO_TEST_CONFIGS) {
    // In free fall nothing presses the boxes together, so nothing should push them apart: the
    // impulses that held them are warm-started once more and must be shed before they do
    // (docs/solver.md, "Releasing a load"). Top box against bottom box after 0.5 s, measured:
    // 2.6 mm at the defaults; 6.7 mm with one relax sweep after the first substep, 4.4 mm at the
    // 12 substeps of 0.9.0 (float and double alike).
    using T = typename C::T;
    World<T> w(C::settings());
    add_ground(w);
    const BodyId plate = add_static_plate(w, T(5), T(2), T(0.25));
    std::vector<BodyId> stack;
    for (int i = 0; i < 3; ++i) stack.push_back(add_box(w, Vec3<T>{T(0), T(5.75) + T(i), T(0)}));
    test::simulate(w, T(3));
    const T height = w.body(stack[2]).position().y - w.body(stack[0]).position().y;
    CHECK(std::abs(height - T(2)) < T(0.01));  // resting, each box on the one below
    w.destroy_body(plate);
    test::simulate(w, T(0.5));
    CHECK(w.body(stack[0]).position().y < T(5.75) - fall_after(T(0.5)) + T(0.01));  // it fell
    const T spread = w.body(stack[2]).position().y - w.body(stack[0]).position().y - height;
    CAPTURE(spread);
    CHECK(std::abs(spread) < T(0.004));
}

TEST_CASE_TEMPLATE(
    "a kinematic body switched dynamic gets its density's mass and keeps its velocity, dynamic to kinematic "
    "keeps moving at constant velocity",
    C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    BodyDef<T> d;
    d.type = BodyType::kinematic;
    d.density = T(250);
    d.linear_velocity = {T(1), T(0), T(0)};
    const BodyId k = w.create_body(Sphere<T>(T(0.5)), d);
    test::simulate(w, T(1));
    CHECK(w.body(k).position().y == T(0));  // kinematic: no gravity
    w.set_type(k, BodyType::dynamic);
    const double volume = 4.0 / 3.0 * 3.14159265358979 * 0.125;
    CHECK(w.body(k).mass() == doctest::Approx(250.0 * volume).epsilon(1e-4));
    CHECK(w.body(k).linear_velocity().x == T(1));
    test::simulate(w, T(0.5));
    CHECK(-w.body(k).position().y == doctest::Approx(static_cast<double>(fall_after(T(0.5)))).epsilon(0.01));

    w.set_type(k, BodyType::kinematic);  // keeps the velocity it had, falls no faster
    const Vec3<T> v = w.body(k).linear_velocity(), p = w.body(k).position();
    CHECK(w.body(k).inverse_mass() == T(0));
    test::simulate(w, T(1));
    CHECK(w.body(k).linear_velocity() == v);
    CHECK(length(w.body(k).position() - (p + v)) < T(1e-4));
}

TEST_CASE_TEMPLATE("a plate turned sensor drops the box asleep on it, turned solid again it catches the next box", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    add_ground(w);
    const BodyId plate = add_static_plate(w, T(2), T(3), T(0.1));
    const BodyId first = add_box(w, Vec3<T>{T(0), T(2.6), T(0)});
    test::simulate(w, T(2));
    CHECK(std::abs(w.body(first).position().y - T(2.6)) < T(0.01));
    if (C::sleeping) CHECK(!w.body(first).awake());  // resting: asleep in the default settings

    w.set_sensor(plate, true);
    test::simulate(w, T(2));
    CHECK(std::abs(w.body(first).position().y - T(0.5)) < T(0.01));  // fell through onto the ground

    w.set_sensor(plate, false);
    const BodyId second = add_box(w, Vec3<T>{T(0), T(4), T(0)});
    test::simulate(w, T(2));
    CHECK(std::abs(w.body(second).position().y - T(2.6)) < T(0.01));
    CHECK(std::abs(w.body(first).position().y - T(0.5)) < T(0.01));
}

TEST_CASE_TEMPLATE("a collision filter changed under a sleeping box lets it fall through, the ground's own filter too", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const BodyId ground = add_ground(w);
    const BodyId a = add_box(w, Vec3<T>{T(-2), T(0.5), T(0)});
    const BodyId b = add_box(w, Vec3<T>{T(2), T(0.5), T(0)});
    test::simulate(w, T(2));
    w.set_collision_filter(a, 2u, ~std::uint32_t(1));  // layer 2, ignores layer 1 (the ground)
    CHECK(w.body(a).layer() == 2u);
    CHECK(w.body(a).mask() == ~std::uint32_t(1));
    test::simulate(w, T(1));
    CHECK(w.body(a).position().y < T(-2));
    CHECK(std::abs(w.body(b).position().y - T(0.5)) < T(0.01));
    w.set_collision_filter(ground, 1u, 0u);  // the ground now collides with nothing: b falls too
    test::simulate(w, T(1));
    CHECK(w.body(b).position().y < T(-2));
}

TEST_CASE_TEMPLATE("a disabled body's contacts end with events, it stays put, out of queries, what rested on it falls", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const BodyId ground = add_ground(w);
    const BodyId bottom = add_box(w, Vec3<T>{T(0), T(0.5), T(0)});
    const BodyId top = add_box(w, Vec3<T>{T(0.3), T(1.5), T(0)});
    test::simulate(w, T(2));
    REQUIRE(w.contacts_of(bottom).size() == 2);

    w.set_enabled(bottom, false);
    CHECK(!w.body(bottom).enabled());
    CHECK(w.contacts_of(bottom).empty());
    w.step(T(1) / T(60));
    CHECK(events_between(w, bottom, ground) == std::vector<ContactEventKind>{ContactEventKind::ended});
    CHECK(events_between(w, bottom, top) == std::vector<ContactEventKind>{ContactEventKind::ended});
    const Vec3<T> held = w.body(bottom).position();
    test::simulate(w, T(1));
    CHECK(w.body(bottom).position() == held);                             // not integrated
    CHECK(std::abs(w.body(top).position().y - T(0.5)) < T(0.01));         // fell through it onto the ground
    const Ray<T> down{{T(0.3), T(5), T(0)}, {T(0), T(-1), T(0)}, T(10)};  // straight through the disabled box
    REQUIRE(w.raycast(down));
    CHECK(w.raycast(down)->body == top);
    for (const BodyId id : w.query_point(held)) CHECK(id != bottom);
    TriangleCounter<T> all, without;  // and it is not drawn: the same world with it destroyed draws as much
    draw_world(w, all);
    World<T> copy;
    restore_snapshot(copy, save_snapshot(w));
    copy.destroy_body(bottom);
    draw_world(copy, without);
    CHECK(all.triangles == without.triangles);
    CHECK(all.triangles > 0);

    // Enabled again where it was (overlapping the box that fell into its place): the two are
    // pushed apart, with began events, and nothing turns into NaN.
    w.set_enabled(bottom, true);
    w.step(T(1) / T(60));
    CHECK(events_between(w, bottom, top) == std::vector<ContactEventKind>{ContactEventKind::began});
    test::simulate(w, T(3));
    CHECK(is_finite(w.body(bottom).position()));
    CHECK(distance(w.body(bottom).position(), w.body(top).position()) > T(0.95));
}

TEST_CASE_TEMPLATE("a joint to a disabled body does nothing: the pendulum bob falls freely, and swings again once enabled", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    BodyDef<T> ad;
    ad.type = BodyType::kinematic;
    ad.position = {T(0), T(10), T(0)};
    const BodyId anchor = w.create_body(Sphere<T>(T(0.1)), ad);
    const BodyId bob = w.create_body(Sphere<T>(T(0.2)), [] {
        BodyDef<T> d;
        d.position = {T(0), T(9), T(0)};
        return d;
    }());
    JointDef<T> j;
    j.type = JointType::ball;
    j.a = anchor;
    j.b = bob;
    j.anchor_a = {T(0), T(10), T(0)};
    w.create_joint(j);
    test::simulate(w, T(0.5));
    CHECK(std::abs(w.body(bob).position().y - T(9)) < T(0.01));  // hangs
    w.set_enabled(anchor, false);
    test::simulate(w, T(0.5));
    CHECK(T(9) - w.body(bob).position().y == doctest::Approx(static_cast<double>(fall_after(T(0.5)))).epsilon(0.01));
    w.set_enabled(anchor, true);  // the joint pulls the bob back towards 1 m below the anchor
    test::simulate(w, T(3));
    CHECK(std::abs(distance(w.body(bob).position(), w.body(anchor).position()) - T(1)) < T(0.02));
}

TEST_CASE_TEMPLATE("set_shape: contacts end and are found again, mass recomputed or kept, the body rises out of the ground", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const BodyId ground = add_ground(w);
    const BodyId box = add_box(w, Vec3<T>{T(0), T(0.5), T(0)});
    test::simulate(w, T(1));
    CHECK(w.body(box).mass() == doctest::Approx(1000.0));

    w.set_shape(box, Box<T>(T(1), T(0.5), T(1)), MassUpdate::keep);
    CHECK(w.body(box).mass() == doctest::Approx(1000.0));
    CHECK(w.contacts_of(box).empty());
    w.step(T(1) / T(60));
    std::vector<ContactEventKind> kinds = events_between(w, box, ground);
    CHECK(kinds.size() == 2);  // the old contact ended, the new one began
    CHECK(std::count(kinds.begin(), kinds.end(), ContactEventKind::ended) == 1);
    CHECK(std::count(kinds.begin(), kinds.end(), ContactEventKind::began) == 1);

    // Taller than the room it has: the ground pushes it out, to rest on its new half height.
    w.set_shape(box, std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(1), T(0.5))));
    CHECK(w.body(box).mass() == doctest::Approx(2000.0).epsilon(1e-5));  // recomputed (the default)
    test::simulate(w, T(3));
    CHECK(std::abs(w.body(box).position().y - T(1)) < T(0.01));
    CHECK(length(w.body(box).linear_velocity()) < T(0.01));
}

TEST_CASE_TEMPLATE("move_kinematic reaches its target pose in one step and carries the box riding on it", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const T dt = w.settings().fixed_time_step;
    BodyDef<T> pd;
    pd.type = BodyType::kinematic;
    const BodyId platform = w.create_body(Box<T>(T(2), T(0.25), T(2)), pd);
    const Vec3<T> target{T(0.03), T(0.01), T(-0.02)};
    const Quat<T> turn = Quat<T>::from_axis_angle(normalized(Vec3<T>{T(1), T(2), T(3)}), T(0.3));
    w.move_kinematic(platform, target, turn, dt);
    w.step(dt);
    const T tolerance = sizeof(T) == 4 ? T(2e-5) : T(1e-10);
    CHECK(length(w.body(platform).position() - target) < tolerance);
    const Quat<T> q = w.body(platform).orientation();
    CHECK(std::abs(std::abs(dot(q, turn)) - T(1)) < tolerance);

    // A box on the platform moved 1 m/s along x for 2 s (a target per step) is carried by friction.
    w.move_kinematic(platform, Vec3<T>::zero(), Quat<T>::identity(), dt);
    w.step(dt);
    w.set_velocity(platform, Vec3<T>::zero(), Vec3<T>::zero());
    const BodyId box = add_box(w, Vec3<T>{T(0), T(0.75), T(0)});
    test::simulate(w, T(1));
    const Vec3<T> start = w.body(box).position();
    for (int i = 1; i <= 120; ++i) {
        w.move_kinematic(platform, Vec3<T>{T(i) * dt, T(0), T(0)}, Quat<T>::identity(), dt);
        w.step(dt);
    }
    CHECK(std::abs(w.body(platform).position().x - T(2)) < T(1e-4));
    // The platform starts at 1 m/s at once; friction (µ = 0.6) brings the box up to speed after it
    // has slipped v²/(2µg) behind.
    const T slip = T(1) / (T(2) * T(0.6) * T(9.81));
    CHECK(T(2) - (w.body(box).position().x - start.x) == doctest::Approx(static_cast<double>(slip)).epsilon(0.05));
    CHECK(std::abs(w.body(box).position().y - start.y) < T(0.01));
}

TEST_CASE_TEMPLATE("regression: move_kinematic turns the short way to a target given as the negated quaternion", T, float,
                   double) {
    // Flipping the turn to the short way round built the quaternion with its parts out of order
    // (Quat's constructor takes w first): a turntable at 1 rad/s whose yaw a game wraps into
    // (-pi, pi] spun at 192 rad/s from the wrap on, and a body told to stay where it was (q and
    // -q) spun at 191 rad/s.
    World<T> w;
    const T dt = w.settings().fixed_time_step;
    BodyDef<T> pd;
    pd.type = BodyType::kinematic;
    const BodyId table = w.create_body(Box<T>(T(2), T(0.25), T(2)), pd);
    T yaw = T(0), fastest = T(0);
    for (int i = 0; i < 240; ++i) {  // 1 rad/s for 4 s: the yaw wraps at pi, near 3.14 s
        yaw += dt;
        const T wrapped = yaw > ScalarTraits<T>::pi ? yaw - T(2) * ScalarTraits<T>::pi : yaw;
        Quat<T> target = Quat<T>::from_axis_angle(Vec3<T>::unit_y(), wrapped);
        if (i % 2 == 1) target = Quat<T>{-target.w, -target.x, -target.y, -target.z};  // the same turn
        w.move_kinematic(table, Vec3<T>::zero(), target, dt);
        fastest = std::max(fastest, length(w.body(table).angular_velocity()));
        w.step(dt);
    }
    CHECK(std::abs(fastest - T(1)) < T(1e-3));
    CHECK(std::abs(std::abs(dot(w.body(table).orientation(), Quat<T>::from_axis_angle(Vec3<T>::unit_y(), T(240) * dt))) - T(1)) <
          T(1e-4));
}

TEST_CASE_TEMPLATE("set_awake(false) puts a falling island to sleep in mid-air, set_awake(true) lets it fall", T, float, double) {
    World<T> w;  // the default settings
    add_ground(w);
    const BodyId a = add_box(w, Vec3<T>{T(0), T(5), T(0)});
    const BodyId b = add_box(w, Vec3<T>{T(0), T(6), T(0)});
    JointDef<T> j;
    j.type = JointType::fixed;
    j.a = a;
    j.b = b;
    j.anchor_a = {T(0), T(5.5), T(0)};
    w.create_joint(j);
    test::simulate(w, T(0.25));
    const T y = w.body(a).position().y;
    w.set_awake(a, false);  // the island: b goes to sleep with it
    CHECK(!w.body(b).awake());
    CHECK(w.body(b).linear_velocity() == Vec3<T>::zero());
    test::simulate(w, T(1));
    CHECK(w.body(a).position().y == y);
    w.set_awake(b, true);  // and b wakes a through the joint at the next step
    test::simulate(w, T(0.5));
    CHECK(w.body(a).awake());
    CHECK(y - w.body(a).position().y == doctest::Approx(static_cast<double>(fall_after(T(0.5)))).epsilon(0.01));
}

TEST_CASE_TEMPLATE("a static body teleported into a sleeping box wakes it and pushes it out (it stayed asleep inside)", T, float,
                   double) {
    World<T> w;  // the default settings
    add_ground(w);
    const BodyId box = add_box(w, Vec3<T>{T(0), T(0.5), T(0)});
    BodyDef<T> wd;
    wd.type = BodyType::static_body;
    wd.position = {T(5), T(1), T(0)};
    const BodyId wall = w.create_body(Box<T>(T(0.5), T(1), T(2)), wd);
    test::simulate(w, T(2));
    REQUIRE(!w.body(box).awake());
    w.set_transform(wall, {T(-0.8), T(1), T(0)}, Quat<T>::identity());  // 0.3 m into the box's left side
    test::simulate(w, T(2));
    CHECK(w.body(box).position().x > T(-0.8) + T(0.5) + T(0.5) - T(0.01));  // pushed clear of the wall
}

TEST_CASE_TEMPLATE("set_fast lifts the speed cap from a body already moving, which still stops at a thin wall", T, float,
                   double) {
    World<T> w;  // the default settings: a 400 m/s cap for bodies that are not fast
    BodyDef<T> wall_def;
    wall_def.type = BodyType::static_body;
    wall_def.position = {T(30), T(0), T(0)};
    w.create_body(Box<T>(T(0.05), T(4), T(2)), wall_def);
    w.set_gravity(Vec3<T>::zero());
    BodyDef<T> d;
    d.linear_velocity = {T(600), T(0), T(0)};  // 10 m a step: jumps the 10 cm wall without CCD
    const BodyId bullet = w.create_body(Sphere<T>(T(0.05)), d);
    d.position = {T(0), T(2), T(0)};
    const BodyId plain = w.create_body(Sphere<T>(T(0.05)), d);
    w.set_fast(bullet, true);
    CHECK(w.body(bullet).fast());
    w.step(w.settings().fixed_time_step);  // 10 m of free flight for the fast one, 6.7 m for the other
    CHECK(w.body(bullet).linear_velocity().x == doctest::Approx(600.0).epsilon(1e-6));  // its momentum kept
    CHECK(w.body(plain).linear_velocity().x == doctest::Approx(400.0).epsilon(1e-6));   // capped
    CHECK(w.body(bullet).position().x == doctest::Approx(10.0).epsilon(1e-4));
    test::simulate(w, T(0.1));
    CHECK(w.body(bullet).position().x < T(30));
    CHECK(w.body(plain).position().x < T(30));
}

TEST_CASE_TEMPLATE("every by-ID setter rejects bad input and changes nothing (snapshot bytes before and after)", T, float,
                   double) {
    World<T> w;
    const BodyId ground = add_ground(w);
    const BodyId box = add_box(w, Vec3<T>{T(0), T(0.5), T(0)});
    BodyDef<T> weightless;
    weightless.type = BodyType::static_body;
    weightless.density = T(0);
    weightless.position = {T(5), T(0.5), T(0)};
    const BodyId no_density = w.create_body(unit_box<T>, weightless);
    BodyDef<T> kd;
    kd.type = BodyType::kinematic;
    kd.position = {T(-5), T(1), T(0)};
    const BodyId kin = w.create_body(unit_box<T>, kd);
    JointDef<T> jd;
    jd.type = JointType::ball;
    jd.a = ground;
    jd.b = box;
    jd.anchor_a = {T(0), T(1), T(0)};
    w.create_joint(jd);
    test::simulate(w, T(0.5));
    const BodyId stale = add_box(w, Vec3<T>{T(3), T(3), T(3)});
    w.destroy_body(stale);

    const T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
    const std::vector<std::uint8_t> before = save_snapshot(w);
    const auto rejects = [&](auto&& call) {
        CHECK_THROWS_AS(call(), InvalidArgument);
        CHECK(save_snapshot(w) == before);
    };
    rejects([&] { w.set_type(stale, BodyType::static_body); });
    rejects([&] { w.set_type(BodyId{}, BodyType::static_body); });
    rejects([&] { w.set_type(box, static_cast<BodyType>(7)); });
    rejects([&] { w.set_type(no_density, BodyType::dynamic); });  // density 0
    rejects([&] { w.set_type(box, BodyType::static_body); });     // jointed to the static ground
    rejects([&] { w.set_shape(box, std::shared_ptr<const Shape<T>>{}); });
    rejects([&] { w.set_shape(box, std::shared_ptr<const Compound<T>>{}); });
    std::vector<Vec3<T>> corners;  // a unit cube whose centre is 2.5 m off its local origin
    for (int i = 0; i < 8; ++i) corners.push_back({T(2 + (i & 1)), T((i >> 1) & 1), T((i >> 2) & 1)});
    const ConvexPolyhedron<T> off_centre(corners,
                                         {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}});
    rejects([&] { w.set_shape(box, Shape<T>(off_centre)); });
    rejects([&] { w.set_density(box, T(0)); });
    rejects([&] { w.set_density(box, nan); });
    rejects([&] { w.set_density(box, inf); });
    rejects([&] { w.set_velocity(box, {nan, T(0), T(0)}, Vec3<T>::zero()); });
    rejects([&] { w.set_velocity(box, Vec3<T>::zero(), {T(0), inf, T(0)}); });
    rejects([&] { w.set_transform(box, {inf, T(0), T(0)}, Quat<T>::identity()); });
    rejects([&] { w.move_kinematic(box, Vec3<T>::zero(), Quat<T>::identity(), T(1) / T(60)); });  // not kinematic
    rejects([&] { w.move_kinematic(kin, Vec3<T>::zero(), Quat<T>::identity(), T(0)); });
    rejects([&] { w.move_kinematic(kin, Vec3<T>::zero(), Quat<T>{T(0), T(0), T(0), T(0)}, T(1) / T(60)); });
    rejects([&] { w.move_kinematic(kin, {std::numeric_limits<T>::max(), T(0), T(0)}, Quat<T>::identity(), T(1e-3)); });
    rejects([&] { w.set_collision_filter(stale, 1u, 1u); });
    rejects([&] { w.set_sensor(stale, true); });
    rejects([&] { w.set_fast(stale, true); });
    rejects([&] { w.set_enabled(stale, false); });
    rejects([&] { w.set_awake(stale, false); });
}

TEST_CASE_TEMPLATE("a snapshot keeps a disabled body and a changed density, the restored world steps to the same bits", T, float,
                   double) {
    World<T> w;
    add_ground(w);
    const BodyId a = add_box(w, Vec3<T>{T(0), T(0.5), T(0)});
    const BodyId b = add_box(w, Vec3<T>{T(0), T(1.5), T(0)});
    test::simulate(w, T(0.5));
    w.set_enabled(a, false);
    w.set_density(b, T(300));
    CHECK(w.body(b).mass() == doctest::Approx(300.0));
    World<T> copy;
    restore_snapshot(copy, save_snapshot(w));
    CHECK(!copy.body(a).enabled());
    CHECK(copy.body(b).density() == T(300));
    test::simulate(w, T(1));
    test::simulate(copy, T(1));
    CHECK(save_snapshot(copy) == save_snapshot(w));
    for (const BodyId id : copy.query_point(Vec3<T>{T(0), T(0.5), T(0)})) CHECK(id != a);  // the disabled box is not found
}

TEST_CASE_TEMPLATE("regression: set_shape keeping the mass takes the new shape's inertia, and the body rests on the floor", C,
                   XENO_TEST_CONFIGS) {
    // MassUpdate::keep kept the inertia too: a 5 cm ball turned into a 10 m box kept the ball's
    // inertia, which left the solver's rows almost no effective mass, and the box fell through
    // the floor (y = −0.08 where it should rest at 5).
    using T = typename C::T;
    World<T> w(C::settings());
    add_ground(w);  // 40 m wide, top at y = 0: room for the 10 m box
    BodyDef<T> d;
    d.position = {T(0), T(5.5), T(0)};
    const BodyId body = w.create_body(Sphere<T>(T(0.05)), d);
    const T mass = w.body(body).mass();
    w.set_shape(body, Box<T>(T(5), T(5), T(5)), MassUpdate::keep);
    CHECK(w.body(body).mass() == doctest::Approx(mass));
    const T expected = mass * T(50) / T(3);  // m (a² + b²) / 3 about each axis, half extents 5 m
    CHECK(w.body(body).local_inertia()[0].x == doctest::Approx(expected).epsilon(1e-5));
    test::simulate(w, T(2));
    CHECK(std::abs(w.body(body).position().y - T(5)) < T(0.01));
}

/// The box's mass properties set to `mass` kg (a unit box's inertia at that mass).
template <class T>
void set_box_mass(Body<T>& body, T mass) {
    MassProperties<T> m = mass_properties(unit_box<T>, T(1));
    m.inertia = m.inertia * (mass / m.mass);
    m.mass = mass;
    body.set_mass_properties(m);
}

TEST_CASE_TEMPLATE("regression: a resting box made 10⁸ times lighter stays at rest", C, XENO_TEST_CONFIGS) {
    // The contacts kept the impulses that held 100 t for the warm start of the 1 g box's next
    // step: it jumped 4 cm at 0.7 m/s (a 10⁹ ratio: 6.6 m at 17 m/s), in float and in double.
    // A lighter body's cached impulses are now scaled down with its mass.
    using T = typename C::T;
    World<T> w(C::settings());
    add_ground(w);
    BodyDef<T> d;
    d.position = {T(0), T(0.5), T(0)};
    d.density = T(1e5);
    const BodyId box = w.create_body(unit_box<T>, d);
    test::simulate(w, T(1));
    const T rest = w.body(box).position().y;
    set_box_mass(w.body(box), T(1e-3));
    T fastest = T(0), farthest = T(0);
    test::simulate(w, T(0.5), [&](int) {
        fastest = std::max(fastest, length(w.body(box).linear_velocity()));
        farthest = std::max(farthest, std::abs(w.body(box).position().y - rest));
    });
    CHECK(fastest < T(1e-3));
    CHECK(farthest < T(1e-4));
}

TEST_CASE_TEMPLATE("regression: a snapshot taken just after a body became very light restores and steps to the same bits", T,
                   float, double) {
    // A 20 t box resting on the ground and another hanging from a ball joint, each set to ten
    // times the least normal mass of T: the cached impulses of their contact and joint, times the
    // new response to a unit impulse, overflowed, and restore_snapshot refused the world it saved.
    const T tiny = T(10) * std::numeric_limits<T>::min();
    World<T> w;
    const BodyId ground = add_ground(w);
    BodyDef<T> d;
    d.density = T(20000);
    d.position = {T(0), T(0.5), T(0)};
    const BodyId resting = w.create_body(unit_box<T>, d);
    d.position = {T(3), T(2.5), T(0)};
    const BodyId hanging = w.create_body(unit_box<T>, d);
    w.create_joint(JointDef<T>::ball(ground, hanging, Vec3<T>{T(3), T(3), T(0)}));
    test::simulate(w, T(0.5));
    for (const BodyId id : {resting, hanging}) set_box_mass(w.body(id), tiny);
    World<T> copy;
    REQUIRE_NOTHROW(restore_snapshot(copy, save_snapshot(w)));
    test::simulate(w, T(0.5));
    test::simulate(copy, T(0.5));
    CHECK(save_snapshot(copy) == save_snapshot(w));
    CHECK(std::abs(w.body(resting).position().y - T(0.5)) < T(1e-3));
    CHECK(std::abs(w.body(hanging).position().y - T(2.5)) < T(1e-3));
}

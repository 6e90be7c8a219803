// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Reusing a manifold (World::reuse_contact, docs/collision.md "Reusing a manifold"): a pair that
// barely moved since its manifold was made has its points re-measured instead of being collided
// again. Every test runs with the default settings (sleeping on) and with sleeping off: the
// bodies settle for 3 s (with sleeping on they fall asleep), are woken and step once, so each
// pair's contact is the one made or re-measured in that step from the settled poses.
// Checked against the narrow phase run afresh on the same poses (generate_contacts) and against
// how deep each shape's lowest point sits below a level floor; a box turned in place, or set
// moving, is collided again.
#include "support/flat_level.hpp"
#include "support/sim.hpp"

#include "scenes/all.hpp"

#include <xeno/collide/collide.hpp>
#include <xeno/dynamics/world.hpp>
#include <xeno/shape/convex_hull.hpp>
#include <xeno/shape/height_field.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace xeno;

namespace {

/// The deepest point of a persistent or a fresh manifold.
template <class M>
auto deepest_point(const M& m) {
    auto d = -std::numeric_limits<decltype(m.points[0].depth)>::infinity();
    for (int i = 0; i < m.count; ++i) d = std::max(d, m.points[static_cast<std::size_t>(i)].depth);
    return d;
}

/// Every convex contact of the world against generate_contacts on the bodies' poses now: the same
/// normal (within 1e-3) and deepest depth (within `depth_tolerance`). Returns the contacts compared.
template <class T>
std::size_t compare_with_fresh(const World<T>& world, T depth_tolerance) {
    std::size_t compared = 0;
    const T margin = world.settings().speculative_distance;
    for (const Contact<T>& c : world.contacts()) {
        const Body<T>& a = world.body(c.a);
        const Body<T>& b = world.body(c.b);
        const ContactManifold<T> fresh =
            generate_contacts(a.child_shape(c.child_a), a.child_transform(c.child_a), b.child_shape(c.child_b),
                              b.child_transform(c.child_b), margin, world.settings().linear_slop);
        CAPTURE(c.a.index);
        CAPTURE(c.b.index);
        REQUIRE(fresh.count > 0);
        CHECK(dot(fresh.normal, c.manifold.normal) >= T(1) - T(1e-3));
        CHECK(std::abs(deepest_point(fresh) - deepest_point(c.manifold)) <= depth_tolerance);
        ++compared;
    }
    return compared;
}

template <class C>
World<typename C::T> world_of(bool reuse = true) {
    WorldSettings<typename C::T> settings = C::settings();
    settings.reuse_contacts = reuse;
    return World<typename C::T>(settings);
}

template <class T>
void step_for(World<T>& world, int steps) {
    for (int i = 0; i < steps; ++i) world.step(T(1) / T(60));
}

/// 3 s of settling (asleep by then with the defaults), then every body woken for one step.
template <class T>
void settle_and_wake(World<T>& world) {
    step_for(world, 180);
    world.for_each_body([&](BodyId id, const Body<T>& b) {
        if (b.is_dynamic()) world.set_awake(id, true);
    });
    world.step(T(1) / T(60));
}

/// How far below y = 0 the body's lowest point is, from its shape's support function alone.
template <class T>
T sunk_below_level(const Body<T>& body) {
    const Vec3<T> down_local = rotate(conjugate(body.orientation()), Vec3<T>{T(0), T(-1), T(0)});
    return std::visit([&](const auto& s) { return dot(s.support(down_local), down_local); }, body.shape()) - body.position().y;
}

/// A dynamic body of `shape` at x, turned by `orientation`, its lowest point on y = 0.
template <class T>
BodyId place_on_level(World<T>& world, const Shape<T>& shape, T x, const Quat<T>& orientation) {
    BodyDef<T> def;
    def.position = {x, T(0), T(0.2)};
    def.orientation = orientation;
    const BodyId id = world.create_body(shape, def);
    world.set_transform(id, {x, sunk_below_level(world.body(id)), T(0.2)}, orientation);  // created at y = 0
    return id;
}

/// A unit box settled on the ground (scenes::column of one), its contact re-measured in the
/// step after it was woken.
template <class T>
BodyId settled_box(World<T>& world) {
    const scenes::Scene scene = scenes::column(world, 1);
    settle_and_wake(world);
    REQUIRE(world.last_step_stats().reused_contacts == 1);
    return scene.bodies.front();
}

}  // namespace

TEST_CASE_TEMPLATE("a pyramid at rest re-measures its contacts, and they are the narrow phase's", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> world = world_of<C>();
    scenes::pyramid(world, 6);
    settle_and_wake(world);
    const StepStats& stats = world.last_step_stats();
    MESSAGE(stats.reused_contacts << " of " << stats.contacts << " contacts re-measured");
    REQUIRE(stats.awake_bodies == 21);
    CHECK(stats.reused_contacts * 10 >= stats.contacts * 9);  // at rest nearly every pair barely moves
    CHECK(compare_with_fresh(world, T(1e-5)) == stats.contacts);
}

TEST_CASE_TEMPLATE("every shape kind at rest on the ground re-measures contacts that are the narrow phase's", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> world = world_of<C>();
    scenes::add_ground(world);
    std::vector<Vec3<T>> rock;  // a hull of 24 points on an ellipsoid
    scenes::Random rng(5);
    for (int i = 0; i < 24; ++i) rock.push_back(hadamard(rng.direction<T>(), Vec3<T>{T(0.35), T(0.25), T(0.3)}));
    const Shape<T> kinds[] = {make_convex_hull(rock).polyhedron, Sphere<T>(T(0.3)),       Capsule<T>(T(0.2), T(0.3)),
                              Cylinder<T>(T(0.3), T(0.25)),      Cone<T>(T(0.3), T(0.7)), Box<T>(T(0.3), T(0.2), T(0.25))};
    const Quat<T> lying = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), T(1.5707963267948966));
    // The capsule lies on its side (two points); the others stand as made.
    for (int i = 0; i < 6; ++i) place_on_level(world, kinds[i], T(2) * T(i), i == 2 ? lying : Quat<T>::identity());
    settle_and_wake(world);
    const StepStats& stats = world.last_step_stats();
    MESSAGE(stats.reused_contacts << " of " << stats.contacts << " contacts re-measured");
    REQUIRE(stats.awake_bodies == 6);
    CHECK(stats.contacts == 6);
    CHECK(stats.reused_contacts == 6);
    CHECK(compare_with_fresh(world, T(1e-5)) == stats.contacts);
}

TEST_CASE_TEMPLATE("a box turned in place about the normal is collided again: its points follow the turn", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> world = world_of<C>();
    const BodyId box = settled_box(world);
    // 1° about the vertical through the box's centre: the centre stays put, the corners move 12 mm.
    const Body<T>& b = world.body(box);
    const Quat<T> turn = Quat<T>::from_axis_angle(Vec3<T>::unit_y(), T(3.14159265358979323846 / 180));
    world.set_transform(box, b.position(), turn * b.orientation());
    world.step(T(1) / T(60));
    CHECK(world.last_step_stats().reused_contacts == 0);
    // Each point's two anchors lie on one normal line: on the ground under a corner of the box.
    REQUIRE(world.contacts().size() == 1);
    const Contact<T>& c = world.contacts().front();
    const Body<T>& ground = world.body(c.a);
    const Body<T>& moved = world.body(c.b);
    CHECK(c.manifold.count == 4);
    for (int i = 0; i < c.manifold.count; ++i) {
        const ContactPoint<T>& p = c.manifold.points[static_cast<std::size_t>(i)];
        const Vec3<T> gap = moved.transform().apply(p.local_b) - ground.transform().apply(p.local_a);
        const Vec3<T> slide = gap - c.manifold.normal * dot(gap, c.manifold.normal);
        CHECK(length(slide) <= T(1e-4));
    }
    CHECK(compare_with_fresh(world, T(1e-5)) == 1);
}

TEST_CASE_TEMPLATE("bodies at rest on a mesh or a heightfield re-measure their contacts, each as deep as the body sinks", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const bool heightfield : {false, true}) {
        CAPTURE(heightfield);
        World<T> world = world_of<C>();
        BodyDef<T> level;
        level.type = BodyType::static_body;
        if (heightfield) world.create_body(HeightField<T>(9, 9, std::vector<T>(81, T(0)), T(1)), level);
        else world.create_body(test::flat_mesh<T>(8), level);
        const Shape<T> kinds[] = {Box<T>(T(0.5), T(0.3), T(0.4)), Sphere<T>(T(0.3)), Capsule<T>(T(0.2), T(0.5))};
        const Quat<T> turns[] = {Quat<T>::from_axis_angle(Vec3<T>::unit_y(), T(0.3)), Quat<T>::identity(),
                                 Quat<T>::from_axis_angle(Vec3<T>::unit_z(), T(1.5707963267948966))};
        std::vector<BodyId> bodies;  // off the triangles' vertices
        for (int i = 0; i < 3; ++i) bodies.push_back(place_on_level(world, kinds[i], T(2) * T(i - 1) + T(0.3), turns[i]));
        settle_and_wake(world);
        const StepStats& stats = world.last_step_stats();
        MESSAGE(stats.reused_contacts << " of " << stats.contacts << " contacts re-measured");
        REQUIRE(stats.awake_bodies == 3);
        CHECK(stats.contacts >= 3);
        CHECK(stats.reused_contacts == stats.contacts);
        for (const BodyId id : bodies) {
            T deepest = -std::numeric_limits<T>::infinity();
            for (const Contact<T>& c : world.contacts_of(id)) {
                CHECK(c.manifold.normal.y >= T(1) - T(1e-5));  // the level is A (created first): up, from A to B
                deepest = std::max(deepest, deepest_point(c.manifold));
            }
            CAPTURE(id.index);
            CHECK(std::abs(deepest - sunk_below_level(world.body(id))) <= T(1e-5));
        }
    }
}

TEST_CASE_TEMPLATE("a box at rest that is set spinning or pushed is collided again in that very step", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const bool spin : {false, true}) {
        CAPTURE(spin);
        World<T> world = world_of<C>();
        const BodyId box = settled_box(world);
        // Its pose is unchanged when the narrow phase runs, but it will move this step: 6 rad/s
        // about the vertical moves its corners 6 cm, 1 m/s sideways 1.7 cm.
        if (spin) world.set_velocity(box, Vec3<T>::zero(), Vec3<T>{T(0), T(6), T(0)});
        else world.set_velocity(box, Vec3<T>{T(1), T(0), T(0)}, Vec3<T>::zero());
        world.step(T(1) / T(60));
        CHECK(world.last_step_stats().reused_contacts == 0);
        CHECK(world.last_step_stats().contacts == 1);
    }
}

TEST_CASE_TEMPLATE("with reuse_contacts off every pair is collided each step, and a pyramid settles where it does with it on", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    std::vector<Vec3<T>> rest[2];
    for (const bool reuse : {false, true}) {
        World<T> world = world_of<C>(reuse);
        const scenes::Scene scene = scenes::pyramid(world, 6);
        settle_and_wake(world);
        const StepStats& stats = world.last_step_stats();
        CHECK((stats.reused_contacts == 0) == !reuse);
        CHECK(compare_with_fresh(world, T(1e-5)) == stats.contacts);
        for (const BodyId id : scene.bodies) rest[reuse].push_back(world.body(id).position());
    }
    // Re-measuring moves no box by more than a fifth of its bound (a tenth of linear_slop, 0.5 mm;
    // measured 14 µm in float, 20 µm in double, with sleeping off).
    REQUIRE(rest[0].size() == rest[1].size());
    T worst = T(0);
    for (std::size_t i = 0; i < rest[0].size(); ++i) worst = std::max(worst, length(rest[0][i] - rest[1][i]));
    MESSAGE("largest difference in rest position: " << worst << " m");
    CHECK(worst <= T(1e-4));
}

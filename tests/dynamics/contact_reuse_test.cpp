// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Reusing a manifold (World::reuse_contact, docs/collision.md "Reusing a manifold"): a pair that
// barely moved since its manifold was made has its points re-measured instead of being collided
// again. Checked against the narrow phase run afresh on the same poses (generate_contacts), on
// default settings: a settled stack and every shape kind at rest on the ground agree with it, and a
// box turned in place, by a rotation that moves no centre, is collided again.
#include "scenes/all.hpp"

#include <xeno/collide/collide.hpp>
#include <xeno/dynamics/world.hpp>
#include <xeno/shape/convex_hull.hpp>
#include <xeno/shape/height_field.hpp>
#include <xeno/shape/triangle_mesh.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <vector>

using namespace xeno;

namespace {

template <class T>
T deepest(const Manifold<T>& m) {
    T d = -std::numeric_limits<T>::infinity();
    for (int i = 0; i < m.count; ++i) d = std::max(d, m.points[static_cast<std::size_t>(i)].depth);
    return d;
}

template <class T>
T deepest(const ContactManifold<T>& m) {
    T d = -std::numeric_limits<T>::infinity();
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
        CHECK(std::abs(deepest(fresh) - deepest(c.manifold)) <= depth_tolerance);
        ++compared;
    }
    return compared;
}

}  // namespace

TEST_CASE_TEMPLATE("a settled pyramid re-measures its contacts, and they are the narrow phase's", T, float, double) {
    World<T> world;
    WorldSettings<T> settings;  // the defaults, but awake: a sleeping pair keeps its contact untouched
    settings.allow_sleeping = false;
    world.set_settings(settings);
    scenes::pyramid(world, 6);
    for (int i = 0; i < 180; ++i) world.step(T(1) / T(60));
    const StepStats& stats = world.last_step_stats();
    MESSAGE(stats.reused_contacts << " of " << stats.contacts << " contacts re-measured");
    CHECK(stats.reused_contacts * 10 >= stats.contacts * 9);  // at rest nearly every pair barely moves
    CHECK(compare_with_fresh(world, T(1e-5)) == stats.contacts);
}

TEST_CASE_TEMPLATE("every shape kind at rest on the ground re-measures contacts that are the narrow phase's", T, float, double) {
    World<T> world;
    WorldSettings<T> settings;
    settings.allow_sleeping = false;
    world.set_settings(settings);
    scenes::add_ground(world);
    std::vector<Vec3<T>> rock;  // a hull of 24 points on an ellipsoid
    scenes::Random rng(5);
    for (int i = 0; i < 24; ++i) rock.push_back(hadamard(rng.direction<T>(), Vec3<T>{T(0.35), T(0.25), T(0.3)}));
    const Shape<T> kinds[] = {make_convex_hull(rock).polyhedron, Sphere<T>(T(0.3)),       Capsule<T>(T(0.2), T(0.3)),
                              Cylinder<T>(T(0.3), T(0.25)),      Cone<T>(T(0.3), T(0.7)), Box<T>(T(0.3), T(0.2), T(0.25))};
    for (int i = 0; i < 6; ++i) {
        BodyDef<T> def;
        def.position = {T(2) * T(i), T(0.8), T(0)};
        // The capsule lies on its side (two points); the others stand as made.
        if (i == 2) def.orientation = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), T(1.5707963267948966));
        world.create_body(kinds[i], def);
    }
    for (int i = 0; i < 180; ++i) world.step(T(1) / T(60));
    const StepStats& stats = world.last_step_stats();
    MESSAGE(stats.reused_contacts << " of " << stats.contacts << " contacts re-measured");
    CHECK(stats.contacts == 6);
    CHECK(stats.reused_contacts == 6);
    CHECK(compare_with_fresh(world, T(1e-5)) == 6);
}

TEST_CASE_TEMPLATE("a box turned in place about the normal is collided again: its points follow the turn", T, float, double) {
    World<T> world;
    WorldSettings<T> settings;
    settings.allow_sleeping = false;
    world.set_settings(settings);
    scenes::column(world, 1);
    BodyId box;
    world.for_each_body([&](BodyId id, const Body<T>& b) {
        if (b.is_dynamic()) box = id;
    });
    for (int i = 0; i < 60; ++i) world.step(T(1) / T(60));
    REQUIRE(world.last_step_stats().reused_contacts == 1);  // at rest on the ground
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

namespace {

/// A flat 8 × 8 m mesh of 128 triangles at y = 0, or a heightfield of the same plane.
template <class T>
BodyId add_flat_level(World<T>& world, bool heightfield) {
    BodyDef<T> d;
    d.type = BodyType::static_body;
    if (heightfield) return world.create_body(HeightField<T>(9, 9, std::vector<T>(81, T(0)), T(1)), d);
    const int n = 8;
    std::vector<Vec3<T>> v;
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) v.push_back({static_cast<T>(i - n / 2), T(0), static_cast<T>(j - n / 2)});
    const auto at = [](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            tris.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            tris.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return world.create_body(TriangleMesh<T>(v, tris), d);
}

/// How far below y = 0 the body's lowest point is, from its shape alone.
template <class T>
T sunk_below_level(const Body<T>& body) {
    const Vec3<T> down_local = rotate(conjugate(body.orientation()), Vec3<T>{T(0), T(-1), T(0)});
    return std::visit([&](const auto& s) { return dot(s.support(down_local), down_local); }, body.shape()) - body.position().y;
}

}  // namespace

TEST_CASE_TEMPLATE("bodies at rest on a mesh or a heightfield re-measure their contacts, each as deep as the body sinks", T,
                   float, double) {
    for (const bool heightfield : {false, true}) {
        CAPTURE(heightfield);
        World<T> world;
        WorldSettings<T> settings;
        settings.allow_sleeping = false;
        world.set_settings(settings);
        add_flat_level(world, heightfield);
        const Shape<T> kinds[] = {Box<T>(T(0.5), T(0.3), T(0.4)), Sphere<T>(T(0.3)), Capsule<T>(T(0.2), T(0.5))};
        std::vector<BodyId> bodies;
        for (int i = 0; i < 3; ++i) {
            BodyDef<T> def;
            def.position = {T(2) * T(i - 1) + T(0.3), T(0.6), T(0.2)};  // off the triangles' vertices
            def.orientation =
                Quat<T>::from_axis_angle(i == 2 ? Vec3<T>::unit_z() : Vec3<T>::unit_y(), i == 2 ? T(1.5707963267948966) : T(0.3));
            bodies.push_back(world.create_body(kinds[i], def));
        }
        for (int i = 0; i < 120; ++i) world.step(T(1) / T(60));
        const StepStats& stats = world.last_step_stats();
        MESSAGE(stats.reused_contacts << " of " << stats.contacts << " contacts re-measured");
        CHECK(stats.contacts >= 3);
        CHECK(stats.reused_contacts == stats.contacts);
        for (const BodyId id : bodies) {
            T deepest_point = -std::numeric_limits<T>::infinity();
            for (const Contact<T>& c : world.contacts_of(id)) {
                CHECK(c.manifold.normal.y >= T(1) - T(1e-5));  // the level is A (created first): up, from A to B
                deepest_point = std::max(deepest_point, deepest(c.manifold));
            }
            CAPTURE(id.index);
            CHECK(std::abs(deepest_point - sunk_below_level(world.body(id))) <= T(1e-5));
        }
    }
}

TEST_CASE_TEMPLATE("a box at rest that is set spinning or pushed is collided again in that very step", T, float, double) {
    for (const bool spin : {false, true}) {
        CAPTURE(spin);
        World<T> world;
        WorldSettings<T> settings;
        settings.allow_sleeping = false;
        world.set_settings(settings);
        scenes::column(world, 1);
        BodyId box;
        world.for_each_body([&](BodyId id, const Body<T>& b) {
            if (b.is_dynamic()) box = id;
        });
        for (int i = 0; i < 60; ++i) world.step(T(1) / T(60));
        REQUIRE(world.last_step_stats().reused_contacts == 1);
        // Its pose is unchanged when the narrow phase runs, but it will move this step: 6 rad/s
        // about the vertical moves its corners 6 cm, 1 m/s sideways 1.7 cm.
        if (spin) world.set_velocity(box, Vec3<T>::zero(), Vec3<T>{T(0), T(6), T(0)});
        else world.set_velocity(box, Vec3<T>{T(1), T(0), T(0)}, Vec3<T>::zero());
        world.step(T(1) / T(60));
        CHECK(world.last_step_stats().reused_contacts == 0);
        CHECK(world.last_step_stats().contacts == 1);
    }
}

TEST_CASE_TEMPLATE("with reuse_contacts off every pair is collided each step, and a pyramid settles where it does with it on", T,
                   float, double) {
    std::vector<Vec3<T>> rest[2];
    for (const bool reuse : {false, true}) {
        World<T> world;
        WorldSettings<T> settings;
        settings.allow_sleeping = false;
        settings.reuse_contacts = reuse;
        world.set_settings(settings);
        const scenes::Scene scene = scenes::pyramid(world, 6);
        for (int i = 0; i < 180; ++i) world.step(T(1) / T(60));
        const StepStats& stats = world.last_step_stats();
        CHECK((stats.reused_contacts == 0) == !reuse);
        CHECK(compare_with_fresh(world, T(1e-5)) == stats.contacts);
        for (const BodyId id : scene.bodies) rest[reuse].push_back(world.body(id).position());
    }
    // Re-measuring moves no box by more than a fifth of its bound (a tenth of linear_slop, 0.5 mm;
    // measured 14 µm in float, 20 µm in double).
    REQUIRE(rest[0].size() == rest[1].size());
    T worst = T(0);
    for (std::size_t i = 0; i < rest[0].size(); ++i) worst = std::max(worst, length(rest[0][i] - rest[1][i]));
    MESSAGE("largest difference in rest position: " << worst << " m");
    CHECK(worst <= T(1e-4));
}

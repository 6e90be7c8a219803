// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Inputs at the edges of the range of T (docs/robustness.md, "Range of T"): each test here is a
// regression for an input the library used to accept and answer with infinity, NaN, a silently
// changed value or a step that never ends. Forces that overflow when added up, a speed whose
// square overflows, quaternions whose squared length under- or overflows, compound children
// beyond the size range, time steps and settings beyond what a step can use, and error messages
// that named the wrong component.
#include "support/rejection.hpp"
#include "support/approx.hpp"

#include <xeno/xeno.hpp>

#include <doctest/doctest.h>

#include <climits>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace xeno;
using xeno::test::rejection;

namespace {

template <class T>
bool body_finite(const Body<T>& b) {
    return is_finite(b.position()) && is_finite(b.orientation()) && is_finite(b.linear_velocity()) &&
           is_finite(b.angular_velocity()) && std::abs(length(b.orientation()) - T(1)) < T(1e-3);
}

template <class T>
int non_finite_bodies(const World<T>& world) {
    int bad = 0;
    world.for_each_body([&](BodyId, const Body<T>& b) { bad += body_finite(b) ? 0 : 1; });
    return bad;
}

/// The floor and 12 bodies, two of every shape kind, settled for 60 steps (1 s).
template <class T>
void settled_pile(World<T>& world) {
    BodyDef<T> ground;
    ground.type = BodyType::static_body;
    ground.position = {T(0), T(-0.5), T(0)};
    world.create_body(Box<T>(T(20), T(0.5), T(20)), ground);
    const std::vector<Vec3<T>> rock = {{T(-0.3), T(-0.2), T(-0.25)},
                                       {T(0.3), T(-0.2), T(-0.25)},
                                       {T(0), T(-0.2), T(0.3)},
                                       {T(0), T(0.3), T(0)},
                                       {T(0.1), T(0.1), T(0.1)}};
    const std::shared_ptr<const Shape<T>> kinds[] = {
        std::make_shared<const Shape<T>>(make_convex_hull(rock).polyhedron),
        std::make_shared<const Shape<T>>(Sphere<T>(T(0.3))),
        std::make_shared<const Shape<T>>(Capsule<T>(T(0.2), T(0.3))),
        std::make_shared<const Shape<T>>(Cylinder<T>(T(0.3), T(0.25))),
        std::make_shared<const Shape<T>>(Cone<T>(T(0.3), T(0.7))),
        std::make_shared<const Shape<T>>(Box<T>(T(0.3), T(0.2), T(0.25))),
    };
    for (int i = 0; i < 12; ++i) {
        BodyDef<T> d;
        d.position = {T(0.2) * T(i % 3), T(0.5) + T(0.7) * T(i), T(0.1) * T(i % 2)};
        d.orientation = normalized(Quat<T>{T(1), T(0.1) * T(i), T(0.2), T(0.05) * T(i)});
        world.create_body(kinds[i % 6], d);
    }
    for (int i = 0; i < 60; ++i) world.step(T(1) / T(60));
}

}  // namespace

// 4. Accumulated forces ---------------------------------------------------------------------------

TEST_CASE_TEMPLATE("regression: forces and torques that overflow when added up are rejected, the sum kept", T, float, double) {
    const T big = std::numeric_limits<T>::max();
    World<T> world(WorldSettings<T>{});
    const BodyId id = world.create_body(Box<T>(T(0.5), T(0.4), T(0.3)));
    Body<T>& b = world.body(id);
    b.apply_force(Vec3<T>{big, T(0), T(0)});  // the largest force there is: accepted
    CHECK_REJECTED(b.apply_force(Vec3<T>{big, T(0), T(0)}), "Body::apply_force", "accumulated force.x");
    CHECK(b.force() == Vec3<T>{big, T(0), T(0)});
    CHECK_REJECTED(b.apply_force_at(Vec3<T>{big, T(0), T(0)}, b.position()), "Body::apply_force_at", "accumulated force.x");
    CHECK(b.force() == Vec3<T>{big, T(0), T(0)});
    CHECK(b.torque() == Vec3<T>::zero());
    // A finite force at a far point whose moment overflows.
    CHECK_REJECTED(b.apply_force_at(Vec3<T>{T(0), big / T(4), T(0)}, Vec3<T>{big / T(4), T(0), T(0)}), "Body::apply_force_at",
                   "torque");
    CHECK(b.torque() == Vec3<T>::zero());
    b.apply_torque(Vec3<T>{T(0), T(0), big / T(1e6)});
    const Vec3<T> torque = b.torque();
    CHECK_REJECTED(b.apply_torque(Vec3<T>{T(0), T(0), big}), "Body::apply_torque", "accumulated torque.z");
    CHECK(b.torque() == torque);
    // A force that is finite but whose acceleration is not (a light body).
    const BodyId light = world.create_body(Sphere<T>(T(0.1)), [] {
        BodyDef<T> d;
        d.mass = T(1e-3);
        d.position = {T(5), T(0), T(0)};
        return d;
    }());
    CHECK_REJECTED(world.body(light).apply_force(Vec3<T>{T(0), big / T(2), T(0)}), "Body::apply_force", "force / mass");
    CHECK_REJECTED(world.body(light).apply_linear_impulse(Vec3<T>{T(0), big / T(2), T(0)}), "Body::apply_linear_impulse",
                   "linear_velocity.y");
    CHECK(world.body(light).force() == Vec3<T>::zero());
    CHECK(world.body(light).linear_velocity() == Vec3<T>::zero());
    // Gravity scales are limited so that gravity × scale stays finite.
    BodyDef<T> heavy;
    heavy.gravity_scale = big;
    CHECK_REJECTED(world.create_body(Sphere<T>(T(1)), heavy), "World::create_body", "gravity_scale");
    CHECK_REJECTED(b.set_gravity_scale(-big), "Body::set_gravity_scale", "scale");
    b.set_gravity_scale(ScalarTraits<T>::max_size);
    // What was accepted steps to a finite state: the speed cap holds the accelerated body.
    world.step(T(1) / T(60));
    CHECK(non_finite_bodies(world) == 0);
    CHECK(length(world.body(id).linear_velocity()) <= world.settings().max_linear_speed * T(1.0001));
}

// 5. The speed cap --------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("regression: the speed cap holds speeds whose square overflows instead of stopping the body", T, float,
                   double) {
    const T huge = std::is_same_v<T, float> ? T(1e20) : T(1e160);
    WorldSettings<T> settings;
    settings.gravity = Vec3<T>::zero();
    World<T> world(settings);
    const BodyId id = world.create_body(Sphere<T>(T(0.5)));
    world.body(id).set_linear_velocity(Vec3<T>{huge, T(0), huge / T(2)});
    world.body(id).set_angular_velocity(Vec3<T>{T(0), huge, T(0)});
    BodyDef<T> far;
    far.position = {T(0), T(100), T(0)};
    const BodyId box = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), far);
    world.body(box).set_angular_velocity(Vec3<T>{T(0), huge, T(0)});
    world.step(T(1) / T(60));
    const Body<T>& b = world.body(id);
    REQUIRE(body_finite(b));
    // Capped at 400 m/s along the direction it had (2, 0, 1)/√5.
    CHECK(test::near(length(b.linear_velocity()), settings.max_linear_speed, T(1e-5)));
    CHECK(test::near(b.linear_velocity().x, T(2) * b.linear_velocity().z, T(1e-5)));
    CHECK(test::near(b.position().x, settings.max_linear_speed * T(2) / std::sqrt(T(5)) / T(60), T(1e-4)));
    // A box's spin is capped to max_rotation_per_step per step about +y; a ball's, whose
    // surface stays in place as it turns, so that its rim moves at max_linear_speed.
    CHECK(test::near(world.body(box).angular_velocity().y, settings.max_rotation_per_step * T(60), T(1e-4)));
    CHECK(test::near(b.angular_velocity().y, settings.max_linear_speed / T(0.5), T(1e-4)));
}

TEST_CASE_TEMPLATE("regression: a huge spin or torque on a body in a pile is capped before the solver, not turned into NaN", T,
                   float, double) {
    // The spin cap came after the gyroscopic term and the contact rows, which overflowed first
    // (found by the world fuzzer): every body of the pile became NaN.
    for (const T big : {T(1e28), std::numeric_limits<T>::max() / T(2)}) {
        CAPTURE(big);
        for (const bool torque : {false, true}) {
            World<T> world;
            settled_pile(world);
            BodyId last{};
            world.for_each_body([&](BodyId id, const Body<T>&) { last = id; });
            Body<T>& b = world.body(last);
            if (torque) b.apply_torque(Vec3<T>{big, -big, big} / T(4));
            else b.set_angular_velocity(Vec3<T>{big, -big, big});
            for (int i = 0; i < 5; ++i) world.step(T(1) / T(60));
            CHECK(non_finite_bodies(world) == 0);
        }
    }
}

TEST_CASE_TEMPLATE("regression: a torque that overflows I^-1 tau after the body turns neither blocks a force nor turns into NaN",
                   T, float, double) {
    // A rod's inertia about its axis is 5,000 times smaller than across it: a torque across it,
    // accepted, overflows I⁻¹τ once the rod is turned to lay its axis along the torque. Then
    // apply_force refused any force for the torque's sake (found by the world fuzzer: it threw
    // from a force of 100 m g), and a step would have turned inf − inf into NaN. A force accepted
    // before the body's mass shrank likewise overflows f / m.
    for (const bool in_pile : {false, true}) {
        CAPTURE(in_pile);
        World<T> world;
        if (in_pile) settled_pile(world);
        BodyDef<T> def;
        def.position = {T(0), T(in_pile ? 6 : 0), T(0)};
        const BodyId rod = world.create_body(Box<T>(T(0.01), T(0.01), T(1)), def);
        Body<T>& b = world.body(rod);
        const T across = b.local_inertia()[1].y, along = b.local_inertia()[2].z;
        REQUIRE(across > T(4000) * along);
        b.apply_torque({T(0), std::numeric_limits<T>::max() / T(4) * across, T(0)});  // I⁻¹τ = max / 4
        world.set_transform(rod, def.position, Quat<T>::from_axis_angle(Vec3<T>::unit_x(), radians(T(90))));
        const Vec3<T> before = b.torque();
        CHECK_NOTHROW(b.apply_force(Vec3<T>{T(0), T(10), T(0)}));
        CHECK(b.torque() == before);
        b.apply_force(Vec3<T>{T(0), std::numeric_limits<T>::max() / T(8) * b.inverse_mass(), T(0)});
        MassProperties<T> lighter;
        lighter.mass = b.mass() / T(1000);
        lighter.inertia = b.local_inertia() * (T(1) / T(1000));
        b.set_mass_properties(lighter);
        for (int i = 0; i < 5; ++i) world.step(T(1) / T(60));
        CHECK(non_finite_bodies(world) == 0);
    }
}

// 6. Quaternions of tiny and huge components ------------------------------------------------------

TEST_CASE_TEMPLATE("regression: orientations with tiny or huge components keep their rotation", T, float, double) {
    const T tiny = std::is_same_v<T, float> ? T(1e-20) : T(1e-160);
    const T huge = std::is_same_v<T, float> ? T(1e20) : T(1e160);
    // 60° about (1, 2, 2)/3.
    const Quat<T> unit{std::sqrt(T(3)) / T(2), T(0.5) / T(3), T(1) / T(3), T(1) / T(3)};
    for (const T scale :
         {tiny, huge, T(1e-30) * (std::is_same_v<T, float> ? T(1) : T(1e-200)), std::numeric_limits<T>::max() / T(2)}) {
        CAPTURE(scale);
        const Quat<T> q = unit * scale;
        CHECK(test::same_rotation(normalized(q), unit, T(1e-6)));
        World<T> world;
        BodyDef<T> def;
        def.orientation = q;
        const BodyId id = world.create_body(Box<T>(T(1), T(0.5), T(0.25)), def);
        CHECK(test::same_rotation(world.body(id).orientation(), unit, T(1e-6)));
        world.set_transform(id, Vec3<T>{T(1), T(2), T(3)}, q * T(0.5));
        CHECK(test::same_rotation(world.body(id).orientation(), unit, T(1e-6)));
        std::vector<CompoundChild<T>> children(2, CompoundChild<T>{Shape<T>(Sphere<T>(T(0.5))), {}});
        children[1].local = {Vec3<T>{T(1), T(0), T(0)}, q};
        const Compound<T> compound(children);
        CHECK(test::same_rotation(compound.children()[1].local.orientation, unit, T(1e-6)));
    }
}

// 7. Compound children beyond the size range ------------------------------------------------------

TEST_CASE_TEMPLATE("regression: a compound child beyond the size range is rejected, not given infinite bounds", T, float,
                   double) {
    for (const T far : {std::numeric_limits<T>::max() / T(4), ScalarTraits<T>::max_size * T(2)}) {
        CAPTURE(far);
        std::vector<CompoundChild<T>> children(2, CompoundChild<T>{Shape<T>(Box<T>(T(1), T(1), T(1))), {}});
        children[1].local.position = {T(0), far, T(0)};
        CHECK_REJECTED(Compound<T>(children), "Compound", "child 1 local.position.y");
    }
    std::vector<CompoundChild<T>> children(2, CompoundChild<T>{Shape<T>(Box<T>(T(1), T(1), T(1))), {}});
    children[1].local.position = {ScalarTraits<T>::max_size, T(0), T(0)};  // the edge: accepted, finite
    const Compound<T> edge(children);
    CHECK(is_finite(edge.shift()));
    CHECK(is_finite(edge.local_bounds().min));
    CHECK(is_finite(edge.local_bounds().max));
    CHECK(std::isfinite(edge.bounding_radius()));
    CHECK(is_finite(edge.unit_mass_properties().inertia));
}

// 9. Time steps and length settings ---------------------------------------------------------------

TEST_CASE_TEMPLATE("regression: step and fixed_time_step reject dt beyond 1 s, every dt up to it keeps a pile finite", T, float,
                   double) {
    const T max_dt = T(1);
    for (const T dt : {std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::min(), T(1e-30), T(1e-6), T(1) / T(60),
                       T(0.25), max_dt}) {
        CAPTURE(dt);
        World<T> world;
        settled_pile(world);
        for (int i = 0; i < 10; ++i) world.step(dt);
        CHECK(non_finite_bodies(world) == 0);
    }
    World<T> world;
    settled_pile(world);
    std::vector<Vec3<T>> before;
    world.for_each_body([&](BodyId, const Body<T>& b) { before.push_back(b.position()); });
    for (const T dt : {max_dt * T(1.5), T(1e20), T(1e30), std::numeric_limits<T>::max()}) {
        CAPTURE(dt);
        CHECK_REJECTED(world.step(dt), "World::step", "dt");
        WorldSettings<T> s;
        s.fixed_time_step = dt;
        CHECK_REJECTED(world.set_settings(s), "WorldSettings", "fixed_time_step");
    }
    std::vector<Vec3<T>> after;
    world.for_each_body([&](BodyId, const Body<T>& b) { after.push_back(b.position()); });
    CHECK(after == before);
    CHECK(non_finite_bodies(world) == 0);
}

TEST_CASE_TEMPLATE("regression: lengths and speeds in the settings beyond their limit are rejected, at it a pile stays finite", T,
                   float, double) {
    using Edit = std::function<void(WorldSettings<T>&, T)>;
    const std::vector<std::pair<const char*, Edit>> fields = {
        {"speculative_distance", [](WorldSettings<T>& s, T v) { s.speculative_distance = v; }},
        {"linear_slop", [](WorldSettings<T>& s, T v) { s.linear_slop = v; }},
        {"contact_match_distance", [](WorldSettings<T>& s, T v) { s.contact_match_distance = v; }},
        {"max_linear_speed", [](WorldSettings<T>& s, T v) { s.max_linear_speed = v; }},
        {"max_push_out_speed", [](WorldSettings<T>& s, T v) { s.max_push_out_speed = v; }},
        {"gravity.x", [](WorldSettings<T>& s, T v) { s.gravity.x = v; }},
    };
    for (const auto& [name, edit] : fields) {
        const std::string field = name;  // clang++ 14 cannot capture a structured binding in INFO's lambda
        INFO(field);
        for (const T v : {detail::max_setting_length<T>() * T(2), T(1e38), std::numeric_limits<T>::max()}) {
            WorldSettings<T> s;
            edit(s, v);
            CHECK_REJECTED(World<T>(s), "WorldSettings", name);
        }
    }
    WorldSettings<T> s;
    s.speculative_distance = detail::max_setting_length<T>();
    World<T> world(s);
    settled_pile(world);
    for (int i = 0; i < 10; ++i) world.step(T(1) / T(60));
    CHECK(non_finite_bodies(world) == 0);
}

// A damping ratio is any finite ζ ≥ 0; one near the top of T's range overflowed the softness
// (2ζ + hω), the step was discarded as an overflow and every body in contact or on a joint froze.
// As ζ → ∞ a row is rigid and corrects no position error: a box lands on a box and stays, a
// pendulum swings on its ball joint.
TEST_CASE_TEMPLATE("regression: damping ratios at the top of the range of T damp fully, not freeze the bodies", T, float,
                   double) {
    WorldSettings<T> s;
    s.contact_damping_ratio = std::numeric_limits<T>::max();
    s.static_contact_damping_ratio = std::numeric_limits<T>::max();
    s.joint_damping_ratio = std::numeric_limits<T>::max();
    World<T> world(s);
    BodyDef<T> def;
    def.type = BodyType::static_body;
    def.position = {T(0), T(-0.5), T(0)};
    const BodyId floor = world.create_body(Box<T>(T(10), T(0.5), T(10)), def);
    def.type = BodyType::dynamic;
    def.position = {T(0), T(0.5), T(0)};
    const BodyId lower = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    def.position = {T(0), T(2.5), T(0)};
    const BodyId upper = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    def.position = {T(4), T(3), T(1)};  // 1 m from its anchor, level with it: it swings down
    const BodyId bob = world.create_body(Sphere<T>(T(0.2)), def);
    world.create_joint(JointDef<T>::ball(floor, bob, {T(4), T(3), T(0)}));
    T lowest = T(3);
    for (int i = 0; i < 120; ++i) {
        world.step(T(1) / T(60));
        lowest = std::min(lowest, world.body(bob).position().y);
    }
    CHECK(non_finite_bodies(world) == 0);
    CHECK(world.body(lower).position().y == doctest::Approx(0.5).epsilon(0.002));
    CHECK(world.body(upper).position().y == doctest::Approx(1.5).epsilon(0.002));
    CHECK(lowest < T(2.1));  // the bottom of the swing is 2 m
    CHECK(length(world.body(bob).position() - Vec3<T>{T(4), T(3), T(0)}) == doctest::Approx(1).epsilon(0.02));
}

// 10. Settings enums and counts -------------------------------------------------------------------

TEST_CASE_TEMPLATE("regression: settings reject unknown enum values and iteration counts that make a step endless", T, float,
                   double) {
    World<T> world;
    WorldSettings<T> s;
    s.broad_phase = static_cast<BroadPhaseKind>(9);
    CHECK_REJECTED(world.set_settings(s), "WorldSettings", "broad_phase");
    s = {};
    s.solver = static_cast<SolverMode>(7);
    CHECK_REJECTED(world.set_settings(s), "WorldSettings", "solver");
    CHECK(world.settings().broad_phase == WorldSettings<T>{}.broad_phase);
    using IntEdit = std::function<void(WorldSettings<T>&, int)>;
    const std::vector<std::tuple<const char*, IntEdit, int>> counts = {
        {"substeps", [](WorldSettings<T>& x, int v) { x.substeps = v; }, 64},
        {"velocity_iterations", [](WorldSettings<T>& x, int v) { x.velocity_iterations = v; }, 256},
        {"relax_iterations", [](WorldSettings<T>& x, int v) { x.relax_iterations = v; }, 256},
        {"first_relax_iterations", [](WorldSettings<T>& x, int v) { x.first_relax_iterations = v; }, 256},
        {"joint_iterations", [](WorldSettings<T>& x, int v) { x.joint_iterations = v; }, 64},
        {"max_steps_per_update", [](WorldSettings<T>& x, int v) { x.max_steps_per_update = v; }, 1000},
    };
    for (const auto& [name, edit, limit] : counts) {
        const std::string field = name;  // as above
        INFO(field);
        for (const int v : {limit + 1, 1000000, INT_MAX}) {
            WorldSettings<T> x;
            edit(x, v);
            CHECK_REJECTED(World<T>(x), "WorldSettings", name);
        }
        WorldSettings<T> x;
        edit(x, limit);
        CHECK(rejection([&] { World<T>{x}; }) == "accepted");
    }
}

// 11. Error messages name the first bad component -------------------------------------------------

TEST_CASE_TEMPLATE("regression: error messages name the bad component and its value", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    World<T> world;
    CHECK_REJECTED(world.set_gravity(Vec3<T>{nan, T(-9.81), T(0)}), "gravity.x", "(got nan)");
    CHECK_REJECTED(world.set_gravity(Vec3<T>{T(0), T(-9.81), inf}), "gravity.z", "(got inf)");
    BodyDef<T> d;
    d.position = {T(1), nan, T(3)};
    CHECK_REJECTED(world.create_body(Sphere<T>(T(1)), d), "World::create_body: position.y must be finite", "(got nan)");
    d = {};
    d.linear_velocity = {T(1), T(2), -inf};
    CHECK_REJECTED(world.create_body(Sphere<T>(T(1)), d), "linear_velocity.z must be finite", "(got -inf)");
    d = {};
    d.orientation = {T(0), T(0), T(0), T(0)};
    CHECK_REJECTED(world.create_body(Sphere<T>(T(1)), d), "World::create_body", "orientation must not be the zero quaternion");
    d.orientation = {T(1), T(0), nan, T(0)};
    CHECK_REJECTED(world.create_body(Sphere<T>(T(1)), d), "orientation.y must be finite", "(got nan)");
    std::vector<CompoundChild<T>> children(2, CompoundChild<T>{Shape<T>(Sphere<T>(T(0.5))), {}});
    children[1].local.orientation = {T(0), T(0), T(0), T(0)};
    CHECK_REJECTED(Compound<T>(children), "Compound: child 1 local.orientation", "zero quaternion");
    children[1].local = {Vec3<T>{T(0), T(0), nan}, Quat<T>::identity()};
    CHECK_REJECTED(Compound<T>(children), "child 1 local.position.z", "(got nan)");
    const BodyId id = world.create_body(Sphere<T>(T(1)));
    CHECK_REJECTED(world.body(id).set_linear_velocity(Vec3<T>{T(0), T(0), nan}), "Body::set_linear_velocity: velocity.z",
                   "(got nan)");
    CHECK_REJECTED(world.set_transform(id, Vec3<T>{T(0), inf, T(0)}, Quat<T>::identity()), "World::set_transform: position.y",
                   "(got inf)");
    CHECK_REJECTED(world.query_point(Vec3<T>{T(0), T(0), nan}), "World::query_point: point.z", "(got nan)");
    CHECK_REJECTED(world.raycast(Ray<T>{Vec3<T>{nan, T(0), T(0)}}), "World::raycast: ray.origin.x", "(got nan)");
    CHECK_REJECTED(collide(Shape<T>(Sphere<T>(T(1))), Transform<T>{Vec3<T>{T(0), nan, T(0)}, Quat<T>::identity()},
                           Shape<T>(Sphere<T>(T(1))), Transform<T>{}),
                   "pose_a.position.y", "(got nan)");
}

TEST_CASE_TEMPLATE("a body at a huge finite speed beside a destroyed one keeps finite boxes and never meets the dead slot", T,
                   float, double) {
    // Found by the world fuzzer: a velocity of 10^38 made the body's broad-phase box infinite,
    // and an infinite box overlapped the empty box of a free slot, so a destroyed body reached
    // the narrow phase. Boxes and margins now use the speed within the integrator's cap.
    World<T> w;
    BodyDef<T> d;
    const BodyId dead = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.position = {T(3), T(0), T(0)};
    const BodyId fast = w.create_body(Sphere<T>(T(0.5)), d);
    w.destroy_body(dead);
    w.body(fast).set_linear_velocity({std::numeric_limits<T>::max() / T(4), T(0), T(0)});
    for (int i = 0; i < 3; ++i) w.step(T(1) / T(60));
    CHECK(w.body_count() == 1);
    CHECK(is_finite(w.body(fast).position()));
    CHECK(length(w.body(fast).linear_velocity()) <= w.settings().max_linear_speed * T(1.0001));
}

TEST_CASE_TEMPLATE("a kinematic body at the largest finite speed touching a dynamic one leaves every state finite", T, float,
                   double) {
    // Found by the world fuzzer: a kinematic body set to 1.5e308 m/s entered the contact rows
    // uncapped and made both bodies NaN; velocities now enter the solver within the caps.
    World<T> w;
    BodyDef<T> k;
    k.type = BodyType::kinematic;
    const BodyId pusher = w.create_body(Box<T>(T(1), T(1), T(1)), k);
    BodyDef<T> d;
    d.position = {T(1.9), T(0), T(0)};
    const BodyId pushed = w.create_body(Sphere<T>(T(0.5)), d);
    const T huge = std::numeric_limits<T>::max() / T(2);
    w.body(pusher).set_linear_velocity({huge, -huge, huge});
    for (int i = 0; i < 3; ++i) w.step(T(1) / T(60));
    for (const BodyId id : {pusher, pushed}) {
        CHECK(is_finite(w.body(id).position()));
        CHECK(is_finite(w.body(id).linear_velocity()));
        CHECK(is_finite(w.body(id).angular_velocity()));
    }
}

TEST_CASE_TEMPLATE("a jointed body teleported to the far end of the range of T keeps every state finite", T, float, double) {
    // Found by the snapshot fuzzer: a body of a jointed stack restored 1.7e35 m away (float) made
    // the joint's pull (error × bias rate) overflow to inf − inf, and the sweep-and-prune axis
    // choice squared the far centre (NaN variance). The pull is capped at max_linear_speed now.
    World<T> w;
    settled_pile(w);
    BodyDef<T> d;
    d.position = {T(4), T(1), T(0)};
    const BodyId a = w.create_body(Sphere<T>(T(0.3)), d);
    d.position = {T(4), T(2), T(0)};
    const BodyId b = w.create_body(Box<T>(T(0.3), T(0.3), T(0.3)), d);
    JointDef<T> j;
    j.type = JointType::ball;
    j.a = a;
    j.b = b;
    j.anchor_a = {T(4), T(1.5), T(0)};
    j.anchor_b = j.anchor_a;
    w.create_joint(j);
    const T far = std::numeric_limits<T>::max() / T(1000);
    w.set_transform(b, {T(4), T(2), -far}, Quat<T>::identity());
    for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
    CHECK(non_finite_bodies(w) == 0);
    CHECK(length(w.body(b).linear_velocity()) <= w.settings().max_linear_speed * T(1.0001));
}

TEST_CASE_TEMPLATE("a fast body swept at its speed cap past a static box leaves every state finite", T, float, double) {
    // Found by the world fuzzer (double): a fast body at the fast-speed cap (10^30 m/s) swept
    // past a static box; the continuous-collision contact had a lever arm of 4e25 m and a closing
    // speed of 1e30 m/s, r x P overflowed and 0 x inf in the static stand-in spread NaN. Each
    // input is within its documented range; a body whose solve overflows keeps its velocity and
    // does not move for that step instead.
    World<T> w;
    BodyDef<T> ground;
    ground.type = BodyType::static_body;
    ground.position = {T(42), T(50), T(50)};
    w.create_body(Box<T>(T(10), T(10), T(10)), ground);
    BodyDef<T> d;
    d.fast = true;
    d.density = T(1e5);
    d.position = {T(-99.6), T(125.7), T(149.2)};
    d.angular_velocity = {T(3), T(5.3), T(-4.9)};
    const BodyId fast = w.create_body(Cylinder<T>(T(100), T(100)), d);
    const T huge = std::numeric_limits<T>::max() / T(1e10);
    for (int i = 0; i < 4; ++i) {
        w.body(fast).set_linear_velocity({huge, -huge, T(0)});
        w.step(T(1e-4));
        CHECK(non_finite_bodies(w) == 0);
    }
}

TEST_CASE_TEMPLATE("regression: an inertia stiff about one axis is positive definite, one with a negative minor is not", T, float,
                   double) {
    // The minors were taken of the inertia divided by its largest diagonal entry: diag(167, 1e25,
    // 167) in float (1e170 in double), a body locked against spin about y, had them underflow to 0
    // and was rejected as not positive definite.
    const T stiff = std::is_same_v<T, float> ? T(1e25) : T(1e170);
    MassProperties<T> m;
    m.mass = T(1000);
    m.inertia = Mat3<T>::diagonal({T(166.7), stiff, T(166.7)});
    World<T> w;
    Body<T>& b = w.body(w.create_body(Box<T>(T(0.5), T(0.5), T(0.5))));
    CHECK_NOTHROW(b.set_mass_properties(m));
    CHECK(b.local_inertia()[1].y == stiff);
    // It spins about x as its inertia there says, and hardly about y: I⁻¹ from rows scaled first.
    CHECK(b.inverse_inertia_local()[0].x == doctest::Approx(T(1) / T(166.7)));
    CHECK(b.inverse_inertia_local()[1].y == doctest::Approx(T(1) / stiff));
    // Still rejected: an off-diagonal term that makes a 2×2 minor negative (I_xy² > I_xx I_yy),
    // whatever the scale, and a negative diagonal entry.
    m.inertia = Mat3<T>{{T(1), T(2), T(0)}, {T(2), T(1), T(0)}, {T(0), T(0), T(1)}} * T(1e-3);
    CHECK_THROWS_AS(b.set_mass_properties(m), InvalidArgument);
    m.inertia = Mat3<T>::diagonal({T(1), T(-1), T(1)});
    CHECK_THROWS_AS(b.set_mass_properties(m), InvalidArgument);
}

TEST_CASE_TEMPLATE(
    "regression: a capsule of subnormal half height gives finite contacts, and a cylinder dropped on it steps finite", T, float,
    double) {
    // Its core's length squared underflows to 0. The contact-point rule took it and a cylinder's
    // side for two parallel segments and divided by that 0: collide() gave NaN points, and in a
    // world the manifold kept NaN anchors until merging a fifth point wrote past its four slots,
    // over its count (float: a crash in the 12th step of the scene below; double: NaN points).
    const T subnormal = std::numeric_limits<T>::denorm_min() * T(1024);
    const Shape<T> capsule = Capsule<T>(T(1), subnormal), cylinder = Cylinder<T>(T(0.5), T(1));
    for (const T x : {T(0.9), T(1), T(1.2)}) {
        CAPTURE(x);
        const Penetration<T> p = collide(capsule, Transform<T>{}, cylinder, Transform<T>{{x, T(0), T(0)}, {}});
        REQUIRE(p.hit);
        CHECK(is_finite(p.point_a));
        CHECK(is_finite(p.point_b));
        CHECK(is_finite(p.normal));
    }
    for (int k = 26; k <= 34; ++k) {
        CAPTURE(k);
        World<T> w;
        BodyDef<T> fixed;
        fixed.type = BodyType::static_body;
        w.create_body(capsule, fixed);
        fixed.position = {T(0), T(-3), T(0)};
        w.create_body(Box<T>(T(10), T(1), T(10)), fixed);
        BodyDef<T> d;
        d.position = {T(0.05) * T(k) - T(1), T(2.5), T(0.03) * T(k)};
        d.orientation = normalized(Quat<T>{T(1), T(0.02) * T(k), T(0), T(0.01) * T(k)});
        d.linear_velocity = {T(0), -T(k), T(0)};
        w.create_body(cylinder, d);
        for (int i = 0; i < 120; ++i) w.step(T(1) / T(60));
        CHECK(non_finite_bodies(w) == 0);
        for (const Contact<T>& c : w.contacts()) {
            REQUIRE(c.manifold.count >= 0);
            REQUIRE(c.manifold.count <= 4);
            for (int i = 0; i < c.manifold.count; ++i) CHECK(is_finite(c.manifold.points[static_cast<std::size_t>(i)].local_a));
        }
    }
}

TEST_CASE_TEMPLATE("regression: merging a point into a manifold of four non-finite anchors keeps it within its four slots", T,
                   float, double) {
    // Old points were dropped when `separation > margin || slide > match`, which NaN passes, so
    // they stayed; with no finite area among the five candidates none was chosen to go, and all
    // five were written back, the fifth past the array over the manifold's count.
    Manifold<T> m;
    m.normal = Vec3<T>::unit_y();
    m.count = Manifold<T>::capacity;
    const T inf = std::numeric_limits<T>::infinity();
    for (ContactPoint<T>& p : m.points) p.local_a = p.local_b = {inf, T(0), inf}, p.depth = T(0.01);
    m.friction_impulse = {T(1), T(2), T(3)};
    ManifoldPoint<T> fresh;
    fresh.point_a = {T(0), T(0), T(0)};
    fresh.point_b = {T(0), T(-0.01), T(0)};
    fresh.depth = T(0.01);
    m.merge_single(fresh, Vec3<T>::unit_y(), Transform<T>{}, Transform<T>{}, T(0.05), T(0.05));
    REQUIRE(m.count >= 1);
    REQUIRE(m.count <= Manifold<T>::capacity);
    for (int i = 0; i < m.count; ++i) CHECK(is_finite(m.points[static_cast<std::size_t>(i)].local_a));
    CHECK(m.friction_impulse == Vec3<T>{T(1), T(2), T(3)});
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The world's contract: handles, bad input at the door, the fixed-step accumulator, kinds of
// bodies, forces and impulses, destroying bodies mid-simulation.
#include "support/approx.hpp"
#include "support/sim.hpp"

#include <xeno/shape/polyhedra.hpp>

using namespace xeno;
using xeno::test::near;

TEST_CASE_TEMPLATE("a destroyed body's handle is stale and every use of it is reported", T, float, double) {
    World<T> w;
    const BodyId id = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)));
    CHECK(w.contains(id));
    w.destroy_body(id);
    CHECK_FALSE(w.contains(id));
    CHECK_THROWS_AS(w.body(id), InvalidArgument);
    CHECK_THROWS_AS(w.destroy_body(id), InvalidArgument);
    CHECK_THROWS_AS(w.set_transform(id, Vec3<T>{}, Quat<T>{}), InvalidArgument);
    CHECK_THROWS_AS(w.body(BodyId{}), InvalidArgument);
    // The slot is reused with a new generation: the old handle stays stale.
    const BodyId again = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)));
    CHECK(again.index == id.index);
    CHECK(again.generation != id.generation);
    CHECK_FALSE(w.contains(id));
    CHECK(w.contains(again));
    try {
        (void)w.body(id);
    } catch (const InvalidArgument& e) {
        CHECK(std::string(e.what()).find("stale") != std::string::npos);
    }
}

TEST_CASE_TEMPLATE("bad input at body creation and stepping is reported, never simulated", T, float, double) {
    World<T> w;
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    const Box<T> cube(T(0.5), T(0.5), T(0.5));
    BodyDef<T> d;
    d.position = {nan, T(0), T(0)};
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    d = {};
    d.orientation = {T(0), T(0), T(0), T(0)};
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    d = {};
    d.linear_velocity = {T(0), inf, T(0)};
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    d = {};
    d.angular_velocity = {nan, T(0), T(0)};
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    d = {};
    d.density = T(0);
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    d.density = T(-5);
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    d = {};
    d.material.friction = T(-1);
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    d = {};
    d.material.restitution = T(1.5);
    CHECK_THROWS_AS(w.create_body(cube, d), InvalidArgument);
    CHECK_THROWS_AS(w.create_body(std::shared_ptr<const Shape<T>>{}, BodyDef<T>{}), InvalidArgument);
    // A polyhedron whose centre of mass is not its local origin.
    const ConvexPolyhedron<T> unit = make_box_polyhedron(Vec3<T>{T(0.5), T(0.5), T(0.5)});
    std::vector<Vec3<T>> moved;
    for (const Vec3<T>& v : unit.vertices()) moved.push_back(v + Vec3<T>{T(3), T(0), T(0)});
    std::vector<std::vector<std::uint32_t>> faces;
    for (const auto& f : unit.faces())
        faces.emplace_back(unit.face_indices().begin() + f.first, unit.face_indices().begin() + f.first + f.count);
    CHECK_THROWS_AS(w.create_body(ConvexPolyhedron<T>(moved, faces)), InvalidArgument);
    CHECK(w.body_count() == 0);
    // dt must be finite and positive.
    CHECK_THROWS_AS(w.step(T(0)), InvalidArgument);
    CHECK_THROWS_AS(w.step(T(-1) / T(60)), InvalidArgument);
    CHECK_THROWS_AS(w.step(nan), InvalidArgument);
    CHECK_THROWS_AS(w.step(inf), InvalidArgument);
    CHECK_THROWS_AS(w.update(T(-1)), InvalidArgument);
    // Forces, velocities and poses at the door.
    const BodyId id = w.create_body(cube);
    CHECK_THROWS_AS(w.body(id).apply_force(Vec3<T>{nan, T(0), T(0)}), InvalidArgument);
    CHECK_THROWS_AS(w.body(id).apply_impulse_at(Vec3<T>{T(1), T(0), T(0)}, Vec3<T>{inf, T(0), T(0)}), InvalidArgument);
    CHECK_THROWS_AS(w.body(id).set_linear_velocity(Vec3<T>{T(0), nan, T(0)}), InvalidArgument);
    CHECK_THROWS_AS(w.set_transform(id, Vec3<T>{T(0), inf, T(0)}, Quat<T>{}), InvalidArgument);
    WorldSettings<T> bad;
    bad.substeps = 0;
    CHECK_THROWS_AS(World<T>{bad}, InvalidArgument);
    bad = {};
    bad.fixed_time_step = nan;
    CHECK_THROWS_AS(World<T>{bad}, InvalidArgument);
}

TEST_CASE_TEMPLATE("update runs whole fixed steps, caps them and leaves an interpolation factor", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    BodyDef<T> d;
    d.linear_velocity = {T(1), T(0), T(0)};
    d.gravity_scale = T(0);
    const BodyId id = w.create_body(Sphere<T>(T(0.5)), d);
    CHECK(w.update(T(1) / T(60) * T(2.5)) == 2);
    CHECK(near(w.interpolation_factor(), T(0.5), T(1e-3)));
    CHECK(near(w.interpolated_transform(id).position.x, T(1.5) / T(60), T(1e-4)));
    CHECK(w.update(T(10)) == w.settings().max_steps_per_update);  // the rest is dropped
    CHECK(w.interpolation_factor() < T(1));
    CHECK(near(w.body(id).position().x, T(10) / T(60), T(1e-4)));
}

// Regression: with half a step in the accumulator, a fixed step set to the smallest subnormal
// made interpolation_factor() inf (float and double alike). The next update() takes
// max_steps_per_update steps and drops the rest, so the factor is that many steps owed plus the
// fraction left: at most max_steps_per_update + 1, then below 1 once update() has run.
TEST_CASE_TEMPLATE("the interpolation factor stays finite when the fixed step shrinks to a subnormal", T, float, double) {
    World<T> w;
    w.create_body(Sphere<T>(T(0.5)));
    REQUIRE(w.update(T(1) / T(60) * T(1.5)) == 1);
    WorldSettings<T> s = w.settings();
    s.fixed_time_step = std::numeric_limits<T>::denorm_min();
    w.set_settings(s);
    const T owed = w.interpolation_factor();
    CHECK(std::isfinite(owed));
    CHECK(owed >= static_cast<T>(s.max_steps_per_update));
    CHECK(owed <= static_cast<T>(s.max_steps_per_update) + T(1));
    CHECK(w.update(T(0)) == s.max_steps_per_update);
    CHECK(w.interpolation_factor() >= T(0));
    CHECK(w.interpolation_factor() < T(1));
}

TEST_CASE_TEMPLATE("static bodies never move and kinematic bodies push dynamic ones", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const BodyId ground = scenes::add_ground(w);
    const BodyId box = scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(0.5), T(0)});
    BodyDef<T> k;
    k.type = BodyType::kinematic;
    k.position = {T(-2), T(0.5), T(0)};
    k.linear_velocity = {T(1), T(0), T(0)};
    const BodyId pusher = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), k);
    test::simulate(w, T(3));
    CHECK(w.body(ground).position() == Vec3<T>{T(0), T(-0.5), T(0)});
    CHECK(near(w.body(pusher).position().x, T(1), T(1e-3)));  // moved by its velocity only
    CHECK(near(w.body(pusher).linear_velocity().x, T(1)));
    CHECK(w.body(box).position().x > T(1.9));  // pushed ahead of it
    CHECK(w.body(pusher).mass() == std::numeric_limits<T>::infinity());
}

namespace {
/// A 0.5 m box 1 m from the axis of a 3 m platform centred at y = 0.5 (top at 0.6) turning at
/// omega about y, resting on it and moving with it.
template <class T>
BodyDef<T> turntable_rider(T omega) {
    BodyDef<T> def;
    def.position = {T(1), T(0.85), T(0)};
    def.linear_velocity = {T(0), T(0), -omega};
    def.angular_velocity = {T(0), omega, T(0)};
    return def;
}
/// Steps a rider on a turntable: while omega^2 r < mu g it stays where it was on the platform
/// (within 2 mm for 10 s); beyond, the platform throws it off within 3 s. Returns whether it held.
template <class T>
bool check_ride(World<T>& w, BodyId table, BodyId box, T omega) {
    if (omega * omega < T(0.6) * T(9.81)) {
        T drift = T(0);
        test::simulate(w, T(10), [&](int) {
            drift = std::max(drift, length(w.body(table).local_point(w.body(box).position()) - Vec3<T>{T(1), T(0.35), T(0)}));
        });
        CHECK(drift < T(0.002));
        return true;
    }
    test::simulate(w, T(3));
    const Vec3<T> p = w.body(box).position();
    CHECK(std::sqrt(p.x * p.x + p.z * p.z) > T(3));  // thrown off the 3 m platform
    return false;
}
}  // namespace

TEST_CASE_TEMPLATE("regression: a box on a turntable turns with it while omega^2 r < mu g and slides off beyond", C,
                   XENO_TEST_CONFIGS) {
    // The friction row held the box to the platform's velocity at the step's start, so it moved
    // along the tangent every step (an explicit Euler step of the circle) and spiralled out: at
    // 1 m, 1 rad/s it drifted 8 mm/s (0.18 m in 10 s), and at 2.2 rad/s it slid off, though
    // friction can hold it up to omega^2 r = mu g (chord_slip, contact_solver.hpp).
    using T = typename C::T;
    for (const T omega : {T(1), T(2.2), T(3)})
        for (const bool table_first : {true, false}) {  // the platform as body A of the contact, then as B
            World<T> w(C::settings());
            BodyDef<T> k;
            k.type = BodyType::kinematic;
            k.position = {T(0), T(0.5), T(0)};  // above the ground, so the box rests on the platform alone
            k.angular_velocity = {T(0), omega, T(0)};
            const BodyDef<T> def = turntable_rider(omega);
            const BodyId first =
                table_first ? w.create_body(Cylinder<T>(T(3), T(0.1)), k) : w.create_body(Box<T>(T(0.25), T(0.25), T(0.25)), def);
            const BodyId second =
                table_first ? w.create_body(Box<T>(T(0.25), T(0.25), T(0.25)), def) : w.create_body(Cylinder<T>(T(3), T(0.1)), k);
            const BodyId table = table_first ? first : second, box = table_first ? second : first;
            CAPTURE(omega);
            CAPTURE(table_first);
            check_ride(w, table, box, omega);
        }
}

TEST_CASE_TEMPLATE(
    "regression: a box on a dynamic turntable, motor-driven or spinning free, turns with it while omega^2 r < mu g", C,
    XENO_TEST_CONFIGS) {
    // The chord slip of the test above was given to kinematic sides only, so a box on a
    // merry-go-round built as a dynamic disc on a hinge drifted as the kinematic one did: 8.7 cm
    // in 10 s at 1 m and 1 rad/s, and at 2 rad/s (omega^2 r = 0.68 mu g) it slid off.
    using T = typename C::T;
    for (const T omega : {T(1), T(2.2), T(3)})
        for (const bool motor : {true, false}) {
            World<T> w(C::settings());
            const BodyId ground = scenes::add_ground(w);
            BodyDef<T> disc;
            disc.position = {T(0), T(0.5), T(0)};  // clear of the ground, so the box rests on the disc alone
            disc.angular_velocity = {T(0), omega, T(0)};
            const BodyId table = w.create_body(Cylinder<T>(T(3), T(0.1)), disc);
            JointDef<T> hinge = JointDef<T>::hinge(ground, table, disc.position, Vec3<T>{T(0), T(1), T(0)});
            hinge.enable_motor = motor;
            hinge.motor_speed = omega;
            hinge.max_motor_torque = T(1e7);
            w.create_joint(hinge);
            const BodyId box = w.create_body(Box<T>(T(0.25), T(0.25), T(0.25)), turntable_rider(omega));
            CAPTURE(omega);
            CAPTURE(motor);
            if (check_ride(w, table, box, omega))
                CHECK(near(w.body(table).angular_velocity().y, omega, T(1e-3)));  // nothing slid: no torque between them
        }
}

TEST_CASE_TEMPLATE("forces and impulses at a point change velocity and spin as Newton says", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    WorldSettings<T> s = C::weightless();
    World<T> w(s);
    const BodyId id = w.create_body(Sphere<T>(T(0.5)));
    Body<T>& b = w.body(id);
    const T m = b.mass();
    CHECK(near(m, T(1000) * T(4) / T(3) * ScalarTraits<T>::pi * T(0.125), T(1e-4)));
    b.apply_impulse_at(Vec3<T>{T(0), T(0), T(2)}, Vec3<T>{T(0.5), T(0), T(0)});
    CHECK(near(b.linear_velocity(), Vec3<T>{T(0), T(0), T(2) / m}));
    const T inertia = T(0.4) * m * T(0.25);
    CHECK(near(b.angular_velocity(), Vec3<T>{T(0), T(-1) / inertia, T(0)}));  // r × J = (0.5,0,0) × (0,0,2)
    b.set_linear_velocity({});
    b.set_angular_velocity({});
    b.apply_force_at(Vec3<T>{T(m), T(0), T(0)}, w.body(id).position() + Vec3<T>{T(0), T(0.5), T(0)});
    w.step(T(1) / T(60));
    CHECK(near(w.body(id).linear_velocity().x, T(1) / T(60), T(1e-4)));  // a = F/m = 1 m/s²
    CHECK(w.body(id).angular_velocity().z < T(0));                       // (0, 0.5, 0) × (m, 0, 0) points along -z
    CHECK(w.body(id).force() == Vec3<T>::zero());                        // forces last one step
    // World/body frame helpers round-trip.
    const Vec3<T> p{T(0.1), T(0.2), T(0.3)};
    CHECK(near(w.body(id).local_point(w.body(id).world_point(p)), p));
    CHECK(near(w.body(id).local_vector(w.body(id).world_vector(p)), p));
}

TEST_CASE_TEMPLATE("destroying a body under another leaves a consistent world and the top one falls", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    scenes::add_ground(w);
    const BodyId bottom = scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(0.5), T(0)});
    const BodyId top = scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(1.5), T(0)});
    test::simulate(w, T(1));
    REQUIRE(w.contacts().size() == 2);
    w.destroy_body(bottom);
    for (const Contact<T>& c : w.contacts()) {
        CHECK(c.a != bottom);
        CHECK(c.b != bottom);
    }
    CHECK_FALSE(w.contains(bottom));
    test::simulate(w, T(2));
    CHECK(near(w.body(top).position().y, T(0.5), T(0.01)));  // on the ground now
    CHECK(w.contacts().size() == 1);
}

TEST_CASE_TEMPLATE("a resting island sleeps, and wakes when touched or pushed", T, float, double) {
    World<T> w;  // sleeping on
    scenes::add_ground(w);
    const BodyId box = scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(0.5), T(0)});
    test::simulate(w, T(2));
    CHECK_FALSE(w.body(box).awake());
    CHECK(w.last_step_stats().awake_bodies == 0);
    // Pushed: awake again, and it moves.
    w.body(box).apply_linear_impulse(Vec3<T>{T(3000), T(0), T(0)});  // 3 m/s on 1000 kg
    CHECK(w.body(box).awake());
    test::simulate(w, T(0.2));
    CHECK(w.body(box).position().x > T(0.05));
    test::simulate(w, T(3));
    CHECK_FALSE(w.body(box).awake());
    // Touched by a falling body: wakes.
    const T x = w.body(box).position().x;
    const BodyId ball = w.create_body(Sphere<T>(T(0.3)), [&] {
        BodyDef<T> d;
        d.position = {x + T(0.3), T(3), T(0)};
        return d;
    }());
    bool woke = false;
    test::simulate(w, T(1), [&](int) { woke |= w.body(box).awake(); });
    CHECK(woke);
    CHECK(w.contains(ball));
    // Opting out keeps it awake.
    w.body(box).set_allow_sleep(false);
    test::simulate(w, T(3));
    CHECK(w.body(box).awake());
}

TEST_CASE_TEMPLATE("a sleeping stack wakes when the body under it is destroyed or starts to move", T, float, double) {
    World<T> w;  // sleeping on
    scenes::add_ground(w);
    BodyDef<T> platform_def;
    platform_def.type = BodyType::kinematic;
    platform_def.position = {T(0), T(0.25), T(0)};
    const BodyId platform = w.create_body(Box<T>(T(2), T(0.25), T(2)), platform_def);
    const BodyId lower = scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(1), T(0)});
    const BodyId upper = scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(2), T(0)});
    test::simulate(w, T(2));
    REQUIRE_FALSE(w.body(upper).awake());
    REQUIRE_FALSE(w.body(lower).awake());
    // Asleep, the island costs nothing: only the kinematic platform is a solver body, and the
    // sleepers are not integrated.
    CHECK(w.last_step_stats().awake_bodies == 1);
    const Vec3<T> rest = w.body(upper).position();
    test::simulate(w, T(1));
    CHECK(w.body(upper).position() == rest);  // bitwise: not integrated

    // The kinematic platform starts to slide: the stack on it wakes and rides along.
    w.body(platform).set_linear_velocity(Vec3<T>{T(0.5), T(0), T(0)});
    test::simulate(w, T(0.5));
    CHECK(w.body(lower).awake());
    CHECK(w.body(upper).awake());
    CHECK(w.body(upper).position().x > rest.x + T(0.1));
    w.body(platform).set_linear_velocity(Vec3<T>{});
    test::simulate(w, T(3));
    REQUIRE_FALSE(w.body(upper).awake());

    // The lower box is destroyed: the upper one wakes and falls onto the platform.
    const T top_before = w.body(upper).position().y;
    w.destroy_body(lower);
    CHECK(w.body(upper).awake());
    test::simulate(w, T(2));
    CHECK(w.body(upper).position().y < top_before - T(0.9));
}

// A moved-from mesh, heightfield, compound or hull is a valid C++ object with nothing in it: the
// mesh crashed create_body (its bounds read an empty tree), and an empty compound or hull was
// accepted and left a world whose own snapshot did not restore. Each is refused, and the world
// is unchanged.
TEST_CASE_TEMPLATE("regression: a moved-from mesh, heightfield, compound or hull is refused by create_body and set_shape", T,
                   float, double) {
    World<T> w;
    BodyDef<T> def;
    def.position = {T(0), T(3), T(0)};
    const BodyId box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    const std::size_t bodies = w.body_count();
    BodyDef<T> fixed;
    fixed.type = BodyType::static_body;

    TriangleMesh<T> mesh({{T(-5), T(0), T(-5)}, {T(5), T(0), T(-5)}, {T(0), T(0), T(5)}}, {{{0, 2, 1}}});
    const TriangleMesh<T> mesh_kept = std::move(mesh);
    CHECK_THROWS_AS(w.create_body(mesh, fixed), InvalidArgument);  // NOLINT(bugprone-use-after-move)
    HeightField<T> field(3, 3, std::vector<T>(9, T(0)), T(1));
    const HeightField<T> field_kept = std::move(field);
    CHECK_THROWS_AS(w.create_body(field, fixed), InvalidArgument);  // NOLINT(bugprone-use-after-move)
    Compound<T> compound({CompoundChild<T>{Sphere<T>(T(1)), {}}});
    const Compound<T> compound_kept = std::move(compound);
    CHECK_THROWS_AS(w.create_body(compound, def), InvalidArgument);  // NOLINT(bugprone-use-after-move)
    CHECK_THROWS_AS(w.set_shape(box, std::make_shared<const Compound<T>>(compound)), InvalidArgument);
    ConvexPolyhedron<T> hull = make_box_polyhedron<T>({T(1), T(1), T(1)});
    const ConvexPolyhedron<T> hull_kept = std::move(hull);
    CHECK_THROWS_AS(w.create_body(Shape<T>(hull), def), InvalidArgument);  // NOLINT(bugprone-use-after-move)
    CHECK_THROWS_AS(w.set_shape(box, std::make_shared<const Shape<T>>(hull)), InvalidArgument);
    CHECK(w.body_count() == bodies);
    CHECK(std::holds_alternative<Box<T>>(w.body(box).shape()));
    // The kept ones still make bodies.
    CHECK_NOTHROW(w.create_body(mesh_kept, fixed));
    CHECK_NOTHROW(w.create_body(compound_kept, def));
    CHECK_NOTHROW(w.create_body(Shape<T>(hull_kept), def));
    (void)field_kept;
    w.step(T(1) / T(60));
}

// The queries took them unchecked: a moved-from hull crashed collide, intersect, shape_cast and
// the world's shape queries (its support read no vertices), a compound took one as a child, and
// a moved-from mesh or heightfield crashed its ray casts and the mesh queries.
TEST_CASE_TEMPLATE("regression: a moved-from hull is refused by every query, and a moved-from mesh has no triangles", T, float,
                   double) {
    World<T> w;
    BodyDef<T> def;
    w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    ConvexPolyhedron<T> kept_hull = make_box_polyhedron<T>({T(1), T(1), T(1)});
    Shape<T> hull = kept_hull;
    const Shape<T> kept = std::move(hull);
    const Shape<T> ball = Sphere<T>(T(1));
    const Transform<T> here{};
    Ray<T> ray;
    ray.origin = {T(0.2), T(5), T(0.2)};
    ray.direction = {T(0), T(-1), T(0)};
    // NOLINTBEGIN(bugprone-use-after-move)
    CHECK_THROWS_AS(intersect(hull, here, ball, here), InvalidArgument);
    CHECK_THROWS_AS(collide(ball, here, hull, here), InvalidArgument);
    CHECK_THROWS_AS(raycast(hull, here, ray), InvalidArgument);
    CHECK_THROWS_AS(shape_cast(hull, here, Vec3<T>{T(1), T(0), T(0)}, ball, here), InvalidArgument);
    CHECK_THROWS_AS(mass_properties(hull, T(1)), InvalidArgument);
    CHECK_THROWS_AS(w.overlap_shape(hull, here), InvalidArgument);
    CHECK_THROWS_AS(w.shape_cast(hull, here, Vec3<T>{T(1), T(0), T(0)}), InvalidArgument);
    CHECK_THROWS_AS(Compound<T>({CompoundChild<T>{hull, {}}}), InvalidArgument);
    CHECK(intersect(kept, here, ball, here));
    TriangleMesh<T> mesh({{T(-5), T(0), T(-5)}, {T(5), T(0), T(-5)}, {T(0), T(0), T(5)}}, {{{0, 2, 1}}});
    const TriangleMesh<T> kept_mesh = std::move(mesh);
    HeightField<T> field(3, 3, std::vector<T>(9, T(0)), T(1));
    const HeightField<T> kept_field = std::move(field);
    CHECK_FALSE(mesh.raycast(ray));
    CHECK_FALSE(field.raycast(ray));
    for (const MeshShape<T>& empty : {MeshShape<T>(mesh), MeshShape<T>(field)}) {
        CHECK_FALSE(raycast(empty, here, ray));
        CHECK_FALSE(intersect_mesh(empty, here, ball, here));
        CHECK_FALSE(shape_cast(ball, Transform<T>{{T(0), T(3), T(0)}, {}}, Vec3<T>{T(0), T(-5), T(0)}, empty, here));
    }
    // NOLINTEND(bugprone-use-after-move)
    CHECK(kept_mesh.raycast(ray));
    CHECK(kept_field.raycast(ray));
}

// A finite, non-zero hinge axis of length 1e-20 (or 1e20 in float) had |axis|² underflow (or
// overflow) and was refused as "zero"; and set_shape took an out-of-range MassUpdate as recompute.
TEST_CASE_TEMPLATE("regression: a tiny or huge joint axis is an axis, and set_shape refuses an unknown MassUpdate", T, float,
                   double) {
    World<T> w;
    BodyDef<T> def;
    const BodyId a = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    def.position = {T(2), T(0), T(0)};
    const BodyId b = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    for (const T length : {T(1e-20), T(1e20)}) {
        CAPTURE(length);
        JointId j{};
        CHECK_NOTHROW(j = w.create_joint(JointDef<T>::hinge(a, b, Vec3<T>{T(1), T(0), T(0)}, Vec3<T>{length, length, T(0)})));
        CHECK_NOTHROW(w.destroy_joint(j));
    }
    const std::size_t bodies = w.body_count();
    CHECK_THROWS_AS(w.set_shape(a, std::make_shared<const Shape<T>>(Sphere<T>(T(1))), static_cast<MassUpdate>(5)),
                    InvalidArgument);
    CHECK(std::holds_alternative<Box<T>>(w.body(a).shape()));
    CHECK(w.body_count() == bodies);
}

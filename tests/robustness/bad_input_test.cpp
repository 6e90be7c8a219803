// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Bad input at every public door (docs/robustness.md, "Bad input"): each case throws
// xeno::InvalidArgument whose message names the function and the argument. Cases already tested
// elsewhere are not repeated here: the world's creation/step/stale-handle basics
// (dynamics/world_test.cpp), shape sizes of one sign and NaN (shape/shapes_test.cpp), degenerate
// hull clouds (shape/convex_hull_test.cpp), broken polyhedra (shape/convex_polyhedron_test.cpp),
// non-positive density (shape/mass_properties_test.cpp) and non-finite MPR poses
// (collide/mpr_test.cpp). The regressions at the end are inputs the library accepted before this
// file existed and answered with NaN, infinity or a wrong answer.
#include "support/rejection.hpp"
#include "support/approx.hpp"

#include <xeno/xeno.hpp>

#include <doctest/doctest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace xeno;
using xeno::test::rejection;

namespace {

template <class T>
std::vector<T> non_positive_or_non_finite() {
    return {T(0),
            T(-0.0),
            T(-1),
            std::numeric_limits<T>::quiet_NaN(),
            std::numeric_limits<T>::infinity(),
            -std::numeric_limits<T>::infinity()};
}

template <class T>
std::vector<T> negative_or_non_finite() {
    return {T(-1), -std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(),
            -std::numeric_limits<T>::infinity()};
}

template <class T>
std::vector<T> non_finite() {
    return {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity()};
}

template <class T>
ConvexPolyhedron<T> unit_cube_hull() {
    return make_box_polyhedron(Vec3<T>{T(0.5), T(0.5), T(0.5)});
}

}  // namespace

// Shapes -----------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("every shape builder rejects zero, negative, NaN and infinite sizes, naming the argument", T, float, double) {
    for (const T v : non_positive_or_non_finite<T>()) {
        CAPTURE(v);
        CHECK_REJECTED(Sphere<T>(v), "Sphere", "radius");
        CHECK_REJECTED(Box<T>(v, T(1), T(1)), "Box", "half_extents.x");
        CHECK_REJECTED(Box<T>(T(1), v, T(1)), "Box", "half_extents.y");
        CHECK_REJECTED(Box<T>(T(1), T(1), v), "Box", "half_extents.z");
        CHECK_REJECTED(Capsule<T>(v, T(1)), "Capsule", "radius");
        if (!(v == T(0))) CHECK_REJECTED(Capsule<T>(T(1), v), "Capsule", "half_height");  // 0 is a sphere
        CHECK_REJECTED(Cylinder<T>(v, T(1)), "Cylinder", "radius");
        CHECK_REJECTED(Cylinder<T>(T(1), v), "Cylinder", "half_height");
        CHECK_REJECTED(Cone<T>(v, T(1)), "Cone", "radius");
        CHECK_REJECTED(Cone<T>(T(1), v), "Cone", "height");
        CHECK_REJECTED(make_box_polyhedron(Vec3<T>{v, T(1), T(1)}), "make_box_polyhedron", "half_extents.x");
        CHECK_REJECTED(make_box_polyhedron(Vec3<T>{T(1), v, T(1)}), "make_box_polyhedron", "half_extents.y");
        CHECK_REJECTED(make_triangular_prism(v, T(1), T(1)), "make_triangular_prism", "half_width");
        CHECK_REJECTED(make_triangular_prism(T(1), v, T(1)), "make_triangular_prism", "height");
        CHECK_REJECTED(make_triangular_prism(T(1), T(1), v), "make_triangular_prism", "half_depth");
        CHECK_REJECTED(make_tetrahedron(v), "make_tetrahedron", "edge");
        CHECK_REJECTED(make_regular_prism(6, v, T(1)), "make_regular_prism", "radius");
        CHECK_REJECTED(make_regular_prism(6, T(1), v), "make_regular_prism", "half_height");
    }
    CHECK_REJECTED(make_regular_prism(-4, T(1), T(1)), "make_regular_prism", "sides");
    CHECK(rejection([] { (void)Capsule<T>(T(1), T(0)); }) == "accepted");
}

TEST_CASE_TEMPLATE("make_convex_hull rejects an empty cloud, infinite coordinates and three points repeated", T, float, double) {
    using V = Vec3<T>;
    CHECK_REJECTED(make_convex_hull(std::vector<V>{}), "make_convex_hull", "at least 4 points");
    for (const T v : non_finite<T>()) {
        CAPTURE(v);
        std::vector<V> points{{T(0), T(0), T(0)}, {T(1), T(0), T(0)}, {T(0), T(1), T(0)}, {T(0), T(0), T(1)}};
        points[2].z = v;
        CHECK_REJECTED(make_convex_hull(points), "make_convex_hull", "point 2.z must be finite");
    }
    std::vector<V> triangle;
    for (int i = 0; i < 30; ++i)
        for (const V& p : {V{T(0), T(0), T(0)}, V{T(1), T(0), T(0)}, V{T(0), T(1), T(0)}}) triangle.push_back(p);
    CHECK_REJECTED(make_convex_hull(triangle), "make_convex_hull", "coplanar");
}

TEST_CASE_TEMPLATE("ConvexPolyhedron rejects too few faces, two-vertex faces, unused vertices and infinite vertices", T, float,
                   double) {
    const ConvexPolyhedron<T> cube = unit_cube_hull<T>();
    std::vector<std::vector<std::uint32_t>> faces;
    for (const auto& f : cube.faces())
        faces.emplace_back(cube.face_indices().begin() + f.first, cube.face_indices().begin() + f.first + f.count);
    const std::vector<Vec3<T>> v = cube.vertices();
    CHECK_REJECTED(ConvexPolyhedron<T>(v, {faces[0], faces[1], faces[2]}), "ConvexPolyhedron", "at least 4 faces");
    auto two = faces;
    two[2] = {two[2][0], two[2][1]};
    CHECK_REJECTED(ConvexPolyhedron<T>(v, two), "ConvexPolyhedron", "face 2 needs 3 or more vertices");
    auto extra = v;
    extra.push_back(Vec3<T>{T(0), T(0), T(0)});
    CHECK_REJECTED(ConvexPolyhedron<T>(extra, faces), "ConvexPolyhedron", "no face uses");
    for (const T bad : non_finite<T>()) {
        auto broken = v;
        broken[5].x = bad;
        CHECK_REJECTED(ConvexPolyhedron<T>(broken, faces), "ConvexPolyhedron", "vertex 5.x must be finite");
    }
}

TEST_CASE_TEMPLATE("mass_properties rejects infinite density for every shape kind", T, float, double) {
    const Shape<T> shapes[] = {Sphere<T>(T(1)),         Box<T>(T(1), T(1), T(1)), Capsule<T>(T(1), T(1)),
                               Cylinder<T>(T(1), T(1)), Cone<T>(T(1), T(1)),      unit_cube_hull<T>()};
    for (const Shape<T>& s : shapes) {
        CAPTURE(shape_name(s));
        CHECK_REJECTED(mass_properties(s, std::numeric_limits<T>::infinity()), "mass_properties", "density");
        CHECK_REJECTED(mass_properties(s, -std::numeric_limits<T>::infinity()), "mass_properties", "density");
        CHECK_REJECTED(mass_properties(s, T(-0.0)), "mass_properties", "density");
    }
}

// World settings ---------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("every WorldSettings field is checked by the constructor, set_settings and set_gravity", T, float, double) {
    using Edit = std::function<void(WorldSettings<T>&, T)>;
    struct Field {
        const char* name;
        Edit edit;
        bool zero_allowed;
    };
    const std::vector<Field> fields = {
        {"gravity", [](WorldSettings<T>& s, T v) { s.gravity.y = v; }, true},
        {"fixed_time_step", [](WorldSettings<T>& s, T v) { s.fixed_time_step = v; }, false},
        {"contact_hertz", [](WorldSettings<T>& s, T v) { s.contact_hertz = v; }, false},
        {"contact_damping_ratio", [](WorldSettings<T>& s, T v) { s.contact_damping_ratio = v; }, true},
        {"static_contact_hertz_scale", [](WorldSettings<T>& s, T v) { s.static_contact_hertz_scale = v; }, false},
        {"static_contact_damping_ratio", [](WorldSettings<T>& s, T v) { s.static_contact_damping_ratio = v; }, true},
        {"baumgarte", [](WorldSettings<T>& s, T v) { s.baumgarte = v; }, true},
        {"max_push_out_speed", [](WorldSettings<T>& s, T v) { s.max_push_out_speed = v; }, false},
        {"linear_slop", [](WorldSettings<T>& s, T v) { s.linear_slop = v; }, true},
        {"speculative_distance", [](WorldSettings<T>& s, T v) { s.speculative_distance = v; }, true},
        {"contact_match_distance", [](WorldSettings<T>& s, T v) { s.contact_match_distance = v; }, false},
        {"restitution_threshold", [](WorldSettings<T>& s, T v) { s.restitution_threshold = v; }, true},
        {"max_linear_speed", [](WorldSettings<T>& s, T v) { s.max_linear_speed = v; }, false},
        {"max_rotation_per_step", [](WorldSettings<T>& s, T v) { s.max_rotation_per_step = v; }, false},
        {"sleep_linear_speed", [](WorldSettings<T>& s, T v) { s.sleep_linear_speed = v; }, true},
        {"sleep_angular_speed", [](WorldSettings<T>& s, T v) { s.sleep_angular_speed = v; }, true},
        {"sleep_time", [](WorldSettings<T>& s, T v) { s.sleep_time = v; }, true},
    };
    World<T> world;
    for (const Field& field : fields) {
        CAPTURE(field.name);
        std::vector<T> bad = non_finite<T>();
        if (std::string(field.name) != "gravity") bad.push_back(T(-1));
        if (!field.zero_allowed) bad.push_back(T(0));
        for (const T v : bad) {
            CAPTURE(v);
            WorldSettings<T> s;
            field.edit(s, v);
            CHECK_REJECTED(World<T>(s), "WorldSettings", field.name);
            CHECK_REJECTED(world.set_settings(s), "WorldSettings", field.name);
        }
    }
    for (const T v : non_finite<T>()) CHECK_REJECTED(world.set_gravity(Vec3<T>{T(0), T(0), v}), "WorldSettings", "gravity");
    using IntEdit = std::function<void(WorldSettings<T>&)>;
    const std::vector<std::pair<const char*, IntEdit>> counts = {
        {"max_steps_per_update", [](WorldSettings<T>& s) { s.max_steps_per_update = 0; }},
        {"velocity_iterations", [](WorldSettings<T>& s) { s.velocity_iterations = 0; }},
        {"relax_iterations", [](WorldSettings<T>& s) { s.relax_iterations = -1; }},
        {"first_relax_iterations", [](WorldSettings<T>& s) { s.first_relax_iterations = -1; }},
        {"substeps", [](WorldSettings<T>& s) { s.substeps = -3; }},
    };
    for (const auto& [name, edit] : counts) {
        WorldSettings<T> s;
        edit(s);
        CHECK_REJECTED(World<T>(s), "WorldSettings", name);
        CHECK_REJECTED(world.set_settings(s), "WorldSettings", name);
    }
    // A rejected change leaves the settings as they were.
    CHECK(world.settings().fixed_time_step == WorldSettings<T>{}.fixed_time_step);
    CHECK(world.settings().gravity == WorldSettings<T>{}.gravity);
}

// Bodies -----------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("body definitions with bad damping, gravity scale, mass, density or pose are rejected and leave no body", T,
                   float, double) {
    World<T> world;
    const auto cube = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
    const char* where = "World::create_body";
    for (const T v : negative_or_non_finite<T>()) {
        CAPTURE(v);
        BodyDef<T> d;
        d.linear_damping = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "linear_damping");
        d = {};
        d.angular_damping = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "angular_damping");
        d = {};
        d.mass = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "mass");
        d = {};
        d.material.friction = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "friction");
        d = {};
        d.material.restitution = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "restitution");
    }
    for (const T v : non_finite<T>()) {
        CAPTURE(v);
        BodyDef<T> d;
        d.gravity_scale = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "gravity_scale");
        d = {};
        d.density = v;
        CHECK_REJECTED(world.create_body(cube, d), "density", "must be finite and > 0");
        d = {};
        d.position.z = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "position");
        d = {};
        d.orientation.y = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "orientation");
        d = {};
        d.type = BodyType::kinematic;  // velocities are checked whatever the type
        d.linear_velocity.x = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "linear_velocity");
        d = {};
        d.type = BodyType::static_body;
        d.angular_velocity.z = v;
        CHECK_REJECTED(world.create_body(cube, d), where, "angular_velocity");
    }
    CHECK(world.body_count() == 0);
    // Accepted: a non-unit orientation is normalised; a static body needs no density.
    BodyDef<T> d;
    d.orientation = Quat<T>{T(2), T(0), T(0), T(2)};
    const BodyId tilted = world.create_body(cube, d);
    CHECK(test::near(length(Vec3<T>{world.body(tilted).orientation().x, world.body(tilted).orientation().y,
                                    world.body(tilted).orientation().z}),
                     T(std::sqrt(0.5))));
    d = {};
    d.type = BodyType::static_body;
    d.density = T(0);
    CHECK(rejection([&] { (void)world.create_body(cube, d); }) == "accepted");
}

TEST_CASE_TEMPLATE("body setters reject non-finite and negative values, name the argument and change nothing", T, float, double) {
    World<T> world;
    const BodyId id = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)));
    Body<T>& b = world.body(id);
    b.set_linear_velocity(Vec3<T>{T(1), T(2), T(3)});
    const Vec3<T> v0 = b.linear_velocity(), w0 = b.angular_velocity();
    for (const T v : non_finite<T>()) {
        CAPTURE(v);
        const Vec3<T> bad{T(0), v, T(0)};
        const Vec3<T> fine{T(1), T(0), T(0)};
        CHECK_REJECTED(b.set_angular_velocity(bad), "Body::set_angular_velocity", "angular_velocity.y");
        CHECK_REJECTED(b.apply_force(bad), "Body::apply_force", "force");
        CHECK_REJECTED(b.apply_force_at(bad, fine), "Body::apply_force_at", "force");
        CHECK_REJECTED(b.apply_force_at(fine, bad), "Body::apply_force_at", "point");
        CHECK_REJECTED(b.apply_torque(bad), "Body::apply_torque", "torque");
        CHECK_REJECTED(b.apply_impulse_at(bad, fine), "Body::apply_impulse_at", "impulse");
        CHECK_REJECTED(b.apply_linear_impulse(bad), "Body::apply_linear_impulse", "impulse");
        CHECK_REJECTED(b.apply_angular_impulse(bad), "Body::apply_angular_impulse", "impulse");
        CHECK_REJECTED(b.set_gravity_scale(v), "Body::set_gravity_scale", "scale");
        CHECK_REJECTED(world.set_transform(id, Vec3<T>::zero(), Quat<T>{v, T(0), T(0), T(0)}), "World::set_transform",
                       "orientation");
    }
    for (const T v : negative_or_non_finite<T>()) {
        CAPTURE(v);
        CHECK_REJECTED(b.set_damping(v, T(0)), "Body::set_damping", "linear");
        CHECK_REJECTED(b.set_damping(T(0), v), "Body::set_damping", "angular");
        Material<T> m;
        m.friction = v;
        CHECK_REJECTED(b.set_material(m), "Body::set_material", "friction");
        m = {};
        m.restitution = v;
        CHECK_REJECTED(b.set_material(m), "Body::set_material", "restitution");
    }
    Material<T> bouncy;
    bouncy.restitution = T(1.5);
    CHECK_REJECTED(b.set_material(bouncy), "Body::set_material", "restitution");
    CHECK(b.linear_velocity() == v0);
    CHECK(b.angular_velocity() == w0);
    CHECK(b.force() == Vec3<T>::zero());
    CHECK(b.torque() == Vec3<T>::zero());
    CHECK(b.linear_damping() == T(0));
    CHECK(b.gravity_scale() == T(1));
    CHECK(b.material().friction == Material<T>{}.friction);
}

TEST_CASE_TEMPLATE("set_mass_properties rejects bad mass, an off-centre centre and a static body", T, float, double) {
    World<T> world;
    BodyDef<T> ground;
    ground.type = BodyType::static_body;
    const BodyId fixed = world.create_body(Box<T>(T(1), T(1), T(1)), ground);
    const BodyId id = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)));
    Body<T>& b = world.body(id);  // no body is created below: the reference stays valid
    const MassProperties<T> good = mass_properties(Box<T>(T(0.5), T(0.5), T(0.5)), T(1000));
    for (const T v : non_positive_or_non_finite<T>()) {
        MassProperties<T> m = good;
        m.mass = v;
        CHECK_REJECTED(b.set_mass_properties(m), "Body::set_mass_properties", "mass");
    }
    MassProperties<T> m = good;
    m.center = {T(0.1), T(0), T(0)};
    CHECK_REJECTED(b.set_mass_properties(m), "Body::set_mass_properties", "center");
    for (const T v : non_positive_or_non_finite<T>()) {
        CAPTURE(v);
        m = good;
        m.inertia.row[1].y = v;
        CHECK_REJECTED(b.set_mass_properties(m), "Body::set_mass_properties", "inertia");
    }
    CHECK_REJECTED(world.body(fixed).set_mass_properties(good), "Body::set_mass_properties", "only dynamic bodies");
    CHECK(test::near(b.mass(), good.mass));
}

// Handles ----------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("stale, default and out-of-range handles are reported by every World method that takes a BodyId", T, float,
                   double) {
    World<T> world;
    const BodyId live = world.create_body(Sphere<T>(T(0.5)));
    const BodyId stale = world.create_body(Sphere<T>(T(0.5)));
    world.destroy_body(stale);
    const World<T>& read_only = world;
    struct Handle {
        BodyId id;
        const char* message;
    };
    for (const Handle& h :
         {Handle{stale, "stale body handle"}, Handle{BodyId{}, "invalid body handle"},
          Handle{BodyId{1000, 0}, "stale body handle"}, Handle{BodyId{live.index, live.generation + 1}, "stale"}}) {
        CAPTURE(h.id.index);
        CAPTURE(h.id.generation);
        CHECK_FALSE(world.contains(h.id));
        CHECK_REJECTED(world.body(h.id), "World::body", h.message);
        CHECK_REJECTED(read_only.body(h.id), "World::body", h.message);
        CHECK_REJECTED(world.destroy_body(h.id), "World::destroy_body", h.message);
        CHECK_REJECTED(world.set_transform(h.id, Vec3<T>::zero(), Quat<T>::identity()), "World::set_transform", h.message);
        CHECK_REJECTED(world.interpolated_transform(h.id), "World::interpolated_transform", h.message);
    }
    CHECK(world.contains(live));
    CHECK(world.body_count() == 1);
}

TEST_CASE_TEMPLATE("update rejects NaN and infinite seconds and step rejects -0 and -inf", T, float, double) {
    World<T> world;
    world.create_body(Sphere<T>(T(0.5)));
    CHECK_REJECTED(world.update(std::numeric_limits<T>::quiet_NaN()), "World::update", "seconds");
    CHECK_REJECTED(world.update(std::numeric_limits<T>::infinity()), "World::update", "seconds");
    CHECK_REJECTED(world.step(T(-0.0)), "World::step", "dt");
    CHECK_REJECTED(world.step(-std::numeric_limits<T>::infinity()), "World::step", "dt");
    CHECK(world.update(T(0)) == 0);  // zero seconds is no time, not an error
    CHECK(world.interpolation_factor() == T(0));
}

// Narrow phase -----------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("collide and intersect reject non-finite poses and zero orientations, naming the pose", T, float, double) {
    const Shape<T> cube = Box<T>(T(0.5), T(0.5), T(0.5));
    const Transform<T> ok{};
    for (const T v : non_finite<T>()) {
        CAPTURE(v);
        const Transform<T> bad_position{{T(0), v, T(0)}, Quat<T>::identity()};
        const Transform<T> bad_orientation{Vec3<T>::zero(), Quat<T>{T(1), T(0), v, T(0)}};
        CHECK_REJECTED(collide(cube, bad_position, cube, ok), "collide", "pose_a.position");
        CHECK_REJECTED(collide(cube, ok, cube, bad_orientation), "collide", "pose_b.orientation");
        CHECK_REJECTED(intersect(cube, bad_position, cube, ok), "intersect", "pose_a.position");
    }
    const Transform<T> zero{Vec3<T>::zero(), Quat<T>{T(0), T(0), T(0), T(0)}};
    CHECK_REJECTED(collide(cube, zero, cube, ok), "collide", "pose_a.orientation");
}

// Regressions: accepted before, answered with NaN, infinity or nonsense -------------------------

TEST_CASE_TEMPLATE("regression: shape sizes beyond what the narrow phase can square are rejected", T, float, double) {
    // Float MPR squares and cubes lengths (its convergence test is of sixth order): sizes of 1e10
    // gave NaN contacts and 1e8 or 1e-7 missed overlaps (docs/robustness.md, "Sizes").
    const T big = ScalarTraits<T>::max_size * T(10), small = ScalarTraits<T>::min_size / T(10);
    for (const T v : {big, small}) {
        CAPTURE(v);
        CHECK_REJECTED(Sphere<T>(v), "Sphere", "radius must be within");
        CHECK_REJECTED(Box<T>(T(1), v, T(1)), "Box", "half_extents.y must be within");
        CHECK_REJECTED(Capsule<T>(v, T(1)), "Capsule", "radius must be within");
        CHECK_REJECTED(Cylinder<T>(T(1), v), "Cylinder", "half_height must be within");
        CHECK_REJECTED(Cone<T>(T(1), v), "Cone", "height must be within");
        const ConvexPolyhedron<T> cube = unit_cube_hull<T>();
        std::vector<Vec3<T>> cloud;
        for (const Vec3<T>& p : cube.vertices()) cloud.push_back(p * v);
        CHECK_REJECTED(make_convex_hull(cloud), "ConvexPolyhedron", "must be within");
    }
    CHECK_REJECTED(Capsule<T>(T(1), big), "Capsule", "half_height must be within");
    // Accepted: the ends of the range, and a capsule's zero or tiny half height (its radius sets its size).
    for (const T v : {ScalarTraits<T>::min_size, ScalarTraits<T>::max_size}) {
        CAPTURE(v);
        CHECK(rejection([&] { (void)Sphere<T>(v); }) == "accepted");
        CHECK(rejection([&] { (void)Box<T>(v, v, v); }) == "accepted");
        CHECK(rejection([&] { (void)Cone<T>(v, v); }) == "accepted");
    }
    CHECK(rejection([&] { (void)Capsule<T>(T(1), small); }) == "accepted");
}

TEST_CASE_TEMPLATE("regression: shapes at the ends of the size range collide with finite unit-normal contacts", T, float,
                   double) {
    for (const T s : {ScalarTraits<T>::min_size, ScalarTraits<T>::max_size}) {
        CAPTURE(s);
        const T f = s == ScalarTraits<T>::min_size ? T(1.6) : T(0.6);  // the other sizes, inside the range
        const Shape<T> shapes[] = {Sphere<T>(s), Box<T>(s, f * s, T(0.9) * f * s), Capsule<T>(f * s, s), Cylinder<T>(s, f * s),
                                   Cone<T>(s, f * s)};
        int hits = 0, bad = 0;
        for (const Shape<T>& a : shapes)
            for (const Shape<T>& b : shapes)
                for (int k = 0; k < 8; ++k) {
                    const Transform<T> ta{Vec3<T>::zero(),
                                          Quat<T>::from_axis_angle(normalized(Vec3<T>{T(1), T(2), T(3)}), T(0.4) * T(k))};
                    const Transform<T> tb{Vec3<T>{T(0.4), T(0.3) * T(k % 3), T(-0.2)} * s,
                                          Quat<T>::from_axis_angle(normalized(Vec3<T>{T(-1), T(2), T(1)}), T(0.7) * T(k))};
                    const Penetration<T> c = collide(a, ta, b, tb);
                    const ContactManifold<T> m = generate_contacts(a, ta, b, tb, T(0.01) * s);
                    if (!c.hit) continue;
                    ++hits;
                    if (!std::isfinite(c.depth) || !(c.depth > T(0)) || !is_finite(c.normal) || !is_finite(c.point_a) ||
                        !is_finite(c.point_b) || !(std::abs(length(c.normal) - T(1)) < T(1e-4)))
                        ++bad;
                    for (int i = 0; i < m.count; ++i)
                        if (!std::isfinite(m.points[static_cast<std::size_t>(i)].depth) ||
                            !is_finite(m.points[static_cast<std::size_t>(i)].point_a))
                            ++bad;
                }
        CHECK(bad == 0);
        CHECK(hits > 100);
    }
}

TEST_CASE_TEMPLATE("regression: a density or mass whose mass or inertia overflows is rejected before a body exists", T, float,
                   double) {
    // Float: a 2e6 m cube of density 1e30 has a mass of 8e48 kg, infinite in float. mass_properties
    // returned infinity (and an infinite inertia); create_body took a slot, then threw from
    // set_mass_properties and left a half-made body alive in the world.
    const T huge_density = std::is_same_v<T, float> ? T(1e30) : T(1e300);
    const T tiny_density = std::is_same_v<T, float> ? T(1e-30) : T(1e-300);
    const T s = ScalarTraits<T>::max_size, tiny = ScalarTraits<T>::min_size;
    CHECK_REJECTED(mass_properties(Box<T>(s, s, s), huge_density), "mass_properties", "mass");
    CHECK_REJECTED(mass_properties(Shape<T>(Sphere<T>(tiny)), tiny_density), "mass_properties", "mass");
    World<T> world;
    BodyDef<T> d;
    d.density = huge_density;
    CHECK_REJECTED(world.create_body(Box<T>(s, s, s), d), "World::create_body", "mass");
    CHECK(world.body_count() == 0);
    d = {};
    d.density = tiny_density;
    CHECK_REJECTED(world.create_body(Sphere<T>(tiny), d), "World::create_body", "mass");
    d = {};
    d.mass = std::numeric_limits<T>::max();  // the inertia, scaled to it, overflows
    CHECK_REJECTED(world.create_body(Box<T>(tiny, tiny, tiny), d), "World::create_body", "mass");
    CHECK(world.body_count() == 0);
    int bodies = 0;
    world.for_each_body([&](BodyId, const Body<T>&) { ++bodies; });
    CHECK(bodies == 0);
}

TEST_CASE_TEMPLATE("regression: set_mass_properties rejects an inertia that is not symmetric positive definite", T, float,
                   double) {
    // Positive diagonal and invertible, so it passed the old check, but indefinite (eigenvalues 3,
    // -1, 1): a negative moment of inertia lets the solver add energy.
    World<T> world;
    Body<T>& b = world.body(world.create_body(Box<T>(T(0.5), T(0.5), T(0.5))));
    MassProperties<T> m;
    m.mass = T(1);
    m.inertia = Mat3<T>{{T(1), T(2), T(0)}, {T(2), T(1), T(0)}, {T(0), T(0), T(1)}};
    CHECK_REJECTED(b.set_mass_properties(m), "Body::set_mass_properties", "inertia");
    m.inertia = Mat3<T>{{T(1), T(0.5), T(0)}, {T(-0.5), T(1), T(0)}, {T(0), T(0), T(1)}};  // not symmetric
    CHECK_REJECTED(b.set_mass_properties(m), "Body::set_mass_properties", "inertia");
    // Accepted: a rotated inertia, symmetric only up to round-off.
    const Mat3<T> r = to_matrix(Quat<T>::from_axis_angle(normalized(Vec3<T>{T(1), T(2), T(3)}), T(0.7)));
    m.inertia = rotated_inertia(Mat3<T>::diagonal({T(1), T(2), T(2.5)}), r);
    CHECK(rejection([&] { b.set_mass_properties(m); }) == "accepted");
}

TEST_CASE_TEMPLATE("regression: collide and mpr reject a non-unit orientation instead of colliding a sheared shape", T, float,
                   double) {
    // (1, 1, 0, 0) has |q|² = 2: rotate() with it scales and shears, so the query answered for a
    // different shape with a normal of length 2.
    const Box<T> box(T(0.5), T(0.5), T(0.5));
    const Transform<T> sheared{Vec3<T>::zero(), Quat<T>{T(1), T(1), T(0), T(0)}};
    const Transform<T> above{Vec3<T>{T(0), T(0.9), T(0)}, Quat<T>::identity()};
    CHECK_REJECTED(collide(Shape<T>(box), sheared, Shape<T>(box), above), "collide",
                   "pose_a.orientation must be a unit quaternion");
    CHECK_REJECTED(mpr_penetration(box, above, box, sheared), "mpr_penetration", "pose_b.orientation must be a unit");
    CHECK_REJECTED(mpr_intersect(box, sheared, box, above), "mpr_intersect", "unit");
    // Accepted: unit within round-off of the precision.
    const Quat<T> q = Quat<T>::from_axis_angle(normalized(Vec3<T>{T(1), T(1), T(0)}), T(0.3));
    const Transform<T> nearly{Vec3<T>::zero(), Quat<T>{q.w * (T(1) + T(4) * ScalarTraits<T>::epsilon), q.x, q.y, q.z}};
    CHECK(rejection([&] { (void)collide(Shape<T>(box), nearly, Shape<T>(box), above); }) == "accepted");
}

TEST_CASE_TEMPLATE("regression: a subnormal mass, whose inverse overflows, is rejected by set_mass_properties and create_body", T,
                   float, double) {
    // Accepted before: the body's inverse mass was infinite, it hung still, ignoring gravity, a
    // box landing on it froze in mid-air, and the world's own snapshot did not restore.
    World<T> world;
    const BodyId id = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)));
    Body<T>& b = world.body(id);
    const T before = b.mass();
    MassProperties<T> m = mass_properties(Box<T>(T(0.5), T(0.5), T(0.5)), T(1000));
    m.mass = std::numeric_limits<T>::denorm_min();
    CHECK_REJECTED(b.set_mass_properties(m), "Body::set_mass_properties", "1 / mass");
    CHECK(b.mass() == before);
    // In double a subnormal BodyDef::mass keeps a normal inertia (m × 0.4 × 1000²), so only
    // 1 / mass overflows (in float the scaled inertia underflows first and is rejected as such).
    if (std::is_same_v<T, double>) {
        BodyDef<T> d;
        d.mass = T(1e-310);
        CHECK_REJECTED(world.create_body(Sphere<T>(T(1000)), d), "World::create_body", "1 / mass");
    }
    CHECK(world.body_count() == 1);
}

TEST_CASE_TEMPLATE("regression: a distance joint whose anchors lie beyond max_size apart or from their bodies is rejected", T,
                   float, double) {
    // Float: anchors 1e30 apart gave an infinite length, accepted, which froze both bodies and
    // made the world's own snapshot unrestorable; an anchor 1e15 m out with length 1 froze them too.
    World<T> world;
    BodyDef<T> d;
    d.position = {T(0), T(0.5), T(0)};
    const BodyId a = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.position = {T(2), T(0.5), T(0)};
    const BodyId b = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    const T far = std::is_same_v<T, float> ? T(1e30) : T(1e300);
    CHECK_REJECTED(world.create_joint(JointDef<T>::distance(a, b, {T(0), T(0.5), T(0)}, {T(2), far, T(0)})),
                   "World::create_joint", "anchor_b's distance from body b");
    JointDef<T> out = JointDef<T>::distance(a, b, {T(0), T(0.5), T(0)}, {T(2), T(0.5), T(0)});
    out.anchor_a = {T(0), T(2) * detail::max_joint_lever<T>(), T(0)};
    CHECK_REJECTED(world.create_joint(out), "World::create_joint", "anchor_a's distance from body a");
    // Double took anchors up to max_size (1e50) out: one 1e30 m out on a light box spun it until
    // its contacts overflowed to inf. Both precisions now stop at max_joint_lever (1e6 m).
    out.anchor_a = {T(0), T(1e7), T(0)};
    CHECK_REJECTED(world.create_joint(out), "World::create_joint", "anchor_a's distance from body a");
    out = JointDef<T>::distance(a, b, {T(0), T(0.5), T(0)}, {T(2), T(0.5), T(0)});
    out.length = T(2) * ScalarTraits<T>::max_size;
    CHECK_REJECTED(world.create_joint(out), "World::create_joint", "length");
    if (std::is_same_v<T, float>) {  // the anchors' distance, 2e6 m, is beyond float's max_size
        out.length = T(-1);
        out.anchor_a = {-detail::max_joint_lever<T>(), T(0.5), T(0)};
        out.anchor_b = {detail::max_joint_lever<T>(), T(0.5), T(0)};
        CHECK_REJECTED(world.create_joint(out), "World::create_joint", "length");
    }
    // Nothing was half made: the first joint accepted takes the first slot.
    CHECK(world.create_joint(JointDef<T>::distance(a, b, {T(0), T(0.5), T(0)}, {T(2), T(0.5), T(0)})).index == 0);
}

TEST_CASE_TEMPLATE("regression: reserve rejects counts no world can hold with InvalidArgument, not std::length_error", T, float,
                   double) {
    World<T> world;
    CHECK_REJECTED(world.reserve(std::numeric_limits<std::size_t>::max()), "World::reserve", "bodies");
    CHECK_REJECTED(world.reserve(0, std::numeric_limits<std::size_t>::max()), "World::reserve", "contacts");
    world.reserve(100, 1000);
    CHECK(world.body_count() == 0);
}

TEST_CASE_TEMPLATE(
    "regression: a motor speed beyond the range of a speed setting is rejected by create_joint and set_joint_motor", T, float,
    double) {
    // A float slider driven at 1e10 m/s left its body at 5e9 m/s after one step and a motor
    // impulse no snapshot of the world restored; speeds now stay within max_setting_length.
    World<T> world;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    const BodyId a = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.type = BodyType::dynamic;
    d.position = {T(2), T(0), T(0)};
    const BodyId b = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    const T too_fast = T(2) * detail::max_setting_length<T>();
    JointDef<T> slider = JointDef<T>::prismatic(a, b, {T(0), T(0), T(0)}, {T(1), T(0), T(0)});
    slider.enable_motor = true;
    slider.max_motor_force = T(100);
    slider.motor_speed = -too_fast;
    CHECK_REJECTED(world.create_joint(slider), "World::create_joint", "motor_speed");
    slider.motor_speed = detail::max_setting_length<T>();
    const JointId joint = world.create_joint(slider);
    CHECK(joint.index == 0);  // nothing was half made by the rejected one
    CHECK_REJECTED(world.set_joint_motor(joint, true, too_fast, T(100)), "World::set_joint_motor", "speed");
    CHECK(world.joint(joint).motor_speed == detail::max_setting_length<T>());
}

// regression: a sphere query with a radius past the size range was refused by the Sphere it
// builds, under the name "Sphere", not the call the user made.
TEST_CASE_TEMPLATE("overlap_sphere names itself for a radius outside the size range", T, float, double) {
    World<T> w;
    for (const T radius : {ScalarTraits<T>::max_size * T(10), ScalarTraits<T>::min_size / T(10)}) {
        CAPTURE(radius);
        CHECK_REJECTED(w.overlap_sphere(Vec3<T>{}, radius), "World::overlap_sphere", "radius");
    }
}

TEST_CASE_TEMPLATE("regression: limits of a joint whose limit is off and the density of a static body are checked when given", T,
                   float, double) {
    // Both were kept unchecked (a hinge's NaN lower angle, a slider's lower limit above its upper,
    // a static or kinematic body's NaN density), and the world's own snapshot could not be restored.
    World<T> world;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    const BodyId base = world.create_body(Box<T>(T(1), T(1), T(1)), d);
    d.type = BodyType::dynamic;
    d.position = {T(0), T(3), T(0)};
    const BodyId arm = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    JointDef<T> hinge = JointDef<T>::hinge(base, arm, {T(0), T(2), T(0)}, {T(0), T(0), T(1)});
    hinge.lower_angle = std::numeric_limits<T>::quiet_NaN();
    CHECK_REJECTED(world.create_joint(hinge), "World::create_joint", "lower limit must be finite");
    JointDef<T> slider = JointDef<T>::prismatic(base, arm, {T(0), T(2), T(0)}, {T(0), T(1), T(0)});
    slider.lower_translation = T(1);
    slider.upper_translation = T(-1);
    CHECK_REJECTED(world.create_joint(slider), "World::create_joint", "lower limit must be <= the upper");
    for (const BodyType type : {BodyType::static_body, BodyType::kinematic}) {
        BodyDef<T> still;
        still.type = type;
        still.density = std::numeric_limits<T>::quiet_NaN();
        CHECK_REJECTED(world.create_body(Sphere<T>(T(1)), still), "World::create_body", "density must be a number");
    }
    CHECK(world.body_count() == 2);

    // What is accepted round-trips: a hinge with its limit off (the first joint: none was half
    // made), a static body of density 0.
    const JointId joint = world.create_joint(JointDef<T>::hinge(base, arm, {T(0), T(2), T(0)}, {T(0), T(0), T(1)}));
    CHECK(joint.index == 0);
    d.type = BodyType::static_body;
    d.density = T(0);
    d.position = {T(5), T(0), T(0)};
    world.create_body(Box<T>(T(1), T(1), T(1)), d);
    World<T> copy;
    restore_snapshot(copy, save_snapshot(world));
    CHECK(copy.body_count() == 3);
    CHECK(copy.contains(joint));
}

TEST_CASE_TEMPLATE("regression: a mass beyond max_mass is rejected, a box of max_mass lands on the floor and rests", T, float,
                   double) {
    // Accepted before (any mass whose inverse is finite): a float box of 8e37 kg landing at 7 m/s
    // took an infinite impulse, the step was discarded, and it froze in mid-air.
    World<T> world;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(0), T(-0.5), T(0)};
    world.create_body(Box<T>(T(5), T(0.5), T(5)), d);
    d = {};
    d.position = {T(0), T(3), T(0)};
    const T over = std::is_same_v<T, float> ? T(8e37) : T(8e307);
    d.mass = over;
    CHECK_REJECTED(world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d), "World::create_body", "max_mass");
    d.mass = T(0);
    const BodyId id = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    MassProperties<T> m = mass_properties(Box<T>(T(0.5), T(0.5), T(0.5)), T(1000));
    const T scale = over / m.mass;
    m.mass = over;
    m.inertia = m.inertia * scale;
    CHECK_REJECTED(world.body(id).set_mass_properties(m), "Body::set_mass_properties", "max_mass");
    CHECK(world.body(id).mass() == doctest::Approx(1000));
    m.mass = detail::max_mass<T>();
    m.inertia = m.inertia * (m.mass / over);
    world.body(id).set_mass_properties(m);
    for (int i = 0; i < 120; ++i) world.step(T(1) / T(60));
    const Body<T>& b = world.body(id);
    CHECK(is_finite(b.linear_velocity()));
    CHECK(b.position().y == doctest::Approx(0.5).epsilon(0.01));
    CHECK(length(b.linear_velocity()) < T(0.01));
}

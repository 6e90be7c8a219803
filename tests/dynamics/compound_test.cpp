// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Compound bodies: combined mass properties against closed forms, stacks of compounds, queries.
#include "support/approx.hpp"
#include "support/sim.hpp"

#include "scenes/compounds.hpp"

using namespace xeno;
using xeno::test::near;

TEST_CASE_TEMPLATE("two boxes side by side have the mass properties of one long box", T, float, double) {
    const Compound<T> pair({{Box<T>(T(0.5), T(0.5), T(0.5)), {{T(0), T(0), T(0)}, Quat<T>::identity()}},
                            {Box<T>(T(0.5), T(0.5), T(0.5)), {{T(1), T(0), T(0)}, Quat<T>::identity()}}});
    CHECK(near(pair.shift(), Vec3<T>{T(0.5), T(0), T(0)}));
    const MassProperties<T> m = mass_properties(pair, T(700));
    const MassProperties<T> one = mass_properties(Box<T>(T(1), T(0.5), T(0.5)), T(700));
    CHECK(near(m.mass, one.mass));
    CHECK(near(m.inertia, one.inertia, T(1e-5)));
    CHECK(near(pair.children()[0].local.position, Vec3<T>{T(-0.5), T(0), T(0)}));
    // A turned part: a box along y turned to lie along x is the same box.
    const Compound<T> turned({{Box<T>(T(0.5), T(1), T(0.5)),
                               {{T(3), T(2), T(1)}, Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 2)}}});
    CHECK(near(mass_properties(turned, T(700)).inertia, one.inertia));
    CHECK(near(turned.shift(), Vec3<T>{T(3), T(2), T(1)}));
    CHECK_THROWS_AS(Compound<T>(std::vector<CompoundChild<T>>{}), InvalidArgument);
}

TEST_CASE_TEMPLATE("stacks of L-shapes and tables stand for 10 s", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const scenes::Scene scene = scenes::compound_stack(w);
    test::simulate(w, T(1));
    std::vector<Vec3<T>> at_one;
    for (BodyId id : scene.bodies) at_one.push_back(w.body(id).position());
    test::simulate(w, T(9));
    T creep = T(0);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
        creep = std::max(creep, length(w.body(scene.bodies[i]).position() - at_one[i]));
    CAPTURE(creep);
    CHECK(creep < T(0.01));
    // The top table is still on top: about two table heights up.
    CHECK(w.body(scene.bodies.back()).position().y > T(1.5));
    // Each table touches the one below with its four legs: four manifolds, one per leg.
    int leg_contacts = 0;
    for (const Contact<T>& c : w.contacts())
        if ((c.a == scene.bodies[4] && c.b == scene.bodies[5]) || (c.a == scene.bodies[5] && c.b == scene.bodies[4]))
            ++leg_contacts;
    CHECK(leg_contacts == 4);
}

namespace {

struct TableMotion {
    double fastest;  ///< m/s, the bottom table's speed from 4 s to 10 s
    double creep;    ///< m, how far it moved from 1 s to 10 s
};

/// The stacked tables of compound-stack simulated awake for 10 s.
template <class T>
TableMotion bottom_table_motion(WorldSettings<T> settings) {
    settings.allow_sleeping = false;  // asleep it would stop whatever the solver did
    World<T> w(settings);
    const scenes::Scene scene = scenes::compound_stack(w);
    const BodyId bottom_table = scene.bodies[4];
    test::simulate(w, T(1));
    const Vec3<T> at_one = w.body(bottom_table).position();
    double fastest = 0;
    test::simulate(w, T(9), [&](int step) {
        if (step > 180) fastest = std::max(fastest, double(length(w.body(bottom_table).linear_velocity())));
    });
    return {fastest, double(length(w.body(bottom_table).position() - at_one))};
}

}  // namespace

TEST_CASE_TEMPLATE("tables on four legs stand still on the ground, awake, instead of vibrating across it", T, float, double) {
    // Each leg's manifold holds 4 points, so a table stands on 16 springs. At a face's stiffness
    // each they made it vibrate for ever (1 cm/s) and walk 5 mm in 9 s at the default settings;
    // softening a body's static rows so it rings no faster than a box on its face keeps it still.
    const TableMotion m = bottom_table_motion(WorldSettings<T>{});
    CAPTURE(m.fastest);
    CAPTURE(m.creep);
    CHECK(m.fastest < 1e-4);  // m/s: 90 µm/s when the summed support mass was shared, 1–4 µm/s now
    CHECK(m.creep < 1e-3);    // m
}

TEST_CASE_TEMPLATE("tables stay put on stiffer static contacts too (the fastest mode is softened, not the sum)", T, float,
                   double) {
    // With static contacts 1.5 times stiffer (ωh = 1.18 on a face) sharing a body's summed
    // support mass down to 1.5 M left a table rocking on its legs at √2.4 of that: it walked
    // 4.1 mm in 9 s at up to 8.9 mm/s (float and double). Bounding its fastest mode to a box's
    // and to ωh 0.8 (support_stiffness.hpp) holds it: 1–4 µm/s, 8 µm, the same as at scale 1
    // (the bound absorbs the scale).
    WorldSettings<T> settings;
    settings.static_contact_hertz_scale = T(1.5);
    const TableMotion m = bottom_table_motion(settings);
    CAPTURE(m.fastest);
    CAPTURE(m.creep);
    CHECK(m.creep < 1e-3);    // m
    CHECK(m.fastest < 1e-4);  // m/s
}

TEST_CASE_TEMPLATE("ray casts and point queries see every part of a compound", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    BodyDef<T> d;
    d.type = BodyType::static_body;
    const auto t = scenes::table<T>();
    d.position = t->shift();
    const BodyId id = w.create_body(t, d);
    // Down through the top's middle: hits the top at y = 0.76.
    const auto top = w.raycast(Ray<T>{{T(0), T(3), T(0)}, -Vec3<T>::unit_y(), T(10)});
    REQUIRE(top);
    CHECK(top->body == id);
    CHECK(near(top->hit.point.y, T(0.76), T(1e-4)));
    // Sideways under the top: hits a leg at x = -0.55.
    const auto leg = w.raycast(Ray<T>{{T(-3), T(0.3), T(0.32)}, Vec3<T>::unit_x(), T(10)});
    REQUIRE(leg);
    CHECK(near(leg->hit.point.x, T(-0.55), T(1e-4)));
    CHECK(w.query_point(Vec3<T>{T(0.52), T(0.2), T(-0.32)}).size() == 1);
    CHECK(w.query_point(Vec3<T>{T(0), T(0.3), T(0)}).empty());  // under the top, between the legs
}

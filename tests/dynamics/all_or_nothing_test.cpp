// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Every mutating call of World and Body is all-or-nothing: a rejected call (InvalidArgument)
// leaves the world exactly as it was, down to the bytes of its snapshot (docs/robustness.md,
// "State left behind"). The exception-free path is checked by world_noexcept_state.cpp.
#include "support/approx.hpp"

#include <xeno/dynamics/snapshot.hpp>

#include <limits>

using namespace xeno;

namespace {

/// A world with something of everything in it: static floor, a stack, a sphere, a compound, a
/// hinge, a destroyed body (a free slot), sleeping off, mid-motion contacts.
template <class T>
struct Scene {
    World<T> w;
    BodyId floor, box, ball, compound;
    JointId hinge;
    Scene() {
        BodyDef<T> d;
        d.type = BodyType::static_body;
        d.position = {T(0), T(-0.5), T(0)};
        floor = w.create_body(Box<T>(T(10), T(0.5), T(10)), d);
        d = {};
        d.position = {T(0), T(0.49), T(0)};
        box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
        d.position = {T(0), T(1.6), T(0)};
        const BodyId gone = w.create_body(Sphere<T>(T(0.3)), d);
        d.position = {T(2), T(0.3), T(0)};
        ball = w.create_body(Sphere<T>(T(0.3)), d);
        d.position = {T(-2), T(1), T(0)};
        compound = w.create_body(
            Compound<T>({{Box<T>(T(0.2), T(0.2), T(0.2)), {}}, {Sphere<T>(T(0.2)), {{T(0.5), T(0), T(0)}, Quat<T>::identity()}}}),
            d);
        hinge = w.create_joint(JointDef<T>::hinge(box, ball, {T(1), T(0.5), T(0)}, {T(0), T(0), T(1)}));
        for (int i = 0; i < 20; ++i) w.step(T(1) / T(60));
        w.destroy_body(gone);
        w.body(box).apply_force({T(1), T(0), T(0)});
    }
};

/// Runs a call that must be rejected and checks that the snapshot bytes did not change.
template <class T, class F>
void rejected_unchanged(World<T>& w, F&& call) {
    const std::vector<std::uint8_t> before = save_snapshot(w);
    const std::size_t count = w.body_count();
    CHECK_THROWS_AS(call(), InvalidArgument);
    CHECK(w.body_count() == count);
    CHECK(save_snapshot(w) == before);
}

}  // namespace

TEST_CASE_TEMPLATE("a rejected create_body leaves no body and no trace behind", T, float, double) {
    Scene<T> s;
    World<T>& w = s.w;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const Box<T> cube(T(0.5), T(0.5), T(0.5));
    // Representable mass, inertia too small to invert in this precision: used to be rejected by
    // set_mass_properties after the slot was taken, leaving a massless body that still fell.
    BodyDef<T> tiny;
    const Sphere<T> speck(ScalarTraits<T>::min_size);
    tiny.density = std::is_same_v<T, float> ? T(1e-10) : T(1e-60);
    rejected_unchanged(w, [&] { w.create_body(speck, tiny); });
    BodyDef<T> d;
    d.type = static_cast<BodyType>(7);  // not a body type
    rejected_unchanged(w, [&] { w.create_body(cube, d); });
    d = {};
    d.position.y = nan;
    rejected_unchanged(w, [&] { w.create_body(cube, d); });
    d = {};
    d.orientation = {T(0), T(0), T(0), T(0)};
    rejected_unchanged(w, [&] { w.create_body(cube, d); });
    d = {};
    d.density = T(-1);
    rejected_unchanged(w, [&] { w.create_body(cube, d); });
    d = {};
    d.material.restitution = T(2);
    rejected_unchanged(w, [&] { w.create_body(cube, d); });
    rejected_unchanged(w, [&] { w.create_body(std::shared_ptr<const Shape<T>>{}); });
    rejected_unchanged(w, [&] { w.create_body(std::shared_ptr<const Compound<T>>{}); });
    std::vector<Vec3<T>> shifted = make_tetrahedron(T(1)).vertices();  // centre of mass 1 m off the origin
    for (Vec3<T>& v : shifted) v.x += T(1);
    const ConvexPolyhedron<T> off(shifted, {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
    rejected_unchanged(w, [&] { w.create_body(off); });
}

TEST_CASE_TEMPLATE("bodies the size rules accept get their mass even when their inertia's determinant underflows", T, float,
                   double) {
    // The reproducers: a 0.1 mm float sphere and box at density 1000, a 0.5 m float box
    // at density 1e-30 and a 1e-30 m double sphere were rejected, with a body left behind. Their
    // mass and inertia are representable, so they are bodies: mass = density × volume, and they
    // rest on a floor.
    struct Case {
        Shape<T> shape;
        T density;
        T volume;
    };
    const T pi = ScalarTraits<T>::pi;
    std::vector<Case> cases{{Sphere<T>(T(1e-4)), T(1000), T(4) / T(3) * pi * T(1e-12)},
                            {Box<T>(T(1e-4), T(1e-4), T(1e-4)), T(1000), T(8e-12)},
                            {Box<T>(T(0.5), T(0.5), T(0.5)), T(1e-30), T(1)}};
    if constexpr (std::is_same_v<T, double>) cases.push_back({Sphere<T>(T(1e-30)), T(1000), T(4) / T(3) * pi * T(1e-90)});
    for (const Case& c : cases) {
        World<T> w;
        BodyDef<T> floor;
        floor.type = BodyType::static_body;
        floor.position = {T(0), T(-1), T(0)};
        w.create_body(Box<T>(T(10), T(1), T(10)), floor);
        BodyDef<T> d;
        d.density = c.density;
        d.position = {T(0), T(0.6), T(0)};
        const BodyId id = w.create_body(c.shape, d);
        CHECK(w.body_count() == 2);
        CHECK(xeno::test::near(w.body(id).mass(), c.density * c.volume, T(1e-5) * c.density * c.volume));
        for (int i = 0; i < 120; ++i) w.step(T(1) / T(60));
        const Body<T>& b = w.body(id);
        CHECK(is_finite(b.position()));
        CHECK(b.position().y > T(-0.01));  // resting on the floor (top at y = 0), not fallen through
        CHECK(b.position().y < T(0.55));   // and it did fall
    }
}

TEST_CASE_TEMPLATE("every rejected World call leaves the world's bytes unchanged", T, float, double) {
    Scene<T> s;
    World<T>& w = s.w;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    BodyId stale = w.create_body(Sphere<T>(T(0.1)));
    w.destroy_body(stale);
    rejected_unchanged(w, [&] { w.destroy_body(stale); });
    rejected_unchanged(w, [&] { w.destroy_body(BodyId{}); });
    rejected_unchanged(w, [&] { w.set_transform(s.box, {nan, T(0), T(0)}, Quat<T>::identity()); });
    rejected_unchanged(w, [&] { w.set_transform(s.box, {}, Quat<T>{T(0), T(0), T(0), T(0)}); });
    rejected_unchanged(w, [&] { w.set_transform(stale, {}, Quat<T>::identity()); });
    // Joints.
    rejected_unchanged(w, [&] { w.create_joint(JointDef<T>::ball(s.box, s.box, {})); });
    rejected_unchanged(w, [&] { w.create_joint(JointDef<T>::ball(s.box, stale, {})); });
    rejected_unchanged(w, [&] { w.create_joint(JointDef<T>::ball(s.box, s.ball, {nan, T(0), T(0)})); });
    rejected_unchanged(w, [&] { w.create_joint(JointDef<T>::hinge(s.box, s.ball, {}, Vec3<T>{})); });
    JointDef<T> j = JointDef<T>::hinge(s.box, s.ball, {}, {T(0), T(1), T(0)});
    j.enable_limit = true;
    j.lower_angle = T(1);
    j.upper_angle = T(-1);
    rejected_unchanged(w, [&] { w.create_joint(j); });
    j = JointDef<T>::ball(s.box, s.ball, {});
    j.type = static_cast<JointType>(9);  // not a joint type
    rejected_unchanged(w, [&] { w.create_joint(j); });
    const JointId ball = w.create_joint(JointDef<T>::ball(s.ball, s.compound, {}));
    rejected_unchanged(w, [&] { w.set_hinge_motor(ball, true, T(1), T(1)); });
    rejected_unchanged(w, [&] { w.set_hinge_motor(s.hinge, true, nan, T(1)); });
    rejected_unchanged(w, [&] { w.set_hinge_motor(s.hinge, true, T(1), T(-1)); });
    w.destroy_joint(ball);
    rejected_unchanged(w, [&] { w.destroy_joint(ball); });
    // Settings, stepping.
    WorldSettings<T> bad = w.settings();
    bad.substeps = 0;
    rejected_unchanged(w, [&] { w.set_settings(bad); });
    rejected_unchanged(w, [&] { w.set_gravity({T(0), nan, T(0)}); });
    rejected_unchanged(w, [&] { w.step(T(0)); });
    rejected_unchanged(w, [&] { w.step(nan); });
    rejected_unchanged(w, [&] { w.update(T(-1)); });
    // Snapshots.
    std::vector<std::uint8_t> bytes = save_snapshot(w);
    bytes.pop_back();
    rejected_unchanged(w, [&] { restore_snapshot(w, bytes); });
}

TEST_CASE_TEMPLATE("every rejected Body setter leaves the world's bytes unchanged", T, float, double) {
    Scene<T> s;
    World<T>& w = s.w;
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    Body<T>& b = w.body(s.box);
    const Vec3<T> bad{T(1), nan, T(0)}, ok{T(1), T(0), T(0)};
    rejected_unchanged(w, [&] { b.set_linear_velocity(bad); });
    rejected_unchanged(w, [&] { b.set_angular_velocity(bad); });
    rejected_unchanged(w, [&] { b.apply_force(bad); });
    rejected_unchanged(w, [&] { b.apply_force_at(ok, bad); });
    rejected_unchanged(w, [&] { b.apply_force_at(bad, ok); });
    rejected_unchanged(w, [&] { b.apply_torque(bad); });
    rejected_unchanged(w, [&] { b.apply_impulse_at(ok, bad); });
    rejected_unchanged(w, [&] { b.apply_impulse_at(bad, ok); });
    rejected_unchanged(w, [&] { b.apply_linear_impulse(bad); });
    rejected_unchanged(w, [&] { b.apply_angular_impulse(bad); });
    rejected_unchanged(w, [&] { b.set_material({T(0.5), T(2)}); });
    rejected_unchanged(w, [&] { b.set_damping(T(1), T(-1)); });  // the first argument is fine
    rejected_unchanged(w, [&] { b.set_damping(T(-1), T(1)); });
    rejected_unchanged(w, [&] { b.set_gravity_scale(inf); });
    MassProperties<T> m{T(2), {}, Mat3<T>::diagonal({T(1), T(-1), T(1)})};
    rejected_unchanged(w, [&] { b.set_mass_properties(m); });
    m.inertia = Mat3<T>::identity();
    m.center = {nan, T(0), T(0)};
    rejected_unchanged(w, [&] { b.set_mass_properties(m); });
    m.center = {};
    rejected_unchanged(w, [&] { w.body(s.floor).set_mass_properties(m); });
}

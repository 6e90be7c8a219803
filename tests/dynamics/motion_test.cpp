// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Closed-form physics: free fall, resting, sliding to a stop, inclines, bouncing, momentum and
// angular momentum, the Dzhanibekov flip. Unit boxes (half extent 0.5) unless said; no sleeping.
#include "support/approx.hpp"
#include "support/sim.hpp"

using namespace xeno;
using xeno::test::simulate;

namespace {
template <class T>
BodyId ground_with_friction(World<T>& w, T mu) {
    return scenes::add_ground(w, T(200), mu);
}
template <class T>
BodyId box_with(World<T>& w, const Vec3<T>& position, T mu, T e = T(0)) {
    BodyDef<T> def;
    def.position = position;
    def.material.friction = mu;
    def.material.restitution = e;
    return w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
}
/// A static ramp of friction mu, 1 m thick, 2 half_length long and 10 m wide, tilted by angle
/// about z so that it falls towards −x; returns its tilt.
template <class T>
Quat<T> add_ramp(World<T>& w, T angle, T half_length, T mu = T(0.6)) {
    BodyDef<T> ramp;
    ramp.type = BodyType::static_body;
    ramp.orientation = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), angle);
    ramp.material.friction = mu;
    w.create_body(Box<T>(half_length, T(0.5), T(5)), ramp);
    return ramp.orientation;
}
}  // namespace

TEST_CASE_TEMPLATE("free fall follows p0 + v0 t + g t^2 / 2 to integrator accuracy", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    BodyDef<T> def;
    def.position = {T(1), T(100), T(-2)};
    def.linear_velocity = {T(3), T(4), T(0)};
    const BodyId id = w.create_body(Sphere<T>(T(0.5)), def);
    const T t = T(2);
    simulate(w, t);
    const Vec3<T> g = w.settings().gravity;
    const Vec3<T> exact = def.position + def.linear_velocity * t + g * (T(0.5) * t * t);
    // Symplectic Euler with substep h lands g h t / 2 past the exact parabola.
    const T h = w.settings().fixed_time_step / static_cast<T>(w.settings().substeps);
    const Vec3<T> expected = exact + g * (T(0.5) * h * t);
    CHECK(length(w.body(id).position() - expected) < T(2e-3));
    CHECK(length(w.body(id).position() - exact) < T(0.5) * T(9.81) * h * t * T(1.01));
    CHECK(test::near(w.body(id).linear_velocity().y, T(4) - T(9.81) * t, T(1e-4)));
}

TEST_CASE_TEMPLATE("a box resting on the ground drifts under a millimetre and keeps four points for 10 s", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    scenes::add_ground(w);
    const BodyId box = box_with(w, Vec3<T>{T(0.3), T(0.5), T(-0.2)}, T(0.6));
    const Vec3<T> start = w.body(box).position();
    int min_points = 4, max_points = 0;
    simulate(w, T(10), [&](int) {
        const int n = w.contacts().empty() ? 0 : w.contacts()[0].manifold.count;
        min_points = std::min(min_points, n);
        max_points = std::max(max_points, n);
    });
    CHECK(length(w.body(box).position() - start) < T(1e-3));
    CHECK(min_points == 4);
    CHECK(max_points == 4);
    CHECK(std::abs(test::yaw(w.body(box).orientation())) < T(1e-4));
}

TEST_CASE_TEMPLATE("a box sliding at 2 and 5 m/s with mu 0.5 stops within 2 % of v^2/(2 mu g)", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const T v0 : {T(2), T(5)}) {
        World<T> w(C::settings());
        ground_with_friction(w, T(0.5));
        const BodyId box = box_with(w, Vec3<T>{T(0), T(0.5), T(0)}, T(0.5));
        simulate(w, T(0.5));  // settle on the ground first: no landing transient in the distance
        const Vec3<T> start = w.body(box).position();
        w.body(box).set_linear_velocity({v0, T(0), T(0)});
        T yaw_max = T(0);
        simulate(w, T(3), [&](int) { yaw_max = std::max(yaw_max, std::abs(test::yaw(w.body(box).orientation()))); });
        const T distance = w.body(box).position().x - start.x;
        const T expected = v0 * v0 / (T(2) * T(0.5) * T(9.81));
        CAPTURE(v0);
        CAPTURE(distance);
        CAPTURE(expected);
        CHECK(std::abs(distance - expected) < T(0.02) * expected);
        CHECK(length(w.body(box).linear_velocity()) < T(1e-3));
        // A symmetric box sliding straight does not turn about the vertical.
        CHECK(yaw_max < radians(T(0.5)));
        CHECK(std::abs(w.body(box).position().z - start.z) < T(1e-3));
    }
}

// The friction row's 2×2 mass K holds the tipping terms (c × t)·I⁻¹·(c × t), which differ along
// the two tangents of a body whose inertia differs across its sliding face; the normal rows stop
// the tipping, so sliding friction should oppose the velocity. The row clamped K⁻¹ v radially to
// the Coulomb disc, so it pushed along K⁻¹ v instead: a 1 × 0.2 × 0.4 m plate launched at 45°
// across the ground ran off at 50°, and yawed half a radian on a 35° slope it slid 0.82 m
// sideways in 3 s (the slide of a cube was exact).
TEST_CASE_TEMPLATE("regression: a plate slides along its launch direction and down the fall line whatever its yaw", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    const T mu = T(0.5), g = T(9.81), v0 = T(4);
    const Vec3<T> plate{T(0.5), T(0.1), T(0.2)};
    for (const T yaw : {T(0), T(0.5), T(1)})
        for (const T heading : {T(20), T(45), T(70)}) {  // degrees from x, on the ground
            World<T> w(C::settings());
            ground_with_friction(w, mu);
            BodyDef<T> def;
            def.position = {T(0), plate.y, T(0)};
            def.orientation = Quat<T>::from_axis_angle(Vec3<T>::unit_y(), yaw);
            def.material.friction = mu;
            const T a = radians(heading);
            def.linear_velocity = Vec3<T>{std::cos(a), T(0), std::sin(a)} * v0;
            const BodyId id = w.create_body(Box<T>(plate), def);
            simulate(w, T(2));
            const Vec3<T> p = w.body(id).position();
            const T distance = std::sqrt(p.x * p.x + p.z * p.z), expected = v0 * v0 / (T(2) * mu * g);
            CAPTURE(yaw);
            CAPTURE(heading);
            CAPTURE(distance);
            CHECK(std::abs(std::atan2(p.z, p.x) - a) < radians(T(0.3)));
            CHECK(std::abs(distance - expected) < T(0.02) * expected);
        }
    for (const T yaw : {T(0), T(0.5), T(1)}) {  // from rest down a 35° slope falling towards -x
        World<T> w(C::settings());
        const Quat<T> tilt = add_ramp(w, radians(T(35)), T(40), mu);
        BodyDef<T> def;
        def.orientation = tilt * Quat<T>::from_axis_angle(Vec3<T>::unit_y(), yaw);
        def.position = rotate(tilt, Vec3<T>{T(20), T(0.5) + plate.y, T(0)});
        def.material.friction = mu;
        const BodyId id = w.create_body(Box<T>(plate), def);
        const Vec3<T> start = w.body(id).position();
        simulate(w, T(3));
        const Vec3<T> moved = rotate(conjugate(tilt), w.body(id).position() - start);                      // in the slope's frame
        const T along = radians(T(35)), expected = g * (std::sin(along) - mu * std::cos(along)) * T(4.5);  // a t^2 / 2
        CAPTURE(yaw);
        CAPTURE(moved);
        CHECK(std::abs(moved.z) < T(0.01));
        CHECK(std::abs(-moved.x - expected) < T(0.02) * expected);
    }
}

// Spun on the ground about the vertical, a body resting on a flat face is braked by
// µ m g ℓ, ℓ the mean distance of the face's area from its centre under a uniform pressure:
// (√2 + ln(1 + √2)) a / 3 for a square of half side a, 2r/3 for a disc. Before ℓ was integrated
// over the patch (contact/patch.hpp) it was the corners' mean distance: a box stopped in 0.56 and
// a cylinder in 0.68 of these times.
TEST_CASE_TEMPLATE("a box, a cylinder and a cone spun on a flat face slow at mu m g times the face's mean radius", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    const double mu = 0.6, g = 9.81;
    for (int kind = 0; kind < 3; ++kind) {
        CAPTURE(kind);
        World<T> w(C::settings());
        scenes::add_ground(w, T(200), T(mu));
        BodyDef<T> def;
        def.material.friction = T(mu);
        double rate = 0;  // rad/s²: µ g ℓ m / I
        BodyId id;
        if (kind == 0) {
            def.position = {T(0), T(0.25), T(0)};
            id = w.create_body(Box<T>(T(0.5), T(0.25), T(0.5)), def);
            const double a = 0.5, lever = a * (std::sqrt(2.0) + std::log(1 + std::sqrt(2.0))) / 3;
            rate = mu * g * lever / (2 * a * a / 3);
        } else if (kind == 1) {
            def.position = {T(0), T(0.4), T(0)};
            id = w.create_body(Cylinder<T>(T(0.25), T(0.4)), def);
            rate = mu * g * (2 * 0.25 / 3) / (0.25 * 0.25 / 2);
        } else {
            def.position = {T(0), T(0.15), T(0)};  // the base 0.15 below the centre of mass
            id = w.create_body(Cone<T>(T(0.3), T(0.6)), def);
            rate = mu * g * (2 * 0.3 / 3) / (0.3 * 0.3 * 3 / 10);
        }
        simulate(w, T(0.5));
        w.body(id).set_angular_velocity({T(0), T(10), T(0)});
        simulate(w, T(0.2));
        const double spin = double(w.body(id).angular_velocity().y), expected = 10 - rate * 0.2;
        CAPTURE(spin);
        CAPTURE(expected);
        CHECK(std::abs(spin - expected) <= 0.005 * (10 - expected));  // the rate within 0.5 %
        CHECK(length(w.body(id).linear_velocity()) < T(1e-3));
    }
}

TEST_CASE_TEMPLATE("a box on an incline stays below the friction angle and slides above it", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    const T mu = T(0.5);
    for (const T offset : {T(-0.05), T(0.05)}) {
        World<T> w(C::settings());
        const Quat<T> tilt = add_ramp(w, std::atan(mu + offset), T(20), mu);
        BodyDef<T> def;
        def.orientation = tilt;
        def.position = rotate(tilt, Vec3<T>{T(0), T(1.0), T(0)});
        def.material.friction = mu;
        const BodyId box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
        simulate(w, T(0.5));
        const Vec3<T> start = w.body(box).position();
        simulate(w, T(10));
        const T moved = length(w.body(box).position() - start);
        CAPTURE(offset);
        CAPTURE(moved);
        if (offset < T(0)) CHECK(moved < T(1e-3));
        else CHECK(moved > T(1));
    }
}

namespace {
// A ball, a capsule and a cylinder of radius 0.5 m (the last two 1 m long, lying across the
// direction of roll), and the fraction k of g sin θ at which each rolls down an incline without
// slipping: k = 1 / (1 + I / (m r²)) with I about the rolling axis, from the solids' closed forms
// (a capsule is a cylinder and a ball: I = m_cyl r² / 2 + 2/5 m_ball r²).
enum class Roller { ball, capsule, cylinder };
template <class T>
BodyId add_roller(World<T>& w, Roller kind, BodyDef<T> def, const Quat<T>& across) {
    const T r = T(0.5), half = T(0.5);
    if (kind == Roller::ball) return w.create_body(Sphere<T>(r), def);
    def.orientation = def.orientation * across;  // the shape's axis (local y) across the roll
    if (kind == Roller::capsule) return w.create_body(Capsule<T>(r, half), def);
    return w.create_body(Cylinder<T>(r, half), def);
}
/// A roller on flat ground of friction mu (its own friction mu too), its axis across x, at x0 with
/// velocity v along x and spin w about z.
template <class T>
BodyId launch_roller(World<T>& w, Roller kind, T mu, T x0, T v, T spin) {
    scenes::add_ground(w, T(2) * std::abs(x0) + T(100), mu);
    BodyDef<T> def;
    def.position = {x0, T(0.5), T(0)};
    def.linear_velocity = {v, T(0), T(0)};
    def.angular_velocity = {T(0), T(0), spin};
    def.material.friction = mu;
    return add_roller(w, kind, def, Quat<T>::from_axis_angle(Vec3<T>::unit_x(), radians(T(90))));
}
double rolling_fraction(Roller kind) {
    const double r = 0.5, half = 0.5, pi = 3.14159265358979323846;
    const double m_cyl = pi * r * r * 2 * half, m_ball = 4.0 / 3.0 * pi * r * r * r;
    if (kind == Roller::ball) return 1 / (1 + 0.4);
    if (kind == Roller::cylinder) return 1 / (1 + 0.5);
    return 1 / (1 + (0.5 * m_cyl + 0.4 * m_ball) / (m_cyl + m_ball));
}
}  // namespace

// Regression: a rolling sphere kept the contact points of earlier steps (on a rolling ball they
// rise along a cycloid without sliding, so the manifold's slide test never dropped them), which
// lifted its friction patch: down 20° it spun 3 % faster than it rolled and fell 1.3 % behind
// 5/7 g sin θ by 2 s.
TEST_CASE_TEMPLATE("a ball, a capsule and a cylinder roll down an incline at their closed-form accelerations without slipping", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const Roller kind : {Roller::ball, Roller::capsule, Roller::cylinder}) {
        CAPTURE(static_cast<int>(kind));
        World<T> w(C::settings());
        const T angle = radians(T(20));
        const Quat<T> tilt = add_ramp(w, angle, T(40));  // rolling needs µ ≥ k tan θ (at most 0.26 here)
        BodyDef<T> def;
        def.orientation = tilt;
        def.position = rotate(tilt, Vec3<T>{T(15), T(1), T(0)});
        def.material.friction = T(0.6);
        const BodyId id = add_roller(w, kind, def, Quat<T>::from_axis_angle(Vec3<T>::unit_x(), radians(T(90))));
        const Vec3<T> down = rotate(tilt, -Vec3<T>::unit_x()), up = rotate(tilt, Vec3<T>::unit_y());
        simulate(w, T(0.25));
        const T v0 = dot(w.body(id).linear_velocity(), down);
        simulate(w, T(2));
        const Body<T>& b = w.body(id);
        const T v1 = dot(b.linear_velocity(), down);
        const double a = double(v1 - v0) / 2.0, expected = rolling_fraction(kind) * 9.81 * std::sin(double(angle));
        // The contact point's speed along the slope: v + ω × (−r n).
        const T slip = dot(b.linear_velocity() + cross(b.angular_velocity(), up * T(-0.5)), down);
        CAPTURE(a);
        CAPTURE(expected);
        CAPTURE(slip);
        CHECK(std::abs(a - expected) <= 2e-3 * expected);
        CHECK(std::abs(slip) <= T(2e-3) * v1);
    }
}

// Regression: the solver turned a contact's anchors with the bodies through the substeps, so a
// rolling ball's anchor rose r (1 − cos θ) off the ground in a step of angle θ and the ball sank
// that much into it: 4.8 mm for a 0.5 m ball at 10 m/s (capsules and cylinders alike), and the
// ball lost 1.6 % of its speed in 2 s.
TEST_CASE_TEMPLATE("a ball, a capsule and a cylinder rolling at 10 m/s keep their speed and ride at their resting height", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const Roller kind : {Roller::ball, Roller::capsule, Roller::cylinder}) {
        CAPTURE(static_cast<int>(kind));
        World<T> w(C::settings());
        const BodyId id = launch_roller(w, kind, T(0.6), T(-150), T(10), T(-20));  // rolling: ω r = v
        T lowest = T(1);
        simulate(w, T(2), [&](int) { lowest = std::min(lowest, w.body(id).position().y); });
        const T speed = w.body(id).linear_velocity().x;
        CAPTURE(speed);
        CAPTURE(lowest);
        CHECK(std::abs(speed - T(10)) <= T(1e-3) * T(10));
        CHECK(lowest >= T(0.5) - T(5e-4));
    }
}

// Regression: a pair that has hardly moved re-measures its contact from its two anchors, and a
// round body's anchor turns with it as it rolls, while where it touches does not: the normal
// force sat up to half a millimetre ahead of the centre and rolled the body on. Pushed by 1e-4
// of their weight, a ball gained 3.9 times the speed the push gives in 2 s, a capsule and a
// cylinder 3.2 times.
TEST_CASE_TEMPLATE("regression: a ball, a capsule and a cylinder pushed by 1e-4 of their weight roll at F / (m + I / r^2)", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const Roller kind : {Roller::ball, Roller::capsule, Roller::cylinder}) {
        CAPTURE(static_cast<int>(kind));
        World<T> w(C::settings());
        const BodyId id = launch_roller(w, kind, T(0.6), T(0), T(0), T(0));
        simulate(w, T(1));
        const T push = T(1e-4) * w.body(id).mass() * T(9.81);
        const T v0 = w.body(id).linear_velocity().x;
        simulate(w, T(2), [&](int) { w.body(id).apply_force(Vec3<T>{push, T(0), T(0)}); });
        // The force of the last step is applied in the next: 2 s of pushing less one step.
        const double gained = double(w.body(id).linear_velocity().x - v0);
        const double expected = rolling_fraction(kind) * 1e-4 * 9.81 * (2.0 - 1.0 / 60.0);
        CAPTURE(gained);
        CAPTURE(expected);
        CHECK(std::abs(gained - expected) <= 0.01 * expected);
    }
}

// Friction turns a slide into rolling: the angular momentum about the contact line is kept, so a
// body launched sliding without spin rolls on at v0 / (1 + I / (m r²)) (5/7 v0 for a ball, 2/3
// for a cylinder), reached after (v0 − v) / (µ g).
TEST_CASE_TEMPLATE("a ball and a cylinder launched sliding roll on at 5/7 and 2/3 of their speed", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const Roller kind : {Roller::ball, Roller::cylinder}) {
        CAPTURE(static_cast<int>(kind));
        World<T> w(C::settings());
        const BodyId id = launch_roller(w, kind, T(0.3), T(-100), T(6), T(0));
        const double expected = 6.0 * rolling_fraction(kind);
        const double rolls_at = (6.0 - expected) / (0.3 * 9.81);  // s
        simulate(w, T(rolls_at + 1.0));
        const Body<T>& b = w.body(id);
        CAPTURE(b.linear_velocity().x);
        CHECK(std::abs(double(b.linear_velocity().x) - expected) <= 1e-3 * expected);
        // and it rolls: the contact point is at rest
        CHECK(std::abs(b.linear_velocity().x + b.angular_velocity().z * T(0.5)) <= T(1e-3) * b.linear_velocity().x);
    }
}

// Regression: every spin was capped at max_rotation_per_step (47 rad/s at 60 Hz), the cap that
// keeps a tumbling body's corners from turning past its contacts. A ball's surface stays in place
// as it turns, yet friction held its contact point to the capped spin: a 5 cm ball rolling down
// 30° reached 2.4 m/s in 3 s instead of 5/7 g sin θ t = 10.5 m/s (ω = 210 rad/s).
TEST_CASE_TEMPLATE("regression: a 5 cm ball rolls down an incline at 5/7 g sin θ past the tumbling spin cap", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const T angle = radians(T(30)), r = T(0.05);
    const Quat<T> tilt = add_ramp(w, angle, T(60));  // rolling needs µ ≥ 2/7 tan θ = 0.16
    BodyDef<T> def;
    def.orientation = tilt;
    def.position = rotate(tilt, Vec3<T>{T(50), T(0.5) + r, T(0)});
    def.material.friction = T(0.6);
    const BodyId id = w.create_body(Sphere<T>(r), def);
    const Vec3<T> down = rotate(tilt, -Vec3<T>::unit_x()), up = rotate(tilt, Vec3<T>::unit_y());
    simulate(w, T(3));
    const Body<T>& b = w.body(id);
    const double v = double(dot(b.linear_velocity(), down)), expected = 5.0 / 7.0 * 9.81 * std::sin(double(angle)) * 3.0;
    const T slip = dot(b.linear_velocity() + cross(b.angular_velocity(), up * -r), down);
    CAPTURE(v);
    CAPTURE(slip);
    CHECK(std::abs(v - expected) <= 2e-3 * expected);
    CHECK(std::abs(slip) <= T(2e-3) * T(v));
}

// Regression (as above): a wheel turning about its own axis keeps its surface in place, so it
// rolls at any speed under max_linear_speed; a 0.33 m cylinder launched rolling at 30 m/s
// (91 rad/s) was braked to 15.6 m/s in 5 s. Tumbling across its axis stays capped.
TEST_CASE_TEMPLATE("regression: a cylinder and a capsule roll on at 30 m/s, and their tumbling stays capped", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    const T r = T(0.33), v = T(30);
    for (const bool capsule : {false, true}) {
        CAPTURE(capsule);
        World<T> w(C::settings());
        scenes::add_ground(w, T(400), T(0.6));
        BodyDef<T> def;
        def.position = {T(-180), r, T(0)};
        def.orientation = Quat<T>::from_axis_angle(Vec3<T>::unit_x(), radians(T(90)));  // axis along z
        def.linear_velocity = {v, T(0), T(0)};
        def.angular_velocity = {T(0), T(0), -v / r};
        def.material.friction = T(0.6);
        const BodyId id = capsule ? w.create_body(Capsule<T>(r, T(0.2)), def) : w.create_body(Cylinder<T>(r, T(0.2)), def);
        simulate(w, T(5));
        const Body<T>& b = w.body(id);
        CAPTURE(b.linear_velocity().x);
        CHECK(std::abs(b.linear_velocity().x - v) <= T(1e-3) * v);
        CHECK(std::abs(b.linear_velocity().x + b.angular_velocity().z * r) <= T(1e-3) * v);
    }
    // In free fall: end over end at 100 rad/s is capped at π/4 a step; about its axis it keeps 100.
    WorldSettings<T> settings = C::weightless();
    World<T> w(settings);
    BodyDef<T> def;
    def.angular_velocity = {T(100), T(0), T(0)};
    const BodyId tumbling = w.create_body(Cylinder<T>(r, T(0.2)), def);
    def.position = {T(10), T(0), T(0)};
    def.angular_velocity = {T(0), T(100), T(0)};
    const BodyId spinning = w.create_body(Cylinder<T>(r, T(0.2)), def);
    simulate(w, T(0.5));
    CHECK(test::near(length(w.body(tumbling).angular_velocity()), settings.max_rotation_per_step * T(60), T(1e-4)));
    CHECK(test::near(w.body(spinning).angular_velocity().y, T(100), T(1e-5)));
}

// Regression: on a ground of half size 400 a capsule shorter than 0.57 m touched by one end of its
// core each step (round_pairs.hpp's short span was a fraction of the ground's size), so it rolled
// rocking from end to end, its old points lifted the friction patch, and it spun faster than it
// rolled: 0.33 m wide at 3 m/s, 2.93 m/s after 2 s with the contact point slipping at 0.13 m/s.
TEST_CASE_TEMPLATE("regression: short capsules roll on a large ground at their speed", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const T r : {T(0.1), T(0.33), T(0.5)}) {
        CAPTURE(r);
        World<T> w(C::settings());
        scenes::add_ground(w, T(400), T(0.6));
        BodyDef<T> def;
        def.position = {T(-180), r, T(0)};
        def.orientation = Quat<T>::from_axis_angle(Vec3<T>::unit_x(), radians(T(90)));  // the core along z
        def.linear_velocity = {T(3), T(0), T(0)};
        def.angular_velocity = {T(0), T(0), T(-3) / r};
        def.material.friction = T(0.6);
        const BodyId id = w.create_body(Capsule<T>(r, T(0.2)), def);
        simulate(w, T(2));
        const Body<T>& b = w.body(id);
        CAPTURE(b.linear_velocity().x);
        CHECK(std::abs(b.linear_velocity().x - T(3)) <= T(3e-3));
        CHECK(std::abs(b.linear_velocity().x + b.angular_velocity().z * r) <= T(3e-3));
    }
}

namespace {
// A ground box (top at y = 0) and a ball or a box of half size 0.5 above it, its bottom at h,
// both with restitution e.
template <class T>
BodyId drop_above_ground(World<T>& w, T e, T h, bool box) {
    BodyDef<T> g;
    g.type = BodyType::static_body;
    g.position = {T(0), T(-0.5), T(0)};
    g.material.restitution = e;
    w.create_body(Box<T>(T(10), T(0.5), T(10)), g);
    BodyDef<T> def;
    def.position = {T(0), T(0.5) + h, T(0)};
    def.material.restitution = e;
    return box ? w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def) : w.create_body(Sphere<T>(T(0.5)), def);
}

/// The apexes of a body of half size 0.5 over `seconds`, heights of its bottom above the ground:
/// each from the last step before it, height plus v²/2g (a 7 cm bounce moves 2.7 mm in its apex
/// step).
template <class T>
std::vector<T> bounce_apexes(World<T>& w, BodyId id, T seconds) {
    std::vector<T> tops;
    T previous_vy = T(0), previous_y = T(0);
    simulate(w, seconds, [&](int) {
        const Body<T>& b = w.body(id);
        if (previous_vy > T(0) && b.linear_velocity().y <= T(0))
            tops.push_back(previous_y + previous_vy * previous_vy / (T(2) * T(9.81)));
        previous_vy = b.linear_velocity().y;
        previous_y = b.position().y - T(0.5);
    });
    return tops;
}
}  // namespace

TEST_CASE_TEMPLATE("a box dropped from h with restitution e bounces to e^2 h within 5 %", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    const T h = T(2), e = T(0.6);
    World<T> w(C::settings());
    const BodyId box = drop_above_ground(w, e, h, true);
    bool bounced = false;
    T apex = T(0);
    simulate(w, T(2.5), [&](int) {
        const Body<T>& b = w.body(box);
        if (b.linear_velocity().y > T(0.5)) bounced = true;
        if (bounced) apex = std::max(apex, b.position().y - T(0.5));
    });
    REQUIRE(bounced);
    CAPTURE(apex);
    CHECK(std::abs(apex - e * e * h) < T(0.05) * e * e * h);
}

TEST_CASE_TEMPLATE(
    "regression: with restitution_threshold 0 a bouncy body at rest stays at rest, and one dropped bounces to e^2 h", C,
    XENO_TEST_CONFIGS) {
    // Every approach bounced, a resting one too: its rebound speed, e v plus what gravity takes
    // back within a substep (set_rebounds), was g h for v = 0, and a resting box or ball with
    // e = 1 jumped between 0 and ±2 cm/s every step. An approach slower than twice that
    // substep's pull no longer bounces (bounce_threshold).
    using T = typename C::T;
    WorldSettings<T> s = C::settings();
    s.restitution_threshold = T(0);
    for (const bool box : {false, true}) {
        CAPTURE(box);
        World<T> w(s);
        const BodyId id = drop_above_ground(w, T(1), T(0), box);
        T fastest = T(0);
        simulate(w, T(4), [&](int step) {
            if (step >= 60) fastest = std::max(fastest, length(w.body(id).linear_velocity()));
        });
        CHECK(fastest < T(1e-3));
        World<T> dropped(s);
        const BodyId body = drop_above_ground(dropped, T(0.8), T(1), box);
        const std::vector<T> tops = bounce_apexes(dropped, body, T(1.6));
        REQUIRE(!tops.empty());
        CAPTURE(tops[0]);
        CHECK(std::abs(tops[0] - T(0.64)) <= T(0.005) * T(0.64));
    }
}

TEST_CASE_TEMPLATE("regression: a ball and a box bounce to e^2 of each apex, bounce after bounce, within 3 %", C,
                   XENO_TEST_CONFIGS) {
    // Restitution took the approach speed from the start of the step, before the gravity of the
    // substeps up to the impact: each bounce lost up to g dt of speed, 5 % of the height at e = 1
    // (apexes 1.96, 1.86, 1.76 m from 2 m) and 5 % on top of e^2 at e = 0.8. Then the first apex
    // was within 0.8 % of e^2 h and each later one within 0.7-2.1 % of e^2 of the one before; since
    // the bounce keeps the integrator's energy (test below), within 0.1 %.
    using T = typename C::T;
    for (const T e : {T(0.8), T(1)}) {
        for (int kind = 0; kind < 2; ++kind) {
            World<T> w(C::settings());
            BodyDef<T> g;
            g.type = BodyType::static_body;
            g.position = {T(0), T(-0.5), T(0)};
            w.create_body(Box<T>(T(10), T(0.5), T(10)), g);  // restitution 0: the larger one counts
            BodyDef<T> def;
            const T h = T(2), bottom = T(0.25);
            def.position = {T(0), bottom + h, T(0)};
            def.material.restitution = e;
            const BodyId id =
                kind == 0 ? w.create_body(Sphere<T>(bottom), def) : w.create_body(Box<T>(bottom, bottom, bottom), def);
            std::vector<T> apexes;
            T previous_vy = T(0);
            simulate(w, T(6), [&](int) {
                const Body<T>& b = w.body(id);
                if (previous_vy > T(0) && b.linear_velocity().y <= T(0)) apexes.push_back(b.position().y - bottom);
                previous_vy = b.linear_velocity().y;
            });
            CAPTURE(e);
            CAPTURE(kind);
            REQUIRE(apexes.size() >= 3);
            CHECK(std::abs(apexes[0] - e * e * h) <= T(0.015) * e * e * h);
            for (std::size_t k = 1; k < 3; ++k) {  // impacts above 3 m/s
                CAPTURE(k);
                CHECK(std::abs(apexes[k] - e * e * apexes[k - 1]) <= T(0.03) * e * e * apexes[k - 1]);
                CHECK(apexes[k] <= apexes[k - 1] + T(1e-3));
            }
        }
    }
}

// Regression: the bounce worked with ½v² − a x, which the substeps' semi-implicit Euler does not
// keep (it keeps ½v² − a x + ½ a h v), and with an approach speed that held its impact substep's
// whole gravity, wherever in the substep the impact fell; and it bounced a point the relax pass
// had stopped short of the surface from there at e times a speed it never reached. Over drops of
// 0.3-3 m a ball or a box bounced to 0.970-1.014 of e^2 h (default settings), and with e = 1 a
// ball lost 0.7-1.3 % of its height a bounce. Now 0.997-1.000, and the height is kept.
TEST_CASE_TEMPLATE("a ball and a box dropped from 0.3 to 3 m bounce to e^2 h within 0.5 %, and with e = 1 keep their height", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    // The apexes of a body of half size 0.5 dropped from h (its bottom), over `seconds`.
    const auto apexes = [](T e, T h, bool box, T seconds) {
        World<T> w(C::settings());
        const BodyId id = drop_above_ground(w, e, h, box);
        return bounce_apexes(w, id, seconds);
    };
    for (const bool box : {false, true})
        for (const T e : {T(0.5), T(0.8), T(1)})
            for (const T h : {T(0.3), T(0.55), T(0.8), T(1.3), T(2.1), T(3)}) {
                CAPTURE(box);
                CAPTURE(e);
                CAPTURE(h);
                const std::vector<T> tops = apexes(e, h, box, T(2) * std::sqrt(T(2) * h / T(9.81)) + T(0.1));
                REQUIRE(!tops.empty());
                CAPTURE(tops[0]);
                CHECK(std::abs(tops[0] - e * e * h) <= T(0.005) * e * e * h);
            }
    // e = 1 from 0.5 m: 40 bounces in 26 s, each to the height it started from (it lost 1.3 % a
    // bounce before, 40 % by the end).
    const std::vector<T> tops = apexes(T(1), T(0.5), false, T(26));
    REQUIRE(tops.size() >= 40);
    for (const T top : tops) CHECK(std::abs(top - T(0.5)) <= T(0.002));
}

TEST_CASE_TEMPLATE("regression: a ball striking a row of touching balls with e = 1 adds no energy", C, XENO_TEST_CONFIGS) {
    // The approach speed of restitution was taken by each row as its turn came in a pass: the
    // contact between the first and second resting balls took the speed the striker had just given
    // the second one and bounced it again. Four balls (one striking three) left with 3.0 times the
    // kinetic energy they came with when the resting balls touched (float; 0.8 in double), 3.0
    // times with 1 mm between them and 1.5 with 1 cm; now 0.58, 0.68 and 0.82 times, in float and
    // double (the solver does not pass the impulse down a touching row as a real cradle does).
    using T = typename C::T;
    for (const T gap : {T(0), T(0.001), T(0.01)}) {
        WorldSettings<T> s = C::weightless();
        World<T> w(s);
        BodyDef<T> def;
        def.material = {T(0), T(1)};
        std::vector<BodyId> balls;
        for (int i = 0; i < 4; ++i) {
            def.position = {i == 0 ? T(-2) : T(i - 1) * (T(1) + gap), T(0), T(0)};
            def.linear_velocity = {i == 0 ? T(3) : T(0), T(0), T(0)};
            balls.push_back(w.create_body(Sphere<T>(T(0.5)), def));
        }
        auto energy = [&] {
            T e = T(0);
            for (const BodyId id : balls) e += T(0.5) * w.body(id).mass() * length_squared(w.body(id).linear_velocity());
            return e;
        };
        auto momentum = [&] {
            T p = T(0);
            for (const BodyId id : balls) p += w.body(id).mass() * w.body(id).linear_velocity().x;
            return p;
        };
        const T e0 = energy(), p0 = momentum();
        simulate(w, T(1.5));
        CAPTURE(gap);
        CAPTURE(energy() / e0);
        CHECK(energy() <= e0 * T(1.0001));
        CHECK(energy() > T(0.5) * e0);
        // With sleeping on, a ball left drifting below the sleep speed stops, and its momentum with it.
        if (!C::sleeping) CHECK(std::abs(momentum() - p0) <= T(1e-4) * p0);
        CHECK(w.body(balls.back()).linear_velocity().x > T(1));  // the push reached the far end
    }
}

TEST_CASE_TEMPLATE("regression: a tumbling box, capsule and cylinder bouncing with e = 1 gain no energy", C, XENO_TEST_CONFIGS) {
    // Restitution drives each point's v_n to -e times its approach, measured at anchors fixed for
    // the step and from the step's start; a body spinning at 10 rad/s turns 0.17 rad a step, so its
    // corners' approach was off by metres per second, and with e = 1 it left the floor with more
    // energy than it fell with: up to 11 % (box, mu 0), 25 % (capsule, mu 0.5) and 8 % (cylinder,
    // mu 0.5) over 10 s; dropped at 20 rad/s onto a 25 t slab resting on the floor (a cap on bodies
    // touching static ones alone did not reach it), up to 28 %, 6 % and 13 %. The energy here is the plain ½mv² + ½ω·Iω + mgy
    // from the bodies' states (the slab's from where it rests); the integrator's own differs from it by ½ m g h v (h the
    // substep), 0.3 % at these speeds.
    using T = typename C::T;
    for (const bool on_slab : {false, true})
        for (int kind = 0; kind < 3; ++kind)
            for (const T mu : {T(0), T(0.5)}) {
                World<T> w(C::settings());
                BodyDef<T> floor;
                floor.type = BodyType::static_body;
                floor.position = {T(0), T(-1), T(0)};
                floor.material = {mu, T(1)};
                w.create_body(Box<T>(T(50), T(1), T(50)), floor);
                BodyDef<T> slab = floor;
                slab.type = BodyType::dynamic;
                slab.position = {T(0), T(0.25), T(0)};
                const BodyId under = w.create_body(Box<T>(T(5), T(0.25), T(5)), slab);
                if (!on_slab) w.destroy_body(under);
                BodyDef<T> def;
                def.position = {T(0), T(on_slab ? 3 : 2), T(0)};
                def.angular_velocity = on_slab ? Vec3<T>{T(6), T(4), T(20)} : Vec3<T>{T(3), T(2), T(10)};
                def.material = {mu, T(1)};
                const Shape<T> shape = kind == 0   ? Shape<T>(Box<T>(T(1), T(0.3), T(0.5)))
                                       : kind == 1 ? Shape<T>(Capsule<T>(T(0.3), T(1)))
                                                   : Shape<T>(Cylinder<T>(T(0.5), T(0.6)));
                const BodyId id = w.create_body(shape, def);
                const auto energy = [&](BodyId body, T rest) {
                    const Body<T>& b = w.body(body);
                    const Vec3<T> spin = rotate(conjugate(b.orientation()), b.angular_velocity());
                    return double(T(0.5) * b.mass() * length_squared(b.linear_velocity()) +
                                  T(0.5) * dot(spin, b.local_inertia() * spin) + b.mass() * T(9.81) * (b.position().y - rest));
                };
                const auto total = [&] { return energy(id, T(0)) + (on_slab ? energy(under, T(0.25)) : 0.0); };
                const double e0 = total();
                double most = e0;
                simulate(w, T(10), [&](int) { most = std::max(most, total()); });
                CAPTURE(on_slab);
                CAPTURE(kind);
                CAPTURE(mu);
                CHECK(most / e0 < 1.005);
            }
}

TEST_CASE_TEMPLATE("regression: a ball striking a floor obliquely leaves as Newton's and Coulomb's laws say", C,
                   XENO_TEST_CONFIGS) {
    // A solid ball (I = 2/5 m r^2) meets the floor at v_t across and v_n down. While it slips,
    // friction takes mu (1 + e) m v_n of its tangential momentum over the impact; it cannot take
    // more than makes the contact point stop, which leaves the ball rolling at 5/7 v_t. Either way
    // the spin is 5 (v_t - v_t') / (2 r). Two faults failed this: friction turned the ball about
    // the midpoint of the anchors, half a step's travel below its surface (8 % too much spin at
    // 5 m/s, and a ball that should roll left slipping), and only the impulse that stopped the
    // approach bounded friction, not the rebound's (at mu 0.1, e = 1 it left at 2.5 m/s for 2.14).
    using T = typename C::T;
    const double r = 0.5, vt = 3, vn = 5;
    for (const double mu : {0.05, 0.1, 0.3})
        for (const double e : {0.0, 0.5, 1.0}) {
            const bool rolls = vt - mu * (1 + e) * vn < 5.0 / 7.0 * vt;
            WorldSettings<T> s = C::weightless();
            World<T> w(s);
            BodyDef<T> floor;
            floor.type = BodyType::static_body;
            floor.position = {T(0), T(-0.5), T(0)};
            floor.material = {T(mu), T(e)};
            w.create_body(Box<T>(T(50), T(0.5), T(50)), floor);
            BodyDef<T> def;
            def.material = {T(mu), T(e)};
            def.position = {T(0), T(1), T(0)};
            def.linear_velocity = {T(vt), T(-vn), T(0)};
            const BodyId ball = w.create_body(Sphere<T>(T(r)), def);
            simulate(w, T(0.5));
            const double after = rolls ? 5.0 / 7.0 * vt : vt - mu * (1 + e) * vn;
            const Vec3<T> v = w.body(ball).linear_velocity(), spin = w.body(ball).angular_velocity();
            CAPTURE(mu);
            CAPTURE(e);
            CHECK(std::abs(double(v.x) - after) < 1e-3 * vt);
            CHECK(std::abs(double(v.y) - e * vn) < 1e-3 * vn);
            CHECK(std::abs(double(spin.z) + 5 * (vt - after) / (2 * r)) < 1e-3 * vt / r);
        }
}

TEST_CASE_TEMPLATE("regression: a box dropped flat lands and bounces without turning or sliding", C, XENO_TEST_CONFIGS) {
    // One Gauss-Seidel sweep over a face's four points does not share an impact evenly: the first
    // point took the most and the body turned. A 0.5 m cube dropped flat from 0.5 m left the floor
    // turning at 0.5 rad/s; with friction it slid off sideways at 0.19 m/s; with e = 1 it left its
    // first bounce at that speed sideways and tipped over on a later one (the restitution pass's
    // four sweeps also left the shares uneven). Now an impact takes more sweeps of its own rows.
    using T = typename C::T;
    for (const T drop : {T(0.5), T(2)})
        for (const T mu : {T(0), T(0.6)})
            for (const T e : {T(0), T(1)}) {
                World<T> w(C::settings());
                BodyDef<T> g;
                g.type = BodyType::static_body;
                g.position = {T(0), T(-0.5), T(0)};
                g.material = {mu, T(0)};
                w.create_body(Box<T>(T(10), T(0.5), T(10)), g);
                BodyDef<T> def;
                def.position = {T(0), T(0.25) + drop, T(0)};
                def.material = {mu, e};
                const BodyId box = w.create_body(Box<T>(T(0.25), T(0.25), T(0.25)), def);
                T spin = T(0), slide = T(0);
                int bounces = 0;
                T previous_vy = T(0);
                simulate(w, T(5), [&](int) {
                    const Body<T>& b = w.body(box);
                    spin = std::max(spin, length(b.angular_velocity()));
                    const Vec3<T> v = b.linear_velocity();
                    slide = std::max(slide, std::sqrt(v.x * v.x + v.z * v.z));
                    if (previous_vy < T(0) && v.y > T(0)) ++bounces;
                    previous_vy = v.y;
                });
                CAPTURE(drop);
                CAPTURE(mu);
                CAPTURE(e);
                CAPTURE(spin);
                CAPTURE(slide);
                if (e > T(0)) CHECK(bounces >= 3);
                CHECK(spin < T(0.01));    // rad/s
                CHECK(slide < T(0.005));  // m/s
            }
}

TEST_CASE_TEMPLATE("regression: a cube landing flat while sliding slides on flat, as far as Coulomb's impulse leaves it", C,
                   XENO_TEST_CONFIGS) {
    // A unit cube with mu < 1 (half width / half height) cannot tip on landing: the front edge's
    // share of the normal impulse answers the friction's moment. The friction row, solved after
    // the normal rows, put mu x the impact impulse at the patch centre unanswered, and the cube
    // left the floor pivoting on its front edge at 1-3 rad/s, rolling up onto it (its centre
    // 0.207 m up) for most impact phases. The drop heights vary where in a step it lands.
    using T = typename C::T;
    const double mu = 0.6, g = 9.81;
    for (const double vy : {2.0, 4.0, 6.0})
        for (const double vx : {2.0, 4.0})
            for (const double h : {0.0, 0.013, 0.029, 0.051}) {
                World<T> w(C::settings());
                BodyDef<T> ground;
                ground.type = BodyType::static_body;
                ground.position = {T(0), T(-0.5), T(0)};
                ground.material = {T(mu), T(0)};
                w.create_body(Box<T>(T(50), T(0.5), T(50)), ground);
                BodyDef<T> def;
                def.position = {T(0), T(0.5 + h), T(0)};
                def.linear_velocity = {T(vx), T(-vy), T(0)};
                def.material = {T(mu), T(0)};
                const BodyId cube = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
                double spin = 0, rise = 0;
                bool landed = false;
                simulate(w, T(4), [&](int) {
                    const Body<T>& b = w.body(cube);
                    landed = landed || b.position().y < T(0.502);  // it falls 33 mm a step or more
                    if (!landed) return;
                    spin = std::max(spin, double(length(b.angular_velocity())));
                    rise = std::max(rise, double(b.position().y) - 0.5);
                });
                // Falling h, then an impact that takes mu x the vertical speed off the slide.
                const double landing = std::sqrt(vy * vy + 2 * g * h), fall = (landing - vy) / g;
                const double after = std::max(vx - mu * landing, 0.0);
                const double exact = vx * fall + after * after / (2 * mu * g);
                CAPTURE(vy);
                CAPTURE(vx);
                CAPTURE(h);
                CHECK(spin < 0.15);  // rad/s (was 1-3)
                CHECK(rise < 1e-3);  // m (was up to 0.207)
                CHECK(std::abs(double(w.body(cube).position().x) - exact) < 0.01 + 0.02 * exact);
            }
}

TEST_CASE_TEMPLATE("regression: a plate landing flat on several manifolds at once lands flat: across tiles, as a compound", C,
                   XENO_TEST_CONFIGS) {
    // Each manifold took its impact sweeps alone, and the first one solved stopped most of the
    // plate and turned it: a 1 x 0.4 x 1 m box dropped 2 m across the seam of two floor tiles
    // 0.1 m off its centre left its landing spinning at 0.51 rad/s (0.35 with friction, sliding
    // off at 0.24 m/s), and a compound of two such halves on one floor at 0.41 rad/s. On one
    // floor: 0.001 rad/s.
    using T = typename C::T;
    for (const bool compound : {false, true})
        for (const T mu : {T(0), T(0.6)}) {
            World<T> w(C::settings());
            const auto tile = [&](T x, T half) {
                BodyDef<T> g;
                g.type = BodyType::static_body;
                g.position = {x, T(-0.5), T(0)};
                g.material = {mu, T(0)};
                w.create_body(Box<T>(half, T(0.5), T(10)), g);
            };
            if (compound) tile(T(0), T(10));
            else tile(T(-5.1), T(5)), tile(T(4.9), T(5));  // the seam at x = -0.1, under the plate
            BodyDef<T> def;
            def.position = {T(0), T(2.2), T(0)};
            def.material = {mu, T(0)};
            const Box<T> half(T(0.25), T(0.2), T(0.5));
            const Transform<T> left{{T(-0.25), T(0), T(0)}, Quat<T>::identity()};
            const Transform<T> right{{T(0.25), T(0), T(0)}, Quat<T>::identity()};
            const BodyId plate = compound ? w.create_body(Compound<T>({{half, left}, {half, right}}), def)
                                          : w.create_body(Box<T>(T(0.5), T(0.2), T(0.5)), def);
            T spin = T(0), slide = T(0);
            simulate(w, T(2), [&](int) {
                const Body<T>& b = w.body(plate);
                spin = std::max(spin, length(b.angular_velocity()));
                slide = std::max(slide, std::hypot(b.linear_velocity().x, b.linear_velocity().z));
            });
            CAPTURE(compound);
            CAPTURE(mu);
            CHECK(spin < T(0.02));   // rad/s
            CHECK(slide < T(0.02));  // m/s
            CHECK(std::abs(w.body(plate).position().x) < T(1e-3));
            CHECK(std::abs(w.body(plate).position().y - T(0.2)) < T(2e-3));
        }
}

TEST_CASE_TEMPLATE("regression: a ball at rest over a thin floor lands on it under strong gravity or a long step", T, float,
                   double) {
    // The contact margin counted a body's speed at the start of the step, not what gravity adds
    // within it (g dt^2): a ball 3 cm over a 2 cm floor fell through it under g = 1000 at 60 Hz
    // (ending 720 m down), and under g at dt = 0.2 s (20 m down).
    struct Case {
        T gravity, dt;
    };
    for (const Case k : {Case{T(1000), T(1) / T(60)}, Case{T(9.81), T(0.2)}}) {
        WorldSettings<T> s;
        s.gravity = {T(0), -k.gravity, T(0)};
        World<T> w(s);
        BodyDef<T> floor;
        floor.type = BodyType::static_body;
        floor.position = {T(0), T(-0.01), T(0)};
        w.create_body(Box<T>(T(5), T(0.01), T(5)), floor);
        BodyDef<T> d;
        d.position = {T(0), T(0.08), T(0)};  // 3 cm over the floor's top
        const BodyId ball = w.create_body(Sphere<T>(T(0.05)), d);
        for (int i = 0; i < static_cast<int>(T(2) / k.dt); ++i) w.step(k.dt);
        CAPTURE(k.gravity);
        CAPTURE(k.dt);
        CHECK(std::abs(w.body(ball).position().y - T(0.05)) < T(0.01));  // on it, sagging a few mm
    }
}

TEST_CASE_TEMPLATE("with restitution 1 a box never bounces higher than it started, over 10 bounces", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    BodyDef<T> g;
    g.type = BodyType::static_body;
    g.position = {T(0), T(-0.5), T(0)};
    g.material.restitution = T(1);
    w.create_body(Box<T>(T(10), T(0.5), T(10)), g);
    BodyDef<T> def;
    def.position = {T(0), T(2.5), T(0)};
    def.material.restitution = T(1);
    const BodyId box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    int bounces = 0;
    T highest = T(0);
    T previous_vy = T(0);
    // 14 s: each bounce keeps 99 % of its height, so ten of them take 13 s (12 s held ten while
    // restitution lost 4-5 % a bounce).
    simulate(w, T(14), [&](int) {
        const Body<T>& b = w.body(box);
        if (previous_vy < T(0) && b.linear_velocity().y > T(0)) ++bounces;
        previous_vy = b.linear_velocity().y;
        if (bounces > 0) highest = std::max(highest, b.position().y);
    });
    CHECK(bounces >= 10);
    CAPTURE(highest);
    CHECK(highest <= T(2.5) + T(1e-3));
    CHECK(highest > T(2.0));  // and it does bounce back most of the way
}

TEST_CASE_TEMPLATE("momentum is conserved when two bodies collide without gravity", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    WorldSettings<T> s = C::weightless();
    World<T> w(s);
    BodyDef<T> a;
    a.position = {T(-2), T(0), T(0)};
    a.linear_velocity = {T(3), T(0.2), T(0)};
    a.material.restitution = T(0.5);
    BodyDef<T> b;
    b.position = {T(2), T(0.3), T(0.1)};
    b.linear_velocity = {T(-1), T(0), T(0)};
    b.density = T(2500);
    const BodyId ia = w.create_body(Box<T>(T(0.5), T(0.4), T(0.3)), a);
    const BodyId ib = w.create_body(Sphere<T>(T(0.6)), b);
    auto momentum = [&] {
        return w.body(ia).linear_velocity() * w.body(ia).mass() + w.body(ib).linear_velocity() * w.body(ib).mass();
    };
    const Vec3<T> p0 = momentum();
    bool touched = false;
    simulate(w, T(2), [&](int) { touched |= !w.contacts().empty() && w.contacts()[0].touching; });
    CHECK(touched);
    CHECK(length(momentum() - p0) < T(1e-4) * length(p0));
    CHECK(w.body(ib).linear_velocity().x > T(-1));  // B was pushed
}

// A ball striking a resting ball off-centre, frictionless: the impulse acts along the line of
// centres at the moment of impact, at angle asin(offset / (r_a + r_b)) to the approach, and with
// e = 1 and equal masses the two leave at right angles (above the restitution threshold). Before the speculative contact was
// moved to the first touch (World::at_first_touch) its normal was the closest features' at the start of the step, which turns as
// the balls close: at 10 m/s, offset 0.95 of a diameter, the struck ball left at 62.2° instead of 71.8° with 49 % too much speed.
TEST_CASE_TEMPLATE("a ball struck off-centre leaves along the line of centres at impact", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    for (const double speed : {3.0, 10.0, 30.0})
        for (const double offset : {0.2, 0.5, 0.95})
            for (const double start : {-2.0, -2.05, -2.1}) {
                WorldSettings<T> s = C::weightless();
                World<T> w(s);
                BodyDef<T> def;
                def.material = {T(0), T(1)};
                def.position = {T(start), T(0), T(0)};
                def.linear_velocity = {T(speed), T(0), T(0)};
                const BodyId striker = w.create_body(Sphere<T>(T(0.5)), def);
                def.position = {T(0), T(offset), T(0)};
                def.linear_velocity = {};
                const BodyId struck = w.create_body(Sphere<T>(T(0.5)), def);
                simulate(w, T(1));
                const Vec3<T> va = w.body(striker).linear_velocity(), vb = w.body(struck).linear_velocity();
                const double angle = std::atan2(double(vb.y), double(vb.x)), exact = std::asin(offset);
                CAPTURE(speed);
                CAPTURE(offset);
                CAPTURE(start);
                CAPTURE(angle);
                CHECK(std::abs(angle - exact) < 1e-3);  // rad
                // Below the restitution threshold (1 m/s along the normal) the impact is inelastic:
                // the struck ball takes half the normal speed.
                const double normal_speed = speed * std::cos(exact);
                const bool bounces = normal_speed > double(s.restitution_threshold);
                CHECK(std::abs(double(length(vb)) - (bounces ? normal_speed : normal_speed / 2)) < 1e-3 * speed);
                if (bounces) CHECK(std::abs(double(dot(va, vb))) < 1e-3 * speed * speed);  // at right angles
                CHECK(length(w.body(striker).angular_velocity()) < T(1e-3));               // struck through their centres
                CHECK(length(w.body(struck).angular_velocity()) < T(1e-3));
            }
}

TEST_CASE_TEMPLATE("a torque-free box keeps its angular momentum within 1 % over 10 s", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    WorldSettings<T> s = C::weightless();
    World<T> w(s);
    BodyDef<T> def;
    def.angular_velocity = {T(2), T(3), T(-1.5)};  // not about a principal axis
    const BodyId id = w.create_body(Box<T>(T(0.2), T(0.5), T(0.9)), def);
    auto angular_momentum = [&] {
        const Body<T>& b = w.body(id);
        const Mat3<T> r = to_matrix(b.orientation());
        return r * (b.local_inertia() * (transpose(r) * b.angular_velocity()));
    };
    const Vec3<T> l0 = angular_momentum();
    T worst = T(0);
    simulate(w, T(10), [&](int) { worst = std::max(worst, length(angular_momentum() - l0) / length(l0)); });
    CAPTURE(worst);
    CHECK(worst < T(0.01));
}

// Regression: the gyroscopic step took ω into the body frame and back through q = Δq · q0, a
// product of two rounded unit quaternions that is on average a little long in float, and the
// round trip scaled ω by |q|⁴ every substep: a free box, cylinder or capsule tumbling in float
// gained 0.14–0.22 % of its energy in 10 s (a straight line; 0.77 % at 32 substeps). Double kept
// it to 1e-12. The midpoint rule keeps the energy and |L| of a free body; the test asks 1e-4.
TEST_CASE_TEMPLATE("regression: a body tumbling freely keeps its energy and |L| in float and double", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    WorldSettings<T> s = C::weightless();
    World<T> w(s);
    BodyDef<T> def;
    def.angular_velocity = {T(2), T(3), T(-1.5)};
    const BodyId box = w.create_body(Box<T>(T(0.2), T(0.5), T(0.9)), def);
    def.position = {T(5), T(0), T(0)};
    def.angular_velocity = {T(1), T(2), T(0.5)};
    const BodyId cylinder = w.create_body(Cylinder<T>(T(0.2), T(1)), def);
    def.position = {T(-5), T(0), T(0)};
    def.angular_velocity = {T(3), T(10), T(0)};
    const BodyId capsule = w.create_body(Capsule<T>(T(0.1), T(0.8)), def);
    // In the body frame, independent of the world-frame round trip the step makes.
    const auto body_spin = [&](BodyId id) {
        return inverse_rotate(normalized(w.body(id).orientation()), w.body(id).angular_velocity());
    };
    const auto energy = [&](BodyId id) { return dot(body_spin(id), w.body(id).local_inertia() * body_spin(id)) / T(2); };
    const auto momentum = [&](BodyId id) { return length(w.body(id).local_inertia() * body_spin(id)); };
    const BodyId bodies[] = {box, cylinder, capsule};
    T e0[3], l0[3], worst_e = T(0), worst_l = T(0);
    for (int i = 0; i < 3; ++i) e0[i] = energy(bodies[i]), l0[i] = momentum(bodies[i]);
    simulate(w, T(10), [&](int) {
        for (int i = 0; i < 3; ++i) {
            worst_e = std::max(worst_e, std::abs(energy(bodies[i]) / e0[i] - T(1)));
            worst_l = std::max(worst_l, std::abs(momentum(bodies[i]) / l0[i] - T(1)));
        }
    });
    CAPTURE(worst_e);
    CAPTURE(worst_l);
    CHECK(worst_e < T(1e-4));
    CHECK(worst_l < T(1e-4));
}

TEST_CASE_TEMPLATE("spun near its intermediate axis a free box flips (Dzhanibekov)", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    WorldSettings<T> s = C::weightless();
    World<T> w(s);
    BodyDef<T> def;
    def.angular_velocity = {T(0.01), T(5), T(0.01)};  // y is the intermediate axis of (0.2, 0.5, 0.9)
    const BodyId id = w.create_body(Box<T>(T(0.2), T(0.5), T(0.9)), def);
    T min_alignment = T(1);
    simulate(w, T(10), [&](int) {
        const Vec3<T> axis = rotate(w.body(id).orientation(), Vec3<T>::unit_y());
        min_alignment = std::min(min_alignment, dot(axis, Vec3<T>::unit_y()));
    });
    CHECK(min_alignment < T(-0.9));  // the body's y axis turned over
}

// regression: a contact's levers were fixed for the step while the body turned through its
// substeps, so a fast top held still a point near its apex where the apex had been, not where it
// was: spun at 300 rad/s and tilted 0.1 rad, its apex slid 0.20 m in 2 s (ending each step at
// 0.11 m/s), and at 150 rad/s its tilt grew from 5.7° to 9.1° in 5 s. A fast top on a point that
// does not slide keeps its tilt and precesses at the rate of a heavy symmetric top.
TEST_CASE_TEMPLATE("regression: a fast top keeps its apex and tilt and precesses as a heavy symmetric top", C,
                   XENO_TEST_CONFIGS) {
    using T = typename C::T;
    const T radius = T(0.3), height = T(0.6), tilt = T(0.1), seconds = T(5);
    const T l = T(0.75) * height;  // the cone's apex is 3H/4 from its centre of mass, along local y
    for (const T spin : {T(150), T(300)}) {
        CAPTURE(spin);
        World<T> w(C::settings());
        scenes::add_ground(w, T(20));
        // Upside down, the apex on the floor at the origin, the axis tilted by `tilt` about x.
        BodyDef<T> def;
        def.orientation = Quat<T>::from_axis_angle(Vec3<T>::unit_x(), ScalarTraits<T>::pi + tilt);
        const Vec3<T> up = rotate(def.orientation, Vec3<T>::unit_y()) * T(-1);  // apex to base
        def.position = up * l + Vec3<T>{T(0), T(0.001), T(0)};
        def.angular_velocity = up * spin;
        const BodyId top = w.create_body(Cone<T>(radius, height), def);
        const auto apex = [&] { return w.body(top).position() + rotate(w.body(top).orientation(), Vec3<T>{T(0), l, T(0)}); };
        // The precession: the turn of the centre of mass about the apex, in the floor's plane.
        const auto azimuth = [&] {
            const Vec3<T> d = w.body(top).position() - apex();
            return std::atan2(d.x, d.z);
        };
        T swept = T(0), last = azimuth(), worst_slide = T(0), worst_tilt = T(0);
        simulate(w, seconds, [&](int) {
            T turn = azimuth() - last;
            last += turn;
            if (turn > ScalarTraits<T>::pi) turn -= T(2) * ScalarTraits<T>::pi;
            if (turn < -ScalarTraits<T>::pi) turn += T(2) * ScalarTraits<T>::pi;
            swept += turn;
            const Vec3<T> a = apex();
            worst_slide = std::max(worst_slide, std::sqrt(a.x * a.x + a.z * a.z));
            worst_tilt = std::max(worst_tilt, std::acos(std::min(T(1), -rotate(w.body(top).orientation(), Vec3<T>::unit_y()).y)));
        });
        // Steady precession of a heavy symmetric top at tilt θ: m g l = Ω (I₃ ω − I₁ Ω cos θ), its
        // slow root; I₃ about the axis, I₁ across it through the apex (a solid cone: 3/10 m r²
        // and 3/20 m r² + 3/80 m H² + m l²). The fast-top limit m g l / (I₃ ω) is 6 % lower at
        // 150 rad/s.
        const T mass = T(1000) * ScalarTraits<T>::pi * radius * radius * height / T(3);
        const T i3 = T(0.3) * mass * radius * radius;
        const T i1 = T(0.15) * mass * radius * radius + T(0.0375) * mass * height * height + mass * l * l;
        const T spin_momentum = i3 * spin, c = i1 * std::cos(tilt), mgl = mass * T(9.81) * l;
        const T expected = (spin_momentum - std::sqrt(spin_momentum * spin_momentum - T(4) * c * mgl)) / (T(2) * c);
        const T measured = std::abs(swept) / seconds;
        CAPTURE(worst_slide);
        CAPTURE(worst_tilt);
        CAPTURE(measured);
        CAPTURE(expected);
        CHECK(worst_slide < T(0.04));                               // 0.028 m at 300 rad/s; was 0.2 m in 2 s
        CHECK(worst_tilt < tilt + T(0.02));                         // was 0.158 rad after 5 s at 150 rad/s
        CHECK(std::abs(measured - expected) < T(0.03) * expected);  // was 6 % slow
    }
}

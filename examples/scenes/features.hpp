// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Scenes that show the game-facing features: `sleeping-pile` (a pile that falls asleep; sleeping
// bodies are drawn faded), `ray-fan` (a fan of rays cast each frame; the renderer draws them),
// `bullet` (a small box fired at 300 m/s at a thin wall), `pendulum`, `chain` (20 links),
// `hinged-door` (a door swung against its limit) and `ragdoll` (capsules joined by swing-twist
// and hinge joints, dropped on a step).
#pragma once

#include "random.hpp"
#include "scene.hpp"

namespace xeno::scenes {

template <class T>
BodyId add_static_box(World<T>& world, const Vec3<T>& half, const Vec3<T>& position, const Quat<T>& q = Quat<T>::identity()) {
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = position;
    d.orientation = q;
    return world.create_body(Box<T>(half), d);
}

/// 64 boxes in a loose heap: they settle within a few seconds and fall asleep (the scene asks
/// for a short sleep time, 0.25 s, so the renderer's two seconds show it).
template <class T>
Scene sleeping_pile(World<T>& world) {
    WorldSettings<T> settings = world.settings();
    settings.allow_sleeping = true;
    settings.sleep_time = T(0.25);
    world.set_settings(settings);
    Scene s;
    s.ground = add_ground(world);
    Random rng(5);
    for (int i = 0; i < 64; ++i)
        s.bodies.push_back(add_box(world, Vec3<T>{T(0.3), T(0.3), T(0.3)},
                                   Vec3<T>{rng.uniform(T(-1.5), T(1.5)), T(0.4) + T(0.12) * T(i), rng.uniform(T(-1.5), T(1.5))},
                                   rng.rotation<T>()));
    s.eye = {6, 5, 8};
    s.target = {0, 0.8, 0};
    s.seconds = 4.5;  // the pile settles and falls asleep (3 s) and sits greyed
    return s;
}

/// A few bodies on the ground for the ray fan to hit; the rays come from (0, 0.45, -4).
template <class T>
Scene ray_fan(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    s.bodies.push_back(add_box(world, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(-1.5), T(0.5), T(1)}));
    BodyDef<T> d;
    d.position = {T(0.5), T(0.6), T(1.5)};
    s.bodies.push_back(world.create_body(Sphere<T>(T(0.6)), d));
    d.position = {T(2.2), T(0.7), T(0.5)};
    s.bodies.push_back(world.create_body(Cylinder<T>(T(0.4), T(0.7)), d));
    d.position = {T(-0.3), T(0.25), T(3.5)};
    d.orientation = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 2);
    s.bodies.push_back(world.create_body(Capsule<T>(T(0.25), T(1)), d));
    d.position = {T(-3), T(0.6), T(0)};
    d.orientation = Quat<T>::identity();
    s.bodies.push_back(world.create_body(Cone<T>(T(0.5), T(1.2)), d));
    s.bodies.push_back(add_box(world, Vec3<T>{T(0.4), T(0.4), T(0.4)}, Vec3<T>{T(3.2), T(0.4), T(-1.5)},
                               Quat<T>::from_axis_angle(Vec3<T>::unit_y(), T(0.6))));
    s.eye = {0, 6, -9};
    s.target = {0, 0.5, 1};
    s.seconds = 3;  // the bodies land under the fan
    return s;
}

/// The fan's rays: `count` directions across 160° in the plane y = 0.45, from (0, 0.45, -4).
template <class T>
std::vector<Ray<T>> ray_fan_rays(int count = 32) {
    std::vector<Ray<T>> rays;
    for (int i = 0; i < count; ++i) {
        const T a = radians(T(-80) + T(160) * T(i) / T(count - 1));
        rays.push_back({{T(0), T(0.45), T(-4)}, {std::sin(a), T(0), std::cos(a)}, T(12)});
    }
    return rays;
}

/// A 10 cm box fired at 300 m/s towards a 10 cm wall: continuous detection stops it.
template <class T>
Scene bullet(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    add_static_box(world, Vec3<T>{T(0.05), T(1.5), T(2)}, Vec3<T>{T(8), T(1.5), T(0)});
    BodyDef<T> d;
    d.fast = true;
    d.position = {T(-6), T(1.5), T(0)};
    d.linear_velocity = {T(300), T(0), T(0)};
    d.angular_velocity = {T(0), T(20), T(10)};
    s.bodies.push_back(world.create_body(Box<T>(T(0.05), T(0.05), T(0.05)), d));
    s.eye = {2, 4, 12};
    s.target = {4, 1.2, 0};
    s.seconds = 2;  // the shot and the box at rest at the wall
    return s;
}

/// A 2 m pendulum released from 30°.
template <class T>
Scene pendulum(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    const Vec3<T> pivot{T(0), T(4), T(0)};
    const BodyId top = add_static_box(world, Vec3<T>{T(0.1), T(0.1), T(0.1)}, pivot);
    BodyDef<T> d;
    const T a = radians(T(30));
    d.position = pivot + Vec3<T>{std::sin(a), -std::cos(a), T(0)} * T(2);
    s.bodies.push_back(world.create_body(Sphere<T>(T(0.2)), d));
    world.create_joint(JointDef<T>::ball(top, s.bodies.back(), pivot));
    s.eye = {0, 3, 8};
    s.target = {0, 2.5, 0};
    s.seconds = 6;  // two swings (period 2π√(L/g) = 2.84 s)
    return s;
}

/// 20 capsule links hung from a pivot, released horizontally.
template <class T>
Scene chain(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    const Vec3<T> pivot{T(0), T(11), T(0)};
    BodyId previous = add_static_box(world, Vec3<T>{T(0.1), T(0.1), T(0.1)}, pivot);
    const Quat<T> along_x = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 2);
    for (int i = 0; i < 20; ++i) {
        BodyDef<T> d;
        d.position = pivot + Vec3<T>{T(0.5) * (T(i) + T(0.5)), T(0), T(0)};
        d.orientation = along_x;
        const BodyId link = world.create_body(Capsule<T>(T(0.06), T(0.2)), d);
        world.create_joint(JointDef<T>::ball(previous, link, pivot + Vec3<T>{T(0.5) * T(i), T(0), T(0)}));
        s.bodies.push_back(link);
        previous = link;
    }
    s.eye = {4, 7, 18};
    s.target = {2, 6, 0};
    s.seconds = 6;  // the chain falls and swings twice
    return s;
}

/// A door on a vertical hinge, pushed open against its 90° stop.
template <class T>
Scene hinged_door(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    const BodyId post = add_static_box(world, Vec3<T>{T(0.05), T(1.1), T(0.05)}, Vec3<T>{T(-0.05), T(1.1), T(0)});
    BodyDef<T> d;
    d.position = {T(0.5), T(1.1), T(0)};
    d.angular_velocity = {T(0), T(3), T(0)};
    s.bodies.push_back(world.create_body(Box<T>(T(0.48), T(1), T(0.03)), d));
    JointDef<T> hinge = JointDef<T>::hinge(post, s.bodies.back(), Vec3<T>{T(0), T(1.1), T(0)}, Vec3<T>::unit_y());
    hinge.enable_limit = true;
    hinge.lower_angle = T(0);
    hinge.upper_angle = ScalarTraits<T>::pi / 2;
    world.create_joint(hinge);
    s.eye = {2.5, 2.5, 4};
    s.target = {0.2, 1, -0.3};
    s.seconds = 3;  // the swing, the stop, the bounce back
    return s;
}

/// A ragdoll of capsules (torso, head, arms, legs) joined by swing-twist joints at the neck,
/// shoulders and hips and hinges at the elbows and knees, dropped onto a step. The parts have some angular
/// damping, as ragdolls in games do.
template <class T>
Scene ragdoll(World<T>& world, const Vec3<T>& at = {T(0), T(3), T(0)}) {
    Scene s;
    s.ground = add_ground(world);
    add_static_box(world, Vec3<T>{T(0.5), T(0.2), T(0.6)}, Vec3<T>{T(0.4), T(0.2), T(0)});
    auto part = [&](T radius, T half, const Vec3<T>& centre, const Quat<T>& q = Quat<T>::identity()) {
        BodyDef<T> d;
        d.position = at + centre;
        d.orientation = q;
        d.angular_damping = T(1);  // limbs lose spin (capsules would otherwise roll for ever)
        s.bodies.push_back(world.create_body(Capsule<T>(radius, half), d));
        return s.bodies.back();
    };
    const Quat<T> sideways = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), ScalarTraits<T>::pi / 2);
    const BodyId torso = part(T(0.18), T(0.2), {T(0), T(0), T(0)});
    const BodyId head = part(T(0.12), T(0.02), {T(0), T(0.56), T(0)});
    const BodyId upper_arm_l = part(T(0.06), T(0.12), {T(-0.4), T(0.25), T(0)}, sideways);
    const BodyId lower_arm_l = part(T(0.05), T(0.12), {T(-0.76), T(0.25), T(0)}, sideways);
    const BodyId upper_arm_r = part(T(0.06), T(0.12), {T(0.4), T(0.25), T(0)}, sideways);
    const BodyId lower_arm_r = part(T(0.05), T(0.12), {T(0.76), T(0.25), T(0)}, sideways);
    const BodyId thigh_l = part(T(0.08), T(0.16), {T(-0.12), T(-0.66), T(0)});
    const BodyId shin_l = part(T(0.07), T(0.16), {T(-0.12), T(-1.12), T(0)});
    const BodyId thigh_r = part(T(0.08), T(0.16), {T(0.12), T(-0.66), T(0)});
    const BodyId shin_r = part(T(0.07), T(0.16), {T(0.12), T(-1.12), T(0)});
    // Swing-twist joints: each limb's twist axis points along it, away from the torso; the cone
    // bounds how far it swings from where it started, the twist how far it turns about itself.
    auto limb = [&](BodyId b, const Vec3<T>& anchor, const Vec3<T>& along, T cone, T twist) {
        world.create_joint(JointDef<T>::swing_twist(torso, b, at + anchor, along, cone, -twist, twist));
    };
    const Vec3<T> up = Vec3<T>::unit_y(), down = -Vec3<T>::unit_y(), left = -Vec3<T>::unit_x(), right = Vec3<T>::unit_x();
    limb(head, {T(0), T(0.42), T(0)}, up, radians(T(40)), radians(T(60)));
    limb(upper_arm_l, {T(-0.22), T(0.25), T(0)}, left, radians(T(80)), radians(T(45)));
    limb(upper_arm_r, {T(0.22), T(0.25), T(0)}, right, radians(T(80)), radians(T(45)));
    limb(thigh_l, {T(-0.12), T(-0.42), T(0)}, down, radians(T(60)), radians(T(20)));
    limb(thigh_r, {T(0.12), T(-0.42), T(0)}, down, radians(T(60)), radians(T(20)));
    auto limited_hinge = [&](BodyId a, BodyId b, const Vec3<T>& anchor, T lower, T upper) {
        JointDef<T> h = JointDef<T>::hinge(a, b, at + anchor, Vec3<T>::unit_z());
        h.enable_limit = true;
        h.lower_angle = lower;
        h.upper_angle = upper;
        world.create_joint(h);
    };
    limited_hinge(upper_arm_l, lower_arm_l, {T(-0.58), T(0.25), T(0)}, T(-2.5), T(0));
    limited_hinge(upper_arm_r, lower_arm_r, {T(0.58), T(0.25), T(0)}, T(0), T(2.5));
    limited_hinge(thigh_l, shin_l, {T(-0.12), T(-0.89), T(0)}, T(-2.5), T(0));
    limited_hinge(thigh_r, shin_r, {T(0.12), T(-0.89), T(0)}, T(-2.5), T(0));
    s.eye = {1.5, 2.2, 5};
    s.target = {0.2, 0.6, 0};
    s.seconds = 3.5;  // the fall down the step, then at rest (2.4 s)
    return s;
}

}  // namespace xeno::scenes

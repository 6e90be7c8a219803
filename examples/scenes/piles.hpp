// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Scenes with many loose bodies: `rain` (boxes and spheres dropped from a grid of heights),
// `mixed-pile` (every shape kind: hulls, spheres, capsules, cylinders, cones, boxes, dropped into
// a pile) and `incline` (boxes of different friction side by side on a ramp, the friction angle
// tan θ = µ between them).
#pragma once

#include "random.hpp"
#include "scene.hpp"

#include <xeno/shape/convex_hull.hpp>

#include <cmath>
#include <memory>

namespace xeno::scenes {

/// `count` bodies (boxes and spheres) falling from heights 2 … 12 m onto the ground.
template <class T>
Scene rain(World<T>& world, int count = 120, std::uint64_t seed = 7) {
    Scene s;
    s.ground = add_ground(world);
    Random rng(seed);
    const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.3), T(0.3), T(0.3)));
    const auto ball = std::make_shared<const Shape<T>>(Sphere<T>(T(0.3)));
    for (int i = 0; i < count; ++i) {
        BodyDef<T> def;
        def.position = {rng.uniform(T(-3), T(3)), T(2) + T(10) * T(i) / T(count), rng.uniform(T(-3), T(3))};
        def.orientation = rng.rotation<T>();
        def.material.restitution = T(0.2);
        s.bodies.push_back(world.create_body(i % 3 == 2 ? ball : box, def));
    }
    s.eye = {9, 7, 12};
    s.target = {0, 1.5, 0};
    s.seconds = 5;  // the rain lands and the pile spreads
    return s;
}

/// `count` unit boxes in a loose grid 1.5 m apart, layer above layer from 2 m up, turned at random,
/// falling onto a 200 m ground: the benchmark's dropped piles (xeno_step_bench), and the pile the
/// slow test of sleeping at scale drops.
template <class T>
Scene dropped_boxes(World<T>& world, int count) {
    Scene s;
    s.ground = add_ground(world, T(100));
    Random rng(3);
    const int side = static_cast<int>(std::ceil(std::sqrt(double(count) / 4)));
    const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
    for (int i = 0; i < count; ++i) {
        const int layer = i / (side * side), k = i % (side * side);
        BodyDef<T> def;
        def.position = {T(1.5) * T(k % side - side / 2), T(2) + T(1.5) * T(layer), T(1.5) * T(k / side - side / 2)};
        def.orientation = rng.rotation<T>();
        s.bodies.push_back(world.create_body(box, def));
    }
    s.eye = {30, 20, 40};
    s.target = {0, 1, 0};
    s.seconds = 10;
    return s;
}

/// Every kind of shape dropped into one pile inside a low pen of static walls.
template <class T>
Scene mixed_pile(World<T>& world, int count = 60, std::uint64_t seed = 11) {
    Scene s;
    s.ground = add_ground(world);
    for (int side = 0; side < 4; ++side) {  // a pen 5 m wide, 0.6 m high
        BodyDef<T> wall;
        wall.type = BodyType::static_body;
        const T sign = side % 2 == 0 ? T(1) : T(-1);
        wall.position = side < 2 ? Vec3<T>{sign * T(2.6), T(0.3), T(0)} : Vec3<T>{T(0), T(0.3), sign * T(2.6)};
        world.create_body(side < 2 ? Box<T>(T(0.1), T(0.3), T(2.7)) : Box<T>(T(2.7), T(0.3), T(0.1)), wall);
    }
    Random rng(seed);
    std::vector<Vec3<T>> rock_points;
    for (int i = 0; i < 24; ++i) rock_points.push_back(hadamard(rng.direction<T>(), Vec3<T>{T(0.35), T(0.25), T(0.3)}));
    const auto rock = std::make_shared<const Shape<T>>(make_convex_hull(rock_points).polyhedron);
    const std::shared_ptr<const Shape<T>> kinds[] = {
        rock,
        std::make_shared<const Shape<T>>(Sphere<T>(T(0.3))),
        std::make_shared<const Shape<T>>(Capsule<T>(T(0.2), T(0.3))),
        std::make_shared<const Shape<T>>(Cylinder<T>(T(0.3), T(0.25))),
        std::make_shared<const Shape<T>>(Cone<T>(T(0.3), T(0.7))),
        std::make_shared<const Shape<T>>(Box<T>(T(0.3), T(0.2), T(0.25))),
    };
    for (int i = 0; i < count; ++i) {
        BodyDef<T> def;
        def.position = {rng.uniform(T(-1.5), T(1.5)), T(1) + T(0.6) * T(i), rng.uniform(T(-1.5), T(1.5))};
        def.orientation = rng.rotation<T>();
        s.bodies.push_back(world.create_body(kinds[i % 6], def));
    }
    s.eye = {6, 6, 9};
    s.target = {0, 0.8, 0};
    s.seconds = 5;  // the pile lands and settles in the pen
    return s;
}

/// Boxes with friction µ = 0.2, 0.3, … 0.8 side by side on a ramp of angle atan(0.5): those
/// with µ above 0.5 stay, the others slide down.
template <class T>
Scene incline(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    const T angle = std::atan(T(0.5));
    const Quat<T> tilt = Quat<T>::from_axis_angle(Vec3<T>::unit_z(), angle);
    BodyDef<T> ramp;
    ramp.type = BodyType::static_body;
    ramp.orientation = tilt;
    ramp.position = {T(0), T(2), T(0)};
    ramp.material.friction = T(1);  // combined friction is sqrt(1 · µ_box)... see below
    world.create_body(Box<T>(T(6), T(0.2), T(4)), ramp);
    for (int i = 0; i < 7; ++i) {
        const T mu = T(0.2) + T(0.1) * T(i);
        BodyDef<T> def;
        def.orientation = tilt;
        def.position = ramp.position + rotate(tilt, Vec3<T>{T(2.5), T(0.2) + T(0.25), T(-3) + T(i)});
        // The pair's friction is √(µ_ramp µ_box) = √µ_box with µ_ramp = 1: give the box µ² so the
        // pair sees µ.
        def.material.friction = mu * mu;
        s.bodies.push_back(world.create_body(Box<T>(T(0.25), T(0.25), T(0.25)), def));
    }
    s.eye = {-3, 5, 11};
    s.target = {0, 1.5, 0};
    s.seconds = 6.5;  // the slippery boxes slide off; the others stop (5.6 s)
    return s;
}

}  // namespace xeno::scenes

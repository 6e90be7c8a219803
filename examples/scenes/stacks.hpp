// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Stacking scenes: `column` (boxes one on another), `pyramid` (a planar pyramid one box deep, as
// Box2D's and Box3D's benchmark pyramids are) and `heavy-on-light` (a box 400 times heavier on a
// light one, the ratio the thesis credits Newton Game Dynamics with, 2.7). Boxes are placed
// exactly touching, at rest, on a ground whose top is y = 0.
#pragma once

#include "scene.hpp"

namespace xeno::scenes {

/// `height` unit boxes (half extent 0.5) in a column at x = 0.
template <class T>
Scene column(World<T>& world, int height = 10) {
    Scene s;
    s.ground = add_ground(world);
    for (int i = 0; i < height; ++i)
        s.bodies.push_back(add_box(world, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(0.5) + T(i), T(0)}));
    s.eye = {7, 0.6 * height, 10};
    s.target = {0, 0.45 * height, 0};
    s.seconds = 2;  // the column stands
    return s;
}

/// A pyramid of unit boxes with `base` boxes in the bottom row: base (base + 1) / 2 boxes.
template <class T>
Scene pyramid(World<T>& world, int base = 20) {
    Scene s;
    s.ground = add_ground(world, T(std::max(50, base)));
    for (int row = 0; row < base; ++row) {
        const int n = base - row;
        for (int j = 0; j < n; ++j) {
            const T x = T(j) - T(n - 1) * T(0.5);
            s.bodies.push_back(add_box(world, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{x, T(0.5) + T(row), T(0)}));
        }
    }
    s.eye = {0.3 * base, 0.55 * base, 1.4 * base};
    s.target = {0, 0.35 * base, 0};
    s.seconds = 3;  // the pyramid settles and stands
    return s;
}

/// A light unit box (density 100 kg/m³) under a box 400 times heavier (same size).
template <class T>
Scene heavy_on_light(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    s.bodies.push_back(add_box(world, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(0.5), T(0)}, Quat<T>::identity(), T(100)));
    s.bodies.push_back(
        add_box(world, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(1.5), T(0)}, Quat<T>::identity(), T(40000)));
    s.eye = {4, 3, 6};
    s.target = {0, 1, 0};
    s.seconds = 2;  // the light box holds the heavy one
    return s;
}

}  // namespace xeno::scenes

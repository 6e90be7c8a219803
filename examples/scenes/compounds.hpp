// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Compound bodies: `compound-stack`, a stack of L-shapes (two boxes each) beside a stack of
// tables (a top and four legs each), every one a single rigid body of several convex parts.
#pragma once

#include "scene.hpp"

#include <memory>

namespace xeno::scenes {

/// A flat L of two boxes, 1 m by 1 m and 0.3 m thick (lying in the x–z plane); re-centred on its
/// centre of mass.
template <class T>
std::shared_ptr<const Compound<T>> l_shape() {
    return std::make_shared<const Compound<T>>(std::vector<CompoundChild<T>>{
        {Box<T>(T(0.5), T(0.15), T(0.15)), {{T(0), T(0), T(0)}, Quat<T>::identity()}},
        {Box<T>(T(0.15), T(0.15), T(0.35)), {{T(-0.35), T(0), T(0.5)}, Quat<T>::identity()}},
    });
}

/// A table: a 1.2 × 0.06 × 0.8 top on four 0.06-thick legs 0.7 long.
template <class T>
std::shared_ptr<const Compound<T>> table() {
    std::vector<CompoundChild<T>> parts{{Box<T>(T(0.6), T(0.03), T(0.4)), {{T(0), T(0.73), T(0)}, Quat<T>::identity()}}};
    for (const T x : {T(-0.52), T(0.52)})
        for (const T z : {T(-0.32), T(0.32)})
            parts.push_back({Box<T>(T(0.03), T(0.35), T(0.03)), {{x, T(0.35), z}, Quat<T>::identity()}});
    return std::make_shared<const Compound<T>>(std::move(parts));
}

/// Four flat L-shapes stacked, and three tables stacked (legs on the top below).
template <class T>
Scene compound_stack(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    const auto l = l_shape<T>();
    const auto t = table<T>();
    // The L's lowest face is 0.15 below its parts' centres.
    const Vec3<T> l_centre_to_bottom = Vec3<T>{T(0), T(0.15), T(0)} + l->shift();
    for (int i = 0; i < 4; ++i) {
        BodyDef<T> d;
        d.position = Vec3<T>{T(-1.5), T(0.3) * T(i), T(0)} + l_centre_to_bottom;
        s.bodies.push_back(world.create_body(l, d));
    }
    for (int i = 0; i < 3; ++i) {
        BodyDef<T> d;
        d.position = Vec3<T>{T(1), T(0.76) * T(i), T(0)} + t->shift();
        s.bodies.push_back(world.create_body(t, d));
    }
    s.eye = {2, 3, 6};
    s.target = {0, 0.9, 0};
    s.seconds = 2;  // the stacks settle and stand
    return s;
}

}  // namespace xeno::scenes

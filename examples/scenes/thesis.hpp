// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The thesis's sample scenarios (3.3.2). 1–6 show each kind of contact between two cubes: a cube
// is dropped from 0.3 m onto a static pedestal cube, turned so that the first touch is
// vertex–vertex, vertex–edge, vertex–face, edge–edge, edge–face or face–face; it then tumbles
// off onto the ground. 7 (`seesaw`): a block on a plank on a rectangular prism on the ground.
// 8 (`dominoes`): a row of dominoes, the first pushed over.
#pragma once

#include "scene.hpp"

namespace xeno::scenes {

/// The six contact kinds, 1 … 6 in the thesis's order.
enum class ContactKind { vertex_vertex = 1, vertex_edge, vertex_face, edge_edge, edge_face, face_face };

namespace detail {
// Orientations of a unit cube that put a corner, an edge or a face lowest (or highest).
template <class T>
Quat<T> corner_down() {
    return Quat<T>::from_to(normalized(Vec3<T>{T(-1), T(-1), T(-1)}), Vec3<T>{T(0), T(-1), T(0)});
}
template <class T>
Quat<T> edge_down(const Vec3<T>& along) {
    return Quat<T>::from_axis_angle(along, ScalarTraits<T>::pi / 4);
}
}  // namespace detail

/// A cube falling onto a static pedestal so that they first touch as `kind` says.
template <class T>
Scene contact_kind(World<T>& world, ContactKind kind) {
    Scene s;
    s.ground = add_ground(world);
    const T corner = std::sqrt(T(0.75)), edge = std::sqrt(T(0.5));
    // The pedestal stands on its lowest feature, static: a face up (top at y = 1), an edge up or
    // a corner up (top at twice its centre height).
    BodyDef<T> pedestal;
    pedestal.type = BodyType::static_body;
    T pedestal_reach = T(0.5);
    switch (kind) {
        case ContactKind::vertex_vertex:
            pedestal.orientation = conjugate(detail::corner_down<T>());
            pedestal_reach = corner;
            break;
        case ContactKind::vertex_edge:
        case ContactKind::edge_edge:
            pedestal.orientation = detail::edge_down<T>(Vec3<T>::unit_z());
            pedestal_reach = edge;
            break;
        default: break;
    }
    pedestal.position = {T(0), pedestal_reach, T(0)};
    world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), pedestal);
    const T top = T(2) * pedestal_reach;
    // The falling cube's lowest feature.
    Quat<T> q = Quat<T>::identity();
    T reach = T(0.5);
    switch (kind) {
        case ContactKind::vertex_vertex:
        case ContactKind::vertex_edge:
        case ContactKind::vertex_face:
            q = detail::corner_down<T>();
            reach = corner;
            break;
        case ContactKind::edge_edge:
        case ContactKind::edge_face:
            q = detail::edge_down<T>(Vec3<T>::unit_x());
            reach = edge;
            break;
        case ContactKind::face_face: break;
    }
    // An offset (and for the tips a slight spin) so the cube does not balance for ever on a tip
    // exactly above the pedestal's centre: it touches as the name says, then tumbles off.
    const Vec3<T> offset = kind == ContactKind::face_face ? Vec3<T>{T(0.45), T(0), T(0.1)} : Vec3<T>{T(0.12), T(0), T(0.06)};
    BodyDef<T> falling;
    falling.position = Vec3<T>{T(0), top + reach + T(0.3), T(0)} + offset;
    falling.orientation = q;
    falling.angular_velocity = kind == ContactKind::face_face ? Vec3<T>{} : Vec3<T>{T(0.3), T(0), T(-0.4)};
    s.bodies.push_back(world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), falling));
    s.eye = {3.5, 2.6, 4.5};
    s.target = {0, 1.2, 0};
    s.seconds = 2.5;  // the fall, the tumble and the rest (1.6–2 s)
    return s;
}

/// Scenario 7: a block on a plank on a rectangular prism on the ground.
template <class T>
Scene seesaw(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    s.bodies.push_back(add_box(world, Vec3<T>{T(0.4), T(0.4), T(0.6)}, Vec3<T>{T(0), T(0.4), T(0)}));  // prism
    s.bodies.push_back(
        add_box(world, Vec3<T>{T(2), T(0.05), T(0.5)}, Vec3<T>{T(0.3), T(0.85), T(0)}, Quat<T>::identity(), T(500)));  // plank
    s.bodies.push_back(add_box(world, Vec3<T>{T(0.25), T(0.25), T(0.25)}, Vec3<T>{T(1.6), T(1.15), T(0)}));            // block
    s.eye = {2, 2.5, 6};
    s.target = {0.3, 0.7, 0};
    s.seconds = 2;  // the seesaw tips and settles (0.9 s)
    return s;
}

/// Scenario 8: `count` dominoes in a row along +x, the first pushed over.
template <class T>
Scene dominoes(World<T>& world, int count = 24) {
    Scene s;
    s.ground = add_ground(world);
    const Vec3<T> half{T(0.05), T(0.5), T(0.25)};
    for (int i = 0; i < count; ++i) {
        BodyDef<T> def;
        def.position = {T(0.5) * T(i), T(0.5), T(0)};
        def.material.friction = T(0.4);
        if (i == 0) def.angular_velocity = {T(0), T(0), T(-2.5)};  // tipped towards +x
        s.bodies.push_back(world.create_body(Box<T>(half), def));
    }
    const double mid = 0.25 * count;  // the row and where its last domino lands
    s.eye = {mid - 2, 4, 0.45 * count + 1.5};
    s.target = {mid, 0.3, 0};
    s.seconds = 0.2 * count + 0.5;  // the chain runs at about 2.5 m/s (24: the last one down at 4.4 s)
    return s;
}

}  // namespace xeno::scenes

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Level geometry: `terrain` (boxes, capsules and a ragdoll tumbling down a hill made of a
// heightfield) and `mesh-bowl` (200 bodies of five convex kinds dropped into a bowl made of a
// triangle mesh). Mesh and heightfield triangles are one-sided: a contact only pushes towards the
// side a triangle's normal points to (counter-clockwise winding, right-hand rule), so the hill's
// triangles face up and the bowl's face up and in, towards what they hold.
#pragma once

#include "features.hpp"
#include "random.hpp"
#include "scene.hpp"

#include <xeno/shape/convex_hull.hpp>
#include <xeno/shape/height_field.hpp>
#include <xeno/shape/triangle_mesh.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace xeno::scenes {

/// user_data that makes draw_world colour a body 0xRRGGBB (world_draw.hpp, body_color).
constexpr std::uint64_t drawn_in(std::uint32_t rgb) { return (std::uint64_t(1) << 24) | rgb; }

/// The hill's surface (m) at (x, z): 5.5 cos²(π r / 32) − 0.3 within r = 16 m of the origin,
/// −0.3 beyond. Its slope, 5.5 π / 32 · sin(π r / 16), is steepest at r = 8 m: 0.54, or 28°.
template <class T>
T hill_height(T x, T z) {
    // The ground box's top (y = 0) carries what runs off the hill, and the renderer draws its floor
    // there. Sunk 0.3 m, the flat margin hides under it instead of fighting it for the same pixels,
    // and the hill comes out of the floor at r = 13.6 m on a 14° slope: a clean edge.
    const T r = std::sqrt(x * x + z * z);
    if (r >= T(16)) return T(-0.3);
    const T c = std::cos(ScalarTraits<T>::pi * r / T(32));
    return T(5.5) * c * c - T(0.3);
}

/// The hill as a static heightfield of 41 × 41 samples 1 m apart, a 40 m square centred on the
/// origin.
template <class T>
BodyId add_hill(World<T>& world) {
    constexpr std::uint32_t n = 41;
    std::vector<T> heights(n * n);
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i) heights[j * n + i] = hill_height(T(i) - T(20), T(j) - T(20));
    BodyDef<T> def;
    def.type = BodyType::static_body;
    // A pair's friction is √(µ_hill µ_body) = √(0.15 · 0.6) = 0.3 for the boxes: they slide where
    // the slope passes atan 0.3 ≈ 17°, from r ≈ 3 m to 13 m, and come to rest near the foot.
    def.material.friction = T(0.15);
    def.user_data = drawn_in(0x8A9A62);  // grass, apart from the grey floor around it
    return world.create_body(HeightField<T>(n, n, std::move(heights), T(1)), def);
}

/// A ragdoll just below the summit and 15 boxes and capsules in two rows across the slope below
/// it, each dropped about a metre onto the hill with a random orientation.
template <class T>
Scene terrain(World<T>& world) {
    // The ragdoll scene brings the ground box around the hill (top at y = 0) and the step the
    // ragdoll lands on in that scene, which here lies buried in the hill under the summit.
    Scene s = ragdoll(world, Vec3<T>{T(2.2), hill_height(T(2.2), T(2.2)) + T(1.6), T(2.2)});
    add_hill(world);
    Random rng(3);
    for (int k = 0; k < 15; ++k) {
        // 7 bodies 20° apart at r = 5.5 m and 8 between them at r = 7.5 m, on the side facing the
        // camera (which looks from 50°, the angle turning from +x towards +z).
        const bool inner = k < 7;
        const T r = inner ? T(5.5) : T(7.5);
        const T a = radians(inner ? T(-15) + T(20) * T(k) : T(-25) + T(20) * T(k - 7));
        BodyDef<T> d;
        d.position = {r * std::cos(a), T(0), r * std::sin(a)};
        d.position.y = hill_height(d.position.x, d.position.z) + T(1.2);
        d.orientation = rng.rotation<T>();
        if (k % 3 == 2) {
            // Capsules roll, and nothing in the solver resists rolling: a little angular damping
            // stops them on the flat instead of at the edge of the world.
            d.angular_damping = T(1);
            s.bodies.push_back(world.create_body(Capsule<T>(T(0.25), T(0.4)), d));
        } else {
            const Vec3<T> half{rng.uniform(T(0.25), T(0.45)), rng.uniform(T(0.25), T(0.45)), rng.uniform(T(0.25), T(0.45))};
            s.bodies.push_back(world.create_body(Box<T>(half), d));
        }
    }
    s.eye = {20, 12, 24};
    s.target = {3, 1.5, 3};
    s.seconds = 8;  // the bodies tumble down the hill and spread over its foot
    return s;
}

/// A bowl y = r² / 12 of rim radius 6 m (3 m deep, 45° steep at the rim) as a polar grid of 24
/// rings by 48 sectors around its bottom: 2,256 triangles.
template <class T>
TriangleMesh<T> bowl_mesh() {
    constexpr std::uint32_t rings = 24, sectors = 48;
    std::vector<Vec3<T>> vertices{Vec3<T>::zero()};  // the bottom, then ring after ring outwards
    for (std::uint32_t i = 1; i <= rings; ++i)
        for (std::uint32_t k = 0; k < sectors; ++k) {
            const T r = T(6) * T(i) / T(rings), a = T(2) * ScalarTraits<T>::pi * T(k) / T(sectors);
            vertices.push_back({r * std::cos(a), r * r / T(12), r * std::sin(a)});
        }
    const auto at = [](std::uint32_t ring, std::uint32_t k) { return 1 + (ring - 1) * sectors + k % sectors; };
    // The angle turns from +x towards +z, clockwise seen from above: counter-clockwise from above
    // (facing up and in) is towards the lower angle, k + 1 before k.
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (std::uint32_t k = 0; k < sectors; ++k) triangles.push_back({0, at(1, k + 1), at(1, k)});
    for (std::uint32_t i = 1; i < rings; ++i)
        for (std::uint32_t k = 0; k < sectors; ++k) {
            triangles.push_back({at(i, k), at(i, k + 1), at(i + 1, k + 1)});
            triangles.push_back({at(i, k), at(i + 1, k + 1), at(i + 1, k)});
        }
    return TriangleMesh<T>(std::move(vertices), triangles);
}

/// 200 bodies, 40 each of rocks (hulls), spheres, capsules, cylinders and boxes, dropped into the
/// bowl from a column of 8 layers of 5 × 5, 1 m apart (no two overlap whatever their turn).
template <class T>
Scene mesh_bowl(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);  // under the bowl, for anything thrown over its rim
    BodyDef<T> bowl;
    bowl.type = BodyType::static_body;
    bowl.user_data = drawn_in(0xC9B28A);  // sand, apart from the grey floor around it
    world.create_body(bowl_mesh<T>(), bowl);
    Random rng(17);
    std::vector<Vec3<T>> rock_points;
    for (int i = 0; i < 24; ++i) rock_points.push_back(hadamard(rng.direction<T>(), Vec3<T>{T(0.35), T(0.25), T(0.3)}));
    const std::shared_ptr<const Shape<T>> kinds[] = {
        std::make_shared<const Shape<T>>(make_convex_hull(rock_points).polyhedron),
        std::make_shared<const Shape<T>>(Sphere<T>(T(0.3))),
        std::make_shared<const Shape<T>>(Capsule<T>(T(0.2), T(0.25))),
        std::make_shared<const Shape<T>>(Cylinder<T>(T(0.3), T(0.25))),
        std::make_shared<const Shape<T>>(Box<T>(T(0.3), T(0.2), T(0.25))),
    };
    for (int i = 0; i < 200; ++i) {
        const int layer = i / 25, row = i / 5 % 5, column = i % 5;
        BodyDef<T> d;
        d.position = {T(column - 2), T(1.5) + T(layer), T(row - 2)};
        d.orientation = rng.rotation<T>();
        s.bodies.push_back(world.create_body(kinds[(column + row + layer) % 5], d));  // every row holds each kind once
    }
    s.eye = {0, 12, 17};
    s.target = {0, 2.5, 0};
    s.seconds = 6;  // the bodies pour in and settle (5 s)
    return s;
}

}  // namespace xeno::scenes

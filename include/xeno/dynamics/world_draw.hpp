// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A world described through DebugDraw: every body as lit triangles with outlined edges (static
// bodies grey, kinematic ones blue, dynamic ones from a fixed palette or the colour in their user
// data, sleeping ones faded), and optionally every contact point with its normal (red points for
// overlapping points, orange for speculative ones; normals from A to B).
#pragma once

#include "../debug_draw.hpp"
#include "world.hpp"

#include <functional>

namespace xeno {

/// What draw_world draws.
template <class T>
struct DrawOptions {
    bool bodies = true;
    bool contacts = false;             ///< contact points and normals
    T normal_length = T(0.3);          ///< metres
    std::function<bool(BodyId)> hide;  ///< bodies for which this returns true are skipped
};

/// The colour of a body: user_data's low 24 bits as 0xRRGGBB when bit 24 is set, else by kind.
template <class T>
Color body_color(BodyId id, const Body<T>& b) {
    if (b.user_data() & (std::uint64_t(1) << 24)) {
        const std::uint64_t rgb = b.user_data() & 0xFFFFFF;
        return {float((rgb >> 16) & 0xFF) / 255.0f, float((rgb >> 8) & 0xFF) / 255.0f, float(rgb & 0xFF) / 255.0f, 1.0f};
    }
    if (b.type() == BodyType::static_body) return {0.55f, 0.55f, 0.58f, 1.0f};
    if (b.type() == BodyType::kinematic) return {0.35f, 0.5f, 0.9f, 1.0f};
    // A palette walked by the golden ratio, so neighbours differ.
    constexpr Color palette[] = {{0.90f, 0.35f, 0.25f, 1}, {0.95f, 0.70f, 0.20f, 1}, {0.35f, 0.70f, 0.35f, 1},
                                 {0.25f, 0.55f, 0.85f, 1}, {0.65f, 0.40f, 0.80f, 1}, {0.20f, 0.75f, 0.75f, 1},
                                 {0.85f, 0.45f, 0.60f, 1}, {0.60f, 0.60f, 0.30f, 1}};
    Color c = palette[(id.index * 5u) % 8u];
    if (!b.awake()) c = {0.25f * c.r + 0.55f, 0.25f * c.g + 0.58f, 0.25f * c.b + 0.68f, 1.0f};  // asleep: pale blue-grey
    return c;
}

/// Every triangle of a mesh or heightfield, filled, front side as wound.
template <class T>
void draw_mesh(DebugDraw<T>& out, const MeshShape<T>& mesh, const Transform<T>& pose, Color fill) {
    for_each_triangle(mesh, local_bounds(mesh), [&](std::uint32_t, const MeshTriangle<T>& t) {
        out.draw_triangle(pose.apply(t.v[0]), pose.apply(t.v[1]), pose.apply(t.v[2]), fill);
    });
}

/// Draws the world into out (see the file comment).
template <class T>
void draw_world(const World<T>& world, DebugDraw<T>& out, const DrawOptions<T>& options = {}) {
    if (options.bodies) {
        world.for_each_body([&](BodyId id, const Body<T>& b) {
            if (!b.enabled() || (options.hide && options.hide(id))) return;  // disabled: out of the world
            const Color fill = body_color(id, b);
            if (const MeshShape<T>* mesh = b.mesh()) draw_mesh(out, *mesh, b.transform(), fill);
            for (std::uint32_t k = 0; k < b.child_count(); ++k)
                draw_shape(out, b.child_shape(k), b.child_transform(k), fill, Color{0.08f, 0.08f, 0.1f, 1.0f});
        });
    }
    if (options.contacts) {
        for (const Contact<T>& c : world.contacts()) {
            const Body<T>& a = world.body(c.a);
            const Body<T>& b = world.body(c.b);
            for (int i = 0; i < c.manifold.count; ++i) {
                const ContactPoint<T>& p = c.manifold.points[static_cast<std::size_t>(i)];
                const Vec3<T> mid = (a.world_point(p.local_a) + b.world_point(p.local_b)) * T(0.5);
                const Color color = p.depth > T(0) ? Color{0.95f, 0.1f, 0.1f, 1} : Color{1.0f, 0.6f, 0.1f, 1};
                out.draw_point(mid, T(0.06), color);
                out.draw_line(mid, mid + c.manifold.normal * options.normal_length, Color{1.0f, 0.9f, 0.2f, 1});
            }
        }
    }
}

namespace f32 {
using DrawOptions = xeno::DrawOptions<float>;
}
namespace f64 {
using DrawOptions = xeno::DrawOptions<double>;
}

}  // namespace xeno

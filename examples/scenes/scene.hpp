// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// What a scene function returns: the bodies a test or a renderer cares about and a suggested
// camera. Scenes are shared by the renderer, the tests and the benchmarks (docs/style.md,
// "Tests and scenes"), so what is drawn is what is tested.
#pragma once

#include <xeno/dynamics/world.hpp>

#include <functional>
#include <string>
#include <vector>

namespace xeno::scenes {

/// Bodies of interest, a suggested view (camera position and target, metres) and length.
struct Scene {
    std::vector<BodyId> bodies;  ///< the scene's dynamic bodies, in creation order
    BodyId ground;               ///< the static ground, if any (renderers draw their own floor)
    f64::Vec3 eye{8, 5, 12};
    f64::Vec3 target{0, 1, 0};
    /// How long the scene's story takes (s): what a viewer should see, e.g. the dominoes to the
    /// last one, the pyramid settled, the ragdoll at rest. The renderer's and the page's default
    /// length.
    double seconds = 3;
    /// For scenes that drive bodies themselves (the character): called before every step with
    /// the step's length (s). Programs that step scenes call it when it is set.
    std::function<void(double)> before_step;
};

/// A static ground box whose top face is the plane y = 0.
template <class T>
BodyId add_ground(World<T>& world, T half_size = T(50), T friction = T(0.6)) {
    BodyDef<T> def;
    def.type = BodyType::static_body;
    def.position = {T(0), T(-0.5), T(0)};
    def.material.friction = friction;
    return world.create_body(Box<T>(half_size, T(0.5), half_size), def);
}

/// A dynamic box of the given half extents at a position (density 1000 kg/m³ unless given).
template <class T>
BodyId add_box(World<T>& world, const Vec3<T>& half_extents, const Vec3<T>& position,
               const Quat<T>& orientation = Quat<T>::identity(), T density = T(1000)) {
    BodyDef<T> def;
    def.position = position;
    def.orientation = orientation;
    def.density = density;
    return world.create_body(Box<T>(half_extents), def);
}

}  // namespace xeno::scenes

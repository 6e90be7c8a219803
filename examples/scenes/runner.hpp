// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// One scene running in one precision: its world, how it advances (fixed steps of the world's
// fixed_time_step, with the scene's before_step hook when it has one) and how it is drawn
// (draw_world, plus the ray fan's rays). The off-screen renderer and the browser page both run
// scenes through it, so they show the same simulation and the same geometry.
#pragma once

#include "all.hpp"

#include <xeno/dynamics/world_draw.hpp>

#include <optional>
#include <string>

namespace xeno::scenes {

template <class T>
class Runner {
public:
    /// Builds the named scene (an unknown name is an InvalidArgument), in a world with `settings`.
    explicit Runner(const std::string& name, const WorldSettings<T>& settings = {})
        : world_(settings), scene_(build(name, world_)), rays_(name == "ray-fan") {}
    Runner(const Runner&) = delete;  // the scene's hook holds a reference to the world
    Runner& operator=(const Runner&) = delete;

    World<T>& world() { return world_; }
    const World<T>& world() const { return world_; }
    const Scene& scene() const { return scene_; }

    /// Advances by `seconds` of simulated time in fixed steps (World::update's accumulator, or
    /// the same accumulator here when the scene's hook must run before every step).
    void advance(double seconds) {
        if (!scene_.before_step) {
            world_.update(static_cast<T>(seconds));
            return;
        }
        const double dt = static_cast<double>(world_.settings().fixed_time_step);
        for (pending_ += seconds; pending_ >= dt * (1 - 1e-9); pending_ -= dt) step();
    }

    /// Exactly one fixed step.
    void step() {
        const double dt = static_cast<double>(world_.settings().fixed_time_step);
        if (scene_.before_step) scene_.before_step(dt);
        world_.step(static_cast<T>(dt));
    }

    /// The bodies (the ground too unless hidden), contacts if asked, and the ray fan's rays to
    /// their first hits with the hits' normals.
    void draw(DebugDraw<T>& out, bool contacts, bool ground) const {
        DrawOptions<T> options;
        options.contacts = contacts;
        const BodyId hidden = scene_.ground;
        if (!ground) options.hide = [hidden](BodyId id) { return id == hidden; };
        draw_world(world_, out, options);
        if (!rays_) return;
        for (const Ray<T>& ray : ray_fan_rays<T>()) {
            const std::optional<WorldRayHit<T>> hit = world_.raycast(ray);
            const Vec3<T> end = hit ? hit->hit.point : ray.origin + ray.direction * ray.max_distance;
            out.draw_line(ray.origin, end, hit ? Color{1.0f, 0.85f, 0.1f, 1} : Color{0.6f, 0.6f, 0.7f, 1});
            if (hit) {
                out.draw_point(end, T(0.08), Color{0.95f, 0.2f, 0.1f, 1});
                out.draw_line(end, end + hit->hit.normal * T(0.4), Color{0.2f, 0.9f, 0.3f, 1});
            }
        }
    }

private:
    World<T> world_;
    Scene scene_;
    bool rays_;
    double pending_ = 0;  ///< seconds owed to a scene with a before_step hook
};

}  // namespace xeno::scenes

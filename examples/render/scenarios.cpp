// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_render's scenario registry: every scene of examples/scenes/all.hpp as a Simulation in float
// or double. The world advances with World::update (fixed 1/60 s steps from an accumulator) and is
// drawn through DrawAdapter, so the frames show exactly what the tests simulate.
#include "render/scenario.hpp"

#include "scenes/all.hpp"

#include <xeno/dynamics/world_draw.hpp>

namespace xeno::render {

namespace {

template <class T>
class WorldSimulation final : public Simulation {
public:
    explicit WorldSimulation(const std::string& name) : scene_(scenes::build(name, world_)), rays_(name == "ray-fan") {}

    void step(double seconds) override {
        if (!scene_.before_step) {
            world_.update(static_cast<T>(seconds));
            return;
        }
        // A scene that drives bodies (the character) runs its hook before every fixed step.
        const double dt = static_cast<double>(world_.settings().fixed_time_step);
        for (pending_ += seconds; pending_ >= dt * (1 - 1e-9); pending_ -= dt) {
            scene_.before_step(dt);
            world_.step(static_cast<T>(dt));
        }
    }

    void draw(Renderer& out, bool contacts) const override {
        DrawAdapter<T> adapter(out);
        DrawOptions<T> options;
        options.contacts = contacts;
        const BodyId ground = scene_.ground;
        options.hide = [ground](BodyId id) { return id == ground; };  // the renderer draws its own floor
        draw_world(world_, adapter, options);
        if (rays_) {  // the ray-fan scene: each ray to its first hit, and the hit's normal
            for (const Ray<T>& ray : scenes::ray_fan_rays<T>()) {
                const std::optional<WorldRayHit<T>> hit = world_.raycast(ray);
                const Vec3<T> end = hit ? hit->hit.point : ray.origin + ray.direction * ray.max_distance;
                adapter.draw_line(ray.origin, end, hit ? Color{1.0f, 0.85f, 0.1f, 1} : Color{0.6f, 0.6f, 0.7f, 1});
                if (hit) {
                    adapter.draw_point(end, T(0.08), Color{0.95f, 0.2f, 0.1f, 1});
                    adapter.draw_line(end, end + hit->hit.normal * T(0.4), Color{0.2f, 0.9f, 0.3f, 1});
                }
            }
        }
    }

    std::vector<BodyState> states() const override {
        std::vector<BodyState> out;
        int index = 0;
        world_.for_each_body([&](BodyId id, const Body<T>& b) {
            if (id == scene_.ground) return;
            const Vec3<T>& p = b.position();
            const Quat<T>& q = b.orientation();
            out.push_back({index++, double(p.x), double(p.y), double(p.z), double(q.w), double(q.x), double(q.y), double(q.z)});
        });
        return out;
    }

    Camera camera() const override {
        Camera c;
        c.position = scene_.eye;
        c.target = scene_.target;
        return c;
    }

private:
    World<T> world_;
    scenes::Scene scene_;
    bool rays_;
    double pending_ = 0;  ///< seconds of simulation owed to a scene with a before_step hook
};

}  // namespace

const std::vector<Scenario>& scenarios() {
    static const std::vector<Scenario> list = [] {
        std::vector<Scenario> out;
        for (const auto& [name, description] : scenes::scene_list()) {
            const std::string n = name;
            out.push_back({n, description, [n](bool use_float) -> std::unique_ptr<Simulation> {
                               if (use_float) return std::make_unique<WorldSimulation<float>>(n);
                               return std::make_unique<WorldSimulation<double>>(n);
                           }});
        }
        return out;
    }();
    return list;
}

}  // namespace xeno::render

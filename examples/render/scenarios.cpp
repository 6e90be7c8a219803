// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_render's scenario registry: every scene of examples/scenes/all.hpp as a Simulation in float
// or double, run by scenes::Runner (fixed 1/60 s steps from an accumulator) and drawn through
// DrawAdapter, so the frames show exactly what the tests simulate.
#include "render/scenario.hpp"

#include "scenes/runner.hpp"

namespace xeno::render {

namespace {

template <class T>
class WorldSimulation final : public Simulation {
public:
    explicit WorldSimulation(const std::string& name) : run_(name) {}

    void step(double seconds) override { run_.advance(seconds); }

    void draw(Renderer& out, bool contacts) const override {
        DrawAdapter<T> adapter(out);
        run_.draw(adapter, contacts, false);  // the renderer draws its own floor
    }

    std::vector<BodyState> states() const override {
        std::vector<BodyState> out;
        int index = 0;
        run_.world().for_each_body([&](BodyId id, const Body<T>& b) {
            if (id == run_.scene().ground) return;
            const Vec3<T>& p = b.position();
            const Quat<T>& q = b.orientation();
            out.push_back({index++, double(p.x), double(p.y), double(p.z), double(q.w), double(q.x), double(q.y), double(q.z)});
        });
        return out;
    }

    double seconds() const override { return run_.scene().seconds; }

    Camera camera() const override {
        Camera c;
        c.position = run_.scene().eye;
        c.target = run_.scene().target;
        return c;
    }

private:
    scenes::Runner<T> run_;
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

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A TEMPORARY scenario registry for xeno_render: kinematic demos (poses integrated from fixed
// angular velocities, no physics) that exercise the renderer, draw_shape and the command line
// end to end. scenarios.cpp with the real scenarios replaces this file
// (XENO_RENDER_SCENARIO_SOURCES in examples/CMakeLists.txt).
#include "render/scenario.hpp"

#include <xeno/debug_draw.hpp>
#include <xeno/shape/polyhedra.hpp>

namespace xeno::render {

namespace {

/// Shapes that turn in place at constant angular velocity; "contacts" are their lowest points.
template <class T>
class KinematicDemo : public Simulation {
public:
    struct Item {
        Shape<T> shape;
        Transform<T> pose;
        Vec3<T> omega;  ///< rad/s, world frame
        Color fill;
    };

    KinematicDemo(std::vector<Item> items, Camera view) : items_(std::move(items)), camera_(view) {}

    void step(double seconds) override {
        for (Item& item : items_) item.pose.orientation = integrate(item.pose.orientation, item.omega, static_cast<T>(seconds));
    }

    void draw(Renderer& out, bool contacts) const override {
        DrawAdapter<T> adapter(out);
        const Color edge{0.08f, 0.08f, 0.1f, 1};
        for (const Item& item : items_) {
            draw_shape(adapter, item.shape, item.pose, item.fill, edge);
            if (contacts) {
                // The shape's lowest point stands in for a contact with the ground; normal up.
                const Vec3<T> local = support(item.shape, item.pose.inverse_apply_direction(-Vec3<T>::unit_y()));
                const Vec3<T> p = item.pose.apply(local);
                adapter.draw_point(p, T(0.1), Color{1, 0.85f, 0.1f, 1});
                adapter.draw_line(p, p + Vec3<T>::unit_y() * T(0.5), Color{1, 0.85f, 0.1f, 1});
            }
        }
    }

    std::vector<BodyState> states() const override {
        std::vector<BodyState> out;
        for (std::size_t i = 0; i < items_.size(); ++i) {
            const Transform<T>& t = items_[i].pose;
            out.push_back({static_cast<int>(i), double(t.position.x), double(t.position.y), double(t.position.z),
                           double(t.orientation.w), double(t.orientation.x), double(t.orientation.y), double(t.orientation.z)});
        }
        return out;
    }

    Camera camera() const override { return camera_; }

private:
    std::vector<Item> items_;
    Camera camera_;
};

const Color red{0.85f, 0.22f, 0.18f, 1}, green{0.3f, 0.72f, 0.35f, 1}, blue{0.25f, 0.45f, 0.85f, 1},
    orange{0.95f, 0.6f, 0.2f, 1}, purple{0.6f, 0.35f, 0.75f, 1}, teal{0.2f, 0.7f, 0.7f, 1}, grey{0.75f, 0.75f, 0.72f, 1};

template <class T>
Transform<T> at(T x, T y, T z) {
    return {{x, y, z}, Quat<T>::identity()};
}

template <class T>
std::unique_ptr<Simulation> make_spin() {
    using Item = typename KinematicDemo<T>::Item;
    std::vector<Item> items;
    items.push_back({Box<T>(T(0.5), T(0.5), T(0.5)), at(T(-1.6), T(0.5), T(0)), {T(0), T(1.2), T(0)}, red});
    items.push_back({Sphere<T>(T(0.5)), at(T(0), T(0.5), T(0)), {T(0), T(0), T(-2)}, blue});
    items.push_back({Cone<T>(T(0.5), T(1.2)), at(T(1.6), T(0.3), T(0)), {T(0), T(-1.5), T(0)}, green});
    Camera view;
    view.position = {1.5, 2.8, 6};
    view.target = {0, 0.5, 0};
    return std::make_unique<KinematicDemo<T>>(std::move(items), view);
}

template <class T>
std::unique_ptr<Simulation> make_shapes() {
    using Item = typename KinematicDemo<T>::Item;
    const Vec3<T> spin{T(0), T(0.8), T(0)};
    std::vector<Item> items;
    items.push_back({Sphere<T>(T(0.5)), at(T(-4.5), T(0.5), T(0)), {T(0.8), T(0), T(0)}, blue});
    items.push_back({Box<T>(T(0.5), T(0.4), T(0.3)), at(T(-3), T(0.4), T(0)), spin, red});
    items.push_back({Capsule<T>(T(0.35), T(0.4)), at(T(-1.5), T(0.75), T(0)), spin, orange});
    items.push_back({Cylinder<T>(T(0.45), T(0.5)), at(T(0), T(0.5), T(0)), spin, green});
    items.push_back({Cone<T>(T(0.5), T(1.2)), at(T(1.5), T(0.3), T(0)), spin, purple});
    const ConvexPolyhedron<T> tetra = make_tetrahedron<T>(T(1.1));
    const T tetra_lift = -tetra.local_bounds().min.y;
    items.push_back({tetra, at(T(3), tetra_lift, T(0)), spin, teal});
    items.push_back({make_regular_prism<T>(6, T(0.5), T(0.35)), at(T(4.5), T(0.35), T(0)), spin, grey});
    Camera view;
    view.position = {0, 3.5, 9.5};
    view.target = {0, 0.5, 0};
    return std::make_unique<KinematicDemo<T>>(std::move(items), view);
}

}  // namespace

const std::vector<Scenario>& scenarios() {
    static const std::vector<Scenario> registry{
        {"demo-spin", "kinematic demo: a box, a sphere and a cone turning in place on the ground",
         [](bool use_float) { return use_float ? make_spin<float>() : make_spin<double>(); }},
        {"demo-shapes", "kinematic demo: every shape type side by side, slowly turning",
         [](bool use_float) { return use_float ? make_shapes<float>() : make_shapes<double>(); }},
    };
    return registry;
}

}  // namespace xeno::render

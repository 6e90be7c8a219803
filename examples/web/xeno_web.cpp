// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The browser page's side of the scenarios (examples/web/, docs/web.md): a C interface over
// scenes::Runner that index.html calls through WebAssembly. One scene runs in float, in double or
// in both side by side (two worlds stepped together); each world is drawn through the library's
// DebugDraw into flat vertex arrays the page hands to WebGL as they are. Compiled natively too,
// by the CTest smoke test web_api_test.cpp, so the interface is checked by every build.
#include "web/xeno_web.h"

#include "scenes/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace xeno;

/// Triangles as (position, normal, colour) and lines as (position, colour), float per value:
/// the page's vertex layouts. A point is a small octahedron of triangles.
template <class T>
class ArrayDraw final : public DebugDraw<T> {
public:
    std::vector<float> triangles, lines;

    void draw_triangle(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, Color color) override {
        const Vec3<T> n = normalized_or(cross(b - a, c - a), Vec3<T>{T(0), T(1), T(0)});
        for (const Vec3<T>* p : {&a, &b, &c})
            push(triangles,
                 {float(p->x), float(p->y), float(p->z), float(n.x), float(n.y), float(n.z), color.r, color.g, color.b, color.a});
    }
    void draw_line(const Vec3<T>& a, const Vec3<T>& b, Color color) override {
        for (const Vec3<T>* p : {&a, &b})
            push(lines, {float(p->x), float(p->y), float(p->z), color.r, color.g, color.b, color.a});
    }
    void draw_point(const Vec3<T>& p, T size, Color color) override {
        const T r = size * T(0.5);
        const Vec3<T> x{r, T(0), T(0)}, y{T(0), r, T(0)}, z{T(0), T(0), r};
        for (int sx = -1; sx <= 1; sx += 2)
            for (int sy = -1; sy <= 1; sy += 2)
                for (int sz = -1; sz <= 1; sz += 2) {
                    const Vec3<T> a = p + x * T(sx), b = p + y * T(sy), c = p + z * T(sz);
                    if (sx * sy * sz > 0) draw_triangle(a, b, c, color);  // counter-clockwise from outside
                    else draw_triangle(a, c, b, color);
                }
    }

private:
    static void push(std::vector<float>& out, std::initializer_list<float> values) { out.insert(out.end(), values); }
};

/// A body held by the mouse: a kinematic sensor sphere at the pointer, ball-jointed to the body.
struct Grab {
    BodyId body, anchor;
    JointId joint;
};

template <class T>
struct Side {
    std::unique_ptr<scenes::Runner<T>> run;
    std::optional<Grab> grab;
    Vec3<T> grab_target{};
    ArrayDraw<T> draw;
};

struct Page {
    int scene = -1;
    int precision = 1;  // 0 float, 1 double, 2 both
    Side<float> f32;
    Side<double> f64;
    double step_ms = 0;  // the last xw_step's mean, per step of every world stepped
    double steps = 0;    // a count exact to 2^53: an int overflowed after 3.6 million calls of 600
    std::string error;
    std::vector<float> empty;
};

Page page;

/// The most steps one xw_step or xw_benchmark call takes (10 s of scene time): the module runs on
/// the page's thread, so a call without a cap could hold the tab for hours.
constexpr int max_steps_per_call = 600;

/// The largest coordinate (m) a pick's origin or a drag's target may have, in every precision so
/// float, double and both accept the same calls: the float world's largest size. Beyond it a
/// double converts to inf in float, or the grab's velocity (distance × 60 /s) overflows.
constexpr double max_coordinate = xeno::ScalarTraits<float>::max_size;

bool within_page(double x, double y, double z) {
    // Written so NaN fails too.
    return std::abs(x) <= max_coordinate && std::abs(y) <= max_coordinate && std::abs(z) <= max_coordinate;
}

/// The unit vector along d, or nothing when d is zero or not finite. Scaled to its largest
/// component first: |d|² of a finite d can overflow (1e200) or be subnormal (1e-161), and the
/// quotient then is no unit vector, which World::raycast throws on.
std::optional<Vec3<double>> unit(const Vec3<double>& d) {
    const double largest = max_component(abs(d));
    if (!is_finite(d) || !(largest > 0)) return std::nullopt;
    return try_normalized(d / largest);
}

template <class T>
void release(Side<T>& side) {
    if (!side.grab || !side.run) return;
    World<T>& w = side.run->world();
    w.destroy_body(side.grab->anchor);  // and with it the joint
    side.grab.reset();
}

template <class T>
void grab(Side<T>& side, BodyId body, const Vec3<double>& point) {
    release(side);
    World<T>& w = side.run->world();
    if (!w.contains(body) || w.body(body).type() != BodyType::dynamic) return;
    BodyDef<T> def;
    def.type = BodyType::kinematic;
    def.position = Vec3<T>(point);
    def.sensor = true;  // pushes nothing, only holds the joint
    const BodyId anchor = w.create_body(Sphere<T>(T(0.05)), def);
    const JointId joint = w.create_joint(JointDef<T>::ball(anchor, body, Vec3<T>(point)));
    w.set_awake(body, true);
    side.grab = Grab{body, anchor, joint};
    side.grab_target = Vec3<T>(point);
}

template <class T>
void step(Side<T>& side) {
    if (!side.run) return;
    if (side.grab) {
        World<T>& w = side.run->world();
        const T dt = w.settings().fixed_time_step;
        w.move_kinematic(side.grab->anchor, side.grab_target, Quat<T>::identity(), dt);
    }
    side.run->step();
}

template <class T>
int count(const Side<T>& side, int what) {
    if (!side.run) return 0;
    const World<T>& w = side.run->world();
    if (what == 0) {
        int n = 0;
        w.for_each_body([&](BodyId, const Body<T>& b) { n += b.type() == BodyType::dynamic ? 1 : 0; });
        return n;
    }
    const StepStats& s = w.last_step_stats();
    return static_cast<int>(what == 1 ? s.contacts : s.awake_bodies);
}

/// ms per step of `steps` steps of a scene in a world of its own, sleeping off so every step
/// does the same work (a resting pyramid would otherwise sleep after half a second).
template <class T>
double time_steps(const std::string& name, int steps) {
    xeno::WorldSettings<T> settings;
    settings.allow_sleeping = false;
    xeno::scenes::Runner<T> run(name, settings);
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < steps; ++i) run.step();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / steps;
}

bool shows_float() { return page.precision == 0 || page.precision == 2; }
bool shows_double() { return page.precision >= 1; }

}  // namespace

extern "C" {

int xw_scene_count() { return static_cast<int>(xeno::scenes::scene_list().size()); }

const char* xw_scene_name(int i) {
    if (i < 0 || i >= xw_scene_count()) return "";
    return xeno::scenes::scene_list()[static_cast<std::size_t>(i)].first.c_str();
}

const char* xw_scene_description(int i) {
    if (i < 0 || i >= xw_scene_count()) return "";
    return xeno::scenes::scene_list()[static_cast<std::size_t>(i)].second.c_str();
}

int xw_load(int scene, int precision) {
    if (scene < 0 || scene >= xw_scene_count() || precision < 0 || precision > 2) return -1;
    const std::string& name = xeno::scenes::scene_list()[static_cast<std::size_t>(scene)].first;
    release(page.f32);
    release(page.f64);
    page.f32.run.reset();
    page.f64.run.reset();
    try {
        page.scene = scene;
        page.precision = precision;
        if (shows_float()) page.f32.run = std::make_unique<xeno::scenes::Runner<float>>(name);
        if (shows_double()) page.f64.run = std::make_unique<xeno::scenes::Runner<double>>(name);
    } catch (const std::exception& e) {
        page.error = e.what();
        return -1;
    }
    page.steps = 0;
    page.step_ms = 0;
    return 0;
}

void xw_step(int n) {
    n = std::clamp(n, 0, max_steps_per_call);
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) {
        step(page.f32);
        step(page.f64);
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const int worlds = (page.f32.run ? 1 : 0) + (page.f64.run ? 1 : 0);
    if (n > 0 && worlds > 0) page.step_ms = ms / (n * worlds);
    page.steps += n;
}

double xw_step_ms() { return page.step_ms; }
double xw_time() { return page.steps / 60.0; }

int xw_draw(int precision, int contacts) {
    const bool c = contacts != 0;
    if (precision == 0 && page.f32.run) {
        page.f32.draw = {};
        page.f32.run->draw(page.f32.draw, c, true);
        return static_cast<int>(page.f32.draw.triangles.size() / 10);
    }
    if (precision == 1 && page.f64.run) {
        page.f64.draw = {};
        page.f64.run->draw(page.f64.draw, c, true);
        return static_cast<int>(page.f64.draw.triangles.size() / 10);
    }
    return 0;
}

float* xw_triangles(int precision) {
    std::vector<float>& v = precision == 0 ? page.f32.draw.triangles : precision == 1 ? page.f64.draw.triangles : page.empty;
    return v.data();
}

int xw_line_vertices(int precision) {
    if (precision == 0) return static_cast<int>(page.f32.draw.lines.size() / 7);
    if (precision == 1) return static_cast<int>(page.f64.draw.lines.size() / 7);
    return 0;
}

float* xw_lines(int precision) {
    std::vector<float>& v = precision == 0 ? page.f32.draw.lines : precision == 1 ? page.f64.draw.lines : page.empty;
    return v.data();
}

int xw_stat(int precision, int what) {
    if (what < 0 || what > 2) return 0;
    if (precision == 0) return count(page.f32, what);
    if (precision == 1) return count(page.f64, what);
    return 0;
}

double xw_max_difference() {
    if (!page.f32.run || !page.f64.run) return 0;
    double most = 0;
    const xeno::World<float>& wf = page.f32.run->world();
    page.f64.run->world().for_each_body([&](xeno::BodyId id, const xeno::Body<double>& b) {
        if (!wf.contains(id) || b.type() != xeno::BodyType::dynamic) return;
        most = std::max(most, xeno::length(xeno::Vec3<double>(wf.body(id).position()) - b.position()));
    });
    return most;
}

double xw_camera(int k) {
    const xeno::scenes::Scene* s = page.f64.run ? &page.f64.run->scene() : page.f32.run ? &page.f32.run->scene() : nullptr;
    if (!s || k < 0 || k > 6) return 0;
    if (k < 3) return s->eye[k];
    if (k < 6) return s->target[k - 3];
    return s->seconds;
}

int xw_pick(double ox, double oy, double oz, double dx, double dy, double dz) {
    const std::optional<xeno::Vec3<double>> direction = unit({dx, dy, dz});
    if (!within_page(ox, oy, oz) || !direction) return 0;
    const xeno::Ray<double> ray{{ox, oy, oz}, *direction, 1000.0};
    std::optional<xeno::BodyId> body;
    xeno::Vec3<double> point;
    if (page.f64.run) {
        if (const auto hit = page.f64.run->world().raycast(ray)) body = hit->body, point = hit->hit.point;
    } else if (page.f32.run) {
        const xeno::Ray<float> r{xeno::Vec3<float>(ray.origin), xeno::Vec3<float>(ray.direction), 1000.0f};
        if (const auto hit = page.f32.run->world().raycast(r)) body = hit->body, point = xeno::Vec3<double>(hit->hit.point);
    }
    if (!body) return 0;
    if (page.f32.run) grab(page.f32, *body, point);
    if (page.f64.run) grab(page.f64, *body, point);
    return page.f32.grab || page.f64.grab ? 1 : 0;
}

double xw_grab_point(int k) {
    if (k < 0 || k > 2) return 0;
    if (page.f64.grab) return page.f64.grab_target[k];
    if (page.f32.grab) return double(page.f32.grab_target[k]);
    return 0;
}

void xw_drag(double x, double y, double z) {
    if (!within_page(x, y, z)) return;
    page.f32.grab_target = xeno::Vec3<float>(xeno::Vec3<double>{x, y, z});
    page.f64.grab_target = {x, y, z};
}

void xw_release() {
    release(page.f32);
    release(page.f64);
}

int xw_grabbed_body() {
    if (page.f64.grab) return static_cast<int>(page.f64.grab->body.index);
    if (page.f32.grab) return static_cast<int>(page.f32.grab->body.index);
    return -1;
}

double xw_body_position(int precision, int index, int k) {
    double out = 0;
    const auto find = [&](const auto& world) {
        world.for_each_body([&](xeno::BodyId id, const auto& b) {
            if (static_cast<int>(id.index) == index && k >= 0 && k < 3) out = double(b.position()[k]);
        });
    };
    if (precision == 0 && page.f32.run) find(page.f32.run->world());
    if (precision == 1 && page.f64.run) find(page.f64.run->world());
    return out;
}

double xw_benchmark(int scene, int precision, int steps) {
    if (scene < 0 || scene >= xw_scene_count() || precision < 0 || precision > 1 || steps <= 0 || steps > max_steps_per_call)
        return -1;
    const std::string& name = xeno::scenes::scene_list()[static_cast<std::size_t>(scene)].first;
    return precision == 0 ? time_steps<float>(name, steps) : time_steps<double>(name, steps);
}

const char* xw_error() { return page.error.c_str(); }

}  // extern "C"

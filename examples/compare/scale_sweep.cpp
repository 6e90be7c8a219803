// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_scale_sweep: where each build (float, double) stops being stable when a scene leaves the
// 0.1–10 m, equal-mass, near-the-origin range the solver's defaults are tuned for
// (docs/conventions.md, "Contacts"). Every case runs in float and in double with the default
// settings but sleeping off (a sleeping body cannot creep, which would hide the very thing
// measured), at 60 Hz:
//   size      a cube of edge s (1 mm … 1 km) on a unit cube on the ground, 5 s; once with the same
//             mass as the unit cube (the size ratio alone), once with the same density (mass ratio
//             s³ as well). Stable: finite; the unit cube moved less than 1 cm; the cube's centre
//             still above the unit cube (not fallen off) and less than s/2 below where it was
//             placed (not sunk through); its creep between t = 1 s and the end under 1 % of s or
//             1 mm, whichever is larger.
//   mass      a unit cube on a unit cube, density ratio r (top : bottom) from 1 to 10⁴, and the
//             inverse, 5 s. Stable: finite; deepest overlap after 1 s under 3 % of the cube; at rest
//             over the last second (no point faster than 1 mm/s, kinetic energy below 10⁻⁶ of
//             m g × 1 m); the top cube still on top.
//   distance  a column of 10 unit cubes on a ground box, all moved by d along x, 10 s (the scene of
//             tests/dynamics/stacking_slow_test.cpp). Stable: creep of any cube between t = 1 s and
//             the end, and sag of the top cube below where it was placed, under 1 cm.
//   slide     a unit cube sliding at 4 m/s along +x from x = d, friction 0.6: v²/(2µg) = 1.36 m.
//             Right: within 1 cm of the same slide at the origin in double (the solver's own
//             error against the closed form is not the question here).
//   glide     a unit cube gliding at 1 cm/s on frictionless ground from x = d, 5 s: 5 cm, i.e.
//             0.17 mm per step. Right: within 1 % of 5 cm. Positions are rounded once per step, so
//             a move below half a float ulp at d (1 mm at 10⁴ m) is lost.
// An input the library rejects counts as unstable, naming the function. Prints a table per sweep
// (--markdown: again in markdown, for docs/precision.md) and writes DIR/sweep/<sweep>.csv.
#include "scenes/scene.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace xeno;

const char* const usage =
    "usage: xeno_scale_sweep [options]\n"
    "Sweeps size ratio, mass ratio and distance from the origin in float and in double and reports\n"
    "where each build stops being stable.\n"
    "  --out DIR     output folder (default out): writes DIR/sweep/{size,mass,distance,slide}.csv\n"
    "  --markdown    also print the tables in markdown\n"
    "  --help        this text\n";

/// The outcome of one case in one build.
struct Cell {
    bool stable = true;
    std::string why;                                      ///< the first criterion that failed; empty when stable
    std::string shown;                                    ///< the measured numbers as the table shows them
    std::vector<std::pair<std::string, double>> numbers;  ///< every measured number, for the CSV

    void fail(const std::string& reason) {
        if (stable) why = reason;
        stable = false;
    }
    /// "stable, creep 0.5 mm" or "UNSTABLE (creeps), creep 12 mm", in the sweep's words.
    std::string text(const std::string& good, const std::string& bad) const {
        std::string upper = bad;
        for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
        return (stable ? good : upper + " (" + why + ")") + (shown.empty() ? "" : ", " + shown);
    }
    std::string markdown(const std::string& good, const std::string& bad) const {
        return (stable ? good : "**" + bad + "** (" + why + ")") + (shown.empty() ? "" : ", " + shown);
    }
};

/// One row of a sweep: the swept value and the two builds.
struct Row {
    std::string value;  ///< as shown
    double number;      ///< as written to the CSV
    Cell f, d;
};

struct Sweep {
    std::string name, title, column;
    std::vector<Row> rows;
    std::string good = "stable", bad = "unstable";  ///< the verdict words (slides are right or wrong)
};

template <class T>
WorldSettings<T> awake_settings() {
    WorldSettings<T> s;
    s.allow_sleeping = false;
    return s;
}

/// Steps `seconds` at the settings' fixed step; after each step calls each(step, time).
template <class T>
void simulate(World<T>& w, double seconds, const std::function<void(int, double)>& each) {
    const T dt = w.settings().fixed_time_step;
    const int steps = static_cast<int>(std::lround(seconds / static_cast<double>(dt)));
    for (int k = 1; k <= steps; ++k) {
        w.step(dt);
        each(k, k * static_cast<double>(dt));
    }
}

template <class T>
Vec3<double> position(const World<T>& w, BodyId id) {
    return Vec3<double>(w.body(id).position());
}

template <class T>
bool all_finite(const World<T>& w) {
    bool ok = true;
    w.for_each_body([&](BodyId, const Body<T>& b) {
        ok = ok && is_finite(b.position()) && is_finite(b.orientation()) && is_finite(b.linear_velocity()) &&
             is_finite(b.angular_velocity());
    });
    return ok;
}

template <class T>
double deepest_contact(const World<T>& w) {
    double deepest = 0;
    for (const Contact<T>& c : w.contacts())
        for (int i = 0; i < c.manifold.count; ++i)
            deepest = std::max(deepest, static_cast<double>(c.manifold.points[static_cast<std::size_t>(i)].depth));
    return deepest;
}

/// The fastest speed (m/s) of any body's point: |v| + |ω| r with r the shape's bounding radius.
template <class T>
double fastest_point(const World<T>& w) {
    double fastest = 0;
    w.for_each_body([&](BodyId, const Body<T>& b) {
        fastest = std::max(fastest, static_cast<double>(length(b.linear_velocity()) +
                                                        length(b.angular_velocity()) * bounding_radius(b.shape())));
    });
    return fastest;
}

template <class T>
double kinetic_energy(const World<T>& w) {
    double e = 0;
    w.for_each_body([&](BodyId, const Body<T>& b) { e += static_cast<double>(b.kinetic_energy()); });
    return e;
}

std::string format(const char* f, double a) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, f, a);
    return buffer;
}
std::string format(const char* f, double a, double b) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, f, a, b);
    return buffer;
}

/// A length in millimetres, as many digits as it deserves: "480 mm", "2.8 mm", "3.1e-05 mm".
std::string mm(double metres) {
    const double v = metres * 1e3, a = std::abs(v);
    if (a == 0) return "0 mm";
    return format(a >= 1000 ? "%.0f mm" : (a >= 0.01 ? "%.3g mm" : "%.1e mm"), v);
}

/// A static ground box whose top face is y = 0, centred at x.
template <class T>
BodyId add_ground_at(World<T>& w, T x, T half_size) {
    BodyDef<T> def;
    def.type = BodyType::static_body;
    def.position = {x, T(-0.5), T(0)};
    return w.create_body(Box<T>(half_size, T(0.5), half_size), def);
}

// Sweep 1: a cube of edge `edge` on a unit cube on the ground, of the same mass (1000 kg) or of
// the same density (so also a mass ratio of edge³).
template <class T>
Cell size_case(double edge, bool same_mass) {
    World<T> w(awake_settings<T>());
    add_ground_at(w, T(0), T(std::max(50.0, 2.0 * edge)));
    const BodyId bottom = scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{T(0), T(0.5), T(0)});
    const T h = static_cast<T>(edge / 2);
    const T density = same_mass ? static_cast<T>(1000.0 / (edge * edge * edge)) : T(1000);
    const BodyId top = scenes::add_box(w, Vec3<T>{h, h, h}, Vec3<T>{T(0), T(1) + h, T(0)}, Quat<T>::identity(), density);
    const double placed = 1.0 + static_cast<double>(h);
    Vec3<double> at_one{};
    bool finite = true;
    simulate(w, 5.0, [&](int k, double) {
        finite = finite && all_finite(w);
        if (k == 60) at_one = position(w, top);
    });
    const Vec3<double> end = position(w, top);
    const double creep = length(end - at_one);
    const double sink = placed - end.y;
    const double offset = std::hypot(end.x, end.z);
    const double bottom_creep = length(position(w, bottom) - Vec3<double>{0, 0.5, 0});
    Cell c;
    c.numbers = {{"creep_m", creep}, {"sink_m", sink}, {"offset_m", offset}, {"bottom_moved_m", bottom_creep}};
    const double tolerance = std::max(0.01 * edge, 1e-3);
    if (!finite) c.fail("not finite");
    else if (offset > 0.5 || end.y < 1.0) c.fail("fell off");
    else if (sink > 0.5 * edge) c.fail("sank through");
    else if (bottom_creep > 0.01) c.fail("moved the unit cube");
    else if (creep > tolerance) c.fail("creeps");
    c.shown = "creep " + mm(creep) + ", sink " + mm(sink);
    return c;
}

// Sweep 2: a unit cube on a unit cube, density ratio `ratio`, heavy on light or light on heavy.
template <class T>
Cell mass_case(double ratio, bool heavy_on_top) {
    World<T> w(awake_settings<T>());
    add_ground_at(w, T(0), T(50));
    const T light = T(1000), heavy = static_cast<T>(1000.0 * ratio);
    const Vec3<T> half{T(0.5), T(0.5), T(0.5)};
    scenes::add_box(w, half, Vec3<T>{T(0), T(0.5), T(0)}, Quat<T>::identity(), heavy_on_top ? light : heavy);
    const BodyId top = scenes::add_box(w, half, Vec3<T>{T(0), T(1.5), T(0)}, Quat<T>::identity(), heavy_on_top ? heavy : light);
    const double total_mass = 1000.0 * (1.0 + ratio);
    const double energy_scale = total_mass * 9.81 * 1.0;  // J: the stack lifted by a metre
    double overlap = 0, ke_last = 0, speed_last = 0;
    bool finite = true;
    simulate(w, 5.0, [&](int k, double) {
        finite = finite && all_finite(w);
        if (k >= 60) overlap = std::max(overlap, deepest_contact(w));
        if (k >= 240) {
            ke_last = std::max(ke_last, kinetic_energy(w));
            speed_last = std::max(speed_last, fastest_point(w));
        }
    });
    const Vec3<double> end = position(w, top);
    Cell c;
    c.numbers = {{"overlap_m", overlap},
                 {"speed_last_second_m_s", speed_last},
                 {"ke_last_second_J", ke_last},
                 {"ke_relative", ke_last / energy_scale},
                 {"top_y_m", end.y}};
    if (!finite) c.fail("not finite");
    else if (std::hypot(end.x, end.z) > 0.5 || end.y < 1.0) c.fail("fell off");
    else if (overlap > 0.03) c.fail("overlap");
    else if (speed_last > 1e-3 || ke_last > 1e-6 * energy_scale) c.fail("never at rest");
    c.shown = "overlap " + mm(overlap) + ", speed " + mm(speed_last) + "/s";
    return c;
}

// Sweep 3: a 10-cube column moved by `offset` along x.
template <class T>
Cell distance_case(double offset) {
    World<T> w(awake_settings<T>());
    const T x = static_cast<T>(offset);
    add_ground_at(w, x, T(50));
    std::vector<BodyId> boxes;
    for (int i = 0; i < 10; ++i)
        boxes.push_back(scenes::add_box(w, Vec3<T>{T(0.5), T(0.5), T(0.5)}, Vec3<T>{x, T(0.5) + T(i), T(0)}));
    const double placed_top = position(w, boxes.back()).y;
    std::vector<Vec3<double>> at_one(boxes.size());
    bool finite = true;
    simulate(w, 10.0, [&](int k, double) {
        finite = finite && all_finite(w);
        if (k == 60)
            for (std::size_t i = 0; i < boxes.size(); ++i) at_one[i] = position(w, boxes[i]);
    });
    double creep = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) creep = std::max(creep, length(position(w, boxes[i]) - at_one[i]));
    const double sag = placed_top - position(w, boxes.back()).y;
    Cell c;
    c.numbers = {{"creep_m", creep}, {"sag_m", sag}};
    if (!finite) c.fail("not finite");
    else if (creep > 0.01) c.fail("creeps");
    else if (std::abs(sag) > 0.01) c.fail("sags");
    c.shown = "creep " + mm(creep) + ", sag " + mm(sag);
    return c;
}

// Sweep 4: a unit cube sliding at 4 m/s along +x from x = offset; returns the slide distance (m)
// in numbers[0]; the verdict is filled in by the caller against the reference slide.
template <class T>
Cell slide_case(double offset) {
    World<T> w(awake_settings<T>());
    const T x = static_cast<T>(offset);
    add_ground_at(w, x, T(50));
    BodyDef<T> def;
    def.position = {x - T(2), T(0.5), T(0)};
    def.linear_velocity = {T(4), T(0), T(0)};
    const BodyId box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    const double start = position(w, box).x;
    bool finite = true;
    simulate(w, 3.0, [&](int, double) { finite = finite && all_finite(w); });
    const Vec3<double> end = position(w, box);
    Cell c;
    c.numbers = {{"slide_m", end.x - start},
                 {"drift_z_m", end.z},
                 {"speed_end", static_cast<double>(length(w.body(box).linear_velocity()))}};
    if (!finite) c.fail("not finite");
    return c;
}

/// Runs one case; an input the library rejects (InvalidArgument) is an unstable cell.
template <class F>
Cell guarded(F&& run) {
    try {
        return run();
    } catch (const std::invalid_argument& e) {
        // "xeno: Body::set_mass_properties: inertia must be ..." -> "by Body::set_mass_properties".
        std::string what = e.what();
        if (what.rfind("xeno: ", 0) == 0) what = what.substr(6);
        Cell c;
        c.fail("rejected by " + what.substr(0, what.find(": ")));
        return c;
    }
}

// Sweep 5: a unit cube gliding on frictionless ground at 1 cm/s along +x from x = offset, 5 s;
// it should travel 5 cm. A step moves it 0.17 mm (a substep 14 µm): float positions far from the
// origin cannot hold such small moves.
template <class T>
Cell glide_case(double offset) {
    World<T> w(awake_settings<T>());
    const T x = static_cast<T>(offset);
    add_ground_at(w, x, T(50));
    BodyDef<T> def;
    def.position = {x, T(0.5), T(0)};
    def.linear_velocity = {T(0.01), T(0), T(0)};
    def.material.friction = T(0);  // the pair's friction √(0 · 0.6) is 0
    const BodyId box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def);
    const double start = position(w, box).x;
    bool finite = true;
    simulate(w, 5.0, [&](int, double) { finite = finite && all_finite(w); });
    const double travel = position(w, box).x - start, expected = 0.05;
    Cell c;
    c.numbers = {{"travel_m", travel},
                 {"error_m", travel - expected},
                 {"speed_end_m_s", static_cast<double>(length(w.body(box).linear_velocity()))}};
    if (!finite) c.fail("not finite");
    else if (std::abs(travel - expected) > 0.01 * expected) c.fail(travel == 0 ? "frozen" : "off by > 1 %");
    c.shown = format("travel %.2f mm (%+.1f %%)", travel * 1e3, (travel - expected) / expected * 100);
    return c;
}

Sweep size_sweep(bool same_mass) {
    Sweep s{same_mass ? "size" : "size_density",
            same_mass ? "Size ratio: a cube of edge s and the same mass (1000 kg) on a unit cube, 5 s"
                      : "Size ratio at the same density: a cube of edge s, mass ratio s^3, on a unit cube, 5 s",
            "edge s (m)",
            {}};
    for (double edge : {0.001, 0.003, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0})
        s.rows.push_back({format("%g", edge), edge, guarded([&] { return size_case<float>(edge, same_mass); }),
                          guarded([&] { return size_case<double>(edge, same_mass); })});
    return s;
}

Sweep mass_sweep() {
    Sweep s{"mass", "Mass ratio: unit cubes, top/bottom density ratio r, 5 s", "top : bottom", {}};
    for (bool heavy_on_top : {true, false})
        for (double r : {1.0, 10.0, 100.0, 400.0, 1000.0, 3000.0, 10000.0}) {
            if (r == 1.0 && !heavy_on_top) continue;
            const std::string label = heavy_on_top ? format("%g : 1", r) : format("1 : %g", r);
            s.rows.push_back({label, heavy_on_top ? r : 1.0 / r, guarded([&] { return mass_case<float>(r, heavy_on_top); }),
                              guarded([&] { return mass_case<double>(r, heavy_on_top); })});
        }
    return s;
}

Sweep distance_sweep() {
    Sweep s{"distance", "Distance from the origin: a column of 10 unit cubes at x = d, 10 s", "d (m)", {}};
    for (double d : {0.0, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7})
        s.rows.push_back({format("%g", d), d, guarded([&] { return distance_case<float>(d); }),
                          guarded([&] { return distance_case<double>(d); })});
    return s;
}

Sweep slide_sweep() {
    Sweep s{"slide", "Distance from the origin: a unit cube sliding at 4 m/s (mu 0.6) from x = d", "d (m)", {}};
    const double reference = slide_case<double>(0.0).numbers[0].second;
    const double closed_form = 16.0 / (2.0 * 0.6 * 9.81);
    for (double d : {0.0, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7}) {
        Row row{format("%g", d), d, slide_case<float>(d), slide_case<double>(d)};
        for (Cell* c : {&row.f, &row.d}) {
            const double slide = c->numbers[0].second, error = slide - reference;
            c->numbers.push_back({"error_vs_origin_double_m", error});
            if (c->stable && std::abs(error) > 0.01) c->fail("slide off by > 1 cm");
            c->shown = format("slide %.4f m (%+.1f mm)", slide, error * 1e3);
        }
        s.rows.push_back(row);
    }
    s.title += format(": v^2/(2 mu g) = %.4f m, double at the origin %.4f m", closed_form, reference);
    s.good = "right";
    s.bad = "wrong";
    return s;
}

Sweep glide_sweep() {
    Sweep s{"glide", "Distance from the origin: a unit cube gliding at 1 cm/s on frictionless ground from x = d, 5 s (5 cm)",
            "d (m)", {},
            "right", "wrong"};
    for (double d : {0.0, 1e1, 1e2, 3e2, 1e3, 3e3, 1e4, 1e5})
        s.rows.push_back(
            {format("%g", d), d, guarded([&] { return glide_case<float>(d); }), guarded([&] { return glide_case<double>(d); })});
    return s;
}

void print_table(const Sweep& s) {
    std::size_t wf = 5, wd = 6;
    for (const Row& r : s.rows) {
        wf = std::max(wf, r.f.text(s.good, s.bad).size());
        wd = std::max(wd, r.d.text(s.good, s.bad).size());
    }
    std::printf("\n%s\n%-14s  %-*s  %s\n", s.title.c_str(), s.column.c_str(), static_cast<int>(wf), "float", "double");
    for (const Row& r : s.rows)
        std::printf("%-14s  %-*s  %s\n", r.value.c_str(), static_cast<int>(wf), r.f.text(s.good, s.bad).c_str(),
                    r.d.text(s.good, s.bad).c_str());
}

void print_markdown(const Sweep& s) {
    std::printf("\n**%s**\n\n| %s | float | double |\n|---|---|---|\n", s.title.c_str(), s.column.c_str());
    for (const Row& r : s.rows)
        std::printf("| %s | %s | %s |\n", r.value.c_str(), r.f.markdown(s.good, s.bad).c_str(),
                    r.d.markdown(s.good, s.bad).c_str());
}

void write_csv(const std::filesystem::path& file, const Sweep& s) {
    std::FILE* f = std::fopen(file.string().c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + file.string());
    // The columns are those of the cells that measured something (a rejected case measured nothing).
    std::vector<std::string> columns;
    for (const Row& r : s.rows)
        for (const Cell* c : {&r.f, &r.d})
            if (c->numbers.size() > columns.size()) {
                columns.clear();
                for (const auto& n : c->numbers) columns.push_back(n.first);
            }
    std::fprintf(f, "value,build,stable,why");
    for (const std::string& name : columns) std::fprintf(f, ",%s", name.c_str());
    std::fprintf(f, "\n");
    for (const Row& r : s.rows)
        for (const auto& [build, c] : {std::pair<const char*, const Cell*>{"float", &r.f}, {"double", &r.d}}) {
            std::fprintf(f, "%.9g,%s,%d,%s", r.number, build, c->stable ? 1 : 0, c->why.c_str());
            for (std::size_t i = 0; i < columns.size(); ++i)
                if (i < c->numbers.size()) std::fprintf(f, ",%.9g", c->numbers[i].second);
                else std::fprintf(f, ",");
            std::fprintf(f, "\n");
        }
    std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
    std::string out = "out";
    bool markdown = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(usage, stdout);
            return 0;
        } else if (a == "--markdown") {
            markdown = true;
        } else if (a == "--out" && i + 1 < argc) {
            out = argv[++i];
        } else {
            std::fprintf(stderr, "xeno_scale_sweep: unknown or incomplete option '%s'\n%s", a.c_str(), usage);
            return 2;
        }
    }
    try {
        const auto start = std::chrono::steady_clock::now();
        const std::filesystem::path dir = std::filesystem::path(out) / "sweep";
        std::filesystem::create_directories(dir);
        std::vector<Sweep> sweeps;
        const std::function<Sweep()> runs[] = {[] { return size_sweep(true); },
                                               [] { return size_sweep(false); },
                                               mass_sweep,
                                               distance_sweep,
                                               slide_sweep,
                                               glide_sweep};
        for (const auto& run : runs) {
            sweeps.push_back(run());
            print_table(sweeps.back());
            write_csv(dir / (sweeps.back().name + ".csv"), sweeps.back());
        }
        if (markdown)
            for (const Sweep& s : sweeps) print_markdown(s);
        std::printf("\n%.1f s; written to %s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                    dir.string().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "xeno_scale_sweep: %s\n", e.what());
        return 1;
    }
    return 0;
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_precision: every scene run in float and in double side by side, in one program, from the
// same initial state, and the two histories compared step by step. This is what templating the
// engine on the scalar buys (docs/style.md, "The scalar parameter"): engines with a build-wide
// precision macro need two binaries and cannot line the runs up step by step.
//
//   1. build the scene in a World<double> and in a World<float>; then overwrite every float body's
//      pose and velocities with the double ones rounded to float, so the float run starts from the
//      double state rounded (scenes compute some poses, e.g. random ones, in T; shapes are still
//      built in each precision, so a hull's vertices differ by their rounding)
//   2. step both at the settings' fixed step (1/60 s) for --seconds, and after every step record
//        pos_diff    max over dynamic bodies of |x_f − x_d| (m)
//        angle_diff  max over dynamic bodies of the angle of the rotation q_d⁻¹ q_f (deg)
//        depth_f/d   deepest contact overlap in each build: max ContactPoint::depth, 0 if none (m)
//        ke_f/d      total kinetic energy in each build (J)
//   3. the runs "part" at the first step where pos_diff exceeds --part (1 cm): the scene is then a
//      different scene in each build. The growth of pos_diff from 10⁻⁶ m to the threshold is fitted
//      as an exponential (least squares on log pos_diff) and reported as the time it takes to grow
//      tenfold. Verdict: "agree" (never parts), "chaotic" (parts before half the run: a rounding
//      difference of 10⁻⁸ m grows to centimetres, the signature of sensitive dependence on the
//      initial state, or of a discrete decision such as a body falling asleep a step apart; run
//      with --no-sleep to tell the two apart), "parts" (parts late, after things mostly settled).
//
// Output: a table on stdout (--markdown adds a markdown copy; its depth columns are the deepest
// overlap after the first second, since random scenes start with bodies overlapping), and in
// DIR/precision/ one CSV per scene (time, pos_diff, angle_diff_deg, depth_f, depth_d, ke_f, ke_d),
// summary.csv, and, when gnuplot is on PATH (run through POSIX popen), one 640×400 PNG per scene
// plus summary.png (how long each scene's two runs stay together).
#include "scenes/all.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace xeno;

const char* const usage =
    "usage: xeno_precision [options] [scene ...|all]\n"
    "Runs each scene in float and in double from the same initial state and reports, over time,\n"
    "the largest position and orientation difference between the two runs, contact depths,\n"
    "kinetic energy, and when the runs part.\n"
    "  --out DIR       output folder (default out): writes DIR/precision/<scene>.csv, .png,\n"
    "                  summary.csv, summary.png (PNGs need gnuplot on PATH)\n"
    "  --seconds S     simulated time per scene (default 10)\n"
    "  --part M        position difference (m) at which the runs part (default 0.01)\n"
    "  --markdown      also print the table as markdown\n"
    "  --no-sleep      keep every body awake (scenes sleep by default; a body falling asleep\n"
    "                  a step apart in the two builds freezes a slightly different state)\n"
    "  --no-plot       skip the PNGs\n"
    "  --list          list the scenes and exit\n"
    "  --help          this text\n";

struct Options {
    std::string out = "out";
    double seconds = 10.0;
    double part = 0.01;
    bool markdown = false;
    bool plot = true;
    bool sleep = true;
    std::vector<std::string> scenes;
};

/// One row of a scene's CSV: the two runs compared after a step.
struct Sample {
    double time;              ///< s since the start
    double pos_diff;          ///< m, max over dynamic bodies
    double angle_diff_deg;    ///< degrees, max over dynamic bodies
    double depth_f, depth_d;  ///< m, deepest contact overlap in each build (0 if none)
    double ke_f, ke_d;        ///< J, total kinetic energy in each build
};

/// One row of the summary table.
struct Result {
    std::string scene;
    std::size_t bodies = 0;  ///< dynamic bodies
    double part_time = -1;   ///< s; < 0: never parted
    double pos_at_1s = 0, pos_end = 0, angle_end_deg = 0;
    double depth_max_f = 0, depth_max_d = 0;  ///< m, deepest overlap after the first second
    bool any_contact = false;                 ///< some contact overlapped at some step (the plot's depth axis)
    double ke_end_f = 0, ke_end_d = 0;
    double decade_time = std::numeric_limits<double>::quiet_NaN();  ///< s for the difference to grow ×10
    std::string verdict;
    double wall = 0;  ///< s of wall-clock time for both runs
};

template <class T>
std::vector<BodyId> all_bodies(const World<T>& w) {
    std::vector<BodyId> ids;
    w.for_each_body([&](BodyId id, const Body<T>&) { ids.push_back(id); });
    return ids;
}

/// Step 1 of the file comment: the float world takes the double world's state, rounded.
void copy_rounded_state(const World<double>& wd, World<float>& wf) {
    const std::vector<BodyId> ids_d = all_bodies(wd), ids_f = all_bodies(wf);
    if (ids_d.size() != ids_f.size()) throw std::runtime_error("the float and double scenes have different body counts");
    for (std::size_t i = 0; i < ids_d.size(); ++i) {
        const Body<double>& bd = wd.body(ids_d[i]);
        if (bd.type() != wf.body(ids_f[i]).type()) throw std::runtime_error("the float and double scenes differ in body types");
        wf.set_transform(ids_f[i], Vec3<float>(bd.position()), Quat<float>(bd.orientation()));
        Body<float>& bf = wf.body(ids_f[i]);
        bf.set_linear_velocity(Vec3<float>(bd.linear_velocity()));
        bf.set_angular_velocity(Vec3<float>(bd.angular_velocity()));
    }
}

template <class T>
void no_sleeping(World<T>& w) {
    WorldSettings<T> s = w.settings();
    s.allow_sleeping = false;
    w.set_settings(s);
}

template <class T>
std::vector<BodyId> dynamic_bodies(const World<T>& w) {
    std::vector<BodyId> ids;
    w.for_each_body([&](BodyId id, const Body<T>& b) {
        if (b.is_dynamic()) ids.push_back(id);
    });
    return ids;
}

/// Deepest overlap (m) over every contact point of the world; 0 when nothing overlaps.
template <class T>
double deepest_contact(const World<T>& w) {
    double deepest = 0;
    for (const Contact<T>& c : w.contacts())
        for (int i = 0; i < c.manifold.count; ++i)
            deepest = std::max(deepest, static_cast<double>(c.manifold.points[static_cast<std::size_t>(i)].depth));
    return deepest;
}

template <class T>
double kinetic_energy(const World<T>& w) {
    double e = 0;
    w.for_each_body([&](BodyId, const Body<T>& b) { e += static_cast<double>(b.kinetic_energy()); });
    return e;
}

/// Angle (rad) of the rotation from a to b. Same as angle_between, but as 2 atan2(|v|, |w|) of
/// a⁻¹ b: acos near 1 loses the small angles (10⁻⁸ rad) this tool is about.
double rotation_angle(const Quat<double>& a, const Quat<double>& b) {
    const Quat<double> r = conjugate(a) * b;
    return 2.0 * std::atan2(std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z), std::abs(r.w));
}

/// Time (s) for pos_diff to grow tenfold, fitted (least squares on ln pos_diff) over the samples
/// from its first crossing of 10⁻⁶ m to its first crossing of `top`; NaN with fewer than two
/// samples in that range or no growth. Only meaningful for runs that part.
double decade_time(const std::vector<Sample>& samples, double top) {
    const double bottom = 1e-6;
    double n = 0, st = 0, sy = 0, stt = 0, sty = 0;
    bool started = false;
    for (const Sample& s : samples) {
        if (!std::isfinite(s.pos_diff)) break;
        if (!started && s.pos_diff < bottom) continue;
        started = true;
        const double y = std::log(std::max(s.pos_diff, 1e-300));
        n += 1;
        st += s.time;
        sy += y;
        stt += s.time * s.time;
        sty += s.time * y;
        if (s.pos_diff > top) break;
    }
    if (n < 2) return std::numeric_limits<double>::quiet_NaN();
    const double denominator = n * stt - st * st;
    if (!(denominator > 0)) return std::numeric_limits<double>::quiet_NaN();
    const double slope = (n * sty - st * sy) / denominator;  // 1/s, growth rate of ln pos_diff
    if (!(slope > 0)) return std::numeric_limits<double>::quiet_NaN();
    return std::log(10.0) / slope;
}

Result run_scene(const std::string& name, const Options& opt, std::vector<Sample>& samples) {
    const auto start = std::chrono::steady_clock::now();
    World<double> wd;
    World<float> wf;
    const scenes::Scene scene = scenes::build(name, wd);
    const scenes::Scene scene_f = scenes::build(name, wf);
    copy_rounded_state(wd, wf);
    if (!opt.sleep) {
        no_sleeping(wd);
        no_sleeping(wf);
    }
    const std::vector<BodyId> bodies_d = dynamic_bodies(wd), bodies_f = dynamic_bodies(wf);

    const double dt = static_cast<double>(wd.settings().fixed_time_step);
    const float dt_f = wf.settings().fixed_time_step;
    const int steps = static_cast<int>(std::lround(opt.seconds / dt));
    const int step_1s = static_cast<int>(std::lround(1.0 / dt));
    Result r;
    r.scene = name;
    r.bodies = scene.bodies.size();
    samples.clear();
    samples.reserve(static_cast<std::size_t>(steps));
    for (int k = 1; k <= steps; ++k) {
        if (scene.before_step) scene.before_step(dt), scene_f.before_step(static_cast<double>(dt_f));  // (the character)
        wd.step(dt);
        wf.step(dt_f);
        Sample s{};
        s.time = k * dt;
        for (std::size_t i = 0; i < bodies_d.size(); ++i) {
            const Body<double>& bd = wd.body(bodies_d[i]);
            const Body<float>& bf = wf.body(bodies_f[i]);
            const double d = length(Vec3<double>(bf.position()) - bd.position());
            s.pos_diff = std::isfinite(d) ? std::max(s.pos_diff, d) : d;  // a NaN stays NaN
            s.angle_diff_deg = std::max(s.angle_diff_deg, rotation_angle(bd.orientation(), Quat<double>(bf.orientation())) *
                                                              180.0 / ScalarTraits<double>::pi);
        }
        s.depth_f = deepest_contact(wf);
        s.depth_d = deepest_contact(wd);
        s.ke_f = kinetic_energy(wf);
        s.ke_d = kinetic_energy(wd);
        samples.push_back(s);

        if (r.part_time < 0 && !(s.pos_diff <= opt.part)) r.part_time = s.time;
        if (k == step_1s) r.pos_at_1s = s.pos_diff;
        // Depth after the first second: random scenes start with bodies overlapping and drop
        // things, so the whole run's deepest point says more about the scene than about precision.
        if (k >= step_1s) {
            r.depth_max_f = std::max(r.depth_max_f, s.depth_f);
            r.depth_max_d = std::max(r.depth_max_d, s.depth_d);
        }
        r.any_contact = r.any_contact || s.depth_f > 0 || s.depth_d > 0;
    }
    if (!samples.empty()) {
        r.pos_end = samples.back().pos_diff;
        r.angle_end_deg = samples.back().angle_diff_deg;
        r.ke_end_f = samples.back().ke_f;
        r.ke_end_d = samples.back().ke_d;
    }
    if (r.part_time >= 0) r.decade_time = decade_time(samples, opt.part);
    r.verdict = r.part_time < 0 ? "agree" : (r.part_time < 0.5 * opt.seconds ? "chaotic" : "parts");
    r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

void write_scene_csv(const std::filesystem::path& file, const std::vector<Sample>& samples) {
    std::FILE* f = std::fopen(file.string().c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + file.string());
    std::fprintf(f, "time,pos_diff,angle_diff_deg,depth_f,depth_d,ke_f,ke_d\n");
    for (const Sample& s : samples)
        std::fprintf(f, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", s.time, s.pos_diff, s.angle_diff_deg, s.depth_f, s.depth_d,
                     s.ke_f, s.ke_d);
    std::fclose(f);
}

std::string part_text(const Result& r, int precision = 2) {
    if (r.part_time < 0) return "never";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.*f", precision, r.part_time);
    return buffer;
}

std::string number(const char* format, double v) {
    if (std::isnan(v)) return "-";
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, format, v);
    return buffer;
}

void write_summary_csv(const std::filesystem::path& file, const std::vector<Result>& results) {
    std::FILE* f = std::fopen(file.string().c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + file.string());
    std::fprintf(f,
                 "scene,bodies,part_time_s,pos_diff_1s_m,pos_diff_end_m,angle_diff_end_deg,max_depth_f_m,max_depth_d_m,"
                 "ke_end_f_J,ke_end_d_J,decade_time_s,verdict,wall_s\n");
    for (const Result& r : results)
        std::fprintf(f, "%s,%zu,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%s,%.3f\n", r.scene.c_str(), r.bodies,
                     r.part_time < 0 ? "never" : number("%.4f", r.part_time).c_str(), r.pos_at_1s, r.pos_end, r.angle_end_deg,
                     r.depth_max_f, r.depth_max_d, r.ke_end_f, r.ke_end_d, number("%.4g", r.decade_time).c_str(),
                     r.verdict.c_str(), r.wall);
    std::fclose(f);
}

const char* const table_header =
    "scene           bodies  part (s)  pos@1s (m)  pos@end (m)  ang@end (deg)  depth>1s f/d (mm)  KE end f / d (J)       x10 (s) "
    " verdict\n";

void print_row(const Result& r) {
    std::printf("%-15s %6zu  %8s  %10.2e  %11.2e  %13.3g  %7.2f / %-7.2f  %9.3g / %-9.3g  %7s  %s\n", r.scene.c_str(), r.bodies,
                part_text(r).c_str(), r.pos_at_1s, r.pos_end, r.angle_end_deg, r.depth_max_f * 1e3, r.depth_max_d * 1e3,
                r.ke_end_f, r.ke_end_d, number("%.2f", r.decade_time).c_str(), r.verdict.c_str());
    std::fflush(stdout);
}

void print_markdown(const std::vector<Result>& results, const Options& opt) {
    std::printf(
        "\n| scene | bodies | part (s) | pos diff at 1 s (m) | pos diff at %g s (m) | angle diff at end (°) | "
        "max depth after 1 s, float / double (mm) | KE at end float / double (J) | ×10 every (s) | verdict |\n",
        opt.seconds);
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (const Result& r : results)
        std::printf("| %s | %zu | %s | %.1e | %.1e | %.3g | %.2f / %.2f | %.3g / %.3g | %s | %s |\n", r.scene.c_str(), r.bodies,
                    part_text(r).c_str(), r.pos_at_1s, r.pos_end, r.angle_end_deg, r.depth_max_f * 1e3, r.depth_max_d * 1e3,
                    r.ke_end_f, r.ke_end_d, number("%.2f", r.decade_time).c_str(), r.verdict.c_str());
}

bool gnuplot_available() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

/// Feeds a script to gnuplot; false when gnuplot failed.
bool run_gnuplot(const std::string& script) {
    std::FILE* pipe = popen("gnuplot", "w");
    if (!pipe) return false;
    std::fputs(script.c_str(), pipe);
    return pclose(pipe) == 0;
}

/// gnuplot quotes strings with '...': a quote in a path is doubled.
std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
    return q + "'";
}

/// Two panels: the differences (position, angle; log scale, with the parting threshold), then
/// kinetic energy in each build (log scale) with the deepest overlap of each build on the right axis.
bool plot_scene(const std::filesystem::path& csv, const std::filesystem::path& png, const Result& r, const Options& opt) {
    char threshold[64];
    std::snprintf(threshold, sizeof threshold, "%g", opt.part);
    std::string s;
    s += "set terminal pngcairo size 640,400 font 'sans,8'\n";
    s += "set output " + quoted(png.string()) + "\n";
    s += "set datafile separator ','\n";
    s += "set multiplot layout 2,1 title " +
         quoted(r.scene + ": float against double (" + r.verdict + ", part " + part_text(r) + (r.part_time < 0 ? "" : " s") +
                ")") +
         "\n";
    s += "set grid lc rgb '#dddddd'\n";
    s += "set xrange [0:" + std::to_string(opt.seconds) + "]\n";
    s += "set lmargin 10\nset rmargin 10\n";
    s += "set key top left opaque box lc rgb '#cccccc' samplen 2 spacing 0.9\n";
    s += "set logscale y\nset format y '10^{%L}'\nset yrange [1e-9:*]\n";
    s += "set ylabel 'difference'\n";
    s += "clip(v) = v > 1e-9 ? v : 1e-9\n";
    s += "plot " + quoted(csv.string()) +
         " using 1:(clip($2)) with lines lw 1.5 lc rgb '#1f77b4' title 'position (m)', "
         "'' using 1:(clip($3)) with lines lw 1 lc rgb '#ff7f0e' title 'angle (deg)', " +
         std::string(threshold) + " with lines dt 2 lc rgb '#888888' title 'part (" + threshold + " m)'\n";
    s += "set ylabel 'kinetic energy (J)'\nset xlabel 'time (s)'\nset yrange [1e-8:*]\n";
    s += "set key top right\n";
    // A depth axis only when something touched (an all-zero range makes gnuplot warn).
    if (r.any_contact) s += "set y2label 'deepest overlap (mm)'\nset y2tics\nset y2range [0:*]\n";
    s += "plot '' using 1:($6 > 1e-8 ? $6 : 1e-8) with lines lw 1.5 lc rgb '#2ca02c' title 'KE float', "
         "'' using 1:($7 > 1e-8 ? $7 : 1e-8) with lines lw 1 dt 2 lc rgb '#000000' title 'KE double'";
    if (r.any_contact)
        s += ", '' using 1:($4*1e3) axes x1y2 with lines lw 0.8 lc rgb '#d62728' title 'depth float', "
             "'' using 1:($5*1e3) axes x1y2 with lines lw 0.8 dt 3 lc rgb '#9467bd' title 'depth double'";
    s += "\n";
    s += "unset multiplot\n";
    return run_gnuplot(s);
}

/// A bar per scene: how long the two builds stay within the threshold of each other.
bool plot_summary(const std::filesystem::path& png, const std::vector<Result>& results, const Options& opt) {
    const std::filesystem::path data = png.parent_path() / "summary_bars.dat";
    {
        std::ofstream f(data);
        for (std::size_t i = 0; i < results.size(); ++i) {
            const Result& r = results[i];
            const double t = r.part_time < 0 ? opt.seconds : r.part_time;
            const int colour = r.verdict == "agree" ? 0 : (r.verdict == "parts" ? 1 : 2);
            f << i << ' ' << t << ' ' << colour << ' ' << '"' << r.scene << '"' << '\n';
        }
    }
    std::string s;
    s += "set terminal pngcairo size 640,400 font 'sans,8'\n";
    s += "set output " + quoted(png.string()) + "\n";
    s += "set title \"Time until float and double part (position difference > " + number("%g", opt.part) +
         " m; a full bar: never)\\ngreen: agree   orange: parts late   red: chaotic (parts before half the run)\"\n";
    s += "set style fill solid 0.8 noborder\nset xrange [0:" + std::to_string(opt.seconds) + "]\n";
    s += "set yrange [" + std::to_string(results.size()) + "-0.5:-0.5]\n";
    s += "set xlabel 'time (s)'\nset grid x lc rgb '#dddddd'\nunset key\n";
    s += "set palette defined (0 '#2ca02c', 1 '#ff7f0e', 2 '#d62728')\nset cbrange [0:2]\nunset colorbox\n";
    s += "plot " + quoted(data.string()) + " using ($2/2):1:($2/2):(0.38):3:ytic(4) with boxxyerror lc palette\n";
    const bool ok = run_gnuplot(s);
    std::error_code ignored;
    std::filesystem::remove(data, ignored);
    return ok;
}

bool parse_number(const std::string& text, double& value) {
    try {
        std::size_t used = 0;
        value = std::stod(text, &used);
        return used == text.size() && std::isfinite(value);
    } catch (const std::exception&) {
        return false;
    }
}

/// Parses argv; returns an exit code >= 0 to stop with (0 after --help, 2 on bad usage), -1 to go on.
int parse(int argc, char** argv, Options& opt) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const char* what) -> const char* {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "xeno_precision: %s needs a value\n", what);
                return nullptr;
            }
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            std::fputs(usage, stdout);
            return 0;
        } else if (a == "--list") {
            for (const auto& [name, description] : scenes::scene_list())
                std::printf("%-15s %s\n", name.c_str(), description.c_str());
            return 0;
        } else if (a == "--out") {
            const char* v = value("--out");
            if (!v) return 2;
            opt.out = v;
        } else if (a == "--seconds" || a == "--part") {
            const char* v = value(a.c_str());
            double x = 0;
            if (!v || !parse_number(v, x) || !(x > 0)) {
                std::fprintf(stderr, "xeno_precision: %s needs a positive number\n", a.c_str());
                return 2;
            }
            (a == "--seconds" ? opt.seconds : opt.part) = x;
        } else if (a == "--markdown") {
            opt.markdown = true;
        } else if (a == "--no-sleep") {
            opt.sleep = false;
        } else if (a == "--no-plot") {
            opt.plot = false;
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "xeno_precision: unknown option '%s'\n%s", a.c_str(), usage);
            return 2;
        } else if (a == "all") {
            for (const auto& entry : scenes::scene_list()) opt.scenes.push_back(entry.first);
        } else {
            const auto& list = scenes::scene_list();
            if (std::none_of(list.begin(), list.end(), [&](const auto& e) { return e.first == a; })) {
                std::fprintf(stderr, "xeno_precision: unknown scene '%s' (--list shows them)\n", a.c_str());
                return 2;
            }
            opt.scenes.push_back(a);
        }
    }
    if (opt.scenes.empty())
        for (const auto& entry : scenes::scene_list()) opt.scenes.push_back(entry.first);
    // Each scene once, in the order first named ("column all" runs column first, not twice).
    std::vector<std::string> unique;
    for (const std::string& name : opt.scenes)
        if (std::find(unique.begin(), unique.end(), name) == unique.end()) unique.push_back(name);
    opt.scenes = unique;
    return -1;
}

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    const int stop = parse(argc, argv, opt);
    if (stop >= 0) return stop;
    try {
        const std::filesystem::path dir = std::filesystem::path(opt.out) / "precision";
        std::filesystem::create_directories(dir);
        const bool plot = opt.plot && gnuplot_available();
        if (opt.plot && !plot) std::fprintf(stderr, "xeno_precision: gnuplot not on PATH, writing CSV only\n");

        std::printf("float against double, %g s at 60 Hz per scene, parting at %g m%s\n%s", opt.seconds, opt.part,
                    opt.sleep ? "" : ", sleeping off", table_header);
        std::vector<Result> results;
        std::vector<Sample> samples;
        bool plots_ok = true;
        double wall = 0;
        for (const std::string& name : opt.scenes) {
            results.push_back(run_scene(name, opt, samples));
            wall += results.back().wall;
            print_row(results.back());
            const std::filesystem::path csv = dir / (name + ".csv");
            write_scene_csv(csv, samples);
            if (plot) plots_ok = plot_scene(csv, dir / (name + ".png"), results.back(), opt) && plots_ok;
        }
        write_summary_csv(dir / "summary.csv", results);
        if (plot) plots_ok = plot_summary(dir / "summary.png", results, opt) && plots_ok;
        if (!plots_ok) std::fprintf(stderr, "xeno_precision: gnuplot failed on some plots\n");
        if (opt.markdown) print_markdown(results, opt);
        const auto count = [&](const char* v) {
            return std::count_if(results.begin(), results.end(), [&](const Result& r) { return r.verdict == v; });
        };
        std::printf("%zu scenes: %td agree, %td part late, %td chaotic; %.1f s of simulation; written to %s\n", results.size(),
                    count("agree"), count("parts"), count("chaotic"), wall, dir.string().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "xeno_precision: %s\n", e.what());
        return 1;
    }
    return 0;
}

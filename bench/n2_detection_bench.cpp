// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The thesis's N² table, measured again (issue "Broad phase and the N² detection benchmark").
// The thesis timed one step of brute-force all-pairs XenoCollide for 500 to 3500 boxes (Quadro 26);
// this program times one detection pass (world boxes + broad phase + contact of every overlapping
// pair, n2_detection.hpp) for each strategy on the same kind of scene, prints the table beside the
// thesis's seconds, and writes
//   DIR/n2.csv          bodies,strategy,seconds,pairs   (full passes; `_mixed` for the mixed scene)
//   DIR/n2_details.csv  scene,bodies,strategy,phase,seconds,pairs   (cold/warm, broad only, threads)
//   DIR/n2_plot.dat     the table in columns for gnuplot, DIR/n2_plot.gp, and DIR/n2.png when
//                       gnuplot is on PATH (log-log time against N, thesis beside xeno).
// Table rows are the best of a few cold passes (a fresh broad phase each time: the thesis's step
// had no state to reuse). Brute strategies run while the N² extrapolation of their last time stays
// under --time-limit seconds; beyond it the table prints the estimate (marked "est", not in CSV).
// One thread unless stated: the parallel section times the narrow phase on 1 and --threads threads.
//
//   xeno_n2_bench [--max-bodies N] [--out DIR] [--quick] [--threads N] [--seed S] [--time-limit SEC]
#include "n2_detection.hpp"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace xeno;
using namespace xeno::bench;
using Real = double;

namespace {

struct Options {
    std::size_t max_bodies = 1000000;
    std::string out = "out";
    bool quick = false;
    bool lanes = false;
    unsigned threads = 2;
    std::uint64_t seed = kN2Seed;
    double time_limit = 20;
};

[[noreturn]] void usage(int code) {
    std::printf(
        "usage: xeno_n2_bench [--max-bodies N] [--out DIR] [--quick] [--lanes] [--threads N] [--seed S] [--time-limit SEC]\n"
        "  --max-bodies N    largest scene (default 1000000; 1,000,000 runs the broad phase alone)\n"
        "  --out DIR         where n2.csv, n2_details.csv, n2_plot.dat and n2.png go (default out)\n"
        "  --quick           small scenes only (CI smoke test, a few seconds)\n"
        "  --lanes           only the early-out's rows: brute force against brute_lanes at 3,500 boxes\n"
        "                    in float and double, sweep and prune at 100,000 with and without it\n"
        "  --threads N       threads for the parallel narrow phase comparison (default 2)\n"
        "  --seed S          scene seed (default %llu)\n"
        "  --time-limit SEC  skip (and estimate) a brute pass predicted to take longer (default 20)\n",
        static_cast<unsigned long long>(kN2Seed));
    std::exit(code);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(2);
            return argv[++i];
        };
        if (a == "--max-bodies") o.max_bodies = std::stoull(value());
        else if (a == "--out") o.out = value();
        else if (a == "--quick") o.quick = true;
        else if (a == "--lanes") o.lanes = true;
        else if (a == "--threads") o.threads = static_cast<unsigned>(std::stoul(value()));
        else if (a == "--seed") o.seed = std::stoull(value());
        else if (a == "--time-limit") o.time_limit = std::stod(value());
        else if (a == "--help" || a == "-h") usage(0);
        else usage(2);
    }
    if (o.threads < 1) o.threads = 1;
    return o;
}

std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

// The fastest of several passes: other jobs on a shared machine only ever add time.
double best(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

// The load average (Linux), to say how busy the machine was.
std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one, five;
    if (!(in >> one >> five)) return "unknown";
    return one + " (1 min), " + five + " (5 min)";
}

std::string format_seconds(double s) {
    char buf[32];
    if (s < 1e-3) std::snprintf(buf, sizeof buf, "%.1f us", s * 1e6);
    else if (s < 1) std::snprintf(buf, sizeof buf, "%.2f ms", s * 1e3);
    else std::snprintf(buf, sizeof buf, "%.2f s", s);
    return buf;
}

struct Row {
    std::size_t bodies;
    std::string strategy;  // CSV name
    double seconds;
    std::size_t pairs;        // contacts (overlapping shape pairs)
    std::size_t broad_pairs;  // pairs the broad phase passed on
    bool estimated;
};

struct Detail {
    std::string scene;
    std::size_t bodies;
    std::string strategy, phase;
    double seconds;
    std::size_t pairs;
};

// The best of a few cold passes: a fresh detector each time; stops after ~1 s or 5 passes.
PassResult best_cold(Strategy strategy, const Scene<Real>& scene, int max_reps = 5) {
    PassResult best;
    double total = 0;
    for (int rep = 0; rep < max_reps && total < 1.0; ++rep) {
        Detector<Real> d(strategy);
        const PassResult r = d.pass(scene);
        if (rep == 0 || r.seconds < best.seconds) best = r;
        total += r.seconds;
    }
    return best;
}

struct ColdWarm {
    std::vector<double> cold, warm, cold_broad, warm_broad;
    PassResult last;
};

// Cold: the first pass of fresh detectors (3). Warm: one detector, first pass, then `frames`
// passes each after every body moved up to 1 cm and turned up to 0.01 rad.
ColdWarm cold_warm(Strategy strategy, const Scene<Real>& scene, bool broad_only, int frames = 5, const ParallelFor& parallel = {},
                   bool early_out = true) {
    ColdWarm cw;
    for (int rep = 0; rep < 3; ++rep) {
        Detector<Real> d(strategy, parallel, Real(0.1), early_out);
        const PassResult r = broad_only ? d.broad_only(scene) : d.pass(scene);
        cw.cold.push_back(r.seconds);
        cw.cold_broad.push_back(r.broad_seconds);
        cw.last = r;
        if (r.seconds > 20) break;
    }
    Scene<Real> moving = scene;
    scenes::Random rng(12345);
    Detector<Real> d(strategy, parallel, Real(0.1), early_out);
    broad_only ? d.broad_only(moving) : d.pass(moving);
    for (int f = 0; f < frames; ++f) {
        jiggle(moving, rng, Real(0.01));
        const PassResult r = broad_only ? d.broad_only(moving) : d.pass(moving);
        cw.warm.push_back(r.seconds);
        cw.warm_broad.push_back(r.broad_seconds);
        cw.last = r;
    }
    return cw;
}

bool make_dir(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    return std::filesystem::is_directory(dir, ec);
}

std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// The target the library's lanes were compiled for (wide.hpp picks the width from it).
const char* lane_target() {
#if defined(XENO_SIMD_AVX) && defined(__AVX2__)
    return "AVX2 (e.g. -march=x86-64-v3)";
#elif defined(XENO_SIMD_AVX)
    return "AVX";
#elif defined(XENO_SIMD_SSE2)
    return "SSE2 (generic x86-64)";
#else
    return "no SIMD (portable lanes)";
#endif
}

// --lanes: the early-out's rows alone (brute force with and without MPR's first test in lanes,
// float and double; sweep and prune at 100,000 boxes with and without it), for a second build
// with other instructions (scripts/main.sh runs it from xeno_n2_bench_v3).
template <class T>
void lanes_rows(const Options& opt) {
    const std::size_t n = std::min<std::size_t>(3500, opt.max_bodies);
    const Scene<T> scene = make_box_scene<T>(n, opt.seed);
    const char* precision = sizeof(T) == 4 ? "float" : "double";
    for (const Strategy strategy : {Strategy::brute, Strategy::brute_lanes}) {
        double best_s = 1e30;
        std::size_t contacts = 0;
        for (int rep = 0; rep < (strategy == Strategy::brute ? 2 : 5); ++rep) {
            Detector<T> d(strategy);
            const PassResult r = d.pass(scene);
            best_s = std::min(best_s, r.seconds);
            contacts = r.contacts;
        }
        std::printf("  %-6s %-12s %zu boxes: %10s  %5.1f ns/pair  %6.0fx the thesis  (%zu contacts, %d lanes)\n", precision,
                    strategy_name(strategy), n, format_seconds(best_s).c_str(),
                    1e9 * best_s / (0.5 * static_cast<double>(n) * static_cast<double>(n - 1)), thesis_seconds(n) / best_s,
                    contacts, strategy == Strategy::brute ? 1 : EarlyOut<T>::width);
    }
}

void lanes_only(const Options& opt) {
    std::printf("xeno N² detection, the early-out in lanes; lanes built for %s\n", lane_target());
    std::printf("machine: %s, one thread; load average at start: %s\n", cpu_model().c_str(), load_average().c_str());
    lanes_rows<float>(opt);
    lanes_rows<double>(opt);
    const std::size_t n = std::min<std::size_t>(100000, opt.max_bodies);
    const Scene<Real> scene = make_box_scene<Real>(n, opt.seed);
    for (const bool early_out : {false, true}) {
        const ColdWarm cw = cold_warm(Strategy::sap, scene, false, 5, {}, early_out);
        std::printf("  double sap %-18s %zu boxes: cold %s, warm %s (broad phase %s), %zu contacts\n",
                    early_out ? "with the early-out" : "without", n, format_seconds(best(cw.cold)).c_str(),
                    format_seconds(best(cw.warm)).c_str(), format_seconds(best(cw.warm_broad)).c_str(), cw.last.contacts);
    }
    std::printf("load average at end: %s\n", load_average().c_str());
}

/// The sizes each part of the run measures (fewer with --quick).
struct Sizes {
    std::vector<std::size_t> table = {500, 1000, 1500, 2000, 2500, 3000, 3500};
    std::vector<std::size_t> large = {10000, 100000};
    std::size_t huge = 1000000;
};

/// What the run measured, for the files it writes.
struct Results {
    std::vector<Row> rows;
    std::vector<Detail> details;
};

/// The machine, the build, the load and the scenes, before any timing.
void print_header(const Options& opt) {
    std::printf("xeno N² detection benchmark (issue: broad phase)\n");
    std::printf("machine: %s, %u hardware threads; one thread unless stated; double precision\n", cpu_model().c_str(),
                std::thread::hardware_concurrency());
#ifdef NDEBUG
    std::printf("build: optimised (NDEBUG)\n");
#else
    std::printf("build: NOT optimised (assertions on): timings are not representative\n");
#endif
    std::printf("load average at start: %s\n", load_average().c_str());
    std::printf("seed: %llu\n", static_cast<unsigned long long>(opt.seed));
    std::printf("scene: %s\n", make_box_scene<Real>(1, opt.seed).description.c_str());
    std::printf("mixed: %s\n", make_mixed_scene<Real>(1, opt.seed).description.c_str());
    std::printf(
        "pass: world boxes + broad phase + collide() per pair (contact of every overlapping pair);\n"
        "      brute = mpr_penetration on every pair, concrete Box<double> (box scene) or one std::visit\n"
        "      per pair (mixed), no bounding-volume test; brute_lanes = the same with MPR's first test run\n"
        "      for %d pairs at once in SIMD lanes (EarlyOut), MPR on the survivors; sap, tree and brute_bounds\n"
        "      run that test on their pairs before collide(); rows: best of up to 5 cold passes\n\n",
        EarlyOut<Real>::width);
}

/// 1. The table: every strategy on the box and the mixed scene, best of up to 5 cold passes; a
/// quadratic strategy past --time-limit is extrapolated, not run.
void strategy_table(const Options& opt, const Sizes& sizes, Results& out) {
    for (const bool mixed : {false, true}) {
        std::printf("%s scene\n", mixed ? "mixed-shape" : "box");
        std::printf("%9s  %-20s %12s %9s %11s %10s %10s\n", "bodies", "strategy", "seconds", "contacts", "broad pairs",
                    "thesis s", "speed-up");
        std::map<Strategy, std::pair<std::size_t, double>> last;  // for the N² extrapolation
        std::vector<std::size_t> ns = sizes.table;
        ns.insert(ns.end(), sizes.large.begin(), sizes.large.end());
        for (const std::size_t n : ns) {
            if (n > opt.max_bodies) continue;
            const Scene<Real> scene = mixed ? make_mixed_scene<Real>(n, opt.seed) : make_box_scene<Real>(n, opt.seed);
            for (const Strategy s : kStrategies) {
                const std::string name = std::string(strategy_name(s)) + (mixed ? "_mixed" : "");
                const bool quadratic = s == Strategy::brute || s == Strategy::brute_lanes || s == Strategy::brute_bounds;
                Row row{n, name, 0, 0, 0, false};
                if (quadratic && last.count(s)) {
                    const double ratio = static_cast<double>(n) / static_cast<double>(last[s].first);
                    const double predicted = last[s].second * ratio * ratio;
                    if (predicted > opt.time_limit) {
                        row.seconds = predicted;
                        row.estimated = true;
                    }
                }
                if (!row.estimated) {
                    const PassResult r = best_cold(s, scene);
                    row.seconds = r.seconds;
                    row.pairs = r.contacts;
                    row.broad_pairs = r.broad_pairs;
                    last[s] = {n, r.seconds};
                    out.rows.push_back(row);
                }
                const double thesis = thesis_seconds(n);
                char thesis_buf[32] = "-", speedup_buf[32] = "-";
                if (!std::isnan(thesis)) {
                    std::snprintf(thesis_buf, sizeof thesis_buf, "%.2f", thesis);
                    std::snprintf(speedup_buf, sizeof speedup_buf, "%.0fx", thesis / row.seconds);
                }
                if (row.estimated)
                    std::printf("%9zu  %-20s %8s est %9s %11s %10s %10s\n", n, name.c_str(), format_seconds(row.seconds).c_str(),
                                "-", "-", thesis_buf, speedup_buf);
                else
                    std::printf("%9zu  %-20s %12s %9zu %11zu %10s %10s\n", n, name.c_str(), format_seconds(row.seconds).c_str(),
                                row.pairs, row.broad_pairs, thesis_buf, speedup_buf);
                std::fflush(stdout);
            }
        }
        std::printf("\n");
    }
}

/// 2. Cold and warm full passes for sap and tree at the large sizes.
void cold_warm_table(const Options& opt, const Sizes& sizes, Results& out) {
    std::printf(
        "cold (first pass, fresh broad phase; best of 3) and warm (after every body moved <= 1 cm and\n"
        "turned <= 0.01 rad; best of 5 frames) full passes, box scene unless stated\n");
    std::printf("%9s  %-6s %-6s %12s %12s %12s %12s %9s\n", "bodies", "scene", "strat", "cold", "cold broad", "warm",
                "warm broad", "contacts");
    for (const std::size_t n : sizes.large) {
        if (n > opt.max_bodies) continue;
        for (const bool mixed : {false, true}) {
            const Scene<Real> scene = mixed ? make_mixed_scene<Real>(n, opt.seed) : make_box_scene<Real>(n, opt.seed);
            for (const Strategy s : {Strategy::sap, Strategy::tree}) {
                const ColdWarm cw = cold_warm(s, scene, false);
                const char* sc = mixed ? "mixed" : "boxes";
                std::printf("%9zu  %-6s %-6s %12s %12s %12s %12s %9zu\n", n, sc, strategy_name(s),
                            format_seconds(best(cw.cold)).c_str(), format_seconds(best(cw.cold_broad)).c_str(),
                            format_seconds(best(cw.warm)).c_str(), format_seconds(best(cw.warm_broad)).c_str(), cw.last.contacts);
                out.details.push_back({sc, n, strategy_name(s), "cold", best(cw.cold), cw.last.contacts});
                out.details.push_back({sc, n, strategy_name(s), "warm", best(cw.warm), cw.last.contacts});
                out.details.push_back({sc, n, strategy_name(s), "cold_broad", best(cw.cold_broad), cw.last.broad_pairs});
                out.details.push_back({sc, n, strategy_name(s), "warm_broad", best(cw.warm_broad), cw.last.broad_pairs});
                std::fflush(stdout);
            }
            // The same sweep and prune pass without the early-out in lanes, for comparison.
            const ColdWarm plain = cold_warm(Strategy::sap, scene, false, 5, {}, false);
            std::printf("%9zu  %-6s %-6s %12s %12s %12s %12s %9zu  (sap without the early-out)\n", n, mixed ? "mixed" : "boxes",
                        "sap-", format_seconds(best(plain.cold)).c_str(), format_seconds(best(plain.cold_broad)).c_str(),
                        format_seconds(best(plain.warm)).c_str(), format_seconds(best(plain.warm_broad)).c_str(),
                        plain.last.contacts);
            out.details.push_back(
                {mixed ? "mixed" : "boxes", n, "sap_no_early_out", "warm", best(plain.warm), plain.last.contacts});
        }
    }
    std::printf("\n");
}

/// 3. The broad phase alone at 1,000,000 boxes (stopped when a cold pass takes over a minute).
void huge_broad_phase(const Options& opt, const Sizes& sizes, Results& out) {
    if (sizes.huge > opt.max_bodies) return;
    std::printf("broad phase alone (world boxes + pairs), %zu boxes\n", sizes.huge);
    const Scene<Real> scene = make_box_scene<Real>(sizes.huge, opt.seed);
    for (const Strategy s : {Strategy::sap, Strategy::tree}) {
        Detector<Real> probe(s);
        const PassResult first = probe.broad_only(scene);
        if (first.seconds > 60) {
            std::printf("  %-5s cold %s: over a minute, not repeated\n", strategy_name(s), format_seconds(first.seconds).c_str());
            out.details.push_back({"boxes", sizes.huge, strategy_name(s), "broad_cold", first.seconds, first.broad_pairs});
            continue;
        }
        const ColdWarm cw = cold_warm(s, scene, true, 3);
        std::printf("  %-5s cold %s (best of %zu), warm %s (best of %zu), %zu box pairs\n", strategy_name(s),
                    format_seconds(best(cw.cold)).c_str(), cw.cold.size(), format_seconds(best(cw.warm)).c_str(), cw.warm.size(),
                    cw.last.broad_pairs);
        out.details.push_back({"boxes", sizes.huge, strategy_name(s), "broad_cold", best(cw.cold), cw.last.broad_pairs});
        out.details.push_back({"boxes", sizes.huge, strategy_name(s), "broad_warm", best(cw.warm), cw.last.broad_pairs});
        std::fflush(stdout);
    }
    std::printf("\n");
}

/// 4. Precision: the thesis's brute force in float as well (the table is double).
void float_brute_force(const Options& opt, const Sizes& sizes, Results& out) {
    const std::size_t nb = std::min<std::size_t>(sizes.table.back(), opt.max_bodies);
    const Scene<float> scene = make_box_scene<float>(nb, opt.seed);
    for (const Strategy strategy : {Strategy::brute, Strategy::brute_lanes}) {
        double best = 1e30;
        std::size_t contacts = 0;
        for (int rep = 0; rep < 3; ++rep) {
            Detector<float> d(strategy);
            const PassResult r = d.pass(scene);
            best = std::min(best, r.seconds);
            contacts = r.contacts;
        }
        const double thesis = thesis_seconds(nb);
        std::printf("%s in float (%d lanes), %zu boxes: %s, %zu contacts", strategy_name(strategy),
                    strategy == Strategy::brute ? 1 : EarlyOut<float>::width, nb, format_seconds(best).c_str(), contacts);
        if (!std::isnan(thesis)) std::printf(", %.0fx the thesis", thesis / best);
        std::printf("\n");
        out.details.push_back({"boxes_float", nb, strategy_name(strategy), "cold", best, contacts});
    }
    std::printf("\n");
}

/// 5. The parallel narrow phase: 1 thread against --threads through the default parallel-for.
void parallel_rows(const Options& opt, const Sizes& sizes, Results& out) {
    if (opt.threads <= 1) return;
    std::printf("parallel narrow phase (xeno::ThreadPool): 1 vs %u threads, best of 3 (sap: of 5 warm frames)\n", opt.threads);
    const std::size_t nb = std::min<std::size_t>(sizes.table.back(), opt.max_bodies);
    const Scene<Real> scene = make_box_scene<Real>(nb, opt.seed);
    for (const unsigned t : {1u, opt.threads}) {
        double best = 1e30;
        for (int rep = 0; rep < 3; ++rep) {
            Detector<Real> d(Strategy::brute, thread_parallel_for(t));
            best = std::min(best, d.pass(scene).seconds);
        }
        std::printf("  brute %zu boxes, %u thread(s): %s\n", nb, t, format_seconds(best).c_str());
        out.details.push_back({"boxes", nb, "brute", "threads" + std::to_string(t), best, 0});
    }
    const std::size_t ns = std::min<std::size_t>(sizes.large.back(), opt.max_bodies);
    const Scene<Real> big = make_box_scene<Real>(ns, opt.seed);
    for (const bool mixed : {false, true}) {
        const Scene<Real> scene_s = mixed ? make_mixed_scene<Real>(ns, opt.seed) : big;
        for (const unsigned t : {1u, opt.threads}) {
            const ColdWarm cw = cold_warm(Strategy::sap, scene_s, false, 5, thread_parallel_for(t));
            std::vector<double> narrow;
            for (std::size_t k = 0; k < cw.warm.size(); ++k) narrow.push_back(cw.warm[k] - cw.warm_broad[k]);
            const char* sc = mixed ? "mixed" : "boxes";
            std::printf("  sap %zu %s warm, %u thread(s): narrow phase %s, whole pass %s\n", ns, sc, t,
                        format_seconds(best(narrow)).c_str(), format_seconds(best(cw.warm)).c_str());
            out.details.push_back({sc, ns, "sap", "narrow_threads" + std::to_string(t), best(narrow), cw.last.contacts});
            out.details.push_back({sc, ns, "sap", "warm_threads" + std::to_string(t), best(cw.warm), cw.last.contacts});
        }
    }
    std::printf("\n");
}

/// 6. Does the tree win anywhere? Warm passes on other distributions.
void tree_against_sap(const Options& opt, const Sizes& sizes, Results& out) {
    const std::size_t n = std::min<std::size_t>(sizes.large.back(), opt.max_bodies);
    std::printf("tree against sweep and prune, %zu bodies: warm full pass / warm broad only / cold full pass (best of 5, 5, 3)\n",
                n);
    struct Workload {
        const char* name;
        Scene<Real> scene;
    };
    std::vector<Workload> loads;
    loads.push_back({"uniform", make_box_scene<Real>(n, opt.seed)});
    loads.push_back({"clustered", make_clustered_scene<Real>(n, 50, opt.seed)});
    loads.push_back({"few_huge", make_few_huge_scene<Real>(n, opt.seed)});
    loads.push_back({"layer", make_layer_scene<Real>(n, opt.seed)});
    for (const Workload& w : loads) {
        std::printf("  %-10s %s\n", w.name, w.scene.description.c_str());
        for (const Strategy s : {Strategy::sap, Strategy::tree}) {
            const ColdWarm full = cold_warm(s, w.scene, false);
            const ColdWarm broad = cold_warm(s, w.scene, true);
            std::printf("    %-5s %12s %12s %12s   %zu box pairs, %zu contacts\n", strategy_name(s),
                        format_seconds(best(full.warm)).c_str(), format_seconds(best(broad.warm)).c_str(),
                        format_seconds(best(full.cold)).c_str(), full.last.broad_pairs, full.last.contacts);
            out.details.push_back({w.name, n, strategy_name(s), "warm", best(full.warm), full.last.contacts});
            out.details.push_back({w.name, n, strategy_name(s), "broad_warm", best(broad.warm), broad.last.broad_pairs});
            out.details.push_back({w.name, n, strategy_name(s), "cold", best(full.cold), full.last.contacts});
            std::fflush(stdout);
        }
    }
    std::printf("\n");
}

/// The gnuplot script that draws n2.png from n2_plot.dat (its columns after bodies and thesis).
void write_plot_script(const Options& opt, const std::vector<std::string>& columns) {
    std::ofstream gp(opt.out + "/n2_plot.gp");
    gp << "# gnuplot script written by xeno_n2_bench: gnuplot n2_plot.gp (run in this folder)\n"
          "set terminal pngcairo size 960,640 noenhanced font ',11'\n"
          "set output 'n2.png'\n"
          "set datafile missing 'NaN'\n"
          "set logscale xy\n"
          "set format x '%g'\n"
          "set format y '%g'\n"
          "set xlabel 'bodies'\n"
          "set ylabel 'seconds per detection pass'\n"
          "set title 'One detection pass: the thesis (Quadro 26, brute-force XenoCollide) and xeno, one thread'\n"
          "set key left top\n"
          "set grid\n"
          "plot 'n2_plot.dat' using 1:2 with linespoints lw 2 pt 7 lc rgb 'black' title 'thesis (brute)'";
    const char* colours[] = {"#d62728", "#9467bd", "#ff7f0e", "#1f77b4", "#2ca02c"};
    for (std::size_t k = 0; k < columns.size(); ++k) {
        const bool mixed = k >= 5;
        gp << ", \\\n     '' using 1:" << (k + 3) << " with linespoints lw 2 pt " << (mixed ? 6 : 5) << " dt " << (mixed ? 2 : 1)
           << " lc rgb '" << colours[k % 5] << "' title 'xeno " << columns[k] << "'";
    }
    gp << "\n";
}

/// 7. The files: the table and the details as CSV, and the plot's data and gnuplot script.
void write_files(const Options& opt, const Results& out) {
    {
        std::ofstream csv(opt.out + "/n2.csv");
        csv << "bodies,strategy,seconds,pairs\n";
        for (const Row& r : out.rows) csv << r.bodies << ',' << r.strategy << ',' << r.seconds << ',' << r.pairs << '\n';
    }
    {
        std::ofstream csv(opt.out + "/n2_details.csv");
        csv << "scene,bodies,strategy,phase,seconds,pairs\n";
        for (const Detail& d : out.details)
            csv << d.scene << ',' << d.bodies << ',' << d.strategy << ',' << d.phase << ',' << d.seconds << ',' << d.pairs
                << '\n';
    }
    const std::vector<std::string> columns = {"brute",     "brute_lanes", "brute_bounds",      "sap",
                                              "tree",      "brute_mixed", "brute_lanes_mixed", "brute_bounds_mixed",
                                              "sap_mixed", "tree_mixed"};
    {
        std::ofstream dat(opt.out + "/n2_plot.dat");
        dat << "# bodies thesis";
        for (const std::string& c : columns) dat << ' ' << c;
        dat << "\n# seconds per detection pass; NaN = not measured\n";
        std::vector<std::size_t> ns;
        for (const Row& r : out.rows) ns.push_back(r.bodies);
        std::sort(ns.begin(), ns.end());
        ns.erase(std::unique(ns.begin(), ns.end()), ns.end());
        for (const std::size_t n : ns) {
            dat << n << ' ' << thesis_seconds(n);
            for (const std::string& c : columns) {
                double v = std::nan("");
                for (const Row& r : out.rows)
                    if (r.bodies == n && r.strategy == c) v = r.seconds;
                dat << ' ' << v;
            }
            dat << '\n';
        }
    }
    write_plot_script(opt, columns);
}

/// n2.png from the gnuplot script, when gnuplot is installed.
void plot(const Options& opt) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
        const std::string cd = "cd " + shell_quote(opt.out) + " && ";
        bool plotted = std::system((cd + "gnuplot n2_plot.gp 2>/dev/null").c_str()) == 0;
        if (!plotted) {
            // No cairo: the libgd png terminal.
            const std::string retry = cd + "sed -i 's/^set terminal pngcairo/set terminal png/' n2_plot.gp && gnuplot n2_plot.gp";
            plotted = std::system(retry.c_str()) == 0;
        }
        if (plotted) std::printf("wrote %s/n2.png\n", opt.out.c_str());
        else std::printf("gnuplot failed: no n2.png\n");
    } else {
        std::printf("gnuplot not on PATH: no n2.png (scripts/setup.sh main installs gnuplot-nox)\n");
    }
}

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse(argc, argv);
    if (opt.lanes) {
        lanes_only(opt);
        return 0;
    }
    if (!make_dir(opt.out)) {
        std::fprintf(stderr, "xeno_n2_bench: cannot create %s\n", opt.out.c_str());
        return 1;
    }
    Sizes sizes;
    if (opt.quick) sizes = {{200, 500, 1000}, {3000}, 20000};
    const auto run_start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    print_header(opt);
    Results out;
    strategy_table(opt, sizes, out);
    cold_warm_table(opt, sizes, out);
    huge_broad_phase(opt, sizes, out);
    float_brute_force(opt, sizes, out);
    parallel_rows(opt, sizes, out);
    tree_against_sap(opt, sizes, out);
    write_files(opt, out);
    const double wall = seconds_since(run_start);
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    std::printf(
        "run: %.1f s wall, %.1f s CPU (this process); load average at end: %s\n"
        "(CPU well under wall in single-threaded sections means other jobs shared the cores)\n",
        wall, cpu, load_average().c_str());
    std::printf("wrote %s/n2.csv, %s/n2_details.csv, %s/n2_plot.dat, %s/n2_plot.gp\n", opt.out.c_str(), opt.out.c_str(),
                opt.out.c_str(), opt.out.c_str());
    plot(opt);
    return 0;
}

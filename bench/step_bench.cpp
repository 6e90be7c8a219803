// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_step_bench: milliseconds per World::step for the dynamics issue's scenes, float and
// double, one thread, with the contacts solved per step; whether the 5,050-box pyramid stands
// after 10 s (no box's centre more than a quarter box from where it was placed) and its top's sag;
// and memory per body and per touching pair measured by a counting allocator (every heap byte
// the world allocates, container slack included), beside the thesis's Quadro 25. Built with
// Bullet (XENO_HAVE_BULLET, bench/CMakeLists.txt), each pyramid also runs in Bullet and its row
// and xeno float's time over Bullet's print under xeno's float row (bullet_peer.hpp).
//
//   xeno_step_bench [--quick] [--workers N]
//     --quick: fewer steps and no 5,050-box pyramid
//     --workers N: instead, each scene on 1 and on N workers (the world's ThreadPool) in this
//                  process, ms per step and per stage with the speed-up, and whether both ended
//                  in the same bits, between two measures of how far apart the cores are
//                  (one atomic's round trip between two threads; docs/parallel.md)
#include "bullet_peer.hpp"
#include "scenes/piles.hpp"
#include "scenes/random.hpp"
#include "scenes/stacks.hpp"

#include <xeno/dynamics/world.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <string>
#include <thread>
#include <vector>
#include <utility>

// The counting allocator: every operator new/delete of this program goes through it.
namespace {
std::atomic<long long> g_heap_bytes{0};
}  // namespace

void* operator new(std::size_t size) {
    void* p = std::malloc(size + 16);
    if (!p) throw std::bad_alloc();
    *static_cast<std::size_t*>(p) = size;
    g_heap_bytes += static_cast<long long>(size);
    return static_cast<char*>(p) + 16;
}
void operator delete(void* p) noexcept {
    if (!p) return;
    char* base = static_cast<char*>(p) - 16;
    g_heap_bytes -= static_cast<long long>(*reinterpret_cast<std::size_t*>(base));
    std::free(base);
}
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }

using namespace xeno;

namespace {

using clock_type = std::chrono::steady_clock;

template <class T>
const char* precision() {
    return std::is_same_v<T, float> ? "float" : "double";
}

struct Timing {
    double ms_per_step;
    double contacts_per_step;
    double points_per_step;
};

template <class T>
Timing time_steps(World<T>& world, int steps) {
    double contacts = 0, points = 0;
    const auto start = clock_type::now();
    for (int i = 0; i < steps; ++i) {
        world.step(T(1) / T(60));
        contacts += double(world.last_step_stats().contacts);
        points += double(world.last_step_stats().contact_points);
    }
    const double ms = std::chrono::duration<double, std::milli>(clock_type::now() - start).count();
    return {ms / steps, contacts / steps, points / steps};
}

template <class T>
WorldSettings<T> no_sleep() {
    WorldSettings<T> s;
    s.allow_sleeping = false;
    return s;
}

/// One pyramid run's numbers, xeno's or Bullet's.
struct PyramidRun {
    std::size_t boxes;
    Timing timing;
    double worst_move;  ///< m: the largest distance of a box's centre from where it was placed
    double top_sag;     ///< m: how far the top box's centre went down
};

/// `engine`: xeno's precision, or "bullet". One layout for both, so the rows line up.
void print_pyramid_row(int base, const char* engine, const PyramidRun& r, int steps) {
    std::printf(
        "pyramid-%-4d %6zu boxes %-6s %8.2f ms/step %7.0f contacts %7.0f points | after %4.1f s: worst move %.3f m, top sag %.4f "
        "m%s\n",
        base, r.boxes, engine, r.timing.ms_per_step, r.timing.contacts_per_step, r.timing.points_per_step, steps / 60.0,
        r.worst_move, r.top_sag, base == 100 ? (r.worst_move < 0.25 ? "  (stands: < 0.25)" : "  (FAILS: >= 0.25)") : "");
}

/// Runs and prints xeno's row for the pyramid; returns its ms/step (for the Bullet ratio).
template <class T>
double pyramid_row(int base, int steps) {
    World<T> world(no_sleep<T>());
    const scenes::Scene scene = scenes::pyramid(world, base);
    std::vector<Vec3<T>> placed;
    for (BodyId id : scene.bodies) placed.push_back(world.body(id).position());
    const Timing t = time_steps(world, steps);
    double worst = 0;
    for (std::size_t i = 0; i < placed.size(); ++i)
        worst = std::max(worst, double(length(world.body(scene.bodies[i]).position() - placed[i])));
    const double sag = double(placed.back().y - world.body(scene.bodies.back()).position().y);
    print_pyramid_row(base, precision<T>(), {scene.bodies.size(), t, worst, sag}, steps);
    return t.ms_per_step;
}

/// Bullet's row for the same pyramid, then xeno float's time over Bullet's. Does nothing when
/// the bench was built without Bullet.
void bullet_pyramid_row([[maybe_unused]] int base, [[maybe_unused]] int steps, [[maybe_unused]] double xeno_float_ms) {
#if XENO_HAVE_BULLET
    const Vec3<float> g = WorldSettings<float>{}.gravity;  // xeno's default, so both pyramids weigh the same
    const bullet_peer::PyramidRun b = bullet_peer::run_pyramid(base, steps, btVector3(g.x, g.y, g.z));
    print_pyramid_row(base, "bullet", {b.boxes, {b.ms_per_step, b.contacts_per_step, b.points_per_step}, b.worst_move, b.top_sag},
                      steps);
    if (b.missed_steps > 0) std::printf("  (Bullet ran %d of its %d steps with other than one substep)\n", b.missed_steps, steps);
    std::printf("  xeno float / Bullet: %.2f%s\n", xeno_float_ms / b.ms_per_step,
                base == 20 ? " (issue goal for the 210 pyramid: <= 0.52)" : "");
#endif
}

/// xeno float, Bullet beside it, then xeno double.
void pyramid_rows(int base, int steps) {
    const double xeno_float_ms = pyramid_row<float>(base, steps);
    bullet_pyramid_row(base, steps, xeno_float_ms);
    pyramid_row<double>(base, steps);
}

template <class T>
void drop_row(int n, int steps) {
    World<T> world(no_sleep<T>());
    scenes::dropped_boxes(world, n);
    const Timing t = time_steps(world, steps);
    std::printf("drop-%-7d %6d boxes %-6s %8.2f ms/step %7.0f contacts %7.0f points | over %.1f s of falling and settling\n", n,
                n, precision<T>(), t.ms_per_step, t.contacts_per_step, t.points_per_step, steps / 60.0);
}

/// Issue "game features": a settled pile asleep against the same pile kept awake. Steps with
/// sleeping on until every island sleeps (at most 30 s), times 60 steps, then wakes every body,
/// turns sleeping off and times 60 more. `block`: 4,000 boxes resting in 20 × 20 columns of 10
/// (settled from the start); otherwise the bodies of scenes::dropped_boxes() after their fall.
template <class T>
void sleep_row(int n, bool block) {
    WorldSettings<T> settings;
    World<T> world(settings);
    std::vector<BodyId> ids;
    if (block) {
        scenes::add_ground(world, T(100));
        const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
        const int side = 20, height = n / (side * side);
        for (int i = 0; i < side * side * height; ++i) {
            BodyDef<T> def;
            def.position = {T(1.01) * T(i % side), T(0.5) + T(i / (side * side)), T(1.01) * T((i / side) % side)};
            ids.push_back(world.create_body(box, def));
        }
    } else {
        ids = scenes::dropped_boxes(world, n).bodies;
    }
    int settle = 0;
    for (; settle < 1800; ++settle) {
        world.step(T(1) / T(60));
        if (world.last_step_stats().awake_bodies == 0) break;
    }
    const std::size_t still_awake = world.last_step_stats().awake_bodies;
    const Timing asleep = time_steps(world, 60);
    settings.allow_sleeping = false;
    world.set_settings(settings);
    for (BodyId id : ids) world.body(id).wake();
    const Timing awake = time_steps(world, 60);
    std::printf("%-6s %5zu boxes %-6s %s %5.1f s: %7.3f ms/step then, %7.2f ms/step awake (%5.1f %%; goal < 10 %%)\n",
                block ? "block" : "pile", ids.size(), precision<T>(),
                still_awake == 0 ? "all asleep after" : "NOT all asleep at ", settle / 60.0, asleep.ms_per_step,
                awake.ms_per_step, 100.0 * asleep.ms_per_step / awake.ms_per_step);
    if (still_awake > 0)
        std::printf("       (%zu bodies in islands still awake: the pile is one island and some box in it keeps moving)\n",
                    still_awake);
}

template <class T>
void memory_row(int n) {
    // Bodies: n boxes sharing one shape, apart in the air (no contacts). Persistent = the world's
    // state between steps; during a step the solver's per-body scratch comes on top.
    const long long before = g_heap_bytes;
    long long persistent = 0, stepping = 0, with_pairs = 0;
    std::size_t touching = 0;
    const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
    const long long shape_bytes = g_heap_bytes - before;
    {
        WorldSettings<T> s = no_sleep<T>();
        s.gravity = Vec3<T>::zero();
        World<T> world(s);
        world.reserve(std::size_t(n));
        const int side = static_cast<int>(std::ceil(std::cbrt(double(n))));
        for (int i = 0; i < n; ++i) {
            BodyDef<T> def;
            def.position = {T(3) * T(i % side), T(3) * T((i / side) % side), T(3) * T(i / (side * side))};
            world.create_body(box, def);
        }
        persistent = g_heap_bytes - before - shape_bytes;
        world.step(T(1) / T(60));
        stepping = g_heap_bytes - before - shape_bytes;
    }
    {
        // Touching pairs: a row of n boxes each pressed 1 mm into the next, no gravity.
        WorldSettings<T> s = no_sleep<T>();
        s.gravity = Vec3<T>::zero();
        World<T> world(s);
        world.reserve(std::size_t(n), std::size_t(n));
        for (int i = 0; i < n; ++i) {
            BodyDef<T> def;
            def.position = {T(0.999) * T(i), T(0), T(0)};
            world.create_body(box, def);
        }
        world.step(T(1) / T(60));
        with_pairs = g_heap_bytes - before - shape_bytes;
        for (const Contact<T>& c : world.contacts()) touching += c.touching ? 1 : 0;
    }
    const double pair_persistent = double(sizeof(Contact<T>) + sizeof(ProxyPair));
    const double pair_stepping = touching > 0 ? double(with_pairs - stepping) / double(touching) : 0.0;
    std::printf(
        "%8d bodies %-6s %9.1f KB | %5.0f bytes/body between steps, %5.0f during a step | %7zu pairs: %4.0f bytes/pair kept, "
        "%5.0f during a step\n",
        n, precision<T>(), double(stepping) / 1024, double(persistent) / n, double(stepping) / n, touching, pair_persistent,
        pair_stepping);
}

/// Milliseconds per step of each stage, summed over a run (StepStats::seconds).
struct StageTimes {
    static constexpr int count = 10;
    static constexpr const char* names[count] = {"bounds", "broad",  "narrow", "wake",    "prepare",
                                                 "solve",  "finish", "sleep",  "queries", "events"};
    double ms[count] = {};
    double total = 0;
    template <class Times>
    void add(const Times& t) {
        const double s[count] = {t.bounds, t.broad, t.narrow, t.wake, t.prepare, t.solve, t.finish, t.sleep, t.queries, t.events};
        for (int i = 0; i < count; ++i) ms[i] += 1000 * s[i];
    }
};

/// Every body's position and orientation as raw bits, folded (FNV-1a): equal runs, equal values.
template <class T>
std::uint64_t pose_bits(const World<T>& world) {
    std::uint64_t h = 1469598103934665603ull;
    world.for_each_body([&](BodyId, const Body<T>& b) {
        const T v[7] = {b.position().x,    b.position().y,    b.position().z,   b.orientation().w,
                        b.orientation().x, b.orientation().y, b.orientation().z};
        unsigned char bytes[sizeof v];
        std::memcpy(bytes, v, sizeof v);
        for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    });
    return h;
}

/// One scene on `workers` workers: stage times per step and the final pose bits.
template <class T, class Build>
std::pair<StageTimes, std::uint64_t> run_on_workers(const Build& build, int steps, unsigned workers) {
    World<T> world(no_sleep<T>());
    build(world);
    world.set_workers(workers);
    StageTimes t;
    const auto start = clock_type::now();
    for (int i = 0; i < steps; ++i) {
        world.step(T(1) / T(60));
        t.add(world.last_step_stats().seconds);
    }
    t.total = std::chrono::duration<double, std::milli>(clock_type::now() - start).count() / steps;
    for (double& ms : t.ms) ms /= steps;
    return {t, pose_bits(world)};
}

template <class T, class Build>
void workers_row(const char* scene, const Build& build, int steps, unsigned workers) {
    const auto [one, bits_one] = run_on_workers<T>(build, steps, 1);
    const auto [many, bits_many] = run_on_workers<T>(build, steps, workers);
    std::printf("%-12s %-6s 1 worker %8.2f ms/step, %u workers %8.2f ms/step: %.2fx  (same bits: %s)\n", scene, precision<T>(),
                one.total, workers, many.total, one.total / many.total, bits_one == bits_many ? "yes" : "NO");
    std::printf("  %-8s", "stage");
    for (const char* name : StageTimes::names) std::printf(" %8s", name);
    std::printf("\n  %-8s", "1 (ms)");
    for (double ms : one.ms) std::printf(" %8.3f", ms);
    std::printf("\n  %-2u%-6s", workers, " (ms)");
    for (double ms : many.ms) std::printf(" %8.3f", ms);
    std::printf("\n  %-8s", "speed-up");
    for (int i = 0; i < StageTimes::count; ++i) std::printf(" %7.2fx", many.ms[i] > 0 ? one.ms[i] / many.ms[i] : 0.0);
    std::printf("\n");
}

/// ns for one atomic to go from this thread to another and back (the median of 5 runs of
/// 100,000): what a cache line written by the other core costs to read. On a virtual machine it
/// moves with where the hypervisor places the two cores, and the speed-up of the rows below with
/// it (docs/parallel.md, "Each worker keeps to its bodies").
double core_round_trip_ns() {
    constexpr int trips = 100000;
    std::vector<double> runs;
    for (int run = 0; run < 5; ++run) {
        alignas(64) std::atomic<int> flag{0};
        std::thread echo([&] {
            for (int i = 0; i < trips; ++i) {
                while (flag.load(std::memory_order_acquire) != 2 * i + 1) {
                }
                flag.store(2 * i + 2, std::memory_order_release);
            }
        });
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < trips; ++i) {
            flag.store(2 * i + 1, std::memory_order_release);
            while (flag.load(std::memory_order_acquire) != 2 * i + 2) {
            }
        }
        runs.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / trips);
        echo.join();
    }
    std::sort(runs.begin(), runs.end());
    return runs[runs.size() / 2];
}

void workers_table(unsigned workers, bool quick) {
    const int steps = quick ? 60 : 300;
    std::printf(
        "World::step on 1 and %u workers (World::set_workers), 60 Hz, %d steps each, default settings, no sleeping;\n"
        "this machine has %u hardware threads; a round trip of one atomic between two threads takes %.0f ns\n",
        workers, steps, std::thread::hardware_concurrency(), core_round_trip_ns());
    for (int base : {20, 40, 100}) {
        if (quick && base == 100) break;
        const std::string name = "pyramid-" + std::to_string(base);
        workers_row<float>(
            name.c_str(), [&](World<float>& w) { scenes::pyramid(w, base); }, steps, workers);
        if (base == 100)
            workers_row<double>(
                name.c_str(), [&](World<double>& w) { scenes::pyramid(w, base); }, steps, workers);
    }
    for (int n : {1000, 4000}) {
        const std::string name = "drop-" + std::to_string(n);
        workers_row<float>(
            name.c_str(), [&](World<float>& w) { scenes::dropped_boxes(w, n); }, steps, workers);
        if (n == 4000)
            workers_row<double>(
                name.c_str(), [&](World<double>& w) { scenes::dropped_boxes(w, n); }, steps, workers);
    }
    std::printf("after the rows, a round trip between two threads takes %.0f ns\n", core_round_trip_ns());
}

void memory_table(bool quick) {
    std::printf(
        "\nMemory (counting allocator, world.reserve() called; bodies share one shape). 'Between steps' is the\n"
        "world's state; 'during a step' adds the solver's scratch (per awake body and per manifold).\n");
    std::printf("thesis (Quadro 25): 1,274 bytes/body, 380 bytes/touching pair\n");
    for (int n : {10, 100, 1000, 10000, 100000}) {
        if (quick && n > 10000) break;
        memory_row<float>(n);
        memory_row<double>(n);
    }
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false, piles = false, memory = false;
    unsigned workers = 0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) quick = true;
        else if (std::strcmp(argv[i], "--piles") == 0) piles = true;
        else if (std::strcmp(argv[i], "--memory") == 0) memory = true;
        else if (std::strcmp(argv[i], "--workers") == 0 && i + 1 < argc) {
            const long n = std::strtol(argv[++i], nullptr, 10);
            if (n < 2 || n > 256) {
                std::fprintf(stderr, "xeno_step_bench: --workers takes 2 to 256\n");
                return 2;
            }
            workers = static_cast<unsigned>(n);
        } else if (std::strcmp(argv[i], "--help") == 0) {
            std::printf(
                "usage: xeno_step_bench [--quick] [--workers N] [--piles] [--memory]\n"
                "  --memory: only the memory table\n"
                "  --piles: only the dropped piles of 500 to 4,000 boxes, stepped until they sleep (docs/features.md)\n");
            return 0;
        } else {
            std::fprintf(stderr, "xeno_step_bench: unknown option '%s' (try --help)\n", argv[i]);
            return 2;
        }
    }
    if (workers > 0) {
        workers_table(workers, quick);
        return 0;
    }
    if (memory) {
        memory_table(quick);
        return 0;
    }
    if (piles) {  // how long dropped piles take to fall asleep (docs/features.md, "Rocking in place")
        for (int n : {500, 1000, 2000, 4000}) sleep_row<float>(n, false);
        return 0;
    }
    const int steps = quick ? 60 : 600;  // 10 s at 60 Hz
    std::printf("World::step, one thread, 60 Hz, %d steps each, default settings (soft step, %d substeps), no sleeping\n", steps,
                xeno::WorldSettings<float>{}.substeps);
#if XENO_HAVE_BULLET
    std::printf(
        "Bullet %d.%02d beside xeno float: btDiscreteDynamicsWorld with its defaults (10 solver iterations), one 1/60 s\n"
        "substep per step, no deactivation; friction 0.6 per body, which Bullet combines to 0.36 per pair (xeno: 0.6)\n",
        btGetVersion() / 100, btGetVersion() % 100);
#endif
    for (int base : {20, 40}) pyramid_rows(base, steps);
    if (!quick) pyramid_rows(100, steps);
    for (int n : {1000, 4000}) {
        drop_row<float>(n, quick ? 60 : 300);
        drop_row<double>(n, quick ? 60 : 300);
    }
    std::printf(
        "\nSleeping: a settled pile steps asleep, then woken with sleeping off (block: resting columns; pile: dropped)\n");
    for (const bool block : {true, false}) {
        sleep_row<float>(quick ? 400 : 4000, block);
        sleep_row<double>(quick ? 400 : 4000, block);
    }
    memory_table(quick);
    return 0;
}

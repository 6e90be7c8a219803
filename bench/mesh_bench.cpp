// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_mesh_bench: what level geometry costs (docs/meshes.md), float and double, one thread.
//   1. 1,000 unit boxes settling on a 100 × 100 m terrain of 20,000 triangles, as a HeightField
//      and as a TriangleMesh of the same triangles, beside the same boxes on a flat box floor:
//      ms per step and the ratio to the floor (the goal: a mesh costs at most 1.5× the
//      floor). The three grounds step in turn in this one process, so the ratios hold on a
//      busy machine.
//      The contacts and points of the last step are printed so the work can be compared: a
//      mesh that found fewer contacts would look cheap for the wrong reason.
//   2. A box against one triangle, by the separating-axis test the meshes use and by MPR (the
//      issue asks for both to be measured): ns per pair.
//   3. TriangleMesh construction for about a million triangles (goal < 1 s) and its memory per
//      triangle, the hierarchy alone and with the vertices.
//   4. Rays straight down onto the terrain, per second (HeightField and TriangleMesh raycast).
//
//   xeno_mesh_bench [--quick]
//     --quick: 60 steps, 10,000 box-triangle pairs, a 20,000-triangle build and 10,000 rays (a smoke test)
#include "scenes/random.hpp"

#include <xeno/xeno.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

using namespace xeno;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

template <class T>
const char* precision() {
    return std::is_same_v<T, float> ? "float" : "double";
}

// The "model name" of /proc/cpuinfo and the load average: what the times below were taken on.
std::string machine() {
    std::ifstream cpu("/proc/cpuinfo"), load("/proc/loadavg");
    std::string line, model = "unknown CPU", one = "?", five = "?";
    while (std::getline(cpu, line))
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    load >> one >> five;
    return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads, load average " + one +
           " (1 min), " + five + " (5 min)";
}

/// A square grid of samples 1 m apart, laid out as HeightField lays out its own (centred on the
/// origin, heights[j * samples + i] at x = i − half, z = j − half).
template <class T>
struct Grid {
    std::uint32_t samples;
    std::vector<T> heights;

    T x(std::uint32_t i) const { return static_cast<T>(i) - T(0.5) * static_cast<T>(samples - 1); }
    /// The heightfield's triangles, wound as it winds them: cell (i, j) is (p00, p01, p11) and
    /// (p00, p11, p10), p01 = sample (i, j + 1), counter-clockwise seen from +y.
    TriangleMesh<T> mesh() const {
        std::vector<Vec3<T>> v;
        v.reserve(heights.size());
        for (std::uint32_t j = 0; j < samples; ++j)
            for (std::uint32_t i = 0; i < samples; ++i) v.push_back({x(i), heights[j * samples + i], x(j)});
        return TriangleMesh<T>(std::move(v), triangles());
    }
    std::vector<std::array<std::uint32_t, 3>> triangles() const {
        std::vector<std::array<std::uint32_t, 3>> t;
        t.reserve(2 * std::size_t(samples - 1) * (samples - 1));
        for (std::uint32_t j = 0; j + 1 < samples; ++j)
            for (std::uint32_t i = 0; i + 1 < samples; ++i) {
                const std::uint32_t p00 = j * samples + i, p10 = p00 + 1, p01 = p00 + samples, p11 = p01 + 1;
                t.push_back({p00, p01, p11});
                t.push_back({p00, p11, p10});
            }
        return t;
    }
};

/// Gentle hills, 0.5 sin(x/7) cos(z/9): never flat, so the boxes meet tilted triangles and
/// their edges, not one plane.
template <class T>
Grid<T> hills(std::uint32_t samples) {
    Grid<T> g{samples, std::vector<T>(std::size_t(samples) * samples)};
    for (std::uint32_t j = 0; j < samples; ++j)
        for (std::uint32_t i = 0; i < samples; ++i)
            g.heights[j * samples + i] = T(0.5) * std::sin(g.x(i) / T(7)) * std::cos(g.x(j) / T(9));
    return g;
}

enum class Ground { box_floor, height_field, triangle_mesh };
const char* ground_names[] = {"box floor", "heightfield", "triangle mesh"};

/// One ground's world, the boxes on it and the time of each of its steps.
template <class T>
struct Scene {
    std::unique_ptr<World<T>> world;
    std::vector<BodyId> boxes;
    std::vector<double> ms;
};

/// A 10 × 10 × 10 block of unit boxes, 1.5 m apart, bottom layer 1.5 m above y = 0 (the hills
/// reach 0.5 m), over `ground`. Turned at random (the same turns on every ground), as
/// step_bench's drops are: upright boxes would land as 100 columns, and only 100 boxes would
/// ever touch the ground. Sleeping is off, so every step does the same work.
template <class T>
Scene<T> drop_scene(Ground ground, const Grid<T>& grid) {
    WorldSettings<T> settings;
    settings.allow_sleeping = false;
    Scene<T> s{std::make_unique<World<T>>(settings), {}, {}};
    BodyDef<T> fixed;
    fixed.type = BodyType::static_body;
    if (ground == Ground::height_field)
        s.world->create_body(HeightField<T>(grid.samples, grid.samples, grid.heights, T(1)), fixed);
    else if (ground == Ground::triangle_mesh) s.world->create_body(grid.mesh(), fixed);
    else {
        fixed.position = {T(0), T(-0.5), T(0)};  // top face at y = 0
        s.world->create_body(Box<T>(T(50), T(0.5), T(50)), fixed);
    }
    const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
    scenes::Random rng(3);
    for (int k = 0; k < 1000; ++k) {
        BodyDef<T> def;
        def.orientation = rng.rotation<T>();
        def.position = {T(1.5) * T(k % 10 - 5) + T(0.75), T(1.5) + T(1.5) * T(k / 100), T(1.5) * T(k / 10 % 10 - 5) + T(0.75)};
        s.boxes.push_back(s.world->create_body(box, def));
    }
    return s;
}

/// Prints the median of the steady part (the second half of the steps) and the mean of all;
/// returns the median.
template <class T>
double print_row(Ground ground, const Scene<T>& s, double floor_ms) {
    double mean = 0;
    for (double m : s.ms) mean += m / double(s.ms.size());
    std::vector<double> steady(s.ms.begin() + std::ptrdiff_t(s.ms.size() / 2), s.ms.end());
    std::nth_element(steady.begin(), steady.begin() + std::ptrdiff_t(steady.size() / 2), steady.end());
    const double median = steady[steady.size() / 2];
    std::size_t fell = 0;
    for (BodyId id : s.boxes) fell += s.world->body(id).position().y < T(-1) ? 1 : 0;  // through the ground
    const StepStats& stats = s.world->last_step_stats();
    std::printf("  %-13s %-6s %8.3f ms/step median %8.3f mean %6zu contacts %6zu points %4zu fell through",
                ground_names[int(ground)], precision<T>(), median, mean, stats.contacts, stats.contact_points, fell);
    if (ground == Ground::box_floor) std::printf("\n");
    else std::printf("  %.2fx the floor (<= 1.5x: goal %s)\n", median / floor_ms, median / floor_ms <= 1.5 ? "met" : "missed");
    return median;
}

/// The three grounds step in turn, one step each, so a burst of other work on a shared machine
/// lands on all three alike and the ratios hold.
template <class T>
void settle_rows(int steps) {
    const Grid<T> grid = hills<T>(101);
    const TriangleMesh<T> mesh = grid.mesh();
    std::printf("%-6s terrain memory: heightfield %.1f KB, triangle mesh %.1f KB (%zu triangles, %zu dropped)\n", precision<T>(),
                double(HeightField<T>(101, 101, grid.heights, T(1)).memory_bytes()) / 1024, double(mesh.memory_bytes()) / 1024,
                mesh.size(), mesh.dropped_triangles());
    const Ground grounds[3] = {Ground::box_floor, Ground::height_field, Ground::triangle_mesh};
    Scene<T> runs[3] = {drop_scene(grounds[0], grid), drop_scene(grounds[1], grid), drop_scene(grounds[2], grid)};
    for (int step = 0; step < steps; ++step)
        for (Scene<T>& s : runs) {
            const auto start = Clock::now();
            s.world->step(T(1) / T(60));
            s.ms.push_back(1000 * seconds_since(start));
        }
    const double floor_ms = print_row(grounds[0], runs[0], 0.0);
    for (int g = 1; g < 3; ++g) print_row(grounds[g], runs[g], floor_ms);
}

/// `cells` × `cells` cells of random heights (0 … 2 m, 1 m apart): a rough terrain whose every
/// triangle is tilted, so the build's adjacency marks edges both ways.
template <class T>
void build_row(std::uint32_t cells, int runs) {
    Grid<T> grid{cells + 1, {}};
    scenes::Random rng(7);
    for (std::uint32_t k = 0; k < grid.samples * grid.samples; ++k) grid.heights.push_back(rng.uniform(T(0), T(2)));
    const TriangleMesh<T> first = grid.mesh();  // for the sizes; the timed builds follow
    const std::vector<std::array<std::uint32_t, 3>> tris = grid.triangles();
    // CPU seconds of this process, as hull_bench times: a busy machine adds less to them than
    // to wall time (the best wall time is printed beside).
    double best = 1e300, best_wall = 1e300;
    for (int r = 0; r < runs; ++r) {
        std::vector<Vec3<T>> v = first.vertices();  // the constructor takes them by value
        const std::clock_t cpu = std::clock();
        const auto start = Clock::now();
        const TriangleMesh<T> mesh(std::move(v), tris);
        best_wall = std::min(best_wall, seconds_since(start));
        best = std::min(best, double(std::clock() - cpu) / CLOCKS_PER_SEC);
    }
    const double n = double(first.size());
    const double vertex_bytes = double(first.vertices().capacity() * sizeof(Vec3<T>));
    std::printf(
        "  %-6s %zu triangles (%zu dropped): %.3f s CPU (%.3f s wall), best of %d (< 1 s: goal %s); %.1f bytes/triangle, "
        "%.1f with the vertices\n",
        precision<T>(), first.size(), first.dropped_triangles(), best, best_wall, runs, best < 1 ? "met" : "missed",
        (double(first.memory_bytes()) - vertex_bytes) / n, double(first.memory_bytes()) / n);
}

/// Rays from 5 m up, straight down, at random points over the hills; every one should hit.
template <class T, class Terrain>
void ray_row(const char* name, const Terrain& terrain, int n) {
    scenes::Random rng(11);
    std::vector<Ray<T>> rays(static_cast<std::size_t>(n));
    for (Ray<T>& r : rays)
        r = {{rng.uniform(T(-49.5), T(49.5)), T(5), rng.uniform(T(-49.5), T(49.5))}, {T(0), T(-1), T(0)}, T(10)};
    int hits = 0;
    const auto start = Clock::now();
    for (const Ray<T>& r : rays) hits += terrain.raycast(r) ? 1 : 0;
    const double s = seconds_since(start);
    std::printf("  %-13s %-6s %10.0f rays/s (%.3f us/ray), %d of %d hit\n", name, precision<T>(), n / s, 1e6 * s / n, hits, n);
}

template <class T>
void ray_rows(int n) {
    const Grid<T> grid = hills<T>(101);
    ray_row<T>("heightfield", HeightField<T>(101, 101, grid.heights, T(1)), n);
    ray_row<T>("triangle mesh", grid.mesh(), n);
}

/// A box against one triangle, the two ways the narrow phase can answer it: the closed-form
/// separating-axis test the meshes use (box_triangle.hpp) and MPR with its least-depth expansion
/// and normal refinement (what every other convex shape takes). The pairs are the hills'
/// triangles and unit boxes at random turns whose lowest corner (along the triangle's normal) is
/// over a point of the triangle, from 5 cm into it to 2 cm above (a 2 cm margin): every pair a
/// contact, through a face, an edge or a corner.
template <class T>
void pair_rows(int n) {
    const Grid<T> grid = hills<T>(101);
    const TriangleMesh<T> mesh = grid.mesh();
    const Box<T> box(T(0.5), T(0.5), T(0.5));
    scenes::Random rng(5);
    std::vector<std::pair<MeshTriangle<T>, Transform<T>>> pairs;
    for (int k = 0; k < n; ++k) {
        const MeshTriangle<T>& t = mesh.triangle(rng.index(static_cast<std::uint32_t>(mesh.size())));
        const T a = rng.uniform(T(0), T(1)), b = rng.uniform(T(0), T(1) - a);
        const Vec3<T> on = t.v[0] + (t.v[1] - t.v[0]) * a + (t.v[2] - t.v[0]) * b;
        const Quat<T> turn = rng.rotation<T>();
        const Vec3<T> lowest = rotate(turn, box.support(inverse_rotate(turn, -t.normal)));  // from the centre
        pairs.push_back({t, {on - lowest + t.normal * rng.uniform(T(-0.05), T(0.02)), turn}});
    }
    const T margin = T(0.02);
    const auto time = [&](auto&& answer) {
        int hits = 0;
        const auto start = Clock::now();
        for (const auto& [t, pose] : pairs) {
            const Triangle<T> tri(t, detail::closest_point_on_triangle(pose.position, t.v[0], t.v[1], t.v[2]));
            const MinkowskiDifference<Triangle<T>, Box<T>> md(tri, Transform<T>{}, box, pose, margin);
            Vec3<T> normal, pa, pb;
            T h;
            hits += answer(md, normal, h, pa, pb) ? 1 : 0;
        }
        return std::make_pair(1e9 * seconds_since(start) / double(pairs.size()), hits);
    };
    const auto [sat_ns, sat_hits] = time([](const auto& md, auto& normal, auto& h, auto& pa, auto& pb) {
        return detail::box_triangle_axis(md, normal, h, pa, pb);
    });
    const auto [mpr_ns, mpr_hits] = time(
        [](const auto& md, auto& normal, auto& h, auto& pa, auto& pb) { return detail::refined_contact(md, normal, h, pa, pb); });
    std::printf("  %-6s separating axes %6.1f ns/pair, MPR %6.1f ns/pair: %.2fx; %d and %d of %zu within the margin\n",
                precision<T>(), sat_ns, mpr_ns, mpr_ns / sat_ns, sat_hits, mpr_hits, pairs.size());
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) quick = true;
        else if (std::strcmp(argv[i], "--help") == 0) {
            std::printf("usage: xeno_mesh_bench [--quick]\n");
            return 0;
        } else {
            std::fprintf(stderr, "xeno_mesh_bench: unknown option '%s' (try --help)\n", argv[i]);
            return 2;
        }
    }
    const int steps = quick ? 60 : 300;
    std::printf("machine: %s; one thread\n", machine().c_str());
#ifdef XENO_ENABLE_ASSERTS
    std::printf("build: xeno's assertions on (no NDEBUG): times are not representative\n");
#endif
    std::printf(
        "\n1,000 boxes settling on a 100 × 100 m heightfield (20,000 triangles), the same triangles as a mesh, and a box floor:\n"
        "%d steps at 60 Hz, default settings, no sleeping, the three grounds stepped in turn; median ms/step of steps\n"
        "%d-%d (the pile settling), mean of all; contacts and points of the last step\n",
        steps, steps / 2 + 1, steps);
    settle_rows<float>(steps);
    settle_rows<double>(steps);

    const int pair_count = quick ? 10000 : 200000;
    std::printf("\nA unit box against one triangle of the hills (its lowest corner 5 cm into it to 2 cm above; 2 cm margin)\n");
    pair_rows<float>(pair_count);
    pair_rows<double>(pair_count);

    const std::uint32_t cells = quick ? 100 : 708;
    std::printf("\nBVH build for %s triangles (%u × %u cells of random heights), TriangleMesh constructor\n",
                quick ? "20,000" : "1,000,000", cells, cells);
    build_row<float>(cells, quick ? 1 : 3);
    build_row<double>(cells, quick ? 1 : 3);

    const int rays = quick ? 10000 : 100000;
    std::printf("\nRays straight down onto the hills (the shapes' own raycast, no world)\n");
    ray_rows<float>(rays);
    ray_rows<double>(rays);
    return 0;
}

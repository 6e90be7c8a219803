// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_hull_bench: seconds to build the convex hull (make_convex_hull, whose ConvexPolyhedron
// construction and re-centring are included) of n points on a unit sphere (every point a hull
// vertex: the worst case) and uniform in a unit ball, n = 1k … 100k doubling, float and double;
// and the ratio t(2n) / t(n), which is 2 for linear cost, a little more for n log n and 4 for
// quadratic (issue 13 item 13: 100k points on a sphere took over a minute, now under 2 s).
// Each time is the best of several runs, in CPU seconds of this process (a busy machine adds
// less to those than to wall time).
//
// Then the support search on hulls of 8 … 256 points on a sphere (issue 19: which wins by vertex
// count): the scan in SIMD lanes (support_index_scan) against hill climbing from the previous
// answer (directions turning slowly, as inside one MPR query) and from the axis-extreme start
// vertex (a fresh query: what support() climbs from above hill_climb_threshold vertices).
//
//   xeno_hull_bench [--quick] [--max N]    (--quick: up to 16k points, one run each)
#include "scenes/random.hpp"

#include <xeno/shape/convex_hull.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

namespace {

using xeno::Vec3;

/// n points on the unit sphere (on_sphere) or uniform in the unit ball; seeded, so every run
/// times the same clouds.
template <class T>
std::vector<Vec3<T>> cloud(std::size_t n, bool on_sphere) {
    xeno::scenes::Random rng(20260101u + n);
    std::vector<Vec3<T>> points;
    points.reserve(n);
    while (points.size() < n) {
        const Vec3<double> p = rng.in_box(Vec3<double>{1.0, 1.0, 1.0});
        const double r = xeno::length(p);
        if (r > 1.0 || r < 1e-3) continue;
        const Vec3<double> q = on_sphere ? p / r : p;
        points.push_back(Vec3<T>{static_cast<T>(q.x), static_cast<T>(q.y), static_cast<T>(q.z)});
    }
    return points;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// Best CPU time of `runs` hull builds; vertices and faces of the hull through the out-parameters.
template <class T>
double time_hull(const std::vector<Vec3<T>>& points, int runs, std::size_t& vertices, std::size_t& faces) {
    double best = 1e300;
    for (int r = 0; r < runs; ++r) {
        const double start = cpu_seconds();
        const xeno::ConvexHull<T> hull = xeno::make_convex_hull(points);
        best = std::min(best, cpu_seconds() - start);
        vertices = hull.polyhedron.vertices().size();
        faces = hull.polyhedron.faces().size();
    }
    return best;
}

template <class T>
void run(const char* precision, bool on_sphere, std::size_t max_points, int runs) {
    double previous = 0.0;
    for (std::size_t n = 1000; n <= max_points; n *= 2) {
        const std::vector<Vec3<T>> points = cloud<T>(n, on_sphere);
        std::size_t vertices = 0, faces = 0;
        const double seconds = time_hull(points, n >= 50000 ? std::min(runs, 2) : runs, vertices, faces);
        std::string ratio = "-";
        if (previous > 0.0) ratio = std::to_string(seconds / previous).substr(0, 4);
        std::printf("%-6s %-6s %8zu %10.4f %8s %9zu %9zu\n", precision, on_sphere ? "sphere" : "ball", n, seconds, ratio.c_str(),
                    vertices, faces);
        std::fflush(stdout);
        previous = seconds;
    }
}

/// Nanoseconds per support search on a hull of n points on a sphere: scan, climb from the last
/// answer, climb from the start vertex; best of 7 sweeps over 4,096 slowly turning directions.
template <class T>
void support_row(const char* precision, std::size_t n) {
    const xeno::ConvexPolyhedron<T> hull = xeno::make_convex_hull(cloud<T>(n, true)).polyhedron;
    xeno::scenes::Random rng(n);
    std::vector<Vec3<T>> directions;
    Vec3<T> d = rng.direction<T>();
    for (int i = 0; i < 4096; ++i) directions.push_back(d = xeno::normalized(d + rng.direction<T>() * T(0.3)));
    std::uint32_t sink = 0;
    const auto time = [&](auto search) {
        double best = 1e300;
        for (int r = 0; r < 7; ++r) {
            const auto start = std::chrono::steady_clock::now();
            for (const Vec3<T>& x : directions) sink += search(x);
            best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        return 1e9 * best / static_cast<double>(directions.size());
    };
    std::uint32_t last = 0;
    const double scan = time([&](const Vec3<T>& x) { return hull.support_index_scan(x); });
    const double warm = time([&](const Vec3<T>& x) { return last = hull.support_index_hill_climb(x, last); });
    const double cold = time([&](const Vec3<T>& x) { return hull.support_index_hill_climb(x, hull.start_vertex(x)); });
    // sink is printed (as nothing) so the compiler must keep every search it sums.
    std::printf("%-6s %4zu %8.1f %12.1f %13.1f%s\n", precision, hull.vertices().size(), scan, warm, cold, sink == 7 ? " " : "");
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t max_points = 128000;
    int runs = 3;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            max_points = 16000;
            runs = 1;
        } else if (std::strcmp(argv[i], "--max") == 0 && i + 1 < argc) {
            max_points = std::strtoul(argv[++i], nullptr, 10);
        } else {
            std::fprintf(stderr, "usage: xeno_hull_bench [--quick] [--max N]\n");
            return 2;
        }
    }
    std::printf("# precision cloud points cpu_seconds t(n)/t(n/2) hull_vertices hull_faces\n");
    for (bool on_sphere : {true, false}) {
        run<double>("double", on_sphere, max_points, runs);
        run<float>("float", on_sphere, max_points, runs);
    }
    std::printf("\n# support search, ns per call: precision vertices scan climb_from_last climb_from_start (%d-lane scan)\n",
                xeno::detail::native_width<float>());
    for (const std::size_t n : {8, 16, 32, 64, 128, 256}) {
        support_row<float>("float", n);
        support_row<double>("double", n);
    }
    return 0;
}

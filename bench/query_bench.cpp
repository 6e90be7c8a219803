// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// World queries (docs/benchmarks.md, "World queries"): n bodies (boxes and spheres, 0.2–1 m, in
// a cube of 8 m³ per body, one static ground under them) and 20,000 random short rays (10 m,
// from inside the cube, any direction) and small overlap queries, timed per query. Beside each
// query tree time, a scan of every body in the same process: a box test per body on stored
// world boxes, then the exact test, what World::raycast did before the query tree (each body's
// box, then its shape, then a sort of the hits). Both give the same answers (checked here on
// every tenth ray; tests/dynamics/query_test.cpp checks every query kind against a scan).
//   xeno_query_bench [float|double = double] [largest n = 100000]
#include "scenes/random.hpp"

#include <xeno/xeno.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

using namespace xeno;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

template <class T>
World<T> scattered_world(int n, T& half_side) {
    scenes::Random rng(42);
    half_side = T(0.5) * static_cast<T>(std::cbrt(8.0 * n));
    World<T> world;
    world.reserve(static_cast<std::size_t>(n) + 1);
    BodyDef<T> ground;
    ground.type = BodyType::static_body;
    ground.position = {T(0), -half_side - T(1), T(0)};
    world.create_body(Box<T>(half_side, T(1), half_side), ground);
    for (int i = 0; i < n; ++i) {
        BodyDef<T> def;
        def.position = rng.in_box(Vec3<T>{half_side, half_side, half_side});
        def.orientation = rng.rotation<T>();
        const T size = rng.uniform(T(0.2), T(1));
        if (i % 2 == 0) world.create_body(Box<T>(size, size, size), def);
        else world.create_body(Sphere<T>(size), def);
    }
    return world;
}

/// The scan World::raycast made before the query tree: every body's stored box, then its shape.
template <class T>
struct Scan {
    std::vector<BodyId> ids;
    std::vector<Aabb<T>> boxes;
    std::vector<const Body<T>*> bodies;

    explicit Scan(const World<T>& world) {
        world.for_each_body([&](BodyId id, const Body<T>& b) {
            ids.push_back(id);
            boxes.push_back(b.world_bounds());
            bodies.push_back(&b);
        });
    }
    std::optional<WorldRayHit<T>> nearest(const Ray<T>& ray) const {
        std::vector<WorldRayHit<T>> hits;
        for (std::size_t i = 0; i < ids.size(); ++i) {
            if (!raycast(boxes[i], ray)) continue;
            if (const auto hit = raycast(bodies[i]->child_shape(0), bodies[i]->child_transform(0), ray))
                hits.push_back({ids[i], *hit});
        }
        if (hits.empty()) return std::nullopt;
        std::sort(hits.begin(), hits.end(), [](const WorldRayHit<T>& x, const WorldRayHit<T>& y) {
            return x.hit.distance != y.hit.distance ? x.hit.distance < y.hit.distance : x.body.index < y.body.index;
        });
        return hits.front();
    }
};

template <class T>
void run(int largest, const char* precision) {
    std::printf(
        "%s: microseconds per query (20,000 rays of 10 m; 20,000 overlaps of r = 1 m spheres / 2 m boxes;\n"
        "20,000 casts of a r = 0.3 m sphere swept 2 m)\n"
        "%8s %10s %10s %10s %10s %10s %10s %8s %9s %9s\n",
        precision, "bodies", "nearest", "scan", "scan/tree", "any", "all", "sphere", "box", "cast", "hit rate");
    for (int n = 100; n <= largest; n *= 10) {
        T half = T(0);
        const World<T> world = scattered_world<T>(n, half);
        scenes::Random rng(7);
        const int queries = 20000;
        std::vector<Ray<T>> rays;
        for (int i = 0; i < queries; ++i) rays.push_back({rng.in_box(Vec3<T>{half, half, half}), rng.direction<T>(), T(10)});
        const int scanned = n <= 10000 ? queries : 2000;  // the scan is slow at 100,000
        const Scan<T> scan(world);
        int hits = 0, mismatches = 0;
        auto start = Clock::now();
        for (const Ray<T>& ray : rays) hits += world.raycast(ray).has_value() ? 1 : 0;
        const double nearest = seconds_since(start) / queries;
        start = Clock::now();
        std::size_t total = 0;  // consumed, so no loop is optimised away
        for (int i = 0; i < scanned; ++i) total += scan.nearest(rays[static_cast<std::size_t>(i)]).has_value() ? 1 : 0;
        const double scanning = seconds_since(start) / scanned;
        for (int i = 0; i < scanned; i += 10) {
            const auto a = world.raycast(rays[static_cast<std::size_t>(i)]);
            const auto b = scan.nearest(rays[static_cast<std::size_t>(i)]);
            if (a.has_value() != b.has_value() || (a && (a->body != b->body || a->hit.distance != b->hit.distance))) ++mismatches;
        }
        start = Clock::now();
        for (const Ray<T>& ray : rays) total += world.raycast_any(ray).has_value() ? 1 : 0;
        const double any = seconds_since(start) / queries;
        start = Clock::now();
        for (const Ray<T>& ray : rays) total += world.raycast_all(ray).size();
        const double all = seconds_since(start) / queries;
        start = Clock::now();
        for (const Ray<T>& ray : rays) total += world.overlap_sphere(ray.origin, T(1)).size();
        const double sphere = seconds_since(start) / queries;
        start = Clock::now();
        for (const Ray<T>& ray : rays) total += world.query_aabb(Aabb<T>::from_center(ray.origin, Vec3<T>::one())).size();
        const double box = seconds_since(start) / queries;
        const Shape<T> ball = Sphere<T>(T(0.3));
        start = Clock::now();
        for (const Ray<T>& ray : rays)
            total +=
                world.shape_cast(ball, Transform<T>{ray.origin, Quat<T>::identity()}, ray.direction * T(2)).has_value() ? 1 : 0;
        const double cast = seconds_since(start) / queries;
        std::printf("%8d %10.2f %10.2f %10.0f %10.2f %10.2f %10.2f %8.2f %9.2f %8.0f%%%s\n", n, nearest * 1e6, scanning * 1e6,
                    scanning / nearest, any * 1e6, all * 1e6, sphere * 1e6, box * 1e6, cast * 1e6, 100.0 * hits / queries,
                    mismatches ? "  MISMATCH" : "");
        if (mismatches) std::exit(1);
        if (total == 1) std::puts("");
    }
}

}  // namespace

int main(int argc, char** argv) {
    const bool single = argc > 1 && std::strcmp(argv[1], "float") == 0;
    const int largest = argc > 2 ? std::atoi(argv[2]) : 100000;
    if (largest < 100) {
        std::fprintf(stderr, "usage: xeno_query_bench [float|double] [largest n >= 100]\n");
        return 2;
    }
    if (single) run<float>(largest, "float");
    else run<double>(largest, "double");
    return 0;
}

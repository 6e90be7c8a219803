// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_determinism: steps a fixed list of scenes a fixed number of steps in float and double and
// prints one line per run, `scene precision final-hash` (hash of every body's state, see
// state_hash.hpp). Two processes must print the same lines (CTest, compare_runs.cmake), and so
// must a g++ build and a clang++ build (scripts/test.sh diffs them): docs/robustness.md,
// "Determinism". Runs in about two seconds in a Release build. --workers N steps on the world's
// own pool of N threads, --shuffled N through a job system that cuts and orders the work at random
// (docs/parallel.md): both must print the one-thread hashes.
#include "robustness/state_hash.hpp"
#include "support/shuffled_tasks.hpp"
#include "scenes/all.hpp"

#include <xeno/collide/early_out.hpp>
#include <xeno/shape/polyhedra.hpp>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Run {
    const char* scene;
    int steps;  // at the default 60 Hz
};

// Every kind of shape (mixed-pile), many impacts (rain), a tall stack (pyramid), a chain of
// events (dominoes), lever and restitution (seesaw), a 400:1 mass ratio, a sloped contact, joints
// with contacts (ragdoll), and a plate carrying 36 boxes (more contacts on one body than the
// solver has colours: its overflow rows, docs/solver.md, "Colours"), and boxes, capsules and a
// ragdoll on a heightfield (mesh contacts, docs/meshes.md).
constexpr Run runs[] = {
    {"mixed-pile", 300},     {"rain", 300},    {"pyramid", 120}, {"dominoes", 300},     {"seesaw", 180},  {"edge-edge", 120},
    {"heavy-on-light", 120}, {"incline", 180}, {"ragdoll", 180}, {"loaded-plate", 120}, {"terrain", 180},
};

template <class T>
void loaded_plate(xeno::World<T>& world) {
    using xeno::Vec3;
    xeno::scenes::add_ground(world);
    xeno::scenes::add_box(world, Vec3<T>{T(4), T(0.1), T(4)}, Vec3<T>{T(0), T(0.1), T(0)});
    for (int i = 0; i < 6; ++i)
        for (int k = 0; k < 6; ++k)
            xeno::scenes::add_box(world, Vec3<T>{T(0.4), T(0.4), T(0.4)},
                                  Vec3<T>{T(-3.5) + T(1.4) * T(i), T(0.6), T(-3.5) + T(1.4) * T(k)});
}

unsigned workers = 1;   // --workers N: the world's own pool
unsigned shuffled = 0;  // --shuffled N: ShuffledTasks on N threads

template <class T>
std::uint64_t final_hash(const char* scene, int steps) {
    xeno::World<T> world;
    xeno::test::ShuffledTasks tasks(shuffled);
    if (shuffled > 0) world.set_task_system(&tasks);
    else world.set_workers(workers);
    if (std::string(scene) == "loaded-plate") loaded_plate(world);
    else xeno::scenes::build<T>(scene, world);
    const T dt = world.settings().fixed_time_step;
    for (int i = 0; i < steps; ++i) world.step(dt);
    return xeno::test::state_hash(world);
}

// The early-out's answer for every pair of a crowd of every shape kind (collide/early_out.hpp),
// in runs of the build's lane width and gathered, as one hash: the portable, SSE2 and AVX2 builds
// must print the same.
template <class T>
std::uint64_t early_out_hash() {
    using namespace xeno;
    constexpr std::uint32_t W = EarlyOut<T>::width;
    const std::vector<Shape<T>> shapes = {Box<T>(T(0.5), T(0.2), T(0.3)), Sphere<T>(T(0.4)),
                                          Capsule<T>(T(0.2), T(0.5)),     Cylinder<T>(T(0.3), T(0.2)),
                                          Cone<T>(T(0.4), T(0.8)),        make_regular_prism(7, T(0.4), T(0.3))};
    scenes::Random rng(2010);
    const std::uint32_t n = 301;
    EarlyOut<T> early;
    early.resize(n);
    for (std::uint32_t i = 0; i < n; ++i)
        early.set(i, shapes[i % shapes.size()], {rng.in_box(Vec3<T>::one() * T(4)), rng.rotation<T>()});
    std::uint64_t h = 1469598103934665603ull;
    const auto mix = [&](unsigned bit) { h = (h ^ bit) * 1099511628211ull; };
    for (std::uint32_t i = 0; i < n; ++i) {
        std::uint32_t j = i + 1;
        for (; j + W <= n; j += W) {
            const unsigned m = early.template apart_run<W>(i, j, T(0.05));
            for (std::uint32_t l = 0; l < W; ++l) mix((m >> l) & 1u);
        }
        for (; j < n; ++j) mix(early.apart(i, j, T(0.05)) ? 1u : 0u);
        for (std::uint32_t c = 0; c < 8; c += W) {  // eight gathered pairs per body, whatever W
            std::uint32_t a[W], b[W];
            T margin[W];
            for (std::uint32_t l = 0; l < W; ++l)
                a[l] = i, b[l] = (i * 7u + (c + l) * 13u + 1u) % n, margin[l] = T(0.01) * T(c + l);
            const unsigned m = early.template apart_pairs<W>(a, b, margin);
            for (std::uint32_t l = 0; l < W; ++l) mix(((m >> l) & 1u) * 2u + (early.apart(a[l], b[l], margin[l]) ? 1u : 0u));
        }
    }
    return h;
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string option = argv[i];
        const auto value = static_cast<unsigned>(std::strtoul(argv[i + 1], nullptr, 10));
        if (option == "--workers") workers = value;
        else if (option == "--shuffled") shuffled = value;
        else {
            std::fprintf(stderr, "usage: xeno_determinism [--workers N | --shuffled N]\n");
            return 2;
        }
    }
    std::printf("early-out float %016" PRIx64 "\n", early_out_hash<float>());
    std::printf("early-out double %016" PRIx64 "\n", early_out_hash<double>());
    for (const Run& run : runs) {
        std::printf("%s float %016" PRIx64 "\n", run.scene, final_hash<float>(run.scene, run.steps));
        std::printf("%s double %016" PRIx64 "\n", run.scene, final_hash<double>(run.scene, run.steps));
    }
    return 0;
}

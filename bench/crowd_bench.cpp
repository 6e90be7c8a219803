// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Crowds (docs/robustness.md, "Crowds"): n unit spheres created at one point, default settings
// except gravity (zero: the crowd is alone). Prints the time of the first steps, the process's
// peak resident memory, and the simulated time at which no two spheres overlap by more than
// 1 cm (checked by brute force every 0.5 s, up to 10 s). One configuration per run, so the peak
// memory is that configuration's:
//   xeno_crowd_bench [n = 3000] [float|double = double]
#include <xeno/xeno.hpp>

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

using namespace xeno;

namespace {

long peak_megabytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024;  // kB on Linux
}

template <class T>
T deepest_overlap(const std::vector<Vec3<T>>& centres) {
    T worst = T(0);
    for (std::size_t i = 0; i < centres.size(); ++i)
        for (std::size_t j = i + 1; j < centres.size(); ++j) worst = std::max(worst, T(1) - length(centres[i] - centres[j]));
    return worst;
}

template <class T>
void run(int n, const char* name) {
    WorldSettings<T> settings;
    settings.gravity = Vec3<T>::zero();
    World<T> world(settings);
    const auto sphere = std::make_shared<const Shape<T>>(Sphere<T>(T(0.5)));
    std::vector<BodyId> ids;
    for (int i = 0; i < n; ++i) ids.push_back(world.create_body(sphere, BodyDef<T>{}));
    std::printf("%d unit spheres at one point, %s, default settings (max_contact_pairs %d), zero gravity\n", n, name,
                settings.max_contact_pairs);
    double slowest = 0;
    for (int step = 1; step <= 600; ++step) {
        const auto start = std::chrono::steady_clock::now();
        world.step(T(1) / T(60));
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        slowest = std::max(slowest, ms);
        const StepStats& st = world.last_step_stats();
        if (step <= 3)
            std::printf("  step %d: %7.0f ms  broad pairs %zu, dropped %zu, contacts %zu, peak memory %ld MB\n", step, ms,
                        st.broad_pairs, st.dropped_pairs, st.contacts, peak_megabytes());
        if (step % 30 != 0) continue;
        std::vector<Vec3<T>> centres;
        bool finite = true;
        for (const BodyId id : ids) {
            centres.push_back(world.body(id).position());
            finite = finite && is_finite(world.body(id).position()) && is_finite(world.body(id).linear_velocity());
        }
        const T overlap = deepest_overlap(centres);
        if (!finite || overlap <= T(0.01) || step == 600) {
            std::printf(
                "  t = %.1f s: deepest overlap %.4f m, every state finite: %s; slowest step %.0f ms, peak memory %ld MB\n",
                step / 60.0, static_cast<double>(overlap), finite ? "yes" : "NO", slowest, peak_megabytes());
            return;
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    const int n = argc > 1 ? std::atoi(argv[1]) : 3000;
    if (n < 2 || n > 100000) {
        std::fprintf(stderr, "usage: xeno_crowd_bench [n in 2..100000] [float|double]\n");
        return 2;
    }
    if (argc > 2 && std::strcmp(argv[2], "float") == 0) run<float>(n, "float");
    else run<double>(n, "double");
}

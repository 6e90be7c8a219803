// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// libFuzzer target over restore_snapshot (docs/robustness.md, "Fuzzing"). The input is the
// snapshot itself, restored into a World<float> and a World<double> (the header's scalar size
// makes at least one reject it). A buffer may be rejected, with InvalidArgument only; a buffer
// that is accepted must give a world that
//   - saves a snapshot that restores again (the checks accept what they let in),
//   - steps ten steps with finite positions, orientations and velocities,
//   - then creates a body in a free or new slot, leaving every living handle alive.
// Anything else traps. Seeds: real snapshots of small worlds (tests/fuzz/corpus/snapshot/,
// written by make_snapshot_corpus.cpp).
//   run:    xeno_fuzz_snapshot -max_total_time=60 <corpus dir>
#include <xeno/xeno.hpp>
#include <xeno/dynamics/snapshot.hpp>

#include <cstdint>
#include <cstdio>
#include <vector>

using namespace xeno;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "xeno fuzz: %s\n", what);
    std::fflush(stderr);
    __builtin_trap();
}

template <class T>
void run(const std::vector<std::uint8_t>& bytes) {
    World<T> w;
    try {
        restore_snapshot(w, bytes);
    } catch (const InvalidArgument&) {
        if (w.body_count() != 0) fail("a rejected snapshot changed the world");
        return;
    }
    try {
        World<T> again;
        restore_snapshot(again, save_snapshot(w));
        if (again.body_count() != w.body_count()) fail("a re-saved snapshot restored another body count");
    } catch (const InvalidArgument&) {
        fail("the snapshot of an accepted world was rejected");
    }
    std::vector<BodyId> living;
    w.for_each_body([&](BodyId id, const Body<T>&) { living.push_back(id); });
    for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
    w.for_each_body([](BodyId, const Body<T>& b) {
        if (!(is_finite(b.position()) && is_finite(b.orientation()) && is_finite(b.linear_velocity()) &&
              is_finite(b.angular_velocity())))
            fail("a body's state is not finite after stepping a restored world");
    });
    const std::size_t count = w.body_count();
    const BodyId fresh = w.create_body(Sphere<T>(T(0.25)));
    if (w.body_count() != count + 1) fail("create_body after a restore did not add a body");
    for (const BodyId id : living)
        if (!w.contains(id) || id == fresh) fail("create_body after a restore overwrote a living body");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::uint8_t> bytes(data, data + size);
    run<float>(bytes);
    run<double>(bytes);
    return 0;
}

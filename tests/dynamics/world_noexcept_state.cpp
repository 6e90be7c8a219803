// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Built with -fno-exceptions: a rejected call reaches the error handler before it has changed
// anything. The handler installed here compares the world's snapshot with the one taken before
// the call, prints "unchanged: <message>" (or "CHANGED: <message>") and exits; CTest checks the
// output (tests/CMakeLists.txt). Usage: xeno_noexcept_state_test <case> <f32|f64>.
#include <xeno/xeno.hpp>
#include <xeno/dynamics/snapshot.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>

using namespace xeno;

namespace {

std::function<bool()> unchanged;  // compares the world with its snapshot before the call

void check_and_exit(const char* message) {
    std::printf("%s: %s\n", unchanged() ? "unchanged" : "CHANGED", message);
    std::fflush(stdout);
    std::exit(0);
}

template <class T>
int run(const char* which) {
    World<T> w;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(0), T(-0.5), T(0)};
    w.create_body(Box<T>(T(4), T(0.5), T(4)), d);
    d = {};
    d.position = {T(0), T(0.49), T(0)};
    const BodyId box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.position = {T(2), T(0.49), T(0)};
    const BodyId ball = w.create_body(Sphere<T>(T(0.5)), d);
    for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
    const std::vector<std::uint8_t> before = save_snapshot(w);
    unchanged = [&] { return save_snapshot(w) == before; };
    set_error_handler(&check_and_exit);

    if (std::strcmp(which, "create_body_inertia") == 0) {  // inertia too small to invert: rejected after the slot was taken
        BodyDef<T> tiny;
        tiny.density = std::is_same_v<T, float> ? T(1e-10) : T(1e-60);
        w.create_body(Sphere<T>(ScalarTraits<T>::min_size), tiny);
    } else if (std::strcmp(which, "create_body_type") == 0) {
        BodyDef<T> bad;
        bad.type = static_cast<BodyType>(7);
        w.create_body(Sphere<T>(T(1)), bad);
    } else if (std::strcmp(which, "create_joint_type") == 0) {
        JointDef<T> j = JointDef<T>::ball(box, ball, {T(1), T(0.5), T(0)});
        j.type = static_cast<JointType>(9);
        w.create_joint(j);
    } else if (std::strcmp(which, "set_damping") == 0) {
        w.body(box).set_damping(T(1), T(-1));
    } else if (std::strcmp(which, "set_mass_properties") == 0) {
        w.body(box).set_mass_properties({T(1), {std::numeric_limits<T>::quiet_NaN(), T(0), T(0)}, Mat3<T>::identity()});
    } else if (std::strcmp(which, "restore_snapshot") == 0) {
        std::vector<std::uint8_t> bad = before;
        const T nan = std::numeric_limits<T>::quiet_NaN();
        std::memcpy(bad.data() + 12 + sizeof(WorldSettings<T>), &nan, sizeof nan);  // the accumulator
        restore_snapshot(w, bad);
    } else {
        std::printf("unknown case %s\n", which);
        return 2;
    }
    std::printf("accepted: %s\n", which);
    return 3;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::printf("usage: %s <case> <f32|f64>\n", argv[0]);
        return 2;
    }
    return std::strcmp(argv[2], "f32") == 0 ? run<float>(argv[1]) : run<double>(argv[1]);
}

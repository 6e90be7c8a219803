// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Writes the seeds of xeno_fuzz_snapshot: real snapshots of small worlds in float and double
// (an empty world; ground, a box and a compound joined by a hinge with a freed body slot, a
// freed joint slot, a slider and a disabled body; a ragdoll; a compound stack), each taken mid-motion so that
// contacts and joints carry warm-start impulses. Running it again rewrites the same values; the
// padding bytes inside the structs a snapshot stores whole (settings, contacts, joints) are not
// specified and may differ (double). Usage: xeno_fuzz_snapshot_corpus <dir>   (the repository's is tests/fuzz/corpus/snapshot)
#include "scenes/all.hpp"

#include <xeno/dynamics/snapshot.hpp>

#include <cstdio>
#include <string>

using namespace xeno;

namespace {

bool write(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return false;
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    return std::fclose(f) == 0 && ok;
}

template <class T>
void small_world(World<T>& w) {
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(0), T(-0.5), T(0)};
    const BodyId ground = w.create_body(Box<T>(T(4), T(0.5), T(2)), d);
    d = {};
    d.position = {T(-1), T(0.49), T(0)};
    const BodyId box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.position = {T(1.25), T(0.49), T(0.25)};
    const BodyId compound = w.create_body(
        Compound<T>({{Box<T>(T(0.3), T(0.5), T(0.3)), {}}, {Sphere<T>(T(0.3)), {{T(0.6), T(0), T(0)}, Quat<T>::identity()}}}), d);
    d.position = {T(0), T(3), T(0)};
    const BodyId falling = w.create_body(Capsule<T>(T(0.2), T(0.4)), d);
    w.create_joint(JointDef<T>::hinge(box, compound, {T(0), T(0.5), T(0)}, {T(0), T(0), T(1)}));
    d.position = {T(3), T(2), T(1)};
    const BodyId carriage = w.create_body(Box<T>(T(0.2), T(0.2), T(0.2)), d);
    JointDef<T> slider = JointDef<T>::prismatic(ground, carriage, {T(3), T(2), T(1)}, {T(0), T(1), T(0)});
    slider.enable_limit = true, slider.lower_translation = T(-0.5), slider.upper_translation = T(0.5);
    slider.enable_motor = true, slider.motor_speed = T(0.1), slider.max_motor_force = T(50);
    w.create_joint(slider);
    const JointId spare = w.create_joint(JointDef<T>::distance(box, falling, {T(-1), T(1), T(0)}, {T(0), T(3), T(0)}));
    for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
    w.destroy_joint(spare);
    w.destroy_body(falling);
    d.position = {T(-3), T(0.5), T(0)};
    w.set_enabled(w.create_body(Sphere<T>(T(0.5)), d), false);
}

template <class T>
bool seeds(const std::string& dir, const char* precision) {
    bool ok = true;
    {
        World<T> w;
        ok = ok && write(dir + "/empty-" + precision, save_snapshot(w));
    }
    {
        World<T> w;
        small_world(w);
        ok = ok && write(dir + "/small-" + precision, save_snapshot(w));
    }
    for (const char* name : {"ragdoll", "compound-stack"}) {
        World<T> w;
        scenes::build(std::string(name), w);
        for (int i = 0; i < 30; ++i) w.step(T(1) / T(60));
        ok = ok && write(dir + "/" + name + "-" + precision, save_snapshot(w));
    }
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s <corpus dir>\n", argv[0]);
        return 2;
    }
    const bool ok = seeds<float>(argv[1], "f32") && seeds<double>(argv[1], "f64");
    if (!ok) std::fprintf(stderr, "could not write the seeds into %s\n", argv[1]);
    return ok ? 0 : 1;
}

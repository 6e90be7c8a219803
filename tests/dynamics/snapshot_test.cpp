// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Snapshots: stepping after a restore is bitwise identical to stepping the original.
#include "support/approx.hpp"
#include "support/sim.hpp"

#include "scenes/all.hpp"

#include <xeno/dynamics/snapshot.hpp>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

using namespace xeno;

namespace {
// FNV-1a over the raw bytes of every body's pose and velocities, in slot order.
template <class T>
std::uint64_t state_hash(const World<T>& w) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](const void* p, std::size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    w.for_each_body([&](BodyId id, const Body<T>& b) {
        mix(&id.index, sizeof id.index);
        mix(&b.position(), sizeof(Vec3<T>));
        mix(&b.orientation(), sizeof(Quat<T>));
        mix(&b.linear_velocity(), sizeof(Vec3<T>));
        mix(&b.angular_velocity(), sizeof(Vec3<T>));
    });
    return h;
}
template <class T>
std::vector<std::uint64_t> run(World<T>& w, int steps) {
    std::vector<std::uint64_t> hashes;
    for (int i = 0; i < steps; ++i) {
        w.step(T(1) / T(60));
        hashes.push_back(state_hash(w));
    }
    return hashes;
}
}  // namespace

TEST_CASE_TEMPLATE("stepping after a restore is bitwise identical to stepping the original", T, float, double) {
    for (const char* name : {"mixed-pile", "ragdoll", "compound-stack", "dominoes", "sleeping-pile"}) {
        CAPTURE(name);
        World<T> original;
        scenes::build(std::string(name), original);
        for (int i = 0; i < 45; ++i) original.step(T(1) / T(60));  // mid-motion: contacts, impulses, joints
        const std::vector<std::uint8_t> snapshot = save_snapshot(original);
        World<T> copy;
        restore_snapshot(copy, snapshot);
        CHECK(copy.body_count() == original.body_count());
        CHECK(state_hash(copy) == state_hash(original));
        const std::vector<std::uint64_t> a = run(original, 90), b = run(copy, 90);
        CHECK(a == b);
        // Rewind the original itself (rollback) and replay: the same again.
        restore_snapshot(original, snapshot);
        CHECK(run(original, 90) == a);
    }
}

TEST_CASE_TEMPLATE("a snapshot keeps handles, shared shapes and rejects bad buffers", T, float, double) {
    World<T> w;
    const auto shape = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
    const BodyId a = w.create_body(shape);
    const BodyId gone = w.create_body(shape);
    w.destroy_body(gone);
    BodyDef<T> d;
    d.position = {T(2), T(0), T(0)};
    const BodyId b = w.create_body(shape, d);
    const std::vector<std::uint8_t> bytes = save_snapshot(w);
    World<T> r;
    restore_snapshot(r, bytes);
    CHECK(r.contains(a));
    CHECK(r.contains(b));
    CHECK_FALSE(r.contains(gone));
    CHECK(r.body(a).shared_shape() == r.body(b).shared_shape());  // shared again
    CHECK(r.body(b).position() == d.position);
    // Truncated, corrupted and other-precision buffers leave the world as it was.
    std::vector<std::uint8_t> truncated(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
    CHECK_THROWS_AS(restore_snapshot(r, truncated), InvalidArgument);
    std::vector<std::uint8_t> corrupt = bytes;
    corrupt[0] ^= 0xFF;
    CHECK_THROWS_AS(restore_snapshot(r, corrupt), InvalidArgument);
    using Other = std::conditional_t<std::is_same_v<T, float>, double, float>;
    World<Other> other;
    CHECK_THROWS_AS(restore_snapshot(other, bytes), InvalidArgument);
    CHECK(r.contains(b));
    CHECK(r.body_count() == 2);
}

TEST_CASE_TEMPLATE("the fuzzer's seed snapshots restore and step: the corpus is of the current format", T, float, double) {
    // A seed the format no longer reads is rejected at its first bytes, and the fuzzer then
    // mutates nothing but the header: the seeds were three versions old before this test.
    const std::string suffix = sizeof(T) == 4 ? "-f32" : "-f64";
    for (const char* name : {"empty", "small", "ragdoll", "compound-stack"}) {
        const std::string path = std::string(XENO_SNAPSHOT_CORPUS) + "/" + name + suffix;
        CAPTURE(path);
        std::ifstream in(path, std::ios::binary);
        REQUIRE(in.good());
        const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        World<T> w;
        REQUIRE_NOTHROW(restore_snapshot(w, bytes));
        CHECK((w.body_count() == 0) == (std::string(name) == "empty"));
        test::simulate(w, T(0.5));
        // The seed's world behaves like any: finite, and a copy restored from its snapshot steps
        // on to the same bits as the original.
        World<T> copy;
        restore_snapshot(copy, save_snapshot(w));
        test::simulate(w, T(0.5));
        test::simulate(copy, T(0.5));
        w.for_each_body([&](BodyId id, const Body<T>& b) {
            CHECK(is_finite(b.position()));
            CHECK(b.position() == copy.body(id).position());
            CHECK(b.orientation() == copy.body(id).orientation());
        });
    }
}

// Regression: apply_force and apply_torque accept any force whose acceleration is finite, and a
// change of mass afterwards may raise it further, but restore_snapshot refused an acceleration
// beyond max_size: 1e10 N on a 1000 kg float box (1e7 m/s²) gave a world whose own snapshot did
// not restore. The step copes with such a force; so must a restore.
TEST_CASE_TEMPLATE("a world with a huge accumulated force or torque restores from its own snapshot and steps the same", T, float,
                   double) {
    const T huge = std::is_same_v<T, float> ? T(1e10) : T(1e54);
    World<T> original;
    BodyDef<T> d;
    d.position = {T(0), T(5), T(0)};
    const BodyId pushed = original.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.position = {T(3), T(5), T(0)};
    const BodyId turned = original.create_body(Box<T>(T(5), T(0.01), T(0.01)), d);
    original.body(pushed).apply_force({huge, T(0), T(0)});
    original.body(turned).apply_torque({T(0), T(1e4), T(0)});
    World<T> copy;
    restore_snapshot(copy, save_snapshot(original));
    CHECK(state_hash(copy) == state_hash(original));
    CHECK(run(copy, 3) == run(original, 3));
    original.for_each_body([](BodyId, const Body<T>& b) {
        CHECK(is_finite(b.position()));
        CHECK(is_finite(b.linear_velocity()));
    });
}

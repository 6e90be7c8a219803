// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Snapshots: stepping after a restore is bitwise identical to stepping the original.
#include "robustness/state_hash.hpp"
#include "support/approx.hpp"
#include "support/shuffled_tasks.hpp"
#include "support/sim.hpp"

#include "scenes/all.hpp"

#include <xeno/dynamics/snapshot.hpp>

#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

using namespace xeno;
using xeno::test::state_hash;

namespace {
template <class T>
std::vector<std::uint64_t> run(World<T>& w, int steps) {
    std::vector<std::uint64_t> hashes;
    for (int i = 0; i < steps; ++i) {
        w.step(T(1) / T(60));
        hashes.push_back(state_hash(w));
    }
    return hashes;
}
// Steps `world` `steps` times at 60 Hz; after each step `check(step)` runs, then the world's own
// snapshot must restore into a new world with the same state, every body's state finite.
template <class T, class Check>
void step_restoring(World<T>& world, int steps, Check check) {
    for (int step = 0; step < steps; ++step) {
        CAPTURE(step);
        world.step(T(1) / T(60));
        check(step);
        world.for_each_body([](BodyId, const Body<T>& b) {
            REQUIRE(is_finite(b.position()));
            REQUIRE(is_finite(b.linear_velocity()));
        });
        World<T> copy;
        REQUIRE_NOTHROW(restore_snapshot(copy, save_snapshot(world)));
        REQUIRE(state_hash(copy) == state_hash(world));
    }
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

// Regression: in float, a motor of "unlimited" force (FLT_MAX, or 1e30 N) pushed against its
// slider's limit, or spun a hinged paddle into the ground at 1e6 rad/s, and a slider's limits set
// 1e30 m out pulled its body there with an impulse of the same order: each stored motor, limit or
// contact impulses beyond what restore_snapshot accepts (and joint_reaction reported +inf N), so
// the world's own snapshot did not restore after the first or second step. (Double failed the
// same way at motor speeds beyond 1e30, which create_joint now rejects: bad_input_test.cpp.) The
// solver now caps a limit and a motor at the impulse that changes the bodies' speed by max_size,
// a limit's pull at the speed cap (as a stretched point row's), and a motor's speed at what the
// integrator lets the bodies reach.
TEST_CASE_TEMPLATE("motors of unlimited force and limits far away leave a world whose own snapshot restores", T, float, double) {
    const T unlimited = std::numeric_limits<T>::max();
    for (const std::string kind : {"slider motor into its limit", "hinge motor into the ground", "slider limits 1e30 m out"}) {
        CAPTURE(kind);
        const bool hinge = kind[0] == 'h', far_limits = kind[14] == '1';
        World<T> original;
        BodyDef<T> d;
        d.type = BodyType::static_body;
        d.position = {T(0), T(-1), T(0)};
        original.create_body(Box<T>(T(20), T(1), T(20)), d);
        d.position = {T(0), T(2), T(0)};
        const BodyId pivot = original.create_body(Box<T>(T(0.5), T(0.1), T(0.5)), d);
        d.type = BodyType::dynamic;
        d.position = {T(1.5), T(2), T(0)};
        const BodyId paddle = original.create_body(Box<T>(T(1.5), T(0.1), T(0.3)), d);
        JointDef<T> j = hinge ? JointDef<T>::hinge(pivot, paddle, {T(0), T(2), T(0)}, {T(0), T(0), T(1)})
                              : JointDef<T>::prismatic(pivot, paddle, {T(0), T(2), T(0)}, {T(1), T(0), T(0)});
        j.enable_motor = !far_limits;
        // Into the ground (rad/s) or into the limit (m/s); in double also at the top of the range.
        j.motor_speed = std::is_same_v<T, float> ? (hinge ? T(1e6) : T(1000)) : detail::max_setting_length<T>();
        j.max_motor_torque = j.max_motor_force = unlimited;
        j.enable_limit = !hinge;
        j.lower_translation = far_limits ? T(1e30) : T(-1);
        j.upper_translation = far_limits ? T(1e30) : T(1);
        const JointId joint = original.create_joint(j);
        step_restoring(original, 20, [&](int) {
            const JointReaction<T> reaction = original.joint_reaction(joint);
            REQUIRE(is_finite(reaction.force));
            REQUIRE(is_finite(reaction.torque));
        });
    }
}

// Regression: two frictions of 1e20 (float) or 1e200 (double), each accepted, were combined as
// √(µ_a µ_b) with an overflowing product: the contact's friction was +inf, its bound inf · 0 = NaN,
// the step's last defence froze the box where it was, and the world's own snapshot did not
// restore. √µ_a √µ_b does not overflow: such a box grips as one at µ = 1e10 does.
TEST_CASE_TEMPLATE("frictions whose product overflows combine to a finite µ: the box grips and the snapshot restores", T, float,
                   double) {
    const T huge = std::is_same_v<T, float> ? T(1e20) : T(1e200);
    CHECK(combined_friction(Material<T>{huge, T(0)}, Material<T>{huge, T(0)}) == doctest::Approx(huge).epsilon(1e-6));
    const T most = std::numeric_limits<T>::max();
    CHECK(std::isfinite(combined_friction(Material<T>{most, T(0)}, Material<T>{most, T(0)})));
    const auto thrown = [](T friction, World<T>& world) {
        BodyDef<T> d;
        d.type = BodyType::static_body;
        d.position = {T(0), T(-1), T(0)};
        d.material.friction = friction;
        world.create_body(Box<T>(T(20), T(1), T(20)), d);
        d.type = BodyType::dynamic;
        d.position = {T(0), T(0.6), T(0)};
        d.linear_velocity = {T(5), T(-3), T(0)};
        return world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    };
    World<T> gripping, reference;
    const BodyId box = thrown(huge, gripping), reference_box = thrown(T(1e10), reference);
    step_restoring(gripping, 60, [&](int) { reference.step(T(1) / T(60)); });
    const Vec3<T> p = gripping.body(box).position(), q = reference.body(reference_box).position();
    CHECK(p.x > T(0.05));  // it moved before it gripped (frozen, it stayed at 0)
    CHECK(p.x == doctest::Approx(q.x).epsilon(1e-3));
    CHECK(p.y == doctest::Approx(q.y).epsilon(1e-3));
}

// Regression: a box welded to two static bodies, one weld anchored 1e5 m from the box (double),
// stored joint impulses past what restore_snapshot accepted within five steps, so the world's own
// snapshot did not restore. A joint's impulses are now capped per substep (a velocity change of
// half max_setting_length at its own levers), and restore asks only that a warm-start impulse
// change its bodies' velocity by a finite amount (docs/robustness.md).
TEST_CASE_TEMPLATE("a box welded with a far anchor leaves a world whose own snapshot restores", T, float, double) {
    for (const T apart : {T(1), T(1e3), T(1e5)}) {
        CAPTURE(apart);
        World<T> world;
        BodyDef<T> d;
        d.type = BodyType::static_body;
        d.position = {T(0), T(4), T(0)};
        const BodyId left = world.create_body(Box<T>(T(0.5), T(0.2), T(0.3)), d);
        d.position = {T(2), T(2), T(0)};
        const BodyId right = world.create_body(Box<T>(T(0.5), T(0.2), T(0.3)), d);
        d.type = BodyType::dynamic;
        d.position = {T(1), T(3), T(0)};
        const BodyId box = world.create_body(Box<T>(T(0.5), T(0.2), T(0.3)), d);
        world.create_joint(JointDef<T>::fixed(left, box, {T(0), T(4), T(0)}));
        world.create_joint(JointDef<T>::fixed(right, box, {T(2) + apart, T(2), T(0)}));
        step_restoring(world, 30, [](int) {});
        // Both welds were made where the box is: it stays there. With the anchor 1e5 m out the
        // rows are too ill-conditioned to hold it (double wanders ~10 m, as before the caps;
        // float now holds to 0.5 mm): not asserted, noted in docs/features.md.
        if (apart <= T(1e3)) CHECK(length(world.body(box).position() - Vec3<T>{T(1), T(3), T(0)}) < T(0.01));
    }
}

// Regression: a fast kinematic box driven down at 1e6 m/s onto a box resting on the ground
// (friction 100) squeezes it with contact impulses far beyond max_size's worth of velocity
// change, as it must; restore_snapshot refused them (float), so the world's own snapshot did not
// restore after the first step.
TEST_CASE_TEMPLATE("a kinematic press at 1e6 m/s leaves a world whose own snapshot restores", T, float, double) {
    World<T> world;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(0), T(-1), T(0)};
    d.material.friction = T(100);
    world.create_body(Box<T>(T(20), T(1), T(20)), d);
    d.type = BodyType::dynamic;
    d.position = {T(0), T(0.5), T(0)};
    const BodyId pressed = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.type = BodyType::kinematic;
    d.position = {T(0.3), T(1.6), T(0)};
    d.linear_velocity = {T(0), T(-1e6), T(0)};
    d.angular_velocity = {T(0), T(40), T(0)};
    d.fast = true;
    world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    step_restoring(world, 20, [](int) {});
    CHECK(world.body(pressed).position().y < T(0.5));  // pressed down, not left where it rested
}

TEST_CASE_TEMPLATE("regression: a restore keeps the restoring world's workers and task system", T, float, double) {
    // docs/parallel.md: a restored snapshot steps on whatever the restoring world was given; the
    // restore moved a fresh world in, and a world of 2 workers stepped on 1 after it.
    World<T> w;
    scenes::add_ground(w);
    const std::vector<std::uint8_t> saved = save_snapshot(w);
    w.set_workers(2);
    restore_snapshot(w, saved);
    CHECK(w.workers() == 2u);
    xeno::test::ShuffledTasks tasks(3);
    w.set_task_system(&tasks);
    restore_snapshot(w, saved);
    CHECK(w.workers() == tasks.workers());
    w.set_task_system(nullptr);
}

// Regression: a ball of 1e-307 kg (double) was accepted: its inertia, 1e-308, has a finite inverse,
// but the spin a unit impulse gives it (the rows of I⁻¹ summed, detail::spin_per_impulse) is
// 3e308 = inf, so every contact impulse on it was "out of range" and the world's own snapshot did
// not restore after its first step. A mass whose response to a unit impulse overflows is refused;
// whatever is accepted, down to the smallest masses each precision holds, steps and restores.
TEST_CASE_TEMPLATE("the lightest balls a world accepts step on a box and their snapshots restore", T, float, double) {
    const T least = std::numeric_limits<T>::min();  // the smallest normal number
    int accepted = 0;
    for (const T mass : {least * T(2), least * T(4.5), least * T(10), least * T(30), least * T(1e3), T(1e-20)}) {
        CAPTURE(mass);
        World<T> world;
        BodyDef<T> d;
        d.type = BodyType::static_body;
        d.position = {T(0), T(-1), T(0)};
        world.create_body(Box<T>(T(20), T(1), T(20)), d);
        d.type = BodyType::dynamic;
        d.position = {T(0), T(0.5), T(0)};
        world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
        d.position = {T(0), T(1.45), T(0.3)};  // 5 cm into the box
        d.mass = mass;
        try {
            world.create_body(Sphere<T>(T(0.5)), d);
        } catch (const InvalidArgument&) {
            continue;
        }
        ++accepted;
        step_restoring(world, 10, [](int) {});
    }
    CHECK(accepted >= 2);
}

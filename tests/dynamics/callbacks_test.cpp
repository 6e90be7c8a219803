// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// What the user's callbacks may do to the world (world.hpp, set_contact_filter and
// set_contact_listener; docs/robustness.md, "Callbacks"): the contact filter runs inside the step
// and may not change the world (every mutating World call is rejected there); the contact
// listener runs after the step and may change it, replace or clear itself, but not step.
// These tests also run in the sanitizer build, where touching freed memory aborts.
#include "support/approx.hpp"
#include "support/sim.hpp"

#include <xeno/dynamics/snapshot.hpp>

#include <memory>
#include <numeric>
#include <optional>
#include <string>

using namespace xeno;

namespace {

/// Ground plus `n` boxes resting on it, touching from the first step: n contact events per step.
template <class T>
std::vector<BodyId> resting_boxes(World<T>& w, int n) {
    scenes::add_ground(w);
    std::vector<BodyId> boxes;
    for (int i = 0; i < n; ++i) {
        BodyDef<T> d;
        d.position = {T(2) * T(i), T(0.49), T(0)};
        boxes.push_back(w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d));
    }
    return boxes;
}

bool mentions(const InvalidArgument& e, const char* what) { return std::string(e.what()).find(what) != std::string::npos; }

}  // namespace

TEST_CASE_TEMPLATE("the contact filter may not change the world: every mutating call is rejected", T, float, double) {
    World<T> w(test::awake_settings<T>());
    const std::vector<BodyId> boxes = resting_boxes(w, 3);
    const BodyId spare = w.create_body(Sphere<T>(T(0.2)), BodyDef<T>{BodyType::static_body, {T(0), T(5), T(0)}});
    const JointId joint = w.create_joint(JointDef<T>::hinge(boxes[0], boxes[1], {T(1), T(0.5), T(0)}, {T(0), T(0), T(1)}));
    const std::vector<std::uint8_t> saved = save_snapshot(w);
    // Each call the filter tries once, in turn; every one must throw and change nothing.
    std::vector<std::function<void()>> attempts{
        [&] { w.create_body(Sphere<T>(T(0.5))); },
        [&] {
            w.create_body(Compound<T>({{Sphere<T>(T(0.5)), {}}}));
        },
        [&] { w.destroy_body(spare); },
        [&] {
            w.set_transform(boxes[2], {T(0), T(9), T(0)}, Quat<T>::identity());
        },
        [&] { w.create_joint(JointDef<T>::ball(boxes[1], boxes[2], {})); },
        [&] { w.destroy_joint(joint); },
        [&] { w.set_hinge_motor(joint, true, T(1), T(1)); },
        [&] { w.set_settings(WorldSettings<T>{}); },
        [&] { w.set_gravity({}); },
        [&] { w.reserve(1000, 1000); },
        [&] { w.set_contact_filter({}); },
        [&] { w.set_contact_listener({}); },
        [&] { w.step(T(1) / T(60)); },
        [&] { w.update(T(1)); },
        [&] { restore_snapshot(w, saved); },
        [&] {
            w.set_velocity(boxes[2], {T(0), T(1), T(0)}, {});
        },
        [&] { w.set_shape(boxes[2], Sphere<T>(T(0.5))); },
        [&] { w.set_density(boxes[2], T(10)); },
        [&] { w.set_type(boxes[2], BodyType::static_body); },
        [&] { w.set_collision_filter(boxes[2], 2u, 0u); },
        [&] { w.set_sensor(boxes[2], true); },
        [&] { w.set_fast(boxes[2], true); },
        [&] { w.set_enabled(boxes[2], false); },
        [&] { w.set_awake(boxes[2], false); },
        [&] { w.move_kinematic(spare, {}, Quat<T>::identity(), T(1) / T(60)); },
        [&] { w.set_joint_limits(joint, true, T(-1), T(1)); },
        [&] { w.set_joint_motor(joint, true, T(1), T(1)); },
    };
    std::size_t next = 0;
    int rejected = 0, calls = 0;
    w.set_contact_filter([&](BodyId, BodyId) {
        ++calls;
        if (next < attempts.size()) {
            try {
                attempts[next]();
            } catch (const InvalidArgument& e) {
                if (mentions(e, "inside the contact filter")) ++rejected;
            }
            ++next;
        }
        return true;
    });
    for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
    CHECK(next == attempts.size());
    CHECK(rejected == static_cast<int>(attempts.size()));
    CHECK(w.body_count() == 5);
    CHECK(w.contains(spare));
    CHECK(w.contains(joint));
    CHECK(w.body(boxes[2]).position().y < T(1));
    // The boxes still rest on the ground: the steps ran normally.
    for (const BodyId id : boxes) CHECK(test::near(w.body(id).position().y, T(0.5), T(0.02)));
    // Outside the filter the same calls work.
    w.set_contact_filter({});
    w.destroy_body(spare);
    CHECK(w.body_count() == 4);
}

TEST_CASE_TEMPLATE("a filter whose rejected call escapes leaves a world that can carry on", T, float, double) {
    World<T> w(test::awake_settings<T>());
    const std::vector<BodyId> boxes = resting_boxes(w, 2);
    w.set_contact_filter([&](BodyId, BodyId b) {
        w.destroy_body(b);  // not caught: step() throws
        return true;
    });
    CHECK_THROWS_AS(w.step(T(1) / T(60)), InvalidArgument);
    CHECK(w.body_count() == 3);
    w.set_contact_filter({});  // no longer "inside the filter"
    for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
    for (const BodyId id : boxes) CHECK(test::near(w.body(id).position().y, T(0.5), T(0.02)));
    w.destroy_body(boxes[0]);
    CHECK(w.body_count() == 2);
}

TEST_CASE_TEMPLATE("a listener that clears itself gets no further event", T, float, double) {
    World<T> w(test::awake_settings<T>());
    resting_boxes(w, 4);
    w.step(T(1) / T(60));
    REQUIRE(w.contact_events().size() == 4);
    int calls = 0;
    w.set_contact_listener([&calls](World<T>& world, const ContactEvent<T>&) {
        ++calls;
        world.set_contact_listener({});
    });
    w.step(T(1) / T(60));  // used to throw std::bad_function_call at the second event
    CHECK(calls == 1);
    w.step(T(1) / T(60));
    CHECK(calls == 1);
}

TEST_CASE_TEMPLATE("a listener that replaces itself finishes its call on its own captures", T, float, double) {
    World<T> w(test::awake_settings<T>());
    resting_boxes(w, 4);
    w.step(T(1) / T(60));
    int old_calls = 0, new_calls = 0;
    long long sum_after_replacing = 0;
    const auto payload = std::make_shared<std::vector<int>>(1000, 7);
    w.set_contact_listener([&, data = std::vector<int>(*payload)](World<T>& world, const ContactEvent<T>&) {
        ++old_calls;
        world.set_contact_listener([&new_calls](World<T>&, const ContactEvent<T>&) { ++new_calls; });
        // This closure's captures must still be alive here (the sanitizer build checks it).
        sum_after_replacing = std::accumulate(data.begin(), data.end(), 0LL);
    });
    w.step(T(1) / T(60));
    CHECK(old_calls == 1);
    CHECK(sum_after_replacing == 7000);
    CHECK(new_calls == 3);  // the rest of the step's events go to the new listener
    w.step(T(1) / T(60));
    CHECK(old_calls == 1);
    CHECK(new_calls == 7);
}

TEST_CASE_TEMPLATE("a listener may change the world but not step it", T, float, double) {
    World<T> w(test::awake_settings<T>());
    const std::vector<BodyId> boxes = resting_boxes(w, 3);
    w.step(T(1) / T(60));
    const std::vector<std::uint8_t> saved = save_snapshot(w);
    int step_rejected = 0, update_rejected = 0, restored = 0;
    std::vector<BodyId> created;
    const std::string tag(200, 'x');  // a capture on the heap, used after the restore below
    w.set_contact_listener([&, tag](World<T>& world, const ContactEvent<T>& e) {
        try {
            world.step(T(1) / T(60));
        } catch (const InvalidArgument& ex) {
            if (mentions(ex, "inside the contact listener")) ++step_rejected;
        }
        try {
            world.update(T(1));
        } catch (const InvalidArgument& ex) {
            if (mentions(ex, "inside the contact listener")) ++update_rejected;
        }
        if (restored == 0) {  // the first event rewinds the world (its listener stays)
            restore_snapshot(world, saved);
            ++restored;
            CHECK(tag.size() == 200);
            return;
        }
        if (world.contains(e.b) && e.b == boxes[2]) {
            world.destroy_body(e.b);
            BodyDef<T> d;
            d.position = {T(0), T(3), T(0)};
            created.push_back(world.create_body(Sphere<T>(T(0.3)), d));
        }
    });
    w.step(T(1) / T(60));
    CHECK(step_rejected == 3);
    CHECK(update_rejected == 3);
    CHECK(restored == 1);
    CHECK_FALSE(w.contains(boxes[2]));
    REQUIRE(created.size() == 1);
    CHECK(w.contains(created[0]));
    CHECK(w.body_count() == 4);
    w.set_contact_listener({});
    for (int i = 0; i < 30; ++i) w.step(T(1) / T(60));
    CHECK(is_finite(w.body(created[0]).position()));
}

TEST_CASE_TEMPLATE("regression: a listener that restores a snapshot or throws inside update() leaves the accumulator in range", T,
                   float, double) {
    // update() took a step's time from the accumulator after the step: a restore inside the
    // listener had already replaced the accumulator, which ended at -dt (interpolation factor -1,
    // and the world's own snapshot was rejected: "the accumulator must be finite and >= 0"); a
    // listener that threw left the step's time in it, to be stepped again.
    const T dt = T(1) / T(60);
    {
        World<T> w(test::awake_settings<T>());
        resting_boxes(w, 2);
        const std::vector<std::uint8_t> saved = save_snapshot(w);
        bool restored = false;
        w.set_contact_listener([&](World<T>& world, const ContactEvent<T>&) {
            if (!restored) restored = true, restore_snapshot(world, saved);
        });
        w.update(dt);
        CHECK(restored);
        CHECK(w.interpolation_factor() >= T(0));
        CHECK(w.interpolation_factor() < T(1));
        World<T> copy;
        CHECK_NOTHROW(restore_snapshot(copy, save_snapshot(w)));
    }
    {
        World<T> w(test::awake_settings<T>());
        resting_boxes(w, 2);
        w.set_contact_listener([](World<T>&, const ContactEvent<T>&) { throw std::runtime_error("listener"); });
        CHECK_THROWS_AS(w.update(T(0.1)), std::runtime_error);  // six steps due; the first one's listener throws
        CHECK(w.interpolation_factor() >= T(0));
        CHECK(w.interpolation_factor() < T(6));  // the step taken is not counted again
        CHECK(test::near(w.interpolation_factor(), T(5), T(1e-3)));
    }
}

TEST_CASE_TEMPLATE("regression: update() far behind drops the frames beyond its cap even when a listener throws", T, float,
                   double) {
    // The frames beyond max_steps_per_update were dropped after the loop, which a throwing
    // listener never reached: update(1000) left 999.98 s in the accumulator (interpolation factor
    // 59,994), and the next update(0) ran max_steps_per_update catch-up steps.
    World<T> w(test::awake_settings<T>());
    resting_boxes(w, 2);
    w.set_contact_listener([](World<T>&, const ContactEvent<T>&) { throw std::runtime_error("listener"); });
    CHECK_THROWS_AS(w.update(T(1000)), std::runtime_error);
    const T cap = static_cast<T>(w.settings().max_steps_per_update);
    CHECK(w.interpolation_factor() >= T(0));
    CHECK(w.interpolation_factor() < cap);  // the first step taken, the rest of the cap still due
    w.set_contact_listener(nullptr);
    CHECK(w.update(T(0)) <= w.settings().max_steps_per_update - 1);
    CHECK(w.interpolation_factor() >= T(0));
    CHECK(w.interpolation_factor() < T(1));
}

TEST_CASE_TEMPLATE("regression: copies and assignments made inside the callbacks carry no callback state", T, float, double) {
    // The flags "inside the filter / listener" were copied with the world: a copy made inside the
    // filter could never be changed or stepped, a checkpoint taken in the listener and assigned
    // back could never step again, a world assigned to inside the listener could step from it,
    // and one assigned to inside the filter was freed under the running step (ASan:
    // heap-use-after-free in World::active).
    const T dt = T(1) / T(60);
    {
        World<T> w(test::awake_settings<T>());
        resting_boxes(w, 2);
        std::optional<World<T>> copy;
        w.set_contact_filter([&](BodyId, BodyId) {
            if (!copy) copy.emplace(w);
            return true;
        });
        w.step(dt);
        REQUIRE(copy.has_value());
        CHECK_NOTHROW(copy->create_body(Sphere<T>(T(0.5))));
        CHECK_NOTHROW(copy->step(dt));
    }
    {
        World<T> w(test::awake_settings<T>());
        resting_boxes(w, 2);
        std::optional<World<T>> checkpoint;
        w.set_contact_listener([&](World<T>& world, const ContactEvent<T>&) {
            if (!checkpoint) checkpoint.emplace(world);
        });
        w.step(dt);
        REQUIRE(checkpoint.has_value());
        w = *checkpoint;  // back to the checkpoint, outside any callback
        CHECK_NOTHROW(w.step(dt));
    }
    {
        World<T> w(test::awake_settings<T>());
        resting_boxes(w, 2);
        const World<T> fresh(test::awake_settings<T>());
        bool rejected = false;
        w.set_contact_listener([&](World<T>& world, const ContactEvent<T>&) {
            world = fresh;  // allowed: the listener may restart the level
            try {
                world.step(dt);
            } catch (const InvalidArgument&) {
                rejected = true;
            }
        });
        w.step(dt);
        CHECK(rejected);  // still inside the listener after the assignment
    }
    {
        World<T> w(test::awake_settings<T>());
        resting_boxes(w, 2);
        const World<T> other(test::awake_settings<T>());
        int rejected = 0;
        w.set_contact_filter([&](BodyId, BodyId) {
            try {
                w = other;
            } catch (const InvalidArgument&) {
                ++rejected;
            }
            return true;
        });
        w.step(dt);
        CHECK(rejected > 0);
        CHECK(w.body_count() == 3);  // the ground and the two boxes, untouched
    }
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A step on several threads (docs/parallel.md): the default pool hands out every item once,
// worlds on 1, 2 and 3 workers and on a job system that cuts and orders the work at random end in
// the same bits with the same events, the physics on the pool is the closed form's, and the
// callbacks run on the stepping thread. scripts/test.sh also runs this file under
// ThreadSanitizer.
#include "robustness/state_hash.hpp"
#include "scenes/all.hpp"
#include "support/approx.hpp"
#include "support/shuffled_tasks.hpp"

#include <xeno/xeno.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

using namespace xeno;

TEST_CASE("the thread pool runs every item from 0 to count - 1 exactly once, call after call") {
    // 33 workers: more than the 32 ranges a call is cut into, so some threads have no share.
    for (const unsigned workers : {2u, 3u, 8u, 33u}) {
        ThreadPool pool(workers);
        CHECK(pool.workers() == workers);
        for (const std::uint32_t count : {1u, 7u, 64u, 1000u, 100000u}) {
            for (const std::uint32_t min_range : {1u, 16u, 256u}) {
                std::vector<std::atomic<int>> seen(count);
                for (int call = 0; call < 20; ++call) {
                    parallel_for(&pool, count, min_range, [&](std::uint32_t begin, std::uint32_t end) {
                        for (std::uint32_t i = begin; i < end; ++i) seen[i].fetch_add(1, std::memory_order_relaxed);
                    });
                }
                int wrong = 0;
                for (const std::atomic<int>& s : seen) wrong += s.load() == 20 ? 0 : 1;
                CAPTURE(workers);
                CAPTURE(count);
                CAPTURE(min_range);
                CHECK(wrong == 0);
            }
        }
    }
}

TEST_CASE("regression: a range that throws reaches the caller once every range is done, and the pool goes on") {
    // A worker's exception ended the process (std::terminate), and one thrown on the caller left
    // the workers running on the job while the caller unwound.
    ThreadPool pool(3);
    for (const std::uint32_t bad : {0u, 500u, 999u}) {
        std::atomic<std::uint32_t> visited{0};
        CHECK_THROWS_AS(parallel_for(&pool, 1000u, 1u,
                                     [&](std::uint32_t begin, std::uint32_t end) {
                                         visited.fetch_add(end - begin, std::memory_order_relaxed);
                                         if (begin <= bad && bad < end) throw std::runtime_error("range");
                                     }),
                        std::runtime_error);
        CHECK(visited.load() == 1000u);  // every range ran before the caller saw the exception
        std::atomic<std::uint32_t> items{0};
        parallel_for(&pool, 1000u, 1u, [&](std::uint32_t begin, std::uint32_t end) { items.fetch_add(end - begin); });
        CHECK(items.load() == 1000u);
    }
}

TEST_CASE_TEMPLATE("regression: a body at half the largest T beside a ball steps a long step on one and two workers", T, float,
                   double) {
    // The first-touch sweep of a ball's contact took the body's travel over 2 dt, beyond the
    // largest T, and handed it to shape_cast, which refused it: step threw half done, and on
    // two workers the process crashed (the exception left a worker, or left the caller while the
    // workers still ran). Such a travel is now no sweep.
    for (const unsigned workers : {1u, 2u}) {
        World<T> w;
        w.set_workers(workers);
        BodyDef<T> d;
        const BodyId ball = w.create_body(Sphere<T>(T(0.5)), d);
        BodyDef<T> k;
        k.type = BodyType::kinematic;
        k.position = {T(1.2), T(0), T(0)};
        const BodyId kin = w.create_body(Sphere<T>(T(0.5)), k);
        w.step(T(1) / 60);  // their speculative contact
        w.set_velocity(kin, Vec3<T>{-std::numeric_limits<T>::max(), T(0), T(0)}, Vec3<T>::zero());
        CHECK_NOTHROW(w.step(T(1)));
        CHECK_NOTHROW(w.step(T(1) / 60));
        CHECK(is_finite(w.body(ball).position()));
        CHECK(length(w.body(ball).linear_velocity()) <= w.settings().max_linear_speed);  // within the world's cap
    }
}

TEST_CASE("worker counts out of range are rejected and change nothing") {
    CHECK_THROWS_AS(ThreadPool(0), InvalidArgument);
    CHECK_THROWS_AS(ThreadPool(257), InvalidArgument);
    World<float> world;
    world.set_workers(2);
    CHECK_THROWS_AS(world.set_workers(0), InvalidArgument);
    CHECK_THROWS_AS(world.set_workers(257), InvalidArgument);
    CHECK(world.workers() == 2);
    world.set_workers(1);
    CHECK(world.workers() == 1);
}

namespace {

/// How a world spreads its step: 1 worker, the pool with n, or the shuffled job system.
struct Spread {
    const char* name;
    unsigned workers;
    bool shuffled;
};
constexpr Spread spreads[] = {{"1 worker", 1, false}, {"2 workers", 2, false}, {"3 workers", 3, false}, {"shuffled", 3, true}};

/// A world with the default settings, made by `build` and stepping as `spread` says, handed to
/// `steps`; returns what `steps` returns (the shuffled job system lives through the call).
template <class T, class Build, class Steps>
auto on_spread(const Spread& spread, const Build& build, const Steps& steps) {
    World<T> world;
    build(world);
    test::ShuffledTasks shuffled(spread.workers);
    if (spread.shuffled) world.set_task_system(&shuffled);
    else world.set_workers(spread.workers);
    return steps(world);
}

/// Checks that `record(spread)` gives on every spread what it gives on one worker.
template <class Record>
void check_same_on_every_spread(const Record& record) {
    const auto one = record(spreads[0]);
    for (const Spread& spread : spreads) {
        const std::string name = spread.name;
        CAPTURE(name);
        CHECK(record(spread) == one);
    }
}

/// Every event field that is a number, as bits, in order.
template <class T>
std::uint64_t events_hash(const World<T>& world) {
    test::Fnv1a h;
    for (const ContactEvent<T>& e : world.contact_events()) {
        h.add(static_cast<int>(e.kind));
        h.add(e.a.index);
        h.add(e.b.index);
        h.add(e.sensor);
        h.add(e.normal);
        h.add(e.count);
        for (const Vec3<T>& p : e.points) h.add(p);
        h.add(e.impulse);
    }
    return h.value();
}

/// The state and event hashes after every step of `scene` with the default settings.
template <class T>
std::vector<std::uint64_t> run(const std::string& scene, int steps, const Spread& spread) {
    return on_spread<T>(
        spread, [&](World<T>& world) { scenes::build<T>(scene, world); },
        [&](World<T>& world) {
            std::vector<std::uint64_t> hashes;
            for (int i = 0; i < steps; ++i) {
                world.step(world.settings().fixed_time_step);
                hashes.push_back(test::state_hash(world));
                hashes.push_back(events_hash(world));
            }
            return hashes;
        });
}

}  // namespace

TEST_CASE_TEMPLATE("every worker count and a shuffled job system give one worker's bits and events", T, float, double) {
    // Shapes of every kind, compounds (collided on the stepping thread), joints with contacts, a
    // pile that falls asleep (sleeping on: the defaults), and mesh pairs (collided on the workers).
    for (const char* scene : {"mixed-pile", "compound-stack", "ragdoll", "sleeping-pile", "terrain"}) {
        const std::string name = scene;
        CAPTURE(name);
        check_same_on_every_spread([&](const Spread& spread) { return run<T>(scene, 90, spread); });
    }
}

// A box put to sleep on the ground while a tilted kinematic box slides up its side, and from
// then on a contact filter vetoes the box and the ground: the veto wakes the box. One worker
// collides pairs in the merge, where the veto woke the box before its pair with the kinematic
// box was collided with the larger margin of a woken body; several workers had collided it
// before. The kinematic box's contact then had 4 points on one worker and 2 on two.
TEST_CASE_TEMPLATE("regression: a sleeper woken by a contact filter's veto steps to the same bits on any worker count", T, float,
                   double) {
    for (const double theta : {0.026, 0.027, 0.028}) {
        CAPTURE(theta);
        check_same_on_every_spread([&](const Spread& spread) {
            BodyId ground, box;
            bool veto = false;
            return on_spread<T>(
                spread,
                [&](World<T>& world) {
                    BodyDef<T> d;
                    d.type = BodyType::static_body;
                    d.position = {T(0), T(-1), T(0)};
                    ground = world.create_body(Box<T>(T(10), T(1), T(10)), d);
                    d.type = BodyType::dynamic;
                    d.position = {T(0), T(0.5), T(0)};
                    box = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
                    d.type = BodyType::kinematic;
                    d.position = {T(0.5 + 0.5 * std::cos(theta) + 0.5 * std::sin(theta) - 0.001), T(0.5), T(0)};
                    d.orientation = {T(std::cos(theta / 2)), T(0), T(std::sin(theta / 2)), T(0)};
                    d.linear_velocity = {T(0), T(0.2), T(0)};
                    world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
                    world.set_contact_filter([&](BodyId a, BodyId b) { return !(veto && a == ground && b == box); });
                },
                [&](World<T>& world) {
                    std::vector<std::uint64_t> hashes;
                    for (int i = 0; i < 20; ++i) {
                        if (i == 10) {
                            world.set_awake(box, false);
                            veto = true;
                        }
                        world.step(T(1) / T(60));
                        hashes.push_back(test::state_hash(world));
                    }
                    return hashes;
                });
        });
    }
}

TEST_CASE_TEMPLATE("bodies in one place, a hair apart or too far apart to measure step on several workers as on one", T, float,
                   double) {
    // Several workers order the solver bodies by cells along the axis the bodies spread most on
    // (World::order_solver_bodies_in_space): no spread, a spread of the smallest subnormal (cells
    // per metre overflow to infinity, 0 · ∞ is NaN) and one that overflows T must neither reach a
    // float-to-integer conversion out of range (UBSan in the sanitizer build) nor change a bit.
    const T far = std::numeric_limits<T>::max() / T(2);
    const T tiny = std::numeric_limits<T>::denorm_min();
    for (const T spread : {T(0), tiny, far}) {
        const auto place = [&](World<T>& world) {
            const auto ball = std::make_shared<const Shape<T>>(Sphere<T>(T(0.5)));
            for (int i = 0; i < 6; ++i) {
                BodyDef<T> def;
                def.position = {i % 2 == 0 ? -spread : spread, T(3 * (i / 2)), T(0)};
                world.create_body(ball, def);
            }
        };
        std::vector<std::uint64_t> hashes[2];
        for (int run_index = 0; run_index < 2; ++run_index) {
            World<T> world;
            world.set_workers(run_index == 0 ? 1u : 2u);
            place(world);
            for (int step = 0; step < 30; ++step) {
                world.step(world.settings().fixed_time_step);
                hashes[run_index].push_back(test::state_hash(world));
            }
        }
        CAPTURE(spread);
        CHECK(hashes[1] == hashes[0]);
    }
}

TEST_CASE_TEMPLATE("300 boxes spread over several sweep columns land on any worker count to one worker's bits", T, float,
                   double) {
    // Past 256 boxes spread on the ground the sweep and prune cuts the scene into columns, which
    // several workers sweep in parallel (broadphase/sweep_and_prune.hpp); the pairs whose boxes
    // overlap while the boxes inside do not are found apart by MPR's first test, W at a time on
    // the workers (World::reject_apart_pairs): as many on every worker count.
    const auto build = [](World<T>& world) {
        scenes::add_ground(world, T(40));
        scenes::Random rng(7);
        const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
        for (int i = 0; i < 300; ++i) {  // turned at random, their lowest corners 3 to 13 cm up
            BodyDef<T> def;
            def.position = {T(1.5) * T(i % 20 - 10), T(0.9) + T(0.05) * T(i % 3), T(1.5) * T(i / 20 - 8)};
            def.orientation = rng.rotation<T>();
            world.create_body(box, def);
        }
    };
    const auto steps = [](World<T>& world) {
        std::vector<std::uint64_t> out;
        std::size_t apart = 0;
        for (int i = 0; i < 20; ++i) {
            world.step(world.settings().fixed_time_step);
            out.push_back(test::state_hash(world));
            out.push_back(events_hash(world));
            out.push_back(world.last_step_stats().apart_pairs);
            apart += world.last_step_stats().apart_pairs;
        }
        CHECK(world.last_step_stats().contacts >= 300);  // every box has landed
        CHECK(apart >= 20 * 100);                        // the early-out had work on every step
        return out;
    };
    {  // the scene does cut into columns (a sweep of the same boxes, on its own)
        World<T> world;
        build(world);
        std::vector<Aabb<T>> boxes;
        for (std::uint32_t slot = 0; slot <= 300; ++slot) boxes.push_back(world.body(BodyId{slot, 0}).world_bounds());
        SweepAndPrune<T> sweep;
        std::vector<ProxyPair> pairs;
        sweep.find_pairs(boxes, pairs);
        REQUIRE(sweep.columns() >= 2);
    }
    check_same_on_every_spread([&](const Spread& spread) { return on_spread<T>(spread, build, steps); });
}

TEST_CASE_TEMPLATE("over 512 contacts, the events collected on several workers are one worker's, ended ones pending included", T,
                   float, double) {
    // Past two blocks of contacts (World::event_block) several workers collect the events in
    // parallel: counted per block, then written into place. Rows of boxes pressed side by side
    // (began, persisted), bodies destroyed between steps (their ended events wait for the next
    // report and come first) and boxes dropped onto the rows (began later).
    const auto build = [](World<T>& world) {
        scenes::add_ground(world, T(30));
        const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
        for (int i = 0; i < 300; ++i) {  // 15 rows of 20, each box 5 mm into its neighbour
            BodyDef<T> def;
            def.position = {T(0.995) * T(i % 20 - 10), T(0.5), T(1.5) * T(i / 20 - 7)};
            world.create_body(box, def);
        }
        for (int i = 0; i < 4; ++i) {  // landing on rows 2, 5, 8 and 11 after about ten steps
            BodyDef<T> def;
            def.position = {T(2 * i - 3), T(2.2), T(1.5) * T(3 * i + 2 - 7)};
            world.create_body(box, def);
        }
    };
    const auto steps = [](World<T>& world) {
        std::vector<std::uint64_t> out;
        std::size_t most = 0;
        for (int i = 0; i < 24; ++i) {
            if (i == 5)
                for (std::uint32_t slot = 3; slot <= 300; slot += 37) world.destroy_body(BodyId{slot, 0});
            world.step(world.settings().fixed_time_step);
            out.push_back(events_hash(world));
            most = std::max(most, world.contact_events().size());
        }
        CHECK(most >= 540);  // more than two blocks of contacts: the parallel collection was used
        return out;
    };
    check_same_on_every_spread([&](const Spread& spread) { return on_spread<T>(spread, build, steps); });
}

TEST_CASE_TEMPLATE("after steps on several workers the query tree answers as after one worker's", T, float, double) {
    // Several workers mark in parallel the bodies that leave their query leaves' boxes, and only
    // those are moved in the tree (World::update_query_tree). Boxes falling in layers leave them
    // every step, so the tree is also rebuilt; a body left unmarked would keep a stale leaf, and
    // the boxes and rays here (any-hit rays return the first body the tree's walk meets) would
    // tell. And every body must be found by a query of the lowest corner of its box (brute force:
    // a falling body leaves its old leaf through the bottom, so a leaf given its new box without
    // its ancestors refitted or the tree rebuilt would hide it there).
    const auto build = [](World<T>& world) {
        scenes::add_ground(world, T(30));
        scenes::Random rng(11);
        const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
        for (int i = 0; i < 300; ++i) {  // 4 layers of 9 × 9, 1.5 m apart
            BodyDef<T> def;
            def.position = {T(1.5) * T(i % 9 - 4), T(2) + T(1.5) * T(i / 81), T(1.5) * T(i % 81 / 9 - 4)};
            def.orientation = rng.rotation<T>();
            // Seven starting speeds, so that a step moves some of the leaves and not all.
            def.linear_velocity = {T(0), T(-0.5) * T(i % 7), T(0)};
            world.create_body(box, def);
        }
    };
    const auto steps = [](World<T>& world) {
        std::vector<std::int64_t> out;
        int hidden = 0;
        for (int step = 0; step < 25; ++step) {
            world.step(world.settings().fixed_time_step);
            world.for_each_body([&](BodyId id, const Body<T>& b) {
                const Vec3<T> low = b.world_bounds().min;
                const std::vector<BodyId> found = world.query_aabb(Aabb<T>{low, low + Vec3<T>::one() * T(0.001)});
                hidden += std::find(found.begin(), found.end(), id) == found.end() ? 1 : 0;
            });
            for (int k = 0; k < 9; ++k) {
                const T x = T(1.5) * T(k - 4), y = T(0.2) * T(k);
                for (const BodyId id : world.query_aabb(Aabb<T>{{x - T(1), y, T(-7)}, {x + T(1), y + T(1.5), T(7)}}))
                    out.push_back(id.index);
                out.push_back(-1);
                Ray<T> ray;
                ray.origin = {x + T(0.3), T(12), T(1.5) * T(k - 4) + T(0.2)};
                const std::optional<WorldRayHit<T>> any = world.raycast_any(ray);
                out.push_back(any ? std::int64_t(any->body.index) : -2);
            }
        }
        CHECK(hidden == 0);
        return out;
    };
    check_same_on_every_spread([&](const Spread& spread) { return on_spread<T>(spread, build, steps); });
}

TEST_CASE_TEMPLATE("300 boxes sliding at 5 m/s on two workers stop within 2 % of v^2/(2 mu g)", T, float, double) {
    // 300 rows with the ground share no moving body: one colour, enough groups that the pool
    // solves it on both threads. The defaults otherwise (sleeping on).
    World<T> world;
    world.set_workers(2);
    BodyDef<T> ground;
    ground.type = BodyType::static_body;
    ground.position = {T(0), T(-0.5), T(0)};
    ground.material.friction = T(0.5);
    world.create_body(Box<T>(T(50), T(0.5), T(50)), ground);
    const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.25), T(0.25), T(0.25)));
    std::vector<BodyId> ids;
    for (int i = 0; i < 300; ++i) {
        BodyDef<T> def;
        def.position = {T(-40) + T(1) * T(i % 20), T(0.25), T(-40) + T(2) * T(i / 20)};
        def.material.friction = T(0.5);
        ids.push_back(world.create_body(box, def));
    }
    for (int i = 0; i < 30; ++i) world.step(world.settings().fixed_time_step);  // settle
    std::vector<Vec3<T>> start;
    for (BodyId id : ids) {
        start.push_back(world.body(id).position());
        world.body(id).set_linear_velocity({T(5), T(0), T(0)});
    }
    world.step(world.settings().fixed_time_step);
    CHECK(world.last_step_stats().contacts >= 300);  // all sliding (and awake) at once
    CHECK(world.last_step_stats().colours >= 1);
    for (int i = 1; i < 180; ++i) world.step(world.settings().fixed_time_step);
    const T expected = T(25) / (T(2) * T(0.5) * T(9.81));
    T worst = T(0);
    for (std::size_t i = 0; i < ids.size(); ++i)
        worst = std::max(worst, std::abs(world.body(ids[i]).position().x - start[i].x - expected));
    CAPTURE(worst);
    CHECK(worst < T(0.02) * expected);
}

TEST_CASE("the contact filter and listener run on the stepping thread") {
    World<double> world;
    scenes::build<double>("rain", world);
    world.set_workers(3);
    const std::thread::id stepping = std::this_thread::get_id();
    int elsewhere = 0, filtered = 0, heard = 0;
    world.set_contact_filter([&](BodyId, BodyId) {
        ++filtered;
        elsewhere += std::this_thread::get_id() == stepping ? 0 : 1;
        return true;
    });
    world.set_contact_listener([&](World<double>& w, const ContactEvent<double>&) {
        ++heard;
        elsewhere += std::this_thread::get_id() == stepping ? 0 : 1;
        CHECK_THROWS_AS(w.set_workers(1), InvalidArgument);  // not while stepping
    });
    for (int i = 0; i < 120; ++i) world.step(1.0 / 60);
    CHECK(filtered > 0);
    CHECK(heard > 0);
    CHECK(elsewhere == 0);
}

TEST_CASE("between steps, several threads may query one world at once") {
    // The contract of world.hpp's queries: they keep no scratch in the world. Three threads cast
    // the same rays and shapes as the stepping thread did alone; the answers must be the same
    // (and ThreadSanitizer, which runs this file, must see no race).
    World<double> world;
    scenes::build<double>("mixed-pile", world);
    for (int i = 0; i < 60; ++i) world.step(1.0 / 60);
    auto answers = [&world](int first) {
        std::vector<double> out;
        for (int k = first; k < first + 200; ++k) {
            const double a = 0.1 * k;
            const Ray<double> ray{
                {4 * std::cos(a), 6, 4 * std::sin(a)}, normalized(Vec3<double>{-std::cos(a), -1.5, -std::sin(a)}), 20};
            if (const auto hit = world.raycast(ray)) out.push_back(hit->hit.distance);
            out.push_back(static_cast<double>(world.overlap_sphere({std::cos(a), 0.5, std::sin(a)}, 0.7).size()));
            const auto cast = world.shape_cast(Sphere<double>(0.2), {{std::cos(a), 5, std::sin(a)}, {}}, {0, -6, 0});
            out.push_back(cast ? cast->hit.fraction : -1.0);
        }
        return out;
    };
    const std::vector<double> alone = answers(0);
    std::vector<std::vector<double>> together(3);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < together.size(); ++t) threads.emplace_back([&, t] { together[t] = answers(0); });
    for (std::thread& t : threads) t.join();
    for (const std::vector<double>& answer : together) CHECK(answer == alone);
    CHECK(alone.size() > 400);
}

TEST_CASE("a copied world gets a pool of its own and steps to the original's bits") {
    World<float> world;
    scenes::build<float>("rain", world);
    world.set_workers(2);
    for (int i = 0; i < 30; ++i) world.step(1.0f / 60);
    World<float> copy = world;
    CHECK(copy.workers() == 2);
    World<float> moved = std::move(copy);
    CHECK(moved.workers() == 2);
    for (int i = 0; i < 60; ++i) {
        world.step(1.0f / 60);
        moved.step(1.0f / 60);
    }
    CHECK(test::state_hash(moved) == test::state_hash(world));
}

// World's destructor, copies and moves are declared in the class and defaulted after it, so that
// compiled mode compiles them once; they must stay what the implicit ones were.
static_assert(std::is_copy_constructible_v<World<float>> && std::is_copy_assignable_v<World<float>>);
static_assert(std::is_move_constructible_v<World<double>> && std::is_nothrow_move_assignable_v<World<double>>);
static_assert(!std::is_nothrow_move_constructible_v<World<double>>);  // std::deque's move may allocate

TEST_CASE("a world assigned by copy and by move steps to the original's bits") {
    World<double> world;
    scenes::build<double>("rain", world);
    world.set_workers(2);
    for (int i = 0; i < 30; ++i) world.step(1.0 / 60);
    World<double> copied;
    copied = world;
    CHECK(copied.workers() == 2);
    World<double> moved;
    moved = std::move(copied);
    CHECK(moved.workers() == 2);
    for (int i = 0; i < 60; ++i) {
        world.step(1.0 / 60);
        moved.step(1.0 / 60);
    }
    CHECK(test::state_hash(moved) == test::state_hash(world));
}

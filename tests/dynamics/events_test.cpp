// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Filtering (layers, masks, a veto callback), sensors and contact events.
#include "support/approx.hpp"
#include "support/sim.hpp"

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

using namespace xeno;

namespace {
template <class T>
BodyId drop_box(World<T>& w, T height, std::uint32_t layer = 1, std::uint32_t mask = ~0u) {
    BodyDef<T> d;
    d.position = {T(0), height, T(0)};
    d.layer = layer;
    d.mask = mask;
    return w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
}
}  // namespace

TEST_CASE_TEMPLATE("contact events begin once, persist while touching and end when apart", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    const BodyId ground = scenes::add_ground(w);
    const BodyId box = drop_box(w, T(1.5));
    int began = 0, persisted = 0, ended = 0, began_step = -1;
    T landing_impulse = T(0);  // over the step that began and the next: the stop spans both
    T last_persisted_impulse = T(0);
    test::simulate(w, T(1), [&](int step) {
        for (const ContactEvent<T>& e : w.contact_events()) {
            CHECK(e.a == ground);
            CHECK(e.b == box);
            if (e.kind == ContactEventKind::began) {
                ++began;
                began_step = step;
                landing_impulse += e.impulse;
                CHECK(e.count == 4);
                CHECK(test::near(e.normal, Vec3<T>::unit_y(), T(1e-4)));
            }
            if (e.kind == ContactEventKind::persisted) {
                ++persisted;
                if (step == began_step + 1) landing_impulse += e.impulse;
                last_persisted_impulse = e.impulse;
            }
            if (e.kind == ContactEventKind::ended) ++ended;
        }
    });
    CHECK(began == 1);
    CHECK(ended == 0);
    // Awake it persists every step after landing; with sleeping on it falls asleep about 0.5 s
    // after it stops, and a sleeping pair repeats no persisted events.
    CHECK(persisted > (C::sleeping ? 20 : 30));
    CHECK(persisted < (C::sleeping ? 40 : 34));
    // It fell 1 m: it lands after about sqrt(2/9.81) s = 27 steps; stopping it takes m v =
    // 1000 · 4.43 N·s, plus two steps of weight, m g dt each.
    CHECK(std::abs(began_step - 27) <= 2);
    const T expected = T(1000) * std::sqrt(T(2) * T(9.81)) + T(2) * T(1000) * T(9.81) / T(60);
    CHECK(std::abs(landing_impulse - expected) < T(0.1) * expected);
    // Resting: each step's impulse carries the weight, m g dt.
    const T rest = last_persisted_impulse;
    CHECK(test::near(rest, T(1000) * T(9.81) / T(60), T(0.02)));
    // Lifted away: one ended event.
    w.body(box).set_linear_velocity({T(0), T(5), T(0)});
    test::simulate(w, T(0.2), [&](int) {
        for (const ContactEvent<T>& e : w.contact_events()) ended += e.kind == ContactEventKind::ended;
    });
    CHECK(ended == 1);
}

TEST_CASE_TEMPLATE("the ended events of bodies destroyed between steps join the step's events in pair order", T, float, double) {
    // The step's events come in pair order, and the ended events recorded between steps are
    // merged in (World::sort_events). 300 boxes in rows on the ground, each touching its
    // neighbours; some destroyed between steps, on one worker and on two (which collect the
    // events in parallel past 512 contacts).
    for (const unsigned workers : {1u, 2u}) {
        CAPTURE(workers);
        World<T> w;
        w.set_workers(workers);
        scenes::add_ground(w, T(40));
        const auto box = std::make_shared<const Shape<T>>(Box<T>(T(0.5), T(0.5), T(0.5)));
        for (int i = 0; i < 300; ++i) {
            BodyDef<T> d;
            d.position = {T(i % 25 - 12), T(0.5), T(1.5) * T(i / 25 - 6)};
            w.create_body(box, d);
        }
        for (int i = 0; i < 3; ++i) w.step(w.settings().fixed_time_step);
        for (int round = 0; round < 3; ++round) {
            CAPTURE(round);
            std::vector<std::uint32_t> victims;
            for (std::uint32_t k = 0; k < 5; ++k) victims.push_back(2 + 8 * std::uint32_t(round) + 61 * k);
            const auto victim = [&](BodyId id) { return std::find(victims.begin(), victims.end(), id.index) != victims.end(); };
            std::vector<std::pair<std::uint32_t, std::uint32_t>> touching;  // the victims' pairs before
            for (const ContactEvent<T>& e : w.contact_events())
                if (e.kind != ContactEventKind::ended && (victim(e.a) || victim(e.b))) touching.push_back({e.a.index, e.b.index});
            REQUIRE(touching.size() >= 5);  // the ground, at least
            for (const std::uint32_t slot : victims) w.destroy_body(BodyId{slot, 0});
            w.step(w.settings().fixed_time_step);
            const std::vector<ContactEvent<T>>& events = w.contact_events();
            std::vector<std::pair<std::uint32_t, std::uint32_t>> ended;
            for (std::size_t i = 0; i < events.size(); ++i) {
                const std::pair<std::uint32_t, std::uint32_t> pair{events[i].a.index, events[i].b.index};
                if (i > 0) CHECK(std::make_pair(events[i - 1].a.index, events[i - 1].b.index) < pair);  // in pair order
                if (victim(events[i].a) || victim(events[i].b)) {
                    CHECK(events[i].kind == ContactEventKind::ended);
                    ended.push_back(pair);
                }
            }
            CHECK(ended == touching);
            CHECK(events.size() - ended.size() >= 2 * 256);  // the step's own: past two blocks of 256 contacts
        }
    }
}

TEST_CASE_TEMPLATE("without relax iterations a resting box's step impulse still carries its weight", T, float, double) {
    // The step totals are summed in each substep's last pass, which is the biased one when
    // relax_iterations and first_relax_iterations are 0 (World::solve).
    WorldSettings<T> settings;
    settings.relax_iterations = 0;
    settings.first_relax_iterations = 0;
    settings.allow_sleeping = false;
    World<T> w(settings);
    scenes::add_ground(w);
    drop_box(w, T(0.5));
    test::simulate(w, T(1), [](int) {});
    REQUIRE(w.contact_events().size() == 1);
    CHECK(test::near(w.contact_events()[0].impulse, T(1000) * T(9.81) / T(60), T(0.02)));
}

TEST_CASE_TEMPLATE("a listener may destroy bodies while events are delivered", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    scenes::add_ground(w);
    std::vector<BodyId> boxes;
    for (int i = 0; i < 5; ++i) {
        BodyDef<T> d;
        d.position = {T(2) * T(i), T(0.6) + T(0.2) * T(i), T(0)};
        boxes.push_back(w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d));
    }
    int destroyed = 0;
    w.set_contact_listener([&](World<T>& world, const ContactEvent<T>& e) {
        if (e.kind == ContactEventKind::began && world.contains(e.b)) {
            world.destroy_body(e.b);  // every box that lands disappears
            ++destroyed;
        }
    });
    test::simulate(w, T(2));
    CHECK(destroyed == 5);
    CHECK(w.body_count() == 1);
    CHECK(w.contacts().empty());
}

TEST_CASE_TEMPLATE("layers, masks and a filter callback keep pairs apart", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    scenes::add_ground(w);
    // Layer 2 does not collide with layer 4: the upper box falls through the lower one.
    const BodyId lower = drop_box(w, T(0.5), 2u, ~4u);
    const BodyId upper = drop_box(w, T(2), 4u, ~2u);
    test::simulate(w, T(1.5));
    CHECK(test::near(w.body(lower).position().y, T(0.5), T(1e-3)));
    CHECK(test::near(w.body(upper).position().y, T(0.5), T(1e-3)));  // both on the ground, overlapping
    // A filter vetoing the pair with the ground lets a third box fall through the floor.
    const BodyId ghost = drop_box(w, T(4));
    w.set_contact_filter([&](BodyId a, BodyId b) { return a != ghost && b != ghost; });
    test::simulate(w, T(1.5));
    CHECK(w.body(ghost).position().y < T(-2));
    w.set_contact_filter({});
}

TEST_CASE_TEMPLATE("a sensor reports overlaps and never pushes", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    scenes::add_ground(w);
    BodyDef<T> s;
    s.type = BodyType::static_body;
    s.sensor = true;
    s.position = {T(0), T(3), T(0)};
    const BodyId sensor = w.create_body(Box<T>(T(1), T(0.5), T(1)), s);
    const BodyId box = drop_box(w, T(5));
    int began = 0, ended = 0;
    test::simulate(w, T(1.5), [&](int) {
        for (const ContactEvent<T>& e : w.contact_events()) {
            if (!(e.a == sensor || e.b == sensor)) continue;
            CHECK(e.sensor);
            began += e.kind == ContactEventKind::began;
            ended += e.kind == ContactEventKind::ended;
        }
    });
    CHECK(began == 1);
    CHECK(ended == 1);                                             // it fell through the sensor
    CHECK(test::near(w.body(box).position().y, T(0.5), T(1e-3)));  // and landed on the ground
}

TEST_CASE_TEMPLATE("regression: without warm starting a resting box's events carry its weight, m g dt a step", T, float, double) {
    // warm_starting = false starts each step from zero impulses; the substeps used not to apply
    // the impulse they had accumulated, so a box resting on the ground reported (n + 1)/2 = 4.5
    // times its weight over the 8 substeps (735 N·s a step for 164) and its rows could pull.
    WorldSettings<T> settings;
    settings.warm_starting = false;
    settings.allow_sleeping = false;
    World<T> w(settings);
    scenes::add_ground(w);
    const BodyId box = drop_box(w, T(0.5));
    test::simulate(w, T(1), [](int) {});
    REQUIRE(w.contact_events().size() == 1);
    const T weight_per_step = T(1000) * T(9.81) / T(60);  // a 1 m cube of 1000 kg/m³
    CHECK(test::near(w.contact_events()[0].impulse, weight_per_step, T(0.02) * weight_per_step));
    CHECK(test::near(w.body(box).position().y, T(0.5), T(0.01)));
}

TEST_CASE_TEMPLATE("regression: a static or kinematic sensor created over a sleeping box reports the overlap", T, float, double) {
    // Two inactive bodies are never collided: a trigger spawned over a settled box never began.
    for (const BodyType type : {BodyType::static_body, BodyType::kinematic}) {
        CAPTURE(static_cast<int>(type));
        World<T> w;
        scenes::add_ground(w);
        const BodyId box = drop_box(w, T(0.5));
        test::simulate(w, T(2), [](int) {});
        REQUIRE(!w.body(box).awake());
        BodyDef<T> s;
        s.type = type;
        s.sensor = true;
        s.position = {T(0), T(1), T(0)};
        const BodyId sensor = w.create_body(Box<T>(T(1), T(1), T(1)), s);
        int began = 0;
        test::simulate(w, T(0.5), [&](int) {
            for (const ContactEvent<T>& e : w.contact_events())
                began += e.kind == ContactEventKind::began && e.sensor && (e.a == sensor || e.b == sensor) &&
                         (e.a == box || e.b == box);
        });
        CHECK(began == 1);
        CHECK(test::near(w.body(box).position().y, T(0.5), T(1e-3)));  // a sensor never pushes
    }
}

TEST_CASE_TEMPLATE("regression: turning a body into a sensor ends its contacts, which begin again as overlaps", T, float,
                   double) {
    // The pair's events used to persist with their sensor flag flipped: no `ended` for the solid
    // contact, no `began` for the overlap (and back).
    World<T> w;
    const BodyId ground = scenes::add_ground(w);
    const BodyId box = drop_box(w, T(0.5));
    test::simulate(w, T(0.5), [](int) {});
    const auto pair_events = [&] {
        std::vector<std::pair<ContactEventKind, bool>> out;
        for (const ContactEvent<T>& e : w.contact_events())
            if ((e.a == ground && e.b == box) || (e.a == box && e.b == ground)) out.push_back({e.kind, e.sensor});
        return out;
    };
    using Kinds = std::vector<std::pair<ContactEventKind, bool>>;
    w.set_sensor(ground, true);
    w.step(w.settings().fixed_time_step);
    CHECK(pair_events() == Kinds{{ContactEventKind::ended, false}, {ContactEventKind::began, true}});
    w.set_sensor(ground, false);
    w.step(w.settings().fixed_time_step);
    CHECK(pair_events() == Kinds{{ContactEventKind::ended, true}, {ContactEventKind::began, false}});
    w.step(w.settings().fixed_time_step);
    CHECK(pair_events() == Kinds{{ContactEventKind::persisted, false}});
}

TEST_CASE_TEMPLATE("a compound's part pairs report their own events, told apart by their part indices", C, XENO_TEST_CONFIGS) {
    // A dumbbell (two boxes 1 m apart) dropped on the ground, one end then lifted by an impulse.
    // Every step, the part pairs whose last event began or persisted are exactly those whose
    // contact touches (contacts_of, an independent record): an end that lifts ends alone.
    using T = typename C::T;
    World<T> w(C::settings());
    const BodyId ground = scenes::add_ground(w);
    const Compound<T> dumbbell({{Box<T>(T(0.25), T(0.25), T(0.25)), {{T(-1), T(0), T(0)}, Quat<T>::identity()}},
                                {Box<T>(T(0.25), T(0.25), T(0.25)), {{T(1), T(0), T(0)}, Quat<T>::identity()}}});
    BodyDef<T> d;
    d.position = {T(0), T(0.3), T(0)};
    const BodyId bar = w.create_body(dumbbell, d);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> live;  // part pairs touching by the events
    int began = 0, ended = 0;
    test::simulate(w, T(3), [&](int step) {
        if (step == 60) w.body(bar).apply_impulse_at({T(0), T(400), T(0)}, w.body(bar).world_point({T(1), T(0), T(0)}));
        for (const ContactEvent<T>& e : w.contact_events()) {
            REQUIRE((e.a == ground && e.b == bar));
            CHECK(e.child_a == 0);
            const std::pair<std::uint32_t, std::uint32_t> parts{e.child_a, e.child_b};
            const auto at = std::find(live.begin(), live.end(), parts);
            if (e.kind == ContactEventKind::began) {
                CHECK(at == live.end());
                live.push_back(parts);
                ++began;
            } else if (e.kind == ContactEventKind::ended) {
                REQUIRE(at != live.end());
                live.erase(at);
                ++ended;
            } else {
                CHECK(at != live.end());
            }
        }
        std::vector<std::pair<std::uint32_t, std::uint32_t>> touching;
        for (const Contact<T>& c : w.contacts_of(bar))
            if (c.touching) touching.push_back({c.child_a, c.child_b});
        std::sort(live.begin(), live.end());
        std::sort(touching.begin(), touching.end());
        CHECK(live == touching);
    });
    CHECK(began >= 3);  // both ends landed, and the lifted end came down again
    CHECK(ended >= 1);  // the lifted end left the ground while the other stayed
}

TEST_CASE_TEMPLATE("regression: with a compound in the world a reused slot's began still follows the old body's ended", T, float,
                   double) {
    // The compound's two part contacts with the ground made the step's events not strictly
    // increasing, which sorted them all with std::sort: not stable, so a destroyed body's `ended`
    // and its slot's new body's `began` (the same pair of slots) came out in either order.
    World<T> w;
    const BodyId ground = scenes::add_ground(w, T(40));
    const Compound<T> dumbbell({{Box<T>(T(0.25), T(0.25), T(0.25)), {{T(-1), T(0), T(0)}, Quat<T>::identity()}},
                                {Box<T>(T(0.25), T(0.25), T(0.25)), {{T(1), T(0), T(0)}, Quat<T>::identity()}}});
    BodyDef<T> d;
    d.position = {T(0), T(0.25), T(-10)};
    w.create_body(dumbbell, d);
    std::vector<BodyId> boxes;
    for (int i = 0; i < 60; ++i) boxes.push_back(drop_box(w, T(0.5)));
    for (int i = 0; i < 60; ++i)
        w.set_transform(boxes[std::size_t(i)], {T(2) * T(i % 10 - 5), T(0.5), T(2) * T(i / 10)}, Quat<T>::identity());
    for (int i = 0; i < 5; ++i) w.step(w.settings().fixed_time_step);
    std::vector<BodyId> fresh;
    for (int i = 0; i < 60; i += 5) {
        const Vec3<T> p = w.body(boxes[std::size_t(i)]).position();
        w.destroy_body(boxes[std::size_t(i)]);
        fresh.push_back(drop_box(w, p.y));
        w.set_transform(fresh.back(), p, Quat<T>::identity());
        REQUIRE(fresh.back().index == boxes[std::size_t(i)].index);  // the slot is reused
    }
    w.step(w.settings().fixed_time_step);
    int checked = 0;
    for (const BodyId id : fresh) {
        int ended_at = -1, began_at = -1;
        const std::vector<ContactEvent<T>>& events = w.contact_events();
        for (std::size_t i = 0; i < events.size(); ++i) {
            if (!(events[i].a == ground || events[i].b == ground)) continue;
            if (events[i].a.index != id.index && events[i].b.index != id.index) continue;
            if (events[i].kind == ContactEventKind::ended) ended_at = static_cast<int>(i);
            if (events[i].kind == ContactEventKind::began) began_at = static_cast<int>(i);
        }
        REQUIRE(ended_at >= 0);
        REQUIRE(began_at >= 0);
        CHECK(ended_at < began_at);
        ++checked;
    }
    CHECK(checked == 12);
}

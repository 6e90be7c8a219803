// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// World::contacts_of against a scan of contacts(): the same contacts, in the same order, for
// every body of a settled mixed pile, after bodies are destroyed and created between steps, and
// after a snapshot is restored.
#include "scenes/all.hpp"

#include <xeno/dynamics/snapshot.hpp>
#include <xeno/dynamics/world.hpp>

#include <doctest/doctest.h>

#include <vector>

using namespace xeno;

namespace {

/// Checks every living body's contacts_of() against the contacts naming it; returns how many
/// (body, contact) entries were compared.
template <class T>
std::size_t check_every_body(const World<T>& world) {
    std::size_t compared = 0;
    world.for_each_body([&](BodyId id, const Body<T>&) {
        std::vector<const Contact<T>*> expected, got;
        for (const Contact<T>& c : world.contacts())
            if (c.a == id || c.b == id) expected.push_back(&c);
        for (const Contact<T>& c : world.contacts_of(id)) got.push_back(&c);
        CAPTURE(id.index);
        CHECK(got == expected);
        CHECK(world.contacts_of(id).size() == expected.size());
        compared += expected.size();
    });
    return compared;
}

}  // namespace

TEST_CASE_TEMPLATE("contacts_of gives a body's contacts as a scan of contacts() does, through steps, changes and a restore", T,
                   float, double) {
    World<T> world;  // default settings: sleeping on
    scenes::mixed_pile(world, 60);
    for (int i = 0; i < 120; ++i) world.step(T(1) / T(60));
    const std::size_t settled = check_every_body(world);
    CHECK(settled > 100);  // a pile: most bodies have several contacts

    // Destroy every fifth body between steps: their contacts go, the others' ranges shrink.
    std::vector<BodyId> doomed;
    world.for_each_body([&](BodyId id, const Body<T>& b) {
        if (id.index % 5 == 3 && b.type() == BodyType::dynamic) doomed.push_back(id);
    });
    REQUIRE(!doomed.empty());
    for (const BodyId id : doomed) world.destroy_body(id);
    check_every_body(world);
    for (const Contact<T>& c : world.contacts())
        for (const BodyId id : doomed) CHECK((c.a != id && c.b != id));
    CHECK_THROWS_AS(world.contacts_of(doomed.front()), InvalidArgument);  // a stale handle

    // A body created since the last step has no contacts yet, even in a reused slot.
    BodyDef<T> def;
    def.position = {T(0), T(3), T(0)};
    const BodyId fresh = world.create_body(Sphere<T>(T(0.5)), def);
    CHECK(world.contacts_of(fresh).empty());
    check_every_body(world);
    for (int i = 0; i < 30; ++i) world.step(T(1) / T(60));
    check_every_body(world);

    World<T> restored;
    restore_snapshot(restored, save_snapshot(world));
    CHECK(check_every_body(restored) == check_every_body(world));
}

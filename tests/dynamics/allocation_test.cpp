// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A settled world steps without touching the heap: the world keeps its scratch (contacts of the
// next step, islands, events and the listener's copy of them) between steps. Counted by replacing
// the global operator new for this test executable; the counter only counts, so other tests are
// unaffected.
#include "support/sim.hpp"

#include <xeno/dynamics/snapshot.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> allocations{0};
std::atomic<long> allocated_bytes{0};  ///< requested, never subtracted
}  // namespace

void* operator new(std::size_t size) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    allocated_bytes.fetch_add(static_cast<long>(size), std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// The nothrow forms too (std::stable_sort's temporary buffer uses them): a replaced delete must
// never free what the library's own new allocated (AddressSanitizer: alloc-dealloc-mismatch).
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    allocations.fetch_add(1, std::memory_order_relaxed);
    allocated_bytes.fetch_add(static_cast<long>(size), std::memory_order_relaxed);
    return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace xeno;

namespace {

// Floor, a column of three boxes, a sphere and a capsule at rest, a hinged pair: contacts,
// manifolds of several kinds, a joint and (with a listener) events every step.
template <class T>
void build_settled_scene(World<T>& w) {
    BodyDef<T> floor;
    floor.type = BodyType::static_body;
    floor.position = {T(0), T(-0.5), T(0)};
    const BodyId ground = w.create_body(Box<T>(T(20), T(0.5), T(20)), floor);
    BodyDef<T> d;
    for (int i = 0; i < 3; ++i) {
        d.position = {T(0), T(0.5) + T(i), T(0)};
        w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    }
    d.position = {T(3), T(0.5), T(0)};
    w.create_body(Sphere<T>(T(0.5)), d);
    d.position = {T(-3), T(0.3), T(0)};
    d.orientation = Quat<T>::from_axis_angle({T(0), T(0), T(1)}, T(1.5707963));
    w.create_body(Capsule<T>(T(0.3), T(0.5)), d);
    d.orientation = Quat<T>::identity();
    d.position = {T(0), T(0.25), T(4)};
    const BodyId door = w.create_body(Box<T>(T(0.5), T(0.25), T(0.1)), d);
    JointDef<T> hinge;
    hinge.type = JointType::hinge;
    hinge.a = ground;
    hinge.b = door;
    hinge.anchor_a = {T(-0.5), T(0.25), T(4)};
    hinge.axis = {T(0), T(1), T(0)};
    w.create_joint(hinge);
}

template <class T>
long allocations_per_settled_steps(bool sleeping, bool listener) {
    WorldSettings<T> s;
    s.allow_sleeping = sleeping;
    World<T> w(s);
    build_settled_scene(w);
    int heard = 0;
    if (listener) w.set_contact_listener([&](World<T>&, const ContactEvent<T>&) { ++heard; });
    test::simulate(w, T(3));  // settle (and fall asleep when allowed); scratch grows here
    const long before = allocations.load();
    test::simulate(w, T(1));
    const long after = allocations.load();
    if (listener && !sleeping) CHECK(heard > 0);
    return after - before;
}

}  // namespace

TEST_CASE_TEMPLATE("a settled world steps without allocating", T, float, double) {
    for (const bool sleeping : {true, false})
        for (const bool listener : {false, true}) {
            CAPTURE(sleeping);
            CAPTURE(listener);
            CHECK(allocations_per_settled_steps<T>(sleeping, listener) == 0);
        }
}

TEST_CASE("reserve and 1,000 moving bodies allocate no room in the static bodies' query tree") {
    // The body (224 bytes in float), its world box and last pose (52), the moving bodies' query
    // tree (84: two 40-byte nodes and the leaf's index; a rebuild works in place) and the
    // deque's blocks: about 375 bytes a body. Both query trees sized for every body took 552
    // (the static one never used here); a tree that kept a second copy of the fat boxes, a
    // rebuild buffer of boxes and a proxy id in every node, 420.
    const auto box = std::make_shared<const Shape<float>>(Box<float>(0.5f, 0.5f, 0.5f));
    std::vector<BodyId> ids;
    ids.reserve(1000);
    const long before = allocated_bytes.load();
    World<float> w;
    w.reserve(1000);
    for (int i = 0; i < 1000; ++i) {
        BodyDef<float> d;
        d.position = {3.0f * static_cast<float>(i % 10), 3.0f * static_cast<float>(i / 10 % 10),
                      3.0f * static_cast<float>(i / 100)};
        ids.push_back(w.create_body(box, d));
    }
    const double per_body = static_cast<double>(allocated_bytes.load() - before) / 1000.0;
    CAPTURE(per_body);
    CHECK(per_body < 400.0);
    // A body turned static still finds room in the static bodies' tree, and queries see it.
    w.set_type(ids[0], BodyType::static_body);
    const std::vector<BodyId> hits = w.query_point({0.0f, 0.0f, 0.0f});
    REQUIRE(hits.size() == 1);
    CHECK(hits[0] == ids[0]);
}

TEST_CASE_TEMPLATE("regression: a snapshot claiming more shapes or bodies than its bytes hold allocates in proportion to it", T,
                   float, double) {
    // Counts were bounded by the buffer's size in bytes, and the tables sized by them up front: an
    // 8 MB buffer of zeros after a header claimed 1.6 million dead body slots and allocated 2.4 GB
    // before it was found truncated; 16 MB of sphere records no body used were accepted (820 MB).
    const std::vector<std::uint8_t> empty = save_snapshot(World<T>());
    const std::size_t counts = empty.size() - 10 * 8;  // shapes, compounds, bodies, then 7 tables
    auto put = [](std::vector<std::uint8_t>& b, auto value) {
        const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
        b.insert(b.end(), p, p + sizeof(value));
    };
    const std::size_t megabyte = 1 << 20;
    std::vector<std::uint8_t> spheres(empty.begin(), empty.begin() + static_cast<std::ptrdiff_t>(counts));
    const std::uint64_t sphere_count = megabyte / (4 + sizeof(T));
    put(spheres, sphere_count);
    for (std::uint64_t i = 0; i < sphere_count; ++i) put(spheres, std::uint32_t(0)), put(spheres, T(0.5));
    for (int i = 0; i < 9; ++i) put(spheres, std::uint64_t(0));
    std::vector<std::uint8_t> slots(empty.begin(), empty.begin() + static_cast<std::ptrdiff_t>(counts));
    put(slots, std::uint64_t(0)), put(slots, std::uint64_t(0)), put(slots, std::uint64_t(megabyte / 5));
    slots.resize(slots.size() + megabyte);  // dead slots: alive 0, generation 0; no tables after them
    for (const std::vector<std::uint8_t>* bytes : {&spheres, &slots}) {
        World<T> w;
        const long before = allocated_bytes.load();
        CHECK_THROWS_AS(restore_snapshot(w, *bytes), InvalidArgument);
        const long used = allocated_bytes.load() - before;
        CAPTURE(used);
        CHECK(used < 8 * static_cast<long>(bytes->size()));
    }
}

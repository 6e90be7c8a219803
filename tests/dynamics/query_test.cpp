// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The world's queries (dynamics/world_query.hpp) against a scan of every living body with the
// same exact tests: the query tree may only decide which bodies are tried, never the answer. The
// scenes mix every shape kind, compounds, static, kinematic and fast dynamic bodies, sensors and
// layers; they are stepped (bodies fall, sleep, fly), changed (destroyed, created, teleported)
// and restored from a snapshot, and every query is compared after each change, with and without
// filters, in the default settings.
#include "scenes/random.hpp"

#include <xeno/dynamics/snapshot.hpp>
#include <xeno/dynamics/world.hpp>
#include <xeno/shape/polyhedra.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <optional>
#include <vector>

using namespace xeno;

namespace {

template <class T>
Shape<T> random_query_shape(scenes::Random& rng) {
    const T a = rng.uniform(T(0.2), T(1)), b = rng.uniform(T(0.2), T(1)), c = rng.uniform(T(0.2), T(1));
    switch (rng.index(6)) {
        case 0: return Sphere<T>(a);
        case 1: return Box<T>(a, b, c);
        case 2: return Capsule<T>(a * T(0.5), b);
        case 3: return Cylinder<T>(a, b);
        case 4: return Cone<T>(a, b);
        default: return make_regular_prism(5, a, b);
    }
}

/// A world of n bodies in a 30 m cube over a static ground: mixed shapes, a few compounds,
/// static and kinematic bodies, sensors, layers 1, 2 and 4, some thrown fast.
template <class T>
World<T> random_world(scenes::Random& rng, int n) {
    World<T> world;
    BodyDef<T> ground;
    ground.type = BodyType::static_body;
    ground.position = {T(0), T(-1), T(0)};
    world.create_body(Box<T>(T(40), T(1), T(40)), ground);
    for (int i = 0; i < n; ++i) {
        BodyDef<T> def;
        def.position = rng.in_box(Vec3<T>{T(15), T(15), T(15)}) + Vec3<T>{T(0), T(16), T(0)};
        def.orientation = rng.rotation<T>();
        const std::uint32_t kind = rng.index(10);
        def.type = kind == 0 ? BodyType::static_body : (kind == 1 ? BodyType::kinematic : BodyType::dynamic);
        def.sensor = rng.index(8) == 0;
        def.layer = std::uint32_t(1) << rng.index(3);
        if (def.type != BodyType::static_body)
            def.linear_velocity = rng.direction<T>() * rng.uniform(T(0), T(rng.index(5) == 0 ? 60 : 3));
        if (rng.index(8) == 0) {
            std::vector<CompoundChild<T>> parts;
            for (int k = 0; k < 3; ++k)
                parts.push_back({random_query_shape<T>(rng), {rng.in_box(Vec3<T>::one()), rng.rotation<T>()}});
            world.create_body(Compound<T>(std::move(parts)), def);
        } else {
            world.create_body(random_query_shape<T>(rng), def);
        }
    }
    return world;
}

template <class T>
std::vector<std::uint32_t> living_slots(const World<T>& world) {
    std::vector<std::uint32_t> slots;
    world.for_each_body([&](BodyId id, const Body<T>&) { slots.push_back(id.index); });
    return slots;
}

template <class T>
std::optional<RayHit<T>> scan_hit(const Body<T>& b, const Ray<T>& ray) {
    std::optional<RayHit<T>> nearest;
    for (std::uint32_t k = 0; k < b.child_count(); ++k)
        if (const auto hit = raycast(b.child_shape(k), b.child_transform(k), ray))
            if (!nearest || hit->distance < nearest->distance) nearest = hit;
    return nearest;
}

/// Every body the ray hits, by scanning all of them: nearest first, ties by slot.
template <class T>
std::vector<WorldRayHit<T>> scan_ray(const World<T>& world, const Ray<T>& ray, const QueryFilter<T>& filter) {
    std::vector<WorldRayHit<T>> hits;
    world.for_each_body([&](BodyId id, const Body<T>& b) {
        if (!filter.passes(id, b)) return;
        if (const auto hit = scan_hit(b, ray)) hits.push_back({id, *hit});
    });
    std::sort(hits.begin(), hits.end(), [](const WorldRayHit<T>& x, const WorldRayHit<T>& y) {
        return x.hit.distance != y.hit.distance ? x.hit.distance < y.hit.distance : x.body.index < y.body.index;
    });
    return hits;
}

template <class T>
bool same_hit(const WorldRayHit<T>& x, const WorldRayHit<T>& y) {
    return x.body == y.body && x.hit.distance == y.hit.distance && x.hit.point == y.hit.point && x.hit.normal == y.hit.normal;
}

template <class T, class Exact>
std::vector<BodyId> scan_overlap(const World<T>& world, const QueryFilter<T>& filter, Exact&& exact) {
    std::vector<BodyId> out;
    world.for_each_body([&](BodyId id, const Body<T>& b) {
        if (filter.passes(id, b) && exact(b)) out.push_back(id);
    });
    return out;
}

template <class T>
QueryFilter<T> random_filter(scenes::Random& rng, const World<T>& world) {
    QueryFilter<T> f;
    if (rng.index(2) == 0) return f;  // the default half of the time
    f.mask = rng.index(2) == 0 ? ~std::uint32_t(0) : (1u + rng.index(7));
    f.ignore_static = rng.index(2) == 0;
    f.ignore_sensors = rng.index(2) == 0;
    const std::vector<std::uint32_t> slots = living_slots(world);
    if (rng.index(2) == 0) f.ignore_body = BodyId{slots[rng.index(static_cast<std::uint32_t>(slots.size()))], 0};
    if (rng.index(3) == 0) f.accept = [](BodyId id, const Body<T>&) { return id.index % 3 != 1; };
    // ignore_body needs the living generation: take it from the world.
    if (f.ignore_body.index != BodyId::invalid_index)
        world.for_each_body([&](BodyId id, const Body<T>&) {
            if (id.index == f.ignore_body.index) f.ignore_body = id;
        });
    return f;
}

struct Counts {
    int ray_hits = 0, overlaps = 0;
};

/// Random rays and overlap queries, each against the scan.
template <class T>
void check_queries(scenes::Random& rng, const World<T>& world, int queries, Counts& counts) {
    for (int q = 0; q < queries; ++q) {
        CAPTURE(q);
        const QueryFilter<T> filter = random_filter(rng, world);
        const Vec3<T> from = rng.in_box(Vec3<T>{T(20), T(20), T(20)}) + Vec3<T>{T(0), T(12), T(0)};
        const T length = rng.index(4) == 0 ? ScalarTraits<T>::max : rng.uniform(T(0.5), T(40));
        // Half the rays aim at a body (they hit things), half go anywhere.
        Vec3<T> direction = rng.direction<T>();
        if (rng.index(2) == 0) {
            const std::vector<std::uint32_t> slots = living_slots(world);
            const std::uint32_t target = slots[rng.index(static_cast<std::uint32_t>(slots.size()))];
            world.for_each_body([&](BodyId id, const Body<T>& b) {
                if (id.index == target) direction = normalized_or(b.position() - from, direction);
            });
        }
        const Ray<T> ray{from, direction, length};
        const std::vector<WorldRayHit<T>> expected = scan_ray(world, ray, filter);
        counts.ray_hits += static_cast<int>(expected.size());
        const auto nearest = world.raycast(ray, filter);
        REQUIRE(nearest.has_value() == !expected.empty());
        if (nearest) CHECK(same_hit(*nearest, expected.front()));
        const auto all = world.raycast_all(ray, filter);
        REQUIRE(all.size() == expected.size());
        for (std::size_t i = 0; i < all.size(); ++i) CHECK(same_hit(all[i], expected[i]));
        const auto any = world.raycast_any(ray, filter);
        REQUIRE(any.has_value() == !expected.empty());
        if (any) CHECK(std::any_of(expected.begin(), expected.end(), [&](const WorldRayHit<T>& h) { return same_hit(h, *any); }));

        const Vec3<T> point = rng.in_box(Vec3<T>{T(15), T(15), T(15)}) + Vec3<T>{T(0), T(10), T(0)};
        const auto inside = scan_overlap(world, filter, [&](const Body<T>& b) {
            for (std::uint32_t k = 0; k < b.child_count(); ++k)
                if (contains_point(b.child_shape(k), b.child_transform(k), point)) return true;
            return false;
        });
        CHECK(world.query_point(point, filter) == inside);

        const Aabb<T> box = Aabb<T>::from_center(point, abs(rng.in_box(Vec3<T>{T(3), T(3), T(3)})));
        const auto boxed = scan_overlap(world, filter, [&](const Body<T>& b) { return overlaps(b.world_bounds(), box); });
        CHECK(world.query_aabb(box, filter) == boxed);

        const T radius = rng.uniform(T(0.1), T(3));
        const Shape<T> ball = Sphere<T>(radius);
        const Transform<T> at{point, Quat<T>{}};
        const auto touched = scan_overlap(world, filter, [&](const Body<T>& b) {
            for (std::uint32_t k = 0; k < b.child_count(); ++k)
                if (intersect(ball, at, b.child_shape(k), b.child_transform(k))) return true;
            return false;
        });
        CHECK(world.overlap_sphere(point, radius, filter) == touched);

        const Shape<T> probe = random_query_shape<T>(rng);
        const Transform<T> pose{point, rng.rotation<T>()};
        const auto hit_by_shape = scan_overlap(world, filter, [&](const Body<T>& b) {
            for (std::uint32_t k = 0; k < b.child_count(); ++k)
                if (intersect(probe, pose, b.child_shape(k), b.child_transform(k))) return true;
            return false;
        });
        CHECK(world.overlap_shape(probe, pose, filter) == hit_by_shape);
        counts.overlaps += static_cast<int>(inside.size() + boxed.size() + touched.size() + hit_by_shape.size());
    }
}

}  // namespace

TEST_CASE_TEMPLATE("world queries through the query tree equal a scan of every body, through steps, changes and a restore", T,
                   float, double) {
    scenes::Random rng(2026);
    World<T> world = random_world<T>(rng, 300);
    Counts counts;
    check_queries(rng, world, 60, counts);  // as created
    for (int s = 0; s < 90; ++s) world.step(T(1) / T(60));
    check_queries(rng, world, 60, counts);  // fallen, some asleep, some thrown far
    // Changes between steps: destroy a third, create new ones into the free slots, teleport some.
    std::vector<BodyId> doomed;
    world.for_each_body([&](BodyId id, const Body<T>&) {
        if (id.index % 3 == 1) doomed.push_back(id);
    });
    for (const BodyId id : doomed) world.destroy_body(id);
    World<T> more = random_world<T>(rng, 60);
    more.for_each_body([&](BodyId, const Body<T>& b) {
        BodyDef<T> def;
        def.type = b.type();
        def.position = b.position();
        def.orientation = b.orientation();
        def.sensor = b.sensor();
        def.layer = b.layer();
        world.create_body(b.child_shape(0), def);
    });
    world.for_each_body([&](BodyId id, const Body<T>&) {
        if (id.index % 5 == 2) doomed.push_back(id);
    });
    for (const BodyId id : doomed)
        if (world.contains(id)) world.set_transform(id, rng.in_box(Vec3<T>{T(15), T(15), T(15)}), rng.rotation<T>());
    check_queries(rng, world, 60, counts);
    for (int s = 0; s < 30; ++s) world.step(T(1) / T(60));
    check_queries(rng, world, 60, counts);
    // A restored snapshot builds its own tree.
    World<T> restored;
    restore_snapshot(restored, save_snapshot(world));
    check_queries(rng, restored, 60, counts);
    MESSAGE("ray hits compared: " << counts.ray_hits << ", overlaps compared: " << counts.overlaps);
    CHECK(counts.ray_hits > 150);  // the queries hit things: not a comparison of empty answers
    CHECK(counts.overlaps > 300);
}

TEST_CASE_TEMPLATE("a pick ray that ignores static bodies passes the ground and finds the dynamic body behind a gap", T, float,
                   double) {
    World<T> world;
    BodyDef<T> ground;
    ground.type = BodyType::static_body;
    const BodyId floor = world.create_body(Box<T>(T(10), T(0.5), T(10)), ground);
    BodyDef<T> cube;
    cube.position = {T(3), T(1), T(0)};
    const BodyId box = world.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), cube);
    BodyDef<T> sensor_def;
    sensor_def.type = BodyType::static_body;
    sensor_def.sensor = true;
    sensor_def.position = {T(0), T(5), T(0)};
    const BodyId sensor = world.create_body(Sphere<T>(T(1)), sensor_def);
    const Ray<T> down{{T(0), T(10), T(0)}, -Vec3<T>::unit_y(), T(100)};
    auto hit = world.raycast(down);
    REQUIRE(hit);
    CHECK(hit->body == sensor);
    CHECK(hit->hit.distance == doctest::Approx(4.0));
    QueryFilter<T> no_sensors;
    no_sensors.ignore_sensors = true;
    hit = world.raycast(down, no_sensors);
    REQUIRE(hit);
    CHECK(hit->body == floor);
    CHECK(hit->hit.distance == doctest::Approx(9.5));
    QueryFilter<T> dynamic_only = no_sensors;
    dynamic_only.ignore_static = true;
    CHECK_FALSE(world.raycast(down, dynamic_only));
    const Ray<T> slanted{{T(3), T(10), T(0)}, -Vec3<T>::unit_y(), T(100)};
    hit = world.raycast(slanted, dynamic_only);
    REQUIRE(hit);
    CHECK(hit->body == box);
    CHECK(hit->hit.distance == doctest::Approx(8.5));
    QueryFilter<T> not_the_box = dynamic_only;
    not_the_box.ignore_body = box;
    CHECK_FALSE(world.raycast(slanted, not_the_box));
    QueryFilter<T> layer_two;
    layer_two.mask = 2;  // every body is on layer 1
    CHECK_FALSE(world.raycast_any(down, layer_two));
    CHECK(world.overlap_sphere(Vec3<T>{T(3), T(1), T(0)}, T(0.1), layer_two).empty());
    CHECK(world.overlap_sphere(Vec3<T>{T(3), T(1), T(0)}, T(0.1)) == std::vector<BodyId>{box});
    CHECK_THROWS_AS(world.overlap_sphere(Vec3<T>{}, T(0)), InvalidArgument);
    CHECK_THROWS_AS(world.raycast_any(Ray<T>{{}, Vec3<T>{T(2), T(0), T(0)}, T(1)}), InvalidArgument);
    // Corners swapped on one axis: an error, not an empty answer; a box of zero size is a point.
    CHECK_THROWS_AS(world.query_aabb(Aabb<T>{{T(-1), T(2), T(-1)}, {T(1), T(0), T(1)}}), InvalidArgument);
    CHECK(world.query_aabb(Aabb<T>{{T(3), T(1), T(0)}, {T(3), T(1), T(0)}}) == std::vector<BodyId>{box});
}

// A query filter's accept that changed the world crashed the query: one destroying the body it
// was shown had raycast_all read the freed body (query_filter.hpp said "must not", nothing held
// it). Now the changing call is rejected from inside the callback, and the world keeps its bodies.
TEST_CASE_TEMPLATE("regression: a query filter's accept cannot change the world, and may still query it", T, float, double) {
    World<T> w;
    BodyDef<T> def;
    std::vector<BodyId> ids;
    for (int i = 0; i < 4; ++i) {
        def.position = {T(0), T(2 * i), T(0)};
        ids.push_back(w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), def));
    }
    Ray<T> ray;
    ray.origin = {T(0), T(20), T(0)};
    ray.direction = {T(0), T(-1), T(0)};
    QueryFilter<T> destroying;
    destroying.accept = [&](BodyId id, const Body<T>&) {
        w.destroy_body(id);
        return true;
    };
    CHECK_THROWS_AS(w.raycast_all(ray, destroying), InvalidArgument);
    CHECK_THROWS_AS(w.overlap_sphere(Vec3<T>{T(0), T(2), T(0)}, T(1), destroying), InvalidArgument);
    QueryFilter<T> moving;
    moving.accept = [&](BodyId id, const Body<T>&) {
        w.set_transform(id, Vec3<T>{T(9), T(9), T(9)}, Quat<T>::identity());
        return true;
    };
    CHECK_THROWS_AS(w.raycast(ray, moving), InvalidArgument);
    CHECK(w.body_count() == 4);
    for (const BodyId id : ids) CHECK(w.body(id).position().x == T(0));
    // Reading and querying from the callback is fine, and after the query the world may change.
    QueryFilter<T> reading;
    int seen = 0;
    reading.accept = [&](BodyId id, const Body<T>&) {
        seen += static_cast<int>(w.overlap_sphere(w.body(id).position(), T(0.1)).size());
        return true;
    };
    CHECK(w.raycast_all(ray, reading).size() == 4);
    CHECK(seen == 4);
    CHECK_NOTHROW(w.destroy_body(ids[0]));
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Shape casts against closed forms (a sphere swept at a box is a ray against the box inflated by
// the radius, a box swept face-on at a box meets it at gap / speed, grazing paths miss, shapes that
// start overlapping report fraction 0) and against an independent search: for random pairs of
// every shape kind, the first fraction at which intersect() holds, found by sampling the path and
// bisecting. Then World::shape_cast through the query trees with filters, against a scan.
#include "support/poses.hpp"
#include "collide/random_pairs.hpp"

#include <xeno/collide/shape_cast.hpp>
#include <xeno/dynamics/world.hpp>

#include <doctest/doctest.h>

#include <cmath>

using namespace xeno;
using xeno::test::at;

namespace {

template <class T>
T cast_tolerance() {
    return std::is_same_v<T, float> ? T(2e-4) : T(1e-7);
}

}  // namespace

TEST_CASE_TEMPLATE("a sphere swept at a box hits where a ray meets the box inflated by the radius", T, float, double) {
    const Shape<T> ball = Sphere<T>(T(0.5)), box = Box<T>(T(1), T(1), T(1));
    const Vec3<T> sweep{T(10), T(0), T(0)};
    // Face: the centre stops 1.5 m before the box's centre.
    std::optional<ShapeCastHit<T>> hit = shape_cast(ball, at(T(0), T(0.3), T(0.2)), sweep, box, at(T(5), T(0), T(0)));
    REQUIRE(hit);
    CHECK(!hit->initially_overlapping);
    CHECK(std::abs(hit->fraction - T(0.35)) < cast_tolerance<T>());
    CHECK(length(hit->normal - Vec3<T>::unit_x()) < T(1e-3));
    CHECK(length(hit->point - Vec3<T>{T(4), T(0.3), T(0.2)}) < T(1e-3));
    // Edge: past the top face by 0.2 m, the inflated box's rounded edge (radius 0.5 about the line
    // x = 4, y = 1) stops the centre at x = 4 − √(0.5² − 0.2²).
    hit = shape_cast(ball, at(T(0), T(1.2), T(0)), sweep, box, at(T(5), T(0), T(0)));
    REQUIRE(hit);
    const T x = T(4) - std::sqrt(T(0.25) - T(0.04));
    CHECK(std::abs(hit->fraction - x / T(10)) < cast_tolerance<T>());
    const Vec3<T> expected_normal = normalized(Vec3<T>{T(4) - x, T(1) - T(1.2), T(0)});
    CHECK(length(hit->normal - expected_normal) < T(1e-3));
    CHECK(length(hit->point - Vec3<T>{T(4), T(1), T(0)}) < T(1e-3));
    // Grazing: 1 mm beyond the inflated box misses, 1 mm inside hits.
    CHECK(!shape_cast(ball, at(T(0), T(1.501), T(0)), sweep, box, at(T(5), T(0), T(0))));
    CHECK(shape_cast(ball, at(T(0), T(1.499), T(0)), sweep, box, at(T(5), T(0), T(0))));
    // Too short, or away from it: no hit.
    CHECK(!shape_cast(ball, at(T(0), T(0), T(0)), Vec3<T>{T(3.4), T(0), T(0)}, box, at(T(5), T(0), T(0))));
    CHECK(!shape_cast(ball, at(T(0), T(0), T(0)), -sweep, box, at(T(5), T(0), T(0))));
}

TEST_CASE_TEMPLATE("a box swept face-on at a box meets it at gap / speed, overlapping at the start is fraction 0", T, float,
                   double) {
    const Shape<T> a = Box<T>(T(0.5), T(0.5), T(0.5)), b = Box<T>(T(0.5), T(2), T(2));
    const Quat<T> tilt = Quat<T>::from_axis_angle(Vec3<T>::unit_x(), T(0.3));  // turned about the sweep: still face-on
    const std::optional<ShapeCastHit<T>> hit =
        shape_cast(a, Transform<T>{Vec3<T>::zero(), tilt}, Vec3<T>{T(4), T(0), T(0)}, b, at(T(3), T(0.1), T(0)));
    REQUIRE(hit);
    CHECK(std::abs(hit->fraction - T(2) / T(4)) < cast_tolerance<T>());  // gap 3 − 0.5 − 0.5 = 2 m at 4 m
    CHECK(length(hit->normal - Vec3<T>::unit_x()) < T(1e-3));
    CHECK(std::abs(hit->point.x - T(2.5)) < T(1e-3));  // on B's face
    // Overlapping where it starts.
    const std::optional<ShapeCastHit<T>> inside =
        shape_cast(a, at(T(2.2), T(0), T(0)), Vec3<T>{T(4), T(0), T(0)}, b, at(T(3), T(0), T(0)));
    REQUIRE(inside);
    CHECK(inside->initially_overlapping);
    CHECK(inside->fraction == T(0));
    CHECK(length(inside->normal - Vec3<T>::unit_x()) < T(1e-3));  // collide()'s: push A out along −x
    CHECK_THROWS_AS(
        shape_cast(a, at(T(0), T(0), T(0)), Vec3<T>{std::numeric_limits<T>::infinity(), T(0), T(0)}, b, at(T(3), T(0), T(0))),
        InvalidArgument);
}

TEST_CASE_TEMPLATE("shape casts of random pairs of every kind agree with a search along the path with intersect()", T, float,
                   double) {
    test::RandomPairs pairs(std::is_same_v<T, float> ? 71 : 72, 0.1, 2.0, 5.0);
    const test::ShapeMaker<T> maker(pairs);
    scenes::Random rng(7);
    int hits = 0, misses = 0, overlapping = 0;
    for (int n = 0; n < 400; ++n) {
        const test::PairParams p = pairs.next();
        Shape<T> sa = Sphere<T>(T(1)), sb = Sphere<T>(T(1));
        const Shape<T>& a = maker.get(p.a, sa);
        const Shape<T>& b = maker.get(p.b, sb);
        const Transform<T> pose_a = test::cast_pose<T>(p.pose_a), pose_b = test::cast_pose<T>(p.pose_b);
        // A is moved back along a random direction by 1 … 3 pair sizes, then swept forward 2 … 4.
        const Vec3<T> dir = rng.direction<double>().cast<T>();
        const T scale = static_cast<T>(p.scale);
        const Transform<T> start{pose_a.position - dir * (scale * static_cast<T>(rng.uniform(1.0, 3.0))), pose_a.orientation};
        const Vec3<T> sweep = dir * (scale * static_cast<T>(rng.uniform(2.0, 4.0)));
        const auto overlaps_at = [&](T f) {
            return intersect(a, Transform<T>{start.position + sweep * f, start.orientation}, b, pose_b);
        };
        // The reference: the first of 2,000 samples that overlaps, then bisection to 2^-30.
        T first = T(-1);
        for (int i = 0; i <= 2000 && first < T(0); ++i)
            if (overlaps_at(T(i) / T(2000))) first = T(i) / T(2000);
        const std::optional<ShapeCastHit<T>> hit = shape_cast(a, start, sweep, b, pose_b);
        CAPTURE(n);
        CAPTURE(p.a.kind);
        CAPTURE(p.b.kind);
        if (first == T(0)) {
            ++overlapping;
            REQUIRE(hit);
            CHECK(hit->initially_overlapping);
            continue;
        }
        if (first < T(0)) {
            // No sample overlaps: a miss, or a graze between samples; the cast may report only a
            // touch that the samples could have skipped.
            ++misses;
            if (hit) CHECK(!overlaps_at(std::min(T(1), hit->fraction + T(1) / T(2000))));
            continue;
        }
        T lo = first - T(1) / T(2000), hi = first;
        for (int i = 0; i < 30; ++i) (overlaps_at((lo + hi) / T(2)) ? hi : lo) = (lo + hi) / T(2);
        ++hits;
        REQUIRE(hit);
        CHECK(!hit->initially_overlapping);
        // The cast stops within its cast_tolerance (geometric_tolerance × the problem's size) of B, and
        // the reference's intersect() (MPR) decides overlap within its own, max(geometric
        // cast_tolerance, 1e-7) × size (mpr.hpp); along the sweep a distance d is d over the speed at
        // which A approaches B, |sweep|·cos θ (θ between the sweep and the normal).
        const T approach = length(sweep) * std::max(std::abs(dot(hit->normal, dir)), T(1e-3));
        const T size = scale + length(sweep) + distance(start.position, pose_b.position);
        const T mpr_tolerance = std::max(ScalarTraits<T>::geometric_tolerance, T(1e-7));
        const T slack = (T(8) * ScalarTraits<T>::geometric_tolerance + T(4) * mpr_tolerance) * size / approach;
        CAPTURE(lo - hit->fraction);
        CAPTURE(slack);
        CHECK(hit->fraction <= hi + slack);
        CHECK(hit->fraction >= lo - slack);
        // The point lies on B's surface (within the slack), the normal points from A into B.
        CHECK(dot(hit->normal, sweep) > T(0));
    }
    CHECK(hits > 100);
    CHECK(misses > 20);
    CHECK(overlapping > 2);
}

TEST_CASE_TEMPLATE("a capsule moved sideways a few millimetres above a 100 m ground box does not touch it", T, float, double) {
    // Regression: in float, C's face is 50 m wide and the offset to it 1 mm, and the closest point
    // summed from the simplex's corners tilted v by 2e-3 rad; the far corners then looked higher
    // than x, the cast never separated and reported an overlap (106 of 400 casts, gaps up to 19 mm).
    const Shape<T> capsule = Capsule<T>(T(0.3), T(0.5)), ground = Box<T>(T(50), T(0.5), T(50));
    const Transform<T> ground_pose = at(T(0), T(-0.5), T(0));
    int touching = 0;
    for (int i = 0; i < 400; ++i) {
        const T gap = T(0.001) * T(1 + i % 40);
        const T x = T((i * 37) % 100) / T(10) - T(5), z = T((i * 53) % 100) / T(10) - T(5);
        const T heading = T(i) * T(0.7);
        const Vec3<T> step{std::cos(heading) * T(0.03), T(0), std::sin(heading) * T(0.03)};
        if (shape_cast(capsule, at(x, T(0.8) + gap, z), step, ground, ground_pose)) ++touching;
    }
    CHECK(touching == 0);
    // A step down by more than the gap lands on it, at gap / drop.
    const std::optional<ShapeCastHit<T>> landing =
        shape_cast(capsule, at(T(3), T(0.81), T(-2)), Vec3<T>{T(0.03), T(-0.02), T(0)}, ground, ground_pose);
    REQUIRE(landing);
    CHECK(!landing->initially_overlapping);
    CHECK(std::abs(landing->fraction - T(0.5)) < T(20) * cast_tolerance<T>());
    CHECK(length(landing->normal + Vec3<T>::unit_y()) < T(1e-3));
}

TEST_CASE_TEMPLATE("World::shape_cast finds the first body along the sweep, with filters, as a scan of every body does", T, float,
                   double) {
    World<T> w;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(0), T(-0.5), T(0)};
    const BodyId ground = w.create_body(Box<T>(T(20), T(0.5), T(20)), d);
    d = {};
    d.position = {T(3), T(0.5), T(0)};
    const BodyId near_box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    d.position = {T(6), T(0.5), T(0)};
    d.layer = 2;
    const BodyId far_box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
    const Shape<T> ball = Sphere<T>(T(0.4));
    const Transform<T> start = at(T(0), T(0.5), T(0));
    const Vec3<T> sweep{T(10), T(0), T(0)};
    // The ball rests 0.1 m above the ground (not touching): the near box comes first.
    std::optional<WorldShapeCastHit<T>> hit = w.shape_cast(ball, start, sweep);
    REQUIRE(hit);
    CHECK(hit->body == near_box);
    CHECK(std::abs(hit->hit.fraction - T(2.1) / T(10)) < cast_tolerance<T>());
    QueryFilter<T> skip_near;
    skip_near.ignore_body = near_box;
    hit = w.shape_cast(ball, start, sweep, skip_near);
    REQUIRE(hit);
    CHECK(hit->body == far_box);
    CHECK(std::abs(hit->hit.fraction - T(5.1) / T(10)) < cast_tolerance<T>());
    QueryFilter<T> layer_one;
    layer_one.mask = 1u;
    layer_one.ignore_body = near_box;
    CHECK(!w.shape_cast(ball, start, sweep, layer_one));  // the far box is on layer 2
    // Swept down, the ground is hit after 0.1 m; lowered into it, it overlaps at the start.
    hit = w.shape_cast(ball, start, Vec3<T>{T(0), T(-1), T(0)});
    REQUIRE(hit);
    CHECK(hit->body == ground);
    CHECK(std::abs(hit->hit.fraction - T(0.1)) < cast_tolerance<T>());
    hit = w.shape_cast(ball, at(T(0), T(0.3), T(0)), sweep);
    REQUIRE(hit);
    CHECK(hit->body == ground);
    CHECK(hit->hit.initially_overlapping);
    QueryFilter<T> no_static;
    no_static.ignore_static = true;
    hit = w.shape_cast(ball, at(T(0), T(0.3), T(0)), sweep, no_static);
    REQUIRE(hit);
    CHECK(hit->body == near_box);
    CHECK_THROWS_AS(w.shape_cast(ball, start, Vec3<T>{std::numeric_limits<T>::quiet_NaN(), T(0), T(0)}), InvalidArgument);
}

TEST_CASE_TEMPLATE("a compound swept at a wall stops where its leading part touches", T, float, double) {
    // Two balls of radius 0.5 one metre either side of the centre (along z), swept 10 m along x.
    const Compound<T> dumbbell({{Sphere<T>(T(0.5)), at(T(0), T(0), T(-1))}, {Sphere<T>(T(0.5)), at(T(0), T(0), T(1))}});
    const Shape<T> wall = Box<T>(T(0.5), T(1), T(1.25));
    const Vec3<T> sweep{T(10), T(0), T(0)};
    // The wall (face at x = 5) spans z from 0.5 to 3: only the ball at z = +1 meets it, at x = 4.5.
    std::optional<ShapeCastHit<T>> hit = shape_cast(dumbbell, at(T(0), T(0), T(0)), sweep, wall, at(T(5.5), T(0), T(1.75)));
    REQUIRE(hit);
    CHECK(std::abs(hit->fraction - T(0.45)) < cast_tolerance<T>());
    CHECK(length(hit->normal - Vec3<T>::unit_x()) < T(1e-3));
    CHECK(std::abs(hit->point.z - T(1)) < T(1e-3));
    // Turned a quarter about y, the balls lie along x: the leading one (1 m ahead) touches at 3.5.
    const Transform<T> turned{Vec3<T>::zero(), Quat<T>::from_axis_angle(Vec3<T>::unit_y(), ScalarTraits<T>::pi / T(2))};
    hit = shape_cast(dumbbell, turned, sweep, wall, at(T(5.5), T(0), T(0)));
    REQUIRE(hit);
    CHECK(std::abs(hit->fraction - T(0.35)) < cast_tolerance<T>());
    // Through the world: the same, with the wall as a body; a filter that ignores it gives nothing.
    World<T> w;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = {T(5.5), T(0), T(1.75)};
    const BodyId body = w.create_body(wall, d);
    std::optional<WorldShapeCastHit<T>> world_hit = w.shape_cast(dumbbell, at(T(0), T(0), T(0)), sweep);
    REQUIRE(world_hit);
    CHECK(world_hit->body == body);
    CHECK(std::abs(world_hit->hit.fraction - T(0.45)) < cast_tolerance<T>());
    QueryFilter<T> skip;
    skip.ignore_body = body;
    CHECK(!w.shape_cast(dumbbell, at(T(0), T(0), T(0)), sweep, skip));
    // Passing below the wall: nothing (its bottom is at y = −1, the balls reach up to −2.5).
    CHECK(!w.shape_cast(dumbbell, at(T(0), T(-3), T(0)), sweep));
    CHECK_THROWS_AS(w.shape_cast(dumbbell, at(T(0), T(0), T(0)), Vec3<T>{T(0), std::numeric_limits<T>::infinity(), T(0)}),
                    InvalidArgument);
}

// Regression: the cast's tolerance is a fraction of the problem's size, and the whole translation
// counted in it: a unit box 4.5 m above a ground box, swept down 1e6 m in float (1e10 m in
// double), was reported overlapping the ground at the start (fraction 0). Now only the part of
// the sweep where the bounding spheres meet is cast.
TEST_CASE_TEMPLATE("a box swept a very long way down at the ground meets it where it is 4.5 m below", T, float, double) {
    const Shape<T> a = Box<T>(T(0.5), T(0.5), T(0.5)), ground = Box<T>(T(20), T(1), T(20));
    for (const T reach : {T(10), T(1e4), T(1e6), std::is_same_v<T, float> ? T(1e9) : T(1e10)}) {
        CAPTURE(reach);
        const std::optional<ShapeCastHit<T>> hit =
            shape_cast(a, at(T(0), T(5), T(0)), Vec3<T>{T(0), -reach, T(0)}, ground, at(T(0), T(-1), T(0)));
        REQUIRE(hit);
        CHECK(!hit->initially_overlapping);
        // The distance travelled, fraction × reach, is the 4.5 m gap (to the cast's tolerance at
        // the trimmed sweep's scale, about 35 m here).
        CHECK(std::abs(hit->fraction * reach - T(4.5)) < T(1e-3));
        CHECK(length(hit->normal + Vec3<T>::unit_y()) < T(1e-3));
    }
    // Swept away from it, or past beside it, nothing.
    CHECK(!shape_cast(a, at(T(0), T(5), T(0)), Vec3<T>{T(0), T(1e6), T(0)}, ground, at(T(0), T(-1), T(0))));
    CHECK(!shape_cast(a, at(T(0), T(5), T(100)), Vec3<T>{T(0), T(-1e6), T(0)}, ground, at(T(0), T(-1), T(0))));
}

// regression: a sweep whose length squared overflows T (from 1.8e19 m in float, 1.3e154 m in
// double) was cast whole, at a tolerance scaled to its length, and a ball 2.7 m clear of a floor
// came back as starting inside it (fraction 0, initially_overlapping). Its length is now taken
// of the translation scaled by its largest component: the hit is where the ball meets the floor,
// 2.7 m along, on a mesh and on a box alike.
TEST_CASE_TEMPLATE("a shape cast longer than the square of T can hold finds the floor 2.7 m along", T, float, double) {
    World<T> w;
    BodyDef<T> level;
    level.type = BodyType::static_body;
    const std::vector<Vec3<T>> corners{{T(-5), T(0), T(-5)}, {T(-5), T(0), T(5)}, {T(5), T(0), T(5)}, {T(5), T(0), T(-5)}};
    w.create_body(TriangleMesh<T>(corners, {{0, 1, 2}, {0, 2, 3}}), level);
    level.position = {T(20), T(-0.5), T(0)};
    w.create_body(Box<T>(T(5), T(0.5), T(5)), level);
    const Shape<T> ball = Sphere<T>(T(0.3));
    const T huge = std::is_same_v<T, float> ? T(2e19) : T(1e155);
    for (const T x : {T(0), T(20)})
        for (const T length : {huge, std::numeric_limits<T>::max() / T(2)}) {
            CAPTURE(x);
            CAPTURE(length);
            const std::optional<WorldShapeCastHit<T>> hit = w.shape_cast(ball, at(x, T(3), T(0)), {T(0), -length, T(0)});
            REQUIRE(hit);
            CHECK(!hit->hit.initially_overlapping);
            CHECK(std::abs(hit->hit.fraction * length - T(2.7)) < T(1e-3));
        }
}

TEST_CASE_TEMPLATE("regression: shapes exactly touching part without a hit, and meet at fraction 0 without overlapping", T, float,
                   double) {
    // A capsule standing exactly on a box (its bottom at y = 0, the box's top) was reported
    // initially overlapping, at fraction 0, whichever way it was cast, up and sideways included:
    // exact contact never gave a separating plane (v·w > 0), and "never separated" was taken for
    // overlap. Touching is not intersecting (intersect() says so): moving apart or along the
    // contact plane is no hit; moving into B is a hit at fraction 0, not overlapping, with the
    // normal from A to B, (0, −1, 0). The same for a box resting on the box, and in the world.
    const Shape<T> ground = Box<T>(T(10), T(0.5), T(10));
    const Transform<T> ground_pose = at(T(0), T(-0.5), T(0));
    const Vec3<T> down{T(0), T(-1), T(0)};
    std::vector<std::pair<Shape<T>, T>> standing = {{Capsule<T>(T(0.25), T(0.5)), T(0.75)},
                                                    {Capsule<T>(T(0.375), T(0.5)), T(0.875)},
                                                    {Box<T>(T(0.5), T(0.5), T(0.5)), T(0.5)}};
    // The reviewer's capsule: 0.3 + 0.5 = 0.8 exactly in double; in float intersect() counts it
    // as overlapping, and so does the cast.
    if (std::is_same_v<T, double>) standing.push_back({Capsule<T>(T(0.3), T(0.5)), T(0.8)});
    const std::vector<Vec3<T>> away = {{T(0), T(1), T(0)}, {T(1), T(0), T(0)}, {T(0), T(0), T(-1)},
                                       {T(1), T(0), T(1)}, {T(1), T(1), T(0)}, {T(-0.2), T(0.01), T(0.3)}};
    const std::vector<Vec3<T>> into = {down, {T(1), T(-1), T(0)}, {T(0.3), T(-0.01), T(-0.2)}};
    World<T> w;
    BodyDef<T> d;
    d.type = BodyType::static_body;
    d.position = ground_pose.position;
    const BodyId floor = w.create_body(ground, d);
    for (std::size_t i = 0; i < standing.size(); ++i) {
        CAPTURE(i);
        const auto& [shape, height] = standing[i];
        const Transform<T> pose = at(T(0), height, T(0));
        REQUIRE_FALSE(intersect(shape, pose, ground, ground_pose));
        for (const Vec3<T>& move : away) {
            CAPTURE(move);
            CHECK_FALSE(shape_cast(shape, pose, move, ground, ground_pose));
            CHECK_FALSE(w.shape_cast(shape, pose, move));
        }
        for (const Vec3<T>& move : into) {
            CAPTURE(move);
            const std::optional<ShapeCastHit<T>> hit = shape_cast(shape, pose, move, ground, ground_pose);
            const std::optional<WorldShapeCastHit<T>> world_hit = w.shape_cast(shape, pose, move);
            REQUIRE(hit);
            REQUIRE(world_hit);
            CHECK(world_hit->body == floor);
            for (const ShapeCastHit<T>& h : {*hit, world_hit->hit}) {
                CHECK(h.fraction == T(0));
                CHECK_FALSE(h.initially_overlapping);
                CHECK(length(h.normal - down) < T(1e-3));
                CHECK(std::abs(h.point.y) < T(1e-5));  // on the box's top
            }
        }
        // Lowered 1 cm into the box: a real overlap, flagged, its normal from A to B as well.
        const std::optional<ShapeCastHit<T>> sunk =
            shape_cast(shape, at(T(0), height - T(0.01), T(0)), down, ground, ground_pose);
        REQUIRE(sunk);
        CHECK(sunk->initially_overlapping);
        CHECK(sunk->fraction == T(0));
        CHECK(length(sunk->normal - down) < T(1e-3));
    }
}

// Regression: from the ends of T's range (a ball at ∓FLT_MAX swept by ±FLT_MAX at a box at the
// origin) the sweep was trimmed once to where the bounding spheres meet, and that start, rounded
// at the scale of FLT_MAX, lay 10³¹ m off: the ball was cast from the far side of the box and
// hit its other face, normal reversed; a box at FLT_MAX / 2 or FLT_MAX beyond a sweep ending at
// the origin made the cast throw "collide: pose_a.position.x must be finite (got -nan)". The trim
// now repeats from each trimmed start until the spheres meet over the whole of what is left, and
// a box farther off than T holds is passed.
TEST_CASE_TEMPLATE("a ball swept from the ends of the range hits the box face it comes to, or passes a box it cannot reach", T,
                   float, double) {
    const T most = std::numeric_limits<T>::max();
    const Shape<T> ball = Sphere<T>(T(1)), box = Box<T>(T(1), T(1), T(1));
    struct Sweep {
        T start, travel, fraction;  // along x; the fraction at which the ball touches the box at the origin
    };
    for (const Sweep s : {Sweep{-most, most, T(1)}, Sweep{most, -most, T(1)}, Sweep{-most / 2, most, T(0.5)},
                          Sweep{most / 2, -most, T(0.5)}, Sweep{-most / 4, most / 2, T(0.5)}}) {
        CAPTURE(s.start);
        CAPTURE(s.travel);
        const T side = s.travel > T(0) ? T(1) : T(-1);  // +x: the ball meets the box's −x face
        const std::optional<ShapeCastHit<T>> hit =
            shape_cast(ball, at(s.start, T(0), T(0)), Vec3<T>{s.travel, T(0), T(0)}, box, at(T(0), T(0), T(0)));
        REQUIRE(hit);
        CHECK(!hit->initially_overlapping);
        CHECK(std::abs(hit->fraction - s.fraction) <= T(4) * std::numeric_limits<T>::epsilon());
        CHECK(length(hit->normal - Vec3<T>{side, T(0), T(0)}) < T(1e-3));
        CHECK(length(hit->point - Vec3<T>{-side, T(0), T(0)}) < T(1e-3));
    }
    // Boxes beyond the sweep's end: half the range on, and past the end of the range.
    for (const T box_x : {most / 2, most})
        CHECK_FALSE(shape_cast(ball, at(-most, T(0), T(0)), Vec3<T>{most, T(0), T(0)}, box, at(box_x, T(0), T(0))));
}

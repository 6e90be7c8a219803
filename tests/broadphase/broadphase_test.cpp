// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The broad phases agree: brute force, sweep and prune and the dynamic AABB tree report the same
// sorted pair list on random scenes with empty slots, huge, coincident, flat and exactly touching
// boxes, and keep agreeing over frames of small moves (their incremental paths) with slots
// emptied, reused, added and dropped. Also the tree's own invariants, and the pair density of
// the N² benchmark's scene (bench/n2_detection.hpp).
#include "support/approx.hpp"

#include "../../bench/n2_detection.hpp"
#include "robustness/state_hash.hpp"
#include "scenes/piles.hpp"
#include "scenes/random.hpp"
#include "support/shuffled_tasks.hpp"

#include <xeno/broadphase/aabb_tree.hpp>
#include <xeno/broadphase/brute_force.hpp>
#include <xeno/broadphase/sweep_and_prune.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace xeno;

namespace {

// Half extents and centres are multiples of 1/64, so sums and differences are exact in float:
// "touching exactly" really touches in both precisions.
template <class T>
T grid(scenes::Random& rng, double low, double high) {
    return static_cast<T>(std::floor(rng.uniform(low, high) * 64.0) / 64.0);
}

template <class T>
Aabb<T> random_box(scenes::Random& rng, double side) {
    const Vec3<T> c{grid<T>(rng, -side / 2, side / 2), grid<T>(rng, -side / 2, side / 2), grid<T>(rng, -side / 2, side / 2)};
    const Vec3<T> h{grid<T>(rng, 0.05, 1.5), grid<T>(rng, 0.05, 1.5), grid<T>(rng, 0.05, 1.5)};
    return Aabb<T>::from_center(c, h);
}

// A scene of n slots: ordinary boxes plus empty slots, huge boxes, copies of other boxes, boxes
// touching another exactly on a face, an edge or a corner, and flat (zero-thickness) boxes.
template <class T>
std::vector<Aabb<T>> random_scene(std::uint64_t seed, std::size_t n, double side) {
    scenes::Random rng(seed);
    std::vector<Aabb<T>> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        const double kind = rng.uniform();
        if (kind < 0.08) {
            boxes.push_back(Aabb<T>{});  // empty slot
        } else if (kind < 0.11) {
            boxes.push_back(Aabb<T>::from_center(random_box<T>(rng, side).center(), Vec3<T>::one() * T(1000)));  // huge
        } else if (kind < 0.18 && !boxes.empty()) {
            boxes.push_back(boxes[rng.index(static_cast<std::uint32_t>(boxes.size()))]);  // coincident
        } else if (kind < 0.30 && !boxes.empty()) {
            // Touching: shifted so that one face (or edge, corner) meets the other's exactly.
            Aabb<T> b = boxes[rng.index(static_cast<std::uint32_t>(boxes.size()))];
            if (b.empty()) b = random_box<T>(rng, side);
            const Vec3<T> size = b.max - b.min;
            Vec3<T> shift{};
            const int axes = 1 + static_cast<int>(rng.index(3));
            for (int k = 0; k < axes; ++k) {
                const int axis = static_cast<int>(rng.index(3));
                shift[axis] = rng.uniform() < 0.5 ? size[axis] : -size[axis];
            }
            boxes.push_back({b.min + shift, b.max + shift});
        } else if (kind < 0.33) {
            Aabb<T> b = random_box<T>(rng, side);
            b.max.y = b.min.y;  // flat
            boxes.push_back(b);
        } else {
            boxes.push_back(random_box<T>(rng, side));
        }
    }
    return boxes;
}

std::string show(const std::vector<ProxyPair>& pairs, std::size_t limit = 8) {
    std::string s = std::to_string(pairs.size()) + " pairs:";
    for (std::size_t k = 0; k < pairs.size() && k < limit; ++k)
        s += " (" + std::to_string(pairs[k].a) + "," + std::to_string(pairs[k].b) + ")";
    return s;
}

template <class T>
void require_same_pairs(const std::vector<Aabb<T>>& boxes, SweepAndPrune<T>& sap, AabbTree<T>& tree) {
    std::vector<ProxyPair> brute, swept, treed;
    brute_force_pairs(boxes, brute);
    sap.find_pairs(boxes, swept);
    tree.find_pairs(boxes, treed);
    INFO("brute ", show(brute), "; sap ", show(swept), "; tree ", show(treed));
    REQUIRE(std::is_sorted(brute.begin(), brute.end()));
    REQUIRE(std::adjacent_find(brute.begin(), brute.end()) == brute.end());
    REQUIRE(swept == brute);
    REQUIRE(treed == brute);
    REQUIRE(tree.valid());
}

}  // namespace

TEST_CASE_TEMPLATE("all broad phases report the same pairs on random scenes", T, float, double) {
    std::size_t most_columns = 0;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        CAPTURE(seed);
        const std::size_t n = 200 + 50 * seed;
        const std::vector<Aabb<T>> boxes = random_scene<T>(seed, n, seed % 2 ? 16.0 : 40.0);
        SweepAndPrune<T> sap;
        AabbTree<T> tree(seed % 3 == 0 ? T(0) : T(0.1));
        require_same_pairs(boxes, sap, tree);
        // Asked again with nothing changed: the same answer from the warm state.
        require_same_pairs(boxes, sap, tree);
        most_columns = std::max(most_columns, sap.columns());
    }
    // The column-split sweep was exercised, not only the single sweep.
    CHECK(most_columns > 1);
}

TEST_CASE_TEMPLATE("sweep and prune over many columns agrees with brute force, boxes on cell borders included", T, float,
                   double) {
    // 3000 boxes on a 1/64 grid: many columns, and box sides that fall exactly on the column
    // borders (cells are whole multiples of the grid in these scenes often enough to matter).
    for (std::uint64_t seed = 11; seed <= 13; ++seed) {
        CAPTURE(seed);
        std::vector<Aabb<T>> boxes = random_scene<T>(seed, 3000, 60.0);
        SweepAndPrune<T> sap;
        AabbTree<T> tree;
        require_same_pairs(boxes, sap, tree);
        CHECK(sap.columns() >= 16);
        // Everything collapsed onto one plane: the cross axes keep their spread, the sweep axis
        // has none.
        for (Aabb<T>& b : boxes)
            if (!b.empty()) b.min.x = b.max.x = T(0);
        require_same_pairs(boxes, sap, tree);
    }
}

TEST_CASE_TEMPLATE("sweep and prune on several workers reports brute force's pairs, however its columns are cut and ordered", T,
                   float, double) {
    test::ShuffledTasks shuffled(3);
    ThreadPool pool(2);
    for (std::uint64_t seed = 21; seed <= 23; ++seed) {
        CAPTURE(seed);
        std::vector<Aabb<T>> boxes = random_scene<T>(seed, 3000, 60.0);
        SweepAndPrune<T> on_shuffled, on_pool;
        for (int frame = 0; frame < 2; ++frame) {
            CAPTURE(frame);
            std::vector<ProxyPair> brute, from_shuffled, from_pool;
            brute_force_pairs(boxes, brute);
            on_shuffled.find_pairs(boxes, from_shuffled, &shuffled);
            on_pool.find_pairs(boxes, from_pool, &pool);
            INFO("brute ", show(brute), "; shuffled ", show(from_shuffled), "; pool ", show(from_pool));
            CHECK(on_shuffled.columns() >= 16);  // the parallel sweep ran
            REQUIRE(from_shuffled == brute);
            REQUIRE(from_pool == brute);
            // The next frame: every box moved a little (the sorted order is repaired, not rebuilt).
            for (Aabb<T>& b : boxes)
                if (!b.empty()) b = {b.min + Vec3<T>{T(0.25), T(0), T(-0.125)}, b.max + Vec3<T>{T(0.25), T(0), T(-0.125)}};
        }
    }
}

TEST_CASE_TEMPLATE("the broad phases agree over frames of small moves with slots emptied, reused, added and dropped", T, float,
                   double) {
    scenes::Random rng(77);
    std::vector<Aabb<T>> boxes = random_scene<T>(5, 300, 20.0);
    SweepAndPrune<T> sap;
    AabbTree<T> tree(T(0.1));
    std::size_t moves = 0;
    for (int frame = 0; frame < 80; ++frame) {
        CAPTURE(frame);
        require_same_pairs(boxes, sap, tree);
        for (Aabb<T>& b : boxes) {
            const double event = rng.uniform();
            if (b.empty()) {
                if (event < 0.1) b = random_box<T>(rng, 20.0);  // slot reused
            } else if (event < 0.03) {
                b = Aabb<T>{};  // body destroyed
            } else {
                const Vec3<T> step = rng.in_box(Vec3<T>::one() * T(0.04));  // a few centimetres a frame
                b = {b.min + step, b.max + step};
                ++moves;
            }
        }
        if (frame % 10 == 3) boxes.push_back(random_box<T>(rng, 20.0));  // a new body at the end
        if (frame % 10 == 7) boxes.resize(boxes.size() - 3);             // the last three slots dropped
        if (frame == 40) std::swap(boxes[0], boxes[1]);                  // a jump: two boxes trade places
    }
    // The incremental path was taken: most small moves stayed inside their fat boxes.
    CHECK(tree.reinsertions() > 0);
    CHECK(tree.reinsertions() < moves / 2);
}

TEST_CASE_TEMPLATE("sweep and prune answers an unchanged frame from the last one, and any change of one box is seen", T, float,
                   double) {
    // Frames alternate between no change (the last pairs are returned) and one box changed in one
    // coordinate, in turn each of the six (sweep axis and cross axes, min and max), by a step that
    // makes or breaks contacts, or one box emptied or refilled.
    scenes::Random rng(91);
    std::vector<Aabb<T>> boxes = random_scene<T>(9, 400, 12.0);
    SweepAndPrune<T> sap;
    AabbTree<T> tree(T(0.1));
    for (int frame = 0; frame < 120; ++frame) {
        CAPTURE(frame);
        require_same_pairs(boxes, sap, tree);
        if (frame % 2 == 0) continue;  // the next frame sees the same boxes
        const std::size_t k = rng.index(static_cast<std::uint32_t>(boxes.size()));
        Aabb<T>& b = boxes[k];
        if (frame % 14 == 13) {
            b = b.empty() ? random_box<T>(rng, 12.0) : Aabb<T>{};
            continue;
        }
        if (b.empty()) continue;
        const int coordinate = (frame / 2) % 6, axis = coordinate % 3;
        const T step = T(0.25) * (rng.uniform() < 0.5 ? T(-1) : T(1));
        if (coordinate < 3) b.min[axis] = std::min(b.min[axis] + step, b.max[axis]);
        else b.max[axis] = std::max(b.max[axis] + step, b.min[axis]);
    }
}

TEST_CASE_TEMPLATE("the tree stays valid and shallow under inserts, removes and moves, and queries its fat boxes", T, float,
                   double) {
    scenes::Random rng(2024);
    AabbTree<T> tree(T(0.05));
    std::vector<Aabb<T>> fat(600);  // what the tree should hold; empty = absent
    for (int op = 0; op < 6000; ++op) {
        const std::uint32_t p = rng.index(static_cast<std::uint32_t>(fat.size()));
        const double kind = rng.uniform();
        if (!tree.contains(p)) {
            const Aabb<T> b = random_box<T>(rng, 30.0);
            tree.insert(p, b);
            fat[p] = b.expanded(T(0.05));
        } else if (kind < 0.2) {
            tree.remove(p);
            fat[p] = Aabb<T>{};
        } else {
            const Aabb<T> b = random_box<T>(rng, 30.0);
            const bool inside = fat[p].contains(b) && b.expanded(T(4) * T(0.05)).contains(fat[p]);
            CHECK(tree.move(p, b) == !inside);
            if (!inside) fat[p] = b.expanded(T(0.05));
        }
        if (op % 500 == 0) REQUIRE(tree.valid());
    }
    REQUIRE(tree.valid());
    std::size_t live = 0;
    for (std::uint32_t p = 0; p < fat.size(); ++p) {
        CHECK(tree.contains(p) == !fat[p].empty());
        if (tree.contains(p)) {
            CHECK(tree.fat_box(p).min == fat[p].min);
            CHECK(tree.fat_box(p).max == fat[p].max);
            ++live;
        }
    }
    REQUIRE(tree.size() == live);
    // Balanced by the rotations: well under the 600 a degenerate (list-like) tree would reach.
    const int log_live = static_cast<int>(std::ceil(std::log2(static_cast<double>(live))));
    CHECK(tree.height() <= 3 * log_live);
    // A rebuild keeps every proxy and fat box and gives a perfectly balanced tree.
    tree.rebuild();
    REQUIRE(tree.valid());
    REQUIRE(tree.size() == live);
    CHECK(tree.height() == log_live);
    for (std::uint32_t p = 0; p < fat.size(); ++p) {
        REQUIRE(tree.contains(p) == !fat[p].empty());
        if (tree.contains(p)) CHECK((tree.fat_box(p).min == fat[p].min && tree.fat_box(p).max == fat[p].max));
    }
    for (int q = 0; q < 50; ++q) {
        const Aabb<T> box = random_box<T>(rng, 30.0);
        std::vector<std::uint32_t> found, expected;
        tree.query(box, [&](std::uint32_t p) { found.push_back(p); });
        for (std::uint32_t p = 0; p < fat.size(); ++p)
            if (!fat[p].empty() && overlaps(fat[p], box)) expected.push_back(p);
        std::sort(found.begin(), found.end());
        CHECK(found == expected);
    }
    tree.clear();
    CHECK(tree.size() == 0);
    CHECK(tree.height() == -1);
    CHECK(tree.valid());
}

TEST_CASE_TEMPLATE("moves before a rebuild give the tree that reinserting each leaf and then rebuilding gives", T, float,
                   double) {
    // The world's query tree sets the leaves of a batch of moves bound to end in a rebuild
    // without reinserting them (move_before_rebuild). Two trees with the same history, one moved
    // leaf by leaf and one not, must come out of the rebuild alike: the same fat boxes, the same
    // shape, and every query visiting the proxies in the same order.
    scenes::Random rng(515);
    AabbTree<T> reinserted(T(0.1)), set_only(T(0.1));
    std::vector<Aabb<T>> boxes;
    for (std::uint32_t p = 0; p < 500; ++p) {
        boxes.push_back(random_box<T>(rng, 25.0));
        if (p % 7 == 3) continue;  // some slots left out of the trees
        reinserted.insert(p, boxes[p]);
        set_only.insert(p, boxes[p]);
    }
    for (int frame = 0; frame < 6; ++frame) {
        CAPTURE(frame);
        std::size_t left = 0;
        for (std::uint32_t p = 0; p < boxes.size(); ++p) {
            if (!reinserted.contains(p)) continue;
            // Most fall out of their fat boxes, some stay inside, some shrink to a sliver.
            const double event = rng.uniform();
            const Vec3<T> step = event < 0.6 ? Vec3<T>{T(0), T(-0.3), T(0.05)} : Vec3<T>{T(0.01), T(0), T(0)};
            boxes[p] = {boxes[p].min + step, boxes[p].max + step};
            if (event > 0.95) boxes[p] = Aabb<T>::from_center(boxes[p].center(), Vec3<T>::one() * T(0.01));
            const bool moved = reinserted.move(p, boxes[p]);
            CHECK(set_only.move_before_rebuild(p, boxes[p]) == moved);
            left += moved ? 1 : 0;
        }
        CHECK(left > 0);
        reinserted.rebuild();
        set_only.rebuild();
        REQUIRE(set_only.valid());
        CHECK(set_only.size() == reinserted.size());
        CHECK(set_only.height() == reinserted.height());
        CHECK(set_only.reinsertions() == reinserted.reinsertions());
        for (std::uint32_t p = 0; p < boxes.size(); ++p) {
            REQUIRE(set_only.contains(p) == reinserted.contains(p));
            if (!set_only.contains(p)) continue;
            CHECK(set_only.fat_box(p).min == reinserted.fat_box(p).min);
            CHECK(set_only.fat_box(p).max == reinserted.fat_box(p).max);
        }
        for (int q = 0; q < 20; ++q) {
            const Aabb<T> box = random_box<T>(rng, 25.0);
            std::vector<std::uint32_t> a, b;
            reinserted.query(box, [&](std::uint32_t p) { a.push_back(p); });
            set_only.query(box, [&](std::uint32_t p) { b.push_back(p); });
            CHECK(a == b);
            const Vec3<T> from = box.center(), direction = normalized(rng.in_box(Vec3<T>::one()) + Vec3<T>{T(0), T(0), T(2)});
            a.clear();
            b.clear();
            const auto visit = [](std::vector<std::uint32_t>& seen) {
                return [&seen](std::uint32_t p, T reach) {
                    seen.push_back(p);
                    return reach;
                };
            };
            reinserted.query_segment(from, direction, T(30), visit(a));
            set_only.query_segment(from, direction, T(30), visit(b));
            CHECK(a == b);
        }
    }
}

TEST_CASE_TEMPLATE("a negative or non-finite tree margin is rejected", T, float, double) {
    const auto make = [](T margin) { return AabbTree<T>(margin); };
    CHECK_THROWS_AS(make(T(-1)), InvalidArgument);
    CHECK_THROWS_AS(make(std::numeric_limits<T>::quiet_NaN()), InvalidArgument);
    CHECK_THROWS_AS(make(std::numeric_limits<T>::infinity()), InvalidArgument);
    CHECK(make(T(0)).margin() == T(0));
}

TEST_CASE_TEMPLATE("the N² benchmark scene has about 0.65 overlapping pairs per box", T, float, double) {
    // Two randomly oriented unit cubes overlap when their centres are within the excluded volume
    // V + V + (M S + M S) / 4π = 2 + 2 (3π · 6) / 4π = 11 (mean curvature M = 3π, area S = 6), so
    // with 8 unit volumes per box a box meets 11 / 8 others: 11/16 ≈ 0.69 pairs per box.
    const std::size_t n = 2000;
    const bench::Scene<T> scene = bench::make_box_scene<T>(n);
    bench::Detector<T> sap(bench::Strategy::sap), brute(bench::Strategy::brute);
    const bench::PassResult r = sap.pass(scene);
    const double per_box = static_cast<double>(r.contacts) / static_cast<double>(n);
    CAPTURE(per_box);
    CHECK(per_box > 0.55);
    CHECK(per_box < 0.8);
    // The thesis's brute force (MPR on every pair) finds the same contacts, pair for pair, bar
    // grazing contacts MPR and the closed-form box test may decide differently.
    const bench::PassResult b = brute.pass(scene);
    CHECK(std::abs(static_cast<double>(b.contacts) - static_cast<double>(r.contacts)) <= 0.002 * static_cast<double>(n));
    // Every contact's pair passed the broad phase.
    for (const bench::PairContact<T>& c : brute.contacts())
        CHECK(std::binary_search(sap.pairs().begin(), sap.pairs().end(), c.pair));
}

// Two passes found the same contacts, pair for pair and bit for bit.
template <class T>
void check_same_contacts(const bench::Detector<T>& x, const bench::Detector<T>& y) {
    REQUIRE(x.contacts().size() == y.contacts().size());
    for (std::size_t k = 0; k < x.contacts().size(); ++k) {
        const Penetration<T>& p = x.contacts()[k].contact;
        const Penetration<T>& q = y.contacts()[k].contact;
        CHECK(x.contacts()[k].pair == y.contacts()[k].pair);
        CHECK(std::memcmp(&p.normal, &q.normal, sizeof p.normal) == 0);
        CHECK(std::memcmp(&p.point_a, &q.point_a, sizeof p.point_a) == 0);
        CHECK(std::memcmp(&p.point_b, &q.point_b, sizeof p.point_b) == 0);
        CHECK(std::memcmp(&p.depth, &q.depth, sizeof p.depth) == 0);
    }
}

TEST_CASE_TEMPLATE("MPR's first test in lanes skips only pairs MPR misses: the same contacts, bit for bit", T, float, double) {
    // brute_lanes against the thesis's brute force, and the pair strategies with and without
    // the early-out, on the box and the mixed scene (early_out.hpp; thesis 4.1 c).
    for (const bool mixed : {false, true}) {
        const bench::Scene<T> scene = mixed ? bench::make_mixed_scene<T>(700) : bench::make_box_scene<T>(700);
        bench::Detector<T> brute(bench::Strategy::brute), lanes(bench::Strategy::brute_lanes);
        brute.pass(scene);
        lanes.pass(scene);
        CHECK(brute.contacts().size() > 200);
        check_same_contacts(brute, lanes);
        bench::Detector<T> sap(bench::Strategy::sap), plain(bench::Strategy::sap, {}, T(0.1), false);
        sap.pass(scene);
        plain.pass(scene);
        check_same_contacts(sap, plain);
    }
}

TEST_CASE_TEMPLATE("the world steps a pile to the same bits with every broad phase", T, float, double) {
    // The pair list is sorted whatever the strategy, so the choice changes the speed only.
    std::vector<std::uint64_t> hashes;
    for (const BroadPhaseKind kind : {BroadPhaseKind::brute_force, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::aabb_tree}) {
        WorldSettings<T> settings;
        settings.broad_phase = kind;
        World<T> world(settings);
        scenes::mixed_pile(world);
        for (int step = 0; step < 240; ++step) world.step(T(1) / T(60));
        CHECK(world.last_step_stats().broad_pairs > 0);
        hashes.push_back(test::state_hash(world));
    }
    CHECK(hashes[0] == hashes[1]);
    CHECK(hashes[0] == hashes[2]);
}

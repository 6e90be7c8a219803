// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The N² detection benchmark's shared parts (issue "Broad phase and the N² detection benchmark"),
// used by the standalone table program (n2_detection_bench.cpp), the Catch2 benchmarks
// (n2_catch_bench.cpp) and the broad-phase tests:
//   scenes      N unit boxes (half extents 0.5) with centres uniform in a cube of side (8N)^(1/3)
//               (eight unit volumes per box) and uniform random orientations, from a fixed seed;
//               a mixed-shape variant; clustered, few-huge and flat-layer variants for the
//               tree-versus-sweep comparison; `jiggle` moves every body a little (a later frame);
//   one pass    detection of every contact: world boxes → broad phase → collide() on each pair,
//               keeping the contact (normal, depth, points) of every overlapping pair. Strategies:
//                 brute         the thesis's method (3.3.1.1): every pair of bodies through
//                               mpr_penetration, no bounding-volume test. On the box scene the
//                               shapes are the concrete Box<T> (no variant dispatch at all); on
//                               the mixed scene one std::visit per pair picks the MPR instance;
//                 brute_lanes   the same, with MPR's first test run for W pairs at once in SIMD
//                               lanes (EarlyOut, collide/early_out.hpp; thesis 4.1 c): each body's
//                               axes once per pass, the pairs that survive through mpr_penetration;
//                 brute_bounds  brute_force_pairs over world boxes, then collide() per pair;
//                 sap           SweepAndPrune, then collide() per pair;
//                 tree          AabbTree, then collide() per pair;
//               the pair strategies run the early-out on their pairs, W at a time, before collide()
//               (Detector's early_out flag, on by default; off gives the pass without it).
//   parallel    the narrow phase (for brute, the whole all-pairs loop) runs through a parallel-for
//               the caller may supply; the default runs std::threads.
// The world box of a body is computed inside the timed pass (it is part of a broad phase's work).
#pragma once

#include "scenes/random.hpp"

#include <xeno/broadphase/aabb_tree.hpp>
#include <xeno/broadphase/brute_force.hpp>
#include <xeno/broadphase/sweep_and_prune.hpp>
#include <xeno/collide/early_out.hpp>
#include <xeno/collide/collide.hpp>
#include <xeno/shape/polyhedra.hpp>
#include <xeno/task_system.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace xeno::bench {

/// The scenes' default seed; printed with every table.
constexpr std::uint64_t kN2Seed = 20080101;

/// The thesis's measurements (Quadro 26): one step of brute-force all-pairs XenoCollide.
struct ThesisPoint {
    std::size_t bodies;
    double seconds;
};
constexpr ThesisPoint kThesis[] = {{500, 1.72},   {1000, 6.55},  {1500, 14.79}, {2000, 26.28},
                                   {2500, 41.10}, {3000, 59.31}, {3500, 80.53}};

/// The thesis's seconds for n bodies, or NaN when it did not measure n.
inline double thesis_seconds(std::size_t n) {
    for (const ThesisPoint& p : kThesis)
        if (p.bodies == n) return p.seconds;
    return std::nan("");
}

/// Bodies sharing a few distinct shapes: body i is shapes[shape_of[i]] placed by poses[i].
template <class T>
struct Scene {
    std::vector<Shape<T>> shapes;         ///< the distinct shapes
    std::vector<std::uint32_t> shape_of;  ///< body -> index into shapes
    std::vector<Transform<T>> poses;      ///< metres, world; position = centre of mass
    T side = T(0);                        ///< metres, side of the cube the centres were drawn in
    std::string description;              ///< one line for the printed report

    std::size_t size() const { return poses.size(); }
    const Shape<T>& shape(std::size_t i) const { return shapes[shape_of[i]]; }
};

/// The scene: n boxes of half extents 0.5, centres uniform in a cube of side (8n)^(1/3)
/// centred at the origin, uniform random orientations.
template <class T>
Scene<T> make_box_scene(std::size_t n, std::uint64_t seed = kN2Seed) {
    Scene<T> s;
    s.shapes.push_back(Box<T>(T(0.5), T(0.5), T(0.5)));
    s.side = static_cast<T>(std::cbrt(8.0 * static_cast<double>(n)));
    scenes::Random rng(seed);
    const Vec3<T> half = Vec3<T>::one() * (T(0.5) * s.side);
    s.shape_of.assign(n, 0);
    s.poses.reserve(n);
    for (std::size_t i = 0; i < n; ++i) s.poses.push_back({rng.in_box(half), rng.rotation<T>()});
    s.description =
        "unit boxes (half extents 0.5), centres uniform in a cube of side (8N)^(1/3), "
        "uniform random orientations";
    return s;
}

/// The mixed variant: the same cube, each body drawn uniformly from a box (half 0.5), a sphere
/// (r 0.5), a capsule (r 0.3, half-height 0.4), a cylinder (r 0.5, half-height 0.5), a cone
/// (r 0.5, height 1) and a hexagonal prism hull (r 0.5, half-height 0.5).
template <class T>
Scene<T> make_mixed_scene(std::size_t n, std::uint64_t seed = kN2Seed) {
    Scene<T> s = make_box_scene<T>(n, seed);
    s.shapes = {Box<T>(T(0.5), T(0.5), T(0.5)), Sphere<T>(T(0.5)),     Capsule<T>(T(0.3), T(0.4)),
                Cylinder<T>(T(0.5), T(0.5)),    Cone<T>(T(0.5), T(1)), make_regular_prism(6, T(0.5), T(0.5))};
    scenes::Random rng(seed ^ 0x9E3779B97F4A7C15ull);
    for (std::uint32_t& k : s.shape_of) k = rng.index(static_cast<std::uint32_t>(s.shapes.size()));
    s.description =
        "mixed: box 0.5, sphere r 0.5, capsule r 0.3 hh 0.4, cylinder r 0.5 hh 0.5, cone r 0.5 h 1, "
        "hexagonal prism hull r 0.5 hh 0.5, uniform choice; same cube and orientations";
    return s;
}

/// Boxes in `clusters` dense clumps (four unit volumes per box inside a clump) whose centres are
/// uniform in a cube eight times the clump's side: much empty space, crowded spots.
template <class T>
Scene<T> make_clustered_scene(std::size_t n, std::size_t clusters, std::uint64_t seed = kN2Seed) {
    Scene<T> s = make_box_scene<T>(n, seed);
    const double clump = std::cbrt(4.0 * static_cast<double>(n) / static_cast<double>(clusters));
    s.side = static_cast<T>(8.0 * clump);
    scenes::Random rng(seed + 1);
    std::vector<Vec3<T>> centres;
    for (std::size_t k = 0; k < clusters; ++k) centres.push_back(rng.in_box(Vec3<T>::one() * (T(0.5) * s.side)));
    for (std::size_t i = 0; i < n; ++i)
        s.poses[i].position = centres[i % clusters] + rng.in_box(Vec3<T>::one() * static_cast<T>(0.5 * clump));
    s.description =
        std::to_string(clusters) + " clumps of unit boxes (4 unit volumes per box), clump centres in a cube 8x the clump side";
    return s;
}

/// The box scene with one body in a hundred replaced by a box ten times larger (half extents 5).
template <class T>
Scene<T> make_few_huge_scene(std::size_t n, std::uint64_t seed = kN2Seed) {
    Scene<T> s = make_box_scene<T>(n, seed);
    s.shapes.push_back(Box<T>(T(5), T(5), T(5)));
    for (std::size_t i = 0; i < n; i += 100) s.shape_of[i] = 1;
    s.description = "the box scene with every 100th box 10x larger (half extents 5)";
    return s;
}

/// The boxes spread over a flat layer (a field of debris): x and z span a square of side
/// sqrt(8n / 2), y spans 2 m.
template <class T>
Scene<T> make_layer_scene(std::size_t n, std::uint64_t seed = kN2Seed) {
    Scene<T> s = make_box_scene<T>(n, seed);
    s.side = static_cast<T>(std::sqrt(4.0 * static_cast<double>(n)));
    scenes::Random rng(seed + 2);
    for (Transform<T>& p : s.poses) p.position = rng.in_box(Vec3<T>{T(0.5) * s.side, T(1), T(0.5) * s.side});
    s.description = "unit boxes in a flat layer: square of side sqrt(4N), 2 m thick";
    return s;
}

/// A later frame: every body moves by up to `step` metres per axis and turns by up to `step`
/// radians about a random axis.
template <class T>
void jiggle(Scene<T>& s, scenes::Random& rng, T step) {
    for (Transform<T>& p : s.poses) {
        p.position += rng.in_box(Vec3<T>::one() * step);
        p.orientation = normalized(Quat<T>::from_axis_angle(rng.direction<T>(), rng.uniform(-step, step)) * p.orientation);
    }
}

/// The world boxes of every body, in body order.
template <class T>
void compute_bounds(const Scene<T>& s, std::vector<Aabb<T>>& boxes) {
    boxes.resize(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) boxes[i] = world_bounds(s.shape(i), s.poses[i]);
}

/// A parallel-for: calls body(begin, end) on disjoint ranges covering [0, count), possibly from
/// several threads at once, and returns when all have finished.
using ParallelFor = std::function<void(std::size_t count, const std::function<void(std::size_t begin, std::size_t end)>& body)>;

/// The default parallel-for: the ThreadPool a World uses for its step (xeno/task_system.hpp;
/// one mechanism in the project), with `threads` workers, the caller among them. threads <= 1
/// runs everything on the caller.
inline ParallelFor thread_parallel_for(unsigned threads) {
    std::shared_ptr<ThreadPool> pool = threads > 1 ? std::make_shared<ThreadPool>(threads) : nullptr;
    return [pool](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body) {
        if (count == 0) return;
        xeno::parallel_for(pool.get(), static_cast<std::uint32_t>(count), 1u,
                           [&](std::uint32_t begin, std::uint32_t end) { body(begin, end); });
    };
}

enum class Strategy { brute, brute_lanes, brute_bounds, sap, tree };
constexpr Strategy kStrategies[] = {Strategy::brute, Strategy::brute_lanes, Strategy::brute_bounds, Strategy::sap,
                                    Strategy::tree};

/// The strategy's name in the CSV: brute, brute_lanes, brute_bounds, sap, tree.
inline const char* strategy_name(Strategy s) {
    constexpr const char* names[] = {"brute", "brute_lanes", "brute_bounds", "sap", "tree"};
    return names[static_cast<int>(s)];
}

/// One overlapping pair with its contact.
template <class T>
struct PairContact {
    ProxyPair pair;
    Penetration<T> contact;  ///< normal A → B, depth > 0, a point on each body (world)
};

/// Seconds and counts of one pass.
struct PassResult {
    double seconds = 0;           ///< the whole pass
    double broad_seconds = 0;     ///< world boxes + broad phase (0 for brute)
    std::size_t broad_pairs = 0;  ///< pairs the broad phase passed on (all n(n−1)/2 for brute)
    std::size_t contacts = 0;     ///< pairs that overlap (narrow-phase hits)
};

/// Runs detection passes with one strategy, keeping the broad phase's state between passes.
template <class T>
class Detector {
public:
    /// parallel: how the narrow phase is spread (empty = on the caller); tree_margin: metres;
    /// early_out: the pair strategies reject separated pairs W at a time before collide().
    explicit Detector(Strategy strategy, ParallelFor parallel = {}, T tree_margin = T(0.1), bool early_out = true)
        : strategy_(strategy), parallel_(std::move(parallel)), tree_(tree_margin), early_out_(early_out) {}

    /// One full pass: world boxes, broad phase, contact of every overlapping pair.
    PassResult pass(const Scene<T>& s);
    /// World boxes and broad phase only (no narrow phase); contacts stays 0.
    PassResult broad_only(const Scene<T>& s);

    Strategy strategy() const { return strategy_; }
    /// The last pass's contacts, sorted by pair.
    const std::vector<PairContact<T>>& contacts() const { return contacts_; }
    /// The last broad phase's pairs (empty for brute).
    const std::vector<ProxyPair>& pairs() const { return pairs_; }
    const AabbTree<T>& tree() const { return tree_; }

private:
    void broad(const Scene<T>& s);
    void narrow(const Scene<T>& s);
    void all_pairs_mpr(const Scene<T>& s);
    void set_bounds(const Scene<T>& s);
    void run(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body) const {
        if (parallel_) parallel_(count, body);
        else if (count > 0) body(0, count);
    }

    Strategy strategy_;
    ParallelFor parallel_;
    SweepAndPrune<T> sap_;
    AabbTree<T> tree_;
    std::vector<Aabb<T>> boxes_;
    std::vector<ProxyPair> pairs_;
    std::vector<Penetration<T>> results_;
    std::vector<PairContact<T>> contacts_;
    bool early_out_;
    EarlyOut<T> bounds_;               ///< each body's rounded box in world coordinates (brute_lanes, early_out)
    std::vector<std::uint8_t> apart_;  ///< per pair: rejected by the early-out
};

/// Seconds elapsed since start on the steady clock.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <class T>
PassResult Detector<T>::pass(const Scene<T>& s) {
    const auto start = std::chrono::steady_clock::now();
    PassResult r;
    if (strategy_ == Strategy::brute || strategy_ == Strategy::brute_lanes) {
        all_pairs_mpr(s);
        r.broad_pairs = s.size() * (s.size() - (s.size() > 0 ? 1 : 0)) / 2;
    } else {
        broad(s);
        r.broad_seconds = seconds_since(start);
        narrow(s);
        r.broad_pairs = pairs_.size();
    }
    r.seconds = seconds_since(start);
    r.contacts = contacts_.size();
    return r;
}

template <class T>
PassResult Detector<T>::broad_only(const Scene<T>& s) {
    const auto start = std::chrono::steady_clock::now();
    broad(s);
    PassResult r;
    r.seconds = r.broad_seconds = seconds_since(start);
    r.broad_pairs = pairs_.size();
    return r;
}

template <class T>
void Detector<T>::broad(const Scene<T>& s) {
    compute_bounds(s, boxes_);
    switch (strategy_) {
        case Strategy::brute_bounds: brute_force_pairs(boxes_, pairs_); break;
        case Strategy::sap: sap_.find_pairs(boxes_, pairs_); break;
        case Strategy::tree: tree_.find_pairs(boxes_, pairs_); break;
        case Strategy::brute:
        case Strategy::brute_lanes: pairs_.clear(); break;
    }
}

template <class T>
void Detector<T>::set_bounds(const Scene<T>& s) {
    bounds_.resize(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) bounds_.set(i, s.shape(i), s.poses[i]);
}

// With the early-out, pairs go W at a time through EarlyOut::apart_pairs (the records of pairs a
// few ahead prefetched: the second bodies come at random) and the last few of a range one at a
// time (the same answer, bit for bit); then only the survivors through collide().
template <class T>
void Detector<T>::narrow(const Scene<T>& s) {
    constexpr int W = EarlyOut<T>::width;
    constexpr std::size_t kAhead = 16;
    if (early_out_) set_bounds(s);
    results_.resize(pairs_.size());
    apart_.assign(pairs_.size(), 0);
    run(pairs_.size(), [&](std::size_t begin, std::size_t end) {
        std::size_t k = begin;
        for (; early_out_ && k + W <= end; k += W) {
            std::uint32_t a[W], b[W];
            T margin[W];
            for (int l = 0; l < W; ++l) {
                const std::size_t m = k + static_cast<std::size_t>(l);
                if (m + kAhead < end) bounds_.prefetch(pairs_[m + kAhead].a), bounds_.prefetch(pairs_[m + kAhead].b);
                a[l] = pairs_[m].a, b[l] = pairs_[m].b, margin[l] = T(0);
            }
            const unsigned apart = bounds_.template apart_pairs<W>(a, b, margin);
            for (int l = 0; l < W; ++l) apart_[k + static_cast<std::size_t>(l)] = static_cast<std::uint8_t>((apart >> l) & 1u);
        }
        for (; early_out_ && k < end; ++k) apart_[k] = bounds_.apart(pairs_[k].a, pairs_[k].b, T(0)) ? 1 : 0;
        for (k = begin; k < end; ++k) {
            const ProxyPair p = pairs_[k];
            results_[k] = apart_[k] ? Penetration<T>{} : collide(s.shape(p.a), s.poses[p.a], s.shape(p.b), s.poses[p.b]);
        }
    });
    contacts_.clear();
    for (std::size_t k = 0; k < pairs_.size(); ++k)
        if (results_[k].hit) contacts_.push_back({pairs_[k], results_[k]});
}

// Every pair (i, j), i < j, through MPR. Row k is processed together with row n − 1 − k so that
// every index of the parallel-for carries the same number of pairs. brute_lanes first tests
// bodies j … j + W − 1 against i in lanes and runs MPR on the survivors only.
template <class T>
void Detector<T>::all_pairs_mpr(const Scene<T>& s) {
    constexpr int W = EarlyOut<T>::width;
    const bool lanes = strategy_ == Strategy::brute_lanes;
    if (lanes) set_bounds(s);
    const std::size_t n = s.size();
    const Box<T>* only_box = s.shapes.size() == 1 ? std::get_if<Box<T>>(&s.shapes[0]) : nullptr;
    std::mutex mutex;
    std::vector<std::pair<std::size_t, std::vector<PairContact<T>>>> chunks;
    run((n + 1) / 2, [&](std::size_t begin, std::size_t end) {
        std::vector<PairContact<T>> found;
        auto pair = [&](std::size_t i, std::size_t j) {
            const Transform<T>& pi = s.poses[i];
            const Penetration<T> p =
                only_box ? mpr_penetration(*only_box, pi, *only_box, s.poses[j])
                         : std::visit([&](const auto& a, const auto& b) { return mpr_penetration(a, pi, b, s.poses[j]); },
                                      s.shape(i), s.shape(j));
            if (p.hit) found.push_back({{static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)}, p});
        };
        auto row = [&](std::size_t i) {
            std::size_t j = i + 1;
            for (; lanes && j + W <= n; j += W) {
                unsigned survivors = ~bounds_.template apart_run<W>(i, j, T(0)) & ((1u << W) - 1u);
                for (int l = 0; survivors != 0; ++l, survivors >>= 1)
                    if (survivors & 1u) pair(i, j + static_cast<std::size_t>(l));
            }
            for (; j < n; ++j)
                if (!lanes || !bounds_.apart(i, j, T(0))) pair(i, j);
        };
        for (std::size_t k = begin; k < end; ++k) {
            row(k);
            if (n - 1 - k != k) row(n - 1 - k);
        }
        const std::lock_guard<std::mutex> lock(mutex);
        chunks.emplace_back(begin, std::move(found));
    });
    contacts_.clear();
    for (auto& chunk : chunks) contacts_.insert(contacts_.end(), chunk.second.begin(), chunk.second.end());
    std::sort(contacts_.begin(), contacts_.end(),
              [](const PairContact<T>& x, const PairContact<T>& y) { return x.pair < y.pair; });
}

}  // namespace xeno::bench

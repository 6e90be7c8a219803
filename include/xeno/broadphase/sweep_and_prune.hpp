// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Sweep and prune (Baraff's "Dynamic simulation of non-penetrating rigid bodies", 1992, ch. 7;
// the thesis's cure for O(n²) in 3.4) over world boxes, the world's default broad phase:
//   1. pick the sweep axis: the one with the largest spread of box centres (re-chosen on every
//      update; a change of axis re-sorts from scratch);
//   2. keep the proxies sorted by their box's minimum on that axis: from one step to the next
//      bodies move little, so an insertion sort of the previous order is close to linear
//      (frame-to-frame coherence);
//   3. sweep: each proxy is compared only with the following proxies whose minimum is not past
//      its maximum, and those pairs are checked on the other two axes.
// Empty boxes (free slots) sort last and never pair.
#pragma once

#include "../math/aabb.hpp"
#include "pair.hpp"

namespace xeno {

/// Incremental sweep-and-prune over a vector of boxes indexed by proxy id.
template <class T>
class SweepAndPrune {
public:
    /// Recomputes the overlapping pairs of `boxes` (a < b, sorted), reusing the previous order.
    void find_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs);
    /// The axis (0, 1, 2) used by the last sweep.
    int axis() const { return axis_; }

private:
    struct Entry {
        T min;               ///< the box's minimum on the sweep axis
        std::uint32_t proxy;
    };
    std::vector<Entry> order_;
    int axis_ = -1;
};

template <class T>
void SweepAndPrune<T>::find_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs) {
    pairs.clear();
    const std::size_t n = boxes.size();
    // 1. The axis of largest spread of the centres (variance over non-empty boxes).
    Vec3<T> sum{}, sum_sq{};
    std::size_t live = 0;
    for (const Aabb<T>& b : boxes) {
        if (b.empty()) continue;
        const Vec3<T> c = b.center();
        sum += c;
        sum_sq += hadamard(c, c);
        ++live;
    }
    int axis = 0;
    if (live > 0) {
        const T inv = T(1) / static_cast<T>(live);
        const Vec3<T> variance = sum_sq * inv - hadamard(sum * inv, sum * inv);
        axis = max_axis(variance);
    }
    // 2. Refresh the keys in the previous order (new proxies appended), then insertion sort.
    if (axis != axis_ || order_.size() > n) {
        order_.clear();
        axis_ = axis;
    }
    for (std::size_t i = order_.size(); i < n; ++i) order_.push_back({T(0), static_cast<std::uint32_t>(i)});
    for (Entry& e : order_) e.min = boxes[e.proxy].empty() ? ScalarTraits<T>::infinity : boxes[e.proxy].min[axis];
    // Insertion sort while the order is nearly right; past a budget of moves (a cold start, or a
    // scene that changed a lot) a full sort is cheaper.
    const auto by_min = [](const Entry& x, const Entry& y) { return x.min < y.min || (x.min == y.min && x.proxy < y.proxy); };
    std::size_t moves = 0;
    const std::size_t budget = 8 * order_.size() + 64;
    for (std::size_t i = 1; i < order_.size() && moves <= budget; ++i) {
        const Entry e = order_[i];
        std::size_t j = i;
        for (; j > 0 && by_min(e, order_[j - 1]); --j) order_[j] = order_[j - 1];
        order_[j] = e;
        moves += i - j;
    }
    if (moves > budget) std::sort(order_.begin(), order_.end(), by_min);
    // 3. The sweep.
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (std::size_t i = 0; i < order_.size(); ++i) {
        const Aabb<T>& a = boxes[order_[i].proxy];
        if (a.empty()) break;  // empty boxes sort last
        const T max = a.max[axis];
        for (std::size_t j = i + 1; j < order_.size() && order_[j].min <= max; ++j) {
            const Aabb<T>& b = boxes[order_[j].proxy];
            if (a.min[u] <= b.max[u] && b.min[u] <= a.max[u] && a.min[v] <= b.max[v] && b.min[v] <= a.max[v]) {
                const std::uint32_t p = order_[i].proxy, q = order_[j].proxy;
                pairs.push_back(p < q ? ProxyPair{p, q} : ProxyPair{q, p});
            }
        }
    }
    detail::sort_pairs(pairs);
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Sweep and prune (Baraff's "Dynamic simulation of non-penetrating rigid bodies", 1992, ch. 7;
// the thesis's cure for O(n²) in 3.4) over world boxes, the world's default broad phase:
//   1. pick the sweep axis: the one with the largest spread of box centres (re-chosen on every
//      update; a change of axis re-sorts from scratch);
//   2. keep the proxies sorted by their box's minimum on that axis: from one step to the next
//      bodies move little, so an insertion sort of the previous order is close to linear
//      (frame-to-frame coherence); past a budget of moves (a cold start) a full sort;
//   3. cut the other two axes into a grid of columns a few box sizes wide and copy each box, in
//      sorted order, into every column it touches (a counting sort, so every column stays sorted);
//   4. sweep each column: each box is compared only with the following boxes whose minimum is not
//      past its maximum, and those pairs are checked on the other two axes. A pair whose boxes
//      share several columns is reported only in the column where both boxes are present first
//      (the largest first cell of the two, on each cross axis), so exactly once.
// Why columns: a single sweep of a scene spread in 3D compares each box with every box of the
// slab its extent cuts across the whole scene, n · n w/L candidates for boxes of size w in a cube
// of side L, 1.6·10⁸ at 100,000 unit boxes against 1.7·10⁵ true pairs. Columns of side c cut that
// by (L/c)² for a few duplicates (a box spans (1 + w/c)² columns on average); with c ≥ 4 w that
// is 1.6·10⁶. Scenes of fewer than 256 boxes, or without spread, use one column: the plain sweep
// (Bullet's btMultiSapBroadPhase and Tracy et al., "Efficient Large-Scale Sweep and Prune Methods
// with AABB Insertion and Removal", IEEE VR 2009, split the sweep the same way).
// Empty boxes (free slots) never pair. Boxes must not contain NaN.
// When no box changed since the last call (a world asleep, or at rest), steps 3 and 4 would find
// the same pairs again: the last call's are returned instead.
// Given a task system with several workers, step 4 sweeps the columns in parallel, each into a
// list of its own, and joins the lists in column order: the same pairs in the same order as one
// thread finds them, however the columns are cut and ordered (docs/parallel.md).
#pragma once

#include "../math/aabb.hpp"
#include "../task_system.hpp"
#include "pair.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace xeno {

/// Incremental sweep-and-prune over a vector of boxes indexed by proxy id.
template <class T>
class SweepAndPrune {
public:
    /// Recomputes the overlapping pairs of `boxes` (a < b, sorted, each once; touching counts),
    /// reusing the previous order; the columns' sweeps run on `tasks` when it has several workers.
    void find_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs, TaskSystem* tasks = nullptr);
    /// The axis (0, 1, 2) used by the last sweep.
    int axis() const { return axis_; }
    /// The number of columns of the last sweep (1: a single sweep over all boxes).
    std::size_t columns() const { return cells_u_ * cells_v_; }

private:
    /// A proxy's box as the sweep reads it. An empty box is stored with every minimum +inf and
    /// every maximum -inf: it sorts last and overlaps nothing.
    struct Item {
        T min, max;                    ///< on the sweep axis
        T min_u, max_u, min_v, max_v;  ///< on the two cross axes
        std::uint32_t proxy;
        std::uint16_t first_u, first_v;  ///< its first column cell on each cross axis
        bool empty() const { return max < min; }
    };
    static constexpr std::size_t kMaxCells = 256;  ///< per cross axis
    /// Fewest columns a worker is handed: one. Columns exist only past 256 boxes and hold 64 or
    /// more each (often hundreds: a scene spread flat is cut along one axis only), tens of µs of
    /// sweeping, more than handing out a range costs.
    static constexpr std::uint32_t kColumnsPerRange = 1;

    /// The spread of the boxes' centres (find_pairs, step 1): the sweep axis is the widest.
    struct Spread {
        std::size_t live = 0;  ///< non-empty boxes
        int axis = 0;
        Vec3<T> low, high;  ///< range of the centres
        int u() const { return (axis + 1) % 3; }
        int v() const { return (axis + 2) % 3; }
    };
    static Spread centre_spread(const std::vector<Aabb<T>>& boxes);
    T choose_columns(const std::vector<Aabb<T>>& boxes, const Spread& spread);
    bool refresh_order(const std::vector<Aabb<T>>& boxes, const Spread& spread);
    const Item* fill_columns(const Spread& spread, T inv_cell);
    void sweep_columns(const Item* sweep, std::vector<ProxyPair>& pairs, TaskSystem* tasks);
    std::size_t sweep_column(const Item* sweep, std::size_t column, std::vector<ProxyPair>& out, std::size_t used) const;

    std::vector<Item> order_;                     ///< every proxy, sorted by (min, proxy)
    std::vector<Item> items_;                     ///< the columns' copies, column after column
    std::vector<std::uint16_t> last_u_, last_v_;  ///< per order_ item: its last column cell
    std::vector<std::uint32_t> start_;            ///< column k is items_[start_[k], start_[k + 1])
    std::vector<std::uint32_t> cursor_;           ///< scratch for filling the columns
    std::vector<T> sizes_;                        ///< scratch: sampled box sizes
    std::vector<std::uint32_t> counts_;           ///< scratch for sorting the pairs
    std::vector<ProxyPair> scratch_;
    std::vector<std::vector<ProxyPair>> column_pairs_;  ///< per column, when the sweeps run in parallel
    std::vector<std::size_t> column_used_;              ///< the pairs in each of column_pairs_ (never shrunk)
    std::vector<ProxyPair> last_pairs_;                 ///< the last call's pairs, for a call whose boxes are the same
    bool last_valid_ = false;
    int axis_ = -1;
    std::size_t cells_u_ = 1, cells_v_ = 1;
};

template <class T>
void SweepAndPrune<T>::find_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs, TaskSystem* tasks) {
    pairs.clear();
    const Spread spread = centre_spread(boxes);
    const T inv_cell = choose_columns(boxes, spread);
    if (refresh_order(boxes, spread)) {  // every box as last time: so are the pairs
        pairs = last_pairs_;
        return;
    }
    const Item* sweep = fill_columns(spread, inv_cell);
    sweep_columns(sweep, pairs, tasks);
    detail::sort_pairs_by_first(pairs, boxes.size(), counts_, scratch_);
    last_pairs_ = pairs;
    last_valid_ = true;
}

/// Step 1: the spread of the non-empty boxes' centres, variance and range. Two passes, the mean
/// summed from c / live: no sum of squares that overflows to inf - inf for centres far out (a
/// variance may still be inf, which picks that axis, but never NaN).
template <class T>
typename SweepAndPrune<T>::Spread SweepAndPrune<T>::centre_spread(const std::vector<Aabb<T>>& boxes) {
    constexpr T inf = ScalarTraits<T>::infinity;
    Spread s;
    s.low = Vec3<T>::one() * inf, s.high = -s.low;
    for (const Aabb<T>& b : boxes) s.live += b.empty() ? 0 : 1;
    if (s.live == 0) return s;
    const T inv = T(1) / static_cast<T>(s.live);
    Vec3<T> mean{};
    for (const Aabb<T>& b : boxes)
        if (!b.empty()) mean += b.center() * inv;
    Vec3<T> variance{};
    for (const Aabb<T>& b : boxes) {
        if (b.empty()) continue;
        const Vec3<T> c = b.center();
        variance += hadamard(c - mean, c - mean) * inv;
        s.low = min(s.low, c);
        s.high = max(s.high, c);
    }
    s.axis = max_axis(variance);
    return s;
}

/// The column grid on the cross axes (sets cells_u_ and cells_v_; returns 1 / the cell's side,
/// 0 for one column): cells at least four typical box sizes wide (the median cross-axis size of
/// up to 1024 boxes spread over the vector: a few huge boxes do not inflate it), about 64 boxes
/// per column or more, at most kMaxCells per axis; one cell when nothing is left to cut. (Four
/// sizes measured best: narrower cells copy more boxes, wider ones compare more.)
template <class T>
T SweepAndPrune<T>::choose_columns(const std::vector<Aabb<T>>& boxes, const Spread& spread) {
    cells_u_ = cells_v_ = 1;
    if (spread.live < 256) return T(0);
    const int u = spread.u(), v = spread.v();
    const std::size_t n = boxes.size();
    sizes_.clear();
    for (std::size_t i = 0, stride = std::max<std::size_t>(1, n / 1024); i < n; i += stride)
        if (!boxes[i].empty()) sizes_.push_back(std::max(boxes[i].max[u] - boxes[i].min[u], boxes[i].max[v] - boxes[i].min[v]));
    const auto middle = sizes_.begin() + static_cast<std::ptrdiff_t>(sizes_.size() / 2);
    std::nth_element(sizes_.begin(), middle, sizes_.end());
    const T size = sizes_.empty() ? T(0) : *middle;
    const T span_u = spread.high[u] - spread.low[u], span_v = spread.high[v] - spread.low[v];
    const T max_columns = static_cast<T>(spread.live / 64);
    const T cell = std::max(T(4) * size, std::sqrt(span_u * span_v / max_columns));
    const auto cells_along = [&](T span) {
        const T count = span / cell;
        return count >= T(kMaxCells) ? kMaxCells : count > T(1) ? static_cast<std::size_t>(count) + 1 : std::size_t(1);
    };
    if (!(std::isfinite(cell) && cell > T(0))) return T(0);
    cells_u_ = cells_along(span_u);
    cells_v_ = cells_along(span_v);
    return cells_u_ * cells_v_ > 1 ? T(1) / cell : T(0);
}

/// Step 2: refreshes the boxes in the previous order (new proxies appended; the one pass that
/// reads `boxes` out of order), then sorts. Returns true, leaving the order as it was, when every
/// box is as at the last call. Insertion sort while the order is nearly right; past a budget of
/// moves (a cold start, or a scene that changed a lot) a full sort is cheaper.
template <class T>
bool SweepAndPrune<T>::refresh_order(const std::vector<Aabb<T>>& boxes, const Spread& spread) {
    constexpr T inf = ScalarTraits<T>::infinity;
    const std::size_t n = boxes.size();
    const int axis = spread.axis, u = spread.u(), v = spread.v();
    bool same = last_valid_ && axis == axis_ && order_.size() == n;
    if (axis != axis_ || order_.size() > n) {
        order_.clear();
        axis_ = axis;
    }
    for (std::size_t i = order_.size(); i < n; ++i)
        order_.push_back({T(0), T(0), T(0), T(0), T(0), T(0), static_cast<std::uint32_t>(i), 0, 0});
    for (Item& it : order_) {
        const Aabb<T>& b = boxes[it.proxy];
        Item fresh = it;
        if (b.empty()) {
            fresh.min = fresh.min_u = fresh.min_v = inf;
            fresh.max = fresh.max_u = fresh.max_v = -inf;
        } else {
            fresh.min = b.min[axis], fresh.max = b.max[axis];
            fresh.min_u = b.min[u], fresh.max_u = b.max[u];
            fresh.min_v = b.min[v], fresh.max_v = b.max[v];
        }
        same = same && fresh.min == it.min && fresh.max == it.max && fresh.min_u == it.min_u && fresh.max_u == it.max_u &&
               fresh.min_v == it.min_v && fresh.max_v == it.max_v;
        it = fresh;
    }
    if (same) return true;
    const auto by_min = [](const Item& x, const Item& y) { return x.min < y.min || (x.min == y.min && x.proxy < y.proxy); };
    std::size_t moves = 0;
    const std::size_t budget = 8 * order_.size() + 64;
    for (std::size_t i = 1; i < order_.size() && moves <= budget; ++i) {
        if (!by_min(order_[i], order_[i - 1])) continue;
        const Item e = order_[i];
        std::size_t j = i;
        for (; j > 0 && by_min(e, order_[j - 1]); --j) order_[j] = order_[j - 1];
        order_[j] = e;
        moves += i - j;
    }
    if (moves > budget) std::sort(order_.begin(), order_.end(), by_min);
    return false;
}

/// Step 3: with several columns, copies each box, in sweep order, into every column it touches
/// (a counting sort: count, prefix sums, place), so every column stays sorted. Returns the boxes
/// to sweep: items_ column after column, or order_ itself as the one column.
template <class T>
const typename SweepAndPrune<T>::Item* SweepAndPrune<T>::fill_columns(const Spread& spread, T inv_cell) {
    const std::size_t columns = cells_u_ * cells_v_;
    start_.assign(columns + 1, 0);
    if (columns == 1) {
        for (Item& it : order_) it.first_u = it.first_v = 0;
        start_[1] = static_cast<std::uint32_t>(order_.size());  // empty boxes at the end pair with nothing
        return order_.data();
    }
    const int u = spread.u(), v = spread.v();
    const Vec3<T>& low = spread.low;
    const auto cell_of = [inv_cell](T x, T lo, std::size_t cells) {
        const T f = (x - lo) * inv_cell;  // clamped in floating point first: no overflow, NaN -> 0
        return static_cast<std::uint16_t>(f >= T(cells - 1) ? T(cells - 1) : f > T(0) ? std::floor(f) : T(0));
    };
    last_u_.resize(order_.size());
    last_v_.resize(order_.size());
    for (std::size_t k = 0; k < order_.size(); ++k) {
        Item& it = order_[k];
        if (it.empty()) continue;
        it.first_u = cell_of(it.min_u, low[u], cells_u_);
        it.first_v = cell_of(it.min_v, low[v], cells_v_);
        last_u_[k] = cell_of(it.max_u, low[u], cells_u_);
        last_v_[k] = cell_of(it.max_v, low[v], cells_v_);
        for (std::size_t cu = it.first_u; cu <= last_u_[k]; ++cu)
            for (std::size_t cv = it.first_v; cv <= last_v_[k]; ++cv) ++start_[cu * cells_v_ + cv + 1];
    }
    for (std::size_t k = 0; k < columns; ++k) start_[k + 1] += start_[k];
    items_.resize(start_[columns]);
    cursor_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < order_.size(); ++k) {
        const Item& it = order_[k];
        if (it.empty()) continue;
        for (std::size_t cu = it.first_u; cu <= last_u_[k]; ++cu)
            for (std::size_t cv = it.first_v; cv <= last_v_[k]; ++cv) items_[cursor_[cu * cells_v_ + cv]++] = it;
    }
    return items_.data();
}

/// Step 4: the sweep, column by column; on several workers each column into its own list, the
/// lists joined in column order, so the pairs come out as one thread lists them.
template <class T>
void SweepAndPrune<T>::sweep_columns(const Item* sweep, std::vector<ProxyPair>& pairs, TaskSystem* tasks) {
    const std::size_t columns = cells_u_ * cells_v_;
    if (tasks == nullptr || tasks->workers() <= 1 || columns <= kColumnsPerRange) {
        std::size_t used = 0;
        for (std::size_t column = 0; column < columns; ++column) used = sweep_column(sweep, column, pairs, used);
        pairs.resize(used);
        return;
    }
    column_pairs_.resize(columns);
    column_used_.resize(columns);
    parallel_for(tasks, static_cast<std::uint32_t>(columns), kColumnsPerRange, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t column = begin; column < end; ++column)
            column_used_[column] = sweep_column(sweep, column, column_pairs_[column], 0);
    });
    for (std::size_t column = 0; column < columns; ++column) {
        const auto from = column_pairs_[column].begin();
        pairs.insert(pairs.end(), from, from + static_cast<std::ptrdiff_t>(column_used_[column]));
    }
}

/// Writes the pairs of one column (step 4 of find_pairs) into `out` from index `used` on and
/// returns the new count; `out` grows as needed and is never shrunk (its tail past the count is
/// scratch). `sweep` holds the columns' boxes, each column sorted.
template <class T>
std::size_t SweepAndPrune<T>::sweep_column(const Item* sweep, std::size_t column, std::vector<ProxyPair>& out,
                                           std::size_t used) const {
    const std::size_t cu = column / cells_v_, cv = column % cells_v_;
    const Item* first = sweep + start_[column];
    const Item* last = sweep + start_[column + 1];
    for (const Item* a = first; a != last; ++a) {
        const T max_a = a->max;
        const Item* end = a + 1;
        while (end != last && end->min <= max_a) ++end;
        // Every candidate is written and the count advanced by whether it pairs: whether a
        // candidate overlaps on the cross axes is close to a coin flip (a quarter to a half of
        // them do in a pile), and a branch on it mispredicted often enough to cost 8 ns a
        // candidate, 1 ms a step for 4,000 falling boxes. Room for all of them first.
        const std::size_t room = used + static_cast<std::size_t>(end - (a + 1));
        if (room > out.size()) out.resize(std::max(room, 2 * out.size() + 64));
        ProxyPair* dst = out.data();
        for (const Item* b = a + 1; b != end; ++b) {
            const bool cross = (a->min_u <= b->max_u) & (b->min_u <= a->max_u) & (a->min_v <= b->max_v) & (b->min_v <= a->max_v);
            // Shared columns: only the one where both boxes are present first reports.
            const std::size_t top_u = std::max(a->first_u, b->first_u), top_v = std::max(a->first_v, b->first_v);
            const bool here = (top_u == cu) & (top_v == cv);
            dst[used] = a->proxy < b->proxy ? ProxyPair{a->proxy, b->proxy} : ProxyPair{b->proxy, a->proxy};
            used += static_cast<std::size_t>(cross & here);
        }
    }
    return used;
}

namespace f32 {
using SweepAndPrune = xeno::SweepAndPrune<float>;
}
namespace f64 {
using SweepAndPrune = xeno::SweepAndPrune<double>;
}

}  // namespace xeno

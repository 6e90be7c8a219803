// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A dynamic AABB tree: a binary tree whose leaves hold one proxy's *fattened* box (its box grown
// by `margin` on every side) and whose inner nodes hold the union of their children. It follows
// Erin Catto's b2DynamicTree (Box2D v2.4, after Nathanael Presson's btDbvt in Bullet) and van den
// Bergen, "Efficient Collision Detection of Complex Deformable Models using AABB Trees" (JGT 1997):
//   insert   descend from the root choosing, at each node, the cheaper of "make a new parent of
//            this node and the leaf here" and "go down into the child whose surface area grows
//            least" (the surface-area heuristic, SAH: a box's area is proportional to the chance
//            that a random query hits it); then walk back to the root refitting boxes and
//            heights and applying AVL rotations where the children's heights differ by more than
//            one, so the tree stays O(log n) deep whatever the insertion order;
//   remove   replace the leaf's parent by its sibling, refit and rebalance up to the root;
//   move     nothing while the new box stays inside the fat box (the common case from one step
//            to the next: frame-to-frame coherence), else remove and reinsert with a new fat box;
//            also reinsert when the box shrank so much that the fat box reaches more than four
//            margins beyond it, so a proxy that was once huge does not stay huge in the tree;
//   build    from empty with many proxies (a cold start), a top-down median split on the axis
//            of largest centre spread, O(n log n), instead of n insertions; the leaves are put
//            in the tree's order and the inner nodes allocated depth first after them, so a
//            subtree's nodes lie in two contiguous runs and a traversal stays in cache.
//            find_pairs rebuilds the same way once the inserts, removes and reinserts since the
//            last build outnumber the proxies: amortised O(log n) per change, and it restores the
//            memory layout the incremental edits scatter (when everything moves far every step,
//            a rebuild per step is cheaper than n reinsertions);
//   pairs    the tree against itself, once per unordered pair of nodes (van den Bergen's
//            simultaneous traversal, on an explicit stack): a node with itself descends into
//            (child1, child1), (child2, child2) and (child1, child2); two different nodes whose
//            fat boxes overlap descend into the taller one; two leaves are a candidate, kept only
//            when their *tight* boxes overlap. Then the list is sorted.
// Because the final test is on the tight boxes, with the same comparisons as brute_force_pairs,
// the pairs equal the other strategies' exactly; the fat boxes only decide how often the tree
// changes. Rejected: one query per proxy down the tree (b2DynamicTree::Query per proxy; it visits
// every overlapping pair twice and, for proxies in id order, jumps around memory: measured 2x
// slower at 10,000 boxes and 10x at 100,000); Box2D v3's per-move-buffer pair search (it reports only pairs of moved proxies
// and relies on a persistent pair set, but find_pairs must return the full list each call), and
// the Bullet-style pair of trees (static / dynamic), which the world's boxes do not distinguish.
#pragma once

#include "../config.hpp"
#include "../error.hpp"
#include "../math/aabb.hpp"
#include "pair.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace xeno {

/// Dynamic AABB tree over boxes indexed by proxy id; see the file comment for the algorithm.
template <class T>
class AabbTree {
public:
    /// margin: metres (finite, >= 0) by which each leaf's box is fattened; 0.1 suits 0.1–10 m
    /// bodies moving a few centimetres per step (Box2D's b2_aabbExtension). InvalidArgument if bad.
    explicit AabbTree(T margin = T(0.1));

    /// Recomputes the overlapping pairs of `boxes` (a < b, sorted, each once), exactly those
    /// brute_force_pairs reports. The tree is kept in sync with the vector: proxy i is boxes[i];
    /// an empty box means no proxy; proxies past the end are removed. Pairs whose tight boxes
    /// only touch count as overlapping.
    void find_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs);

    /// Adds proxy with a non-empty box; the proxy must not be in the tree yet.
    void insert(std::uint32_t proxy, const Aabb<T>& box);
    /// Removes proxy; nothing happens when it is not in the tree.
    void remove(std::uint32_t proxy);
    /// Gives proxy (in the tree) a new non-empty box; returns true when it had to be reinserted.
    bool move(std::uint32_t proxy, const Aabb<T>& box);
    /// move() for a tree that rebuild() will rebuild before any other call: the leaf gets the fat
    /// box move() would give it, but is not taken out and reinserted, so the inner boxes are left
    /// stale until the rebuild. A batch of moves bound to end in a rebuild (a world falling leaves
    /// most fat boxes every step) then costs a comparison a proxy instead of a removal and an
    /// insertion, and gives the same tree: rebuild() reads only the leaves, in proxy order.
    bool move_before_rebuild(std::uint32_t proxy, const Aabb<T>& box);
    /// True when move(proxy, box) would reinsert proxy (in the tree): box leaves its fat box, or
    /// the fat box reaches more than four margins beyond it. Reads only; changes nothing.
    bool would_reinsert(std::uint32_t proxy, const Aabb<T>& box) const { return needs_reinsert(fat_box(proxy), box); }
    /// Removes every proxy.
    void clear();
    /// Rebuilds the tree top-down from the current fat boxes (balanced, depth-first layout).
    void rebuild();

    /// True when proxy is in the tree.
    bool contains(std::uint32_t proxy) const { return proxy < leaf_of_.size() && leaf_of_[proxy] != kNull; }
    /// The fattened box stored for proxy (which must be in the tree), metres.
    const Aabb<T>& fat_box(std::uint32_t proxy) const { return nodes_[leaf_of_[proxy]].box; }
    /// Calls f(proxy) for every proxy whose fat box overlaps box (touching counts), in tree order.
    template <class F>
    void query(const Aabb<T>& box, F&& f) const;
    /// Walks the proxies whose fat box the segment origin + t · direction, 0 <= t <= reach, meets,
    /// nearer boxes first, calling reach = f(proxy, reach) for each; reach starts at `length`.
    /// f returns the reach to go on with: unchanged, a hit's distance (only nearer boxes are
    /// visited after that, what a closest-hit search wants), or a negative value to stop.
    template <class F>
    void query_segment(const Vec3<T>& origin, const Vec3<T>& direction, T length, F&& f) const;
    /// Room for this many proxies (their ids below it) without allocating on insert or rebuild.
    void reserve(std::size_t proxies);

    /// Number of proxies in the tree.
    std::size_t size() const { return proxy_count_; }
    /// Height of the tree: 0 for a single leaf, -1 when empty.
    int height() const { return root_ == kNull ? -1 : nodes_[root_].height; }
    /// The fattening margin, metres.
    T margin() const { return margin_; }
    /// Reinsertions (moves out of the fat box) since construction: the cost of incoherence.
    std::size_t reinsertions() const { return reinsertions_; }
    /// Inserts, removes and reinsertions since the last build: a tree grown by many edits is
    /// several times slower to query than a built one (docs/benchmarks.md, "World queries").
    std::size_t edits_since_build() const { return edits_since_build_; }
    /// Checks every invariant (links, heights, inner boxes enclose children, leaf count); for
    /// tests, O(n).
    bool valid() const;

private:
    static constexpr std::uint32_t kNull = 0xffffffffu;
    // 40 bytes in float, 64 in double: two nodes a proxy are most of the tree's memory, so a
    // leaf keeps its proxy id where an inner node keeps its second child, and the leaf's fat box
    // is the only copy of it.
    struct Node {
        Aabb<T> box;           ///< fat box for a leaf, union of the children for an inner node
        std::uint32_t parent;  ///< kNull at the root; next free node when on the free list
        std::uint32_t child1;  ///< kNull for a leaf
        std::uint32_t child2;  ///< a leaf's proxy id
        std::int32_t height;   ///< 0 for a leaf, -1 when free
        bool leaf() const { return child1 == kNull; }
        std::uint32_t proxy() const { return child2; }
    };
    static_assert(sizeof(Node) == 6 * sizeof(T) + 16, "a node is its box and four 32-bit numbers");
    struct NodePair {
        std::uint32_t x, y;
    };

    std::uint32_t allocate();
    void release(std::uint32_t node);
    std::uint32_t make_leaf(std::uint32_t proxy, const Aabb<T>& box);
    void insert_leaf(std::uint32_t leaf);
    void remove_leaf(std::uint32_t leaf);
    std::uint32_t balance(std::uint32_t a);
    void refit_up(std::uint32_t node);
    void replace_child(std::uint32_t parent, std::uint32_t old_child, std::uint32_t new_child);
    std::uint32_t leaves_in_proxy_order();
    void split(std::uint32_t begin, std::uint32_t end);
    std::uint32_t build_inner(std::uint32_t begin, std::uint32_t end, std::uint32_t parent);
    void self_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs);
    bool needs_reinsert(const Aabb<T>& fat, const Aabb<T>& box) const;
    int check(std::uint32_t node, std::size_t& leaves) const;

    std::vector<Node> nodes_;
    std::vector<std::uint32_t> leaf_of_;  ///< proxy id -> leaf node, kNull when absent
    std::vector<NodePair> stack_;         ///< scratch for find_pairs
    std::vector<std::uint32_t> added_;    ///< scratch for find_pairs: proxies new this call
    std::vector<std::uint32_t> counts_;   ///< scratch for sorting the pairs
    std::vector<ProxyPair> scratch_;
    std::uint32_t root_ = kNull;
    std::uint32_t free_ = kNull;
    std::size_t proxy_count_ = 0;
    std::size_t reinsertions_ = 0;
    std::size_t edits_since_build_ = 0;  ///< inserts, removes and reinsertions
    T margin_;
};

template <class T>
AabbTree<T>::AabbTree(T margin) : margin_(margin) {
    detail::require_non_negative(margin, "AabbTree", "margin");
}

template <class T>
void AabbTree<T>::find_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs) {
    pairs.clear();
    const std::uint32_t n = static_cast<std::uint32_t>(boxes.size());
    // 1. Sync the proxies with the vector: drop those past the end and those now empty, move the
    //    rest (usually nothing to do), collect the new ones.
    for (std::uint32_t i = n; i < leaf_of_.size(); ++i) remove(i);
    leaf_of_.resize(n, kNull);
    std::vector<std::uint32_t>& added = added_;
    added.clear();
    for (std::uint32_t i = 0; i < n; ++i) {
        const bool live = !boxes[i].empty();
        if (leaf_of_[i] == kNull) {
            if (live) added.push_back(i);
        } else if (!live) {
            remove(i);
        } else {
            move(i, boxes[i]);
        }
    }
    // 2. New proxies: a cold start builds the whole tree top-down; otherwise insert one by one,
    //    and rebuild when the edits since the last build outnumber the proxies.
    if (root_ == kNull && added.size() > 1) {
        for (const std::uint32_t i : added) make_leaf(i, boxes[i]);
        rebuild();
    } else {
        for (const std::uint32_t i : added) insert(i, boxes[i]);
        if (edits_since_build_ > std::max<std::size_t>(proxy_count_, 64)) rebuild();
    }
    // 3. The tree against itself, then the list sorted.
    self_pairs(boxes, pairs);
    detail::sort_pairs_by_first(pairs, n, counts_, scratch_);
}

// Every pair of leaves whose fat boxes overlap, by a simultaneous traversal of the tree with
// itself; candidates are kept when their tight boxes overlap.
template <class T>
void AabbTree<T>::self_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs) {
    if (root_ == kNull) return;
    stack_.clear();
    stack_.push_back({root_, root_});
    while (!stack_.empty()) {
        const NodePair top = stack_.back();
        stack_.pop_back();
        const Node& x = nodes_[top.x];
        if (top.x == top.y) {  // a subtree with itself
            if (x.leaf()) continue;
            stack_.push_back({x.child1, x.child2});
            stack_.push_back({x.child2, x.child2});
            stack_.push_back({x.child1, x.child1});
            continue;
        }
        const Node& y = nodes_[top.y];
        if (!overlaps(x.box, y.box)) continue;
        if (x.leaf() && y.leaf()) {
            const std::uint32_t px = x.proxy(), py = y.proxy();
            if (overlaps(boxes[px], boxes[py])) pairs.push_back(px < py ? ProxyPair{px, py} : ProxyPair{py, px});
        } else if (y.leaf() || (!x.leaf() && x.height >= y.height)) {
            stack_.push_back({x.child2, top.y});
            stack_.push_back({x.child1, top.y});
        } else {
            stack_.push_back({top.x, y.child2});
            stack_.push_back({top.x, y.child1});
        }
    }
}

template <class T>
void AabbTree<T>::insert(std::uint32_t proxy, const Aabb<T>& box) {
    XENO_ASSERT(!contains(proxy) && !box.empty());
    insert_leaf(make_leaf(proxy, box));
    ++edits_since_build_;
}

template <class T>
void AabbTree<T>::remove(std::uint32_t proxy) {
    if (!contains(proxy)) return;
    const std::uint32_t leaf = leaf_of_[proxy];
    remove_leaf(leaf);
    release(leaf);
    leaf_of_[proxy] = kNull;
    --proxy_count_;
    ++edits_since_build_;
}

template <class T>
bool AabbTree<T>::move(std::uint32_t proxy, const Aabb<T>& box) {
    XENO_ASSERT(contains(proxy) && !box.empty());
    const std::uint32_t leaf = leaf_of_[proxy];
    if (!needs_reinsert(nodes_[leaf].box, box)) return false;
    remove_leaf(leaf);
    nodes_[leaf].box = box.expanded(margin_);
    insert_leaf(leaf);
    ++reinsertions_;
    ++edits_since_build_;
    return true;
}

template <class T>
bool AabbTree<T>::move_before_rebuild(std::uint32_t proxy, const Aabb<T>& box) {
    XENO_ASSERT(contains(proxy) && !box.empty());
    Node& leaf = nodes_[leaf_of_[proxy]];
    if (!needs_reinsert(leaf.box, box)) return false;
    leaf.box = box.expanded(margin_);
    ++reinsertions_;
    ++edits_since_build_;
    return true;
}

template <class T>
void AabbTree<T>::clear() {
    nodes_.clear();
    leaf_of_.clear();
    root_ = free_ = kNull;
    proxy_count_ = 0;
    edits_since_build_ = 0;
}

// Top-down, in place: the leaves, where the tree keeps its only copy of each fat box, are put at
// the front of nodes_ in proxy order and everything else dropped (leaves_in_proxy_order); they
// are then split recursively at the median centre along the axis of largest centre spread, so
// a subtree's leaves lie side by side (split), and the inner nodes are built above them, depth
// first (build_inner). Every split is at the middle of its range, so the last pass needs only
// the ranges. No scratch: the leaves are moved, not indexed.
template <class T>
void AabbTree<T>::rebuild() {
    const std::uint32_t n = leaves_in_proxy_order();
    split(0, n);
    root_ = n == 0 ? kNull : build_inner(0, n, kNull);
    for (std::uint32_t k = 0; k < n; ++k) leaf_of_[nodes_[k].proxy()] = k;
    edits_since_build_ = 0;
}

// The leaves to nodes_[0, n) with the k-th proxy in the tree at k; returns n. First packed in
// the order they lie, then each sent to its rank, which it carries in `parent` until then (the
// build sets every parent again).
template <class T>
std::uint32_t AabbTree<T>::leaves_in_proxy_order() {
    std::uint32_t n = 0;
    for (std::uint32_t i = 0; i < nodes_.size(); ++i) {
        if (nodes_[i].height != 0) continue;  // inner or free
        nodes_[n] = nodes_[i];
        leaf_of_[nodes_[n].proxy()] = n;
        ++n;
    }
    nodes_.resize(n);
    free_ = kNull;
    std::uint32_t rank = 0;
    for (const std::uint32_t leaf : leaf_of_)
        if (leaf != kNull) nodes_[leaf].parent = rank++;
    for (std::uint32_t k = 0; k < n; ++k)
        while (nodes_[k].parent != k) std::swap(nodes_[k], nodes_[nodes_[k].parent]);
    return n;
}

namespace detail {

/// The traversal stack of the queries: nodes and the distances at which a segment enters them, on the
/// call's own stack while the tree is no deeper than its array (an AVL tree of 2^32 leaves is at
/// most 46 deep), spilling to the heap past that: no allocation per query, and queries from
/// several threads share nothing.
template <class T>
class SegmentStack {
public:
    struct Item {
        std::uint32_t node;
        T enter;
    };
    bool empty() const { return size_ == 0; }
    void push(std::uint32_t node, T enter) {
        if (size_ < kFixed) fixed_[size_] = {node, enter};
        else spill_.push_back({node, enter});
        ++size_;
    }
    Item pop() {
        --size_;
        if (size_ < kFixed) return fixed_[size_];
        const Item item = spill_.back();
        spill_.pop_back();
        return item;
    }

private:
    static constexpr std::size_t kFixed = 64;
    Item fixed_[kFixed];
    std::vector<Item> spill_;
    std::size_t size_ = 0;
};

/// Where the segment origin + t · direction, t in [0, reach], enters box; infinity when it misses.
/// `inverse` holds 1 / direction per axis (unused where direction is 0).
template <class T>
T segment_entry(const Aabb<T>& box, const Vec3<T>& origin, const Vec3<T>& direction, const Vec3<T>& inverse, T reach) {
    T enter = T(0), exit = reach;
    for (int i = 0; i < 3; ++i) {
        if (direction[i] == T(0)) {
            if (origin[i] < box.min[i] || origin[i] > box.max[i]) return ScalarTraits<T>::infinity;
            continue;
        }
        T t0 = (box.min[i] - origin[i]) * inverse[i], t1 = (box.max[i] - origin[i]) * inverse[i];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        exit = std::min(exit, t1);
        if (enter > exit) return ScalarTraits<T>::infinity;
    }
    return enter;
}

}  // namespace detail

template <class T>
template <class F>
void AabbTree<T>::query(const Aabb<T>& box, F&& f) const {
    if (root_ == kNull) return;
    detail::SegmentStack<T> stack;  // (the entry distances unused)
    stack.push(root_, T(0));
    while (!stack.empty()) {
        const Node& node = nodes_[stack.pop().node];
        if (!overlaps(node.box, box)) continue;
        if (node.leaf()) {
            f(node.proxy());
        } else {
            stack.push(node.child1, T(0));
            stack.push(node.child2, T(0));
        }
    }
}

// Depth first on an explicit stack, the nearer child on top; a node is tested when its parent is
// popped and skipped at its own turn if the reach has shrunk below its entry since. The boxes are
// fat (a margin beyond every shape), so the reciprocal's rounding cannot cut off a shape the
// exact test would hit.
template <class T>
template <class F>
void AabbTree<T>::query_segment(const Vec3<T>& origin, const Vec3<T>& direction, T length, F&& f) const {
    if (root_ == kNull) return;
    Vec3<T> inverse;
    for (int i = 0; i < 3; ++i) inverse[i] = direction[i] == T(0) ? T(0) : T(1) / direction[i];
    T reach = length;
    detail::SegmentStack<T> stack;
    stack.push(root_, detail::segment_entry(nodes_[root_].box, origin, direction, inverse, reach));
    while (!stack.empty()) {
        const typename detail::SegmentStack<T>::Item item = stack.pop();
        if (item.enter > reach) continue;
        const Node& node = nodes_[item.node];
        if (node.leaf()) {
            reach = f(node.proxy(), reach);
            if (reach < T(0)) return;
            continue;
        }
        const T enter1 = detail::segment_entry(nodes_[node.child1].box, origin, direction, inverse, reach);
        const T enter2 = detail::segment_entry(nodes_[node.child2].box, origin, direction, inverse, reach);
        const bool one_first = enter1 <= enter2;  // a miss enters at infinity
        const std::uint32_t near = one_first ? node.child1 : node.child2, far = one_first ? node.child2 : node.child1;
        const T near_enter = std::min(enter1, enter2), far_enter = std::max(enter1, enter2);
        if (far_enter <= reach) stack.push(far, far_enter);
        if (near_enter <= reach) stack.push(near, near_enter);
    }
}

template <class T>
void AabbTree<T>::reserve(std::size_t proxies) {
    const auto grow = [](auto& table, std::size_t n) {
        if (table.capacity() < n) table.reserve(std::max(n, 2 * table.capacity()));
    };
    grow(nodes_, 2 * proxies);
    grow(leaf_of_, proxies);
}

template <class T>
bool AabbTree<T>::valid() const {
    std::size_t leaves = 0;
    if (root_ != kNull && (nodes_[root_].parent != kNull || check(root_, leaves) < 0)) return false;
    if (leaves != proxy_count_) return false;
    std::size_t mapped = 0;
    for (std::uint32_t p = 0; p < leaf_of_.size(); ++p) {
        if (leaf_of_[p] == kNull) continue;
        const Node& leaf = nodes_[leaf_of_[p]];
        if (!leaf.leaf() || leaf.proxy() != p || leaf.height != 0) return false;
        ++mapped;
    }
    return mapped == proxy_count_;
}

// Returns the subtree's height, or -1 on a broken invariant; counts the leaves.
template <class T>
int AabbTree<T>::check(std::uint32_t index, std::size_t& leaves) const {
    const Node& node = nodes_[index];
    if (node.leaf()) {
        ++leaves;
        return node.height == 0 ? 0 : -1;
    }
    const Node& c1 = nodes_[node.child1];
    const Node& c2 = nodes_[node.child2];
    if (c1.parent != index || c2.parent != index) return -1;
    if (!node.box.contains(c1.box) || !node.box.contains(c2.box)) return -1;
    const int h1 = check(node.child1, leaves), h2 = check(node.child2, leaves);
    if (h1 < 0 || h2 < 0 || node.height != 1 + std::max(h1, h2)) return -1;
    return node.height;
}

template <class T>
std::uint32_t AabbTree<T>::allocate() {
    if (free_ == kNull) {
        nodes_.push_back({});
        return static_cast<std::uint32_t>(nodes_.size() - 1);
    }
    const std::uint32_t node = free_;
    free_ = nodes_[node].parent;
    return node;
}

template <class T>
void AabbTree<T>::release(std::uint32_t node) {
    nodes_[node].parent = free_;
    nodes_[node].height = -1;
    free_ = node;
}

template <class T>
std::uint32_t AabbTree<T>::make_leaf(std::uint32_t proxy, const Aabb<T>& box) {
    const std::uint32_t leaf = allocate();
    if (leaf_of_.size() <= proxy) leaf_of_.resize(proxy + std::size_t(1), kNull);
    nodes_[leaf] = {box.expanded(margin_), kNull, kNull, proxy, 0};
    leaf_of_[proxy] = leaf;
    ++proxy_count_;
    return leaf;
}

// Reinsert when the box left the fat box, or when the fat box reaches more than four margins
// beyond the box on some side (the proxy shrank or jumped back).
template <class T>
bool AabbTree<T>::needs_reinsert(const Aabb<T>& fat, const Aabb<T>& box) const {
    return !fat.contains(box) || !box.expanded(T(4) * margin_).contains(fat);
}

template <class T>
void AabbTree<T>::insert_leaf(std::uint32_t leaf) {
    if (root_ == kNull) {
        root_ = leaf;
        nodes_[leaf].parent = kNull;
        return;
    }
    // 1. Find the best sibling by the SAH (Catto's branch descent). Making a new parent at
    //    `index` costs 2 area(index ∪ leaf); going down adds the area every ancestor grows by
    //    (`inherited`) plus what the child would cost.
    const Aabb<T> box = nodes_[leaf].box;
    std::uint32_t index = root_;
    while (!nodes_[index].leaf()) {
        const Node& node = nodes_[index];
        const T area = node.box.surface_area();
        const T combined = merged(node.box, box).surface_area();
        const T cost_here = T(2) * combined;
        const T inherited = T(2) * (combined - area);
        auto descend_cost = [&](std::uint32_t child) {
            const Node& c = nodes_[child];
            const T grown = merged(box, c.box).surface_area();
            return (c.leaf() ? grown : grown - c.box.surface_area()) + inherited;
        };
        const T cost1 = descend_cost(node.child1), cost2 = descend_cost(node.child2);
        if (cost_here < cost1 && cost_here < cost2) break;
        index = cost1 < cost2 ? node.child1 : node.child2;
    }
    // 2. A new parent for the sibling and the leaf, in the sibling's place.
    const std::uint32_t sibling = index;
    const std::uint32_t old_parent = nodes_[sibling].parent;
    const std::uint32_t parent = allocate();
    nodes_[parent] = {merged(box, nodes_[sibling].box), old_parent, sibling, leaf, nodes_[sibling].height + 1};
    if (old_parent == kNull) root_ = parent;
    else replace_child(old_parent, sibling, parent);
    nodes_[sibling].parent = parent;
    nodes_[leaf].parent = parent;
    // 3. Refit and rebalance up to the root.
    refit_up(parent);
}

template <class T>
void AabbTree<T>::remove_leaf(std::uint32_t leaf) {
    if (leaf == root_) {
        root_ = kNull;
        return;
    }
    const std::uint32_t parent = nodes_[leaf].parent;
    const std::uint32_t grandparent = nodes_[parent].parent;
    const std::uint32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    release(parent);
    nodes_[sibling].parent = grandparent;
    if (grandparent == kNull) {
        root_ = sibling;
        return;
    }
    replace_child(grandparent, parent, sibling);
    refit_up(grandparent);
}

template <class T>
void AabbTree<T>::replace_child(std::uint32_t parent, std::uint32_t old_child, std::uint32_t new_child) {
    Node& p = nodes_[parent];
    if (p.child1 == old_child) p.child1 = new_child;
    else p.child2 = new_child;
}

template <class T>
void AabbTree<T>::refit_up(std::uint32_t index) {
    while (index != kNull) {
        index = balance(index);
        Node& node = nodes_[index];
        const Node& c1 = nodes_[node.child1];
        const Node& c2 = nodes_[node.child2];
        node.height = 1 + std::max(c1.height, c2.height);
        node.box = merged(c1.box, c2.box);
        index = node.parent;
    }
}

// An AVL rotation at inner node A when one child is more than one level taller than the other:
// the taller child (C, with children F and G) takes A's place; A keeps the shorter child B and
// takes C's shorter grandchild, C keeps its taller one. Returns the subtree's new root.
//     A(B, C(F, G))  ->  C(A(B, G), F)      when F is taller than G, else C(A(B, F), G)
template <class T>
std::uint32_t AabbTree<T>::balance(std::uint32_t ia) {
    Node& a = nodes_[ia];
    if (a.leaf() || a.height < 2) return ia;
    const int diff = nodes_[a.child2].height - nodes_[a.child1].height;
    if (diff >= -1 && diff <= 1) return ia;
    // Rotate the taller child up; `keep` is A's other child.
    const bool right = diff > 1;
    const std::uint32_t ic = right ? a.child2 : a.child1;
    const std::uint32_t ib = right ? a.child1 : a.child2;
    Node& c = nodes_[ic];
    const std::uint32_t i_f = c.child1, ig = c.child2;
    const bool f_taller = nodes_[i_f].height > nodes_[ig].height;
    const std::uint32_t up = f_taller ? i_f : ig;    // stays with C
    const std::uint32_t down = f_taller ? ig : i_f;  // moves to A
    // C takes A's place.
    c.child1 = ia;
    c.child2 = up;
    c.parent = a.parent;
    a.parent = ic;
    if (c.parent == kNull) root_ = ic;
    else replace_child(c.parent, ia, ic);
    // A keeps B and takes the shorter grandchild in C's old slot.
    if (right) a.child2 = down;
    else a.child1 = down;
    nodes_[down].parent = ia;
    nodes_[up].parent = ic;
    a.box = merged(nodes_[ib].box, nodes_[down].box);
    a.height = 1 + std::max(nodes_[ib].height, nodes_[down].height);
    c.box = merged(a.box, nodes_[up].box);
    c.height = 1 + std::max(a.height, nodes_[up].height);
    return ic;
}

// The leaves nodes_[begin, end) below the median centre along the axis of largest centre spread
// to the first half, then each half the same way.
template <class T>
void AabbTree<T>::split(std::uint32_t begin, std::uint32_t end) {
    if (end - begin < 2) return;
    Aabb<T> centres;
    for (std::uint32_t k = begin; k < end; ++k) centres.merge(nodes_[k].box.center());
    const int axis = max_axis(centres.max - centres.min);
    const auto centre = [axis](const Node& leaf) {  // as Aabb::center, on one axis
        return leaf.box.min[axis] * T(0.5) + leaf.box.max[axis] * T(0.5);
    };
    const std::uint32_t mid = begin + (end - begin) / 2;
    const auto first = nodes_.begin();
    std::nth_element(first + begin, first + mid, first + end,
                     [&centre](const Node& x, const Node& y) { return centre(x) < centre(y); });
    split(begin, mid);
    split(mid, end);
}

// The inner nodes over the leaves nodes_[begin, end), split in the middle as split did,
// allocated depth first after the leaves (a node, then its first subtree's, then its
// second's), so a subtree's inner nodes are contiguous, as are its leaves. Returns the subtree's
// root; its heights are exact and it is balanced.
template <class T>
std::uint32_t AabbTree<T>::build_inner(std::uint32_t begin, std::uint32_t end, std::uint32_t parent) {
    if (end - begin == 1) {
        nodes_[begin].parent = parent;
        return begin;
    }
    const std::uint32_t node = allocate();
    const std::uint32_t mid = begin + (end - begin) / 2;
    const std::uint32_t left = build_inner(begin, mid, node);
    const std::uint32_t right = build_inner(mid, end, node);
    nodes_[node] = {merged(nodes_[left].box, nodes_[right].box), parent, left, right,
                    1 + std::max(nodes_[left].height, nodes_[right].height)};
    return node;
}

namespace f32 {
using AabbTree = xeno::AabbTree<float>;
}
namespace f64 {
using AabbTree = xeno::AabbTree<double>;
}

}  // namespace xeno

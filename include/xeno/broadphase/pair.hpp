// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The broad phase's output: pairs of proxy indices whose bounding boxes overlap. Every strategy
// reports a pair once, as (a, b) with a < b, and the list sorted, so that all strategies give the
// same list for the same boxes and the world's order of work is deterministic.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace xeno {

/// Two proxies (bodies) whose boxes overlap; a < b.
struct ProxyPair {
    std::uint32_t a;
    std::uint32_t b;
    friend bool operator==(const ProxyPair& x, const ProxyPair& y) { return x.a == y.a && x.b == y.b; }
    friend bool operator<(const ProxyPair& x, const ProxyPair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; }
};

/// The broad-phase strategies the world can use; see broadphase/*.hpp.
enum class BroadPhaseKind {
    brute_force,      ///< every pair's boxes compared: O(n²), the reference
    sweep_and_prune,  ///< sorted sweep on one axis, incremental re-sort (default)
    aabb_tree,        ///< dynamic tree of fattened boxes, incremental refit
};

namespace detail {
inline void sort_pairs(std::vector<ProxyPair>& pairs) { std::sort(pairs.begin(), pairs.end()); }

/// A well-spread 64-bit hash of a pair of slots (the SplitMix64 finaliser, Steele, Lea and
/// Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014): the world's
/// deterministic coin when it must keep only some pairs of a crowd.
inline std::uint64_t mix_pair(std::uint32_t a, std::uint32_t b) {
    std::uint64_t z = (static_cast<std::uint64_t>(a) << 32 | b) + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
}  // namespace detail

}  // namespace xeno

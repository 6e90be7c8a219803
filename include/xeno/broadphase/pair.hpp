// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The broad phase's output: pairs of proxy indices whose bounding boxes overlap. Every strategy
// reports a pair once, as (a, b) with a < b, and the list sorted, so that all strategies give the
// same list for the same boxes and the world's order of work is deterministic.
#pragma once

#include <algorithm>
#include <cstddef>
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

namespace detail {
inline void sort_pairs(std::vector<ProxyPair>& pairs) { std::sort(pairs.begin(), pairs.end()); }

/// Sorts pairs (a < b < proxies) as detail::sort_pairs does, in O(proxies + pairs) when there are
/// many: a least-significant-digit radix sort with the proxy ids as digits, a counting sort on b
/// and then a stable one on a. (Counting on a alone and sorting each run of equal a by b cost twice
/// as much: a run's order is random, and a huge box's run, the ground's, needed std::sort.)
inline void sort_pairs_by_first(std::vector<ProxyPair>& pairs, std::size_t proxies, std::vector<std::uint32_t>& counts,
                                std::vector<ProxyPair>& scratch) {
    if (pairs.size() < 64 || pairs.size() < proxies / 8) {
        sort_pairs(pairs);
        return;
    }
    scratch.resize(pairs.size());
    auto counting_sort = [&](const std::vector<ProxyPair>& from, std::vector<ProxyPair>& to, auto key) {
        counts.assign(proxies + 1, 0);
        for (const ProxyPair& p : from) ++counts[key(p) + 1];
        for (std::size_t k = 0; k < proxies; ++k) counts[k + 1] += counts[k];
        for (const ProxyPair& p : from) to[counts[key(p)]++] = p;  // stable: equal keys keep their order
    };
    counting_sort(pairs, scratch, [](const ProxyPair& p) { return p.b; });
    counting_sort(scratch, pairs, [](const ProxyPair& p) { return p.a; });
}

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

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
/// many: a counting sort on a, then each run of equal a sorted on b (runs are short: a body has a
/// handful of partners; a long run, say a huge box's, gets std::sort).
inline void sort_pairs_by_first(std::vector<ProxyPair>& pairs, std::size_t proxies, std::vector<std::uint32_t>& counts,
                                std::vector<ProxyPair>& scratch) {
    if (pairs.size() < 64 || pairs.size() < proxies / 8) {
        sort_pairs(pairs);
        return;
    }
    counts.assign(proxies + 1, 0);
    for (const ProxyPair& p : pairs) ++counts[p.a + 1];
    for (std::size_t k = 0; k < proxies; ++k) counts[k + 1] += counts[k];
    scratch.resize(pairs.size());
    for (const ProxyPair& p : pairs) scratch[counts[p.a]++] = p;  // afterwards counts[a] = end of run a
    std::size_t begin = 0;
    for (std::size_t a = 0; a < proxies && begin < scratch.size(); ++a) {
        const std::size_t end = counts[a];
        if (end - begin > 16) {
            std::sort(scratch.begin() + static_cast<std::ptrdiff_t>(begin), scratch.begin() + static_cast<std::ptrdiff_t>(end));
        } else {
            for (std::size_t i = begin + 1; i < end; ++i) {
                const ProxyPair p = scratch[i];
                std::size_t j = i;
                for (; j > begin && p.b < scratch[j - 1].b; --j) scratch[j] = scratch[j - 1];
                scratch[j] = p;
            }
        }
        begin = end;
    }
    pairs.swap(scratch);
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

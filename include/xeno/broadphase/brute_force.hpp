// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Brute-force broad phase: every pair of boxes compared, O(n²). The reference the other
// strategies are tested against, and the thesis's own method (3.3.1.1 ran XenoCollide on every
// pair; with boxes first this is the "bounding volume early-out" of 3.4). Empty boxes (free
// slots) never pair.
#pragma once

#include "../math/aabb.hpp"
#include "pair.hpp"

namespace xeno {

/// Appends every overlapping pair of boxes (a < b), sorted.
template <class T>
void brute_force_pairs(const std::vector<Aabb<T>>& boxes, std::vector<ProxyPair>& pairs) {
    pairs.clear();
    const std::uint32_t n = static_cast<std::uint32_t>(boxes.size());
    for (std::uint32_t i = 0; i < n; ++i) {
        if (boxes[i].empty()) continue;
        for (std::uint32_t j = i + 1; j < n; ++j)
            if (overlaps(boxes[i], boxes[j]) && !boxes[j].empty()) pairs.push_back({i, j});
    }
}

}  // namespace xeno

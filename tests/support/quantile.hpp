// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The q-quantile of a sample, as the tests that state error distributions report it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace xeno::test {

/// The value at rank q·(n − 1) of the sorted sample (no interpolation); 0 for an empty sample.
template <class T>
T quantile(std::vector<T> v, double q) {
    if (v.empty()) return T(0);
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

}  // namespace xeno::test

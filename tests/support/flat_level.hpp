// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Level geometry for dynamics tests: a flat triangle mesh at y = 0.
#pragma once

#include <xeno/shape/triangle_mesh.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace xeno::test {

/// A flat `cells` × `cells` m mesh at y = 0 centred on the origin (1 m cells, each split along a
/// diagonal: 2 · cells² triangles).
template <class T>
TriangleMesh<T> flat_mesh(int cells) {
    std::vector<Vec3<T>> v;
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) v.push_back({static_cast<T>(i - cells / 2), T(0), static_cast<T>(j - cells / 2)});
    const auto at = [cells](int i, int j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            tris.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            tris.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return TriangleMesh<T>(v, tris);
}

}  // namespace xeno::test

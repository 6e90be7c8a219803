// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Level geometry for tests: triangle meshes over a grid of cells, flat or shaped by a height
// function.
#pragma once

#include <xeno/shape/triangle_mesh.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace xeno::test {

/// An n × n grid of cells `cell` metres wide in the xz plane, centred on the origin, heights
/// from `height(x, z)`, split like a HeightField's cells (both triangles facing +y).
template <class T, class H>
TriangleMesh<T> grid_mesh(int n, T cell, H height) {
    std::vector<Vec3<T>> v;
    std::vector<std::array<std::uint32_t, 3>> tris;
    const T half = T(0.5) * cell * static_cast<T>(n);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const T x = cell * static_cast<T>(i) - half, z = cell * static_cast<T>(j) - half;
            v.push_back({x, height(x, z), z});
        }
    const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            tris.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            tris.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return TriangleMesh<T>(v, tris);
}

/// A flat `cells` × `cells` m mesh at y = 0 centred on the origin (1 m cells: 2 · cells²
/// triangles).
template <class T>
TriangleMesh<T> flat_mesh(int cells) {
    return grid_mesh<T>(cells, T(1), [](T, T) { return T(0); });
}

}  // namespace xeno::test

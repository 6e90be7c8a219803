// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Compiled mode (README, "Compiled mode"). Header-only is the default: every translation unit
// that steps a World compiles the whole engine, World<T> and the narrow phase over the full
// shape-pair matrix, at a cost of seconds per file. A game that defines XENO_COMPILED_LIB (the
// CMake target xeno::compiled does it for whoever links it) sees the heavy templates below as
// `extern template`s for float and double: its files only parse them, and one source file,
// src/xeno_compiled.cpp (the static library xeno::compiled), compiles them once. The pattern of
// fmt's and spdlog's compiled modes. Other scalar types stay header-only in both modes.
//
// Each header declares its own templates `extern` at its end (world.hpp, collide.hpp, raycast.hpp,
// convex_hull.hpp, snapshot.hpp), so a file that includes only <xeno/dynamics/world.hpp> gets
// compiled mode too; the list below is the definitions, and must name everything they declare.
#pragma once

#include "collide/collide.hpp"
#include "collide/raycast.hpp"
#include "dynamics/snapshot.hpp"
#include "dynamics/world.hpp"
#include "shape/convex_hull.hpp"

/// The templates compiled once in compiled mode, for scalar T: the explicit instantiations of
/// src/xeno_compiled.cpp (the headers hold the matching `extern` declarations).
#define XENO_DETAIL_COMPILED_TEMPLATES(T)                                                                                   \
    template class xeno::World<T>;                                                                                          \
    template bool xeno::intersect<T>(const xeno::Shape<T>&, const xeno::Transform<T>&, const xeno::Shape<T>&,               \
                                     const xeno::Transform<T>&);                                                            \
    template xeno::Penetration<T> xeno::collide<T>(const xeno::Shape<T>&, const xeno::Transform<T>&, const xeno::Shape<T>&, \
                                                   const xeno::Transform<T>&);                                              \
    template xeno::ContactManifold<T> xeno::generate_contacts<T>(const xeno::Shape<T>&, const xeno::Transform<T>&,          \
                                                                 const xeno::Shape<T>&, const xeno::Transform<T>&, T, T);   \
    template std::optional<xeno::RayHit<T>> xeno::raycast<T>(const xeno::Shape<T>&, const xeno::Transform<T>&,              \
                                                             const xeno::Ray<T>&);                                          \
    template xeno::ConvexHull<T> xeno::make_convex_hull<T>(const std::vector<xeno::Vec3<T>>&);                              \
    template std::vector<std::uint8_t> xeno::save_snapshot<T>(const xeno::World<T>&);                                       \
    template void xeno::restore_snapshot<T>(xeno::World<T>&, const std::vector<std::uint8_t>&);

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Seen by every test translation unit through the precompiled header: World's members are
// compiled once, in tests/instantiate.cpp, instead of in each of the forty test files.
#pragma once

#include <xeno/collide/collide.hpp>
#include <xeno/collide/raycast.hpp>
#include <xeno/dynamics/world.hpp>

extern template class xeno::World<float>;
extern template class xeno::World<double>;

// The narrow phase over the Shape variant (each visits the whole shape-pair matrix).
#define XENO_EXTERN_NARROW_PHASE(T)                                                                                                  \
    extern template bool xeno::intersect<T>(const xeno::Shape<T>&, const xeno::Transform<T>&, const xeno::Shape<T>&,                 \
                                            const xeno::Transform<T>&);                                                              \
    extern template xeno::Penetration<T> xeno::collide<T>(const xeno::Shape<T>&, const xeno::Transform<T>&, const xeno::Shape<T>&,   \
                                                          const xeno::Transform<T>&);                                                \
    extern template xeno::ContactManifold<T> xeno::generate_contacts<T>(const xeno::Shape<T>&, const xeno::Transform<T>&,            \
                                                                        const xeno::Shape<T>&, const xeno::Transform<T>&, T);        \
    extern template std::optional<xeno::RayHit<T>> xeno::raycast<T>(const xeno::Shape<T>&, const xeno::Transform<T>&,                \
                                                                    const xeno::Ray<T>&);
XENO_EXTERN_NARROW_PHASE(float)
XENO_EXTERN_NARROW_PHASE(double)
#undef XENO_EXTERN_NARROW_PHASE

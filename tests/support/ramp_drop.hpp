// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A fast body dropped onto a 45-degree ramp (the plane y = -x) towards a wall at x = 1 that the
// ramp turns it into: the scene of the out-of-reach regression tests (docs/collision.md,
// "Speculative contacts out of reach"), built of boxes or of meshes by the caller.
#pragma once

#include "sim.hpp"

#include <algorithm>
#include <cmath>

namespace xeno::test {

/// Drops `shape` (radius `radius`, 10 cm from the wall at x = 1) at `speed` straight down onto
/// the ramp of world `w`, a few steps above it and a fraction phase / 5 of a step more, and
/// returns the farthest x its centre reaches in 1.5 s.
template <class T>
T farthest_after_ramp_drop(World<T>& w, const Shape<T>& shape, T radius, T speed, int phase) {
    const T x0 = T(1) - radius - T(0.1);
    BodyDef<T> def;
    def.position = {x0, -x0 + radius * std::sqrt(T(2)) + speed / T(60) * (T(3) + T(phase) / T(5)), T(0)};
    def.linear_velocity = {T(0), -speed, T(0)};
    def.fast = true;
    const BodyId id = w.create_body(shape, def);
    T farthest = -ScalarTraits<T>::infinity;
    simulate(w, T(1.5), [&](int) { farthest = std::max(farthest, w.body(id).position().x); });
    return farthest;
}

}  // namespace xeno::test

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// SupportFace<T>: the flat feature of a shape most aligned with a direction, as a convex polygon
// in the shape's local frame. Contact manifolds clip two of these against each other
// (docs/collision.md, "Contact manifolds by clipping"). Vertices wind counter-clockwise seen from
// outside the shape (looking against the face normal). A curved part answers with fewer vertices: 1
// for a sphere or a rounded end, 2 for a capsule's or a cylinder's side (a segment).
#pragma once

#include "../math/vec3.hpp"

#include <array>

namespace xeno {

/// A convex polygon of at most `capacity` vertices, local frame, counter-clockwise from outside.
template <class T>
struct SupportFace {
    /// Enough for a box face, a hull face, and the 12-gon that stands for a cylinder cap; larger
    /// hull faces are thinned evenly (their vertices stay on the face, so clipping stays exact
    /// inside the thinned polygon).
    static constexpr int capacity = 16;

    std::array<Vec3<T>, capacity> vertex{};  ///< metres, shape-local frame
    int count = 0;                           ///< number of valid vertices (1, 2 or >= 3)
    Vec3<T> normal{};                        ///< unit outward normal (for 1 or 2 vertices: the query direction)

    void push(const Vec3<T>& p) {
        if (count < capacity) vertex[static_cast<std::size_t>(count++)] = p;
    }
    const Vec3<T>& operator[](int i) const { return vertex[static_cast<std::size_t>(i)]; }
};

namespace f32 {
using SupportFace = xeno::SupportFace<float>;
}
namespace f64 {
using SupportFace = xeno::SupportFace<double>;
}

}  // namespace xeno

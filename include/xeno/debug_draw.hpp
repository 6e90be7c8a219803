// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// DebugDraw<T>: the small drawing interface through which xeno describes what it simulates
// (bodies as lit triangles with outlined edges, contact points, normals). No graphics API and no
// dependency: a renderer implements the three calls. examples/render/ implements it on OSMesa.
// draw_shape() tessellates any Shape<T> placed by a Transform<T> into triangles (counter-clockwise
// seen from outside, so a renderer can light them by their geometric normal) and feature edges.
#pragma once

#include "shape/shape.hpp"

namespace xeno {

/// Linear RGBA in [0, 1].
struct Color {
    float r = 1, g = 1, b = 1, a = 1;
};

/// Receives world-space primitives; all coordinates in metres.
template <class T>
class DebugDraw {
public:
    virtual ~DebugDraw() = default;
    /// A filled triangle, counter-clockwise seen from its front (outside of a body).
    virtual void draw_triangle(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, Color color) = 0;
    /// A line segment (edges, normals).
    virtual void draw_line(const Vec3<T>& a, const Vec3<T>& b, Color color) = 0;
    /// A point marker of the given size in metres (contact points).
    virtual void draw_point(const Vec3<T>& p, T size, Color color) = 0;
};

}  // namespace xeno

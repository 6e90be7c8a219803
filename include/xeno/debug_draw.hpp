// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// DebugDraw<T>: the small drawing interface through which xeno describes what it simulates
// (bodies as lit triangles with outlined edges, contact points, normals). No graphics API and no
// dependency: a renderer implements the three calls. examples/render/ implements it on OSMesa.
// draw_shape() tessellates any Shape<T> placed by a Transform<T> into triangles (counter-clockwise
// seen from outside, so a renderer can light them by their geometric normal) and feature edges.
// Polyhedra (boxes, hulls) are drawn exactly, face by face. Round shapes are surfaces of
// revolution about their local y axis: a profile from the top pole down to the bottom one is swept
// around the axis (a "lathe"), so sphere, capsule, cylinder and cone share one routine; their
// edges are a few rings and one meridian, enough to see a round body turn.
#pragma once

#include "shape/shape.hpp"

#include <cstddef>
#include <vector>

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

/// Draws shape s placed by t: filled triangles (CCW from outside) in `fill`, feature edges as lines in `edge`.
/// Edges: every face outline of a box or hull; a sphere's equator and one meridian; a capsule's two
/// rims and one meridian; a cylinder's cap rims and one side line; a cone's base rim and one side line.
template <class T>
void draw_shape(DebugDraw<T>& out, const Shape<T>& s, const Transform<T>& t, Color fill, Color edge);

namespace detail {

/// Slices around the axis and stacks from pole to pole used to tessellate round shapes.
inline constexpr int sphere_slices = 20, sphere_stacks = 12;
inline constexpr int round_slices = 24;  ///< cylinders and cones

/// A surface of revolution about local y: profile points (radius, y) from the top of the shape
/// down its outside to the bottom, swept over `slices` angles. Points with radius 0 are poles.
template <class T>
class Lathe {
public:
    Lathe(const std::vector<T>& radius, const std::vector<T>& y, int slices, const Transform<T>& t);

    /// Triangles between consecutive profile points, counter-clockwise from outside.
    void draw_surface(DebugDraw<T>& out, Color fill) const;
    /// The ring (closed polyline) at profile point i.
    void draw_ring(DebugDraw<T>& out, std::size_t i, Color edge) const;
    /// The polyline along the angle-0 meridian from profile point first to last.
    void draw_meridian(DebugDraw<T>& out, std::size_t first, std::size_t last, Color edge) const;

private:
    const Vec3<T>& at(std::size_t i, std::size_t k) const { return points_[i * slices_ + k % slices_]; }

    std::vector<T> radius_, y_;  ///< the profile, local frame
    std::size_t slices_;
    std::vector<Vec3<T>> points_;  ///< world frame, profile-major
};

template <class T>
Lathe<T>::Lathe(const std::vector<T>& radius, const std::vector<T>& y, int slices, const Transform<T>& t)
    : radius_(radius), y_(y), slices_(static_cast<std::size_t>(slices)) {
    points_.reserve(radius.size() * slices_);
    for (std::size_t i = 0; i < radius.size(); ++i)
        for (std::size_t k = 0; k < slices_; ++k) {
            const T angle = T(2) * ScalarTraits<T>::pi * static_cast<T>(k) / static_cast<T>(slices_);
            points_.push_back(t.apply(Vec3<T>{radius[i] * std::cos(angle), y[i], radius[i] * std::sin(angle)}));
        }
}

template <class T>
void Lathe<T>::draw_surface(DebugDraw<T>& out, Color fill) const {
    // With p(i, k) = (r_i cos φ_k, y_i, r_i sin φ_k), the derivative along the angle crossed with
    // the derivative down the profile points outward, so (p(i,k), p(i,k+1), p(i+1,k+1)) and
    // (p(i,k), p(i+1,k+1), p(i+1,k)) are counter-clockwise seen from outside. At a pole one of the
    // two collapses to a segment and is skipped.
    for (std::size_t i = 0; i + 1 < radius_.size(); ++i) {
        if (radius_[i] == radius_[i + 1] && y_[i] == y_[i + 1]) continue;  // repeated point (capsule, h = 0)
        for (std::size_t k = 0; k < slices_; ++k) {
            if (radius_[i] > T(0)) out.draw_triangle(at(i, k), at(i, k + 1), at(i + 1, k + 1), fill);
            if (radius_[i + 1] > T(0)) out.draw_triangle(at(i, k), at(i + 1, k + 1), at(i + 1, k), fill);
        }
    }
}

template <class T>
void Lathe<T>::draw_ring(DebugDraw<T>& out, std::size_t i, Color edge) const {
    for (std::size_t k = 0; k < slices_; ++k) out.draw_line(at(i, k), at(i, k + 1), edge);
}

template <class T>
void Lathe<T>::draw_meridian(DebugDraw<T>& out, std::size_t first, std::size_t last, Color edge) const {
    for (std::size_t i = first; i < last; ++i) out.draw_line(at(i, 0), at(i + 1, 0), edge);
}

/// Appends the profile of a half sphere of radius r centred at height y0, `stacks` steps from the
/// pole (top when upper, else from the equator down to the bottom pole).
template <class T>
void append_hemisphere(std::vector<T>& radius, std::vector<T>& y, T r, T y0, int stacks, bool upper) {
    for (int j = 0; j <= stacks; ++j) {
        const int step = upper ? j : stacks + j;  // polar angle in steps of π / (2 stacks) from +y
        const T theta = ScalarTraits<T>::pi * static_cast<T>(step) / static_cast<T>(2 * stacks);
        radius.push_back(step == 0 || step == 2 * stacks ? T(0) : r * std::sin(theta));
        y.push_back(y0 + r * std::cos(theta));
    }
}

template <class T>
void draw_box(DebugDraw<T>& out, const Box<T>& box, const Transform<T>& t, Color fill, Color edge) {
    // Corner i has bit 0 for x, bit 1 for y, bit 2 for z set on the + side; faces are listed
    // counter-clockwise from outside (the same table as make_box_polyhedron).
    const Vec3<T>& h = box.half_extents();
    Vec3<T> corner[8];
    for (int i = 0; i < 8; ++i) corner[i] = t.apply(Vec3<T>{(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
    constexpr int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& f : faces) {
        out.draw_triangle(corner[f[0]], corner[f[1]], corner[f[2]], fill);
        out.draw_triangle(corner[f[0]], corner[f[2]], corner[f[3]], fill);
    }
    for (int i = 0; i < 8; ++i)
        for (int bit = 1; bit < 8; bit <<= 1)
            if (!(i & bit)) out.draw_line(corner[i], corner[i | bit], edge);
}

template <class T>
void draw_polyhedron(DebugDraw<T>& out, const ConvexPolyhedron<T>& hull, const Transform<T>& t, Color fill, Color edge) {
    std::vector<Vec3<T>> world;
    world.reserve(hull.vertices().size());
    for (const Vec3<T>& v : hull.vertices()) world.push_back(t.apply(v));
    const std::vector<std::uint32_t>& index = hull.face_indices();
    // A convex face is a fan from its first vertex; the fan keeps the face's winding.
    for (const auto& f : hull.faces())
        for (std::uint32_t k = 1; k + 1 < f.count; ++k)
            out.draw_triangle(world[index[f.first]], world[index[f.first + k]], world[index[f.first + k + 1]], fill);
    for (const auto& e : hull.edges()) out.draw_line(world[e.first], world[e.second], edge);
}

template <class T>
void draw_round(DebugDraw<T>& out, const Shape<T>& s, const Transform<T>& t, Color fill, Color edge) {
    std::vector<T> radius, y;
    if (const auto* sphere = std::get_if<Sphere<T>>(&s)) {
        // Equator and one meridian, so a spinning ball shows its spin.
        append_hemisphere(radius, y, sphere->radius(), T(0), sphere_stacks / 2, true);
        radius.pop_back();
        y.pop_back();
        append_hemisphere(radius, y, sphere->radius(), T(0), sphere_stacks / 2, false);
        const Lathe<T> lathe(radius, y, sphere_slices, t);
        lathe.draw_surface(out, fill);
        lathe.draw_ring(out, static_cast<std::size_t>(sphere_stacks / 2), edge);
        lathe.draw_meridian(out, 0, radius.size() - 1, edge);
    } else if (const auto* capsule = std::get_if<Capsule<T>>(&s)) {
        // Top cap down to the ring at +h, the side, the ring at -h down to the bottom pole.
        append_hemisphere(radius, y, capsule->radius(), capsule->half_height(), sphere_stacks / 2, true);
        append_hemisphere(radius, y, capsule->radius(), -capsule->half_height(), sphere_stacks / 2, false);
        const Lathe<T> lathe(radius, y, sphere_slices, t);
        lathe.draw_surface(out, fill);
        lathe.draw_ring(out, static_cast<std::size_t>(sphere_stacks / 2), edge);
        lathe.draw_ring(out, static_cast<std::size_t>(sphere_stacks / 2 + 1), edge);
        lathe.draw_meridian(out, 0, radius.size() - 1, edge);
    } else if (const auto* cylinder = std::get_if<Cylinder<T>>(&s)) {
        const T r = cylinder->radius(), h = cylinder->half_height();
        const Lathe<T> lathe({T(0), r, r, T(0)}, {h, h, -h, -h}, round_slices, t);
        lathe.draw_surface(out, fill);
        lathe.draw_ring(out, 1, edge);
        lathe.draw_ring(out, 2, edge);
        lathe.draw_meridian(out, 1, 2, edge);
    } else if (const auto* cone = std::get_if<Cone<T>>(&s)) {
        const T r = cone->radius(), apex = cone->apex().y, base = cone->base_y();
        const Lathe<T> lathe({T(0), r, T(0)}, {apex, base, base}, round_slices, t);
        lathe.draw_surface(out, fill);
        lathe.draw_ring(out, 1, edge);
        lathe.draw_meridian(out, 0, 1, edge);
    }
}

}  // namespace detail

template <class T>
void draw_shape(DebugDraw<T>& out, const Shape<T>& s, const Transform<T>& t, Color fill, Color edge) {
    if (const auto* box = std::get_if<Box<T>>(&s)) {
        detail::draw_box(out, *box, t, fill, edge);
    } else if (const auto* hull = std::get_if<ConvexPolyhedron<T>>(&s)) {
        detail::draw_polyhedron(out, *hull, t, fill, edge);
    } else {
        detail::draw_round(out, s, t, fill, edge);
    }
}

namespace f32 {
using DebugDraw = xeno::DebugDraw<float>;
}
namespace f64 {
using DebugDraw = xeno::DebugDraw<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Shape casts: shape A swept along a straight translation against a resting shape B, giving the
// first time of impact (a fraction of the translation), the normal and the point. The method is
// the GJK ray cast (G. van den Bergen, "Ray Casting against General Convex Objects with
// Application to Continuous Collision Detection", 2004): A touches B after moving λ·r exactly when
// λ·r lies in the Minkowski difference C = B ⊖ A, so the cast is a ray from the origin along r
// against C, which is only ever seen through its support function s_C(v) = s_B(v) − s_A(−v).
// Each iteration keeps a GJK simplex of points of C and v, the vector from the simplex's closest
// point to the ray's current point x = λ·r. When the support plane of C along v separates x from C,
// x cannot be in C up to that plane: λ advances to the plane (or the ray misses, if it runs away
// from it). Otherwise the support point joins the simplex. It ends when |v| falls below a
// tolerance: x is on C's surface, λ is the time of impact, the last separating v the normal, and
// the simplex's barycentric weights give the point on B. λ only ever moves to separating planes,
// so it never passes the true time of impact: a cast that runs out of iterations reports a time
// that is early, never late. Works for every shape, curved ones included (their support functions
// are exact); no margins. Shapes that overlap at the start report fraction 0 with
// `initially_overlapping` set and collide()'s normal and point. Shapes that only touch (no
// overlap, as intersect() has it) are not overlapping: moved apart or along the contact they miss,
// moved into each other they hit at fraction 0 with the contact's normal, the flag unset.
#pragma once

#include "../shape/compound.hpp"
#include "collide.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

namespace xeno {

/// Where a swept shape first touches another.
template <class T>
struct ShapeCastHit {
    T fraction{};                        ///< of the translation, 0 … 1, at which A touches B
    Vec3<T> normal{};                    ///< unit, world, from A to B at the moment of contact
    Vec3<T> point{};                     ///< world, the point of B that A touches
    bool initially_overlapping = false;  ///< A overlapped B before moving: fraction 0; normal and point are collide()'s
};

namespace detail {

/// A point of C = B ⊖ A with its witnesses on A (at the start) and on B, world frame relative to
/// an origin near the shapes (keeps the numbers small far from the world origin).
template <class T>
struct CastVertex {
    Vec3<T> c, a, b;  // c = b − a
};

/// The point of the simplex {x − c_i} closest to the origin, as weights on its vertices; the
/// vertices with weight 0 are dropped from the simplex. Returns the closest point (v).
/// Closest-feature regions as in Ericson, "Real-Time Collision Detection" (2005), 5.1.2–5.1.6.
template <class T>
class CastSimplex {
public:
    int size() const { return n_; }
    const CastVertex<T>& vertex(int i) const { return vertices_[static_cast<std::size_t>(i)]; }
    T weight(int i) const { return weights_[static_cast<std::size_t>(i)]; }
    void add(const CastVertex<T>& p) { vertices_[static_cast<std::size_t>(n_++)] = p; }
    bool holds(const Vec3<T>& c) const {
        for (int i = 0; i < n_; ++i)
            if (vertices_[static_cast<std::size_t>(i)].c == c) return true;
        return false;
    }

    /// Reduces the simplex to the smallest one whose hull holds the closest point to x and
    /// returns x − (that point). A tetrahedron that holds x returns zero.
    Vec3<T> closest(const Vec3<T>& x) {
        std::array<Vec3<T>, 4> q;
        for (int i = 0; i < n_; ++i) q[static_cast<std::size_t>(i)] = x - vertices_[static_cast<std::size_t>(i)].c;
        std::array<T, 4> w{};
        if (n_ == 1) w[0] = T(1);
        if (n_ == 2) segment(q[0], q[1], w[0], w[1]);
        if (n_ == 3) triangle(q[0], q[1], q[2], w[0], w[1], w[2]);
        if (n_ == 4) tetrahedron(q, w);
        int kept = 0;
        Vec3<T> v = Vec3<T>::zero();
        for (int i = 0; i < n_; ++i) {
            const std::size_t s = static_cast<std::size_t>(i);
            if (!(w[s] > T(0))) continue;
            v += q[s] * w[s];
            vertices_[static_cast<std::size_t>(kept)] = vertices_[s];
            weights_[static_cast<std::size_t>(kept++)] = w[s];
        }
        n_ = kept;
        if (n_ == 2) v = edge_offset(v);
        if (n_ == 3) v = face_offset(x, v);
        return v;
    }

private:
    // Σ wᵢqᵢ loses the direction of the offset to cancellation when the simplex is much larger
    // than the offset: a capsule 1 mm above a 100 m box gives, in float, a tilt of 2e-3 rad, the
    // far corners then pass for support points above x, and the cast never separates. The offset
    // from an edge or a face is perpendicular to it, and these two restore that from the edges,
    // which carry no such error.

    /// The offset from an edge with the round-off along the edge taken out.
    Vec3<T> edge_offset(const Vec3<T>& summed) const {
        const Vec3<T> e = vertices_[1].c - vertices_[0].c;
        const T ee = dot(e, e);
        return ee > T(0) ? summed - e * (dot(summed, e) / ee) : summed;
    }
    /// x minus its projection on the plane of the face, along the face's normal.
    Vec3<T> face_offset(const Vec3<T>& x, const Vec3<T>& summed) const {
        const Vec3<T>&a = vertices_[0].c, &b = vertices_[1].c, &c = vertices_[2].c;
        const Vec3<T> n = cross(b - a, c - a);
        const T nn = dot(n, n);
        return nn > T(0) ? n * (dot(n, x - a) / nn) : summed;
    }
    static void segment(const Vec3<T>& a, const Vec3<T>& b, T& wa, T& wb) {
        const Vec3<T> ab = b - a;
        const T denom = dot(ab, ab);
        const T t = denom > T(0) ? clamp(-dot(a, ab) / denom, T(0), T(1)) : T(0);
        wa = T(1) - t, wb = t;
    }
    static void triangle(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, T& wa, T& wb, T& wc) {
        wa = wb = wc = T(0);
        const Vec3<T> ab = b - a, ac = c - a, ap = -a;
        const T d1 = dot(ab, ap), d2 = dot(ac, ap);
        if (d1 <= T(0) && d2 <= T(0)) return void(wa = T(1));
        const Vec3<T> bp = -b;
        const T d3 = dot(ab, bp), d4 = dot(ac, bp);
        if (d3 >= T(0) && d4 <= d3) return void(wb = T(1));
        const T vc = d1 * d4 - d3 * d2;
        if (vc <= T(0) && d1 >= T(0) && d3 <= T(0)) return segment(a, b, wa, wb);
        const Vec3<T> cp = -c;
        const T d5 = dot(ab, cp), d6 = dot(ac, cp);
        if (d6 >= T(0) && d5 <= d6) return void(wc = T(1));
        const T vb = d5 * d2 - d1 * d6;
        if (vb <= T(0) && d2 >= T(0) && d6 <= T(0)) return segment(a, c, wa, wc);
        const T va = d3 * d6 - d5 * d4;
        if (va <= T(0) && (d4 - d3) >= T(0) && (d5 - d6) >= T(0)) return segment(b, c, wb, wc);
        const T sum = va + vb + vc;
        if (!(sum > T(0))) return segment(a, b, wa, wb);  // degenerate (collinear): its longest edge will do
        wa = va / sum, wb = vb / sum, wc = vc / sum;
    }
    /// Whether the origin and d lie on opposite sides of the plane through a, b, c.
    static bool origin_outside(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, const Vec3<T>& d) {
        const Vec3<T> n = cross(b - a, c - a);
        const T sign_origin = dot(-a, n), sign_d = dot(d - a, n);
        return sign_origin * sign_d < T(0);
    }
    static void tetrahedron(const std::array<Vec3<T>, 4>& q, std::array<T, 4>& w) {
        constexpr std::size_t faces[4][4] = {
            {0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};  // three corners, the opposite one
        T best = ScalarTraits<T>::infinity;
        bool outside_any = false;
        for (const auto& f : faces) {
            const Vec3<T>&a = q[f[0]], &b = q[f[1]], &c = q[f[2]];
            if (!origin_outside(a, b, c, q[f[3]])) continue;
            outside_any = true;
            T wa, wb, wc;
            triangle(a, b, c, wa, wb, wc);
            const Vec3<T> p = a * wa + b * wb + c * wc;
            if (dot(p, p) < best) {
                best = dot(p, p);
                w = {};
                w[f[0]] = wa, w[f[1]] = wb, w[f[2]] = wc;
            }
        }
        if (!outside_any) inside(q, w);
    }
    /// Barycentric weights of the origin inside the tetrahedron (signed volumes); a flat one that
    /// the origin is "inside" of falls back to its best face.
    static void inside(const std::array<Vec3<T>, 4>& q, std::array<T, 4>& w) {
        const Vec3<T> e1 = q[1] - q[0], e2 = q[2] - q[0], e3 = q[3] - q[0];
        const T volume = dot(e1, cross(e2, e3));
        if (volume == T(0)) {
            T wa, wb, wc;
            triangle(q[0], q[1], q[2], wa, wb, wc);
            w = {wa, wb, wc, T(0)};
            return;
        }
        w[1] = dot(-q[0], cross(e2, e3)) / volume;
        w[2] = dot(e1, cross(-q[0], e3)) / volume;
        w[3] = dot(e1, cross(e2, -q[0])) / volume;
        w[0] = T(1) - w[1] - w[2] - w[3];
        T sum = T(0);
        for (T& x : w) sum += (x = std::max(x, T(0)));  // (round-off just outside a face)
        for (T& x : w) x /= sum;
    }

    std::array<CastVertex<T>, 4> vertices_{};
    std::array<T, 4> weights_{};
    int n_ = 0;
};

}  // namespace detail

namespace detail {

/// The GJK ray cast itself, on C = B ⊖ A given by `support_c(v)` (a CastVertex relative to
/// pose_a.position) and a point `inside` it; `touch(pose)` is collide() of A at `pose` with B,
/// for the start's overlap and the final normal. `size` scales the tolerance.
template <class T, class SupportC, class Touch>
std::optional<ShapeCastHit<T>> gjk_cast(const SupportC& support_c, const Vec3<T>& inside, T size, const Transform<T>& pose_a,
                                        const Vec3<T>& translation, const Touch& touch) {
    const Vec3<T> origin = pose_a.position;
    const T tolerance = ScalarTraits<T>::geometric_tolerance * size;
    const int max_iterations = 64;
    T lambda = T(0);
    Vec3<T> x = Vec3<T>::zero(), normal = Vec3<T>::zero();
    Vec3<T> v = x - inside;  // from a point inside C to x
    CastSimplex<T> simplex;
    for (int i = 0; i < max_iterations && dot(v, v) > tolerance * tolerance; ++i) {
        const CastVertex<T> p = support_c(v);
        const Vec3<T> w = x - p.c;
        const T vw = dot(v, w);
        // C's support plane along v separates x from C, or (vw = 0) holds x: shapes exactly
        // touching have no gap, and taking only vw > 0 left them "never separated", reported as
        // overlapping whichever way A moved. Touching is not intersecting: moving away or along
        // the plane misses, moving into it is a hit at this λ with this plane's normal.
        if (vw >= T(0)) {
            const T vr = dot(v, translation);
            if (vr >= T(0)) return std::nullopt;  // moving away from (or along) the plane: never enters C
            lambda -= vw / vr;
            if (lambda > T(1)) return std::nullopt;  // beyond the translation
            x = translation * lambda;
            normal = v;
        }
        if (simplex.size() == 4) break;  // (a tetrahedron that held x ended the loop with v = 0)
        if (simplex.holds(p.c)) {
            // Exactly, a support point already in the simplex separates (v·w = |v|²), so x moved
            // and only v is new; one that does not is round-off: x is on C as far as T can tell.
            if (!(vw > T(0))) break;
        } else {
            simplex.add(p);
        }
        v = simplex.closest(x);
    }
    if (normal == Vec3<T>::zero()) {  // never separated: they overlap where A starts
        const Penetration<T> p = touch(pose_a);
        ShapeCastHit<T> hit;
        hit.initially_overlapping = true;
        // From A to B as documented: collide()'s, or (if it finds no depth) from A's interior
        // point towards B's, then the way A moves.
        hit.normal = p.hit ? p.normal : normalized_or(inside, normalized_or(translation, Vec3<T>::unit_y()));
        hit.point = p.hit ? p.point_b : pose_a.position;
        return hit;
    }
    ShapeCastHit<T> hit;
    hit.fraction = lambda;
    hit.normal = -normalized(normal);
    Vec3<T> on_b = Vec3<T>::zero();
    for (int i = 0; i < simplex.size(); ++i) on_b += simplex.vertex(i).b * simplex.weight(i);
    hit.point = simplex.size() > 0 ? on_b + origin : x + origin;
    // The last separating plane's normal is only as good as the simplex was when it was found
    // (1 % off at a rounded edge in float). A few tolerances further on, A just overlaps B, and
    // collide()'s refined normal and point at that depth are the contact's.
    const T reach = length(translation);
    const T nudge = reach > T(0) ? std::min(T(1) - lambda, T(4) * tolerance / reach) : T(0);
    const Penetration<T> p = touch(Transform<T>{pose_a.position + translation * (lambda + nudge), pose_a.orientation});
    if (p.hit && p.depth <= T(16) * tolerance) {
        hit.normal = p.normal;
        hit.point = p.point_b;
    }
    return hit;
}

/// The part of a sweep in which two spheres meet (sphere_sweep_span): [first, last] in fractions
/// of the translation, and where the moving one's centre enters and leaves (world).
template <class T>
struct SweepSpan {
    T first{}, last{};
    Vec3<T> entry{}, exit{};
};

/// The part of a sweep of a sphere from `start` along `translation` in which it meets a sphere
/// resting at `centre` (radii adding up to `reach`); nothing when they never do. A translation
/// too long to measure in T (or none) gives the whole sweep. Where the square of its length
/// overflows (from 1.8e19 m in float, 1.3e154 in double) or underflows, the length is taken of
/// the translation divided by its largest component: a whole sweep's tolerance took a shape
/// 2.7 m clear of a floor for one that started inside it. The entry and exit points are taken
/// from the resting centre, not as start + first × translation: from FLT_MAX that sum is rounded
/// 10³¹ m off, and a ball was cast from the far side of a box and hit its other face.
template <class T>
std::optional<SweepSpan<T>> sphere_sweep_span(const Vec3<T>& start, const Vec3<T>& centre, T reach, const Vec3<T>& translation) {
    const SweepSpan<T> whole{T(0), T(1), start, start + translation};
    const T largest = std::max({std::abs(translation.x), std::abs(translation.y), std::abs(translation.z)});
    if (!(largest > T(0)) || !std::isfinite(largest)) return whole;
    T length_t = length(translation);
    Vec3<T> along = length_t > T(0) ? translation / length_t : translation;
    if (!std::isfinite(length_t) || !(length_t > T(0))) {  // its square overflowed or underflowed
        const Vec3<T> scaled = translation / largest;      // components in [-1, 1], length in [1, √3]
        const T length_scaled = length(scaled);
        length_t = largest * length_scaled;
        along = scaled / length_scaled;
        if (!std::isfinite(length_t)) return whole;
    }
    const Vec3<T> offset = centre - start;
    const T ahead = dot(offset, along);
    const Vec3<T> across = offset - along * ahead;  // from the sweep's line to the centre
    const T across_sq = length_squared(across);
    if (across_sq > reach * reach) return std::nullopt;  // passes beside
    const T half_chord = std::sqrt(reach * reach - across_sq);
    SweepSpan<T> span = whole;
    if (ahead - half_chord > T(0)) {
        span.first = std::min((ahead - half_chord) / length_t, T(1));
        span.entry = centre - across - along * half_chord;
    }
    if (ahead + half_chord < length_t) {
        span.last = std::max((ahead + half_chord) / length_t, T(0));
        span.exit = centre - across + along * half_chord;
    }
    if (ahead + half_chord < T(0) || ahead - half_chord > length_t) return std::nullopt;  // starts past it, or stops short
    return span;
}

/// Runs `cast(from, move)` (a shape cast from pose `from` along `move`) over the part of the
/// sweep of A from pose_a along `translation` in which A's bounding sphere (about pose_a's
/// position) meets B's (`reach` the two radii, B's centre at `centre_b`, world), and gives its hit
/// as a fraction of the whole sweep. The cast's tolerance is a fraction of the problem's size,
/// translation included: over the whole of a long sweep (1e6 m in float, 1e10 m in double) it
/// exceeded the gap, and a box 4.5 m above the ground was reported overlapping it.
template <class T, class Cast>
std::optional<ShapeCastHit<T>> cast_where_spheres_meet(const Vec3<T>& centre_b, T reach, const Transform<T>& pose_a,
                                                       const Vec3<T>& translation, const Cast& cast) {
    // The radii are bounds about each shape's centre; the slack covers their round-off.
    const std::optional<SweepSpan<T>> span = sphere_sweep_span(pose_a.position, centre_b, reach * (T(1) + T(1e-3)), translation);
    if (!span) return std::nullopt;
    if (span->first == T(0) && span->last == T(1)) return cast(pose_a, translation);
    std::optional<ShapeCastHit<T>> hit = cast(Transform<T>{span->entry, pose_a.orientation}, span->exit - span->entry);
    if (!hit) return hit;
    if (span->first > T(0)) hit->initially_overlapping = false;  // the spheres only meet there: round-off
    hit->fraction = std::min(span->first + hit->fraction * (span->last - span->first), T(1));
    return hit;
}

}  // namespace detail

/// Sweeps shape A from pose_a along `translation` (metres, world) against B resting at pose_b.
/// Returns the first contact, or nothing when A passes B (or stops short of it). Shapes that
/// overlap at the start give fraction 0 and `initially_overlapping`; shapes that only touch there
/// give nothing when A moves away or along the contact, and fraction 0 without the flag when it
/// moves into B. Poses and the translation must
/// be finite (InvalidArgument). Only the part of the sweep where the bounding spheres meet is
/// cast (detail::cast_where_spheres_meet).
template <class T>
std::optional<ShapeCastHit<T>> shape_cast(const Shape<T>& a, const Transform<T>& pose_a, const Vec3<T>& translation,
                                          const Shape<T>& b, const Transform<T>& pose_b) {
    detail::require_moved_in(a, "shape_cast");
    detail::require_moved_in(b, "shape_cast");
    detail::require_finite_pose(pose_a, "shape_cast", "pose_a");
    detail::require_finite_pose(pose_b, "shape_cast", "pose_b");
    detail::require_finite_xyz(translation, "shape_cast", "translation");
    const auto cast = [&](const Transform<T>& from, const Vec3<T>& move) {
        const Vec3<T> origin = from.position;  // every point below is relative to it
        const auto support_c = [&](const Vec3<T>& v) {
            detail::CastVertex<T> p;
            p.a = rotate(from.orientation, support(a, inverse_rotate(from.orientation, -v)));
            p.b = pose_b.position - origin + rotate(pose_b.orientation, support(b, inverse_rotate(pose_b.orientation, v)));
            p.c = p.b - p.a;
            return p;
        };
        // The tolerance on |v|: a fraction of the problem's size, as MPR's (ScalarTraits).
        const T size = bounding_radius(a) + bounding_radius(b) + length(move) + length(pose_b.position - origin);
        const Vec3<T> centre_a = rotate(from.orientation, interior_point(a));
        const Vec3<T> centre_b = pose_b.position - origin + rotate(pose_b.orientation, interior_point(b));
        return detail::gjk_cast(support_c, centre_b - centre_a, size, from, move,
                                [&](const Transform<T>& at) { return collide(a, at, b, pose_b); });
    };
    // B's centre farther off than T holds: no translation (its components within T) reaches it.
    if (!detail::offset_is_finite(pose_a, pose_b)) return std::nullopt;
    return detail::cast_where_spheres_meet(pose_b.position, bounding_radius(a) + bounding_radius(b), pose_a, translation, cast);
}

/// A compound A (posed by its centre-of-mass frame, as a body) swept against B: the first touch of
/// any of its parts.
template <class T>
std::optional<ShapeCastHit<T>> shape_cast(const Compound<T>& a, const Transform<T>& pose_a, const Vec3<T>& translation,
                                          const Shape<T>& b, const Transform<T>& pose_b) {
    detail::require_finite_pose(pose_a, "shape_cast", "pose_a");
    std::optional<ShapeCastHit<T>> best;
    for (const CompoundChild<T>& child : a.children()) {
        const std::optional<ShapeCastHit<T>> hit = shape_cast(child.shape, pose_a * child.local, translation, b, pose_b);
        if (hit && (!best || hit->fraction < best->fraction)) best = hit;
    }
    return best;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The single contact of a pair once its normal n (A → B, unit) is final: a point on each body.
// Contract (README, "Narrow phase"; tests/collide/contact_points_test.cpp):
//   point_a lies on A's support plane along n and on or inside A within the depth,
//   point_b lies on B's support plane along −n and on or inside B within the depth,
//   point_a − point_b = depth · n (the two support planes are depth apart).
// Construction, in A's frame: the support features of A along n and of B along −n (the vertices
// of each shape's supporting face within a small tolerance of its support plane: a polygon, a
// segment or a point) are projected along n. Where the projections overlap, a point of the
// overlap (the centroid of one feature clipped by the other's sides, or where two segments cross)
// is lifted onto both support planes: both points are then on their bodies' surfaces, exactly for
// face, edge and vertex contacts. At the exact direction of least penetration the projections
// always overlap (the closest point of A ⊖ B's boundary to the origin is a − b for an a in A's
// feature and a b in B's), so only a normal that is not exactly the minimising one can miss:
// then the middle of the two features' closest points is used while each point stays within the
// depth of its feature, else a point known to be inside both bodies (from MPR's answer: the
// caller's, or MPR run here for the pairs solved without it, box–box).
#pragma once

#include "../shape/cone.hpp"
#include "../shape/cylinder.hpp"
#include "../shape/sphere.hpp"
#include "face_clip.hpp"
#include "minkowski.hpp"
#include "mpr.hpp"

namespace xeno {

namespace detail {

/// Closest points of segments p1–q1 and p2–q2 (Ericson 5.1.9), clamped to both segments.
template <class T>
void closest_points_of_segments(const Vec3<T>& p1, const Vec3<T>& q1, const Vec3<T>& p2, const Vec3<T>& q2, Vec3<T>& c1,
                                Vec3<T>& c2) {
    const Vec3<T> d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const T a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
    const T tiny = ScalarTraits<T>::epsilon * ScalarTraits<T>::epsilon;
    T s = T(0), u = T(0);
    if (a <= tiny && e <= tiny) {
        s = u = T(0);
    } else if (a <= tiny) {
        u = clamp(f / e, T(0), T(1));
    } else {
        const T c = dot(d1, r);
        if (e <= tiny) {
            s = clamp(-c / a, T(0), T(1));
        } else {
            const T b = dot(d1, d2), denom = a * e - b * b;
            s = denom > tiny * a * e ? clamp((b * f - c * e) / denom, T(0), T(1)) : T(0);
            u = (b * s + f) / e;
            if (u < T(0)) {
                u = T(0);
                s = clamp(-c / a, T(0), T(1));
            } else if (u > T(1)) {
                u = T(1);
                s = clamp((b - c) / a, T(0), T(1));
            }
        }
    }
    c1 = p1 + d1 * s;
    c2 = p2 + d2 * u;
}

/// The support feature of `shape` along d (shape frame, any length): the vertices of its supporting
/// face within `tau` (metres) of the support plane, in the face's order; at least the support point.
template <class S>
SupportFace<typename S::scalar_type> support_feature(const S& shape, const Vec3<typename S::scalar_type>& d,
                                                     typename S::scalar_type tau) {
    using T = typename S::scalar_type;
    const Vec3<T> u = normalized_or(d, Vec3<T>::unit_y());
    const Vec3<T> top = shape.support(u);
    SupportFace<T> out;
    out.normal = u;
    bool extended = true;  // may the feature be more than a point? (skips building curved faces)
    if constexpr (std::is_same_v<S, Sphere<T>>) {
        extended = false;
    } else if constexpr (std::is_same_v<S, Cylinder<T>>) {
        const T sigma = std::sqrt(u.x * u.x + u.z * u.z);
        extended = sigma * shape.radius() <= T(4) * tau || std::abs(u.y) * shape.half_height() <= T(4) * tau;
    } else if constexpr (std::is_same_v<S, Cone<T>>) {
        const T sigma = std::sqrt(u.x * u.x + u.z * u.z);
        const T slant = std::sqrt(shape.radius() * shape.radius() + shape.height() * shape.height());
        // The base (u ≈ −y) or the side line (u ≈ the side's normal in u's azimuth plane).
        const T side_gap = T(1) - (shape.height() * sigma + shape.radius() * u.y) / slant;
        extended = (u.y < T(0) && sigma * shape.radius() <= T(4) * tau) || side_gap * slant <= T(4) * tau;
    }
    if (extended) {
        const SupportFace<T> face = shape.support_face(u);
        const T level = dot(top, u);
        for (int i = 0; i < face.count; ++i)
            if (level - dot(face[i], u) <= tau) out.push(face[i]);
    }
    if (out.count == 0) out.push(top);
    return out;
}

/// The same for a shape of any kind: its own kind's rule.
template <class T>
SupportFace<T> support_feature(const ShapeRef<T>& shape, const Vec3<T>& d, T tau) {
    return shape.visit([&](const auto& concrete) { return support_feature(concrete, d, tau); });
}

/// Moves the points of `poly` (any count) to the part inside the prism over the convex polygon
/// `ref` (3+ vertices) along n.
template <class T>
ClipPolygon<T> clip_to_prism(const ClipPolygon<T>& poly, const SupportFace<T>& ref, const Vec3<T>& n) {
    Vec3<T> area{};
    for (int i = 0; i < ref.count; ++i) area += cross(ref[i], ref[(i + 1) % ref.count]);
    const T orient = dot(area, n) >= T(0) ? T(1) : T(-1);
    ClipPolygon<T> polygons[2] = {poly, {}};  // clipped back and forth (clip_by_plane)
    int current = 0;
    for (int i = 0; i < ref.count && polygons[current].count > 0; ++i) {
        const Vec3<T>& r0 = ref[i];
        const Vec3<T>& r1 = ref[(i + 1) % ref.count];
        clip_by_plane(polygons[current], r0, cross(r1 - r0, n) * orient, polygons[1 - current]);
        current = 1 - current;
    }
    return polygons[current];
}

template <class T>
Vec3<T> centroid(const ClipPolygon<T>& p) {
    Vec3<T> c{};
    for (int i = 0; i < p.count; ++i) c += p.p[static_cast<std::size_t>(i)];
    return c / static_cast<T>(p.count);
}

template <class T>
Vec3<T> centroid(const SupportFace<T>& f) {
    Vec3<T> c{};
    for (int i = 0; i < f.count; ++i) c += f[i];
    return c / static_cast<T>(f.count);
}

/// A point whose projection along n lies in both features' projections, if found; `gap` gets the
/// distance between the projections when a closest pair was computed instead (else stays −1).
template <class T>
bool common_point(const SupportFace<T>& fa, const SupportFace<T>& fb, const Vec3<T>& n, Vec3<T>& x, T& gap) {
    auto to_poly = [](const SupportFace<T>& f) {
        ClipPolygon<T> p;
        for (int i = 0; i < f.count; ++i) p.push(f[i]);
        return p;
    };
    if (fa.count >= 3 || fb.count >= 3) {
        const bool a_is_ref = fa.count >= 3 && (fb.count < 3 || fa.count >= fb.count);
        const ClipPolygon<T> clipped = clip_to_prism(to_poly(a_is_ref ? fb : fa), a_is_ref ? fa : fb, n);
        if (clipped.count == 0) return false;
        x = centroid(clipped);
        gap = T(0);
        return true;
    }
    // Points and segments: the closest points of the two, measured across n.
    const Vec3<T> a0 = fa[0], a1 = fa[fa.count - 1], b0 = fb[0], b1 = fb[fb.count - 1];
    auto flat = [&](const Vec3<T>& v) { return v - n * dot(v, n); };
    const Vec3<T> da = flat(a1 - a0), db = flat(b1 - b0);
    const T la = length_squared(da), lb = length_squared(db);
    // A segment whose length squared underflows (a capsule of subnormal half height) is a point
    // here: as "parallel" it divided by la = 0 and gave NaN points (and a NaN manifold in the world).
    if (fa.count == 2 && fb.count == 2 && la > T(0) && lb > T(0) && length_squared(cross(da, db)) <= T(1e-6) * la * lb) {
        // Parallel segments: the middle of the part of B's within A's extent along the shared line.
        const T t0 = dot(flat(b0 - a0), da) / la, t1 = dot(flat(b1 - a0), da) / la;
        const T lo = std::max(std::min(t0, t1), T(0)), hi = std::min(std::max(t0, t1), T(1));
        if (lo <= hi) {
            const Vec3<T> on_a = a0 + (a1 - a0) * (T(0.5) * (lo + hi));
            const Vec3<T> off = flat(b0 - on_a) - da * (dot(flat(b0 - on_a), da) / la);  // B's line across
            x = on_a + off * T(0.5);
            gap = length(off);
            return true;
        }
    }
    Vec3<T> ca, cb;
    closest_points_of_segments(flat(a0), flat(a1), flat(b0), flat(b1), ca, cb);
    x = (ca + cb) * T(0.5);
    gap = length(ca - cb);
    return true;
}

/// A point inside both shapes (A's frame) from MPR's answer: on the segment from the interior
/// point v0 (the difference of the shapes' centres, inside D) to the portal's exit, the point of
/// D nearest the origin there, split back into its A and B parts and averaged. Falls inside
/// both when the shapes overlap; used only when the support features do not overlap across n.
template <class A, class B>
Vec3<typename A::scalar_type> point_inside_both(const MinkowskiDifference<A, B>& md,
                                                const Penetration<typename A::scalar_type>& p) {
    using T = typename A::scalar_type;
    const SupportPoint<T> v0 = md.interior();
    const Vec3<T> e = (p.point_a - p.point_b) - v0.v;
    const T e_sq = length_squared(e);
    const T t = e_sq > T(0) ? clamp(-dot(v0.v, e) / e_sq, T(0), T(1)) : T(0);
    const Vec3<T> in_a = v0.a + (p.point_a - v0.a) * t;
    const Vec3<T> in_b = v0.b() + (p.point_b - v0.b()) * t;
    return (in_a + in_b) * T(0.5);
}

/// Contact points (A's frame) for the final unit normal n (A → B) and overlap h along it, by the
/// contract at the top of this file. `inside`, if given, is a point of A ∩ B (A's frame).
template <class A, class B>
void place_contact_points(const MinkowskiDifference<A, B>& md, const Vec3<typename A::scalar_type>& n, typename A::scalar_type h,
                          const Vec3<typename A::scalar_type>* inside, Vec3<typename A::scalar_type>& point_a,
                          Vec3<typename A::scalar_type>& point_b) {
    using T = typename A::scalar_type;
    const T tau = std::max(ScalarTraits<T>::geometric_tolerance, T(1e-7)) * md.scale();
    const SupportFace<T> fa = support_feature(md.shape_a(), n, tau);
    SupportFace<T> fb = support_feature(md.shape_b(), md.direction_to_b(-n), tau);
    for (int i = 0; i < fb.count; ++i) fb.vertex[static_cast<std::size_t>(i)] = md.to_a(fb[i]);
    const T level_a = dot(md.shape_a().support(n), n);
    const T level_b = dot(md.to_a(md.shape_b().support(md.direction_to_b(-n))), n);
    Vec3<T> x;
    T gap = T(-1);
    const bool found = common_point(fa, fb, n, x, gap);
    // The closest pair of points of two features that do not overlap across n is used only while
    // each lifted point stays within the depth of its body (half the gap each); else the point
    // inside both bodies, lifted onto the two planes, is within the depth by construction.
    if (!found || gap > std::max(h, T(0)) + tau) {
        if (inside) {
            x = *inside;
        } else if (const Penetration<T> p = mpr(md, false); p.hit) {
            x = point_inside_both(md, p);  // rare (box–box with a face axis taken within slack)
        } else if (!found) {
            x = (centroid(fa) + centroid(fb)) * T(0.5);
        }
    }
    point_a = x + n * (level_a - dot(x, n));
    point_b = x + n * (level_b - dot(x, n));
}

}  // namespace detail

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A convex shape against a mesh or heightfield (docs/meshes.md):
//   1. the triangles under the convex's box (grown by the margin), found in the mesh's frame;
//   2. each collided like any convex pair (MPR, least depth, normal refinement, face clipping),
//      the triangle being a flat convex shape whose MPR start point is its point nearest the
//      convex's centre (triangle.hpp); a box by separating axes instead (box_triangle.hpp);
//   3. internal edges: a normal that comes from an edge or a corner the neighbours cover (a
//      coplanar or concave neighbour: triangle.hpp, "active_edges"), or that turns past the
//      neighbour's normal at a convex edge, is replaced by the triangle's own normal and the
//      manifold rebuilt along it, so a box sliding over a flat mesh meets no
//      ghost edge (the idea of Jolt's active edges and Bullet's internal-edge utility: only a
//      convex edge may push sideways). A contact that would push the convex out through the
//      back of a triangle is dropped (triangles are one-sided, like Jolt's default);
//   4. the manifolds whose normals agree within about 2.5° (coplanar neighbours, gentle bends)
//      are merged and reduced to four points (the deepest, then the widest spread, as
//      face_clip.hpp does), so a box on a flat mesh has one manifold of four points however many
//      triangles it covers; a box in a crease keeps one manifold per face it leans on.
#pragma once

#include "../shape/mesh_shape.hpp"
#include "../shape/triangle.hpp"
#include "box_triangle.hpp"
#include "collide.hpp"
#include "shape_cast.hpp"

#include <vector>

namespace xeno {

/// One manifold of a convex body against a mesh: the normal points from the mesh to the convex;
/// `triangle` is the triangle of the deepest point (the mesh's own numbering).
template <class T>
struct MeshContact {
    ContactManifold<T> manifold;
    std::uint32_t triangle = 0;
};

namespace detail {

/// The unit direction in the triangle's plane, square to edge e, pointing out of the triangle
/// (counter-clockwise winding).
template <class T>
Vec3<T> outward_of_edge(const MeshTriangle<T>& t, int e) {
    return normalized(cross(t.v[(e + 1) % 3] - t.v[e], t.normal));
}

/// Whether the normal n (mesh frame, from the triangle) is a ghost: it comes from an inactive
/// edge or a corner both of whose edges in this triangle are inactive, or it turns from the face
/// normal by more than the fold of the active edge (or corner) it comes from: past the
/// neighbour's own normal, where only the neighbour's face can push (a box corner on a slightly
/// convex edge of a smooth hill was otherwise held on a 26° slope by a normal 38° uphill).
template <class T>
bool is_ghost_normal(const MeshTriangle<T>& t, const Vec3<T>& n, T tolerance) {
    T d[3];
    for (int i = 0; i < 3; ++i) d[i] = dot(t.v[i], n);
    const T top = std::max({d[0], d[1], d[2]});
    int on = 0, mask = 0;
    for (int i = 0; i < 3; ++i)
        if (d[i] >= top - tolerance) ++on, mask |= 1 << i;
    if (on == 3) return false;  // the face itself
    const auto active = [&](int edge) { return (t.active_edges >> edge & 1) != 0; };
    const T turn = dot(n, t.normal);
    const T slack = T(1e-3);  // in cosine: about 2.6° near 0°, so round-off never flips it
    if (on == 2) {
        const int edge = mask == 3 ? 0 : mask == 6 ? 1 : 2;  // {0,1} → 0, {1,2} → 1, {2,0} → 2
        return !active(edge) || turn < t.fold_cos[edge] - slack;
    }
    const int v = mask == 1 ? 0 : mask == 2 ? 1 : 2;  // edges v and v − 1 meet at corner v
    const int in = (v + 2) % 3;
    if (!active(v) && !active(in)) return true;
    // A corner normal that leans out across the corner's inactive edge leans over the neighbour
    // there (coplanar or folding up), which answers for that side. At a border corner the active
    // edge's fold (−1) allowed any normal: a ball rolling at 10 m/s past a platform's corner, 2 cm
    // beyond the triangle, was pushed back along (centre − corner) and thrown up at 3-5 m/s.
    const int inactive = active(v) ? in : v;
    if (!active(inactive) && dot(n, outward_of_edge(t, inactive)) > slack) return true;
    T limit = T(1);
    if (active(v)) limit = std::min(limit, t.fold_cos[v]);
    if (active(in)) limit = std::min(limit, t.fold_cos[in]);
    return turn < limit - slack;
}

/// The tolerance of is_ghost_normal's corners on the support plane: 1e-3 of the triangle's size,
/// or of its least height if smaller. On a sliver (4 m long, 1.5 cm tall) a normal tilted 5°
/// across its long edge lowers the far corner by 1.3 mm, within 1e-3 of 2 m: all three corners
/// were "on" the plane, the edge normal passed for the face's own, and a ball rolling across it
/// hopped 12 mm.
template <class T>
T ghost_tolerance(const MeshTriangle<T>& t, T radius) {
    T longest = T(0);
    for (int e = 0; e < 3; ++e) longest = std::max(longest, length(t.v[(e + 1) % 3] - t.v[e]));
    const T height = longest > T(0) ? length(cross(t.v[1] - t.v[0], t.v[2] - t.v[0])) / longest : T(0);
    return T(1e-3) * std::min(radius, height);
}

/// Removes the points of a face contact (mesh frame) whose convex point lies beyond one of the
/// triangle's edges in `edges` (bit i: edge i): a sphere's or a corner's single contact, found by
/// the face through the closest points of the two features, can sit a centimetre past an
/// inactive edge, where the neighbour gives the true point; kept, it would be a second support
/// off to the side (measured: a rolling sphere lost 1 % of its speed crossing a flat mesh's
/// edges). After a ghost normal was replaced, every edge counts: the body's lowest point along
/// the face normal may lie over a neighbour that folds away, and its depth below this triangle's
/// extended plane is no depth at all (bodies tumbling down a hill sank 7 cm with it). Over a
/// coplanar neighbour that depth is exact, and triangle_manifold keeps such points when nothing
/// else is left: a cone's apex that pokes through one triangle into the space under its flat
/// neighbour, which the cone never meets, was dropped by both, and cones fell through flat
/// terrain (707 of 5,000 placements 1-10 cm deep had no contact).
template <class T>
void drop_points_beyond_edges(const MeshTriangle<T>& t, int edges, ContactManifold<T>& m, T tolerance) {
    int kept = 0;
    for (int i = 0; i < m.count; ++i) {
        const Vec3<T>& p = m.points[static_cast<std::size_t>(i)].point_b;
        bool beyond = false;
        for (int e = 0; e < 3 && !beyond; ++e) {
            if ((edges >> e & 1) == 0) continue;
            beyond = dot(p - t.v[e], outward_of_edge(t, e)) > tolerance;
        }
        if (!beyond) m.points[static_cast<std::size_t>(kept++)] = m.points[static_cast<std::size_t>(i)];
    }
    m.count = kept;
}

/// Removes the points of a face contact (mesh frame) whose point on the triangle lies off its
/// plane: not a point of the triangle at all. When clipping leaves nothing, build_manifold falls
/// back to MPR's witness, inflated by the margin (7 cm for a fast body): on a cylinder rolling
/// across a mesh it lay 4 cm ahead of the contact line and 2.7 mm above the triangle, on the
/// cylinder's curve, and pushed it up as if 0.05 mm deep (hops of 15-29 mm, 4-6 % of its roll
/// lost). The triangle's own points are on its plane; the neighbour gives the real contact.
template <class T>
void drop_points_off_the_face(const MeshTriangle<T>& t, ContactManifold<T>& m, T tolerance) {
    int kept = 0;
    for (int i = 0; i < m.count; ++i)
        if (std::abs(dot(m.points[static_cast<std::size_t>(i)].point_a - t.v[0], t.normal)) <= tolerance)
            m.points[static_cast<std::size_t>(kept++)] = m.points[static_cast<std::size_t>(i)];
    m.count = kept;
}

/// Moves the points of a capsule's or a cylinder's manifold (mesh frame) onto the plane through
/// its axis and the normal, keeping their depths and their places along the axis, when it lies on
/// its side (the axis within about 6° of square to the normal): there it touches along its side
/// line, and every point where it truly touches is its lowest point along the normal, in that
/// plane (as detail::rolling_point puts the solver's anchors). A triangle just beside the contact
/// line, which the side line misses, fell back to MPR's witness: on 5 cm cells a point 0.7-2.4 cm
/// ahead of the line at the true point's depth. Its push, off the line, braked the roll: rolling
/// at 0.5 m/s, in 1 s a capsule lost 8-11 % of its speed on 5 cm cells and 14 % on 2.5 cm cells, a
/// cylinder 3 % and 5-6 % (none on a box floor). Dropped instead of moved, such points took the
/// only support of capsules tumbling down a hill, whose witnesses on folds lie up to 1.5 cm off
/// that plane, and they sank 11 cm. A cylinder on a cap or a rim keeps its cap polygon.
template <class T>
void move_points_under_the_axis(ContactManifold<T>& m, const Vec3<T>& centre, const Vec3<T>& axis) {
    if (!(std::abs(dot(m.normal, axis)) < T(0.1))) return;
    const Vec3<T> across = normalized(cross(m.normal, axis));
    for (int i = 0; i < m.count; ++i) {
        ManifoldPoint<T>& p = m.points[static_cast<std::size_t>(i)];
        const Vec3<T> off = across * dot(p.point_b - centre, across);
        p.point_a -= off;
        p.point_b -= off;
    }
}

/// True when the placed convex is farther than `margin` from the triangle along its normal (in
/// front or behind) or beyond one of its edges in its plane: a separating axis, found with at
/// most five support calls, so the triangles under a body's box that it does not reach cost no
/// MPR. Exact: a pair it rejects is more than `margin` apart, which MPR would have found too.
/// `r` is the pose's rotation as a matrix, made once per body, not per triangle.
template <class S>
bool separated_from_triangle(const MeshTriangle<typename S::scalar_type>& t, const S& convex,
                             const Transform<typename S::scalar_type>& pose, const Mat3<typename S::scalar_type>& r,
                             typename S::scalar_type margin) {
    using T = typename S::scalar_type;
    const auto extreme = [&](const Vec3<T>& d) { return r * convex.support(transposed_transform(r, d)) + pose.position; };
    if (dot(extreme(-t.normal) - t.v[0], t.normal) > margin) return true;  // wholly in front
    if (dot(extreme(t.normal) - t.v[0], t.normal) < -margin) return true;  // wholly behind
    for (int e = 0; e < 3; ++e) {
        const Vec3<T> out = normalized(cross(t.v[(e + 1) % 3] - t.v[e], t.normal));  // outward, in the plane
        if (dot(extreme(-out) - t.v[e], out) > margin) return true;
    }
    return false;
}

/// The manifold of one triangle and the convex (a Box, or any kind as a ShapeRef), mesh frame
/// (A = the triangle), after the edge correction; count 0 when they are apart or the contact faces
/// the triangle's back.
template <class S>
ContactManifold<typename S::scalar_type> triangle_manifold(const MeshTriangle<typename S::scalar_type>& t, const S& convex,
                                                           const Transform<typename S::scalar_type>& pose,
                                                           const Vec3<typename S::scalar_type>& centre,
                                                           typename S::scalar_type margin, typename S::scalar_type exact_above) {
    using T = typename S::scalar_type;
    const Triangle<T> tri(t, closest_point_on_triangle(centre, t.v[0], t.v[1], t.v[2]));
    const MinkowskiDifference<Triangle<T>, S> md(tri, Transform<T>{}, convex, pose, margin);
    Vec3<T> n, pa, pb;
    T h;
    bool round = IsRound<S>::value;
    // Round shapes touch in single points that must sit exactly under their centres (a rolling
    // sphere is otherwise braked): their points on the surfaces (collide()'s contract). The
    // others' manifolds come from face clipping; MPR's cheaper points are only its fallback.
    // A box, the most common body, takes the closed-form separating-axis test (box_triangle.hpp).
    if constexpr (std::is_same_v<S, Box<T>>) {
        if (!box_triangle_axis(md, n, h, pa, pb)) return {};
    } else {
        if constexpr (is_shape_ref<S>)
            round = convex.visit([](const auto& shape) { return IsRound<std::decay_t<decltype(shape)>>::value; });
        const bool hit =
            round ? refined_contact<true>(md, n, h, pa, pb, exact_above) : refined_contact<false>(md, n, h, pa, pb, exact_above);
        if (!hit) return {};
    }
    // A normal out through the back: a body behind the triangle stays there (no contact), but a
    // body in front whose tip pokes through (a cone's apex, a hull's corner) gets the face normal,
    // as for a ghost. The pair's least depth may slip the tip out past the triangle's edge, partly
    // downwards; dropped, that triangle left nothing (its neighbour's edge normal is a ghost whose
    // points lie beyond its edges), and cones fell through terrain (6 % of tilted apexes).
    const bool back = dot(n, t.normal) < T(0);
    if (back && !(dot(centre - t.v[0], t.normal) > T(0))) return {};
    const bool ghost =
        back || (dot(n, t.normal) < T(1) - T(1e-6) && is_ghost_normal(t, n, ghost_tolerance(t, tri.bounding_radius())));
    if (ghost) {
        n = t.normal;
        pb = md.to_a(convex.support(md.direction_to_b(-n)));  // the convex's lowest point along the face
        h = dot(t.v[0] - pb, n);
        if (!(h > -margin)) return {};
        pa = pb + n * h;
    }
    ContactManifold<T> m = build_manifold(md, n, pa, pb, h, margin);
    const T tolerance = T(1e-4) * tri.bounding_radius();
    if (ghost) {
        const ContactManifold<T> built = m;
        drop_points_beyond_edges(t, 7, m, tolerance);
        // All beyond: keep those over a coplanar neighbour, for a tip poked through. Not for a
        // ball or capsule, whose lowest point over a neighbour the neighbour itself finds, and
        // which lies past the mesh's border when the neighbour ends there: a ball sliding off a
        // platform's edge at 10 m/s was held level by the last row's triangles for 2-3 steps.
        if (m.count == 0 && !round) {
            int coplanar = 0;
            for (int e = 0; e < 3; ++e) coplanar |= t.fold_cos[e] >= T(1) - T(1e-6) ? 1 << e : 0;
            m = built;
            drop_points_beyond_edges(t, 7 & ~coplanar, m, tolerance);
        }
    } else if (dot(n, t.normal) >= T(1) - T(1e-6)) {
        drop_points_beyond_edges(t, ~t.active_edges & 7, m, tolerance);  // inactive ones
        drop_points_off_the_face(t, m, tolerance);
    }
    return m;
}

/// A capsule over a triangle's face (mesh frame): the ends of its core that lie over the face
/// become points, each at its own depth (the farther one speculative, within `margin`), as
/// round_manifold gives a capsule on a box's face. MPR gives a round shape one point per
/// triangle, and a triangle beside the one under the tip gives none (its edge normal is a ghost,
/// and a round shape keeps no point beyond its edges): a capsule that landed on one end had
/// nothing under the other, which swung through the surface, and the one-sided triangles let the
/// rest follow. 11 of 100 thin capsules dropped from 5 m went through a flat mesh or heightfield,
/// none through a box. A triangle without a manifold of its own gives the ends it lies under
/// when the capsule's centre is in front of it; one with a manifold along another normal (an edge
/// or a fold) gives none.
template <class T>
void add_capsule_ends(const MeshTriangle<T>& t, const Capsule<T>& capsule, const Transform<T>& pose, const Vec3<T>& centre,
                      T margin, ContactManifold<T>& m) {
    constexpr T same_normal = T(0.999);  // cos 2.6°, as collide_mesh groups normals
    if (m.count > 0 ? !(dot(m.normal, t.normal) >= same_normal) : !(dot(centre - t.v[0], t.normal) > T(0))) return;
    if (m.count == 0) m.normal = t.normal;
    const T tolerance = T(1e-4) * capsule.bounding_radius();
    for (const T side : {T(-1), T(1)}) {
        const Vec3<T> end = pose.apply(Vec3<T>{T(0), side * capsule.half_height(), T(0)});
        const T height = dot(end - t.v[0], t.normal);
        const ManifoldPoint<T> p{end - t.normal * height, end - t.normal * capsule.radius(), capsule.radius() - height};
        bool over = p.depth > -margin;
        for (int e = 0; e < 3 && over; ++e) over = dot(p.point_a - t.v[e], outward_of_edge(t, e)) <= tolerance;
        for (int i = 0; i < m.count && over; ++i)  // MPR's point is the nearer end's, or near it
            over = length_squared(m.points[static_cast<std::size_t>(i)].point_b - p.point_b) > square(tolerance);
        if (over && m.count < ContactManifold<T>::capacity) m.points[static_cast<std::size_t>(m.count++)] = p;
    }
}

/// Candidate points of manifolds sharing a normal, reduced to four whenever the buffer fills.
template <class T>
struct NormalGroup {
    Vec3<T> normal{};
    T deepest = -ScalarTraits<T>::infinity;
    std::uint32_t triangle = 0;
    ClipPoints<T> points;  ///< the first `count` set
    int count = 0;

    void add(const ContactManifold<T>& m, std::uint32_t tri, T size) {
        for (int i = 0; i < m.count; ++i) {
            const ManifoldPoint<T>& p = m.points[static_cast<std::size_t>(i)];
            if (p.depth > deepest) {
                deepest = p.depth;
                normal = m.normal;
                triangle = tri;
            }
            // Neighbours clipped along a shared edge give the same point twice: keep one.
            bool seen = false;
            for (int j = 0; j < count && !seen; ++j)
                seen = length_squared(points[static_cast<std::size_t>(j)].point_b - p.point_b) <= square(T(1e-4) * size);
            if (seen) continue;
            if (count == ClipPolygon<T>::capacity) reduce();
            points.set(static_cast<std::size_t>(count++), p);
        }
    }
    /// One point, the one nearest the line through `centre` along the normal: a ball touches a
    /// surface once, under its centre. Neighbouring triangles gave a turned ball a second point
    /// 1-4 mm off it, whose share of the friction row, off the true point, braked a rolling ball
    /// (one rolling at 0.5 m/s on 2.5 cm cells lost 40 % of its speed in 3 s).
    void keep_point_under(const Vec3<T>& centre) {
        int best = 0;
        T nearest = ScalarTraits<T>::infinity;
        for (int i = 0; i < count; ++i) {
            const Vec3<T> off = points[static_cast<std::size_t>(i)].point_b - centre;
            const T across = length_squared(off - normal * dot(off, normal));
            if (across < nearest) nearest = across, best = i;
        }
        if (best != 0) points.set(0, points[static_cast<std::size_t>(best)]);
        count = std::min(count, 1);
    }
    /// Depths along the group's normal, then the four points that keep the deepest and span most.
    /// On flat ground many points tie for the deepest: the one farthest from the points' centre
    /// is kept first, so the four are the patch's corners rather than the first point found.
    void reduce() {
        Vec3<T> centre{};
        for (int i = 0; i < count; ++i) {
            ManifoldPoint<T>& p = points[static_cast<std::size_t>(i)];
            p.depth = dot(p.point_a - p.point_b, normal);
            centre += p.point_b;
        }
        centre = centre / static_cast<T>(std::max(count, 1));
        T reach = T(0), top = -ScalarTraits<T>::infinity;
        for (int i = 0; i < count; ++i) {
            reach = std::max(reach, length(points[static_cast<std::size_t>(i)].point_b - centre));
            top = std::max(top, points[static_cast<std::size_t>(i)].depth);
        }
        int first = -1;
        T farthest = -T(1);
        for (int i = 0; i < count; ++i) {
            const ManifoldPoint<T>& p = points[static_cast<std::size_t>(i)];
            const T d = length_squared(p.point_b - centre);
            if (p.depth >= top - T(1e-3) * reach && d > farthest) farthest = d, first = i;
        }
        count = reduce_to_four(points, count, normal, first);
    }
};

}  // namespace detail

namespace detail {

/// Sweeps convex shape A (`shape`, its ShapeRef) from pose_a along `translation` against one
/// triangle (in the same frame): where A first touches it, from either side.
template <class T>
std::optional<ShapeCastHit<T>> cast_triangle(const ShapeRef<T>& shape, const Transform<T>& pose_a, const Vec3<T>& translation,
                                             const MeshTriangle<T>& placed) {
    const Vec3<T> centre_a = pose_a.apply(shape.interior_point());
    const Triangle<T> tri(placed, closest_point_on_triangle(centre_a, placed.v[0], placed.v[1], placed.v[2]));
    const auto cast = [&](const Transform<T>& from, const Vec3<T>& move) {
        const Vec3<T> origin = from.position;
        const auto support_c = [&](const Vec3<T>& v) {
            CastVertex<T> p;
            p.a = rotate(from.orientation, shape.support(inverse_rotate(from.orientation, -v)));
            p.b = tri.support(v) - origin;
            p.c = p.b - p.a;
            return p;
        };
        const T size = shape.bounding_radius() + tri.bounding_radius() + length(move) + length(tri.interior_point() - origin);
        const Vec3<T> inside_a = from.apply(shape.interior_point());
        return gjk_cast(support_c, tri.interior_point() - inside_a, size, from, move,
                        [&](const Transform<T>& at) { return collide_pair(shape, at, tri, Transform<T>{}); });
    };
    return cast_where_spheres_meet(tri.interior_point(), shape.bounding_radius() + tri.bounding_radius(), pose_a, translation,
                                   cast);
}

}  // namespace detail

/// How far a convex shape moves against what it collides with during the coming step (world
/// frame, metres), for dropping speculative contacts it cannot reach: a manifold whose every
/// point is farther than `near` is kept only if the shape, swept along `move`, meets the other
/// shape (docs/collision.md, "Speculative contacts out of reach"). Inactive (keep everything)
/// while `move` is zero.
template <class T>
struct SpeculativeSweep {
    Vec3<T> move{};
    T near{};
    T rise{};  ///< m: how far a triangle beside the path may rise above the one that turns the convex
    bool active() const { return move != Vec3<T>::zero(); }
};

/// The manifolds of a convex shape (placed by pose_convex) against mesh m (placed by pose_mesh),
/// appended to `out` in world coordinates, normals from the mesh to the convex: points within
/// `margin` metres, least-depth expansion above `exact_depth_above` (as generate_contacts).
template <class T>
void collide_mesh(const MeshShape<T>& m, const Transform<T>& pose_mesh, const Shape<T>& convex, const Transform<T>& pose_convex,
                  T margin, T exact_depth_above, std::vector<MeshContact<T>>& out, const SpeculativeSweep<T>& sweep = {}) {
    const Transform<T> pose = inverse(pose_mesh) * pose_convex;  // the convex in the mesh's frame
    const Vec3<T> sweep_move = pose_mesh.inverse_apply_direction(sweep.move);
    const detail::ShapeRef<T> swept_shape(convex);
    const Aabb<T> box = world_bounds(convex, pose).expanded(margin);
    const Vec3<T> centre = pose.apply(interior_point(convex));
    constexpr T same_normal = T(0.999);  // cos 2.6°
    const T size = bounding_radius(convex);
    std::vector<detail::NormalGroup<T>> groups;
    // A capsule or a cylinder lying on its side: its points under its axis.
    const bool round_side = std::holds_alternative<Capsule<T>>(convex) || std::holds_alternative<Cylinder<T>>(convex);
    const Vec3<T> axis = pose.apply_direction(Vec3<T>::unit_y());
    const Capsule<T>* capsule = std::get_if<Capsule<T>>(&convex);
    // Triangle k's manifold joins the group of its normal (within same_normal), or starts one.
    const auto group_up = [&](std::uint32_t k, const ContactManifold<T>& c) {
        detail::NormalGroup<T>* group = nullptr;
        for (detail::NormalGroup<T>& g : groups)
            if (dot(g.normal, c.normal) >= same_normal) {
                group = &g;
                break;
            }
        if (!group) {
            groups.emplace_back();
            group = &groups.back();
            group->normal = c.normal;
        }
        group->add(c, k, size);
    };
    const auto add = [&](std::uint32_t k, const ContactManifold<T>& found) {
        if (!round_side) return group_up(k, found);  // copied only to be changed
        ContactManifold<T> c = found;
        detail::move_points_under_the_axis(c, centre, axis);
        group_up(k, c);
    };
    // With a sweep (see SpeculativeSweep): a triangle farther than sweep.near that the convex,
    // swept along its move, never meets is beside the path. It gives no manifold unless it rises
    // more than sweep.rise above a triangle that first turns the convex on the way (one within
    // sweep.near, or the nearest met along the sweep): a ramp turns a fast body into the wall
    // beside it within the step.
    std::vector<std::pair<T, MeshTriangle<T>>> turns;  // distance along the path, triangle
    struct Beside {
        MeshTriangle<T> triangle;
        std::uint32_t index;
        ContactManifold<T> manifold;
    };
    std::vector<Beside> beside;
    const auto classify = [&](std::uint32_t k, const MeshTriangle<T>& t, const ContactManifold<T>& c) {
        if (!sweep.active()) return add(k, c);
        bool near = false;
        for (int i = 0; i < c.count; ++i) near = near || !(c.points[static_cast<std::size_t>(i)].depth < -sweep.near);
        T distance = T(0);
        if (!near) {
            const std::optional<ShapeCastHit<T>> hit = detail::cast_triangle(swept_shape, pose, sweep_move, t);
            if (!hit) return beside.push_back({t, k, c});
            distance = hit->fraction * length(sweep_move);
        }
        turns.push_back({distance, t});
        add(k, c);
    };
    // A box takes its closed-form triangle test; the other kinds share one compiled copy of the
    // triangle pair (shape_ref.hpp).
    const auto collide_convex = [&](const auto& shape) {
        const Mat3<T> r = to_matrix(pose.orientation);
        const auto reaches = [&](const MeshTriangle<T>& t) {
            return !detail::separated_from_triangle(t, shape, pose, r, margin);
        };
        for_each_triangle(
            m, box,
            [&](std::uint32_t k, const MeshTriangle<T>& t) {
                ContactManifold<T> c = detail::triangle_manifold(t, shape, pose, centre, margin, exact_depth_above);
                if (capsule) detail::add_capsule_ends(t, *capsule, pose, centre, margin, c);
                if (c.count > 0) classify(k, t, c);
            },
            reaches);
    };
    if (const Box<T>* cuboid = std::get_if<Box<T>>(&convex)) collide_convex(*cuboid);
    else collide_convex(detail::ShapeRef<T>(convex));
    // Without a triangle of its own that turns the convex, this mesh cannot tell what will (a box
    // ramp beside a wall that is a mesh of its own): it keeps them all, and the world's test of
    // the body's contacts with static bodies (World::drop_out_of_reach) treats them as turning.
    T first = ScalarTraits<T>::infinity;
    for (const auto& turn : turns) first = std::min(first, turn.first);
    for (const Beside& b : beside) {
        bool rises = turns.empty();
        for (const auto& [distance, under] : turns)
            if (distance <= first + sweep.rise)
                for (const Vec3<T>& v : b.triangle.v) rises = rises || dot(v - under.v[0], under.normal) > sweep.rise;
        if (rises) add(b.index, b.manifold);
    }
    const bool ball = std::holds_alternative<Sphere<T>>(convex);
    for (detail::NormalGroup<T>& g : groups) {
        g.reduce();
        if (ball) g.keep_point_under(centre);
        MeshContact<T> c;
        c.triangle = g.triangle;
        c.manifold.normal = pose_mesh.apply_direction(g.normal);
        c.manifold.count = g.count;
        for (int i = 0; i < g.count; ++i) {
            const ManifoldPoint<T>& p = g.points[static_cast<std::size_t>(i)];
            c.manifold.points[static_cast<std::size_t>(i)] = {pose_mesh.apply(p.point_a), pose_mesh.apply(p.point_b), p.depth};
        }
        out.push_back(c);
    }
}

/// True when the convex shape overlaps some triangle of mesh m (touching is not overlapping).
template <class T>
bool intersect_mesh(const MeshShape<T>& m, const Transform<T>& pose_mesh, const Shape<T>& convex,
                    const Transform<T>& pose_convex) {
    detail::require_moved_in(convex, "intersect_mesh");
    const Transform<T> pose = inverse(pose_mesh) * pose_convex;
    const Vec3<T> centre = pose.apply(interior_point(convex));
    const Mat3<T> r = to_matrix(pose.orientation);
    bool hit = false;
    const detail::ShapeRef<T> shape(convex);  // every kind through one compiled copy (shape_ref.hpp)
    for_each_triangle(m, world_bounds(convex, pose), [&](std::uint32_t, const MeshTriangle<T>& t) {
        if (hit || detail::separated_from_triangle(t, shape, pose, r, T(0))) return;
        const Triangle<T> tri(t, detail::closest_point_on_triangle(centre, t.v[0], t.v[1], t.v[2]));
        hit = detail::mpr(MinkowskiDifference<Triangle<T>, detail::ShapeRef<T>>(tri, Transform<T>{}, shape, pose), true).hit;
    });
    return hit;
}

/// Sweeps convex shape A from pose_a along `translation` against mesh m placed by pose_mesh: the
/// first triangle it touches from the front (one met from behind is passed through, as contacts
/// are one-sided). The same GJK ray cast as two convex shapes, per triangle under the swept box;
/// internal edges are not corrected here (a cast grazing a flat mesh can stop at an edge of it).
template <class T>
std::optional<ShapeCastHit<T>> shape_cast(const Shape<T>& a, const Transform<T>& pose_a, const Vec3<T>& translation,
                                          const MeshShape<T>& m, const Transform<T>& pose_mesh) {
    detail::require_moved_in(a, "shape_cast");
    detail::require_finite_pose(pose_a, "shape_cast", "pose_a");
    detail::require_finite_pose(pose_mesh, "shape_cast", "pose_mesh");
    detail::require_finite_xyz(translation, "shape_cast", "translation");
    const Transform<T> local = inverse(pose_mesh) * pose_a;
    const Vec3<T> step = pose_mesh.inverse_apply_direction(translation);
    Aabb<T> swept = world_bounds(a, local);
    swept.merge(world_bounds(a, Transform<T>{local.position + step, local.orientation}));
    std::optional<ShapeCastHit<T>> best;
    const detail::ShapeRef<T> shape(a);  // every kind through one compiled copy (shape_ref.hpp)
    for_each_triangle(m, swept, [&](std::uint32_t, const MeshTriangle<T>& t) {
        MeshTriangle<T> placed = t;  // in the world, so the cast's frame is the convex pair's
        for (Vec3<T>& v : placed.v) v = pose_mesh.apply(v);
        placed.normal = pose_mesh.apply_direction(t.normal);
        const std::optional<ShapeCastHit<T>> hit = detail::cast_triangle(shape, pose_a, translation, placed);
        if (!hit || dot(hit->normal, placed.normal) > T(0)) return;  // missed, or met from behind
        if (!best || hit->fraction < best->fraction) best = hit;
    });
    return best;
}

namespace f32 {
using MeshContact = xeno::MeshContact<float>;
}
namespace f64 {
using MeshContact = xeno::MeshContact<double>;
}

}  // namespace xeno

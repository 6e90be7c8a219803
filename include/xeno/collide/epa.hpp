// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The least penetration depth of a pair MPR has found overlapping, to within 1 %: an expanding
// polytope (van den Bergen, "Proximity Queries and Penetration Depth Computation on 3D Game
// Objects", GDC 2001) grown inside D = A ⊖ B from MPR's last tetrahedron (docs/collision.md,
// "Least depth").
//
// Why it is needed: MPR's depth is the support distance of D along the portal where the centre
// line leaves D, which can be several times the least depth on curved or elongated pairs (a cone
// against a capsule: 33.8 m reported for 5.2 m). Why it can be trusted: the polytope P has its
// vertices in D and contains the origin, so the distance from the origin to P's nearest face is a
// lower bound L on the least depth; every support query along a face normal n gives D's support
// distance h(n), an upper bound U (moving B by h(n) · n separates the pair). Expanding the nearest
// face until U − L ≤ 1 % of U gives a depth within 1 % of the least one, without searching
// directions blindly. Every array is fixed (no allocation, the world calls this per pair); when a
// cap is reached or the polytope turns degenerate in round-off, the best U found so far stands,
// which is never worse than MPR's answer.
#pragma once

#include "minkowski.hpp"

#include <cmath>
#include <cstdint>
#include <optional>

namespace xeno::detail {

/// A convex polytope with outward, unit face normals, grown one support point at a time.
template <class T>
class ExpandingPolytope {
public:
    static constexpr int kMaxVertices = 64;
    static constexpr int kMaxFaces = 2 * kMaxVertices - 4;  // Euler: a closed triangulated surface

    struct Face {
        Vec3<T> normal;           ///< unit, outward
        T distance;               ///< from the origin to the face's plane (normal · any vertex)
        std::int16_t v[3];        ///< vertex indices, counter-clockwise seen from outside
        std::int16_t adj[3];      ///< adj[k]: the face across edge v[k] → v[k+1]
        std::int8_t adj_edge[3];  ///< which edge of adj[k] that is
        bool alive;
    };

    /// The tetrahedron with apex p[0] over the triangle p[1..3] (MPR's v0 and portal); false
    /// when it is flat within round-off of `scale` (metres).
    bool start(const Vec3<T> (&p)[4], T scale) {
        // A face's normal, from two edges of length e with coordinates of size `scale`, carries a
        // round-off of about ε · scale / e radians: faces with edges under 128 ε · scale (twice
        // the area under its square) would have normals off by more than 1/128 and are refused.
        min_twice_area_ = square(T(128) * ScalarTraits<T>::epsilon * scale);
        visible_ = T(16) * ScalarTraits<T>::epsilon * scale;
        for (int i = 0; i < 4; ++i) vertices_[i] = p[i];
        vertex_count_ = 4;
        // Flat when the apex is within round-off of the base's plane. (Measured from the base: the
        // portal is small and v0 far from it, so a triple product of the three long edges from v0
        // would carry a round-off larger than the volume.)
        const Vec3<T> base = cross(p[2] - p[1], p[3] - p[1]);
        const T base_sq = length_squared(base);
        if (!(base_sq > square(min_twice_area_))) return false;
        const T height = dot(base, p[0] - p[1]) / std::sqrt(base_sq);
        if (!(std::abs(height) > T(64) * ScalarTraits<T>::epsilon * scale)) return false;
        // Below the base's normal the order 0-1-2-3 has a positive volume, and p3 lies on the side
        // of (p1 − p0) × (p2 − p0): face 0-2-1 faces away from it.
        const std::int16_t s = height < T(0) ? 0 : 1;  // else swap 1 and 2
        const std::int16_t i1 = s ? 2 : 1, i2 = s ? 1 : 2;
        const std::int16_t tri[4][3] = {{0, i2, i1}, {0, i1, 3}, {i1, i2, 3}, {0, 3, i2}};
        face_count_ = 4;
        for (int f = 0; f < 4; ++f)
            if (!set_face(f, tri[f][0], tri[f][1], tri[f][2])) return false;
        link_tetrahedron();
        nearest_ = nearest_index();
        return true;
    }

    /// The live face nearest the origin.
    const Face& nearest() const { return faces_[nearest_]; }
    /// Whether the origin is inside (or on, within round-off) every face: MPR's tetrahedron
    /// always holds it, another start may not.
    bool holds_origin() const {
        for (int f = 0; f < face_count_; ++f)
            if (faces_[f].distance < -visible_) return false;
        return true;
    }

    /// Adds w (a point of D beyond the nearest face): removes every face that sees it and closes
    /// the hole with a fan of faces to w. False when a cap is reached or round-off breaks the
    /// surface; the polytope must not be used after that.
    bool expand(const Vec3<T>& w) {
        if (vertex_count_ == kMaxVertices) return false;
        const int first = nearest_;
        horizon_count_ = 0;
        free_count_ = 0;
        remove(first);
        for (int k = 0; k < 3; ++k) visit(faces_[first].adj[k], faces_[first].adj_edge[k], w);
        if (horizon_count_ < 3 || horizon_count_ > kMaxHorizon) return false;
        const std::int16_t wi = static_cast<std::int16_t>(vertex_count_++);
        vertices_[wi] = w;
        if (!close_hole(wi)) return false;
        nearest_ = nearest_index();
        return true;
    }

    /// Whether every live face's neighbours are live faces that name it back across the same
    /// edge: the invariant expand() keeps (or reports false). For tests and asserts.
    bool well_linked() const {
        for (int f = 0; f < face_count_; ++f) {
            if (!faces_[f].alive) continue;
            for (int k = 0; k < 3; ++k) {
                const int g = faces_[f].adj[k], j = faces_[f].adj_edge[k];
                if (g < 0 || g >= face_count_ || j < 0 || j > 2 || !faces_[g].alive) return false;
                if (faces_[g].adj[j] != f || faces_[g].adj_edge[j] != k) return false;
                if (faces_[g].v[j] != faces_[f].v[(k + 1) % 3] || faces_[g].v[(j + 1) % 3] != faces_[f].v[k]) return false;
            }
        }
        return true;
    }

private:
    static constexpr int kMaxHorizon = kMaxFaces;

    struct HorizonEdge {
        std::int16_t face;  ///< the face that stays, beyond the edge
        std::int8_t edge;   ///< its edge along the horizon
    };

    // Over a plain array of the faces' distances (a removed face's is +infinity): a tight loop the
    // compiler keeps in registers, where the scan over the faces themselves strode 48-byte records.
    int nearest_index() const {
        int best = 0;
        for (int f = 1; f < face_count_; ++f)
            if (distance_[f] < distance_[best]) best = f;
        return best;
    }

    bool set_face(int f, std::int16_t a, std::int16_t b, std::int16_t c) {
        Face& face = faces_[f];
        face.v[0] = a;
        face.v[1] = b;
        face.v[2] = c;
        face.alive = true;
        const Vec3<T> n = cross(vertices_[b] - vertices_[a], vertices_[c] - vertices_[a]);
        const T length_sq = length_squared(n);
        if (!(length_sq > square(min_twice_area_))) return false;  // a sliver: its normal is round-off
        face.normal = n / std::sqrt(length_sq);
        face.distance = dot(face.normal, vertices_[a]);
        if (!std::isfinite(face.distance)) return false;  // nearest_index() takes +inf as removed
        distance_[f] = face.distance;
        return true;
    }

    // The four faces of the first tetrahedron share edges pairwise. start() lists them as
    // {0, i2, i1}, {0, i1, 3}, {i1, i2, 3}, {0, 3, i2}, so each edge's twin is the same whichever
    // way i1 and i2 were swapped: edge k of face f runs backwards along edge kEdge[f][k] of face
    // kFace[f][k] (well_linked() checks it in the tests).
    void link_tetrahedron() {
        static constexpr std::int16_t kFace[4][3] = {{3, 2, 1}, {0, 2, 3}, {0, 3, 1}, {1, 2, 0}};
        static constexpr std::int8_t kEdge[4][3] = {{2, 0, 0}, {2, 2, 0}, {1, 1, 1}, {2, 1, 0}};
        for (int f = 0; f < 4; ++f)
            for (int k = 0; k < 3; ++k) {
                faces_[f].adj[k] = kFace[f][k];
                faces_[f].adj_edge[k] = kEdge[f][k];
            }
    }

    void remove(int f) {
        faces_[f].alive = false;
        distance_[f] = ScalarTraits<T>::infinity;
        free_[free_count_++] = static_cast<std::int16_t>(f);
    }

    // Depth-first over the faces w sees, entered through edge `edge` of face f: the faces that do
    // not see w leave their shared edge on the horizon, in order around it (each face's other two
    // edges are walked counter-clockwise after the one it was entered by).
    void visit(int f, int edge, const Vec3<T>& w) {
        Face& face = faces_[f];
        if (!face.alive) return;
        if (!(dot(face.normal, w) - face.distance > visible_)) {
            if (horizon_count_ < kMaxHorizon)
                horizon_[horizon_count_] = {static_cast<std::int16_t>(f), static_cast<std::int8_t>(edge)};
            ++horizon_count_;
            return;
        }
        remove(f);
        for (int k = 1; k <= 2; ++k) {
            const int e = (edge + k) % 3;
            visit(face.adj[e], face.adj_edge[e], w);
        }
    }

    // One new face per horizon edge (its far end, its near end, w), linked to the face beyond the
    // edge and to its neighbours in the fan; the slots of removed faces are reused (a new vertex
    // removes r faces and adds r + 2, so the live faces never exceed kMaxFaces).
    bool close_hole(std::int16_t wi) {
        std::int16_t created[kMaxHorizon];
        for (int i = 0; i < horizon_count_; ++i) {
            const HorizonEdge& h = horizon_[i];
            const Face& beyond = faces_[h.face];
            const std::int16_t a = beyond.v[(h.edge + 1) % 3], b = beyond.v[h.edge];
            std::int16_t slot;
            if (i < free_count_) slot = free_[i];
            else if (face_count_ < kMaxFaces) slot = static_cast<std::int16_t>(face_count_++);
            else return false;
            if (!set_face(slot, a, b, wi)) return false;
            faces_[slot].adj[0] = h.face;
            faces_[slot].adj_edge[0] = h.edge;
            faces_[h.face].adj[h.edge] = slot;
            faces_[h.face].adj_edge[h.edge] = 0;
            created[i] = slot;
        }
        // Link the fan in order around w: face i's edge b → w is the twin of the edge w → b of
        // the face whose near end is b. In exact arithmetic the horizon is one simple loop; round-off
        // can pinch it (a vertex met twice) or split it, and then some face would be linked twice
        // and another never: walk the loop and refuse anything but one cycle through every face.
        std::int16_t next[kMaxHorizon];
        if (fan_in_visit_order(created, next)) return link_fan(created, next);
        for (int i = 0; i < horizon_count_; ++i) {
            next[i] = -1;
            for (int j = 0; j < horizon_count_; ++j) {
                if (faces_[created[j]].v[0] != faces_[created[i]].v[1]) continue;
                if (next[i] >= 0 || j == i) return false;  // two candidates, or a face to itself
                next[i] = static_cast<std::int16_t>(j);
            }
            if (next[i] < 0) return false;
        }
        int at = 0;
        for (int step = 1; step <= horizon_count_; ++step) {
            at = next[at];
            if ((at == 0) != (step == horizon_count_)) return false;  // back to the start too soon
        }
        return link_fan(created, next);
    }

    // The common case in O(h): visit() met the horizon in order, each face's near end is the next
    // face's far end, and no vertex is met twice. Then face i + 1 is the one and only candidate the
    // general search in close_hole would find for face i, so the links are the same.
    bool fan_in_visit_order(const std::int16_t* created, std::int16_t* next) {
        const int h = horizon_count_;
        ++stamp_;
        for (int i = 0; i < h; ++i) {
            const int j = i + 1 == h ? 0 : i + 1;
            const std::int16_t near_end = faces_[created[i]].v[1];
            if (faces_[created[j]].v[0] != near_end || seen_[near_end] == stamp_) return false;
            seen_[near_end] = stamp_;
            next[i] = static_cast<std::int16_t>(j);
        }
        return true;
    }

    bool link_fan(const std::int16_t* created, const std::int16_t* next) {
        for (int k = 0; k < horizon_count_; ++k) {
            Face& f = faces_[created[k]];
            Face& g = faces_[created[next[k]]];
            f.adj[1] = created[next[k]];
            f.adj_edge[1] = 2;
            g.adj[2] = created[k];
            g.adj_edge[2] = 1;
        }
        return true;
    }

    Vec3<T> vertices_[kMaxVertices];
    Face faces_[kMaxFaces];
    T distance_[kMaxFaces];  ///< faces_[f].distance, or +infinity once f is removed (nearest_index)
    HorizonEdge horizon_[kMaxHorizon];
    std::int16_t free_[kMaxFaces];
    int seen_[kMaxVertices] = {};  ///< fan_in_visit_order: the call that last met each vertex
    int stamp_ = 0;
    int vertex_count_ = 0, face_count_ = 0, horizon_count_ = 0, free_count_ = 0;
    int nearest_ = 0;     ///< the live face nearest the origin, found once per change (nearest_index)
    T min_twice_area_{};  ///< m², below which a face's normal is mostly round-off
    T visible_{};         ///< m, how far beyond a face's plane a point must be to see it
};

/// A start for the polytope when MPR's portal is one point of D (a corner of D on the centre
/// line). Two shapes that turn about one axis, their centres on it (a capsule standing on a cone's
/// axis), put v0, the origin and the portal on one line: the portal shrank to a point, the
/// expansion was skipped, and MPR's depth along the axis stood, 41 % deeper than the least. When
/// D is shallower a little off the line, its support points in three directions around the line
/// (120° apart) and one along it, either way, make the start: the first such tetrahedron that
/// holds the origin. False (MPR's answer stands) otherwise. `queries` counts the support calls.
template <class A, class B>
bool start_around_centre_line(const MinkowskiDifference<A, B>& md, const Vec3<typename A::scalar_type> (&flat)[4],
                              typename A::scalar_type h, ExpandingPolytope<typename A::scalar_type>& polytope, int& queries) {
    using T = typename A::scalar_type;
    const std::optional<Vec3<T>> line = try_normalized(flat[1] + flat[2] + flat[3] - flat[0] * T(3));  // v0 → portal
    if (!line) return false;
    const Vec3<T> u = any_perpendicular(*line), v = cross(*line, u);
    const T half_root3 = std::sqrt(T(3)) / T(2);
    const Vec3<T> around[3] = {u, u * T(-0.5) + v * half_root3, u * T(-0.5) - v * half_root3};
    // Only where D is shallower a little off the line (45°): a sphere's D, whose least depth is
    // along the line, often ends MPR on one point too, and there the expansion would only cost.
    bool shallower = false;
    for (int k = 0; k < 3 && !shallower; ++k) {
        const Vec3<T> tilted = normalized(*line + around[k]);
        shallower = dot(md.support_fresh(tilted).v, tilted) < T(0.99) * h;
        ++queries;
    }
    if (!shallower) return false;
    const Vec3<T> ring[3] = {md.support_fresh(around[0]).v, md.support_fresh(around[1]).v, md.support_fresh(around[2]).v};
    queries += 3;
    for (const T side : {T(1), T(-1)}) {
        const Vec3<T> tetrahedron[4] = {md.support_fresh(*line * side).v, ring[0], ring[1], ring[2]};
        ++queries;
        if (polytope.start(tetrahedron, md.scale()) && polytope.holds_origin()) return true;
    }
    return false;
}

/// Lowers the depth h (D's support distance along the unit normal n, margin included) towards the
/// least support distance of D over all directions, starting from MPR's tetrahedron `simplex`
/// (which contains the origin). n and h change only to a direction with a smaller support
/// distance; returns the number of support queries made.
template <class A, class B>
int expand_to_least_depth(const MinkowskiDifference<A, B>& md, const Vec3<typename A::scalar_type> (&simplex)[4],
                          Vec3<typename A::scalar_type>& n, typename A::scalar_type& h) {
    using T = typename A::scalar_type;
    constexpr T relative = T(0.01);
    // Below this the support distances are round-off (MPR's own convergence tolerance, mpr.hpp).
    const T absolute = std::max((std::is_same_v<T, float> ? T(1e-5) : T(1e-7)) * md.tolerance_scale(), md.round_off());
    ExpandingPolytope<T> polytope;
    int queries = 0;
    if (!polytope.start(simplex, md.scale())) {
        // A flat start with a portal of three distinct points is MPR converged on a smooth part of
        // D, whose answer stands; a portal that is one point is a corner of D on the centre line.
        const bool corner = simplex[1] == simplex[2] && simplex[2] == simplex[3];
        if (!corner || !start_around_centre_line(md, simplex, h, polytope, queries)) return queries;
    }
    for (int k = 0; k < ExpandingPolytope<T>::kMaxVertices; ++k) {
        const auto& face = polytope.nearest();
        const T lower = face.distance;
        if (h - lower <= std::max(relative * h, absolute)) break;  // h is within 1 % of the least
        const Vec3<T> w = md.support_fresh(face.normal).v;
        ++queries;
        const T along = dot(w, face.normal);
        if (along < h) {
            h = along;
            n = face.normal;
        }
        if (along - lower <= absolute) break;  // the face lies on D's boundary: L is final
        if (!polytope.expand(w)) break;
    }
    return queries;
}

}  // namespace xeno::detail

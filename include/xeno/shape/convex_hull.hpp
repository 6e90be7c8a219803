// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// make_convex_hull: the convex hull of a point cloud as a ConvexPolyhedron<T>, by Quickhull
// (Barber, Dobkin & Huhdanpaa, "The Quickhull algorithm for convex hulls", ACM Transactions on
// Mathematical Software 22(4), 1996), keeping faces convex by merging neighbours as John Lloyd's
// QuickHull3D (2004) and Gregorius, "Implementing Quickhull" (GDC 2014) do. Points are in metres.
// Every hull vertex is an input point; points inside, on a face or on the inside of an edge are
// dropped; coplanar triangles become one polygon face, counter-clockwise seen from outside. The
// result is re-centred on its centroid (docs/conventions.md, "Frames"): input point = polyhedron
// vertex + shift, up to the round-off in T of subtracting and adding the shift.
//
// Tolerances scale with the cloud. With d the diagonal of its bounding box, a face is ε = d ×
// geometric_tolerance thick (1e-5 d in float, 1e-9 d in double): a point less than ε above the hull
// counts as on it, two faces whose centroids lie within ε of each other's planes are one face, and
// a sliver narrower than ε is merged into its neighbour. Heights are measured from a face's outer
// plane (through its highest vertex), so a merged face, planar only to a few ε, never sees one of
// its own vertices (or a duplicate of one) as outside. ConvexPolyhedron checks planarity and
// convexity to 64 ε, so merged faces pass with room to spare. Clouds that do not reach 64 ε out
// of a line or a plane, or whose hull is too flat for ConvexPolyhedron's volume check, are rejected
// as collinear or coplanar; so are coincident points (all within 4 ulps of their coordinates).
//
// Precision. The hull is decided in double for both scalar types, on points moved by the centre of
// their bounding box. It only chooses input points, so no output value passes through double;
// deciding it in float would not do: a sliver triangle's normal is off by ~ulp × length / height,
// enough to see a point far outside as inside and tear the mesh.
//
// Faces too small for ConvexPolyhedron<T>. The polyhedron rejects a face of area at most
// 32 × geometric_tolerance × d² (3.2e-4 d² in float, 3.2e-8 d² in double), whatever its shape: a
// float hull cannot have more than a few thousand faces, and a double hull cannot keep a cluster
// of points 1e-4 d across. Such a face loses the vertex whose removal moves the hull least and
// the hull is rebuilt from the remaining vertices, until every face passes. The dropped points
// then stand out of the hull by about the size of the face times the angle between its
// neighbours: up to 1-2 % of d for a dense float cloud (of 2,000 points on a sphere ~770 stay),
// 1e-4 d for tight double clusters. Double clouds of ordinary shape never need this.
#pragma once

#include "../error.hpp"
#include "convex_polyhedron.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace xeno {

/// A hull centred on its centroid: input point = polyhedron vertex + shift.
template <class T>
struct ConvexHull {
    ConvexPolyhedron<T> polyhedron;  ///< local frame, origin at the centroid (centre of mass)
    Vec3<T> shift;                   ///< metres: where the polyhedron's origin was among the points
};

/// The convex hull of points (metres, any order, duplicates allowed), re-centred on its centroid:
/// original point = polyhedron vertex + shift. Every point lies inside or less than ε outside,
/// except vertices dropped from faces too small for ConvexPolyhedron<T> (see above). Rejects
/// (InvalidArgument, naming make_convex_hull) fewer than 4 points, a non-finite coordinate
/// (naming the point), coordinates too large to square in T, and clouds whose points coincide,
/// are collinear or are coplanar within the tolerance above. O(n log n) for n points, measured up
/// to 128k points on a sphere, where every point is on the hull (docs/benchmarks.md).
template <class T>
ConvexHull<T> make_convex_hull(const std::vector<Vec3<T>>& points);

namespace detail {

/// Quickhull on points already centred (working precision W), with merged polygon faces.
///
///  1. Start from a tetrahedron of four far-apart points; give each other point to the face it is
///     farthest above, if more than ε (its conflict list); the rest are inside.
///  2. While a face has a conflict list: take its farthest point, the eye (unless it duplicates
///     one of the face's vertices to within ε).
///  3. Walk from that face over every face the eye is more than ε above (the visible faces);
///     the edges where the walk stops form the horizon, a closed loop.
///  4. Delete the visible faces and join the eye to each horizon edge by a new triangle.
///  5. Merge each new triangle narrower than ε into the face across its longest edge. Merge each
///     new face with a neighbour when either centroid is not at least ε below the other's plane
///     (coplanar or concave), first judged from the larger face, then from both; a vertex left
///     between only two faces (on a straight edge) is removed with its edges.
///  6. Give the deleted faces' conflict points to the new face they are farthest above, or drop
///     them as inside.
///
/// Every loop is capped; an inconsistent mesh (a numerical failure) makes build() return false.
template <class W>
class QuickHullBuilder {
public:
    QuickHullBuilder(const std::vector<Vec3<W>>& points, W tolerance) : points_(points), tolerance_(tolerance) {}

    /// Builds the hull of the points listed in candidates, starting from the tetrahedron simplex
    /// (four candidates, not coplanar). False when the mesh became inconsistent.
    bool build(const std::vector<std::uint32_t>& candidates, const std::array<std::uint32_t, 4>& simplex);

    /// The faces as loops of point indices, counter-clockwise seen from outside.
    std::vector<std::vector<std::uint32_t>> face_loops() const;

private:
    static constexpr std::uint32_t none = 0xffffffffu;

    struct HalfEdge {
        std::uint32_t origin;  // point index the edge starts at
        std::uint32_t face;
        std::uint32_t next, prev, twin;
    };
    struct Face {
        std::uint32_t edge = none;  // any half-edge of the face
        std::uint32_t count = 0;    // number of vertices
        Vec3<W> normal{}, centroid{};
        W offset = W(0);  // normal · centroid: the mean plane, for merging
        W outer = W(0);   // max of normal · vertex: the outer plane, for points
        W area = W(0);
        bool alive = true, nonconvex = false, queued = false;
        bool degenerate = false;             // no reliable plane (narrower than ε): to be merged away
        std::vector<std::uint32_t> outside;  // conflict list: points more than ε above the face
    };

    std::uint32_t head(std::uint32_t e) const { return edges_[edges_[e].next].origin; }
    std::uint32_t twin_face(std::uint32_t e) const { return edges_[edges_[e].twin].face; }
    // Height of a point above a face's outer plane: a merged face is planar only to within a few
    // ε, and a point must not count as outside a face it is a vertex of.
    W height(std::uint32_t f, std::uint32_t point) const { return dot(faces_[f].normal, points_[point]) - faces_[f].outer; }
    W mean_distance(std::uint32_t f, const Vec3<W>& p) const { return dot(faces_[f].normal, p) - faces_[f].offset; }

    std::uint32_t add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
    void link(std::uint32_t e, std::uint32_t f) {
        edges_[e].twin = f;
        edges_[f].twin = e;
    }
    void update_plane(std::uint32_t f);
    std::uint32_t longest_edge(std::uint32_t f) const;
    bool merge_degenerate_faces();
    void add_outside(std::uint32_t f, std::uint32_t point);
    void assign(std::uint32_t point, const std::vector<std::uint32_t>& candidate_faces);
    std::uint32_t take_eye(std::uint32_t f);
    void remove_face(std::uint32_t f);
    bool add_point(std::uint32_t eye, std::uint32_t eye_face);
    bool find_horizon(std::uint32_t eye, std::uint32_t eye_face);
    bool merge_with_neighbour(std::uint32_t f, bool strict);
    void merge_faces(std::uint32_t e);
    std::uint32_t connect(std::uint32_t f, std::uint32_t before, std::uint32_t after);
    bool mesh_is_consistent() const;

    const std::vector<Vec3<W>>& points_;
    W tolerance_;
    std::vector<HalfEdge> edges_;
    // A deque: faces are only ever appended (a dead face keeps its index), and a vector would
    // copy them all each time it grew: at 100k points on a sphere, half a million faces, and the
    // copies and fresh pages were a third of the build.
    std::deque<Face> faces_;
    std::vector<std::uint32_t> pending_;  // faces that received conflict points, in order
    std::vector<std::uint32_t> horizon_, unclaimed_, new_faces_, discarded_, scratch_, degenerate_;
    std::vector<std::uint32_t> stamp_;  // per point: last add_point that saw it on the horizon
    struct HorizonFrame {
        std::uint32_t edge;       // next edge of this face to look across
        std::uint32_t remaining;  // edges of this face still to look across
    };
    std::vector<HorizonFrame> stack_;  // find_horizon's depth-first walk
    std::uint32_t step_ = 0;
    bool failed_ = false;
};

template <class W>
std::uint32_t QuickHullBuilder<W>::add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const std::uint32_t f = static_cast<std::uint32_t>(faces_.size());
    const std::uint32_t e = static_cast<std::uint32_t>(edges_.size());
    edges_.push_back({a, f, e + 1, e + 2, none});
    edges_.push_back({b, f, e + 2, e, none});
    edges_.push_back({c, f, e, e + 1, none});
    faces_.emplace_back();
    faces_[f].edge = e;
    update_plane(f);
    return f;
}

template <class W>
void QuickHullBuilder<W>::update_plane(std::uint32_t f) {
    // Centroid first, then Newell's normal about it (the exact area vector of a planar polygon,
    // a least-squares-like normal of a nearly planar one, and well conditioned either way).
    Face& face = faces_[f];
    Vec3<W> sum = Vec3<W>::zero();
    std::uint32_t count = 0;
    std::uint32_t e = face.edge;
    do {
        sum += points_[edges_[e].origin];
        e = edges_[e].next;
        if (++count > edges_.size()) {
            failed_ = true;
            return;
        }
    } while (e != face.edge);
    face.count = count;
    face.centroid = sum / static_cast<W>(count);
    Vec3<W> newell = Vec3<W>::zero();
    do {
        newell += cross(points_[edges_[e].origin] - face.centroid, points_[head(e)] - face.centroid);
        e = edges_[e].next;
    } while (e != face.edge);
    const std::optional<Vec3<W>> normal = try_normalized(newell);
    face.area = length(newell) / W(2);
    // Narrower than ε (area over longest edge): the eye was in line with a horizon edge, or a
    // merge left a sliver. Its plane is noise; merge_degenerate_faces() removes it.
    face.degenerate =
        !normal || !(face.area <= ScalarTraits<W>::max) ||
        !(W(2) * face.area > tolerance_ * length(points_[edges_[longest_edge(f)].origin] - points_[head(longest_edge(f))]));
    if (face.degenerate) {
        degenerate_.push_back(f);
        if (!normal) return;
    }
    face.normal = *normal;
    face.offset = dot(face.normal, face.centroid);
    face.outer = face.offset;
    do {
        face.outer = std::max(face.outer, dot(face.normal, points_[edges_[e].origin]));
        e = edges_[e].next;
    } while (e != face.edge);
}

template <class W>
std::uint32_t QuickHullBuilder<W>::longest_edge(std::uint32_t f) const {
    std::uint32_t best = faces_[f].edge, e = best;
    W best_length = W(-1);
    for (std::uint32_t k = 0; k < faces_[f].count; ++k, e = edges_[e].next) {
        const W l = length_squared(points_[head(e)] - points_[edges_[e].origin]);
        if (l > best_length) {
            best_length = l;
            best = e;
        }
    }
    return best;
}

template <class W>
bool QuickHullBuilder<W>::merge_degenerate_faces() {
    // A sliver lies along its longest edge, so the face across that edge holds it in its plane
    // (to within ε); merging into it changes the hull by less than ε.
    const std::size_t cap = faces_.size() + 8;
    for (std::size_t k = 0; k < degenerate_.size(); ++k) {
        if (k > cap) return false;
        const std::uint32_t f = degenerate_[k];
        if (!faces_[f].alive || !faces_[f].degenerate) continue;
        merge_faces(longest_edge(f));
        if (failed_) return false;
    }
    degenerate_.clear();
    return true;
}

template <class W>
void QuickHullBuilder<W>::add_outside(std::uint32_t f, std::uint32_t point) {
    faces_[f].outside.push_back(point);
    if (!faces_[f].queued) {
        faces_[f].queued = true;
        pending_.push_back(f);
    }
}

template <class W>
void QuickHullBuilder<W>::assign(std::uint32_t point, const std::vector<std::uint32_t>& candidate_faces) {
    std::uint32_t best = none;
    W best_distance = tolerance_;
    for (std::uint32_t f : candidate_faces) {
        if (!faces_[f].alive) continue;
        const W d = height(f, point);
        if (d > best_distance) {
            best_distance = d;
            best = f;
        }
    }
    if (best != none) add_outside(best, point);  // otherwise inside (or within ε of) the hull
}

template <class W>
std::uint32_t QuickHullBuilder<W>::take_eye(std::uint32_t f) {
    std::vector<std::uint32_t>& outside = faces_[f].outside;
    std::size_t best = outside.size();
    W best_distance = tolerance_;
    for (std::size_t k = 0; k < outside.size(); ++k) {
        const W d = height(f, outside[k]);
        if (d > best_distance) {
            best_distance = d;
            best = k;
        }
    }
    if (best == outside.size()) {
        // The face was merged or trimmed after these points were given to it and none is above
        // it any more: offer them to its neighbours, else they are inside.
        std::vector<std::uint32_t> moved;
        moved.swap(outside);
        scratch_.clear();
        std::uint32_t e = faces_[f].edge;
        for (std::uint32_t k = 0; k < faces_[f].count; ++k, e = edges_[e].next) scratch_.push_back(twin_face(e));
        for (std::uint32_t point : moved) assign(point, scratch_);
        return none;
    }
    const std::uint32_t eye = outside[best];
    outside[best] = outside.back();
    outside.pop_back();
    // A near-duplicate of one of the face's vertices is on the hull already.
    std::uint32_t e = faces_[f].edge;
    for (std::uint32_t k = 0; k < faces_[f].count; ++k, e = edges_[e].next) {
        if (length_squared(points_[eye] - points_[edges_[e].origin]) <= tolerance_ * tolerance_) {
            if (!outside.empty() && !faces_[f].queued) {
                faces_[f].queued = true;
                pending_.push_back(f);
            }
            return none;
        }
    }
    return eye;
}

template <class W>
void QuickHullBuilder<W>::remove_face(std::uint32_t f) {
    faces_[f].alive = false;
    unclaimed_.insert(unclaimed_.end(), faces_[f].outside.begin(), faces_[f].outside.end());
    std::vector<std::uint32_t>().swap(faces_[f].outside);  // freed for the faces to come
}

template <class W>
bool QuickHullBuilder<W>::build(const std::vector<std::uint32_t>& candidates, const std::array<std::uint32_t, 4>& simplex) {
    edges_.clear();
    faces_.clear();
    pending_.clear();
    degenerate_.clear();
    stamp_.assign(points_.size(), 0);
    step_ = 0;
    failed_ = false;

    // 1. The tetrahedron, wound so that every face looks away from the fourth point.
    std::uint32_t a = simplex[0], b = simplex[1], c = simplex[2];
    const std::uint32_t d = simplex[3];
    if (triple(points_[b] - points_[a], points_[c] - points_[a], points_[d] - points_[a]) > W(0)) std::swap(b, c);
    add_triangle(a, b, c);
    add_triangle(a, d, b);
    add_triangle(b, d, c);
    add_triangle(c, d, a);
    for (std::uint32_t i = 0; i < 12; ++i)
        for (std::uint32_t j = i + 1; j < 12; ++j)
            if (edges_[i].origin == head(j) && edges_[j].origin == head(i)) link(i, j);
    for (const HalfEdge& e : edges_)
        if (e.twin == none) return false;
    if (failed_ || !degenerate_.empty()) return false;

    const std::vector<std::uint32_t> first_faces{0, 1, 2, 3};
    for (std::uint32_t point : candidates)
        if (point != a && point != b && point != c && point != d) assign(point, first_faces);

    // 2.-6. Add eyes until no face has a conflict list. A round adds a point to the hull, drops
    // a duplicate, or hands a list on from a face that changed since it got the points (a face
    // changes only when created or merged); so the cap, which grows with the faces, is never
    // reached by a consistent mesh.
    std::size_t rounds = 0;
    for (std::size_t next = 0; next < pending_.size(); ++next) {
        const std::uint32_t f = pending_[next];
        faces_[f].queued = false;
        if (!faces_[f].alive || faces_[f].outside.empty()) continue;
        if (++rounds > 2 * candidates.size() + 4 * faces_.size() + 64) return false;
        const std::uint32_t eye = take_eye(f);
        if (eye != none && !add_point(eye, f)) return false;
        if (failed_) return false;
    }
    return mesh_is_consistent();
}

template <class W>
bool QuickHullBuilder<W>::add_point(std::uint32_t eye, std::uint32_t eye_face) {
    horizon_.clear();
    unclaimed_.clear();
    new_faces_.clear();
    ++step_;

    // 3. Visible faces and the horizon.
    if (!find_horizon(eye, eye_face)) return false;
    const std::size_t n = horizon_.size();
    if (n < 3) return false;
    for (std::size_t i = 0; i < n; ++i) {
        // A closed loop through distinct vertices; anything else means the visible faces did not
        // form a disc (possible only through round-off) and the mesh cannot be patched.
        const std::uint32_t e = horizon_[i];
        if (head(e) != edges_[horizon_[(i + 1) % n]].origin) return false;
        if (stamp_[edges_[e].origin] == step_) return false;
        stamp_[edges_[e].origin] = step_;
    }

    // 4. A fan of triangles from the eye; edge 1 of each lies on the horizon, edges 2 and 0 of
    // consecutive triangles are twins.
    for (std::uint32_t e : horizon_) {
        const std::uint32_t outer = edges_[e].twin;
        const std::uint32_t f = add_triangle(eye, edges_[e].origin, head(e));
        link(faces_[f].edge + 1, outer);
        new_faces_.push_back(f);
    }
    for (std::size_t i = 0; i < n; ++i) link(faces_[new_faces_[i]].edge + 2, faces_[new_faces_[(i + 1) % n]].edge);
    if (failed_) return false;

    // 5. Merge slivers away, then coplanar or concave neighbours: judged from the larger face,
    // then from both.
    if (!merge_degenerate_faces()) return false;
    const std::size_t merge_cap = faces_.size() + 8;
    for (std::uint32_t f : new_faces_) {
        for (std::size_t k = 0; faces_[f].alive && merge_with_neighbour(f, false); ++k)
            if (k > merge_cap || failed_) return false;
    }
    if (!merge_degenerate_faces()) return false;
    for (std::uint32_t f : new_faces_) {
        if (!faces_[f].alive || !faces_[f].nonconvex) continue;
        faces_[f].nonconvex = false;
        for (std::size_t k = 0; faces_[f].alive && merge_with_neighbour(f, true); ++k)
            if (k > merge_cap || failed_) return false;
    }
    if (failed_ || !merge_degenerate_faces()) return false;

    // 6. Conflict points of the deleted faces go to the new face they are farthest above.
    scratch_.clear();
    for (std::uint32_t f : new_faces_)
        if (faces_[f].alive) scratch_.push_back(f);
    for (std::uint32_t point : unclaimed_) assign(point, scratch_);
    return true;
}

template <class W>
bool QuickHullBuilder<W>::find_horizon(std::uint32_t eye, std::uint32_t eye_face) {
    // Depth-first over the visible faces (Lloyd's recursion with an explicit stack). A face is
    // entered through one edge and its other edges are visited in order, so the horizon edges
    // come out as one counter-clockwise loop around the visible region.
    std::vector<HorizonFrame>& stack = stack_;
    stack.clear();
    remove_face(eye_face);
    stack.push_back({faces_[eye_face].edge, faces_[eye_face].count});
    const std::size_t cap = 2 * edges_.size() + 8;
    for (std::size_t steps = 0; !stack.empty(); ++steps) {
        if (steps > cap) return false;
        HorizonFrame& top = stack.back();
        if (top.remaining == 0) {
            stack.pop_back();
            continue;
        }
        const std::uint32_t e = top.edge;
        top.edge = edges_[e].next;
        --top.remaining;
        const std::uint32_t across = edges_[e].twin;
        const std::uint32_t g = edges_[across].face;
        if (!faces_[g].alive) continue;  // visible, already removed
        if (height(g, eye) > tolerance_) {
            remove_face(g);
            stack.push_back({edges_[across].next, faces_[g].count - 1});
        } else {
            horizon_.push_back(e);
        }
    }
    return true;
}

template <class W>
bool QuickHullBuilder<W>::merge_with_neighbour(std::uint32_t f, bool strict) {
    // Lloyd's test: the centroid of one face must lie more than ε below the other's plane. In the
    // first pass only the larger face judges (its plane is the better estimate), and a face that
    // fails only the smaller face's judgement is marked for the second pass, where both judge.
    bool convex = true;
    std::uint32_t e = faces_[f].edge;
    for (std::uint32_t k = 0; k < faces_[f].count; ++k, e = edges_[e].next) {
        const std::uint32_t g = twin_face(e);
        const W g_above_f = mean_distance(f, faces_[g].centroid);
        const W f_above_g = mean_distance(g, faces_[f].centroid);
        bool merge = false;
        if (strict) {
            merge = g_above_f > -tolerance_ || f_above_g > -tolerance_;
        } else if (faces_[f].area > faces_[g].area) {
            if (g_above_f > -tolerance_) merge = true;
            else if (f_above_g > -tolerance_) convex = false;
        } else {
            if (f_above_g > -tolerance_) merge = true;
            else if (g_above_f > -tolerance_) convex = false;
        }
        if (merge) {
            merge_faces(e);
            return true;
        }
    }
    if (!convex) faces_[f].nonconvex = true;
    return false;
}

template <class W>
void QuickHullBuilder<W>::merge_faces(std::uint32_t e) {
    // Face f absorbs g, its neighbour across e (and across any run of edges next to e that also
    // border g). The two ends of the removed run are then reconnected.
    const std::uint32_t f = edges_[e].face, opposite = edges_[e].twin, g = edges_[opposite].face;
    discarded_.clear();
    discarded_.push_back(g);
    faces_[g].alive = false;
    std::uint32_t before = edges_[e].prev, after = edges_[e].next;                    // in f
    std::uint32_t g_before = edges_[opposite].prev, g_after = edges_[opposite].next;  // in g
    const std::size_t cap = faces_[f].count + faces_[g].count;
    for (std::size_t k = 0; twin_face(before) == g; ++k) {
        if (k > cap) {
            failed_ = true;
            return;
        }
        before = edges_[before].prev;
        g_after = edges_[g_after].next;
    }
    for (std::size_t k = 0; twin_face(after) == g; ++k) {
        if (k > cap) {
            failed_ = true;
            return;
        }
        g_before = edges_[g_before].prev;
        after = edges_[after].next;
    }
    std::size_t k = 0;
    for (std::uint32_t h = g_after; h != edges_[g_before].next; h = edges_[h].next) {
        if (++k > cap) {
            failed_ = true;
            return;
        }
        edges_[h].face = f;
    }
    faces_[f].edge = after;
    const std::uint32_t at_head = connect(f, g_before, after);
    if (at_head != none) discarded_.push_back(at_head);
    const std::uint32_t at_tail = connect(f, before, g_after);
    if (at_tail != none) discarded_.push_back(at_tail);
    update_plane(f);
    if (failed_) return;

    // The absorbed faces' conflict points stay with f when still above it.
    for (std::uint32_t dead : discarded_) {
        std::vector<std::uint32_t> moved;
        moved.swap(faces_[dead].outside);
        for (std::uint32_t point : moved) {
            if (height(f, point) > tolerance_) add_outside(f, point);
            else unclaimed_.push_back(point);
        }
    }
}

template <class W>
std::uint32_t QuickHullBuilder<W>::connect(std::uint32_t f, std::uint32_t before, std::uint32_t after) {
    // before ends and after starts at vertex v, both in f. If both border the same face o, v lies
    // between only two faces: on a straight edge. It is removed: before and o's edge into v go,
    // after and o's edge out of v now span the gap. A triangle o would be left with two edges, so
    // it goes too, its third edge's twin becoming after's. Returns o when it was deleted.
    const std::uint32_t o = twin_face(after);
    if (twin_face(before) != o) {
        edges_[before].next = after;
        edges_[after].prev = before;
        return none;
    }
    if (faces_[f].edge == before) faces_[f].edge = after;
    const std::uint32_t into_v = edges_[after].twin;  // in o: w -> v
    std::uint32_t opposite;
    std::uint32_t deleted = none;
    if (faces_[o].count == 3) {
        opposite = edges_[edges_[into_v].prev].twin;  // beyond o's third edge u -> w: w -> u
        faces_[o].alive = false;
        deleted = o;
    } else {
        opposite = edges_[into_v].next;  // in o: v -> u, becomes w -> u
        const std::uint32_t into_w = edges_[into_v].prev;
        if (faces_[o].edge == into_v) faces_[o].edge = opposite;
        edges_[opposite].prev = into_w;
        edges_[into_w].next = opposite;
        edges_[opposite].origin = edges_[into_v].origin;
    }
    edges_[after].prev = edges_[before].prev;
    edges_[edges_[after].prev].next = after;
    edges_[after].origin = edges_[before].origin;  // after: u -> w
    link(after, opposite);
    if (deleted == none) update_plane(o);
    return deleted;
}

template <class W>
bool QuickHullBuilder<W>::mesh_is_consistent() const {
    // A closed, oriented 2-manifold of genus 0 whose faces have 3 or more vertices.
    std::size_t face_count = 0, half_edges = 0;
    std::vector<bool> used(points_.size(), false);
    for (std::uint32_t f = 0; f < faces_.size(); ++f) {
        if (!faces_[f].alive) continue;
        ++face_count;
        std::uint32_t e = faces_[f].edge, count = 0;
        do {
            const HalfEdge& h = edges_[e];
            if (h.face != f || edges_[h.next].prev != e || h.twin == none || edges_[h.twin].twin != e) return false;
            const std::uint32_t g = edges_[h.twin].face;
            if (g == f || !faces_[g].alive || edges_[h.twin].origin != head(e)) return false;
            used[h.origin] = true;
            e = h.next;
            if (++count > edges_.size()) return false;
        } while (e != faces_[f].edge);
        if (count < 3 || count != faces_[f].count) return false;
        half_edges += count;
    }
    const std::size_t vertex_count = static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
    return face_count >= 4 && vertex_count + face_count == half_edges / 2 + 2;
}

template <class W>
std::vector<std::vector<std::uint32_t>> QuickHullBuilder<W>::face_loops() const {
    std::vector<std::vector<std::uint32_t>> loops;
    for (const Face& face : faces_) {
        if (!face.alive) continue;
        std::vector<std::uint32_t> loop;
        std::uint32_t e = face.edge;
        do {
            loop.push_back(edges_[e].origin);
            e = edges_[e].next;
        } while (e != face.edge);
        loops.push_back(std::move(loop));
    }
    return loops;
}

/// The starting tetrahedron: the two farthest-apart of the six axis-extreme points, the point
/// farthest from their line, the point farthest from the plane of those three.
template <class W>
struct HullSimplex {
    std::array<std::uint32_t, 4> index{};
    W line_distance = W(0);   // metres: how far the third point is from the first two's line
    W plane_distance = W(0);  // metres: how far the fourth is from the first three's plane
};

template <class W>
HullSimplex<W> hull_simplex(const std::vector<Vec3<W>>& points, const std::vector<std::uint32_t>& candidates) {
    HullSimplex<W> s;
    std::array<std::uint32_t, 6> extreme;
    extreme.fill(candidates[0]);
    for (std::uint32_t i : candidates)
        for (int axis = 0; axis < 3; ++axis) {
            if (points[i][axis] < points[extreme[static_cast<std::size_t>(2 * axis)]][axis])
                extreme[static_cast<std::size_t>(2 * axis)] = i;
            if (points[i][axis] > points[extreme[static_cast<std::size_t>(2 * axis + 1)]][axis])
                extreme[static_cast<std::size_t>(2 * axis + 1)] = i;
        }
    W best = W(-1);
    for (std::uint32_t i : extreme)
        for (std::uint32_t j : extreme)
            if (length_squared(points[i] - points[j]) > best) {
                best = length_squared(points[i] - points[j]);
                s.index[0] = i;
                s.index[1] = j;
            }
    const Vec3<W> a = points[s.index[0]];
    const Vec3<W> axis = normalized_or(points[s.index[1]] - a, Vec3<W>::unit_x());
    s.index[2] = s.index[0];
    for (std::uint32_t i : candidates) {
        const W d = length(cross(points[i] - a, axis));
        if (d > s.line_distance) {
            s.line_distance = d;
            s.index[2] = i;
        }
    }
    const Vec3<W> normal = normalized_or(cross(points[s.index[1]] - a, points[s.index[2]] - a), Vec3<W>::unit_x());
    s.index[3] = s.index[0];
    for (std::uint32_t i : candidates) {
        const W d = std::abs(dot(points[i] - a, normal));
        if (d > s.plane_distance) {
            s.plane_distance = d;
            s.index[3] = i;
        }
    }
    return s;
}

/// Removes vertices that lie between only two faces (the inside of a straight edge) from both,
/// unless that would leave one of them with fewer than 3 vertices.
inline void remove_straight_edge_vertices(std::vector<std::vector<std::uint32_t>>& faces, std::size_t point_count) {
    // On a closed surface the faces around a vertex are as many as its edges.
    std::vector<std::uint32_t> degree(point_count, 0), first_face(point_count, 0), second_face(point_count, 0);
    for (std::uint32_t f = 0; f < faces.size(); ++f)
        for (std::uint32_t v : faces[f]) {
            (degree[v] == 0 ? first_face[v] : second_face[v]) = f;
            ++degree[v];
        }
    std::vector<std::size_t> size(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) size[f] = faces[f].size();
    std::vector<bool> removed(point_count, false);
    for (std::size_t v = 0; v < point_count; ++v) {
        if (degree[v] != 2 || size[first_face[v]] <= 3 || size[second_face[v]] <= 3) continue;
        removed[v] = true;
        --size[first_face[v]];
        --size[second_face[v]];
    }
    for (auto& face : faces)
        face.erase(std::remove_if(face.begin(), face.end(), [&](std::uint32_t v) { return removed[v]; }), face.end());
}

/// What ConvexPolyhedron<T>'s constructor will check (keep the two in step), with a margin for
/// its round-off in T: per face, whether it is too small or not planar enough; and the volume.
template <class W>
struct HullCheck {
    std::vector<bool> bad_face;
    std::vector<W> area;  // m^2, per face
    W volume = W(0);
    W min_volume = W(0);
    bool all_faces_good = true;
};

template <class T, class W>
HullCheck<W> check_hull_faces(const std::vector<Vec3<W>>& v, const std::vector<std::vector<std::uint32_t>>& faces) {
    HullCheck<W> out;
    Aabb<W> bounds;
    Vec3<W> reference = Vec3<W>::zero();
    std::size_t used = 0;
    for (const auto& face : faces)
        for (std::uint32_t i : face) {
            bounds.merge(v[i]);
            reference += v[i];
            ++used;
        }
    reference /= static_cast<W>(used);
    const W scale = length(bounds.max - bounds.min);
    const W tolerance = W(64) * W(ScalarTraits<T>::geometric_tolerance) * scale;  // as ConvexPolyhedron
    out.bad_face.assign(faces.size(), false);
    out.area.assign(faces.size(), W(0));
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        Vec3<W> centre = Vec3<W>::zero(), newell = Vec3<W>::zero();
        W longest_edge = W(0);
        for (std::uint32_t i : face) centre += v[i];
        centre /= static_cast<W>(face.size());
        for (std::size_t k = 0; k < face.size(); ++k) {
            const Vec3<W> p = v[face[k]] - reference, q = v[face[(k + 1) % face.size()]] - reference;
            newell += cross(p, q);
            longest_edge = std::max(longest_edge, length(q - p));
            if (k > 0 && k + 1 < face.size()) out.volume += triple(v[face[0]] - reference, p, q) / W(6);
        }
        out.area[f] = length(newell) / W(2);
        bool bad = !(length(newell) > W(1.05) * tolerance * longest_edge);  // as ConvexPolyhedron: width
        if (!bad) {
            const Vec3<W> n = normalized(newell);
            for (std::uint32_t i : face) bad = bad || std::abs(dot(n, v[i] - centre)) > tolerance / W(2);
        }
        out.bad_face[f] = bad;
        if (bad) out.all_faces_good = false;
    }
    // As ConvexPolyhedron: a mean thickness (2 V / area) above the tolerance.
    W area = W(0);
    for (const W a : out.area) area += a;
    out.min_volume = W(1.05) * tolerance * std::max(area / W(2), tolerance * scale);
    return out;
}

/// Distance from p to the triangle abc (Ericson, "Real-Time Collision Detection", 5.1.5).
template <class W>
W distance_to_triangle(const Vec3<W>& p, const Vec3<W>& a, const Vec3<W>& b, const Vec3<W>& c) {
    const Vec3<W> ab = b - a, ac = c - a, ap = p - a;
    const W d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= W(0) && d2 <= W(0)) return length(ap);
    const Vec3<W> bp = p - b;
    const W d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= W(0) && d4 <= d3) return length(bp);
    const W vc = d1 * d4 - d3 * d2;
    if (vc <= W(0) && d1 >= W(0) && d3 <= W(0)) return length(ap - ab * (d1 / (d1 - d3)));
    const Vec3<W> cp = p - c;
    const W d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= W(0) && d5 <= d6) return length(cp);
    const W vb = d5 * d2 - d1 * d6;
    if (vb <= W(0) && d2 >= W(0) && d6 <= W(0)) return length(ap - ac * (d2 / (d2 - d6)));
    const W va = d3 * d6 - d5 * d4;
    if (va <= W(0) && d4 - d3 >= W(0) && d5 - d6 >= W(0)) return length(bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    const W denominator = va + vb + vc;
    if (!(std::abs(denominator) > W(0))) return length(ap);  // degenerate triangle: a vertex bounds it
    return length(ap - ab * (vb / denominator) - ac * (vc / denominator));
}

/// Chooses vertices to drop so that the faces flagged bad disappear. Dropping v moves the hull
/// by at most v's distance to the hull of its neighbours; that is bounded here by the distance to
/// the nearest triangle of neighbours, and each bad face (smallest first) loses its vertex with
/// the smallest bound. Neighbours of a dropped vertex wait for the next round, so each drop is
/// seen in the rebuilt hull before the next one nearby.
template <class W>
std::vector<bool> vertices_to_drop(const std::vector<Vec3<W>>& v, const std::vector<std::vector<std::uint32_t>>& faces,
                                   const std::vector<W>& face_area, const std::vector<bool>& bad_face) {
    std::vector<std::vector<std::uint32_t>> neighbours(v.size());
    for (const auto& face : faces)
        for (std::size_t k = 0; k < face.size(); ++k) neighbours[face[k]].push_back(face[(k + 1) % face.size()]);
    std::vector<W> cost(v.size(), ScalarTraits<W>::infinity);
    auto removal_cost = [&](std::uint32_t i) {
        if (cost[i] < ScalarTraits<W>::infinity) return cost[i];
        const std::vector<std::uint32_t>& ring = neighbours[i];
        const std::size_t m = ring.size(), all_triples = 10;  // beyond this degree, fans only
        W best = ScalarTraits<W>::infinity;
        for (std::size_t a = 0; a < m; ++a)
            for (std::size_t b = a + 1; b < m; ++b)
                for (std::size_t c = b + 1; c < m; ++c) {
                    if (m > all_triples && c != b + 1) break;
                    best = std::min(best, distance_to_triangle(v[i], v[ring[a]], v[ring[b]], v[ring[c]]));
                }
        return cost[i] = best;
    };
    std::vector<std::size_t> order;
    for (std::size_t f = 0; f < faces.size(); ++f)
        if (bad_face[f]) order.push_back(f);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return face_area[a] < face_area[b]; });
    std::vector<bool> drop(v.size(), false), spared(v.size(), false);
    for (std::size_t f : order) {
        std::uint32_t cheapest = faces[f][0];
        for (std::uint32_t i : faces[f])
            if (removal_cost(i) < removal_cost(cheapest)) cheapest = i;
        if (spared[cheapest]) continue;
        drop[cheapest] = spared[cheapest] = true;
        for (std::uint32_t j : neighbours[cheapest]) spared[j] = true;
    }
    return drop;
}

/// Step 4 of make_convex_hull: Quickhull over `candidates` of the centred points q (starting at
/// `simplex`), then drop vertices of faces too small for ConvexPolyhedron<T> (`rounded`: the
/// points as it will see them) and rebuild from the remaining vertices until none is left (see
/// the top of the file). Each round drops at least one vertex, so the loop ends. A mesh torn by
/// round-off (not seen in testing) is rebuilt with thicker faces. Returns the faces' vertex loops.
template <class T, class W>
std::vector<std::vector<std::uint32_t>> hull_faces(const std::vector<Vec3<W>>& q, const std::vector<Vec3<W>>& rounded,
                                                   std::vector<std::uint32_t> candidates, HullSimplex<W> simplex, W tolerance) {
    const char* where = "make_convex_hull";
    const std::size_t n = q.size();
    const W flat = W(64) * tolerance;  // ConvexPolyhedron's tolerance
    std::vector<std::vector<std::uint32_t>> faces;
    constexpr int max_rounds = 1000;
    for (int round = 0;; ++round) {
        bool built = false;
        W thickness = tolerance;
        for (int attempt = 0; attempt < 3 && !built; ++attempt, thickness *= W(4)) {
            QuickHullBuilder<W> builder(q, thickness);
            built = builder.build(candidates, simplex.index);
            if (built) faces = builder.face_loops();
        }
        if (!built)
            report_invalid(where, "could not build a consistent hull (round-off defeated every tolerance); point count",
                           static_cast<double>(n));
        remove_straight_edge_vertices(faces, n);

        const HullCheck<W> check = check_hull_faces<T>(rounded, faces);
        if (!(check.volume > check.min_volume))
            report_invalid(where, "points are collinear or coplanar within tolerance; hull volume (m^3)", check.volume);
        if (check.all_faces_good) return faces;
        if (round == max_rounds)
            report_invalid(where, "could not reduce the hull to faces ConvexPolyhedron can represent; point count",
                           static_cast<double>(n));

        const std::vector<bool> drop = vertices_to_drop(rounded, faces, check.area, check.bad_face);
        std::vector<bool> on_hull(n, false);
        for (const auto& face : faces)
            for (std::uint32_t i : face) on_hull[i] = true;
        candidates.clear();
        for (std::uint32_t i = 0; i < n; ++i)
            if (on_hull[i] && !drop[i]) candidates.push_back(i);
        if (candidates.size() < 4)
            report_invalid(where, "points are coplanar within tolerance; usable vertex count",
                           static_cast<double>(candidates.size()));
        simplex = hull_simplex(q, candidates);
        if (!(simplex.line_distance > flat && simplex.plane_distance > flat))
            report_invalid(where, "points are coplanar within tolerance; largest distance from their plane (m)",
                           simplex.plane_distance);
    }
}

}  // namespace detail

template <class T>
ConvexHull<T> make_convex_hull(const std::vector<Vec3<T>>& points) {
    //  1. Check the input: count, finiteness, magnitude.
    //  2. Centre on the bounding box; reject coincident points; set ε.
    //  3. Find the starting tetrahedron; reject collinear and coplanar clouds.
    //  4. Quickhull; drop vertices of faces ConvexPolyhedron<T> would reject and rebuild.
    //  5. Build the polyhedron at the box centre and re-centre it on its centroid.
    // Decided in double for both scalar types; see "Precision" at the top of the file.
    using W = double;
    const char* where = "make_convex_hull";

    // 1. Input at the door.
    const std::size_t n = points.size();
    if (n < 4) detail::report_invalid(where, "needs at least 4 points, point count", static_cast<double>(n));
    if (n >= std::size_t(0xffffffffu))
        detail::report_invalid(where, "needs fewer than 2^32 - 1 points, point count", static_cast<double>(n));
    Aabb<T> bounds;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3<T>& p = points[i];
        if (!is_finite(p)) detail::require_finite_xyz(p, where, ("point " + std::to_string(i)).c_str());
        bounds.merge(p);
    }
    const T largest = std::max(max_component(abs(bounds.min)), max_component(abs(bounds.max)));
    if (largest > std::sqrt(ScalarTraits<T>::max) / T(64))
        detail::report_invalid(where, "has coordinates too large to square in this precision; largest |coordinate| (m)",
                               static_cast<double>(largest));

    // 2. Centre on the bounding box (ConvexPolyhedron's Newell sums lose a face's normal to
    // round-off when the coordinates dwarf the cloud) and measure the cloud.
    const Vec3<T> centre = bounds.center();
    const Vec3<W> centre_w(centre);
    std::vector<Vec3<W>> q(n);
    for (std::size_t i = 0; i < n; ++i) q[i] = Vec3<W>(points[i]) - centre_w;
    const W diagonal = length(Vec3<W>(bounds.max) - Vec3<W>(bounds.min));
    // Coincident: the whole cloud within a few rounding units of its coordinates, or too small
    // for squared lengths to stay normal numbers.
    const W rounding = W(4) * W(ScalarTraits<T>::epsilon) * W(largest);
    if (!(diagonal > rounding) || !(diagonal > W(std::sqrt(std::numeric_limits<T>::min()))))
        detail::report_invalid(where, "points all coincide; bounding-box diagonal (m)", diagonal);
    const W tolerance = W(ScalarTraits<T>::geometric_tolerance) * diagonal;  // ε, a face's thickness
    const W flat = W(64) * tolerance;                                        // ConvexPolyhedron's tolerance

    // 3. The starting tetrahedron; a cloud that has none is collinear or coplanar.
    std::vector<std::uint32_t> candidates(n);
    for (std::size_t i = 0; i < n; ++i) candidates[i] = static_cast<std::uint32_t>(i);
    detail::HullSimplex<W> simplex = detail::hull_simplex(q, candidates);
    if (!(simplex.line_distance > flat))
        detail::report_invalid(where, "points are collinear; largest distance from their line (m)", simplex.line_distance);
    if (!(simplex.plane_distance > flat))
        detail::report_invalid(where, "points are coplanar; largest distance from their plane (m)", simplex.plane_distance);

    // 4. Quickhull, then drop vertices of faces too small for ConvexPolyhedron<T> and rebuild.
    std::vector<Vec3<W>> rounded(n);  // what ConvexPolyhedron<T> will see: p - centre in T
    for (std::size_t i = 0; i < n; ++i) rounded[i] = Vec3<W>(points[i] - centre);
    std::vector<std::vector<std::uint32_t>> faces = detail::hull_faces<T>(q, rounded, std::move(candidates), simplex, tolerance);

    // 5. The polyhedron, on compact vertex indices, then re-centred on its centroid.
    std::vector<std::uint32_t> index_of(n, 0xffffffffu);
    std::vector<Vec3<T>> vertices;
    for (auto& face : faces)
        for (std::uint32_t& i : face) {
            if (index_of[i] == 0xffffffffu) {
                index_of[i] = static_cast<std::uint32_t>(vertices.size());
                vertices.push_back(points[i] - centre);
            }
            i = index_of[i];
        }
    const ConvexPolyhedron<T> at_box_centre(std::move(vertices), faces);
    std::pair<ConvexPolyhedron<T>, Vec3<T>> centred = at_box_centre.recentered();
    return ConvexHull<T>{std::move(centred.first), centre + centred.second};
}

namespace f32 {
using ConvexHull = xeno::ConvexHull<float>;
}
namespace f64 {
using ConvexHull = xeno::ConvexHull<double>;
}

#ifdef XENO_COMPILED_LIB
// Compiled mode (compiled.hpp): float and double are compiled once, in src/xeno_compiled.cpp.
extern template ConvexHull<float> make_convex_hull<float>(const std::vector<Vec3<float>>&);
extern template ConvexHull<double> make_convex_hull<double>(const std::vector<Vec3<double>>&);
#endif

}  // namespace xeno

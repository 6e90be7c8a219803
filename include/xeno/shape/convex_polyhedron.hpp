// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// ConvexPolyhedron<T>: a convex polytope given by vertices and polygon faces, the thesis's
// PolygonalShape (3.2.2.4) grown up. Faces list vertex indices counter-clockwise seen from outside
// and carry an outward unit normal and plane offset (n·p = offset on the face). The constructor
// checks what the narrow phase and the mass integration rely on: finite vertices, a closed surface
// (every edge shared by exactly two faces, in opposite directions), planar faces, and convexity
// (every vertex on or behind every face plane, asked of a tree of vertex boxes so that it costs
// n log n, not vertices × faces). Adjacency (vertex → neighbours, vertex → faces, unique edges)
// is built once.
//
// Support: a linear scan over the vertices for small hulls (what the thesis did, Quadro 14, and the
// fastest choice below a few dozen vertices); for large ones hill climbing over the vertex graph
// (thesis 3.4), which on a convex polytope stops only at a global maximum.
//
// The local origin is not required to be inside: interior_point() returns the volume centroid,
// which is. Builders (convex_hull.hpp, the make_* functions) re-centre on the centroid so the local
// origin is the centre of mass, as bodies expect (docs/conventions.md, "Frames").
#pragma once

#include "../error.hpp"
#include "../math/aabb.hpp"
#include "../math/wide.hpp"
#include "mass_properties.hpp"
#include "support_face.hpp"

#include <optional>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace xeno {

namespace detail {

/// The vertices of a polyhedron in a balanced tree of oriented boxes, so that the constructor's
/// convexity check ("no vertex in front of any face plane") costs about log n box tests per face
/// instead of n dot products (the plain double loop made a 40k-vertex hull take 17 s).
///
/// Each node bounds its vertices by intervals along its own orthonormal frame, whose third axis
/// points from the middle of the whole cloud to the node's. Deep nodes hold small patches of the
/// surface, flat in that frame: a face plane can then reach only the few boxes near the face,
/// where axis-aligned boxes, as thick as they are wide, would be reached by √n leaves per face.
/// The box bound is computed in T; it exceeds the value computed for any vertex of the box by
/// at most a few rounding units of the vertices' size, and a margin of 64 units covers that,
/// so the tree answers exactly what the double loop answered.
template <class T>
class VertexBoxTree {
public:
    explicit VertexBoxTree(const std::vector<Vec3<T>>& vertices);
    /// Whether some vertex v has dot(normal, v) - offset > tolerance (normal of unit length).
    bool any_in_front(const Vec3<T>& normal, T offset, T tolerance) const;

private:
    static constexpr std::uint32_t leaf_size = 8;
    static constexpr std::uint32_t no_child = 0xffffffffu;
    struct Node {
        Vec3<T> axis[3];             // orthonormal frame
        T low[3], high[3];           // range of dot(axis[i], v) over the node's vertices
        std::uint32_t begin, end;    // into points_
        std::uint32_t second_child;  // the first is the next node; no_child for a leaf
    };
    std::uint32_t add_node(std::uint32_t begin, std::uint32_t end, const Vec3<T>& middle_of_all);

    std::vector<Vec3<T>> points_;  // the vertices, each node's a contiguous range
    std::vector<Node> nodes_;      // depth first: a subtree is contiguous, kind to the cache
    T margin_ = T(0);              // metres: rounding allowance of the box bounds
};

template <class T>
VertexBoxTree<T>::VertexBoxTree(const std::vector<Vec3<T>>& vertices) : points_(vertices) {
    Aabb<T> all;
    T radius = T(0);
    for (const Vec3<T>& v : vertices) {
        all.merge(v);
        radius = std::max(radius, length(v));
    }
    margin_ = T(64) * ScalarTraits<T>::epsilon * radius;
    nodes_.reserve(4 * (points_.size() / leaf_size + 1));
    add_node(0, static_cast<std::uint32_t>(points_.size()), all.center());
}

template <class T>
std::uint32_t VertexBoxTree<T>::add_node(std::uint32_t begin, std::uint32_t end, const Vec3<T>& middle_of_all) {
    // The node is bounded in its frame, then split at the median along the frame axis of its
    // widest extent: a balanced tree (depth log2(n / leaf_size), so this recursion is shallow)
    // of compact patches.
    Node node{};
    node.begin = begin;
    node.end = end;
    node.second_child = no_child;
    Aabb<T> box;
    for (std::uint32_t k = begin; k < end; ++k) box.merge(points_[k]);
    node.axis[2] = try_normalized(box.center() - middle_of_all).value_or(Vec3<T>::unit_z());
    node.axis[0] = any_perpendicular(node.axis[2]);
    node.axis[1] = cross(node.axis[2], node.axis[0]);
    for (int i = 0; i < 3; ++i) {
        node.low[i] = ScalarTraits<T>::infinity;
        node.high[i] = -ScalarTraits<T>::infinity;
        for (std::uint32_t k = begin; k < end; ++k) {
            const T along = dot(node.axis[i], points_[k]);
            node.low[i] = std::min(node.low[i], along);
            node.high[i] = std::max(node.high[i], along);
        }
    }
    const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back(node);
    if (end - begin <= leaf_size) return index;
    const Vec3<T> extent{node.high[0] - node.low[0], node.high[1] - node.low[1], node.high[2] - node.low[2]};
    const Vec3<T> axis = node.axis[max_axis(extent)];
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(points_.begin() + begin, points_.begin() + middle, points_.begin() + end,
                     [&](const Vec3<T>& a, const Vec3<T>& b) { return dot(axis, a) < dot(axis, b); });
    add_node(begin, middle, middle_of_all);
    const std::uint32_t second = add_node(middle, end, middle_of_all);
    nodes_[index].second_child = second;
    return index;
}

template <class T>
bool VertexBoxTree<T>::any_in_front(const Vec3<T>& normal, T offset, T tolerance) const {
    // Depth first; a balanced tree of fewer than 2^32 vertices is at most 32 levels deep, and the
    // stack holds at most one waiting sibling per level.
    std::uint32_t stack[64];
    std::size_t size = 0;
    stack[size++] = 0;
    while (size > 0) {
        const std::uint32_t index = stack[--size];
        const Node& node = nodes_[index];
        T reach = margin_;  // the largest dot(normal, v) in the box, plus the margin
        for (int i = 0; i < 3; ++i) {
            const T along = dot(normal, node.axis[i]);
            reach += along * (along >= T(0) ? node.high[i] : node.low[i]);
        }
        if (!(reach - offset > tolerance)) continue;  // no vertex of the box is in front
        if (node.second_child == no_child) {
            for (std::uint32_t k = node.begin; k < node.end; ++k)
                if (dot(normal, points_[k]) - offset > tolerance) return true;
            continue;
        }
        stack[size++] = node.second_child;
        stack[size++] = index + 1;
    }
    return false;
}

}  // namespace detail

/// A closed convex polyhedron with polygon faces and adjacency.
template <class T>
class ConvexPolyhedron {
public:
    using scalar_type = T;

    /// One face: indices[first .. first + count) counter-clockwise from outside; plane n·p = offset.
    struct Face {
        std::uint32_t first;  ///< into face_indices()
        std::uint32_t count;  ///< >= 3
        Vec3<T> normal;       ///< unit, outward, local frame
        T offset;             ///< metres: n·p for any point p of the face
    };

    /// Above this many vertices support() climbs the vertex graph instead of scanning.
    static constexpr std::size_t hill_climb_threshold = 48;

    /// Builds from vertices (local frame, metres) and faces (vertex indices, counter-clockwise seen
    /// from outside). Rejects (InvalidArgument) non-finite vertices, fewer than 4 vertices or faces,
    /// bad indices, faces with < 3 vertices, zero-area or non-planar faces, an open surface, a
    /// non-convex shape or zero volume. Unused vertices are rejected too.
    ConvexPolyhedron(std::vector<Vec3<T>> vertices, const std::vector<std::vector<std::uint32_t>>& faces);

    const std::vector<Vec3<T>>& vertices() const { return vertices_; }
    const std::vector<Face>& faces() const { return faces_; }
    const std::vector<std::uint32_t>& face_indices() const { return face_indices_; }
    /// The i-th vertex of face f, in counter-clockwise order.
    const Vec3<T>& face_vertex(const Face& f, std::uint32_t i) const { return vertices_[face_indices_[f.first + i]]; }
    /// Unique edges as vertex index pairs (first < second).
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges() const { return edges_; }
    /// Vertices joined to vertex v by an edge: neighbor_indices()[neighbor_offsets()[v] .. [v + 1]).
    const std::vector<std::uint32_t>& neighbor_offsets() const { return neighbor_offsets_; }
    const std::vector<std::uint32_t>& neighbor_indices() const { return neighbors_; }

    /// Index of a vertex farthest along d (ties: any); d need not be unit.
    std::uint32_t support_index(const Vec3<T>& d) const {
        return vertices_.size() > hill_climb_threshold ? support_index_hill_climb(d, start_vertex(d)) : support_index_scan(d);
    }
    /// A good vertex to start climbing from: the extreme vertex of the axis direction (±x, ±y, ±z)
    /// closest to d, found once at construction.
    std::uint32_t start_vertex(const Vec3<T>& d) const {
        const Vec3<T> a = abs(d);
        const int axis = max_axis(a);
        return axis_extreme_[static_cast<std::size_t>(2 * axis + (d[axis] >= T(0) ? 0 : 1))];
    }
    /// Linear scan over all vertices (thesis Quadro 14).
    std::uint32_t support_index_scan(const Vec3<T>& d) const;
    /// Greedy ascent over the vertex graph from vertex `start`; exact on a convex polytope.
    /// Starting from the previous answer of a nearby direction (as MPR's successive portal
    /// normals are) makes it a few neighbour checks instead of a scan.
    std::uint32_t support_index_hill_climb(const Vec3<T>& d, std::uint32_t start = 0) const;
    /// The farthest point along d (local frame).
    Vec3<T> support(const Vec3<T>& d) const { return vertices_[support_index(d)]; }
    /// Among the faces touching the support vertex of d, the one whose normal is most aligned with d.
    SupportFace<T> support_face(const Vec3<T>& d) const;
    /// Index of that face in faces(); `start` seeds the support search (see hill climbing).
    std::uint32_t support_face_index(const Vec3<T>& d) const { return face_at_vertex(d, support_index(d)); }
    std::uint32_t support_face_index(const Vec3<T>& d, std::uint32_t start) const {
        return face_at_vertex(d, support_index_hill_climb(d, start));
    }
    /// Among the faces touching vertex v, the one whose normal is most aligned with d.
    std::uint32_t face_at_vertex(const Vec3<T>& d, std::uint32_t v) const;
    /// The outward normal of support_face(d) when that face is a polygon (3 or more vertices),
    /// else nothing: the narrow phase tries it as a contact normal without building the face.
    std::optional<Vec3<T>> flat_normal(const Vec3<T>& d) const { return faces_[support_face_index(d)].normal; }

    Aabb<T> local_bounds() const { return bounds_; }
    /// Radius about the local origin of a sphere holding every vertex.
    T bounding_radius() const { return radius_; }
    /// The volume centroid: strictly inside even when the local origin is not.
    Vec3<T> interior_point() const { return unit_mass_.center; }
    /// Half extents of a box centred on interior_point() that lies strictly inside the shape:
    /// the narrow phase moves its interior point within it toward a much smaller partner.
    Vec3<T> inner_half_extents() const { return inner_half_extents_; }
    T volume() const { return unit_mass_.mass; }
    /// Mass properties at density 1 (see mass_properties()).
    MassProperties<T> unit_mass_properties() const { return unit_mass_; }

    /// The same polyhedron moved by -interior_point(), so its centroid is the local origin; the
    /// shift that was subtracted is returned beside it.
    std::pair<ConvexPolyhedron, Vec3<T>> recentered() const;

private:
    std::vector<Vec3<T>> vertices_;
    std::vector<T> xs_, ys_, zs_;  // the vertices again as coordinate arrays for the scan, padded to 8k
    std::vector<std::uint32_t> face_indices_;
    std::uint32_t axis_extreme_[6] = {};  // support vertices of +x, -x, +y, -y, +z, -z
    std::vector<Face> faces_;
    std::vector<std::uint32_t> neighbor_offsets_, neighbors_;        // CSR: vertex -> vertices
    std::vector<std::uint32_t> vertex_face_offsets_, vertex_faces_;  // CSR: vertex -> faces
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges_;
    Aabb<T> bounds_;
    T radius_{};
    MassProperties<T> unit_mass_;
    Vec3<T> inner_half_extents_;
};

template <class T>
ConvexPolyhedron<T>::ConvexPolyhedron(std::vector<Vec3<T>> vertices, const std::vector<std::vector<std::uint32_t>>& faces)
    : vertices_(std::move(vertices)) {
    const char* where = "ConvexPolyhedron";
    const std::size_t n = vertices_.size();
    if (n < 4) detail::report_invalid(where, "needs at least 4 vertices, vertex count", static_cast<double>(n));
    if (faces.size() < 4) detail::report_invalid(where, "needs at least 4 faces, face count", static_cast<double>(faces.size()));
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3<T>& v = vertices_[i];
        if (!is_finite(v)) detail::require_finite_xyz(v, where, ("vertex " + std::to_string(i)).c_str());
        bounds_.merge(v);
        radius_ = std::max(radius_, length(v));
    }
    for (int i = 0; i < 6; ++i) {
        const Vec3<T> axis = Vec3<T>::axis(i / 2) * (i % 2 == 0 ? T(1) : T(-1));
        std::uint32_t best = 0;
        for (std::uint32_t k = 1; k < n; ++k)
            if (dot(vertices_[k], axis) > dot(vertices_[best], axis)) best = k;
        axis_extreme_[i] = best;
    }
    for (std::size_t i = 0; i < (n + 7) / 8 * 8; ++i) {  // whole runs of the widest lanes (wide.hpp)
        const Vec3<T>& v = vertices_[i < n ? i : 0];
        xs_.push_back(v.x);
        ys_.push_back(v.y);
        zs_.push_back(v.z);
    }
    const T scale = length(bounds_.max - bounds_.min);
    // The size of the polyhedron (and its distance from the local origin) must be one the narrow
    // phase can compute in (ScalarTraits<T>::min_size, max_size).
    detail::require_size(scale, where, "size (bounding-box diagonal)");
    if (radius_ > ScalarTraits<T>::max_size) detail::require_size(radius_, where, "distance of a vertex from the local origin");
    const T tolerance = T(64) * ScalarTraits<T>::geometric_tolerance * scale;

    // Faces: indices, normals (Newell's method: robust for any planar polygon), planarity.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> directed_edges;
    T area = T(0);  // m², the surface's
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const std::vector<std::uint32_t>& face = faces[f];
        const std::string face_name = "face " + std::to_string(f);
        if (face.size() < 3)
            detail::report_invalid(where, (face_name + " needs 3 or more vertices, count").c_str(),
                                   static_cast<double>(face.size()));
        // Every index checked before any is used: each edge reads the next vertex too (an
        // out-of-range last index was read before it was checked; found by AddressSanitizer).
        for (std::uint32_t index : face)
            if (index >= n)
                detail::report_invalid(where, (face_name + " has a vertex index out of range").c_str(),
                                       static_cast<double>(index));
        // A vertex listed twice makes an edge from it to itself, which the closure check below
        // let pass and the edge list left out ({0, 4, 4, 6, 2} on a cube was accepted).
        std::vector<std::uint32_t> sorted(face);
        std::sort(sorted.begin(), sorted.end());
        const auto repeat = std::adjacent_find(sorted.begin(), sorted.end());
        if (repeat != sorted.end())
            detail::report_invalid(where, (face_name + " lists a vertex twice; vertex").c_str(), static_cast<double>(*repeat));
        Vec3<T> newell = Vec3<T>::zero(), centre = Vec3<T>::zero();
        T longest_edge = T(0);
        for (std::size_t k = 0; k < face.size(); ++k) {
            const Vec3<T>& p = vertices_[face[k]];
            const Vec3<T>& q = vertices_[face[(k + 1) % face.size()]];
            newell += cross(p, q);
            centre += p;
            longest_edge = std::max(longest_edge, length(q - p));
            directed_edges.emplace_back(face[k], face[(k + 1) % face.size()]);
        }
        centre /= static_cast<T>(face.size());
        area += length(newell) / T(2);
        // A face is degenerate when it is thinner than the tolerance (twice its area over its
        // longest edge): small but well-shaped faces are fine, slivers are not.
        const std::optional<Vec3<T>> normal = try_normalized(newell);
        if (!normal || !(length(newell) > tolerance * longest_edge))
            detail::report_invalid(where, (face_name + " is degenerate (zero area or a sliver); its width (m)").c_str(),
                                   static_cast<double>(longest_edge > T(0) ? length(newell) / longest_edge : T(0)));
        Face out{static_cast<std::uint32_t>(face_indices_.size()), static_cast<std::uint32_t>(face.size()), *normal,
                 dot(*normal, centre)};
        for (std::uint32_t index : face) {
            const T off_plane = dot(*normal, vertices_[index]) - out.offset;
            if (std::abs(off_plane) > tolerance)
                detail::report_invalid(where, (face_name + " is not planar; a vertex is off its plane by (m)").c_str(),
                                       static_cast<double>(off_plane));
            face_indices_.push_back(index);
        }
        faces_.push_back(out);
    }

    // Closed: every directed edge appears once and its reverse once.
    std::sort(directed_edges.begin(), directed_edges.end());
    for (std::size_t i = 0; i + 1 < directed_edges.size(); ++i)
        if (directed_edges[i] == directed_edges[i + 1])
            detail::report_invalid(
                where, "is not a closed 2-manifold (an edge is used twice in one direction; check face winding), vertex",
                static_cast<double>(directed_edges[i].first));
    // Each edge's reverse is there when the reversed edges, sorted, are the same list (one sort
    // instead of a binary search per edge); else the search finds the edge to report.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> reversed;
    reversed.reserve(directed_edges.size());
    for (const auto& e : directed_edges) reversed.emplace_back(e.second, e.first);
    std::sort(reversed.begin(), reversed.end());
    const bool closed = reversed == directed_edges;
    for (const auto& e : directed_edges) {
        if (!closed && !std::binary_search(directed_edges.begin(), directed_edges.end(), std::make_pair(e.second, e.first)))
            detail::report_invalid(where, "is not closed (an edge belongs to only one face), vertex",
                                   static_cast<double>(e.first));
        if (e.first < e.second) edges_.push_back(e);
    }

    // Convex: no vertex in front of any face plane. The box tree finds the faces that fail; the
    // scan of such a face only picks the vertex to report (the first, in index order).
    const detail::VertexBoxTree<T> vertex_tree(vertices_);
    for (const Face& f : faces_) {
        if (!vertex_tree.any_in_front(f.normal, f.offset, tolerance)) continue;
        for (const Vec3<T>& v : vertices_)
            if (dot(f.normal, v) - f.offset > tolerance)
                detail::report_invalid(where, "is not convex; a vertex lies in front of a face plane by (m)",
                                       static_cast<double>(dot(f.normal, v) - f.offset));
    }

    // Adjacency in compressed rows.
    std::vector<std::uint32_t> degree(n, 0), face_degree(n, 0);
    for (const auto& e : edges_) {
        ++degree[e.first];
        ++degree[e.second];
    }
    for (std::uint32_t index : face_indices_) ++face_degree[index];
    neighbor_offsets_.assign(n + 1, 0);
    vertex_face_offsets_.assign(n + 1, 0);
    for (std::size_t v = 0; v < n; ++v) {
        if (degree[v] == 0) detail::report_invalid(where, "has a vertex that no face uses, vertex", static_cast<double>(v));
        neighbor_offsets_[v + 1] = neighbor_offsets_[v] + degree[v];
        vertex_face_offsets_[v + 1] = vertex_face_offsets_[v] + face_degree[v];
    }
    // One surface: every face pairs its edges with its neighbours', but two shells (a doubled
    // surface, a copy inside the other) would too. Euler's formula V − E + F = 2 holds for one
    // closed surface of genus 0 (a convex one) and gives 4 for two.
    const long euler = static_cast<long>(n) - static_cast<long>(edges_.size()) + static_cast<long>(faces_.size());
    if (euler != 2)
        detail::report_invalid(
            where, "is not one closed surface (V - E + F must be 2: two shells, e.g. a doubled or nested copy?); V - E + F",
            static_cast<double>(euler));
    neighbors_.resize(neighbor_offsets_[n]);
    vertex_faces_.resize(vertex_face_offsets_[n]);
    std::vector<std::uint32_t> fill(neighbor_offsets_.begin(), neighbor_offsets_.end() - 1);
    for (const auto& e : edges_) {
        neighbors_[fill[e.first]++] = e.second;
        neighbors_[fill[e.second]++] = e.first;
    }
    fill.assign(vertex_face_offsets_.begin(), vertex_face_offsets_.end() - 1);
    for (std::uint32_t f = 0; f < faces_.size(); ++f)
        for (std::uint32_t k = 0; k < faces_[f].count; ++k) {
            const std::uint32_t v = face_indices_[faces_[f].first + k];
            vertex_faces_[fill[v]++] = f;
        }

    unit_mass_ = detail::polyhedron_unit_density(vertices_, face_indices_, faces_);
    // Zero volume: a mean thickness (2 V / area) within the tolerance, as a face's width. V above
    // tolerance × scale² (a plate's area) rejected every solid slimmer than 1:40 in float: a
    // 2 m × 5 cm × 5 cm plank was "zero volume".
    if (!(unit_mass_.mass > tolerance * std::max(area / T(2), tolerance * scale)))
        detail::report_invalid(where, "has zero volume; volume (m^3)", static_cast<double>(unit_mass_.mass));

    // The bounding box's shape scaled about the centroid until a corner meets a face plane,
    // then every side pulled in by a tenth of the smallest: a box strictly inside.
    const Vec3<T> c = unit_mass_.center, e = bounds_.half_extents();
    T fit = ScalarTraits<T>::infinity;
    for (const Face& f : faces_)
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3<T> offset{(corner & 1) ? e.x : -e.x, (corner & 2) ? e.y : -e.y, (corner & 4) ? e.z : -e.z};
            const T reach = dot(f.normal, offset);
            if (reach > T(0)) fit = std::min(fit, (f.offset - dot(f.normal, c)) / reach);
        }
    inner_half_extents_ = e * fit - Vec3<T>::one() * (T(0.1) * fit * min_component(e));
}

// W running maxima in SIMD lanes (wide.hpp: 4 / 8 floats, 2 / 4 doubles, 1 without SIMD) over the
// coordinate arrays, padded with copies of vertex 0. Each dot product is x·dx + y·dy + z·dz in
// that order whatever W, a lane keeps its first maximum (strict >) and the lanes are merged
// keeping the lowest index among equal values, so every width returns the same vertex. Indices
// ride in the lanes as numbers of type T: exact below 2^24 vertices in float, far past any hull.
template <class T>
std::uint32_t ConvexPolyhedron<T>::support_index_scan(const Vec3<T>& d) const {
    constexpr int W = detail::native_width<T>();
    using V = detail::Wide<T, W>;
    const V dx = V::splat(d.x), dy = V::splat(d.y), dz = V::splat(d.z), step = V::splat(T(W));
    V best = V::splat(-ScalarTraits<T>::infinity), index = V::splat(T(0)), lane_index = V::splat(T(0));
    for (int l = 0; l < W; ++l) lane_index.set(l, T(l));
    const std::size_t padded = xs_.size();
    for (std::size_t i = 0; i < padded; i += W) {
        const V value = V::loadu(&xs_[i]) * dx + V::loadu(&ys_[i]) * dy + V::loadu(&zs_[i]) * dz;
        const typename V::Mask better = value > best;
        best = select(better, value, best);
        index = select(better, lane_index, index);
        lane_index = lane_index + step;
    }
    std::uint32_t result = static_cast<std::uint32_t>(index.get(0));
    T result_value = best.get(0);
    for (int l = 1; l < W; ++l) {
        const std::uint32_t k = static_cast<std::uint32_t>(index.get(l));
        if (best.get(l) > result_value || (best.get(l) == result_value && k < result)) result_value = best.get(l), result = k;
    }
    return result < vertices_.size() ? result : 0;
}

template <class T>
std::uint32_t ConvexPolyhedron<T>::support_index_hill_climb(const Vec3<T>& d, std::uint32_t start) const {
    // Each move strictly increases the value, so the walk ends; on a convex polytope a vertex
    // with no better neighbour is a global maximum. The cap only guards against a NaN direction.
    std::uint32_t current = start < vertices_.size() ? start : 0;
    T current_value = dot(vertices_[current], d);
    for (std::size_t steps = 0; steps < vertices_.size(); ++steps) {
        std::uint32_t best = current;
        for (std::uint32_t k = neighbor_offsets_[current]; k < neighbor_offsets_[current + 1]; ++k) {
            const T value = dot(vertices_[neighbors_[k]], d);
            if (value > current_value) {
                current_value = value;
                best = neighbors_[k];
            }
        }
        if (best == current) break;
        current = best;
    }
    return current;
}

template <class T>
std::uint32_t ConvexPolyhedron<T>::face_at_vertex(const Vec3<T>& d, std::uint32_t v) const {
    std::uint32_t best = vertex_faces_[vertex_face_offsets_[v]];
    T best_alignment = dot(faces_[best].normal, d);
    for (std::uint32_t k = vertex_face_offsets_[v] + 1; k < vertex_face_offsets_[v + 1]; ++k) {
        const T alignment = dot(faces_[vertex_faces_[k]].normal, d);
        if (alignment > best_alignment) {
            best_alignment = alignment;
            best = vertex_faces_[k];
        }
    }
    return best;
}

template <class T>
SupportFace<T> ConvexPolyhedron<T>::support_face(const Vec3<T>& d) const {
    const Face& f = faces_[support_face_index(d)];
    SupportFace<T> out;
    out.normal = f.normal;
    // Faces larger than the capacity are thinned evenly; the kept vertices stay in order.
    const std::uint32_t keep = std::min<std::uint32_t>(f.count, SupportFace<T>::capacity);
    for (std::uint32_t k = 0; k < keep; ++k) out.push(face_vertex(f, k * f.count / keep));
    return out;
}

template <class T>
std::pair<ConvexPolyhedron<T>, Vec3<T>> ConvexPolyhedron<T>::recentered() const {
    const Vec3<T> shift = interior_point();
    std::vector<Vec3<T>> moved(vertices_);
    for (Vec3<T>& v : moved) v -= shift;
    std::vector<std::vector<std::uint32_t>> faces;
    faces.reserve(faces_.size());
    for (const Face& f : faces_) faces.emplace_back(face_indices_.begin() + f.first, face_indices_.begin() + f.first + f.count);
    return {ConvexPolyhedron(std::move(moved), faces), shift};
}

namespace f32 {
using ConvexPolyhedron = xeno::ConvexPolyhedron<float>;
}
namespace f64 {
using ConvexPolyhedron = xeno::ConvexPolyhedron<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// TriangleMesh and HeightField on their own: input checks, what the build drops, active edges
// against hand-worked cases, box and ray queries against brute force over every triangle, and rays
// aimed at a grid's shared edges and corners (watertight ray casts).
#include "support/approx.hpp"
#include "support/flat_level.hpp"

#include <xeno/xeno.hpp>

#include <doctest/doctest.h>

#include <random>
#include <set>

using namespace xeno;
using xeno::test::grid_mesh;
using xeno::test::near;
using Tri = std::array<std::uint32_t, 3>;

namespace {

template <class T>
Aabb<T> box_of(const MeshTriangle<T>& t) {
    Aabb<T> b;
    for (const Vec3<T>& v : t.v) b.merge(v);
    return b;
}

}  // namespace

TEST_CASE_TEMPLATE("a triangle mesh rejects bad input and drops degenerate and duplicate triangles", T, float, double) {
    const std::vector<Vec3<T>> v{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {2, 0, 0}, {1, 0, 1}};
    CHECK_THROWS_AS(TriangleMesh<T>(v, {{0, 1, 7}}), InvalidArgument);  // index past the vertices
    std::vector<Vec3<T>> bad = v;
    bad[2].y = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_AS(TriangleMesh<T>(bad, {{0, 2, 1}}), InvalidArgument);
    CHECK_THROWS_AS(TriangleMesh<T>(v, {{0, 1, 3}}), InvalidArgument);  // collinear: nothing left
    CHECK_THROWS_AS(TriangleMesh<T>(v, {}), InvalidArgument);
    // One good triangle, the same one again (other winding, other start), a collinear one and a
    // repeated corner: one triangle stays.
    const TriangleMesh<T> m(v, {{0, 2, 1}, {1, 0, 2}, {0, 1, 3}, {1, 1, 2}, {1, 2, 0}});
    CHECK(m.size() == 1);
    CHECK(m.dropped_triangles() == 4);
    CHECK(m.source_index(0) == 0);
    CHECK(near(m.triangle(0).normal, Vec3<T>{0, 1, 0}));
    // Corners at the same place under different indices are welded: these two are duplicates.
    const std::vector<Vec3<T>> split{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    CHECK(TriangleMesh<T>(split, {{0, 2, 1}, {3, 5, 4}}).size() == 1);
}

TEST_CASE_TEMPLATE("edges between coplanar or concave neighbours are inactive, convex and border edges active", T, float,
                   double) {
    // A flat grid: every inner edge is between coplanar triangles.
    const TriangleMesh<T> flat = grid_mesh<T>(4, T(1), [](T, T) { return T(0); });
    int active = 0, border = 0;
    for (std::uint32_t k = 0; k < flat.size(); ++k) {
        const MeshTriangle<T> t = flat.triangle(k);
        for (int e = 0; e < 3; ++e) {
            const Vec3<T> mid = (t.v[e] + t.v[(e + 1) % 3]) * T(0.5);
            const bool on_border = std::abs(mid.x) == T(2) || std::abs(mid.z) == T(2);
            active += (t.active_edges >> e) & 1;
            border += on_border;
            CHECK(((t.active_edges >> e & 1) != 0) == on_border);
            CHECK(t.fold_cos[e] == (on_border ? T(-1) : T(1)));  // a border may turn any way; coplanar: no fold
        }
    }
    CHECK(active == 16);  // the 4 × 4 border edges
    CHECK(border == 16);
    // A ridge along z at x = 0 (a roof, convex), and a valley (concave).
    for (const T sign : {T(1), T(-1)}) {
        const TriangleMesh<T> fold = grid_mesh<T>(2, T(1), [sign](T x, T) { return -sign * T(0.5) * std::abs(x); });
        int folds = 0;
        for (std::uint32_t k = 0; k < fold.size(); ++k) {
            const MeshTriangle<T> t = fold.triangle(k);
            for (int e = 0; e < 3; ++e) {
                const Vec3<T>& p = t.v[e];
                const Vec3<T>& q = t.v[(e + 1) % 3];
                if (p.x != T(0) || q.x != T(0)) continue;  // not the fold
                ++folds;
                CAPTURE(sign);
                CHECK(((t.active_edges >> e & 1) != 0) == (sign > T(0)));  // only the ridge's fold is active
                // Slopes of 1:2 either side: the normals are 2 atan(1/2) apart, cos = 0.6.
                CHECK(near(t.fold_cos[e], T(0.6), T(1e-5)));
            }
        }
        CHECK(folds == 4);  // two edges along the fold, seen from both sides
    }
}

TEST_CASE_TEMPLATE("mesh box and ray queries find what brute force over every triangle finds", T, float, double) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    auto r = [&]() { return static_cast<T>(u(rng)); };
    std::vector<Vec3<T>> v;
    std::vector<Tri> tris;
    for (std::uint32_t k = 0; k < 600; ++k) {
        const Vec3<T> c{r(), r(), r()};
        for (int i = 0; i < 3; ++i) v.push_back(c + Vec3<T>{r(), r(), r()} * T(0.1));
        tris.push_back({3 * k, 3 * k + 1, 3 * k + 2});
    }
    const TriangleMesh<T> mesh(v, tris);
    REQUIRE(mesh.size() == 600);
    std::vector<MeshTriangle<T>> by_source(600);
    for (std::uint32_t k = 0; k < mesh.size(); ++k) by_source[mesh.source_index(k)] = mesh.triangle(k);
    for (int q = 0; q < 200; ++q) {
        const Vec3<T> c{r(), r(), r()};
        const Aabb<T> box = Aabb<T>::from_center(c, Vec3<T>{T(1.5), T(2), T(1)});
        std::set<std::uint32_t> found, expected;
        mesh.for_each_triangle(box, [&](std::uint32_t k, const MeshTriangle<T>&) { CHECK(found.insert(k).second); });
        for (std::uint32_t k = 0; k < 600; ++k)
            if (overlaps(box_of(by_source[k]), box)) expected.insert(k);
        CHECK(found == expected);
        // A ray from c in a random direction: the nearest hit over all triangles.
        const Ray<T> ray{c, normalized(Vec3<T>{r(), r(), r()}), T(30)};
        std::optional<T> nearest;
        for (const MeshTriangle<T>& t : by_source)
            if (const std::optional<T> d = detail::ray_triangle(ray, t.v[0], t.v[1], t.v[2]))
                if (!nearest || *d < *nearest) nearest = d;
        const auto hit = mesh.raycast(ray);
        REQUIRE(hit.has_value() == nearest.has_value());
        if (hit) CHECK(hit->first.distance == *nearest);
    }
}

TEST_CASE_TEMPLATE("a heightfield has the triangles and active edges of the same grid built as a mesh", T, float, double) {
    const auto height = [](T x, T z) { return T(0.3) * std::sin(T(0.9) * x) + T(0.2) * std::cos(T(1.3) * z) + T(0.1) * x; };
    const int n = 6;
    std::vector<T> heights;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) heights.push_back(height(static_cast<T>(i) - T(3), static_cast<T>(j) - T(3)));
    const HeightField<T> field(n + 1, n + 1, heights, T(1));
    const TriangleMesh<T> mesh = grid_mesh<T>(n, T(1), height);
    REQUIRE(field.size() == mesh.size());
    for (std::uint32_t k = 0; k < mesh.size(); ++k) {
        const MeshTriangle<T> m = mesh.triangle(k);
        const MeshTriangle<T> f = field.triangle(mesh.source_index(k));  // the same numbering, cell by cell
        CAPTURE(k);
        for (int i = 0; i < 3; ++i) CHECK(near(m.v[i], f.v[i], T(1e-5)));
        CHECK(m.active_edges == f.active_edges);
        for (int e = 0; e < 3; ++e) CHECK(near(m.fold_cos[e], f.fold_cos[e], T(1e-5)));
    }
    // Box queries agree too.
    const Aabb<T> box{{T(-1.2), T(-5), T(0.3)}, {T(0.7), T(5), T(1.9)}};
    std::set<std::uint32_t> from_field, from_mesh;
    field.for_each_triangle(box, [&](std::uint32_t k, const MeshTriangle<T>&) { from_field.insert(k); });
    mesh.for_each_triangle(box, [&](std::uint32_t k, const MeshTriangle<T>&) { from_mesh.insert(k); });
    CHECK(from_field == from_mesh);
    // A vertical ray lands on the surface: at a sample, the sample's height.
    const auto hit = field.raycast(Ray<T>{{T(1), T(10), T(-2)}, {T(0), T(-1), T(0)}, T(100)});
    REQUIRE(hit);
    CHECK(near(hit->first.point.y, height(T(1), T(-2)), T(1e-5)));
    CHECK(hit->first.normal.y > T(0));
}

TEST_CASE_TEMPLATE("a heightfield rejects bad input, and its holes have no triangles", T, float, double) {
    CHECK_THROWS_AS(HeightField<T>(1, 4, std::vector<T>(4, T(0)), T(1)), InvalidArgument);
    CHECK_THROWS_AS(HeightField<T>(3, 3, std::vector<T>(8, T(0)), T(1)), InvalidArgument);
    CHECK_THROWS_AS(HeightField<T>(3, 3, std::vector<T>(9, T(0)), T(0)), InvalidArgument);
    CHECK_THROWS_AS(HeightField<T>(3, 3, std::vector<T>(9, std::numeric_limits<T>::infinity()), T(1)), InvalidArgument);
    CHECK_THROWS_AS(HeightField<T>(3, 3, std::vector<T>(9, T(0)), T(1), std::vector<std::uint8_t>(3, 0)), InvalidArgument);
    std::vector<std::uint8_t> holes(4, 0);
    holes[3] = 1;  // cell (1, 1)
    const HeightField<T> field(3, 3, std::vector<T>(9, T(0)), T(1), holes);
    int seen = 0;
    field.for_each_triangle(field.local_bounds().expanded(T(1)), [&](std::uint32_t k, const MeshTriangle<T>& t) {
        ++seen;
        CHECK(k / 2 != 3);
        // Edges next to the hole are borders now: active.
        for (int e = 0; e < 3; ++e) {
            const Vec3<T> mid = (t.v[e] + t.v[(e + 1) % 3]) * T(0.5);
            const bool by_hole = (mid.x == T(0) && mid.z == T(0.5)) || (mid.z == T(0) && mid.x == T(0.5));
            if (by_hole) CHECK((t.active_edges >> e & 1) != 0);
        }
    });
    CHECK(seen == 6);
    CHECK_FALSE(field.raycast(Ray<T>{{T(0.5), T(3), T(0.5)}, {T(0), T(-1), T(0)}, T(10)}));  // through the hole
}

// regression: a cell whose heights step a thousand spacings or more was accepted with triangles
// of no normal (detail::triangle_normal's sliver test): rays hit it with a zero normal and
// bodies passed through. A step of 500 spacings is a steep cell, not a broken one.
TEST_CASE_TEMPLATE("a heightfield rejects a cell too steep for its spacing to have a normal", T, float, double) {
    std::vector<T> cliff(9, T(0));
    for (std::size_t j = 0; j < 3; ++j) cliff[j * 3 + 2] = T(1e6);
    CHECK_THROWS_AS(HeightField<T>(3, 3, cliff, T(1)), InvalidArgument);
    CHECK_THROWS_AS(HeightField<T>(3, 3, cliff, T(1), {0, 1, 0, 0}), InvalidArgument);  // one cliff cell left
    const HeightField<T> holed(3, 3, cliff, T(1), {0, 1, 0, 1});                        // both are holes
    CHECK(holed.size() == 8);
    std::vector<T> steep(9, T(0));
    steep[4] = T(500);
    const HeightField<T> peak(3, 3, steep, T(1));
    for (std::uint32_t k = 0; k < peak.size(); ++k) CHECK(double(length(peak.triangle(k).normal)) == doctest::Approx(1.0));
}

// regression: in float, spacing × i puts two samples on one coordinate past about 2^23 samples
// along an axis; a field of 2 × (2^24 + 4) samples was accepted, and a body at its far edge read
// heights past the end of the array (the last cell's index rounded up in T).
TEST_CASE("a float heightfield with more rows than float can place apart is rejected") {
    const std::uint32_t rows = (1u << 24) + 4;
    CHECK_THROWS_AS(HeightField<float>(2, rows, std::vector<float>(2 * std::size_t(rows), 0.f), 0.01f), InvalidArgument);
}

namespace {

/// A uniform number in [lo, hi) from rng alone (std::uniform_real_distribution differs between
/// standard libraries).
double uniform(std::mt19937& rng, double lo, double hi) { return lo + (hi - lo) * (double(rng()) / 4294967296.0); }

/// The grid of the seam tests: 13 × 13 samples 0.7 m apart, flat or bumpy (0.4 U(−1, 1)).
template <class T>
HeightField<T> seam_field(bool bumpy) {
    std::mt19937 rng(2013);
    std::vector<T> heights(13 * 13, T(0));
    if (bumpy)
        for (T& h : heights) h = static_cast<T>(0.4 * uniform(rng, -1.0, 1.0));
    return HeightField<T>(13, 13, heights, T(0.7));
}

/// The same triangles as a TriangleMesh, from the field's own samples.
template <class T>
TriangleMesh<T> as_mesh(const HeightField<T>& f) {
    std::vector<Vec3<T>> v;
    for (std::uint32_t j = 0; j < f.rows(); ++j)
        for (std::uint32_t i = 0; i < f.columns(); ++i) v.push_back(f.sample(i, j));
    std::vector<Tri> tris;
    const auto at = [&](std::uint32_t i, std::uint32_t j) { return j * f.columns() + i; };
    for (std::uint32_t j = 0; j + 1 < f.rows(); ++j)
        for (std::uint32_t i = 0; i + 1 < f.columns(); ++i) {
            tris.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            tris.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return TriangleMesh<T>(v, tris);
}

/// Where rays slipped between triangles: every interior sample and the midpoint of every interior
/// edge (along x, along z and each cell's diagonal).
template <class T>
std::vector<Vec3<T>> seam_points(const HeightField<T>& f) {
    std::vector<Vec3<T>> p;
    const std::uint32_t n = f.columns() - 1;
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i) {
            const bool inner_i = i > 0 && i<n, inner_j = j> 0 && j < n;
            if (inner_i && inner_j) p.push_back(f.sample(i, j));
            if (i < n && inner_j) p.push_back((f.sample(i, j) + f.sample(i + 1, j)) * T(0.5));
            if (j < n && inner_i) p.push_back((f.sample(i, j) + f.sample(i, j + 1)) * T(0.5));
            if (i < n && j < n) p.push_back((f.sample(i, j) + f.sample(i + 1, j + 1)) * T(0.5));
        }
    return p;
}

/// Directions within 17° of straight down: straight down, tilted along the grid lines and the
/// diagonals, and 8 at random. A triangle of seam_field rises at most 1.62 m a metre and
/// tan 17° × 1.62 < 1, so each of these crosses the surface once.
template <class T>
std::vector<Vec3<T>> steep_directions(std::mt19937& rng) {
    const double tilt = 0.2;  // 11.5°
    std::vector<Vec3<double>> d{{0, -1, 0},     {tilt, -1, 0},    {-tilt, -1, 0},    {0, -1, tilt},
                                {0, -1, -tilt}, {tilt, -1, tilt}, {-tilt, -1, -tilt}};
    const double pi = 3.14159265358979323846, most = 17.0 * pi / 180.0;
    for (int k = 0; k < 8; ++k) {
        const double c = uniform(rng, std::cos(most), 1.0), s = std::sqrt(1.0 - c * c), phi = uniform(rng, 0.0, 2 * pi);
        d.push_back({s * std::cos(phi), -c, s * std::sin(phi)});
    }
    std::vector<Vec3<T>> out;
    for (const Vec3<double>& v : d)
        out.push_back(normalized(Vec3<T>(static_cast<T>(v.x), static_cast<T>(v.y), static_cast<T>(v.z))));
    return out;
}

/// Casts a ray at every seam point from each steep direction, from `reach` metres back along it;
/// cast(local origin, local direction) returns the hit's distance (if any). Counts the rays that
/// missed and the hits not within rounding of `reach`.
template <class T, class Cast>
std::pair<int, int> seam_misses(const HeightField<T>& f, Cast cast) {
    std::mt19937 rng(17);
    const T reach = T(3), tolerance = T(256) * std::numeric_limits<T>::epsilon() * T(8);
    int missed = 0, off = 0;
    for (const Vec3<T>& p : seam_points(f))
        for (const Vec3<T>& d : steep_directions<T>(rng)) {
            const std::optional<T> hit = cast(p - d * reach, d);
            if (!hit) ++missed;
            else if (!(std::abs(*hit - reach) <= tolerance)) ++off;
        }
    return {missed, off};
}

}  // namespace

// regression: detail::ray_triangle was Möller–Trumbore with strict tests per triangle; two
// triangles sharing an edge work it out from different corners, and rounding could reject a ray
// in both (4–8 % of the rays at these points missed, float and double). The hierarchy's node
// boxes, tested unpadded, culled a few more on the mesh.
TEST_CASE_TEMPLATE("rays at a grid's shared edges and corners never slip between its triangles", T, float, double) {
    for (const bool bumpy : {false, true}) {
        CAPTURE(bumpy);
        const HeightField<T> field = seam_field<T>(bumpy);
        const TriangleMesh<T> mesh = as_mesh(field);
        const auto on = [](const auto& shape) {
            return [&shape](const Vec3<T>& o, const Vec3<T>& d) -> std::optional<T> {
                const auto hit = shape.raycast(Ray<T>{o, d, T(10)});
                if (hit) CHECK(dot(hit->first.normal, d) <= T(0));  // facing the ray's origin
                return hit ? std::optional<T>(hit->first.distance) : std::nullopt;
            };
        };
        const std::pair<int, int> field_misses = seam_misses(field, on(field));
        CHECK(field_misses.first == 0);
        CHECK(field_misses.second == 0);
        const std::pair<int, int> mesh_misses = seam_misses(field, on(mesh));
        CHECK(mesh_misses.first == 0);
        CHECK(mesh_misses.second == 0);
    }
}

// regression: the same through World::raycast, the body placed square and turned (its rays cross
// the grid lines and diagonals after a rotation's rounding).
TEST_CASE_TEMPLATE("world rays at a placed grid's shared edges and corners hit it", T, float, double) {
    const Quat<T> turns[] = {Quat<T>::identity(), Quat<T>::from_axis_angle(normalized(Vec3<T>{T(1), T(2), T(3)}), T(0.9))};
    for (const bool bumpy : {false, true})
        for (const bool turned : {false, true})
            for (const bool as_field : {true, false}) {
                CAPTURE(bumpy);
                CAPTURE(turned);
                CAPTURE(as_field);
                const HeightField<T> field = seam_field<T>(bumpy);
                World<T> w;
                BodyDef<T> d;
                d.type = BodyType::static_body;
                d.position = {T(1.3), T(-0.4), T(2.1)};
                d.orientation = turns[turned ? 1 : 0];
                const BodyId ground = as_field ? w.create_body(field, d) : w.create_body(as_mesh(field), d);
                const Transform<T> pose = w.body(ground).transform();
                const std::pair<int, int> misses = seam_misses(field, [&](const Vec3<T>& o, const Vec3<T>& dir) {
                    const Vec3<T> world_dir = pose.apply_direction(dir);
                    const auto hit = w.raycast(Ray<T>{pose.apply(o), world_dir, T(10)});
                    if (hit) CHECK(dot(hit->hit.normal, world_dir) <= T(0));
                    return hit ? std::optional<T>(hit->hit.distance) : std::nullopt;
                });
                CHECK(misses.first == 0);
                CHECK(misses.second == 0);
            }
}

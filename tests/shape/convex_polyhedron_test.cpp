// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
#include "support/approx.hpp"

#include "scenes/random.hpp"

#include <xeno/shape/polyhedra.hpp>

#include <string>

using namespace xeno;
using xeno::test::near;

TEST_CASE_TEMPLATE("builders produce closed convex polyhedra centred on their centroid", T, float, double) {
    const ConvexPolyhedron<T> box = make_box_polyhedron(Vec3<T>{T(1), T(2), T(3)});
    CHECK(box.vertices().size() == 8);
    CHECK(box.faces().size() == 6);
    CHECK(box.edges().size() == 12);
    CHECK(near(box.volume(), T(48)));
    const ConvexPolyhedron<T> wedge = make_triangular_prism(T(1), T(3), T(0.5));
    CHECK(wedge.vertices().size() == 6);
    CHECK(wedge.faces().size() == 5);
    CHECK(near(wedge.volume(), T(3)));  // triangle area 3 × depth 1
    CHECK(near(wedge.interior_point(), Vec3<T>::zero()));
    const ConvexPolyhedron<T> tetra = make_tetrahedron(T(2));
    CHECK(tetra.faces().size() == 4);
    CHECK(near(tetra.volume(), T(8) / (T(6) * std::sqrt(T(2)))));
    CHECK(near(tetra.interior_point(), Vec3<T>::zero()));
    bool has_down_face = false;
    for (const auto& f : tetra.faces()) has_down_face |= near(f.normal, Vec3<T>{T(0), T(-1), T(0)});
    CHECK(has_down_face);
    const ConvexPolyhedron<T> prism = make_regular_prism(6, T(1), T(1));
    CHECK(prism.vertices().size() == 12);
    CHECK(prism.faces().size() == 8);
    // Hexagon of circumradius 1: area 3√3/2, height 2.
    CHECK(near(prism.volume(), T(3) * std::sqrt(T(3))));
    for (const ConvexPolyhedron<T>* p : {&box, &wedge, &tetra, &prism}) {
        const std::size_t v = p->vertices().size(), e = p->edges().size(), f = p->faces().size();
        CHECK(v + f == e + 2);  // Euler characteristic of a closed convex surface
        for (const auto& face : p->faces()) CHECK(near(length(face.normal), T(1)));
    }
}

TEST_CASE_TEMPLATE("hill climbing and scanning agree on a prism with many sides", T, float, double) {
    const ConvexPolyhedron<T> prism = make_regular_prism(64, T(1), T(0.5));
    REQUIRE(prism.vertices().size() > ConvexPolyhedron<T>::hill_climb_threshold);
    for (int k = 0; k < 1000; ++k) {
        const T a = T(k) * T(0.0123), b = T(k) * T(0.731);
        const Vec3<T> d{std::cos(a) * std::cos(b), std::sin(b), std::sin(a) * std::cos(b)};
        CHECK(near(dot(prism.vertices()[prism.support_index_hill_climb(d)], d),
                   dot(prism.vertices()[prism.support_index_scan(d)], d)));
    }
}

TEST_CASE_TEMPLATE("the convexity check's box tree finds a vertex in front of a plane exactly when a loop over the vertices does",
                   T, float, double) {
    // The constructor asks detail::VertexBoxTree whether any vertex is more than a tolerance in
    // front of a face plane (issue 13 item 13: the loop over every vertex for every face was
    // quadratic). Its answers must be the loop's, to the last rounding: planes are placed so the
    // farthest vertex is just below, at, or just above the tolerance, for clouds on a sphere, in
    // a ball, on a flat disc and far from the origin.
    scenes::Random rng(31);
    const T tolerance = T(1e-3);
    int disagreements = 0, in_front = 0, queries = 0;
    for (int cloud = 0; cloud < 8; ++cloud) {
        const Vec3<T> offset = cloud % 4 == 3 ? Vec3<T>{T(900), T(-400), T(50)} : Vec3<T>::zero();
        std::vector<Vec3<T>> v;
        for (int i = 0; i < 700 + 300 * cloud; ++i) {
            Vec3<T> p = rng.direction<T>();
            if (cloud % 4 == 1) p = p * rng.uniform(T(0), T(1));
            if (cloud % 4 == 2) p.y = p.y * T(1e-3);
            v.push_back(p + offset);
        }
        const detail::VertexBoxTree<T> tree(v);
        for (int k = 0; k < 300; ++k) {
            const Vec3<T> n = rng.direction<T>();
            T top = -ScalarTraits<T>::infinity;
            for (const Vec3<T>& p : v) top = std::max(top, dot(n, p));
            // At the limit, a few rounding units either side, or well clear of it.
            const T shifts[] = {T(0),
                                ScalarTraits<T>::epsilon * std::abs(top),
                                -ScalarTraits<T>::epsilon * std::abs(top),
                                T(4) * ScalarTraits<T>::epsilon * std::abs(top),
                                T(0.5),
                                T(-0.5)};
            for (const T shift : shifts) {
                const T plane = top - tolerance + shift;
                bool loop = false;
                for (const Vec3<T>& p : v) loop = loop || dot(n, p) - plane > tolerance;
                if (tree.any_in_front(n, plane, tolerance) != loop) ++disagreements;
                if (loop) ++in_front;
                ++queries;
            }
        }
    }
    CHECK(disagreements == 0);
    CHECK(in_front > queries / 4);  // both answers were asked for
    CHECK(in_front < 3 * queries / 4);
}

TEST_CASE_TEMPLATE("an off-centre polyhedron keeps its origin and reports an interior centroid", T, float, double) {
    const ConvexPolyhedron<T> unit = make_box_polyhedron(Vec3<T>{T(0.5), T(0.5), T(0.5)});
    std::vector<Vec3<T>> v;
    for (const Vec3<T>& p : unit.vertices()) v.push_back(p + Vec3<T>{T(10.5), T(0), T(0)});
    std::vector<std::vector<std::uint32_t>> faces;
    for (const auto& f : unit.faces())
        faces.emplace_back(unit.face_indices().begin() + f.first, unit.face_indices().begin() + f.first + f.count);
    const ConvexPolyhedron<T> far_box(v, faces);
    CHECK(near(far_box.interior_point(), Vec3<T>{T(10.5), T(0), T(0)}));
    CHECK(near(far_box.bounding_radius(), length(Vec3<T>{T(11), T(0.5), T(0.5)})));
    const auto [centred, shift] = far_box.recentered();
    CHECK(near(shift, Vec3<T>{T(10.5), T(0), T(0)}));
    CHECK(near(centred.interior_point(), Vec3<T>::zero()));
    CHECK(near(centred.unit_mass_properties().inertia, far_box.unit_mass_properties().inertia));
}

TEST_CASE_TEMPLATE("polyhedron construction rejects broken input with a clear message", T, float, double) {
    const ConvexPolyhedron<T> unit = make_box_polyhedron(Vec3<T>{T(1), T(1), T(1)});
    std::vector<std::vector<std::uint32_t>> faces;
    for (const auto& f : unit.faces())
        faces.emplace_back(unit.face_indices().begin() + f.first, unit.face_indices().begin() + f.first + f.count);
    const std::vector<Vec3<T>> v = unit.vertices();

    auto message = [](auto&& build) -> std::string {
        try {
            build();
        } catch (const InvalidArgument& e) {
            return e.what();
        }
        return "no error";
    };
    std::vector<Vec3<T>> nan_vertices = v;
    nan_vertices[3].y = std::numeric_limits<T>::quiet_NaN();
    CHECK(message([&] { ConvexPolyhedron<T>(nan_vertices, faces); }).find("vertex 3.y must be finite") != std::string::npos);
    auto open = faces;
    open.pop_back();
    CHECK(message([&] { ConvexPolyhedron<T>(v, open); }).find("closed") != std::string::npos);
    auto flipped = faces;
    std::reverse(flipped[0].begin(), flipped[0].end());
    CHECK(message([&] { ConvexPolyhedron<T>(v, flipped); }).find("ConvexPolyhedron") != std::string::npos);
    auto bad_index = faces;
    bad_index[1][2] = 99;
    CHECK(message([&] { ConvexPolyhedron<T>(v, bad_index); }).find("out of range") != std::string::npos);
    std::vector<Vec3<T>> dented = v;
    dented[7] = dented[7] * T(0.5);  // pulls a corner in: three faces no longer planar
    CHECK(message([&] { ConvexPolyhedron<T>(dented, faces); }).find("planar") != std::string::npos);
    CHECK(message([&] { ConvexPolyhedron<T>({v[0], v[1], v[2]}, faces); }).find("at least 4 vertices") != std::string::npos);
    // All inside-out faces: the orientation test catches it as non-convex or negative volume.
    auto inside_out = faces;
    for (auto& f : inside_out) std::reverse(f.begin(), f.end());
    CHECK(message([&] { ConvexPolyhedron<T>(v, inside_out); }) != "no error");
    // Regression: a face listing a vertex twice (next to itself, or closing on its first) was
    // accepted, its self-loop edge passing the closure check and missing from the edge list.
    for (const bool closing : {false, true}) {
        auto repeated = faces;
        if (closing) repeated[0].push_back(repeated[0][0]);
        else repeated[0].insert(repeated[0].begin() + 1, repeated[0][1]);
        CAPTURE(closing);
        CHECK(message([&] { ConvexPolyhedron<T>(v, repeated); }).find("lists a vertex twice") != std::string::npos);
    }
}

TEST_CASE_TEMPLATE("regression: two shells (a doubled surface, a nested copy) are not one polyhedron", T, float, double) {
    // Each shell alone pairs every edge with its reverse and is convex, so both passed: a doubled
    // tetrahedron had twice the volume and mass. V − E + F is 4 for two shells, 2 for one.
    const ConvexPolyhedron<T> tetra = make_tetrahedron(T(1));
    std::vector<std::vector<std::uint32_t>> faces;
    for (const auto& f : tetra.faces())
        faces.emplace_back(tetra.face_indices().begin() + f.first, tetra.face_indices().begin() + f.first + f.count);
    CHECK(tetra.vertices().size() - tetra.edges().size() + tetra.faces().size() == 2);
    auto message = [](auto&& build) -> std::string {
        try {
            build();
        } catch (const InvalidArgument& e) {
            return e.what();
        }
        return "no error";
    };
    // Scale 1: two coincident copies; just below 1: a copy inside, within the convexity tolerance.
    for (const T scale : {T(1), T(1) - T(16) * ScalarTraits<T>::geometric_tolerance}) {
        CAPTURE(scale);
        std::vector<Vec3<T>> vertices = tetra.vertices();
        for (const Vec3<T>& v : tetra.vertices()) vertices.push_back(v * scale);
        std::vector<std::vector<std::uint32_t>> doubled = faces;
        for (std::vector<std::uint32_t> f : faces) {
            for (std::uint32_t& index : f) index += 4;
            doubled.push_back(f);
        }
        const std::string m = message([&] { ConvexPolyhedron<T>(vertices, doubled); });
        INFO(m);
        CHECK(m.find("ConvexPolyhedron: is not one closed surface") != std::string::npos);
        CHECK(m.find("(got 4)") != std::string::npos);
    }
}

TEST_CASE_TEMPLATE("regression: a slim plank is a solid, a slab or a needle within the tolerance is not", T, float, double) {
    // The volume check asked for V > 64 ε d × d² (a plate's area), which a square beam passes
    // only if its width is 1/40 of its length in float: a 2 m × 5 cm × 5 cm plank was "zero
    // volume" and the hull of its corners "collinear or coplanar". The check is now on the mean
    // thickness 2 V / area, against the same 64 ε d as a face's width.
    const Vec3<T> half{T(1), T(0.025), T(0.025)};
    const ConvexPolyhedron<T> plank = make_box_polyhedron(half);
    CHECK(plank.volume() == doctest::Approx(T(0.005)).epsilon(1e-5));
    std::vector<Vec3<T>> corners;
    for (int k = 0; k < 8; ++k) corners.push_back({k & 1 ? half.x : -half.x, k & 2 ? half.y : -half.y, k & 4 ? half.z : -half.z});
    CHECK(make_convex_hull(corners).polyhedron.volume() == doctest::Approx(T(0.005)).epsilon(1e-5));
    // 64 ε d is 1.3 mm at d = 2 m in float (1.3e-7 m in double): thinner than half of it is flat.
    const T flat = std::is_same_v<T, float> ? T(2e-4) : T(2e-11);
    CHECK_THROWS_AS(make_box_polyhedron(Vec3<T>{T(1), T(1), flat}), InvalidArgument);  // a slab
    CHECK_THROWS_AS(make_box_polyhedron(Vec3<T>{T(1), flat, flat}), InvalidArgument);  // a needle
    for (Vec3<T>& c : corners) c.z = c.z > T(0) ? flat : -flat;
    CHECK_THROWS_AS(make_convex_hull(corners), InvalidArgument);
}

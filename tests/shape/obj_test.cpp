// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The examples' OBJ reader (examples/mesh/obj.hpp): what it accepts, and that every malformed
// line is refused with its line number.
#include "mesh/obj.hpp"

#include <xeno/xeno.hpp>

#include <doctest/doctest.h>

#include <sstream>

using xeno::examples::ObjMesh;
using xeno::examples::parse_obj;

namespace {
ObjMesh<double> read(const std::string& text) {
    std::istringstream in(text);
    return parse_obj<double>(in);
}
std::string error_of(const std::string& text) {
    try {
        read(text);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST_CASE("the OBJ reader takes vertices, polygons in every index form, and skips the rest") {
    const ObjMesh<double> m = read(
        "# a unit square and a triangle\n"
        "mtllib x.mtl\no square\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvn 0 1 0\nvt 0 0\n"
        "f 1/1/1 4/1/1 3/1/1 2/1/1\n"  // a quad: fanned into two triangles
        "v 2 0 0 1.0\n"                // an optional w is ignored
        "f -1 2//1 3\n\n");            // negative: from the last vertex
    REQUIRE(m.vertices.size() == 5);
    CHECK(m.vertices[4].x == 2.0);
    REQUIRE(m.triangles.size() == 3);
    CHECK(m.triangles[0] == std::array<std::uint32_t, 3>{0, 3, 2});
    CHECK(m.triangles[1] == std::array<std::uint32_t, 3>{0, 2, 1});
    CHECK(m.triangles[2] == std::array<std::uint32_t, 3>{4, 1, 2});
    // And it makes a mesh.
    const xeno::TriangleMesh<double> mesh(m.vertices, m.triangles);
    CHECK(mesh.size() == 3);
}

TEST_CASE("the OBJ reader refuses malformed lines with their numbers") {
    CHECK(error_of("v 0 0\n").find("line 1") != std::string::npos);
    CHECK(error_of("v 0 0 0\nv 1 x 0\n").find("line 2") != std::string::npos);
    CHECK(error_of("v 0 0 nan\n").find("finite") != std::string::npos);
    CHECK(error_of("v 0 0 1e999\n").find("finite") != std::string::npos);
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2\n").find("three corners") != std::string::npos);
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 4\n").find("outside") != std::string::npos);
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 0 1 2\n").find("outside") != std::string::npos);
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 0 1\nf -4 1 2\n").find("outside") != std::string::npos);
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3x\n").find("not an index") != std::string::npos);
    CHECK(error_of("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 99999999999999999999\n").find("line 4") != std::string::npos);
    CHECK(error_of("f 1 2 3\n").find("outside") != std::string::npos);  // no vertices yet
}

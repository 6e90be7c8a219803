// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A minimal Wavefront OBJ reader for the examples (the library itself reads no files): vertex
// lines `v x y z` and face lines `f a b c …` (indices from 1, negative ones counted back from the
// last vertex so far, `a/t/n` and `a//n` forms, polygons fanned into triangles from their first
// corner). Every other line (normals, texture coordinates, groups, materials, comments) is
// skipped. Everything read is checked: a number that does not parse or is not finite, an index of
// 0 or past the vertices, a face of fewer than three corners, or more than 2³² − 1 vertices is
// reported with its line number (std::runtime_error), and nothing is returned half-read.
#pragma once

#include <xeno/math/vec3.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace xeno::examples {

/// Vertices and triangles as TriangleMesh takes them.
template <class T>
struct ObjMesh {
    std::vector<Vec3<T>> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

namespace detail {

[[noreturn]] inline void obj_error(std::size_t line, const std::string& what) {
    throw std::runtime_error("OBJ line " + std::to_string(line) + ": " + what);
}

/// The vertex index of one face corner ("7", "7/2", "7//3", "-1"), zero-based.
inline std::uint32_t obj_index(const std::string& corner, std::size_t vertices, std::size_t line) {
    const std::string first = corner.substr(0, corner.find('/'));
    char* end = nullptr;
    const long long i = std::strtoll(first.c_str(), &end, 10);
    if (first.empty() || *end != '\0') obj_error(line, "face corner '" + corner + "' is not an index");
    const long long resolved = i < 0 ? static_cast<long long>(vertices) + i : i - 1;
    if (i == 0 || resolved < 0 || resolved >= static_cast<long long>(vertices))
        obj_error(line, "face index " + first + " is outside the " + std::to_string(vertices) + " vertices read so far");
    return static_cast<std::uint32_t>(resolved);
}

}  // namespace detail

/// Reads OBJ text (see the file comment).
template <class T>
ObjMesh<T> parse_obj(std::istream& in) {
    ObjMesh<T> out;
    std::string text;
    for (std::size_t line = 1; std::getline(in, text); ++line) {
        std::istringstream words(text);
        std::string key;
        if (!(words >> key)) continue;
        if (key == "v") {
            double xyz[3];
            for (double& c : xyz) {
                std::string word;
                char* end = nullptr;
                if (!(words >> word)) detail::obj_error(line, "a vertex needs three coordinates");
                c = std::strtod(word.c_str(), &end);
                if (*end != '\0' || !std::isfinite(c))
                    detail::obj_error(line, "coordinate '" + word + "' is not a finite number");
            }
            if (out.vertices.size() == 0xffffffffu) detail::obj_error(line, "more than 2^32 - 1 vertices");
            out.vertices.push_back({static_cast<T>(xyz[0]), static_cast<T>(xyz[1]), static_cast<T>(xyz[2])});
        } else if (key == "f") {
            std::vector<std::uint32_t> corners;
            for (std::string corner; words >> corner;) corners.push_back(detail::obj_index(corner, out.vertices.size(), line));
            if (corners.size() < 3) detail::obj_error(line, "a face needs at least three corners");
            for (std::size_t k = 1; k + 1 < corners.size(); ++k)
                out.triangles.push_back({corners[0], corners[k], corners[k + 1]});
        }
    }
    return out;
}

/// Reads an OBJ file; std::runtime_error if it cannot be opened or is malformed.
template <class T>
ObjMesh<T> load_obj(const std::string& path) {
    std::ifstream file(path);
    if (!file) throw std::runtime_error("cannot open OBJ file " + path);
    return parse_obj<T>(file);
}

}  // namespace xeno::examples

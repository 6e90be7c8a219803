// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Tests of xeno_query's format (query_format.hpp): every shape kind parses, the conversions to the
// library (axis z → y, the cone's origin, a hull's shift) put the shapes where the format says
// (checked by depths against boxes at known heights, which a wrong sign or a wrong composition
// order would change), headers and extra columns, bad lines, the printed digits, and swapping A
// and B. The sample file is checked against its expected output within a tolerance here, and byte
// for byte by the query.sample_pairs test.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include "query/query_format.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <vector>

namespace {

using namespace xeno::query;
using xeno::Penetration;
using xeno::Quat;
using xeno::Transform;
using xeno::Vec3;

/// A tab-separated line from its columns.
std::string tsv(const std::vector<std::string>& columns) {
    std::string line;
    for (std::size_t i = 0; i < columns.size(); ++i) line += (i ? "\t" : "") + columns[i];
    return line;
}

/// The pair (shape_a at pos_a, quat_a) – (shape_b at pos_b, quat_b) as a line with id "p".
std::string pair_line(const std::string& shape_a, const std::string& pos_a, const std::string& quat_a, const std::string& shape_b,
                      const std::string& pos_b, const std::string& quat_b) {
    return tsv({"p", shape_a, pos_a, quat_a, shape_b, pos_b, quat_b});
}

const std::string identity = "1 0 0 0";

template <class T>
Penetration<T> query_line(const std::string& line) {
    return run_query(parse_line<T>(line));
}

template <class T>
T tolerance() {
    return std::is_same_v<T, float> ? T(2e-4) : T(1e-7);
}

/// |a - b| <= tol for each component.
template <class T>
bool near(const Vec3<T>& a, const Vec3<T>& b, T tol) {
    return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol && std::abs(a.z - b.z) <= tol;
}

/// Expects a hit of depth about `depth` along `normal`.
template <class T>
void expect_hit(const Penetration<T>& p, T depth, const Vec3<T>& normal) {
    REQUIRE(p.hit);
    CHECK(std::abs(p.depth - depth) <= tolerance<T>() * T(10));
    CHECK(near(p.normal, normal, tolerance<T>() * T(10)));
    // The points are h apart along the normal: moving B by depth · normal separates them.
    CHECK(near(p.point_a - p.point_b, p.normal * p.depth, tolerance<T>() * T(10)));
}

/// Runs process() on text; returns stdout, fills err and bad.
std::string run_process(const std::string& text, Precision precision, std::string& err, int& bad) {
    std::istringstream in(text);
    std::ostringstream out, errors;
    bad = process(in, out, errors, precision);
    err = errors.str();
    return out.str();
}

std::vector<std::string> words_of(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

}  // namespace

TEST_CASE_TEMPLATE("every shape kind parses with its parameters", T, float, double) {
    const ShapeSpec<T> box = parse_shape<T>("box 1 2.5 3");
    CHECK(box.kind == ShapeKind::box);
    CHECK(box.params == std::vector<T>{T(1), T(2.5), T(3)});
    const ShapeSpec<T> sphere = parse_shape<T>("sphere 0.5");
    CHECK(sphere.kind == ShapeKind::sphere);
    CHECK(sphere.params == std::vector<T>{T(0.5)});
    const ShapeSpec<T> capsule = parse_shape<T>("capsule 0.25  1");  // runs of spaces are one separator
    CHECK(capsule.kind == ShapeKind::capsule);
    CHECK(capsule.params == std::vector<T>{T(0.25), T(1)});
    CHECK(parse_shape<T>("capsule 0.25 0").params[1] == T(0));  // hh = 0: a sphere
    const ShapeSpec<T> cylinder = parse_shape<T>(" cylinder 2 0.75 ");
    CHECK(cylinder.kind == ShapeKind::cylinder);
    CHECK(cylinder.params == std::vector<T>{T(2), T(0.75)});
    const ShapeSpec<T> cone = parse_shape<T>("cone 1 2");
    CHECK(cone.kind == ShapeKind::cone);
    CHECK(cone.params == std::vector<T>{T(1), T(2)});
    const ShapeSpec<T> hull = parse_shape<T>("hull 4 0 0 0 1 0 0 0 1 0 0 0 1e0");
    CHECK(hull.kind == ShapeKind::hull);
    REQUIRE(hull.points.size() == 4);
    CHECK(hull.points[1].x == T(1));
    CHECK(hull.points[3].z == T(1));

    // The library shapes: sizes carried over, axis shapes along library y.
    const Transform<T> here{};
    CHECK(std::get<xeno::Box<T>>(to_library(box, here).shape).half_extents().y == T(2.5));
    CHECK(std::get<xeno::Capsule<T>>(to_library(capsule, here).shape).half_height() == T(1));
    CHECK(std::get<xeno::Cylinder<T>>(to_library(cylinder, here).shape).radius() == T(2));
    CHECK(std::get<xeno::Cone<T>>(to_library(cone, here).shape).height() == T(2));
    CHECK(std::get<xeno::ConvexPolyhedron<T>>(to_library(hull, here).shape).vertices().size() == 4);
}

TEST_CASE_TEMPLATE("R_zy is +90 degrees about x and takes library y to format z", T, float, double) {
    const Quat<T> r = library_to_format_axes<T>();
    const T tol = tolerance<T>();
    CHECK(near(rotate(r, Vec3<T>{T(0), T(1), T(0)}), Vec3<T>{T(0), T(0), T(1)}, tol));
    CHECK(near(rotate(r, Vec3<T>{T(0), T(0), T(1)}), Vec3<T>{T(0), T(-1), T(0)}, tol));  // right-handed: z → -y
    CHECK(near(rotate(r, Vec3<T>{T(1), T(0), T(0)}), Vec3<T>{T(1), T(0), T(0)}, tol));
    const Quat<T> expected = Quat<T>::from_axis_angle({T(1), T(0), T(0)}, xeno::ScalarTraits<T>::pi / T(2));
    CHECK(std::abs(dot(r, expected)) == doctest::Approx(1).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("a capsule along format z lies between two boxes at the depth its radius gives", T, float, double) {
    // Capsule r 0.5, hh 1 along format z at the origin: |x|, |y| <= 0.5 beside the axis, |z| <= 1.5.
    const std::string capsule = "capsule 0.5 1";
    // Boxes below and above along y touch its side: 0.1 and 0.05 deep. Were the axis y, the box
    // below would reach 1.1 deep.
    expect_hit(query_line<T>(pair_line(capsule, "0 0 0", identity, "box 1 1 1", "0 -1.4 0", identity)), T(0.1),
               Vec3<T>{T(0), T(-1), T(0)});
    expect_hit(query_line<T>(pair_line(capsule, "0 0 0", identity, "box 1 1 1", "0 1.45 0", identity)), T(0.05),
               Vec3<T>{T(0), T(1), T(0)});
    // A box beyond the end cap along z: 0.05 deep.
    expect_hit(query_line<T>(pair_line(capsule, "0 0 0", identity, "box 1 1 1", "0 0 2.45", identity)), T(0.05),
               Vec3<T>{T(0), T(0), T(1)});
    // ... and one along y at the cap's height is missed: the capsule does not reach y = 1.55.
    CHECK_FALSE(query_line<T>(pair_line(capsule, "0 0 0", identity, "box 1 1 1", "0 2.55 0", identity)).hit);

    // Turned by +90° about y (format z → world x): orientation q · R_zy, not R_zy · q (which would
    // leave the capsule along z, since q turns about the library axis).
    const std::string about_y = "0.7071067811865476 0 0.7071067811865476 0";
    expect_hit(query_line<T>(pair_line(capsule, "0 0 0", about_y, "box 1 1 1", "2.45 0 0", identity)), T(0.05),
               Vec3<T>{T(1), T(0), T(0)});
    expect_hit(query_line<T>(pair_line(capsule, "0 0 0", about_y, "box 1 1 1", "-2.4 0 0", identity)), T(0.1),
               Vec3<T>{T(-1), T(0), T(0)});
    CHECK_FALSE(query_line<T>(pair_line(capsule, "0 0 0", about_y, "box 1 1 1", "0 0 2.45", identity)).hit);
}

TEST_CASE_TEMPLATE("a cylinder along format z stands on a box on its flat end", T, float, double) {
    // Box top at z = 0; cylinder r 0.5, hh 1 centred at z = 0.9: its bottom face at -0.1.
    expect_hit(query_line<T>(pair_line("box 2 2 1", "0 0 -1", identity, "cylinder 0.5 1", "0 0 0.9", identity)), T(0.1),
               Vec3<T>{T(0), T(0), T(1)});
}

TEST_CASE_TEMPLATE("a cone standing on its base on a box sinks by the overlap of its base", T, float, double) {
    // Cone r 1, h 2: base at format z = -1, apex at +1 from its origin. Box top at z = 0.
    const std::string cone = "cone 1 2";
    expect_hit(query_line<T>(pair_line("box 2 2 1", "0 0 -1", identity, cone, "0 0 0.9", identity)), T(0.1),
               Vec3<T>{T(0), T(0), T(1)});
    CHECK_FALSE(query_line<T>(pair_line("box 2 2 1", "0 0 -1", identity, cone, "0 0 1.01", identity)).hit);
    // A box hanging over the apex (bottom face at z = 0.95): the apex is 0.05 inside.
    expect_hit(query_line<T>(pair_line(cone, "0 0 0", identity, "box 1 1 1", "0 0 1.95", identity)), T(0.05),
               Vec3<T>{T(0), T(0), T(1)});
    CHECK_FALSE(query_line<T>(pair_line(cone, "0 0 0", identity, "box 1 1 1", "0 0 2.01", identity)).hit);
    // Turned by -90° about x, format z is world y (y up): the cone stands on a floor whose top is
    // at y = 0, its origin 0.9 above: base 0.1 deep.
    const std::string z_to_y = "0.7071067811865476 -0.7071067811865476 0 0";
    expect_hit(query_line<T>(pair_line("box 5 1 5", "0 -1 0", identity, cone, "3 0.9 -2", z_to_y)), T(0.1),
               Vec3<T>{T(0), T(1), T(0)});

    // The library pose: origin (centre of mass) a quarter of the height above the base, h/4
    // below the format origin along format z.
    const PlacedShape<T> placed =
        to_library(parse_shape<T>(cone), Transform<T>{{T(3), T(0.9), T(-2)}, parse_orientation<T>(z_to_y)});
    CHECK(near(placed.pose.position, Vec3<T>{T(3), T(0.4), T(-2)}, tolerance<T>()));
}

TEST_CASE_TEMPLATE("a hull keeps its points where the format puts them, origin outside", T, float, double) {
    // A unit cube around (5, 0, 0) in the format's local frame; the local origin is 4.5 outside it.
    const std::string cube =
        "hull 8 4.5 -0.5 -0.5 5.5 -0.5 -0.5 4.5 0.5 -0.5 5.5 0.5 -0.5 4.5 -0.5 0.5 5.5 -0.5 0.5 4.5 0.5 0.5 5.5 0.5 0.5";
    const PlacedShape<T> placed = to_library(parse_shape<T>(cube), Transform<T>{});
    CHECK(near(placed.pose.position, Vec3<T>{T(5), T(0), T(0)}, tolerance<T>()));

    expect_hit(query_line<T>(pair_line(cube, "0 0 0", identity, "sphere 0.5", "5.9 0 0", identity)), T(0.1),
               Vec3<T>{T(1), T(0), T(0)});
    CHECK_FALSE(query_line<T>(pair_line(cube, "0 0 0", identity, "sphere 0.5", "0 0 0", identity)).hit);
    // Moved to (1, 0, 0) and turned 90° about z: the points now lie around (1, 5, 0), so the shift
    // turns with the body. Where the shift is not turned, the sphere at (5.9, 0, 0) would be hit.
    const std::string about_z = "0.7071067811865476 0 0 0.7071067811865476";
    expect_hit(query_line<T>(pair_line(cube, "1 0 0", about_z, "sphere 0.5", "1 5.9 0", identity)), T(0.1),
               Vec3<T>{T(0), T(1), T(0)});
    expect_hit(query_line<T>(pair_line("sphere 0.5", "1 4.1 0", identity, cube, "1 0 0", about_z)), T(0.1),
               Vec3<T>{T(0), T(1), T(0)});
    CHECK_FALSE(query_line<T>(pair_line(cube, "1 0 0", about_z, "sphere 0.5", "5.9 0 0", identity)).hit);
}

TEST_CASE_TEMPLATE("quaternions are normalised", T, float, double) {
    const Quat<T> q = parse_orientation<T>("2 0 0 0");
    CHECK(q.w == T(1));
    const Quat<T> big = parse_orientation<T>("3e30 4e30 0 0");
    CHECK(std::abs(big.w - T(0.6)) <= tolerance<T>());
    CHECK(std::abs(big.x - T(0.8)) <= tolerance<T>());
    // Unnormalised input gives the same answer as normalised.
    const Penetration<T> a = query_line<T>(pair_line("box 1 1 1", "0 0 0", "0.5 0 0.5 0", "sphere 1", "0 0 1.9", identity));
    const Penetration<T> b = query_line<T>(
        pair_line("box 1 1 1", "0 0 0", "0.7071067811865476 0 0.7071067811865476 0", "sphere 1", "0 0 1.9", identity));
    REQUIRE(a.hit);
    REQUIRE(b.hit);
    CHECK(std::abs(a.depth - b.depth) <= tolerance<T>());
}

TEST_CASE("sphere against sphere: depth r1 + r2 - d") {
    const Penetration<double> p = query_line<double>(pair_line("sphere 1", "0 0 0", identity, "sphere 1", "1.5 0 0", identity));
    REQUIRE(p.hit);
    CHECK(p.depth == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(near(p.normal, Vec3<double>{1, 0, 0}, 1e-12));
    CHECK(near(p.point_a, Vec3<double>{1, 0, 0}, 1e-12));
    CHECK(near(p.point_b, Vec3<double>{0.5, 0, 0}, 1e-12));
}

TEST_CASE("a header on the first line is skipped, elsewhere it is a bad line") {
    const std::string header = "id\tshapeA\tposA\tquatA\tshapeB\tposB\tquatB";
    const std::string good = tsv({"7", "sphere 1", "0 0 0", identity, "sphere 1", "1.5 0 0", identity});
    std::string err;
    int bad = 0;
    std::string out = run_process(header + "\n" + good + "\n", Precision::double_float, err, bad);
    CHECK(bad == 0);
    CHECK(err.empty());
    REQUIRE(lines_of(out).size() == 1);
    CHECK(lines_of(out)[0].rfind("7 1 0.5 1 0 0 ", 0) == 0);
    // With Windows line ends and a byte-order mark.
    out = run_process("\xEF\xBB\xBF" + header + "\r\n" + good + "\r\n", Precision::double_float, err, bad);
    CHECK(bad == 0);
    CHECK(lines_of(out).size() == 1);
    // No header: the first line is data.
    out = run_process(good + "\n" + good + "\n", Precision::double_float, err, bad);
    CHECK(bad == 0);
    CHECK(lines_of(out).size() == 2);
    // An id that only starts with "id" is data.
    out = run_process(tsv({"id1", "sphere 1", "0 0 0", identity, "sphere 1", "3 0 0", identity}) + "\n", Precision::double_float,
                      err, bad);
    CHECK(out == "id1 0\n");
    // A header on line 2 is a bad line.
    out = run_process(good + "\n" + header + "\n", Precision::double_float, err, bad);
    CHECK(bad == 1);
    CHECK(err.find("line 2:") != std::string::npos);
    // Blank lines are skipped without a message.
    out = run_process(header + "\n\n   \n" + good + "\n", Precision::double_float, err, bad);
    CHECK(bad == 0);
    CHECK(lines_of(out).size() == 1);
}

TEST_CASE("columns after the seventh are ignored") {
    const std::string seven = tsv({"x", "box 1 1 1", "0 0 0", identity, "sphere 0.5", "0 1.25 0", identity});
    const Penetration<double> a = query_line<double>(seven);
    const Penetration<double> b = query_line<double>(seven + "\tnote: resting\t42\t");
    REQUIRE(a.hit);
    REQUIRE(b.hit);
    CHECK(a.depth == b.depth);
    CHECK(a.depth == doctest::Approx(0.25));
    std::string err;
    int bad = 0;
    CHECK(run_process(seven + "\textra\n", Precision::double_float, err, bad) == format_result("x", a) + "\n");
    CHECK(bad == 0);
}

TEST_CASE("bad lines are reported by number and the run goes on") {
    const std::string good = tsv({"ok", "sphere 1", "0 0 0", identity, "sphere 1", "1.5 0 0", identity});
    struct Bad {
        std::string line, message;
    };
    const std::vector<Bad> cases = {
        {tsv({"b", "sphere 1", "0 0 0", identity, "boxx 1 1 1", "0 0 0", identity}), "shape B: unknown shape 'boxx'"},
        {tsv({"b", "sphere 1", "0 0 0", identity}), "expected 7 tab-separated columns"},
        {tsv({"b", "box 1 1", "0 0 0", identity, "sphere 1", "0 0 0", identity}),
         "shape A: expected 3 numbers (box hx hy hz), got 2"},
        {tsv({"b", "sphere 1 2", "0 0 0", identity, "sphere 1", "0 0 0", identity}),
         "shape A: expected 1 numbers (sphere r), got 2"},
        {tsv({"b", "sphere 1", "0 0", identity, "sphere 1", "0 0 0", identity}), "posA: expected 3 numbers"},
        {tsv({"b", "sphere 1", "0 0 0", identity, "sphere 1", "0 nan 0", identity}), "posB: 'nan' is not finite"},
        {tsv({"b", "sphere 1", "0 0 0", identity, "sphere 1", "0 0 0", "1 0 inf 0"}), "quatB: 'inf' is not finite"},
        {tsv({"b", "sphere 1", "0 0 0", "0 0 0 0", "sphere 1", "0 0 0", identity}), "quatA: the zero quaternion"},
        {tsv({"b", "sphere 1", "0 0 0", "1 0 0", "sphere 1", "0 0 0", identity}), "quatA: expected 4 numbers"},
        {tsv({"b", "sphere 1", "0 0 0", identity, "cylinder 1 x", "0 0 0", identity}), "shape B: 'x' is not a number"},
        {tsv({"b", "sphere 1", "0 0 0", identity, "box 1 -1 1", "0 0 0", identity}), "shape B: box hy must be > 0 (got -1)"},
        {tsv({"b", "sphere 0", "0 0 0", identity, "sphere 1", "0 0 0", identity}), "shape A: sphere r must be > 0"},
        {tsv({"b", "cone 1 0", "0 0 0", identity, "sphere 1", "0 0 0", identity}), "shape A: cone h must be > 0"},
        {tsv({"b", "capsule 1 -0.5", "0 0 0", identity, "sphere 1", "0 0 0", identity}), "shape A: capsule hh must be >= 0"},
        {tsv({"b", "hull 3 0 0 0 1 0 0 0 1 0", "0 0 0", identity, "sphere 1", "0 0 0", identity}),
         "shape A: hull needs at least 4 points"},
        {tsv({"b", "hull 4 0 0 0 1 0 0 0 1 0 0 0", "0 0 0", identity, "sphere 1", "0 0 0", identity}),
         "shape A: hull of 4 points takes 12 coordinates, got 11"},
        {tsv({"b", "hull 6148914691236517206 0 0 0 1 0 0 0 1 0 0 0 1", "0 0 0", identity, "sphere 1", "0 0 0", identity}),
         "shape A: hull of 6148914691236517206 points takes 3 × 6148914691236517206 coordinates, got 12"},  // 3 n wrapped to 2
        {tsv({"b", "hull 4.5 0 0 0", "0 0 0", identity, "sphere 1", "0 0 0", identity}),
         "shape A: hull point count '4.5' is not an integer"},
        {tsv({"b", "hull 4 0 0 0 1 0 0 0 1 0 1 1 0", "0 0 0", identity, "sphere 1", "0 0 0", identity}),
         "shape A: xeno: make_convex_hull"},  // coplanar points
        {tsv({"b", "", "0 0 0", identity, "sphere 1", "0 0 0", identity}), "shape A: empty"},
        {tsv({"two words", "sphere 1", "0 0 0", identity, "sphere 1", "0 0 0", identity}), "id: must be one word"},
    };
    std::string text = good + "\n";
    for (const Bad& c : cases) text += c.line + "\n" + good + "\n";
    std::string err;
    int bad = 0;
    const std::string out = run_process(text, Precision::double_float, err, bad);
    CHECK(bad == static_cast<int>(cases.size()));
    CHECK(lines_of(out).size() == cases.size() + 1);  // every good line answered
    const std::vector<std::string> messages = lines_of(err);
    REQUIRE(messages.size() == cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::string prefix = "xeno_query: line " + std::to_string(2 * i + 2) + ": ";
        INFO(messages[i]);
        CHECK(messages[i].rfind(prefix + cases[i].message, 0) == 0);
    }
    // The same in float, where 1e39 does not fit.
    const std::string overflow = tsv({"b", "sphere 1e39", "0 0 0", identity, "sphere 1", "0 0 0", identity});
    run_process(overflow + "\n", Precision::single_float, err, bad);
    CHECK(bad == 1);
    CHECK(err.find("shape A: '1e39' is not finite") != std::string::npos);
    run_process(overflow + "\n", Precision::double_float, err, bad);
    CHECK(bad == 0);
}

TEST_CASE("regression: a NUL byte makes a bad line instead of ending it") {
    // "sphere 1\0garbage" was read as "sphere 1".
    const std::string good = tsv({"ok", "sphere 1", "0 0 0", identity, "sphere 1", "1.5 0 0", identity});
    const std::string nul = tsv({"n", std::string("sphere 1\0garbage", 16), "0 0 0", identity, "sphere 1", "1.5 0 0", identity});
    const std::string nul_only = std::string("\0", 1);
    std::string err;
    int bad = 0;
    const std::string out =
        run_process(good + "\n" + nul + "\n" + nul_only + "\n" + good + "\n", Precision::double_float, err, bad);
    CHECK(bad == 2);
    CHECK(lines_of(out).size() == 2);
    const std::vector<std::string> messages = lines_of(err);
    REQUIRE(messages.size() == 2);
    CHECK(messages[0].rfind("xeno_query: line 2: byte 11: a NUL byte", 0) == 0);
    CHECK(messages[1].rfind("xeno_query: line 3: byte 1: a NUL byte", 0) == 0);
}

TEST_CASE("regression: a stream that fails to read is reported, not taken as an empty input") {
    // A directory opens as a file and then fails to read: the tool exited 0 with no message.
    struct FailingBuffer : std::streambuf {
        int_type underflow() override { throw std::runtime_error("EISDIR"); }
    } buffer;
    std::istream in(&buffer);
    std::ostringstream out, errors;
    CHECK_THROWS_AS(process(in, out, errors, Precision::double_float), ReadError);
    CHECK(out.str().empty());
}

TEST_CASE("results print with the digits that round-trip the precision") {
    Penetration<float> pf;
    pf.hit = true;
    pf.depth = 0.1f;
    pf.normal = {0.0f, -0.0f, 1.0f};
    pf.point_a = {1.0f / 3.0f, 2.0f, -5.5f};
    pf.point_b = {1e-10f, 123456789.0f, 0.0f};
    CHECK(format_result("a", pf) == "a 1 0.100000001 0 0 1 0.333333343 2 -5.5 1.00000001e-10 123456792 0");
    Penetration<double> pd;
    pd.hit = true;
    pd.depth = 0.1;
    pd.normal = {0.0, 0.0, -1.0};
    pd.point_a = {1.0 / 3.0, 2.0, -5.5};
    pd.point_b = {1e-10, 123456789.0, -0.0};
    CHECK(format_result("b", pd) == "b 1 0.10000000000000001 0 0 -1 0.33333333333333331 2 -5.5 1e-10 123456789 0");
    CHECK(format_result("c", Penetration<double>{}) == "c 0");

    // Every number printed by a float run reads back (strtof) as the float the query returned.
    const std::string line =
        tsv({"r", "box 0.3 0.7 1.1", "0.1 0.2 0.3", "0.9 0.1 0.2 0.3", "cone 0.6 1.3", "0.4 0.5 0.9", "0.8 -0.3 0.1 0.2"});
    const Penetration<float> f = query_line<float>(line);
    REQUIRE(f.hit);
    std::string err;
    int bad = 0;
    const std::vector<std::string> words = words_of(run_process(line + "\n", Precision::single_float, err, bad));
    REQUIRE(words.size() == 12);
    const float expected[] = {f.depth,     f.normal.x,  f.normal.y,  f.normal.z,  f.point_a.x,
                              f.point_a.y, f.point_a.z, f.point_b.x, f.point_b.y, f.point_b.z};
    for (std::size_t i = 0; i < 10; ++i) CHECK(std::strtof(words[i + 2].c_str(), nullptr) == expected[i]);
    // The double run of the same line prints 17 digits and agrees to float accuracy.
    const std::vector<std::string> dwords = words_of(run_process(line + "\n", Precision::double_float, err, bad));
    REQUIRE(dwords.size() == 12);
    CHECK(std::strtod(dwords[2].c_str(), nullptr) == doctest::Approx(static_cast<double>(f.depth)).epsilon(1e-3));
}

TEST_CASE_TEMPLATE("swapping A and B flips the normal and swaps the points", T, float, double) {
    struct Side {
        std::string shape, pos, quat;
    };
    struct Pair {
        Side a, b;
        bool one_point;  ///< the contact is a single point (else any point of a patch will do)
    };
    const std::vector<Pair> pairs = {
        {{"box 1 0.5 0.75", "0 0 0", "0.9 0.1 0.2 0.3"}, {"cone 0.6 1.3", "0.3 0.4 1.1", "0.8 -0.3 0.1 0.2"}, true},
        {{"capsule 0.3 0.8", "0 0 0", "0.7 0.7 0 0"}, {"cylinder 0.5 0.4", "0.2 0.6 0.1", "1 0 0 0"}, true},
        {{"hull 5 0 0 0 1 0 0 0 1 0 0 0 1 0.5 0.5 0.5", "2 0 0", "1 0 0 0"}, {"sphere 0.4", "2.25 0.35 0.6", "1 0 0 0"}, true},
        // A face of the small box against a face of the large one: a patch.
        {{"box 1 1 1", "0 0 0", "1 0 0 0"}, {"box 0.5 0.5 0.5", "1.2 0.3 -0.2", "0.95 0 0.31 0"}, false},
    };
    for (const Pair& pair : pairs) {
        const Side& a = pair.a;
        const Side& b = pair.b;
        const Penetration<T> ab = query_line<T>(pair_line(a.shape, a.pos, a.quat, b.shape, b.pos, b.quat));
        const Penetration<T> ba = query_line<T>(pair_line(b.shape, b.pos, b.quat, a.shape, a.pos, a.quat));
        INFO(a.shape << " / " << b.shape);
        REQUIRE(ab.hit);
        REQUIRE(ba.hit);
        const T tol = std::is_same_v<T, float> ? T(2e-3) : T(1e-4);
        CHECK(std::abs(ab.depth - ba.depth) <= tol);
        CHECK(dot(ab.normal, ba.normal) <= T(-1) + tol);
        CHECK(near(ab.point_a - ab.point_b, ab.normal * ab.depth, tol));
        CHECK(near(ba.point_a - ba.point_b, ba.normal * ba.depth, tol));
        if (pair.one_point) {
            CHECK(near(ab.point_a, ba.point_b, tol));
            CHECK(near(ab.point_b, ba.point_a, tol));
        }
    }
}

TEST_CASE("options: precision, help, unknown options") {
    const char* plain[] = {"xeno_query"};
    Options o = parse_options(1, plain);
    CHECK(o.precision == Precision::double_float);
    CHECK(o.input.empty());
    const char* with_float[] = {"xeno_query", "--precision", "float", "pairs.tsv"};
    o = parse_options(4, with_float);
    CHECK(o.precision == Precision::single_float);
    CHECK(o.input == "pairs.tsv");
    const char* with_equals[] = {"xeno_query", "--precision=double", "-"};
    o = parse_options(3, with_equals);
    CHECK(o.precision == Precision::double_float);
    CHECK(o.input == "-");
    const char* help[] = {"xeno_query", "--help"};
    CHECK(parse_options(2, help).help);
    CHECK(usage().find("xeno::collide()") != std::string::npos);
    const char* unknown[] = {"xeno_query", "--fast"};
    CHECK_THROWS_AS(parse_options(2, unknown), OptionsError);
    const char* bad_value[] = {"xeno_query", "--precision", "half"};
    CHECK_THROWS_AS(parse_options(3, bad_value), OptionsError);
    const char* missing[] = {"xeno_query", "--precision"};
    CHECK_THROWS_AS(parse_options(2, missing), OptionsError);
    const char* two_files[] = {"xeno_query", "a.tsv", "b.tsv"};
    CHECK_THROWS_AS(parse_options(3, two_files), OptionsError);
}

TEST_CASE("the sample file gives its expected output") {
    std::ifstream input(XENO_QUERY_SAMPLE_DIR "/sample_pairs.tsv");
    std::ifstream expected_file(XENO_QUERY_SAMPLE_DIR "/sample_pairs.expected");
    REQUIRE(input);
    REQUIRE(expected_file);
    std::ostringstream out, err, expected;
    expected << expected_file.rdbuf();
    CHECK(process(input, out, err, Precision::double_float) == 2);
    const std::vector<std::string> got = lines_of(out.str()), want = lines_of(expected.str());
    REQUIRE(got.size() == want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        // Ids and hit flags exactly, numbers to 1e-9 (another compiler may round differently).
        const std::vector<std::string> g = words_of(got[i]), w = words_of(want[i]);
        INFO(got[i]);
        REQUIRE(g.size() == w.size());
        CHECK(g[0] == w[0]);
        CHECK(g[1] == w[1]);
        for (std::size_t k = 2; k < g.size(); ++k)
            CHECK(std::strtod(g[k].c_str(), nullptr) ==
                  doctest::Approx(std::strtod(w[k].c_str(), nullptr)).epsilon(1e-9).scale(1));
    }
}

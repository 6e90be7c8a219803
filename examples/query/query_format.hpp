// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The text format of xeno_query, the narrow-phase query tool, and its conversion to the library's
// conventions. The format is an interchange format fixed by its issue (docs/conventions.md, "Units
// and axes"): one pair per line, tab-separated columns
//     id  shapeA  posA  quatA  shapeB  posB  quatB      (columns after the seventh are ignored)
// where a position is "x y z" (the shape's local origin in the world), a quaternion "w x y z"
// (normalised here; zero or non-finite is rejected) and a shape one of
//     box hx hy hz      half extents                    sphere r
//     capsule r hh      segment half-length, caps excluded (hh = 0 is a sphere)
//     cylinder r hh     half height                     cone r h    full height
//     hull n x1 y1 z1 ... xn yn zn                      convex hull of n >= 4 local points
// Capsule, cylinder and cone lie along the format's local z; the cone's local origin is at
// mid-height (base at z = -h/2, apex at +h/2); a hull's local origin need not be inside it.
// A first line whose first column is "id" is a header.
//
// Conversion to the library (axis along local y, origins at the centre of mass). A format shape
// placed by the pose F = (p, q) becomes a library shape placed by F ∘ L, L = (offset, R):
//   R      = R_zy = rotation by +90° about x for capsule, cylinder and cone, identity otherwise.
//            R_zy takes library-local y to format-local z: rotating (0, 1, 0) by +θ about x gives
//            (0, cos θ, sin θ), which is (0, 0, 1) for θ = +90° (q = (cos 45°, sin 45°, 0, 0)).
//   offset = where the library origin lies in the format's local frame:
//            cone: its centre of mass, a quarter of the height above the base, so
//                  -h/2 + h/4 = -h/4 along z: offset (0, 0, -h/4);
//            hull: the shift make_convex_hull reports (the centroid among the given points);
//            other shapes: 0.
//   World pose of the library shape: position p + rotate(q, offset), orientation q · R.
// Results need no conversion back: the normal and the points are in world space.
#pragma once

#include <xeno/collide/collide.hpp>

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace xeno::query {

/// A rejected input line; what() says what is wrong, without the "xeno_query: line N: " prefix.
class LineError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A rejected command line (unknown option, missing or bad value); main exits with status 2.
class OptionsError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The input stream failed while being read (a directory, a device that fails to read); main
/// exits with status 2.
class ReadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The scalar every number of a run is parsed, computed and printed in.
enum class Precision { single_float, double_float };

/// Everything the command line can say.
struct Options {
    Precision precision = Precision::double_float;  ///< --precision float|double
    std::string input;                              ///< file to read; empty or "-" = standard input
    bool help = false;                              ///< --help / -h: print usage and exit
};

/// Parses argv[1 .. argc). Throws OptionsError for unknown options, a bad --precision value or
/// more than one input file.
Options parse_options(int argc, const char* const* argv);

/// The --help text.
std::string usage();

/// The format's shape kinds.
enum class ShapeKind { box, sphere, capsule, cylinder, cone, hull };

/// One shape column as written, in the format's conventions (axis along local z).
template <class T>
struct ShapeSpec {
    ShapeKind kind = ShapeKind::sphere;
    std::vector<T> params;        ///< box: hx hy hz; sphere: r; capsule, cylinder: r hh; cone: r h
    std::vector<Vec3<T>> points;  ///< hull: the local points (metres, format frame)
};

/// A shape converted to the library's conventions, with the world pose of its library frame.
template <class T>
struct PlacedShape {
    Shape<T> shape;
    Transform<T> pose;
};

/// One parsed input line, converted.
template <class T>
struct Query {
    std::string id;
    PlacedShape<T> a, b;
};

/// R_zy: the rotation taking library-local y (the library's shape axis) to format-local z, a
/// +90° rotation about x.
template <class T>
Quat<T> library_to_format_axes();

/// Parses a shape column such as "box 1 2 3" or "hull 4 0 0 0 1 0 0 0 1 0 0 0 1". Throws
/// LineError for an unknown name, a wrong number of parameters, a token that is not a finite
/// number, a non-positive size (capsule hh may be 0) or a hull of fewer than 4 points.
template <class T>
ShapeSpec<T> parse_shape(const std::string& column);

/// Parses a position column "x y z". Throws LineError for a wrong count or a non-finite number.
template <class T>
Vec3<T> parse_position(const std::string& column);

/// Parses a quaternion column "w x y z" and normalises it. Throws LineError for a wrong count, a
/// non-finite component or a zero quaternion.
template <class T>
Quat<T> parse_orientation(const std::string& column);

/// The library shape for spec and the world pose of its frame, given the format pose (position
/// of the format's local origin, unit orientation); see the file comment. Throws LineError when
/// the library rejects the shape (a hull of coincident, collinear or coplanar points).
template <class T>
PlacedShape<T> to_library(const ShapeSpec<T>& spec, const Transform<T>& format_pose);

/// True for a header line: its first column is "id".
bool is_header(const std::string& line);

/// Parses and converts a whole data line (a trailing '\r' is ignored). Throws LineError whose
/// message names the column ("shape B: unknown shape 'boxx'"); the functions above leave the
/// column's name out of their messages and parse_line puts it in.
template <class T>
Query<T> parse_line(const std::string& line);

/// The output line for a result, without newline: "id 1 depth nx ny nz pAx pAy pAz pBx pBy pBz"
/// on a hit, "id 0" otherwise; numbers with enough digits to read back the same T (%.9g for
/// float, %.17g for double), -0 written as 0.
template <class T>
std::string format_result(const std::string& id, const Penetration<T>& result);

/// Runs xeno::collide() (the refined query) on a parsed line. Throws LineError when the library
/// rejects the poses or returns a non-finite number.
template <class T>
Penetration<T> run_query(const Query<T>& query);

/// Reads every line of in, writes one result line per good pair to out and one message per bad
/// line to err ("xeno_query: line 7: shape B: unknown shape 'boxx'"). Blank lines are skipped;
/// a line holding a NUL byte is a bad line. Returns the number of bad lines; throws ReadError
/// when reading in fails (the lines before are answered).
int process(std::istream& in, std::ostream& out, std::ostream& err, Precision precision);

}  // namespace xeno::query

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Parsing, conversion and printing for xeno_query (the format and the conversion formulas are in
// query_format.hpp). Numbers are read straight into the run's scalar (strtof or strtod, in the
// "C" locale main never changes), so a float run sees the correctly rounded float of every token.
// The templates are instantiated below for float and double.
#include "query/query_format.hpp"

#include <xeno/shape/convex_hull.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <istream>
#include <ostream>
#include <utility>

namespace xeno::query {

namespace {

/// The line without a trailing carriage return (files written on Windows).
std::string without_cr(const std::string& line) {
    if (!line.empty() && line.back() == '\r') return line.substr(0, line.size() - 1);
    return line;
}

/// Tab-separated columns.
std::vector<std::string> split_columns(const std::string& line) {
    std::vector<std::string> columns;
    std::size_t start = 0;
    for (;;) {
        const std::size_t tab = line.find('\t', start);
        columns.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
        if (tab == std::string::npos) return columns;
        start = tab + 1;
    }
}

/// Whitespace-separated words of one column.
std::vector<std::string> split_words(const std::string& column) {
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < column.size()) {
        while (i < column.size() && std::isspace(static_cast<unsigned char>(column[i]))) ++i;
        const std::size_t start = i;
        while (i < column.size() && !std::isspace(static_cast<unsigned char>(column[i]))) ++i;
        if (i > start) words.push_back(column.substr(start, i - start));
    }
    return words;
}

float to_scalar(const char* text, char** end, float) { return std::strtof(text, end); }
double to_scalar(const char* text, char** end, double) { return std::strtod(text, end); }

/// The whole word as a finite T; LineError for anything else ("1.5x", "nan", "1e39" in float).
template <class T>
T parse_number(const std::string& word) {
    char* end = nullptr;
    const T value = to_scalar(word.c_str(), &end, T{});
    if (end == word.c_str() || *end != '\0') throw LineError("'" + word + "' is not a number");
    if (!std::isfinite(value)) throw LineError("'" + word + "' is not finite");
    return value;
}

/// Exactly count numbers in words[first ..]; what describes them for the message.
template <class T>
std::vector<T> parse_numbers(const std::vector<std::string>& words, std::size_t first, std::size_t count,
                             const std::string& what) {
    const std::size_t given = words.size() - first;
    if (given != count)
        throw LineError("expected " + std::to_string(count) + " numbers (" + what + "), got " + std::to_string(given));
    std::vector<T> values;
    for (std::size_t i = first; i < words.size(); ++i) values.push_back(parse_number<T>(words[i]));
    return values;
}

std::string number_text(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", value);
    return buffer;
}

/// Rejects a size that is not > 0 (or, with zero_allowed, not >= 0).
template <class T>
void require_size(T value, const char* shape, const char* name, bool zero_allowed = false) {
    if (value > T(0) || (zero_allowed && value == T(0))) return;
    throw LineError(std::string(shape) + " " + name + (zero_allowed ? " must be >= 0" : " must be > 0") + " (got " +
                    number_text(static_cast<double>(value)) + ")");
}

/// Runs parse and prefixes a LineError's message with the column's name.
template <class F>
auto in_column(const char* column, F parse) -> decltype(parse()) {
    try {
        return parse();
    } catch (const LineError& e) {
        throw LineError(std::string(column) + ": " + e.what());
    }
}

/// Prints a number with the digits that round-trip T; -0 prints as 0.
template <class T>
void append_number(std::string& out, T value) {
    if (value == T(0)) value = T(0);
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, std::is_same_v<T, float> ? "%.9g" : "%.17g", static_cast<double>(value));
    out += ' ';
    out += buffer;
}

template <class T>
bool is_finite_result(const Penetration<T>& p) {
    return std::isfinite(p.depth) && is_finite(p.normal) && is_finite(p.point_a) && is_finite(p.point_b);
}

template <class T>
int process_as(std::istream& in, std::ostream& out, std::ostream& err) {
    int bad = 0;
    long line_number = 0;
    std::string line;
    while (std::getline(in, line)) {
        ++line_number;
        if (line_number == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);  // UTF-8 byte-order mark
        if (line_number == 1 && is_header(line)) continue;
        if (split_words(line).empty() && line.find('\0') == std::string::npos) continue;  // blank line
        try {
            // A NUL would end the line for the number parser ("sphere 1\0garbage" read as "sphere 1").
            if (const std::size_t nul = line.find('\0'); nul != std::string::npos)
                throw LineError("byte " + std::to_string(nul + 1) + ": a NUL byte (binary input?)");
            const Query<T> query = parse_line<T>(line);
            out << format_result(query.id, run_query(query)) << '\n';
        } catch (const std::exception& e) {
            // LineError for bad input; anything else (out of memory on a huge hull) is reported
            // the same way, so one line never stops the run.
            err << "xeno_query: line " << line_number << ": " << e.what() << '\n';
            ++bad;
        }
    }
    if (in.bad())
        throw ReadError("reading failed after line " + std::to_string(line_number) + " (a directory or an unreadable file?)");
    return bad;
}

}  // namespace

Options parse_options(int argc, const char* const* argv) {
    Options options;
    bool have_input = false, only_files = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (!only_files && (arg == "--help" || arg == "-h")) {
            options.help = true;
        } else if (!only_files && (arg == "--precision" || arg.rfind("--precision=", 0) == 0)) {
            std::string value;
            if (arg == "--precision") {
                if (i + 1 >= argc) throw OptionsError("--precision needs a value (float or double)");
                value = argv[++i];
            } else {
                value = arg.substr(std::string("--precision=").size());
            }
            if (value == "float") options.precision = Precision::single_float;
            else if (value == "double") options.precision = Precision::double_float;
            else throw OptionsError("--precision must be float or double (got '" + value + "')");
        } else if (!only_files && arg == "--") {
            only_files = true;
        } else if (!only_files && arg.size() > 1 && arg[0] == '-') {
            throw OptionsError("unknown option '" + arg + "'");
        } else {
            if (have_input) throw OptionsError("only one input file is read (got '" + options.input + "' and '" + arg + "')");
            options.input = arg;
            have_input = true;
        }
    }
    return options;
}

std::string usage() {
    return "usage: xeno_query [--precision float|double] [FILE]\n"
           "\n"
           "Answers narrow-phase queries: for each pair of shapes read from FILE (standard input\n"
           "when FILE is absent or '-') prints whether they overlap and, if so, how. Each pair is\n"
           "run through xeno::collide(), the refined query the world uses (MPR penetration, then\n"
           "the supporting faces tried as normals; closed-form separating axes for two boxes).\n"
           "\n"
           "Input: one pair per line, tab-separated columns\n"
           "  id  shapeA  posA  quatA  shapeB  posB  quatB      (further columns are ignored)\n"
           "  position  x y z      the shape's local origin in the world\n"
           "  quaternion w x y z   orientation, normalised (zero or non-finite is an error)\n"
           "  shape     box hx hy hz | sphere r | capsule r hh | cylinder r hh | cone r h |\n"
           "            hull n x1 y1 z1 ... xn yn zn\n"
           "  box: half extents; capsule: hh = segment half-length, caps excluded; cylinder: hh =\n"
           "  half height; cone: h = full height, base at local z = -h/2, apex at +h/2; hull: the\n"
           "  convex hull of n >= 4 local points (the local origin need not be inside).\n"
           "  Capsule, cylinder and cone lie along local z. A first line whose first column is\n"
           "  'id' is a header. Blank lines are skipped.\n"
           "\n"
           "Output: one line per good pair, space-separated:\n"
           "  id 1 depth nx ny nz pAx pAy pAz pBx pBy pBz   overlap: normal from A to B, points on\n"
           "                                                A and B, all in world space\n"
           "  id 0                                          no overlap (touching is no overlap)\n"
           "  Numbers have enough digits to read back exactly (9 for float, 17 for double).\n"
           "\n"
           "Options:\n"
           "  --precision float|double   scalar for parsing, the query and printing (default double)\n"
           "  -h, --help                 print this text\n"
           "\n"
           "A bad line (a NUL byte makes one) is reported on standard error with its line number\n"
           "and skipped.\n"
           "Exit status: 0 all lines good, 1 some line was bad, 2 bad command line or input that\n"
           "cannot be opened or read (a directory, a read error).\n";
}

template <class T>
Quat<T> library_to_format_axes() {
    // +90° about x: (cos 45°, sin 45° · (1, 0, 0)); rotate(q, y) = (0, cos 90°, sin 90°) = z.
    const T half = std::sqrt(T(0.5));
    return {half, half, T(0), T(0)};
}

template <class T>
ShapeSpec<T> parse_shape(const std::string& column) {
    const std::vector<std::string> words = split_words(column);
    if (words.empty()) throw LineError("empty (expected box, sphere, capsule, cylinder, cone or hull)");
    const std::string& name = words[0];
    ShapeSpec<T> spec;
    if (name == "box") {
        spec.kind = ShapeKind::box;
        spec.params = parse_numbers<T>(words, 1, 3, "box hx hy hz");
        require_size(spec.params[0], "box", "hx");
        require_size(spec.params[1], "box", "hy");
        require_size(spec.params[2], "box", "hz");
    } else if (name == "sphere") {
        spec.kind = ShapeKind::sphere;
        spec.params = parse_numbers<T>(words, 1, 1, "sphere r");
        require_size(spec.params[0], "sphere", "r");
    } else if (name == "capsule") {
        spec.kind = ShapeKind::capsule;
        spec.params = parse_numbers<T>(words, 1, 2, "capsule r hh");
        require_size(spec.params[0], "capsule", "r");
        require_size(spec.params[1], "capsule", "hh", true);  // hh = 0: a sphere, as in the library
    } else if (name == "cylinder") {
        spec.kind = ShapeKind::cylinder;
        spec.params = parse_numbers<T>(words, 1, 2, "cylinder r hh");
        require_size(spec.params[0], "cylinder", "r");
        require_size(spec.params[1], "cylinder", "hh");
    } else if (name == "cone") {
        spec.kind = ShapeKind::cone;
        spec.params = parse_numbers<T>(words, 1, 2, "cone r h");
        require_size(spec.params[0], "cone", "r");
        require_size(spec.params[1], "cone", "h");
    } else if (name == "hull") {
        spec.kind = ShapeKind::hull;
        if (words.size() < 2) throw LineError("hull needs a point count n and n points");
        char* end = nullptr;
        errno = 0;
        const long n = std::strtol(words[1].c_str(), &end, 10);
        if (end == words[1].c_str() || *end != '\0' || errno == ERANGE)
            throw LineError("hull point count '" + words[1] + "' is not an integer");
        if (n < 4) throw LineError("hull needs at least 4 points (got n = " + words[1] + ")");
        const std::size_t given = words.size() - 2;
        if (static_cast<unsigned long>(n) > given || given != 3 * static_cast<std::size_t>(n)) {
            // 3 n only when n fits the line: for n of 6·10¹⁸ it wrapped and the message named 2.
            const std::string needed =
                static_cast<unsigned long>(n) <= given ? std::to_string(3 * static_cast<unsigned long>(n)) : "3 × " + words[1];
            throw LineError("hull of " + words[1] + " points takes " + needed + " coordinates, got " + std::to_string(given));
        }
        for (std::size_t i = 2; i < words.size(); i += 3)
            spec.points.push_back({parse_number<T>(words[i]), parse_number<T>(words[i + 1]), parse_number<T>(words[i + 2])});
    } else {
        throw LineError("unknown shape '" + name + "' (expected box, sphere, capsule, cylinder, cone or hull)");
    }
    return spec;
}

template <class T>
Vec3<T> parse_position(const std::string& column) {
    const std::vector<T> v = parse_numbers<T>(split_words(column), 0, 3, "x y z");
    return {v[0], v[1], v[2]};
}

template <class T>
Quat<T> parse_orientation(const std::string& column) {
    const std::vector<T> v = parse_numbers<T>(split_words(column), 0, 4, "w x y z");
    // Scale by the largest component first, so that neither tiny nor huge values under- or
    // overflow when squared.
    T largest = T(0);
    for (const T c : v) largest = std::max(largest, std::abs(c));
    if (largest == T(0)) throw LineError("the zero quaternion is not a rotation");
    const Quat<T> scaled{v[0] / largest, v[1] / largest, v[2] / largest, v[3] / largest};
    return scaled * (T(1) / length(scaled));
}

template <class T>
PlacedShape<T> to_library(const ShapeSpec<T>& spec, const Transform<T>& format_pose) {
    // local = where the library frame sits in the format's local frame (file comment of the header).
    Transform<T> local = Transform<T>::identity();
    const std::vector<T>& p = spec.params;
    try {
        switch (spec.kind) {
            case ShapeKind::box: return {Box<T>(p[0], p[1], p[2]), format_pose};
            case ShapeKind::sphere: return {Sphere<T>(p[0]), format_pose};
            case ShapeKind::capsule:
                local.orientation = library_to_format_axes<T>();
                return {Capsule<T>(p[0], p[1]), format_pose * local};
            case ShapeKind::cylinder:
                local.orientation = library_to_format_axes<T>();
                return {Cylinder<T>(p[0], p[1]), format_pose * local};
            case ShapeKind::cone:
                // Format origin at mid-height, base at z = -h/2; the library's origin is the centre
                // of mass, h/4 above the base: z = -h/2 + h/4 = -h/4.
                local.orientation = library_to_format_axes<T>();
                local.position = {T(0), T(0), T(-0.25) * p[1]};
                return {Cone<T>(p[0], p[1]), format_pose * local};
            case ShapeKind::hull: {
                ConvexHull<T> hull = make_convex_hull(spec.points);
                local.position = hull.shift;  // the centroid among the format's local points
                return {std::move(hull.polyhedron), format_pose * local};
            }
        }
    } catch (const InvalidArgument& e) {
        throw LineError(e.what());
    }
    throw LineError("unknown shape kind");
}

bool is_header(const std::string& line) {
    const std::vector<std::string> words = split_words(split_columns(without_cr(line))[0]);
    return words.size() == 1 && words[0] == "id";
}

template <class T>
Query<T> parse_line(const std::string& raw_line) {
    const std::vector<std::string> columns = split_columns(without_cr(raw_line));
    if (columns.size() < 7)
        throw LineError("expected 7 tab-separated columns (id shapeA posA quatA shapeB posB quatB), got " +
                        std::to_string(columns.size()));
    const std::vector<std::string> id_words = split_words(columns[0]);
    if (id_words.size() != 1) throw LineError("id: must be one word without spaces (got '" + columns[0] + "')");
    const ShapeSpec<T> spec_a = in_column("shape A", [&] { return parse_shape<T>(columns[1]); });
    const Transform<T> pose_a{in_column("posA", [&] { return parse_position<T>(columns[2]); }),
                              in_column("quatA", [&] { return parse_orientation<T>(columns[3]); })};
    const ShapeSpec<T> spec_b = in_column("shape B", [&] { return parse_shape<T>(columns[4]); });
    const Transform<T> pose_b{in_column("posB", [&] { return parse_position<T>(columns[5]); }),
                              in_column("quatB", [&] { return parse_orientation<T>(columns[6]); })};
    PlacedShape<T> a = in_column("shape A", [&] { return to_library(spec_a, pose_a); });
    PlacedShape<T> b = in_column("shape B", [&] { return to_library(spec_b, pose_b); });
    return {id_words[0], std::move(a), std::move(b)};
}

template <class T>
std::string format_result(const std::string& id, const Penetration<T>& result) {
    std::string line = id;
    if (!result.hit) return line + " 0";
    line += " 1";
    append_number(line, result.depth);
    for (const Vec3<T>* v : {&result.normal, &result.point_a, &result.point_b}) {
        append_number(line, v->x);
        append_number(line, v->y);
        append_number(line, v->z);
    }
    return line;
}

template <class T>
Penetration<T> run_query(const Query<T>& query) {
    Penetration<T> result;
    try {
        result = collide(query.a.shape, query.a.pose, query.b.shape, query.b.pose);
    } catch (const InvalidArgument& e) {
        // A pose that overflowed while converting (a finite position plus a huge offset).
        throw LineError(e.what());
    }
    if (result.hit && !is_finite_result(result)) throw LineError("the query returned a non-finite number");
    return result;
}

int process(std::istream& in, std::ostream& out, std::ostream& err, Precision precision) {
    return precision == Precision::single_float ? process_as<float>(in, out, err) : process_as<double>(in, out, err);
}

// The two scalars a run can use.
template Quat<float> library_to_format_axes<float>();
template ShapeSpec<float> parse_shape<float>(const std::string&);
template Vec3<float> parse_position<float>(const std::string&);
template Quat<float> parse_orientation<float>(const std::string&);
template PlacedShape<float> to_library<float>(const ShapeSpec<float>&, const Transform<float>&);
template Query<float> parse_line<float>(const std::string&);
template std::string format_result<float>(const std::string&, const Penetration<float>&);
template Penetration<float> run_query<float>(const Query<float>&);
template Quat<double> library_to_format_axes<double>();
template ShapeSpec<double> parse_shape<double>(const std::string&);
template Vec3<double> parse_position<double>(const std::string&);
template Quat<double> parse_orientation<double>(const std::string&);
template PlacedShape<double> to_library<double>(const ShapeSpec<double>&, const Transform<double>&);
template Query<double> parse_line<double>(const std::string&);
template std::string format_result<double>(const std::string&, const Penetration<double>&);
template Penetration<double> run_query<double>(const Query<double>&);

}  // namespace xeno::query

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Tests of the OSMesa renderer against a scene whose image is known in outline: a red unit box on
// the ground seen from (4, 3, 6). They check what a broken pipeline gets wrong (a blank or
// upside-down frame, geometry where the camera maths does not put it, a PNG that does not read
// back), the command-line parser, and draw_shape's winding.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include "render/options.hpp"
#include "render/renderer.hpp"

#include <xeno/debug_draw.hpp>
#include <xeno/shape/polyhedra.hpp>

#include <png.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace {

using namespace xeno::render;
using xeno::f64::Vec3;

constexpr int width = 320, height = 240;

struct Rgb {
    double r, g, b;
};

Rgb pixel(const Renderer& r, int x, int y) {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width()) + static_cast<std::size_t>(x)) * 4;
    const std::vector<unsigned char>& p = r.pixels();
    return {double(p[i]), double(p[i + 1]), double(p[i + 2])};
}

bool is_red(const Rgb& c) { return c.r > 80 && c.r > 1.6 * c.g && c.r > 1.6 * c.b; }

Camera test_camera() {
    Camera c;
    c.position = {4, 3, 6};
    c.target = {0, 0.5, 0};
    return c;
}

/// Renders the red box (half extent 0.5) centred at `centre` with the test camera.
void render_box(Renderer& r, const Vec3& centre) {
    r.begin_frame(test_camera());
    DrawAdapter<double> out(r);
    const xeno::f64::Shape box = xeno::f64::Box(0.5, 0.5, 0.5);
    xeno::draw_shape(out, box, xeno::f64::Transform{centre, xeno::f64::Quat::identity()}, xeno::Color{0.9f, 0.12f, 0.1f, 1},
                     xeno::Color{0.1f, 0.05f, 0.05f, 1});
    r.end_frame();
}

/// Mean position of the red pixels; count returned through n.
Vec3 red_centroid(const Renderer& r, int& n) {
    double sx = 0, sy = 0;
    n = 0;
    for (int y = 0; y < r.height(); ++y)
        for (int x = 0; x < r.width(); ++x)
            if (is_red(pixel(r, x, y))) {
                sx += x + 0.5;
                sy += y + 0.5;
                ++n;
            }
    return n > 0 ? Vec3{sx / n, sy / n, 0} : Vec3{-1, -1, 0};
}

/// Fraction of red pixels in the (2k+1)² window around p.
double red_fraction_around(const Renderer& r, const Vec3& p, int k) {
    const int cx = static_cast<int>(p.x), cy = static_cast<int>(p.y);
    int red = 0, all = 0;
    for (int y = cy - k; y <= cy + k; ++y)
        for (int x = cx - k; x <= cx + k; ++x)
            if (x >= 0 && y >= 0 && x < r.width() && y < r.height()) {
                ++all;
                red += is_red(pixel(r, x, y)) ? 1 : 0;
            }
    return all ? double(red) / all : 0;
}

Rgb row_mean(const Renderer& r, int y) {
    Rgb m{0, 0, 0};
    for (int x = 0; x < r.width(); ++x) {
        const Rgb c = pixel(r, x, y);
        m.r += c.r / r.width();
        m.g += c.g / r.width();
        m.b += c.b / r.width();
    }
    return m;
}

std::string temp_png(const char* tag) {
    return (std::filesystem::temp_directory_path() /
            ("xeno_render_test_" + std::string(tag) + "_" + std::to_string(::getpid()) + ".png"))
        .string();
}

}  // namespace

TEST_CASE("a frame of a red box on the ground is lit, the right way up and not blank") {
    Renderer r(width, height);
    render_box(r, {0, 0.5, 0});
    REQUIRE(r.pixels().size() == std::size_t(width) * height * 4);

    // Not blank: the luminance varies.
    double sum = 0, sum_sq = 0;
    const double n = double(width) * height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Rgb c = pixel(r, x, y);
            const double l = 0.3 * c.r + 0.59 * c.g + 0.11 * c.b;
            sum += l;
            sum_sq += l * l;
        }
    const double variance = sum_sq / n - (sum / n) * (sum / n);
    CHECK(variance > 100);

    // Sky on top (bluish), ground at the bottom (grey, clearly different): the image is not flipped.
    const Rgb top = row_mean(r, 0), bottom = row_mean(r, height - 1);
    INFO("top row ", top.r, " ", top.g, " ", top.b, ", bottom row ", bottom.r, " ", bottom.g, " ", bottom.b);
    CHECK(top.b > top.r + 25);
    CHECK(top.b > 180);
    CHECK(std::abs(top.b - bottom.b) + std::abs(top.r - bottom.r) > 40);
    CHECK(std::abs(bottom.r - bottom.b) < 25);
    // Every pixel is opaque (sky, ground and bodies all write alpha 1).
    CHECK(r.pixels()[3] == 255);
    CHECK(r.pixels()[r.pixels().size() - 1] == 255);
    CHECK(r.triangle_count() == 12);
    CHECK(r.line_count() == 12);
}

TEST_CASE("the box appears where project() puts it, and nothing red beside it") {
    Renderer r(width, height);
    render_box(r, {0, 0.5, 0});
    const Vec3 centre = r.project({0, 0.5, 0});
    CHECK(centre.z > 0);
    CHECK(centre.z < 1);
    CHECK(red_fraction_around(r, centre, 3) > 0.7);
    for (const Vec3& side : {Vec3{3, 0.5, 0}, Vec3{-3, 0.5, 0}, Vec3{0, 0.5, -3}, Vec3{0, 2.2, 0}}) {
        const Vec3 p = r.project(side);
        REQUIRE(p.x >= 0);
        REQUIRE(p.x < width);
        REQUIRE(p.y >= 0);
        REQUIRE(p.y < height);
        CHECK_FALSE(is_red(pixel(r, int(p.x), int(p.y))));
    }
    // The target of the camera is at the image centre.
    const Vec3 target = r.project(test_camera().target);
    CHECK(target.x == doctest::Approx(width / 2.0));
    CHECK(target.y == doctest::Approx(height / 2.0));
}

TEST_CASE("moving the box moves its red pixels as project() predicts") {
    Renderer r(width, height);
    const Vec3 a{0, 0.5, 0}, b{1.5, 0.5, -1.5};
    render_box(r, a);
    int n_a = 0, n_b = 0;
    const Vec3 seen_a = red_centroid(r, n_a), predicted_a = r.project(a);
    render_box(r, b);
    const Vec3 seen_b = red_centroid(r, n_b), predicted_b = r.project(b);
    REQUIRE(n_a > 200);
    REQUIRE(n_b > 200);
    INFO("centroid a ", seen_a.x, ",", seen_a.y, " predicted ", predicted_a.x, ",", predicted_a.y);
    INFO("centroid b ", seen_b.x, ",", seen_b.y, " predicted ", predicted_b.x, ",", predicted_b.y);
    CHECK(std::hypot(seen_a.x - predicted_a.x, seen_a.y - predicted_a.y) < 10);
    CHECK(std::hypot(seen_b.x - predicted_b.x, seen_b.y - predicted_b.y) < 10);
    // Direction of the move on screen.
    const double sx = seen_b.x - seen_a.x, sy = seen_b.y - seen_a.y;
    const double px = predicted_b.x - predicted_a.x, py = predicted_b.y - predicted_a.y;
    CHECK(std::hypot(px, py) > 20);
    CHECK((sx * px + sy * py) / (std::hypot(sx, sy) * std::hypot(px, py)) > 0.98);
    // Farther away, the box covers fewer pixels.
    CHECK(n_b < n_a);
}

TEST_CASE("write_png writes a PNG that reads back as the same image, top row first") {
    Renderer r(width, height);
    render_box(r, {0, 0.5, 0});
    const std::string path = temp_png("roundtrip");
    REQUIRE(r.write_png(path));

    // Signature and IHDR size, by hand.
    unsigned char head[24] = {};
    std::FILE* f = std::fopen(path.c_str(), "rb");
    REQUIRE(f != nullptr);
    CHECK(std::fread(head, 1, sizeof head, f) == sizeof head);
    std::fclose(f);
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    CHECK(std::equal(signature, signature + 8, head));
    const auto be32 = [&](int at) {
        return (unsigned(head[at]) << 24) | (unsigned(head[at + 1]) << 16) | (unsigned(head[at + 2]) << 8) |
               unsigned(head[at + 3]);
    };
    CHECK(std::string(reinterpret_cast<const char*>(head + 12), 4) == "IHDR");
    CHECK(be32(16) == unsigned(width));
    CHECK(be32(20) == unsigned(height));

    // The whole image, through libpng's simplified API: lossless, same orientation.
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    REQUIRE(png_image_begin_read_from_file(&image, path.c_str()));
    image.format = PNG_FORMAT_RGBA;
    std::vector<unsigned char> back(PNG_IMAGE_SIZE(image));
    REQUIRE(png_image_finish_read(&image, nullptr, back.data(), 0, nullptr));
    CHECK(image.width == unsigned(width));
    CHECK(image.height == unsigned(height));
    CHECK(back == r.pixels());
    std::filesystem::remove(path);

    CHECK_FALSE(r.write_png("/nonexistent-directory/x.png"));
}

TEST_CASE("two renderers can take turns") {
    Renderer a(width, height), b(160, 120);
    render_box(a, {0, 0.5, 0});
    const std::vector<unsigned char> first = a.pixels();
    render_box(b, {0, 0.5, 0});
    render_box(a, {0, 0.5, 0});
    CHECK(a.pixels() == first);
    int n = 0;
    red_centroid(b, n);
    CHECK(n > 50);
}

TEST_CASE("a degenerate camera is rejected before anything is drawn") {
    Renderer r(64, 48);
    Camera c = test_camera();
    c.target = c.position;
    CHECK_THROWS_AS(r.begin_frame(c), std::invalid_argument);
    c = test_camera();
    c.far = c.near;
    CHECK_THROWS_AS(r.begin_frame(c), std::invalid_argument);
    c = test_camera();
    c.up = {0, 0, 0};
    CHECK_THROWS_AS(r.begin_frame(c), std::invalid_argument);
    // Looking straight down (up parallel to the view) still works.
    c = test_camera();
    c.position = {0, 10, 0};
    c.target = {0, 0, 0};
    CHECK_NOTHROW(r.begin_frame(c));
    CHECK_NOTHROW(r.end_frame());
    CHECK_THROWS_AS(Renderer(0, 10), std::runtime_error);
}

TEST_CASE("orbit turns the camera about the target around +y, right-handed") {
    Camera c;
    c.position = {1, 2, 5};
    c.target = {1, 0, 0};
    const Camera turned = orbit(c, std::acos(-1.0) / 2);
    CHECK(turned.position.x == doctest::Approx(6));
    CHECK(turned.position.y == doctest::Approx(2));
    CHECK(turned.position.z == doctest::Approx(0).epsilon(1e-12));
    CHECK(turned.target == c.target);
    CHECK(orbit(c, 0).position == c.position);
}

namespace {

Options parse(std::vector<const char*> args) {
    args.insert(args.begin(), "xeno_render");
    return parse_options(static_cast<int>(args.size()), args.data());
}

std::string parse_error(std::vector<const char*> args) {
    try {
        parse(std::move(args));
    } catch (const OptionsError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("the command line has the documented defaults") {
    const Options o = parse({});
    CHECK(o.scenarios.empty());
    CHECK(o.frames == 0);  // each scenario's own length
    CHECK(o.fps == 60);
    CHECK(o.width == 640);
    CHECK(o.height == 480);
    CHECK_FALSE(o.use_float);
    CHECK(o.out_dir == "out");
    CHECK_FALSE(o.contacts);
    CHECK(o.orbit_degrees == 0);
    CHECK(o.states_path.empty());
    CHECK(o.images);
    CHECK_FALSE(o.list);
    CHECK_FALSE(o.help);
}

TEST_CASE("every option of the command line is parsed, in both spellings") {
    const Options o = parse({"vertex-face", "--frames", "30", "--fps=30", "--size", "320x240", "--float", "--out", "/tmp/x",
                             "--contacts", "--orbit", "-90", "--states=s.csv", "--no-images", "stack"});
    CHECK(o.scenarios == std::vector<std::string>{"vertex-face", "stack"});
    CHECK(o.frames == 30);
    CHECK(o.fps == 30);
    CHECK(o.width == 320);
    CHECK(o.height == 240);
    CHECK(o.use_float);
    CHECK(o.out_dir == "/tmp/x");
    CHECK(o.contacts);
    CHECK(o.orbit_degrees == -90);
    CHECK(o.states_path == "s.csv");
    CHECK_FALSE(o.images);
    CHECK_FALSE(parse({"--float", "--double"}).use_float);
    CHECK(parse({"--list"}).list);
    CHECK(parse({"-h"}).help);
    CHECK(parse({"--", "--odd-name"}).scenarios == std::vector<std::string>{"--odd-name"});
}

TEST_CASE("bad command-line values are rejected with a message naming them") {
    CHECK(parse_error({"--frames", "abc"}).find("'abc'") != std::string::npos);
    CHECK(parse_error({"--frames", "abc"}).find("--frames") != std::string::npos);
    CHECK(parse_error({"--frames", "0"}).find("--frames") != std::string::npos);
    CHECK(parse_error({"--frames", "12x"}) != "");
    CHECK(parse_error({"--size", "10"}).find("'10'") != std::string::npos);
    CHECK(parse_error({"--size", "10x10"}).find("--size") != std::string::npos);
    CHECK(parse_error({"--size", "x480"}) != "");
    CHECK(parse_error({"--fps", "0"}).find("--fps") != std::string::npos);
    CHECK(parse_error({"--fps", "nan"}) != "");
    CHECK(parse_error({"--orbit", "inf"}) != "");
    CHECK(parse_error({"--bogus"}).find("'--bogus'") != std::string::npos);
    CHECK(parse_error({"--frames"}).find("needs a value") != std::string::npos);
    CHECK(parse_error({"--contacts=yes"}).find("takes no value") != std::string::npos);
    CHECK(parse_error({"--out="}) != "");
}

TEST_CASE("scenario names resolve in order, 'all' expands, unknown names are rejected") {
    const std::vector<std::string> available{"a", "b", "c"};
    CHECK(resolve_scenarios({}, available) == available);
    CHECK(resolve_scenarios({"all"}, available) == available);
    CHECK(resolve_scenarios({"c", "a", "c"}, available) == std::vector<std::string>{"c", "a"});
    CHECK(resolve_scenarios({"b", "all"}, available) == std::vector<std::string>{"b", "a", "c"});
    try {
        resolve_scenarios({"a", "zzz"}, available);
        FAIL("no exception");
    } catch (const OptionsError& e) {
        CHECK(std::string(e.what()).find("'zzz'") != std::string::npos);
    }
    CHECK(usage("xeno_render").find("--states FILE") != std::string::npos);
}

namespace {

/// Counts draw_shape's output and checks every triangle faces away from the shape's centre.
template <class T>
struct WindingCheck : xeno::DebugDraw<T> {
    xeno::Vec3<T> centre;
    int triangles = 0, inward = 0, lines = 0;
    double area = 0;
    void draw_triangle(const xeno::Vec3<T>& a, const xeno::Vec3<T>& b, const xeno::Vec3<T>& c, xeno::Color) override {
        ++triangles;
        const xeno::Vec3<T> n = cross(b - a, c - a);
        area += double(length(n)) / 2;
        if (!(dot(n, (a + b + c) / T(3) - centre) > T(0))) ++inward;
    }
    void draw_line(const xeno::Vec3<T>&, const xeno::Vec3<T>&, xeno::Color) override { ++lines; }
    void draw_point(const xeno::Vec3<T>&, T, xeno::Color) override {}
};

}  // namespace

TEST_CASE_TEMPLATE("draw_shape winds every triangle outward and covers the surface", T, float, double) {
    using namespace xeno;
    const Transform<T> t{{T(1), T(2), T(3)}, Quat<T>::from_axis_angle({T(1), T(2), T(0.5)}, T(0.7))};
    const T pi = ScalarTraits<T>::pi;
    struct Case {
        Shape<T> shape;
        double area;  // exact surface area; tessellations are slightly smaller
    };
    const T r = T(0.5), h = T(0.4);
    const Case cases[] = {
        {Sphere<T>(r), double(4 * pi * r * r)},
        {Box<T>(T(0.5), T(0.3), T(0.2)), 2 * (1.0 * 0.6 + 1.0 * 0.4 + 0.6 * 0.4)},
        {Capsule<T>(r, h), double(4 * pi * r * r + 4 * pi * r * h)},
        {Capsule<T>(r, T(0)), double(4 * pi * r * r)},
        {Cylinder<T>(r, h), double(2 * pi * r * r + 4 * pi * r * h)},
        {Cone<T>(r, T(1)), double(pi * r * r + pi * r * std::sqrt(r * r + T(1)))},
        {make_tetrahedron<T>(T(1)), std::sqrt(3.0)},
    };
    for (const Case& c : cases) {
        WindingCheck<T> check;
        check.centre = t.position;
        draw_shape(check, c.shape, t, Color{}, Color{});
        INFO(shape_name(c.shape));
        CHECK(check.triangles > 0);
        CHECK(check.inward == 0);
        CHECK(check.lines > 0);
        CHECK(check.area <= c.area * (1 + 1e-5));
        CHECK(check.area > c.area * 0.95);
    }
}

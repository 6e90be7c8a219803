// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The browser page's C interface (xeno_web.h), compiled natively: every scene loads in each
// precision, steps and draws; both precisions side by side start equal and part as they should;
// a body picked by a ray follows the drag; bad arguments are refused, not crashed on. The page
// itself is tested in headless Chromium by examples/web/test_page.py.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include "web/xeno_web.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace {

int scene(const std::string& name) {
    for (int s = 0; s < xw_scene_count(); ++s)
        if (xw_scene_name(s) == name) return s;
    return -1;
}

// The column scene in one precision (0 float, 1 double, 2 both), half a second in.
void load_settled_column(int precision) {
    const int column = scene("column");
    REQUIRE(column >= 0);
    REQUIRE(xw_load(column, precision) == 0);
    xw_step(30);
}

bool finite_position(int precision, int body) {
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(xw_body_position(precision, body, k))) return false;
    return true;
}

}  // namespace

TEST_CASE("every scene loads, steps and draws in float, double and both") {
    REQUIRE(xw_scene_count() >= 25);
    for (int s = 0; s < xw_scene_count(); ++s) {
        CAPTURE(std::string(xw_scene_name(s)));
        for (int precision = 0; precision <= 2; ++precision) {
            REQUIRE(xw_load(s, precision) == 0);
            xw_step(3);
            CHECK(xw_time() > 0.04);
            for (int p = 0; p <= 1; ++p) {
                const bool shown = precision == 2 || precision == p;
                const int triangles = xw_draw(p, 1);
                CHECK((triangles > 0) == shown);
                if (!shown) continue;
                CHECK(xw_stat(p, 0) > 0);
                const float* t = xw_triangles(p);
                bool finite = true;
                for (int i = 0; i < 10 * triangles; ++i) finite = finite && std::isfinite(t[i]);
                CHECK(finite);
            }
        }
        CHECK(xw_camera(6) > 0);  // the scene's length
    }
}

TEST_CASE("float and double side by side: the same scene, apart only by rounding at first") {
    int dominoes = -1;
    for (int s = 0; s < xw_scene_count(); ++s)
        if (std::string(xw_scene_name(s)) == "dominoes") dominoes = s;
    REQUIRE(dominoes >= 0);
    REQUIRE(xw_load(dominoes, 2) == 0);
    xw_step(1);
    CHECK(xw_max_difference() < 1e-5);
    xw_step(120);
    CHECK(xw_max_difference() < 1.0);
    CHECK(xw_stat(0, 0) == xw_stat(1, 0));
}

TEST_CASE("a body picked by a ray follows the drag, and lets go") {
    load_settled_column(2);
    // A ray from the side at the top box's height (the column of 10 unit boxes, top at y = 9.5).
    REQUIRE(xw_pick(0, 9.5, 10, 0, 0, -1) == 1);
    const int body = xw_grabbed_body();
    REQUIRE(body >= 0);
    const double y0 = xw_body_position(1, body, 1);
    xw_drag(xw_grab_point(0) + 2, xw_grab_point(1) + 1, xw_grab_point(2));
    xw_step(60);
    CHECK(xw_body_position(1, body, 1) > y0 + 0.8);
    CHECK(xw_body_position(0, body, 1) > y0 + 0.8);  // the float world holds it too
    xw_release();
    CHECK(xw_grabbed_body() == -1);
    CHECK(xw_pick(0, 100, 0, 0, 1, 0) == 0);  // a ray into the sky picks nothing
}

TEST_CASE("bad arguments are refused") {
    CHECK(xw_load(-1, 1) == -1);
    CHECK(xw_load(xw_scene_count(), 1) == -1);
    CHECK(xw_load(0, 3) == -1);
    CHECK(std::string(xw_scene_name(-1)).empty());
    REQUIRE(xw_load(0, 1) == 0);
    CHECK(xw_pick(0, 0, 0, 0, 0, 0) == 0);
    CHECK(xw_pick(0, 0, 0, NAN, 0, 1) == 0);
    xw_drag(NAN, 0, 0);
    CHECK(xw_draw(0, 0) == 0);  // float not loaded
    CHECK(xw_benchmark(0, 1, 0) == -1);
}

// The WebAssembly module is built without exceptions: a throw from the library ends the page, so
// every call below must be refused (or cut) at the interface, not thrown on inside.
TEST_CASE("a pick from an origin that is not finite or beyond +-1e6 m is refused, and any finite direction picks") {
    for (int precision = 0; precision <= 2; ++precision) {
        CAPTURE(precision);
        load_settled_column(precision);
        CHECK(xw_pick(NAN, 9.5, 10, 0, 0, -1) == 0);
        CHECK(xw_pick(0, INFINITY, 10, 0, 0, -1) == 0);
        CHECK(xw_pick(1e300, 9.5, 10, 0, 0, -1) == 0);  // inf once float
        CHECK(xw_pick(0, 9.5, 2e6, 0, 0, -1) == 0);
        CHECK(xw_pick(0, 9.5, 10, 0, 0, -INFINITY) == 0);
        CHECK(xw_grabbed_body() == -1);
        // |d|² subnormal (normalising it gave no unit vector) and |d|² overflowing: both still a direction.
        CHECK(xw_pick(0, 9.5, 10, 0, 0, -1e-161) == 1);
        xw_release();
        CHECK(xw_pick(0, 9.5, 10, 0, 0, -1e200) == 1);
        xw_release();
    }
}

TEST_CASE("a drag target beyond +-1e6 m is refused in every precision, and one at the bound steps") {
    for (int precision = 0; precision <= 2; ++precision) {
        CAPTURE(precision);
        load_settled_column(precision);
        REQUIRE(xw_pick(0, 9.5, 10, 0, 0, -1) == 1);
        const int body = xw_grabbed_body();
        const double target[3] = {xw_grab_point(0), xw_grab_point(1), xw_grab_point(2)};
        const int shown = precision == 0 ? 0 : 1;
        // inf once float; finite in double, but not the velocity that reaches it in a step; beyond 1e6 m.
        for (const double far : {1e300, -1e308, 2e6}) {
            CAPTURE(far);
            xw_drag(far, far, far);
            for (int k = 0; k < 3; ++k) CHECK(xw_grab_point(k) == target[k]);
            CHECK_NOTHROW(xw_step(1));
            CHECK(finite_position(shown, body));
        }
        xw_drag(1e6, -1e6, 1e6);
        CHECK(xw_grab_point(0) == 1e6);
        xw_step(2);
        CHECK(finite_position(shown, body));
        xw_release();
    }
}

TEST_CASE("a negative step count does nothing, and more than 600 steps a call are cut to 600") {
    const int column = scene("column");
    REQUIRE(column >= 0);
    REQUIRE(xw_load(column, 2) == 0);
    xw_step(-1000);
    CHECK(xw_time() == 0);
    xw_step(1000);
    CHECK(xw_time() == 10);  // 600 steps of 1/60 s
    CHECK(xw_benchmark(column, 0, 601) == -1);
    CHECK(xw_benchmark(column, 1, -5) == -1);
    CHECK(xw_benchmark(column, 0, 600) > 0);
}

TEST_CASE("a stat of an unknown precision or kind is 0") {
    REQUIRE(xw_load(scene("column"), 1) == 0);
    xw_step(1);
    CHECK(xw_stat(1, 0) == 10);
    CHECK(xw_stat(5, 0) == 0);
    CHECK(xw_stat(-1, 0) == 0);
    CHECK(xw_stat(1, 3) == 0);
    CHECK(xw_stat(0, 0) == 0);  // float not loaded
}

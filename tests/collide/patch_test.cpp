// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The twist lever of a contact patch (contact/patch.hpp): the mean distance from the patch centre
// over the area the corners span, against closed forms (a square, a line) and against a
// brute-force sum over a fine grid of the polygon (not the code under test), for corners given in
// any order.
#include <xeno/contact/patch.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace xeno;

namespace {

// The polygon of the corners (any order) as the lines through two corners that have every corner
// on their inner side (or on them): a point is inside when it is on the inner side of each.
struct Edge {
    double x0, y0, dx, dy;  ///< a corner and the direction to the other
};

std::vector<Edge> hull_edges(const std::array<double, 4>& u, const std::array<double, 4>& v, int n) {
    std::vector<Edge> edges;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if (i == j) continue;
            const Edge e{u[i], v[i], u[j] - u[i], v[j] - v[i]};
            bool edge = true;
            for (int k = 0; k < n; ++k) edge = edge && e.dx * (v[k] - e.y0) - e.dy * (u[k] - e.x0) >= -1e-12;
            if (edge) edges.push_back(e);
        }
    return edges;
}

// (Found once per polygon, not per grid point: under AddressSanitizer at -O0 the search at each
// of the 360,000 points took 23-30 s, now 1 s.)
bool inside_hull(const std::vector<Edge>& edges, double x, double y) {
    for (const Edge& e : edges)
        if (e.dx * (y - e.y0) - e.dy * (x - e.x0) < 0) return false;
    return true;
}

double grid_mean_radius(const std::array<double, 4>& u, const std::array<double, 4>& v, int n) {
    double lo_u = 1e9, hi_u = -1e9, lo_v = 1e9, hi_v = -1e9;
    for (int i = 0; i < n; ++i)
        lo_u = std::min(lo_u, u[i]), hi_u = std::max(hi_u, u[i]), lo_v = std::min(lo_v, v[i]), hi_v = std::max(hi_v, v[i]);
    const std::vector<Edge> edges = hull_edges(u, v, n);
    const int cells = 600;
    double sum = 0, area = 0;
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
            const double x = lo_u + (hi_u - lo_u) * (i + 0.5) / cells, y = lo_v + (hi_v - lo_v) * (j + 0.5) / cells;
            if (!inside_hull(edges, x, y)) continue;
            sum += std::sqrt(x * x + y * y);
            area += 1;
        }
    return sum / area;
}

}  // namespace

TEST_CASE_TEMPLATE("a patch's twist lever is (sqrt 2 + ln(1 + sqrt 2)) a / 3 for a square and a quarter of a line", T, float,
                   double) {
    const T a = T(0.7);
    const T square = a * (std::sqrt(T(2)) + std::log(T(1) + std::sqrt(T(2)))) / T(3);
    // corners in every order give the same lever
    std::array<int, 4> order{0, 1, 2, 3};
    const std::array<T, 4> cu{a, -a, -a, a}, cv{a, a, -a, -a};
    do {
        std::array<T, 4> u{}, v{};
        for (int i = 0; i < 4; ++i) u[i] = cu[order[i]], v[i] = cv[order[i]];
        CHECK(detail::patch_mean_radius(u, v, 4) == doctest::Approx(square).epsilon(1e-5));
    } while (std::next_permutation(order.begin(), order.end()));
    CHECK(detail::patch_mean_radius<T>({T(0.3), T(-0.3), T(0), T(0)}, {T(0.4), T(-0.4), T(0), T(0)}, 2) ==
          doctest::Approx(T(0.25)));
    CHECK(detail::patch_mean_radius<T>({T(0.5), T(0), T(0), T(0)}, {T(0), T(0), T(0), T(0)}, 1) == T(0));
    // three or four corners in a line are a line
    CHECK(detail::patch_mean_radius<T>({T(-1), T(0), T(1), T(0)}, {T(0), T(0), T(0), T(0)}, 3) == doctest::Approx(T(0.5)));
}

TEST_CASE("a patch's twist lever matches a grid sum over random triangles and convex quadrilaterals") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(0, 2 * 3.141592653589793), radius(0.2, 1.5);
    for (int trial = 0; trial < 40; ++trial) {
        const int n = 3 + trial % 2;
        // corners on a circle at sorted random angles are convex; shuffled before the call
        std::array<double, 4> t{};
        for (int i = 0; i < n; ++i) t[i] = angle(rng);
        std::sort(t.begin(), t.begin() + n);
        const double r = radius(rng);
        std::array<double, 4> u{}, v{};
        double cu = 0, cv = 0;
        for (int i = 0; i < n; ++i) u[i] = r * std::cos(t[i]) * 1.3, v[i] = r * std::sin(t[i]), cu += u[i] / n, cv += v[i] / n;
        for (int i = 0; i < n; ++i) u[i] -= cu, v[i] -= cv;  // about the mean of the corners
        // skip slivers, whose grid sum is too coarse
        const double area = std::abs((u[1] - u[0]) * (v[2] - v[0]) - (v[1] - v[0]) * (u[2] - u[0]));
        if (area < 0.05 * r * r) continue;
        std::array<int, 4> perm{0, 1, 2, 3};
        std::shuffle(perm.begin(), perm.begin() + n, rng);
        std::array<double, 4> su{}, sv{};
        for (int i = 0; i < n; ++i) su[i] = u[perm[i]], sv[i] = v[perm[i]];
        const double expected = grid_mean_radius(u, v, n);
        CAPTURE(trial);
        CHECK(detail::patch_mean_radius(su, sv, n) == doctest::Approx(expected).epsilon(2e-3));
        std::array<float, 4> fu{}, fv{};
        for (int i = 0; i < n; ++i) fu[i] = float(su[i]), fv[i] = float(sv[i]);
        CHECK(double(detail::patch_mean_radius(fu, fv, n)) == doctest::Approx(expected).epsilon(2e-3));
    }
}

TEST_CASE("regression: three corners a few ulps apart have a finite lever within their span") {
    // A mesh manifold's three points at one place (found in a pile settling in a bowl): the line
    // test passed by round-off and the lever came out −∞; the step's solve overflowed and was
    // discarded every step after, so the body froze in the air with its velocity.
    const std::array<Vec3<double>, 4> p{Vec3<double>{0.68824794228114716, 0.15597342096145889, -0.89281702198420687},
                                        Vec3<double>{0.68824794228114727, 0.1559734209614588, -0.89281702198420687},
                                        Vec3<double>{0.68824794228114727, 0.15597342096145878, -0.89281702198420687},
                                        Vec3<double>{}};
    const double lever = detail::patch_twist_lever(p, 3);
    CHECK(std::isfinite(lever));
    CHECK(lever >= 0);
    CHECK(lever < 1e-15);
}

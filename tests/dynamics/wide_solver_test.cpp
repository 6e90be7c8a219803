// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The wide contact solver (docs/solver.md, "Colours" and "Wide rows"): SIMD lanes give the bits of
// the portable lanes, operation by operation; the colouring keeps every colour free of shared
// bodies, checked by brute force; and a body with more contacts than there are colours (its
// overflow rows) rests on them. The whole-world comparison across widths is the determinism test:
// the portable-lane (XENO_NO_SIMD), SSE2 and AVX2 builds print the same state hashes.
#include "support/approx.hpp"
#include "support/sim.hpp"

#include <xeno/dynamics/wide_contact_solver.hpp>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>

using namespace xeno;
using xeno::detail::Wide;

namespace {

template <class T>
std::vector<T> awkward_values(std::size_t n) {
    std::vector<T> v = {T(0),
                        -T(0),
                        T(1),
                        T(-1),
                        std::numeric_limits<T>::infinity(),
                        -std::numeric_limits<T>::infinity(),
                        std::numeric_limits<T>::quiet_NaN(),
                        std::numeric_limits<T>::denorm_min(),
                        std::numeric_limits<T>::max(),
                        std::numeric_limits<T>::min()};
    std::mt19937 rng(7);
    std::uniform_real_distribution<T> u(T(-100), T(100));
    while (v.size() < n) v.push_back(u(rng));
    return v;
}

template <class T>
bool same_bits(T a, T b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

}  // namespace

TEST_CASE_TEMPLATE("SIMD lanes give the portable lanes' bits for every operation, special values included", T, float, double) {
    constexpr int W = detail::native_width<T>();
    using V = Wide<T, W>;
    using S = Wide<T, 1>;
    const std::vector<T> values = awkward_values<T>(64);
    int checked = 0;
    for (std::size_t i = 0; i + W <= values.size(); ++i)
        for (std::size_t j = 0; j + W <= values.size(); j += 3) {
            alignas(64) T xa[W], xb[W];
            for (int l = 0; l < W; ++l)
                xa[l] = values[i + std::size_t(l)], xb[l] = values[(j + std::size_t(l) * 5) % values.size()];
            const V a = V::load(xa), b = V::load(xb);
            const V wide[] = {
                a + b, a - b, a * b, a / b, max(a, b), min(a, b), sqrt(a), select(a > b, a, b), select(a < b, a, b)};
            for (int l = 0; l < W; ++l) {
                const S p = S::splat(xa[l]), q = S::splat(xb[l]);
                const S narrow[] = {
                    p + q, p - q, p * q, p / q, max(p, q), min(p, q), sqrt(p), select(p > q, p, q), select(p < q, p, q)};
                for (std::size_t k = 0; k < std::size(wide); ++k) {
                    INFO("operation " << k << " on " << xa[l] << ", " << xb[l]);
                    CHECK(same_bits(wide[k].get(l), narrow[k].get(0)));
                    ++checked;
                }
            }
        }
    CHECK(checked > 1000);
}

TEST_CASE_TEMPLATE("transposed loads and stores put record l, number r in lane l of row r (and back)", T, float, double) {
    constexpr int W = detail::native_width<T>();
    for (const int rows : {1, 4, 6, 13}) {
        T records[W][16];
        const T* src[W];
        T out_records[W][16] = {};
        T* dst[W];
        for (int l = 0; l < W; ++l) {
            for (int r = 0; r < 16; ++r) records[l][r] = T(100 * l + r);
            src[l] = records[l];
            dst[l] = out_records[l];
        }
        Wide<T, W> lanes[16];
        detail::load_transposed(src, rows, lanes);
        for (int r = 0; r < rows; ++r)
            for (int l = 0; l < W; ++l) CHECK(lanes[r].get(l) == records[l][r]);
        detail::store_transposed(lanes, rows, dst);
        for (int l = 0; l < W; ++l)
            for (int r = 0; r < 16; ++r) CHECK(out_records[l][r] == (r < rows ? records[l][r] : T(0)));
    }
}

TEST_CASE("colouring: no colour holds two rows of one moving body, every row once, rows by lower moving body (brute force)") {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 50; ++trial) {
        const std::size_t bodies = 2 + rng() % 60, rows = rng() % 400;
        std::vector<std::uint32_t> a(rows), b(rows);
        for (std::size_t i = 0; i < rows; ++i) {
            a[i] = static_cast<std::uint32_t>(rng() % bodies);  // 0 is the static stand-in
            b[i] = static_cast<std::uint32_t>(rng() % bodies);
            if (b[i] == a[i]) b[i] = 0;  // a row joins two bodies
        }
        detail::ConstraintColouring c;
        c.build(
            rows, bodies, [&](std::size_t i) { return a[i]; }, [&](std::size_t i) { return b[i]; });
        std::vector<int> seen(rows, 0);
        for (int colour = 0; colour < detail::ConstraintColouring::colours; ++colour) {
            std::set<std::uint32_t> used;
            // Listed by the lower moving body (distinct within a colour); rows with none, only
            // possible here, first and in row order.
            const auto lower_moving = [&](std::uint32_t r) {
                return a[r] == 0 ? b[r] : (b[r] == 0 ? a[r] : std::min(a[r], b[r]));
            };
            for (std::uint32_t k = c.colour_begin[std::size_t(colour)]; k < c.colour_begin[std::size_t(colour) + 1]; ++k) {
                const std::uint32_t row = c.order[k];
                if (k > c.colour_begin[std::size_t(colour)]) {
                    const std::uint32_t before = c.order[k - 1];
                    CHECK((lower_moving(row) > lower_moving(before) || (lower_moving(row) == 0 && row > before)));
                }
                ++seen[row];
                for (const std::uint32_t body : {a[row], b[row]}) {
                    if (body == 0) continue;
                    CHECK(used.count(body) == 0);
                    used.insert(body);
                }
            }
        }
        for (const std::uint32_t row : c.overflow) ++seen[row];
        for (std::size_t i = 0; i < rows; ++i) CHECK(seen[i] == 1);
        // A row overflows only when its bodies already sit in every colour before it.
        for (const std::uint32_t row : c.overflow) {
            int colours_taken = 0;
            for (int colour = 0; colour < detail::ConstraintColouring::colours; ++colour) {
                bool taken = false;
                for (std::uint32_t k = c.colour_begin[std::size_t(colour)]; k < c.colour_begin[std::size_t(colour) + 1]; ++k) {
                    const std::uint32_t r = c.order[k];
                    if (r > row) continue;  // coloured after it
                    taken = taken || (a[row] != 0 && (a[r] == a[row] || b[r] == a[row])) ||
                            (b[row] != 0 && (a[r] == b[row] || b[r] == b[row]));
                }
                colours_taken += taken ? 1 : 0;
            }
            CHECK(colours_taken == detail::ConstraintColouring::colours);
        }
    }
}

TEST_CASE_TEMPLATE("a plate carrying 36 boxes (more contacts than colours) holds them at rest", C, XENO_TEST_CONFIGS) {
    using T = typename C::T;
    World<T> w(C::settings());
    scenes::add_ground(w);
    const BodyId plate = scenes::add_box(w, Vec3<T>{T(4), T(0.1), T(4)}, Vec3<T>{T(0), T(0.1), T(0)});
    std::vector<BodyId> boxes;
    for (int i = 0; i < 6; ++i)
        for (int k = 0; k < 6; ++k)
            boxes.push_back(scenes::add_box(w, Vec3<T>{T(0.4), T(0.4), T(0.4)},
                                            Vec3<T>{T(-3.5) + T(1.4) * T(i), T(0.6), T(-3.5) + T(1.4) * T(k)}));
    std::size_t overflow = 0;
    test::simulate(w, T(2), [&](int) { overflow = std::max(overflow, w.last_step_stats().overflow_contacts); });
    CHECK(overflow > 0);  // the case this test is for: the plate's rows overflowed the colours
    // Resting: the plate on the ground, each box on the plate, within soft-contact penetration.
    CHECK(std::abs(w.body(plate).position().y - T(0.1)) < T(0.005));
    for (const BodyId id : boxes) {
        const Body<T>& b = w.body(id);
        CHECK(std::abs(b.position().y - T(0.6)) < T(0.01));
        CHECK(length(b.linear_velocity()) < T(0.01));
    }
}

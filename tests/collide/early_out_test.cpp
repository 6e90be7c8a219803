// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// EarlyOut (collide/early_out.hpp): a pair it calls apart is apart, measured independently with
// the shapes' own support functions and by the narrow phase; it is exact enough to reject boxes,
// spheres and capsules a few per cent beyond touching; and every lane width gives the same bits.
#include "collide/random_pairs.hpp"
#include "scenes/random.hpp"

#include <xeno/collide/early_out.hpp>
#include <xeno/xeno.hpp>

#include <doctest/doctest.h>

#include <vector>

namespace {

using namespace xeno;

// How far B lies beyond A along unit n (metres; < 0 when their projections overlap), from the
// shapes' support functions: min over B of x·n minus max over A of x·n.
template <class T>
T gap_along(const Shape<T>& a, const Transform<T>& pa, const Shape<T>& b, const Transform<T>& pb, const Vec3<T>& n) {
    const auto reach = [](const Shape<T>& s, const Transform<T>& p, const Vec3<T>& d) {
        const Vec3<T> local = rotate(conjugate(p.orientation), d);
        const Vec3<T> x = std::visit([&](const auto& shape) { return shape.support(local); }, s);
        return dot(p.apply(x), d);
    };
    return -reach(b, pb, -n) - reach(a, pa, n);
}

template <class T>
void check_random_pairs() {
    test::RandomPairs pairs(91, 0.05, 2.0, 10.0);
    pairs.set_touching_fraction(0.3);
    const test::ShapeMaker<T> maker(pairs);
    EarlyOut<T> early;
    early.resize(2);
    int rejected = 0, exact_kinds = 0, exact_rejected = 0;
    for (int k = 0; k < 4000; ++k) {
        const test::PairParams p = pairs.next();
        Shape<T> sa = Sphere<T>(T(1)), sb = Sphere<T>(T(1));
        const Shape<T>& a = maker.get(p.a, sa);
        const Shape<T>& b = maker.get(p.b, sb);
        const Transform<T> pa = test::cast_pose<T>(p.pose_a), pb = test::cast_pose<T>(p.pose_b);
        early.set(0, a, pa);
        early.set(1, b, pb);
        const T margin = k % 2 ? T(0) : static_cast<T>(0.05 * p.scale);
        const Vec3<T> d = pb.position - pa.position;
        if (length(d) == T(0)) continue;
        const T gap = gap_along(a, pa, b, pb, normalized(d));
        if (early.apart(0, 1, margin)) {
            ++rejected;
            INFO("pair ", k, ": gap ", gap, " margin ", margin);
            CHECK(gap > margin);
            CHECK_FALSE(collide(a, pa, b, pb).hit);
            CHECK(generate_contacts(a, pa, b, pb, margin, T(0.005)).count == 0);
        }
        // Boxes, spheres and capsules are bounded exactly: a gap of 3 % of the centre distance
        // beyond the margin is always rejected.
        const bool exact = p.a.kind <= 2 && p.b.kind <= 2;
        if (exact && gap > margin + T(0.03) * length(d)) {
            ++exact_kinds;
            exact_rejected += early.apart(0, 1, margin) ? 1 : 0;
        }
    }
    MESSAGE("rejected ", rejected, " of 4000; exact kinds clearly apart ", exact_kinds);
    CHECK(rejected > 300);  // most random pairs are placed within touching range
    CHECK(exact_kinds > 100);
    CHECK(exact_rejected == exact_kinds);
}

TEST_CASE_TEMPLATE("early-out: a pair called apart is apart (support functions, MPR, contacts)", T, float, double) {
    check_random_pairs<T>();
}

// A crowd of mixed shapes in a small cube, so pairs of every kind overlap, touch and miss.
template <class T>
std::vector<std::uint32_t> all_pair_bits_width_1(const EarlyOut<T>& early, std::size_t n, T margin) {
    std::vector<std::uint32_t> bits;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) bits.push_back(early.apart(i, j, margin) ? 1u : 0u);
    return bits;
}

template <class T, int W>
std::vector<std::uint32_t> all_pair_bits_runs(const EarlyOut<T>& early, std::size_t n, T margin) {
    std::vector<std::uint32_t> bits;
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t j = i + 1;
        for (; j + W <= n; j += W) {
            const unsigned m = early.template apart_run<W>(i, j, margin);
            for (int l = 0; l < W; ++l) bits.push_back((m >> l) & 1u);
        }
        for (; j < n; ++j) bits.push_back(early.apart(i, j, margin) ? 1u : 0u);
    }
    return bits;
}

template <class T, int W>
std::vector<std::uint32_t> all_pair_bits_gathered(const EarlyOut<T>& early, std::size_t n, T margin) {
    std::vector<std::uint32_t> a, b, bits;
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = i + 1; j < n; ++j) a.push_back(i), b.push_back(j);
    std::size_t k = 0;
    for (; k + W <= a.size(); k += W) {
        std::uint32_t la[W], lb[W];
        T lm[W];
        for (int l = 0; l < W; ++l) la[l] = a[k + l], lb[l] = b[k + l], lm[l] = margin;
        const unsigned m = early.template apart_pairs<W>(la, lb, lm);
        for (int l = 0; l < W; ++l) bits.push_back((m >> l) & 1u);
    }
    for (; k < a.size(); ++k) bits.push_back(early.apart(a[k], b[k], margin) ? 1u : 0u);
    return bits;
}

TEST_CASE_TEMPLATE("early-out: every lane width gives the scalar answer of every pair", T, float, double) {
    scenes::Random rng(7);
    const std::vector<Shape<T>> shapes = {Box<T>(T(0.5), T(0.2), T(0.3)), Sphere<T>(T(0.4)),
                                          Capsule<T>(T(0.2), T(0.5)),     Cylinder<T>(T(0.3), T(0.2)),
                                          Cone<T>(T(0.4), T(0.8)),        make_regular_prism(7, T(0.4), T(0.3))};
    const std::size_t n = 203;  // not a multiple of any width: runs end in a scalar tail
    EarlyOut<T> early;
    early.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (i % 50 == 17) continue;  // a few bodies without a bound: never rejected
        early.set(i, shapes[i % shapes.size()], {rng.in_box(Vec3<T>::one() * T(3)), rng.rotation<T>()});
    }
    for (const T margin : {T(0), T(0.1)}) {
        const std::vector<std::uint32_t> scalar = all_pair_bits_width_1(early, n, margin);
        std::size_t apart = 0;
        for (const std::uint32_t b : scalar) apart += b;
        CHECK(apart > scalar.size() / 4);
        CHECK(apart < scalar.size());
        CHECK(all_pair_bits_runs<T, 2>(early, n, margin) == scalar);
        CHECK(all_pair_bits_runs<T, 4>(early, n, margin) == scalar);
        CHECK(all_pair_bits_runs<T, 8>(early, n, margin) == scalar);
        CHECK(all_pair_bits_runs<T, EarlyOut<T>::width>(early, n, margin) == scalar);
        CHECK(all_pair_bits_gathered<T, 4>(early, n, margin) == scalar);
        CHECK(all_pair_bits_gathered<T, EarlyOut<T>::width>(early, n, margin) == scalar);
        std::size_t k = 0;  // bodies without a bound are never rejected
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j, ++k)
                if (i % 50 == 17 || j % 50 == 17) CHECK(scalar[k] == 0u);
    }
}

TEST_CASE("early-out: two unit boxes face to face, rejected from 2 % beyond touching, never before") {
    EarlyOut<double> early;
    early.resize(2);
    const Box<double> box(0.5, 0.5, 0.5);
    early.set(0, box, Transform<double>::identity());
    for (const double gap : {0.0, 0.001, 0.01}) {
        early.set(1, box, {{1.0 + gap, 0.0, 0.0}, Quat<double>::identity()});
        CHECK_FALSE(early.apart(0, 1, 0.0));
    }
    early.set(1, box, {{1.03, 0.0, 0.0}, Quat<double>::identity()});
    CHECK(early.apart(0, 1, 0.0));
    CHECK_FALSE(early.apart(0, 1, 0.02));  // within the margin: a speculative contact may follow
    CHECK(early.apart(0, 1, 0.005));
}

TEST_CASE_TEMPLATE("the world's narrow phase skips convex pairs the early-out finds apart, not those within the margin", T, float,
                   double) {
    // Two balls of radius 0.5 side by side along a diagonal: their boxes overlap whatever the gap,
    // so the broad phase pairs them. Default settings, no gravity (nothing moves).
    const auto step_pair = [](T gap) {
        WorldSettings<T> settings;
        settings.gravity = Vec3<T>::zero();
        World<T> world(settings);
        const T offset = (T(1) + gap) / std::sqrt(T(2));
        BodyDef<T> def;
        world.create_body(Sphere<T>(T(0.5)), def);
        def.position = {offset, offset, T(0)};
        world.create_body(Sphere<T>(T(0.5)), def);
        world.step(T(1) / T(60));
        return std::pair{world.last_step_stats(), world.contacts().size()};
    };
    const auto [far, far_contacts] = step_pair(T(0.15));
    CHECK(far.broad_pairs == 1);
    CHECK(far.apart_pairs == 1);  // rejected before the narrow phase
    CHECK(far_contacts == 0);
    // 1 cm apart: within the default speculative distance (2 cm), a speculative contact.
    const auto [near, near_contacts] = step_pair(T(0.01));
    CHECK(near.broad_pairs == 1);
    CHECK(near.apart_pairs == 0);
    CHECK(near_contacts == 1);
    // 3 cm apart: beyond the margin but within the test's slack: left to the narrow phase,
    // which finds no contact.
    const auto [edge, edge_contacts] = step_pair(T(0.03));
    CHECK(edge.apart_pairs == 0);
    CHECK(edge_contacts == 0);
}

}  // namespace

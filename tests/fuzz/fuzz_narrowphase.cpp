// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// libFuzzer target over the narrow phase (docs/robustness.md, "Fuzzing"). The bytes decode into
// two shapes of any kind (hulls from 4 … 12 points, degenerate clouds included), sizes
// 1e-4 … 1e4 m, positions up to 1e4 m with B placed anywhere from inside A to beyond it, and a
// speculative margin; the same pair runs in float and in double through intersect(), collide(),
// mpr_penetration() and generate_contacts(). It traps on: a non-finite depth, normal or point; a
// normal of a hit that is not unit; a negative depth from collide() or MPR; a manifold with more
// than four points or a point deeper than collide() or farther than the margin; MPR at its cap
// three times over; intersect() and collide() disagreeing on an overlap deeper than 5 % of the
// pair's size. A few inputs also carry a NaN or infinite pose, which collide() and mpr_*
// must reject with InvalidArgument (generate_contacts() assumes checked input and is not fed it).
//   build:  cmake -DCMAKE_CXX_COMPILER=clang++ -DXENO_BUILD_FUZZ=ON ... (tests/fuzz/CMakeLists.txt)
//   run:    xeno_fuzz_narrowphase -max_total_time=60 <corpus dir>
#include "decode.hpp"

#include <cstdint>

using namespace xeno;

namespace {

struct PairSpec {
    fuzz::ShapeSpec a, b;
    Transform<double> pose_a, pose_b;
    double margin = 0;
    int poison = 0;  // 0: finite poses; 1: NaN/inf in pose_a's position; 2: in pose_b's orientation
    double poison_value = 0;
};

PairSpec decode(FuzzedDataProvider& in) {
    PairSpec p;
    p.a = fuzz::shape_spec(in, -4, 4);
    p.b = fuzz::shape_spec(in, -4, 4);
    const Vec3<double> position_a{fuzz::signed_unit(in), fuzz::signed_unit(in), fuzz::signed_unit(in)};
    const double far = fuzz::log_uniform(in, -2, 4);
    p.pose_a = {position_a * far, fuzz::rotation(in)};
    // B from A's centre out to past the sum of the largest sizes, in any direction.
    const double reach = (p.a.size[0] + p.a.size[1] + p.a.size[2] + p.b.size[0] + p.b.size[1] + p.b.size[2]) * 1.2 *
                         in.ConsumeProbability<double>();
    const Vec3<double> direction{fuzz::signed_unit(in), fuzz::signed_unit(in), fuzz::signed_unit(in)};
    p.pose_b = {p.pose_a.position + normalized_or(direction, Vec3<double>::unit_x()) * reach, fuzz::rotation(in)};
    p.margin = in.ConsumeBool() ? 0.0 : fuzz::log_uniform(in, -4, 1);
    if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {
        p.poison = in.ConsumeIntegralInRange<int>(1, 2);
        p.poison_value = in.ConsumeBool() ? std::numeric_limits<double>::quiet_NaN()
                                          : (in.ConsumeBool() ? 1.0 : -1.0) * std::numeric_limits<double>::infinity();
    }
    return p;
}

template <class T>
void check_hit(const Penetration<T>& p, const char* query) {
    if (!p.hit) return;
    if (!fuzz::finite_contact(p)) {
        std::fprintf(stderr, "%s\n", query);
        fuzz::fail("non-finite contact for finite input");
    }
    if (!(p.depth >= T(0))) fuzz::fail("negative depth on a hit");
    if (!fuzz::unit(p.normal)) fuzz::fail("normal of a hit is not unit");
}

/// Every query on one pair in precision T.
template <class T>
void run(const PairSpec& spec) {
    const std::shared_ptr<const Shape<T>> a = fuzz::build<T>(spec.a);
    const std::shared_ptr<const Shape<T>> b = fuzz::build<T>(spec.b);
    if (!a || !b) return;  // a builder rejected the shape: fine
    Transform<T> pose_a = spec.pose_a.cast<T>(), pose_b = spec.pose_b.cast<T>();

    if (spec.poison != 0) {
        const T bad = static_cast<T>(spec.poison_value);
        if (spec.poison == 1) pose_a.position.y = bad;
        else pose_b.orientation.x = bad;
        auto rejects = [](auto&& query) {
            try {
                query();
            } catch (const InvalidArgument&) {
                return true;
            }
            return false;
        };
        if (!rejects([&] { (void)collide(*a, pose_a, *b, pose_b); })) fuzz::fail("collide accepted a non-finite pose");
        if (!rejects([&] { (void)intersect(*a, pose_a, *b, pose_b); })) fuzz::fail("intersect accepted a non-finite pose");
        if (!rejects([&] { (void)mpr_penetration(detail::ShapeRef<T>(*a), pose_a, detail::ShapeRef<T>(*b), pose_b); }))
            fuzz::fail("mpr_penetration accepted a non-finite pose");
        return;
    }

    const bool hit = intersect(*a, pose_a, *b, pose_b);
    const Penetration<T> c = collide(*a, pose_a, *b, pose_b);
    check_hit(c, "collide");
    // Through ShapeRef, as the narrow phase runs it: one instantiation instead of one per pair of
    // kinds (tests/collide/shape_ref_test.cpp compares the typed and ShapeRef paths).
    const Penetration<T> m = mpr_penetration(detail::ShapeRef<T>(*a), pose_a, detail::ShapeRef<T>(*b), pose_b);
    check_hit(m, "mpr_penetration");
    if (m.iterations >= 3 * detail::kMprMaxIterations) fuzz::fail("MPR ran past its caps");
    const T margin = static_cast<T>(spec.margin);
    const T scale = bounding_radius(*a) + bounding_radius(*b) + margin;
    // The boolean and the penetration query may disagree only on touching pairs.
    if (hit != c.hit && std::max(c.hit ? c.depth : T(0), m.hit ? m.depth : T(0)) > T(0.05) * scale)
        fuzz::fail("intersect and collide disagree on a deep overlap");

    const ContactManifold<T> manifold = generate_contacts(*a, pose_a, *b, pose_b, margin);
    if (manifold.count < 0 || manifold.count > 4) fuzz::fail("manifold count outside 0 … 4");
    if (manifold.count > 0 && !(is_finite(manifold.normal) && fuzz::unit(manifold.normal)))
        fuzz::fail("manifold normal not finite and unit");
    for (int i = 0; i < manifold.count; ++i) {
        const ManifoldPoint<T>& p = manifold.points[static_cast<std::size_t>(i)];
        if (!(is_finite(p.point_a) && is_finite(p.point_b) && std::isfinite(p.depth))) fuzz::fail("non-finite manifold point");
        // Points are within the margin (speculative) and not absurdly deep: no deeper than the
        // pair could overlap at all.
        if (!(p.depth >= -margin - T(1e-2) * scale)) fuzz::fail("manifold point beyond the margin");
        if (!(p.depth <= T(2) * scale)) fuzz::fail("manifold point deeper than the pair's size");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    const PairSpec spec = decode(in);
    run<float>(spec);
    run<double>(spec);
    return 0;
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Per-pair cost of the narrow phase: box–box, 32-vertex hull pairs (a regular 16-sided prism, and
// 32 random points on a sphere: `rhull32`), capsule–hull, the pairs
// answered in closed form (sphere–sphere, sphere–capsule, capsule–capsule, sphere–box, capsule–box)
// and curved pairs left to MPR (cylinder–cone, capsule–cone, cylinder–hull), overlapping and
// separated (bounding spheres overlap, shapes do not: what a broad phase lets through), float and
// double. Columns: the MPR path (mpr_intersect, mpr_penetration: what intersect() and collide() ran
// for every pair but box–box before the closed forms), the public intersect() and collide(), and
// the world's manifold. libccd's MPR (ccdMPRIntersect / ccdMPRPenetration, Debian's libccd-dev,
// double precision) runs on the same poses in the same process as the baseline, fed with the same
// support functions through its void* callbacks, as a libccd user would.
//
//   xeno_narrowphase_bench "[summary]"   the ratio table (what the README quotes)
//   xeno_narrowphase_bench "[bench]"     Catch2 statistics per query
#define CATCH_CONFIG_ENABLE_BENCHMARKING
#include <catch2/catch.hpp>

#include "scenes/random.hpp"

#include <xeno/collide/collide.hpp>
#include <xeno/collide/sat.hpp>
#include <xeno/shape/convex_hull.hpp>
#include <xeno/shape/polyhedra.hpp>

#ifdef XENO_HAVE_LIBCCD
#include <ccd/ccd.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

using namespace xeno;

namespace {

constexpr int kPairs = 256;

template <class T>
struct Poses {
    std::vector<Transform<T>> a, b;
};

// Poses drawn in double and classified by the double-precision query, so float and double and
// libccd all see the same configurations.
template <class SA, class SB>
std::pair<Poses<double>, Poses<double>> make_poses(const SA& a, const SB& b, std::uint64_t seed) {
    scenes::Random rng(seed);
    Poses<double> overlapping, separated;
    // Two spheres within their bounding spheres always overlap: their separated poses come from up
    // to 1.25 times that reach, where their bounding boxes still overlap.
    const double reach = (a.bounding_radius() + b.bounding_radius()) *
                         (std::is_same_v<SA, Sphere<double>> && std::is_same_v<SB, Sphere<double>> ? 1.25 : 1.0);
    while (overlapping.a.size() < kPairs || separated.a.size() < kPairs) {
        const Transform<double> ta{rng.in_box(Vec3<double>{1, 1, 1}), rng.rotation<double>()};
        const Transform<double> tb{ta.position + rng.direction<double>() * rng.uniform(0.0, reach), rng.rotation<double>()};
        Poses<double>& set = mpr_intersect(a, ta, b, tb) ? overlapping : separated;
        if (set.a.size() < kPairs) {
            set.a.push_back(ta);
            set.b.push_back(tb);
        }
    }
    return {overlapping, separated};
}

template <class T>
Poses<T> cast(const Poses<double>& p) {
    Poses<T> out;
    for (std::size_t i = 0; i < p.a.size(); ++i) {
        out.a.push_back(p.a[i].template cast<T>());
        out.b.push_back(p.b[i].template cast<T>());
    }
    return out;
}

// Nanoseconds per pair: best of several repetitions of a sweep over all poses (min filters out
// the other jobs sharing this machine).
template <class F>
double ns_per_pair(F&& sweep) {
    using clock = std::chrono::steady_clock;
    double best = 1e30;
    for (int rep = 0; rep < 7; ++rep) {
        int rounds = 0;
        const auto start = clock::now();
        double elapsed = 0;
        do {
            sweep();
            ++rounds;
            elapsed = std::chrono::duration<double, std::nano>(clock::now() - start).count();
        } while (elapsed < 4e6);
        best = std::min(best, elapsed / (rounds * double(kPairs)));
    }
    return best;
}

#ifdef XENO_HAVE_LIBCCD
// A shape placed in the world for libccd's callbacks (double precision, as libccd is built).
template <class S>
struct CcdObject {
    const S* shape;
    Mat3<double> rotation;
    Vec3<double> position;
};
template <class S>
CcdObject<S> ccd_object(const S& s, const Transform<double>& t) {
    return {&s, to_matrix(t.orientation), t.position};
}
template <class S>
void ccd_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject<S>*>(obj);
    const Vec3<double> d{dir->v[0], dir->v[1], dir->v[2]};
    const Vec3<double> p = o.rotation * o.shape->support(transposed_transform(o.rotation, d)) + o.position;
    ccdVec3Set(out, p.x, p.y, p.z);
}
template <class S>
void ccd_center(const void* obj, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject<S>*>(obj);
    const Vec3<double> c = o.rotation * o.shape->interior_point() + o.position;
    ccdVec3Set(out, c.x, c.y, c.z);
}
template <class SA, class SB>
ccd_t ccd_setup() {
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = &ccd_support<SA>;
    ccd.support2 = &ccd_support<SB>;
    ccd.center1 = &ccd_center<SA>;
    ccd.center2 = &ccd_center<SB>;
    ccd.mpr_tolerance = 1e-6;
    return ccd;
}
#endif

struct Row {
    std::string pair, set, precision;
    double intersect_ns, penetration_ns, public_intersect_ns, collide_ns, manifold_ns, ccd_intersect_ns, ccd_penetration_ns;
};

template <class T, class SA, class SB>
Row time_xeno(const std::string& pair, const std::string& set, const SA& a, const SB& b, const Poses<double>& poses_d) {
    const Poses<T> poses = cast<T>(poses_d);
    const Shape<T> shape_a = a, shape_b = b;
    Row r{pair, set, std::is_same_v<T, float> ? "float" : "double", 0, 0, 0, 0, 0, 0, 0};
    volatile int sink = 0;
    r.intersect_ns = ns_per_pair([&] {
        for (int i = 0; i < kPairs; ++i) sink = sink + mpr_intersect(a, poses.a[i], b, poses.b[i]);
    });
    r.penetration_ns = ns_per_pair([&] {
        for (int i = 0; i < kPairs; ++i) sink = sink + mpr_penetration(a, poses.a[i], b, poses.b[i]).hit;
    });
    r.public_intersect_ns = ns_per_pair([&] {
        for (int i = 0; i < kPairs; ++i) sink = sink + intersect(shape_a, poses.a[i], shape_b, poses.b[i]);
    });
    r.collide_ns = ns_per_pair([&] {
        for (int i = 0; i < kPairs; ++i) sink = sink + collide(shape_a, poses.a[i], shape_b, poses.b[i]).hit;
    });
    r.manifold_ns = ns_per_pair([&] {
        for (int i = 0; i < kPairs; ++i)
            sink = sink + generate_contacts(shape_a, poses.a[i], shape_b, poses.b[i], T(0), T(0.005))
                              .count;  // the world's default linear_slop
    });
    return r;
}

template <class SA, class SB>
void time_ccd(Row& r, const SA& a, const SB& b, const Poses<double>& poses) {
#ifdef XENO_HAVE_LIBCCD
    const ccd_t ccd = ccd_setup<SA, SB>();
    std::vector<CcdObject<SA>> oa;
    std::vector<CcdObject<SB>> ob;
    volatile int sink = 0;
    r.ccd_intersect_ns = ns_per_pair([&] {
        for (int i = 0; i < kPairs; ++i) {
            const CcdObject<SA> x = ccd_object(a, poses.a[i]);
            const CcdObject<SB> y = ccd_object(b, poses.b[i]);
            sink = sink + ccdMPRIntersect(&x, &y, &ccd);
        }
    });
    r.ccd_penetration_ns = ns_per_pair([&] {
        for (int i = 0; i < kPairs; ++i) {
            const CcdObject<SA> x = ccd_object(a, poses.a[i]);
            const CcdObject<SB> y = ccd_object(b, poses.b[i]);
            ccd_real_t depth;
            ccd_vec3_t dir, pos;
            sink = sink + ccdMPRPenetration(&x, &y, &ccd, &depth, &dir, &pos);
        }
    });
#else
    (void)r, (void)a, (void)b, (void)poses;
#endif
}

// 32 points on a sphere of radius 0.5, every one a hull vertex: what users' hulls look like (a
// regular prism has many parallel faces and symmetric ties).
template <class T>
ConvexPolyhedron<T> random_hull32() {
    scenes::Random rng(32);
    std::vector<Vec3<T>> points;
    for (int i = 0; i < 32; ++i) points.push_back(rng.direction<T>() * T(0.5));
    return make_convex_hull(points).polyhedron;
}

template <class T>
struct Shapes {
    Box<T> box{T(0.5), T(0.5), T(0.5)};
    ConvexPolyhedron<T> hull = make_regular_prism(16, T(0.5), T(0.4));  // 32 vertices
    ConvexPolyhedron<T> random_hull = random_hull32<T>();
    Sphere<T> sphere{T(0.5)};
    Capsule<T> capsule{T(0.25), T(0.5)};
    Cylinder<T> cylinder{T(0.4), T(0.5)};
    Cone<T> cone{T(0.5), T(1)};
};

// Accuracy against the exact minimum depth (separating axes) on the overlapping poses.
template <class SA, class SB>
void accuracy(const char* name, const SA& a, const SB& b, std::uint64_t seed) {
    const Poses<double> poses = make_poses(a, b, seed).first;
    const Shape<double> sa = a, sb = b;
    double xeno_sum = 0, xeno_max = 0, mpr_sum = 0, mpr_max = 0, ccd_sum = 0, ccd_max = 0;
    int n = 0;
#ifdef XENO_HAVE_LIBCCD
    const ccd_t ccd = ccd_setup<SA, SB>();
#endif
    for (int i = 0; i < kPairs; ++i) {
        const double exact = separating_axis(a, poses.a[i], b, poses.b[i]).depth;
        if (exact < 1e-3) continue;
        const double x = collide(sa, poses.a[i], sb, poses.b[i]).depth / exact - 1;
        const double m = mpr_penetration(a, poses.a[i], b, poses.b[i]).depth / exact - 1;
        xeno_sum += x, xeno_max = std::max(xeno_max, x);
        mpr_sum += m, mpr_max = std::max(mpr_max, m);
#ifdef XENO_HAVE_LIBCCD
        const CcdObject<SA> oa = ccd_object(a, poses.a[i]);
        const CcdObject<SB> ob = ccd_object(b, poses.b[i]);
        ccd_real_t depth = 0;
        ccd_vec3_t dir, pos;
        ccdMPRPenetration(&oa, &ob, &ccd, &depth, &dir, &pos);
        const double c = depth / exact - 1;
        ccd_sum += c, ccd_max = std::max(ccd_max, c);
#endif
        ++n;
    }
    std::printf(
        "%-14s depth above the exact minimum: xeno refined mean %6.2f%% max %6.2f%% | xeno MPR alone mean %6.2f%% max %6.2f%%",
        name, 100 * xeno_sum / n, 100 * xeno_max, 100 * mpr_sum / n, 100 * mpr_max);
#ifdef XENO_HAVE_LIBCCD
    std::printf(" | libccd mean %6.2f%% max %6.2f%%\n", 100 * ccd_sum / n, 100 * ccd_max);
#else
    std::printf(" | libccd not built in\n");
    static_cast<void>(ccd_sum), static_cast<void>(ccd_max);
#endif
}

}  // namespace

TEST_CASE("narrow phase cost per pair, xeno against libccd in one run", "[summary]") {
    const Shapes<double> d;
    const Shapes<float> f;
    std::vector<Row> rows;
    auto both = [&](const char* name, const auto& ad, const auto& bd, const auto& af, const auto& bf, std::uint64_t seed) {
        const auto [overlapping, separated] = make_poses(ad, bd, seed);
        for (const auto& [set_name, poses] : {std::pair{"overlap", overlapping}, std::pair{"separate", separated}}) {
            Row rd = time_xeno<double>(name, set_name, ad, bd, poses);
            time_ccd(rd, ad, bd, poses);
            rows.push_back(rd);
            rows.push_back(time_xeno<float>(name, set_name, af, bf, poses));
        }
    };
    both("box-box", d.box, d.box, f.box, f.box, 1);
    both("hull32-hull32", d.hull, d.hull, f.hull, f.hull, 2);
    both("sphere-box", d.sphere, d.box, f.sphere, f.box, 3);
    both("capsule-hull32", d.capsule, d.hull, f.capsule, f.hull, 4);
    both("sphere-sphere", d.sphere, d.sphere, f.sphere, f.sphere, 5);
    both("sphere-capsule", d.sphere, d.capsule, f.sphere, f.capsule, 6);
    both("capsule-capsule", d.capsule, d.capsule, f.capsule, f.capsule, 7);
    both("capsule-box", d.capsule, d.box, f.capsule, f.box, 8);
    // Curved pairs still on MPR: collide() adds the least-depth expansion (epa.hpp) to MPR.
    both("cylinder-cone", d.cylinder, d.cone, f.cylinder, f.cone, 9);
    both("capsule-cone", d.capsule, d.cone, f.capsule, f.cone, 10);
    both("cylinder-hull32", d.cylinder, d.hull, f.cylinder, f.hull, 11);
    // 32 random points on a sphere (the rows above use the 16-sided prism).
    both("rhull32-rhull32", d.random_hull, d.random_hull, f.random_hull, f.random_hull, 12);
    both("capsule-rhull32", d.capsule, d.random_hull, f.capsule, f.random_hull, 13);
    both("cylinder-rhull32", d.cylinder, d.random_hull, f.cylinder, f.random_hull, 14);

    std::printf("\nNarrow phase, ns per pair (best of 7 sweeps over %d random poses; libccd is double only)\n", kPairs);
#ifndef XENO_HAVE_LIBCCD
    std::printf("libccd was not found when this was configured (Debian: libccd-dev): its columns read 0\n");
#endif
    std::printf("%-15s %-9s %-7s %13s %15s %11s %9s %9s | %14s %16s | %s\n", "pair", "set", "scalar", "mpr_intersect",
                "mpr_penetration", "intersect", "collide", "manifold", "libccd intersect", "libccd penetration",
                "libccd / xeno collide");
    for (const Row& r : rows) {
        char ratio[32] = "";
        if (r.ccd_penetration_ns > 0) std::snprintf(ratio, sizeof ratio, "%.2fx", r.ccd_penetration_ns / r.collide_ns);
        std::printf("%-15s %-9s %-7s %13.0f %15.0f %11.0f %9.0f %9.0f | %14.0f %16.0f | %s\n", r.pair.c_str(), r.set.c_str(),
                    r.precision.c_str(), r.intersect_ns, r.penetration_ns, r.public_intersect_ns, r.collide_ns, r.manifold_ns,
                    r.ccd_intersect_ns, r.ccd_penetration_ns, ratio);
    }
    std::printf("\n");
    accuracy("box-box", d.box, d.box, 1);
    accuracy("hull32-hull32", d.hull, d.hull, 2);
    accuracy("rhull32-rhull32", d.random_hull, d.random_hull, 12);
    CHECK(rows.size() == 56);
}

TEMPLATE_TEST_CASE("narrow phase queries", "[bench]", float, double) {
    using T = TestType;
    const Shapes<T> s;
    const Shape<T> box = s.box, hull = s.hull;
    const Poses<T> poses = cast<T>(make_poses(Shapes<double>{}.box, Shapes<double>{}.box, 1).first);
    BENCHMARK("box-box mpr_penetration x256") {
        int hits = 0;
        for (int i = 0; i < kPairs; ++i) hits += mpr_penetration(s.box, poses.a[i], s.box, poses.b[i]).hit;
        return hits;
    };
    BENCHMARK("box-box collide (refined) x256") {
        int hits = 0;
        for (int i = 0; i < kPairs; ++i) hits += collide(box, poses.a[i], box, poses.b[i]).hit;
        return hits;
    };
    BENCHMARK("hull32-hull32 collide (refined) x256") {
        int hits = 0;
        for (int i = 0; i < kPairs; ++i) hits += collide(hull, poses.a[i], hull, poses.b[i]).hit;
        return hits;
    };
}

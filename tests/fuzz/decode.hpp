// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Turning fuzzer bytes into xeno inputs, shared by fuzz_narrowphase.cpp and fuzz_world.cpp.
// Everything is decoded in double (log-uniform sizes, positions, unit quaternions) and then
// rounded to the precision under test, so one input exercises float and double alike. The
// FuzzedDataProvider of libFuzzer returns defaults once the bytes run out, so every input decodes.
#pragma once

#include <xeno/xeno.hpp>

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <vector>

namespace xeno::fuzz {

/// Stops the run with a message: libFuzzer (and the sanitizers) report it as a crash and save
/// the input.
[[noreturn]] inline void fail(const char* what) {
    std::fprintf(stderr, "xeno fuzz: %s\n", what);
    std::fflush(stderr);
    __builtin_trap();
}

/// 10^u with u uniform in [low, high].
inline double log_uniform(FuzzedDataProvider& in, double low_exponent, double high_exponent) {
    return std::pow(10.0, low_exponent + (high_exponent - low_exponent) * in.ConsumeProbability<double>());
}

/// Uniform in [-1, 1].
inline double signed_unit(FuzzedDataProvider& in) { return 2.0 * in.ConsumeProbability<double>() - 1.0; }

/// A unit quaternion from four decoded numbers (the identity when they are all zero).
inline Quat<double> rotation(FuzzedDataProvider& in) {
    Quat<double> q{signed_unit(in), signed_unit(in), signed_unit(in), signed_unit(in)};
    const double n = length_squared(q);
    if (!(n > 1e-12)) return Quat<double>::identity();
    return normalized(q);
}

/// A value that no door may accept as a size, a velocity or a time step.
inline double poison(FuzzedDataProvider& in) {
    switch (in.ConsumeIntegralInRange<int>(0, 4)) {
        case 0: return std::numeric_limits<double>::quiet_NaN();
        case 1: return std::numeric_limits<double>::infinity();
        case 2: return -std::numeric_limits<double>::infinity();
        case 3: return -1.0;
        default: return 0.0;
    }
}

/// A shape as numbers: kind (Shape<T> variant index), three sizes and, for hulls, the points.
struct ShapeSpec {
    int kind = 0;
    double size[3] = {1, 1, 1};
    std::vector<Vec3<double>> points;
};

/// Sizes log-uniform in [10^low, 10^high] metres; hulls from 4 … 12 points (duplicates,
/// coplanar and collinear clouds included: the hull builder must reject those cleanly).
inline ShapeSpec shape_spec(FuzzedDataProvider& in, double low_exponent, double high_exponent) {
    ShapeSpec s;
    s.kind = in.ConsumeIntegralInRange<int>(0, 5);
    for (double& d : s.size) d = log_uniform(in, low_exponent, high_exponent);
    if (s.kind == 5) {
        const int n = in.ConsumeIntegralInRange<int>(4, 12);
        const int flatten = in.ConsumeIntegralInRange<int>(0, 7);  // 1: collinear, 2: coplanar, 3: repeat
        for (int i = 0; i < n; ++i) {
            Vec3<double> p{signed_unit(in) * s.size[0], signed_unit(in) * s.size[1], signed_unit(in) * s.size[2]};
            if (flatten == 1) p = Vec3<double>{p.x, 0.5 * p.x, -p.x};
            if (flatten == 2) p.z = 0.25 * p.x - 0.5 * p.y;
            if (flatten == 3 && i >= 2) p = s.points[static_cast<std::size_t>(i % 2)];
            s.points.push_back(p);
        }
    }
    return s;
}

/// The shape in precision T, or nothing when the builder rejects it (InvalidArgument: a rejected
/// input is a fine outcome, anything else is not).
template <class T>
std::shared_ptr<const Shape<T>> build(const ShapeSpec& s) {
    const T a = static_cast<T>(s.size[0]), b = static_cast<T>(s.size[1]), c = static_cast<T>(s.size[2]);
    try {
        switch (s.kind) {
            case 0: return std::make_shared<const Shape<T>>(Sphere<T>(a));
            case 1: return std::make_shared<const Shape<T>>(Box<T>(a, b, c));
            case 2: return std::make_shared<const Shape<T>>(Capsule<T>(a, b));
            case 3: return std::make_shared<const Shape<T>>(Cylinder<T>(a, b));
            case 4: return std::make_shared<const Shape<T>>(Cone<T>(a, b));
            default: {
                std::vector<Vec3<T>> points;
                for (const Vec3<double>& p : s.points) points.push_back(p.cast<T>());
                return std::make_shared<const Shape<T>>(make_convex_hull(points).polyhedron);
            }
        }
    } catch (const InvalidArgument&) {
        return nullptr;
    }
}

template <class T>
bool finite_contact(const Penetration<T>& p) {
    return std::isfinite(p.depth) && is_finite(p.normal) && is_finite(p.point_a) && is_finite(p.point_b);
}

template <class T>
bool unit(const Vec3<T>& n) {
    return std::abs(length(n) - T(1)) <= T(1e-3);
}

}  // namespace xeno::fuzz

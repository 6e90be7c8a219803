// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The scalar parameter T that every numeric type in xeno is templated on (float or double), its
// traits (epsilon, pi, default tolerances) and small helpers for comparing and clamping.
// No build-wide precision switch exists: one program can hold World<float> and World<double>.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>

namespace xeno {

/// Constants for the scalar type T (float or double).
template <class T>
struct ScalarTraits {
    static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>, "xeno is templated on float or double only");

    /// Machine epsilon: the gap between 1 and the next representable value.
    static constexpr T epsilon = std::numeric_limits<T>::epsilon();
    static constexpr T pi = T(3.14159265358979323846);
    static constexpr T infinity = std::numeric_limits<T>::infinity();
    static constexpr T max = std::numeric_limits<T>::max();
    /// Relative tolerance for "equal" in geometric tests: about 2^10 ulps, so round-off of a
    /// few dozen operations never flips a test (1.2e-4 in float, 2.3e-13 in double).
    static constexpr T relative_tolerance = T(1024) * epsilon;
    /// Relative tolerance for iterative geometry (MPR, hull building), scaled by the problem
    /// size: tight enough for contacts of 0.1 mm on 1 m bodies in float.
    static constexpr T geometric_tolerance = std::is_same_v<T, float> ? T(1e-5) : T(1e-9);
    /// The sizes (metres) a shape may have: MPR's convergence test is of sixth order in lengths,
    /// and within 1e-6 … 1e6 m in float (1e-50 … 1e50 m in double) it stays a normal number, so
    /// queries are finite and right (float failed from 1e-7 and 1e8 m; docs/robustness.md, "Sizes").
    static constexpr T min_size = T(std::is_same_v<T, float> ? 1e-6 : 1e-50);
    static constexpr T max_size = T(std::is_same_v<T, float> ? 1e6 : 1e50);
};

/// x * x.
template <class T>
constexpr T square(T x) {
    return x * x;
}

/// The value limited to [low, high].
template <class T>
constexpr T clamp(T x, T low, T high) {
    return x < low ? low : (x > high ? high : x);
}

/// True when a and b differ by at most max(absolute, relative * max(|a|, |b|)).
template <class T>
bool approx_equal(T a, T b, T relative = ScalarTraits<T>::relative_tolerance, T absolute = ScalarTraits<T>::relative_tolerance) {
    const T diff = std::abs(a - b);
    const T scale = std::abs(a) > std::abs(b) ? std::abs(a) : std::abs(b);
    return diff <= absolute || diff <= relative * scale;
}

namespace detail {
/// x halved `times` times: multiplied by a power of two, which is exact unless the result is
/// subnormal (and then rounded the same way everywhere); 0 from 255 halvings on. For the cached
/// impulses of a body that got lighter (Body::impulse_halvings_).
template <class T>
T halved(T x, int times) {
    return times >= 255 ? T(0) : std::ldexp(x, -times);
}
}  // namespace detail

/// Degrees to radians.
template <class T>
constexpr T radians(T degrees) {
    return degrees * (ScalarTraits<T>::pi / T(180));
}

/// Radians to degrees.
template <class T>
constexpr T degrees(T radians_value) {
    return radians_value * (T(180) / ScalarTraits<T>::pi);
}

/// The scalar of each precision's names (`xs::Real(0.2) * i` reads the same in f32 and f64).
namespace f32 {
using Real = float;
}
namespace f64 {
using Real = double;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A small deterministic random generator (SplitMix64) for scenes, tests and benchmarks: the same
// seed gives the same numbers on every compiler and standard library, which <random>'s
// distributions do not promise.
#pragma once

#include <xeno/math/quat.hpp>

#include <cstdint>

namespace xeno::scenes {

class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next_u64() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1).
    double uniform() { return static_cast<double>(next_u64() >> 11) * (1.0 / 9007199254740992.0); }
    /// Uniform in [low, high).
    template <class T>
    T uniform(T low, T high) {
        return low + static_cast<T>(uniform()) * (high - low);
    }
    /// Uniform integer in [0, n).
    std::uint32_t index(std::uint32_t n) { return static_cast<std::uint32_t>(uniform() * n); }
    /// Uniform point in the box [-h, h].
    template <class T>
    Vec3<T> in_box(const Vec3<T>& h) {
        return {uniform(-h.x, h.x), uniform(-h.y, h.y), uniform(-h.z, h.z)};
    }
    /// Uniform direction on the unit sphere.
    template <class T>
    Vec3<T> direction() {
        const double z = 2.0 * uniform() - 1.0;
        const double phi = 2.0 * 3.14159265358979323846 * uniform();
        const double r = std::sqrt(1.0 - z * z);
        return {static_cast<T>(r * std::cos(phi)), static_cast<T>(r * std::sin(phi)), static_cast<T>(z)};
    }
    /// Uniform random rotation (Shoemake, "Uniform random rotations", Graphics Gems III).
    template <class T>
    Quat<T> rotation() {
        const double u1 = uniform(), u2 = 2.0 * 3.14159265358979323846 * uniform(), u3 = 2.0 * 3.14159265358979323846 * uniform();
        const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
        return {static_cast<T>(a * std::sin(u2)), static_cast<T>(a * std::cos(u2)), static_cast<T>(b * std::sin(u3)),
                static_cast<T>(b * std::cos(u3))};
    }

private:
    std::uint64_t state_;
};

}  // namespace xeno::scenes

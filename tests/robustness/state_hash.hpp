// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A 64-bit FNV-1a hash of a world's state: the raw bytes of every living body's position,
// orientation, linear and angular velocity, in body slot order (Box2D's test/test_determinism.c
// hashes its final state the same way). Two runs are bitwise identical exactly when their hashes
// are equal after every step (up to a 2^-64 chance of collision). Shared by
// determinism_test.cpp and the xeno_determinism executable.
#pragma once

#include <xeno/dynamics/world.hpp>

#include <cstdint>
#include <cstring>

namespace xeno::test {

/// FNV-1a, 64 bits (Fowler, Noll, Vo): offset basis and prime of the published parameters.
class Fnv1a {
public:
    void add_bytes(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            hash_ ^= bytes[i];
            hash_ *= 0x100000001b3ull;
        }
    }
    /// The bytes of one scalar, as stored (no formatting, no rounding).
    template <class T>
    void add(T value) {
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        add_bytes(bytes, sizeof(T));
    }
    template <class T>
    void add(const Vec3<T>& v) {
        add(v.x);
        add(v.y);
        add(v.z);
    }
    template <class T>
    void add(const Quat<T>& q) {
        add(q.w);
        add(q.x);
        add(q.y);
        add(q.z);
    }
    std::uint64_t value() const { return hash_; }

private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

/// The hash of every body's pose and velocities, in slot order.
template <class T>
std::uint64_t state_hash(const World<T>& world) {
    Fnv1a h;
    world.for_each_body([&](BodyId, const Body<T>& b) {
        h.add(b.position());
        h.add(b.orientation());
        h.add(b.linear_velocity());
        h.add(b.angular_velocity());
    });
    return h.value();
}

}  // namespace xeno::test

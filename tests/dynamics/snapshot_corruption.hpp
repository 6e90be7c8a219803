// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Corrupt snapshots (docs/robustness.md, "Corrupt snapshots"): a small world whose snapshot the
// corruption tests damage byte by byte, and the check that what restore_snapshot accepts is a
// world that steps and grows like any other.
#pragma once

#include "support/approx.hpp"

#include <xeno/dynamics/snapshot.hpp>

#include <cstring>
#include <limits>
#include <utility>

namespace xeno::test {

/// Ground, a resting box, a resting compound joined to it by a hinge, a freed body slot and a
/// freed joint slot, stepped until the contacts carry impulses. Every body has a position x
/// whose bytes occur once in the snapshot, so tests can find its record.
template <class T>
struct CorruptionScene {
    World<T> w;
    BodyId ground, box, compound;
    JointId hinge;
    static constexpr T ground_x = T(0.0078125);  // exact in both precisions
    static constexpr T box_x = T(-1.0546875);
    CorruptionScene() {
        BodyDef<T> d;
        d.type = BodyType::static_body;
        d.position = {ground_x, T(-0.5), T(0)};
        ground = w.create_body(Box<T>(T(4), T(0.5), T(2)), d);
        d = {};
        d.position = {box_x, T(0.49), T(0)};
        d.user_data = 0x1122334455667788ull;
        box = w.create_body(Box<T>(T(0.5), T(0.5), T(0.5)), d);
        d = {};
        d.position = {T(1.25), T(0.49), T(0.25)};
        compound = w.create_body(
            Compound<T>({{Box<T>(T(0.3), T(0.5), T(0.3)), {}}, {Sphere<T>(T(0.3)), {{T(0.6), T(0), T(0)}, Quat<T>::identity()}}}),
            d);
        d = {};
        d.position = {T(50), T(50), T(50)};
        const BodyId far = w.create_body(Sphere<T>(T(0.5)), d);
        hinge = w.create_joint(JointDef<T>::hinge(box, compound, {T(0), T(0.5), T(0)}, {T(0), T(0), T(1)}));
        const JointId spare = w.create_joint(JointDef<T>::ball(box, far, {T(25), T(25), T(25)}));
        for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
        w.destroy_joint(spare);
        w.destroy_body(far);  // far from everything: no contact, so no pending event
    }
};

/// Offset of the first occurrence of the bytes of v in bytes (or bytes.size()).
template <class V>
std::size_t find_bytes(const std::vector<std::uint8_t>& bytes, const V& v) {
    for (std::size_t i = 0; i + sizeof(V) <= bytes.size(); ++i)
        if (std::memcmp(bytes.data() + i, &v, sizeof(V)) == 0) return i;
    return bytes.size();
}

/// Overwrites the bytes at `offset` with those of v.
template <class V>
void poke(std::vector<std::uint8_t>& bytes, std::size_t offset, const V& v) {
    REQUIRE(offset + sizeof(V) <= bytes.size());
    std::memcpy(bytes.data() + offset, &v, sizeof(V));
}

/// Byte distance of a member from the start of its object.
template <class S, class M>
std::size_t member_offset(const S& s, const M& m) {
    return static_cast<std::size_t>(reinterpret_cast<const char*>(&m) - reinterpret_cast<const char*>(&s));
}

/// A world restored from an accepted buffer must behave: ten steps with finite state, then a
/// new body that takes a free slot or a new one, never a living body's.
template <class T>
bool behaves(World<T>& w) {
    std::vector<BodyId> living;
    w.for_each_body([&](BodyId id, const Body<T>&) { living.push_back(id); });
    for (int i = 0; i < 10; ++i) w.step(T(1) / T(60));
    bool ok = true;
    w.for_each_body([&](BodyId, const Body<T>& b) {
        ok = ok && is_finite(b.position()) && is_finite(b.orientation()) && is_finite(b.linear_velocity()) &&
             is_finite(b.angular_velocity());
    });
    const std::size_t count = w.body_count();
    const BodyId fresh = w.create_body(Sphere<T>(T(0.25)));
    ok = ok && w.body_count() == count + 1 && w.contains(fresh);
    for (const BodyId id : living) ok = ok && w.contains(id) && id != fresh;
    return ok;
}

/// Changes byte i of a CorruptionScene snapshot to each of `changes(byte)` for every i in
/// first, first + stride, …: each buffer must be rejected (InvalidArgument) or restore a world
/// that behaves(). Returns {rejected, accepted}.
template <class T>
std::pair<std::size_t, std::size_t> sweep_corruptions(std::size_t first, std::size_t stride, int values) {
    const CorruptionScene<T> s;
    const std::vector<std::uint8_t> good = save_snapshot(s.w);
    std::size_t rejected = 0, accepted = 0;
    for (std::size_t i = first; i < good.size(); i += stride) {
        for (int v = 0; v < values; ++v) {
            std::vector<std::uint8_t> b = good;
            switch (v) {  // the sign or top exponent bit, the lowest bit, every bit, 0 <-> 1
                case 0: b[i] ^= 0x80; break;
                case 1: b[i] ^= 0x01; break;
                case 2: b[i] ^= 0xFF; break;
                default: b[i] = b[i] == 0 ? 1 : 0; break;
            }
            if (b == good) continue;
            World<T> w;
            try {
                restore_snapshot(w, b);
            } catch (const InvalidArgument&) {
                ++rejected;
                continue;
            }
            ++accepted;
            CAPTURE(i);
            CAPTURE(v);
            CHECK(behaves(w));
        }
    }
    return {rejected, accepted};
}

}  // namespace xeno::test

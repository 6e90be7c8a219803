// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// restore_snapshot rejects corrupt buffers (InvalidArgument) and leaves the target world as it
// was; what it accepts steps like any world. Each case the issue saw, by hand, then every byte of
// a small snapshot flipped (the slow test tries more values per byte).
#include "dynamics/snapshot_corruption.hpp"

using namespace xeno;
using namespace xeno::test;

namespace {

/// Where the parts of a CorruptionScene snapshot are (the format is in snapshot.hpp, save()).
template <class T>
struct Layout {
    std::size_t settings = 12;                         // after magic, version, scalar size
    std::size_t free_slots, bounds, contacts, joints;  // first element of each table
    std::size_t box_user_data, box_position;
    Layout(const CorruptionScene<T>& s, const std::vector<std::uint8_t>& bytes) {
        const std::size_t slots = 4, free = 1, joint_slots = 2, free_joints = 1;
        std::size_t at = bytes.size() - 8;  // pending events: none
        at -= 8 + 4 * free_joints;
        at -= 8 + joint_slots * sizeof(Joint<T>);
        joints = at + 8;
        at -= 8 + s.w.contacts().size() * sizeof(Contact<T>);
        contacts = at + 8;
        at -= 8 + slots * sizeof(Transform<T>);  // previous poses
        at -= 8 + slots * sizeof(Aabb<T>);
        bounds = at + 8;
        at -= 8 + 4 * free;
        free_slots = at + 8;
        box_user_data = find_bytes(bytes, std::uint64_t(0x1122334455667788ull));
        box_position =
            box_user_data - (6 * sizeof(Vec3<T>) + 2 * sizeof(Quat<T>) + sizeof(Mat3<T>) + 6 * sizeof(T) + sizeof(Material<T>));
    }
};

template <class T>
void check_rejected(const std::vector<std::uint8_t>& bad, const char* what) {
    CAPTURE(what);
    CorruptionScene<T> target;
    const std::vector<std::uint8_t> before = save_snapshot(target.w);
    CHECK_THROWS_AS(restore_snapshot(target.w, bad), InvalidArgument);
    CHECK(save_snapshot(target.w) == before);
}

}  // namespace

TEST_CASE_TEMPLATE("restore_snapshot rejects each corruption seen, leaving the world untouched", T, float, double) {
    const CorruptionScene<T> s;
    const std::vector<std::uint8_t> good = save_snapshot(s.w);
    const Layout<T> at(s, good);
    REQUIRE(at.box_user_data < good.size());
    REQUIRE(s.w.contacts().size() >= 2);
    {
        World<T> copy;  // the layout is right: the untouched buffer restores and steps
        restore_snapshot(copy, good);
        CHECK(copy.body_count() == 3);
        CHECK(behaves(copy));
    }
    const WorldSettings<T> settings{};
    const Contact<T> contact{};
    const Joint<T> joint{};
    const Aabb<T> box{};
    auto bad = [&](std::size_t offset, auto value, const char* what) {
        std::vector<std::uint8_t> b = good;
        poke(b, offset, value);
        check_rejected<T>(b, what);
    };
    const std::uint8_t two = 2;
    // Free slots: out of range (heap overflow in the next create_body), or a living body (which the
    // next create_body overwrote).
    bad(at.free_slots, std::uint32_t(1000), "free slot out of range");
    bad(at.free_slots, std::uint32_t(s.box.index), "free slot holding a living body");
    // Contacts: a manifold of 60 points (stack overflow in contact matching), bools, part
    // indices, order.
    bad(at.contacts + member_offset(contact, contact.manifold.count), 60, "manifold count 60");
    bad(at.contacts + member_offset(contact, contact.manifold.count), -1, "manifold count -1");
    bad(at.contacts + member_offset(contact, contact.touching), two, "contact bool byte 2");
    bad(at.contacts + member_offset(contact, contact.child_a), std::uint32_t(3), "contact part index out of range");
    bad(at.contacts + member_offset(contact, contact.b.index), std::uint32_t(0), "contact pair not a < b");
    bad(at.contacts + member_offset(contact, contact.b.generation), std::uint32_t(77), "contact with a stale handle");
    bad(at.contacts + member_offset(contact, contact.manifold.normal.x), std::numeric_limits<T>::quiet_NaN(),
        "contact normal NaN");
    bad(at.contacts + member_offset(contact, contact.made_normal.y), T(3), "contact made normal not unit");
    bad(at.contacts + member_offset(contact, contact.made_turn.w), std::numeric_limits<T>::quiet_NaN(), "contact made turn NaN");
    // The twist lever kept under its points' key: NaN, negative, or not the one the points give
    // (the next step would use it as it is).
    bad(at.contacts + member_offset(contact, contact.twist_lever), std::numeric_limits<T>::quiet_NaN(), "twist lever NaN");
    bad(at.contacts + member_offset(contact, contact.twist_lever), T(-1), "twist lever negative");
    REQUIRE(s.w.contacts()[0].twist_lever_key != 0);
    bad(at.contacts + member_offset(contact, contact.twist_lever), s.w.contacts()[0].twist_lever + T(0.25),
        "twist lever not its points'");
    // Settings: an iteration count that makes a step never end, bool bytes, enum values.
    bad(at.settings + member_offset(settings, settings.velocity_iterations), 33554433, "33,554,433 iterations");
    bad(at.settings + member_offset(settings, settings.substeps), 0, "no substeps");
    bad(at.settings + member_offset(settings, settings.warm_starting), two, "settings bool byte 2");
    bad(at.settings + member_offset(settings, settings.reuse_contacts), two, "settings reuse bool byte 2");
    bad(at.settings + member_offset(settings, settings.broad_phase), 9, "broad phase 9");
    bad(at.settings + member_offset(settings, settings.solver), 7, "solver 7");
    bad(at.settings + member_offset(settings, settings.gravity.y), std::numeric_limits<T>::infinity(), "infinite gravity");
    // Joints: type, bodies out of range, bool bytes, a live joint slot listed as free.
    bad(at.joints + member_offset(joint, joint.type), std::uint8_t(9), "joint type 9");
    bad(at.joints + member_offset(joint, joint.b.index), std::uint32_t(1000), "joint body out of range");
    bad(at.joints + member_offset(joint, joint.alive), two, "joint bool byte 2");
    bad(at.joints + sizeof(Joint<T>) + member_offset(joint, joint.alive), std::uint8_t(1), "freed joint alive again");
    // What create_joint refuses: a negative length, a hinge limit beyond pi.
    bad(at.joints + member_offset(joint, joint.length), T(-3), "joint length negative");
    bad(at.joints + member_offset(joint, joint.upper_angle), T(3.5), "hinge limit beyond pi");
    // Broad-phase boxes: NaN, inverted, a dead slot's box not empty.
    bad(at.bounds + sizeof(Aabb<T>) + member_offset(box, box.min.x), std::numeric_limits<T>::quiet_NaN(), "NaN bounds");
    bad(at.bounds + sizeof(Aabb<T>) + member_offset(box, box.min.x), T(1e6), "inverted bounds");
    bad(at.bounds + 3 * sizeof(Aabb<T>), Vec3<T>{}, "a dead slot's box");
    // A static body's box that does not hold it, finite and ordered: the steps keep a static body's
    // box until it moves, so the boxes on the ground fell through it for good (a review's probe:
    // the ground's box moved 1 km, or its min.x's sign bit flipped into a sliver at its edge).
    Aabb<T> ground_box;
    std::memcpy(&ground_box, good.data() + at.bounds, sizeof ground_box);
    REQUIRE(ground_box.contains(s.w.body(s.ground).world_bounds()));
    bad(at.bounds, Aabb<T>{ground_box.min + Vec3<T>{T(1000), T(0), T(0)}, ground_box.max + Vec3<T>{T(1000), T(0), T(0)}},
        "a static body's box 1 km off");
    bad(at.bounds + member_offset(box, box.min.x), -ground_box.min.x, "a static body's box a sliver at its edge");
    // The box's own record: bool and type bytes, shape index, pose.
    bad(at.box_user_data + 16, std::uint8_t(7), "body type 7");
    bad(at.box_user_data + 17, two, "body bool byte 2");
    bad(at.box_position - 8, std::uint32_t(99), "shape index out of range");
    bad(at.box_position, std::numeric_limits<T>::quiet_NaN(), "NaN position");
    // A gravity scale set_gravity_scale refuses (FLT_MAX made gravity x scale inf).
    bad(at.box_user_data - sizeof(Quat<T>) - sizeof(Vec3<T>) - 3 * sizeof(T), std::numeric_limits<T>::max(),
        "gravity scale beyond max_size");
    bad(at.box_position + sizeof(Vec3<T>), T(3), "orientation not unit");
}

TEST_CASE_TEMPLATE("restore_snapshot rejects a pending event naming a part its body does not have", T, float, double) {
    // A listener may index a compound's parts with an event's part index: one of 1,000,000 on a
    // box was accepted and handed to the listener.
    CorruptionScene<T> s;
    s.w.set_enabled(s.box, false);  // its contacts end between steps: pending events, the last table
    const std::vector<std::uint8_t> good = save_snapshot(s.w);
    const std::size_t size = sizeof(ContactEvent<T>);
    std::uint64_t pending = 0;
    for (std::uint64_t n = 1; n <= 8 && pending == 0; ++n) {
        std::uint64_t count = 0;
        std::memcpy(&count, good.data() + good.size() - n * size - 8, 8);
        if (count == n) pending = n;
    }
    REQUIRE(pending >= 1);
    const ContactEvent<T> event{};
    const std::size_t first = good.size() - pending * size;
    for (const auto child : {&ContactEvent<T>::child_a, &ContactEvent<T>::child_b}) {
        std::vector<std::uint8_t> b = good;
        poke(b, first + member_offset(event, event.*child), std::uint32_t(1000000));
        check_rejected<T>(b, "pending event part index 1,000,000");
    }
    World<T> copy;  // the untouched buffer restores, and its step reports the events
    restore_snapshot(copy, good);
    copy.step(T(1) / T(60));
    CHECK(copy.contact_events().size() >= pending);
}

TEST_CASE_TEMPLATE("single-byte corruptions of a snapshot are rejected or restore a world that behaves", T, float, double) {
    // Every fifth byte (the slow test takes every byte, four values each), flipped whole.
#ifdef XENO_SANITIZE
    const std::size_t stride = 23;
#else
    const std::size_t stride = 5;
#endif
    const auto [rejected, accepted] = sweep_corruptions<T>(0, stride, 3);
    MESSAGE(rejected << " rejected, " << accepted << " accepted");
    CHECK(rejected > 0);
}

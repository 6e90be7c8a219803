// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Snapshots: the whole state of a World<T> as a byte buffer, and back. Everything that decides the
// next step is saved (settings, bodies with their shapes, handles' generations and free slots,
// broad-phase boxes, contacts with their warm-start impulses, joints with theirs, the
// accumulator, pending events), so stepping after a restore is bitwise identical to stepping
// the original: the basis of rollback networking and replays. Shapes shared by several bodies are
// stored once and shared again after a restore. Callbacks (contact listener, pair filter) are
// code, not state: the restored world keeps its own.
//
// The format is for the same program on the same machine (native byte order and scalar type); a
// buffer from another scalar type, a truncated buffer or a wrong header is rejected with
// InvalidArgument before the world is touched.
#pragma once

#include "world.hpp"

#include <cstdint>
#include <cstring>
#include <map>
#include <type_traits>
#include <vector>

namespace xeno {

/// The world's state as bytes (see the file comment).
template <class T>
std::vector<std::uint8_t> save_snapshot(const World<T>& world);

/// Replaces the world's state by a snapshot's. A malformed buffer is rejected (InvalidArgument)
/// and leaves the world unchanged.
template <class T>
void restore_snapshot(World<T>& world, const std::vector<std::uint8_t>& bytes);

namespace detail {

class ByteWriter {
public:
    template <class V>
    void put(const V& value) {
        static_assert(std::is_trivially_copyable_v<V>, "only plain values are written byte for byte");
        const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
        bytes.insert(bytes.end(), p, p + sizeof(V));
    }
    template <class V>
    void put_vector(const std::vector<V>& values) {
        put(static_cast<std::uint64_t>(values.size()));
        for (const V& v : values) put(v);
    }
    std::vector<std::uint8_t> bytes;
};

class ByteReader {
public:
    explicit ByteReader(const std::vector<std::uint8_t>& bytes) : bytes_(bytes) {}
    template <class V>
    V get() {
        static_assert(std::is_trivially_copyable_v<V>, "only plain values are read byte for byte");
        if (bytes_.size() - offset_ < sizeof(V)) report_invalid("restore_snapshot", "the buffer is truncated at byte", static_cast<double>(offset_));
        V value;
        std::memcpy(&value, bytes_.data() + offset_, sizeof(V));
        offset_ += sizeof(V);
        return value;
    }
    template <class V>
    std::vector<V> get_vector() {
        const std::uint64_t n = get<std::uint64_t>();
        if (n > (bytes_.size() - offset_) / (sizeof(V) > 0 ? sizeof(V) : 1))
            report_invalid("restore_snapshot", "a length runs past the end of the buffer; length", static_cast<double>(n));
        std::vector<V> out;
        out.reserve(static_cast<std::size_t>(n));
        for (std::uint64_t i = 0; i < n; ++i) out.push_back(get<V>());
        return out;
    }
    bool done() const { return offset_ == bytes_.size(); }

private:
    const std::vector<std::uint8_t>& bytes_;
    std::size_t offset_ = 0;
};

constexpr std::uint32_t kSnapshotMagic = 0x4F4E4558;  // "XENO"
constexpr std::uint32_t kSnapshotVersion = 1;

template <class T>
void write_shape(ByteWriter& w, const Shape<T>& shape) {
    w.put(static_cast<std::uint32_t>(shape.index()));
    std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, Sphere<T>>) {
                w.put(s.radius());
            } else if constexpr (std::is_same_v<S, Box<T>>) {
                w.put(s.half_extents());
            } else if constexpr (std::is_same_v<S, Capsule<T>> || std::is_same_v<S, Cylinder<T>>) {
                w.put(s.radius());
                w.put(s.half_height());
            } else if constexpr (std::is_same_v<S, Cone<T>>) {
                w.put(s.radius());
                w.put(s.height());
            } else {
                w.put_vector(s.vertices());
                w.put(static_cast<std::uint64_t>(s.faces().size()));
                for (const auto& f : s.faces()) {
                    w.put(f.count);
                    for (std::uint32_t k = 0; k < f.count; ++k) w.put(s.face_indices()[f.first + k]);
                }
            }
        },
        shape);
}

template <class T>
Shape<T> read_shape(ByteReader& r) {
    switch (r.get<std::uint32_t>()) {
        case 0: return Sphere<T>(r.get<T>());
        case 1: return Box<T>(r.get<Vec3<T>>());
        case 2: {
            const T radius = r.get<T>();
            return Capsule<T>(radius, r.get<T>());
        }
        case 3: {
            const T radius = r.get<T>();
            return Cylinder<T>(radius, r.get<T>());
        }
        case 4: {
            const T radius = r.get<T>();
            return Cone<T>(radius, r.get<T>());
        }
        case 5: {
            std::vector<Vec3<T>> vertices = r.get_vector<Vec3<T>>();
            const std::uint64_t face_count = r.get<std::uint64_t>();
            std::vector<std::vector<std::uint32_t>> faces;
            for (std::uint64_t f = 0; f < face_count && f < (std::uint64_t(1) << 24); ++f) {
                const std::uint32_t count = r.get<std::uint32_t>();
                if (count > vertices.size()) report_invalid("restore_snapshot", "a face lists more vertices than the hull has", count);
                std::vector<std::uint32_t> face;
                for (std::uint32_t k = 0; k < count; ++k) face.push_back(r.get<std::uint32_t>());
                faces.push_back(std::move(face));
            }
            return ConvexPolyhedron<T>(std::move(vertices), faces);
        }
        default: report_invalid("restore_snapshot", "unknown shape kind in the buffer", -1.0);
    }
}

}  // namespace detail

/// Friend of World and Body: reads and writes their private state.
template <class T>
struct SnapshotAccess {
    static std::vector<std::uint8_t> save(const World<T>& world) {
        detail::ByteWriter w;
        w.put(detail::kSnapshotMagic);
        w.put(detail::kSnapshotVersion);
        w.put(static_cast<std::uint32_t>(sizeof(T)));
        w.put(world.settings_);
        w.put(world.accumulator_);
        // Shapes and compounds, each once, in order of first use.
        std::map<const void*, std::uint32_t> shape_ids, compound_ids;
        std::vector<const Shape<T>*> shapes;
        std::vector<const Compound<T>*> compounds;
        for (const Body<T>& b : world.bodies_) {
            if (b.shape_ && shape_ids.emplace(b.shape_.get(), static_cast<std::uint32_t>(shapes.size())).second) shapes.push_back(b.shape_.get());
            if (b.compound_ && compound_ids.emplace(b.compound_.get(), static_cast<std::uint32_t>(compounds.size())).second)
                compounds.push_back(b.compound_.get());
        }
        w.put(static_cast<std::uint64_t>(shapes.size()));
        for (const Shape<T>* s : shapes) detail::write_shape(w, *s);
        w.put(static_cast<std::uint64_t>(compounds.size()));
        for (const Compound<T>* c : compounds) {
            w.put(static_cast<std::uint64_t>(c->size()));
            for (const CompoundChild<T>& child : c->children()) {
                detail::write_shape(w, child.shape);
                w.put(child.local);
            }
            w.put(c->shift_), w.put(c->unit_mass_), w.put(c->bounds_), w.put(c->radius_);
        }
        w.put(static_cast<std::uint64_t>(world.bodies_.size()));
        for (const Body<T>& b : world.bodies_) {
            w.put(b.alive_);
            w.put(b.generation_);
            if (!b.alive_) continue;
            w.put(b.shape_ ? shape_ids.at(b.shape_.get()) : ~std::uint32_t(0));
            w.put(b.compound_ ? compound_ids.at(b.compound_.get()) : ~std::uint32_t(0));
            w.put(b.position_), w.put(b.orientation_), w.put(b.linear_velocity_), w.put(b.angular_velocity_);
            w.put(b.force_), w.put(b.torque_), w.put(b.inertia_local_), w.put(b.inverse_mass_), w.put(b.material_);
            w.put(b.linear_damping_), w.put(b.angular_damping_), w.put(b.gravity_scale_), w.put(b.sleep_time_);
            w.put(b.user_data_), w.put(b.layer_), w.put(b.mask_), w.put(b.type_);
            w.put(b.awake_), w.put(b.allow_sleep_), w.put(b.fast_), w.put(b.sensor_), w.put(b.isotropic_), w.put(b.moved_);
        }
        w.put_vector(world.free_slots_);
        w.put_vector(world.bounds_);
        w.put_vector(world.previous_pose_);
        w.put_vector(world.contacts_);
        w.put_vector(world.joints_);
        w.put_vector(world.free_joints_);
        w.put_vector(world.events_pending_);
        return std::move(w.bytes);
    }

    static void restore(World<T>& world, const std::vector<std::uint8_t>& bytes) {
        world.require_outside_filter("restore_snapshot");
        // Everything is read into a fresh world first: a bad buffer leaves `world` untouched.
        detail::ByteReader r(bytes);
        if (r.get<std::uint32_t>() != detail::kSnapshotMagic) detail::report_invalid("restore_snapshot", "not a xeno snapshot (bad header); size", static_cast<double>(bytes.size()));
        const std::uint32_t version = r.get<std::uint32_t>();
        if (version != detail::kSnapshotVersion) detail::report_invalid("restore_snapshot", "unsupported snapshot version", version);
        const std::uint32_t scalar = r.get<std::uint32_t>();
        if (scalar != sizeof(T)) detail::report_invalid("restore_snapshot", "the snapshot is of another scalar type; its scalar size", scalar);
        World<T> out(r.get<WorldSettings<T>>());
        out.accumulator_ = r.get<T>();
        std::vector<std::shared_ptr<const Shape<T>>> shapes(static_cast<std::size_t>(std::min<std::uint64_t>(r.get<std::uint64_t>(), bytes.size())));
        for (auto& s : shapes) s = std::make_shared<const Shape<T>>(detail::read_shape<T>(r));
        std::vector<std::shared_ptr<const Compound<T>>> compounds(static_cast<std::size_t>(std::min<std::uint64_t>(r.get<std::uint64_t>(), bytes.size())));
        for (auto& c : compounds) {
            const std::uint64_t n = r.get<std::uint64_t>();
            Compound<T> compound;  // restored field by field: rebuilding would re-centre by round-off
            for (std::uint64_t i = 0; i < n && i < bytes.size(); ++i) {
                Shape<T> shape = detail::read_shape<T>(r);
                compound.children_.push_back({std::move(shape), r.get<Transform<T>>()});
            }
            compound.shift_ = r.get<Vec3<T>>(), compound.unit_mass_ = r.get<MassProperties<T>>();
            compound.bounds_ = r.get<Aabb<T>>(), compound.radius_ = r.get<T>();
            if (compound.children_.empty()) detail::report_invalid("restore_snapshot", "a compound without parts", 0.0);
            c = std::make_shared<const Compound<T>>(std::move(compound));
        }
        const std::uint64_t body_count = r.get<std::uint64_t>();
        if (body_count > bytes.size()) detail::report_invalid("restore_snapshot", "body count runs past the buffer", static_cast<double>(body_count));
        out.bodies_.resize(static_cast<std::size_t>(body_count));
        for (Body<T>& b : out.bodies_) {
            b.alive_ = r.get<bool>();
            b.generation_ = r.get<std::uint32_t>();
            if (!b.alive_) continue;
            const std::uint32_t shape = r.get<std::uint32_t>(), compound = r.get<std::uint32_t>();
            if (shape != ~std::uint32_t(0)) {
                if (shape >= shapes.size()) detail::report_invalid("restore_snapshot", "a body refers to a missing shape", shape);
                b.shape_ = shapes[shape];
            } else {
                if (compound >= compounds.size()) detail::report_invalid("restore_snapshot", "a body refers to a missing compound", compound);
                b.compound_ = compounds[compound];
            }
            b.position_ = r.get<Vec3<T>>(), b.orientation_ = r.get<Quat<T>>();
            b.linear_velocity_ = r.get<Vec3<T>>(), b.angular_velocity_ = r.get<Vec3<T>>();
            b.force_ = r.get<Vec3<T>>(), b.torque_ = r.get<Vec3<T>>(), b.inertia_local_ = r.get<Mat3<T>>();
            b.inverse_mass_ = r.get<T>(), b.material_ = r.get<Material<T>>();
            b.linear_damping_ = r.get<T>(), b.angular_damping_ = r.get<T>(), b.gravity_scale_ = r.get<T>(), b.sleep_time_ = r.get<T>();
            b.user_data_ = r.get<std::uint64_t>(), b.layer_ = r.get<std::uint32_t>(), b.mask_ = r.get<std::uint32_t>();
            b.type_ = r.get<BodyType>();
            b.awake_ = r.get<bool>(), b.allow_sleep_ = r.get<bool>(), b.fast_ = r.get<bool>(), b.sensor_ = r.get<bool>();
            b.isotropic_ = r.get<bool>(), b.moved_ = r.get<bool>();
        }
        out.free_slots_ = r.get_vector<std::uint32_t>();
        out.bounds_ = r.get_vector<Aabb<T>>();
        out.previous_pose_ = r.get_vector<Transform<T>>();
        out.contacts_ = r.get_vector<Contact<T>>();
        out.joints_ = r.get_vector<Joint<T>>();
        out.free_joints_ = r.get_vector<std::uint32_t>();
        out.events_pending_ = r.get_vector<ContactEvent<T>>();
        if (!r.done()) detail::report_invalid("restore_snapshot", "bytes left over after the world (not a snapshot of this version?); size", static_cast<double>(bytes.size()));
        if (out.bounds_.size() != out.bodies_.size() || out.previous_pose_.size() != out.bodies_.size())
            detail::report_invalid("restore_snapshot", "inconsistent body tables; bodies", static_cast<double>(out.bodies_.size()));
        for (const Contact<T>& c : out.contacts_)
            if (c.a.index >= out.bodies_.size() || c.b.index >= out.bodies_.size() || !out.bodies_[c.a.index].alive_ || !out.bodies_[c.b.index].alive_)
                detail::report_invalid("restore_snapshot", "a contact refers to a missing body; index", static_cast<double>(c.a.index));
        for (const Joint<T>& j : out.joints_)
            if (j.alive && (j.a.index >= out.bodies_.size() || j.b.index >= out.bodies_.size()))
                detail::report_invalid("restore_snapshot", "a joint refers to a missing body; index", static_cast<double>(j.a.index));
        out.solver_index_.assign(out.bodies_.size(), 0);
        out.rebuild_joint_pairs();
        // Keep the target's callbacks; take everything else.
        out.listener_ = std::move(world.listener_);
        out.filter_ = std::move(world.filter_);
        out.in_listener_ = world.in_listener_;  // restored from inside the listener: still inside it
        world = std::move(out);
    }
};

template <class T>
std::vector<std::uint8_t> save_snapshot(const World<T>& world) {
    return SnapshotAccess<T>::save(world);
}

template <class T>
void restore_snapshot(World<T>& world, const std::vector<std::uint8_t>& bytes) {
    SnapshotAccess<T>::restore(world, bytes);
}

}  // namespace xeno

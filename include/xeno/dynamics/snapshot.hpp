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
#include <algorithm>
#include <array>
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
        if (bytes_.size() - offset_ < sizeof(V))
            report_invalid("restore_snapshot", "the buffer is truncated at byte", static_cast<double>(offset_));
        V value;
        std::memcpy(&value, bytes_.data() + offset_, sizeof(V));
        offset_ += sizeof(V);
        return value;
    }
    template <class V>
    std::vector<V> get_vector() {
        const std::uint64_t n = get_count(sizeof(V), "a length runs past the end of the buffer; length");
        std::vector<V> out;
        out.reserve(static_cast<std::size_t>(n));
        for (std::uint64_t i = 0; i < n; ++i) out.push_back(get<V>());
        return out;
    }
    /// A bool written as one byte: 0 or 1, anything else is rejected (loading it as a bool would
    /// be undefined behaviour).
    bool get_bool() {
        const std::uint8_t b = get<std::uint8_t>();
        if (b > 1) report_invalid("restore_snapshot", "a bool byte is neither 0 nor 1; byte", b);
        return b == 1;
    }
    bool done() const { return offset_ == bytes_.size(); }
    std::size_t remaining() const { return bytes_.size() - offset_; }
    /// A count read before the records it counts, each at least `record` bytes of what follows:
    /// larger than the rest of the buffer can hold is rejected before anything is sized by it
    /// (an 8 MB buffer of zeros claimed 1.6 million bodies and allocated 2.4 GB).
    std::uint64_t get_count(std::size_t record, const char* what) {
        const std::uint64_t n = get<std::uint64_t>();
        if (n > remaining() / record) report_invalid("restore_snapshot", what, static_cast<double>(n));
        return n;
    }

private:
    const std::vector<std::uint8_t>& bytes_;
    std::size_t offset_ = 0;
};

/// The byte of a bool stored inside a struct read byte for byte, inspected without loading it as
/// a bool (a byte other than 0 or 1 is not a bool value).
template <class B>
bool raw_bool_ok(const B& b) {
    static_assert(sizeof(B) == 1, "a bool is one byte here");
    std::uint8_t u;
    std::memcpy(&u, &b, 1);
    return u <= 1;
}

/// The underlying value of an enum stored inside a struct read byte for byte.
template <class E>
std::underlying_type_t<E> raw_enum(const E& e) {
    std::underlying_type_t<E> u;
    std::memcpy(&u, &e, sizeof u);
    return u;
}

/// |q|² within the relative tolerance of 1: what normalising leaves.
template <class T>
bool unit_quat(const Quat<T>& q) {
    return is_finite(q) && std::abs(length_squared(q) - T(1)) <= ScalarTraits<T>::relative_tolerance;
}
template <class T>
bool unit_vector(const Vec3<T>& v) {
    return is_finite(v) && std::abs(length_squared(v) - T(1)) <= ScalarTraits<T>::relative_tolerance;
}
template <class T>
bool box_ok(const Aabb<T>& b) {
    return is_finite(b.min) && is_finite(b.max) && b.min.x <= b.max.x && b.min.y <= b.max.y && b.min.z <= b.max.z;
}

constexpr std::uint32_t kSnapshotMagic = 0x4F4E4558;  // "XENO"
constexpr std::uint32_t kSnapshotVersion = 9;         // 2: WorldSettings::max_contact_pairs; 3: Body enabled and density,
                                                      // the last substep, prismatic and swing-twist joints; 4: the
                                                      // pose each contact's manifold was made at,
                                                      // WorldSettings::reuse_contacts; 5: static_contact_damping_ratio,
                                                      // first_relax_iterations; 6: each body's rest pose;
                                                      // 7: each contact's twist lever and its key;
                                                      // 8: the parts of a pending event;
                                                      // 9: each body's impulse halvings

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
                if (count > vertices.size())
                    report_invalid("restore_snapshot", "a face lists more vertices than the hull has", count);
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
    // restore() checks every field it reads: what the doors of the world would have let in
    // (ranges, finiteness, enum values, bools), and the cross-references the step relies on
    // (free slots are exactly the dead slots, contacts and joints join living bodies, contacts are
    // sorted as the narrow phase merges them). A corrupt buffer is rejected, never simulated.
    // The fewest bytes a record takes in the buffer, to bound the counts read before them
    // (ByteReader::get_count): a shape is at least its kind and one scalar (a sphere); a body
    // slot at least its alive flag and generation, plus its world box and last pose in the
    // tables after the bodies; a living body at least that, its geometry indices, pose,
    // velocities and inertia.
    static constexpr std::size_t kShapeBytes = 4 + sizeof(T);
    static constexpr std::size_t kSlotBytes = 1 + 4 + sizeof(Aabb<T>) + sizeof(Transform<T>);
    static constexpr std::size_t kLiveBodyBytes = kSlotBytes + 8 + 3 * sizeof(Vec3<T>) + sizeof(Quat<T>) + sizeof(Mat3<T>);
    static void check_geometry_used(const std::vector<std::shared_ptr<const Shape<T>>>& shapes,
                                    const std::vector<std::shared_ptr<const Compound<T>>>& compounds) {
        for (std::size_t i = 0; i < shapes.size(); ++i)
            if (shapes[i].use_count() == 1)
                detail::report_invalid("restore_snapshot", "a shape no body uses; shape", static_cast<double>(i));
        for (std::size_t i = 0; i < compounds.size(); ++i)
            if (compounds[i].use_count() == 1)
                detail::report_invalid("restore_snapshot", "a compound no body uses; compound", static_cast<double>(i));
    }
    static void check_settings(const WorldSettings<T>& s);
    static void check_compound(const Compound<T>& c);
    static void check_body(const World<T>& w, std::uint32_t slot);
    static void check_world(const World<T>& w);
    static void check_body_slots(const World<T>& w);
    static void check_contact(const World<T>& w, std::size_t k);
    static void check_joints(const World<T>& w);
    static void check_joint(const World<T>& w, std::size_t k);
    static void check_pending_events(const World<T>& w);
    static bool linear_ok(const World<T>& w, T impulse, std::uint32_t a, std::uint32_t b);
    static bool angular_ok(const World<T>& w, T impulse, std::uint32_t a, std::uint32_t b);
    static int pending_halvings(const World<T>& w, std::uint32_t a, std::uint32_t b) {
        return std::max(w.bodies_[a].impulse_halvings_, w.bodies_[b].impulse_halvings_);
    }
    static T magnitude(const Vec3<T>& v);
    static bool living(const World<T>& w, BodyId id);

    static std::vector<std::uint8_t> save(const World<T>& world) {
        // Meshes and heightfields are not in the format yet (docs/meshes.md, "Limits"): refuse
        // rather than write a snapshot that would load without its level.
        for (std::uint32_t i = 0; i < world.bodies_.size(); ++i)
            if (world.bodies_[i].alive_ && world.bodies_[i].mesh())
                detail::report_invalid("save_snapshot", "snapshots cannot hold mesh or heightfield bodies yet; body index",
                                       static_cast<double>(i));
        detail::ByteWriter w;
        w.put(detail::kSnapshotMagic);
        w.put(detail::kSnapshotVersion);
        w.put(static_cast<std::uint32_t>(sizeof(T)));
        w.put(world.settings_);
        w.put(world.accumulator_);
        w.put(world.last_substep_);
        // Shapes and compounds, each once, in order of first use.
        std::map<const void*, std::uint32_t> shape_ids, compound_ids;
        std::vector<const Shape<T>*> shapes;
        std::vector<const Compound<T>*> compounds;
        for (const Body<T>& b : world.bodies_) {
            if (b.convex_shape() && shape_ids.emplace(b.convex_shape(), static_cast<std::uint32_t>(shapes.size())).second)
                shapes.push_back(b.convex_shape());
            if (b.compound() && compound_ids.emplace(b.compound(), static_cast<std::uint32_t>(compounds.size())).second)
                compounds.push_back(b.compound());
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
            w.put(b.convex_shape() ? shape_ids.at(b.convex_shape()) : ~std::uint32_t(0));
            w.put(b.compound() ? compound_ids.at(b.compound()) : ~std::uint32_t(0));
            w.put(b.position_), w.put(b.orientation_), w.put(b.linear_velocity_), w.put(b.angular_velocity_);
            w.put(b.force_), w.put(b.torque_), w.put(b.inertia_local_), w.put(b.inverse_mass_), w.put(b.material_);
            w.put(b.linear_damping_), w.put(b.angular_damping_), w.put(b.gravity_scale_), w.put(b.sleep_time_), w.put(b.density_);
            w.put(b.rest_position_), w.put(b.rest_orientation_);
            w.put(b.user_data_), w.put(b.layer_), w.put(b.mask_), w.put(b.type_);
            w.put(b.awake_), w.put(b.allow_sleep_), w.put(b.fast_), w.put(b.sensor_), w.put(b.isotropic_), w.put(b.moved_);
            w.put(b.enabled_), w.put(b.impulse_halvings_);
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

    /// One compound, restored field by field: rebuilding it would re-centre it by round-off.
    static std::shared_ptr<const Compound<T>> read_compound(detail::ByteReader& r) {
        const std::uint64_t n =
            r.get_count(kShapeBytes + sizeof(Transform<T>), "a compound has more parts than the buffer holds");
        Compound<T> compound;
        for (std::uint64_t i = 0; i < n; ++i) {
            Shape<T> shape = detail::read_shape<T>(r);
            compound.children_.push_back({std::move(shape), r.get<Transform<T>>()});
        }
        compound.shift_ = r.get<Vec3<T>>(), compound.unit_mass_ = r.get<MassProperties<T>>();
        compound.bounds_ = r.get<Aabb<T>>(), compound.radius_ = r.get<T>();
        if (compound.children_.empty()) detail::report_invalid("restore_snapshot", "a compound without parts", 0.0);
        check_compound(compound);
        return std::make_shared<const Compound<T>>(std::move(compound));
    }

    /// One body slot, its geometry one of `shapes` or `compounds` (check_body checks the rest).
    static void read_body(detail::ByteReader& r, const std::vector<std::shared_ptr<const Shape<T>>>& shapes,
                          const std::vector<std::shared_ptr<const Compound<T>>>& compounds, Body<T>& b) {
        b.alive_ = r.get_bool();
        b.generation_ = r.get<std::uint32_t>();
        if (!b.alive_) return;
        const std::uint32_t shape = r.get<std::uint32_t>(), compound = r.get<std::uint32_t>();
        if (shape != ~std::uint32_t(0)) {
            if (shape >= shapes.size()) detail::report_invalid("restore_snapshot", "a body refers to a missing shape", shape);
            if (compound != ~std::uint32_t(0))
                detail::report_invalid("restore_snapshot", "a body refers to both a shape and a compound", compound);
            b.set_geometry(shapes[shape], nullptr, nullptr);
        } else {
            if (compound >= compounds.size())
                detail::report_invalid("restore_snapshot", "a body refers to a missing compound", compound);
            b.set_geometry(nullptr, compounds[compound], nullptr);
        }
        b.position_ = r.get<Vec3<T>>(), b.orientation_ = r.get<Quat<T>>();
        b.linear_velocity_ = r.get<Vec3<T>>(), b.angular_velocity_ = r.get<Vec3<T>>();
        b.force_ = r.get<Vec3<T>>(), b.torque_ = r.get<Vec3<T>>(), b.inertia_local_ = r.get<Mat3<T>>();
        b.inverse_mass_ = r.get<T>(), b.material_ = r.get<Material<T>>();
        b.linear_damping_ = r.get<T>(), b.angular_damping_ = r.get<T>(), b.gravity_scale_ = r.get<T>(),
        b.sleep_time_ = r.get<T>(), b.density_ = r.get<T>();
        b.rest_position_ = r.get<Vec3<T>>(), b.rest_orientation_ = r.get<Quat<T>>();
        b.user_data_ = r.get<std::uint64_t>(), b.layer_ = r.get<std::uint32_t>(), b.mask_ = r.get<std::uint32_t>();
        const std::uint8_t type = r.get<std::uint8_t>();
        if (type > static_cast<std::uint8_t>(BodyType::dynamic))
            detail::report_invalid("restore_snapshot", "a body's type is not a BodyType", type);
        b.type_ = static_cast<BodyType>(type);
        b.awake_ = r.get_bool(), b.allow_sleep_ = r.get_bool(), b.fast_ = r.get_bool(), b.sensor_ = r.get_bool();
        b.isotropic_ = r.get_bool(), b.moved_ = r.get_bool();
        b.enabled_ = r.get_bool();
        b.impulse_halvings_ = r.get<std::uint8_t>();
    }

    static void restore(World<T>& world, const std::vector<std::uint8_t>& bytes) {
        world.require_outside_filter("restore_snapshot");
        // Everything is read into a fresh world first: a bad buffer leaves `world` untouched.
        detail::ByteReader r(bytes);
        if (r.get<std::uint32_t>() != detail::kSnapshotMagic)
            detail::report_invalid("restore_snapshot", "not a xeno snapshot (bad header); size",
                                   static_cast<double>(bytes.size()));
        const std::uint32_t version = r.get<std::uint32_t>();
        if (version != detail::kSnapshotVersion)
            detail::report_invalid("restore_snapshot", "unsupported snapshot version", version);
        const std::uint32_t scalar = r.get<std::uint32_t>();
        if (scalar != sizeof(T))
            detail::report_invalid("restore_snapshot", "the snapshot is of another scalar type; its scalar size", scalar);
        const WorldSettings<T> settings = r.get<WorldSettings<T>>();
        check_settings(settings);
        World<T> out(settings);  // the constructor validates the settings as set_settings does
        out.accumulator_ = r.get<T>();
        out.last_substep_ = r.get<T>();
        if (!(std::isfinite(out.last_substep_) && out.last_substep_ >= T(0)))
            detail::report_invalid("restore_snapshot", "the last substep must be finite and >= 0",
                                   static_cast<double>(out.last_substep_));
        if (!(std::isfinite(out.accumulator_) && out.accumulator_ >= T(0)))
            detail::report_invalid("restore_snapshot", "the accumulator must be finite and >= 0",
                                   static_cast<double>(out.accumulator_));
        // Every count is bounded by the bytes its records need (get_count), and the tables grow
        // as records are read: a restore allocates in proportion to its buffer. A shape or
        // compound needs a living body's record too, and save_snapshot writes none that no body
        // uses (check_geometry_used).
        std::vector<std::shared_ptr<const Shape<T>>> shapes(static_cast<std::size_t>(
            r.get_count(kShapeBytes + kLiveBodyBytes, "more shapes than the buffer can hold; shape count")));
        for (auto& s : shapes) s = std::make_shared<const Shape<T>>(detail::read_shape<T>(r));
        std::vector<std::shared_ptr<const Compound<T>>> compounds(static_cast<std::size_t>(r.get_count(
            8 + kShapeBytes + sizeof(Transform<T>) + kLiveBodyBytes, "more compounds than the buffer can hold; compound count")));
        for (auto& c : compounds) c = read_compound(r);
        const std::uint64_t body_count = r.get_count(kSlotBytes, "more bodies than the buffer can hold; body count");
        out.bodies_.resize(static_cast<std::size_t>(body_count));
        for (Body<T>& b : out.bodies_) read_body(r, shapes, compounds, b);
        check_geometry_used(shapes, compounds);
        out.free_slots_ = r.get_vector<std::uint32_t>();
        out.bounds_ = r.get_vector<Aabb<T>>();
        out.previous_pose_ = r.get_vector<Transform<T>>();
        out.contacts_ = r.get_vector<Contact<T>>();
        out.joints_ = r.get_vector<Joint<T>>();
        out.free_joints_ = r.get_vector<std::uint32_t>();
        out.events_pending_ = r.get_vector<ContactEvent<T>>();
        if (!r.done())
            detail::report_invalid("restore_snapshot", "bytes left over after the world (not a snapshot of this version?); size",
                                   static_cast<double>(bytes.size()));
        check_world(out);
        out.solver_index_.assign(out.bodies_.size(), 0);
        out.rebuild_joint_pairs();
        if (std::any_of(out.joints_.begin(), out.joints_.end(), [](const Joint<T>& j) { return j.alive; })) out.bind_joints();
        out.rebuild_query_tree();
        out.index_contacts(out.bodies_.size());
        // Keep the target's callbacks and where it steps (its pool or the game's task system,
        // docs/parallel.md: they are the machine's, not the scene's); take everything else.
        out.listener_ = std::move(world.listener_);
        out.filter_ = std::move(world.filter_);
        out.tasks_ = std::move(world.tasks_);
        world = std::move(out);  // the target keeps its callback state: restored from inside the listener, still inside it
    }
};

namespace detail {
/// "restore_snapshot: <what>; <name> <index>" for a field that fails its check.
[[noreturn]] inline void report_corrupt(const char* what, std::size_t index) {
    report_invalid("restore_snapshot", what, static_cast<double>(index));
}
}  // namespace detail

template <class T>
void SnapshotAccess<T>::check_settings(const WorldSettings<T>& s) {
    // Bools and enums first, by their bytes; then the same validation as set_settings.
    if (!detail::raw_bool_ok(s.warm_starting) || !detail::raw_bool_ok(s.reuse_contacts) || !detail::raw_bool_ok(s.allow_sleeping))
        detail::report_invalid("restore_snapshot", "a settings bool byte is neither 0 nor 1", 0.0);
    const auto solver = detail::raw_enum(s.solver);
    if (solver != detail::raw_enum(SolverMode::soft_step) && solver != detail::raw_enum(SolverMode::baumgarte))
        detail::report_invalid("restore_snapshot", "settings.solver is not a SolverMode", static_cast<double>(solver));
    const auto broad = detail::raw_enum(s.broad_phase);
    if (broad != detail::raw_enum(BroadPhaseKind::brute_force) && broad != detail::raw_enum(BroadPhaseKind::sweep_and_prune) &&
        broad != detail::raw_enum(BroadPhaseKind::aabb_tree))
        detail::report_invalid("restore_snapshot", "settings.broad_phase is not a BroadPhaseKind", static_cast<double>(broad));
    // Counts that would make a step take hours: the settings' own validation bounds them too.
    constexpr int most_substeps = 64, most_iterations = 256, most_joint_iterations = 64, most_steps_per_update = 1000;
    if (s.substeps > most_substeps) detail::report_invalid("restore_snapshot", "settings.substeps above 64", s.substeps);
    if (s.velocity_iterations > most_iterations)
        detail::report_invalid("restore_snapshot", "settings.velocity_iterations above 256", s.velocity_iterations);
    if (s.relax_iterations > most_iterations)
        detail::report_invalid("restore_snapshot", "settings.relax_iterations above 256", s.relax_iterations);
    if (s.first_relax_iterations > most_iterations)
        detail::report_invalid("restore_snapshot", "settings.first_relax_iterations above 256", s.first_relax_iterations);
    if (s.joint_iterations > most_joint_iterations)
        detail::report_invalid("restore_snapshot", "settings.joint_iterations above 64", s.joint_iterations);
    if (s.max_steps_per_update > most_steps_per_update)
        detail::report_invalid("restore_snapshot", "settings.max_steps_per_update above 1000", s.max_steps_per_update);
    detail::validate(s);
}

template <class T>
void SnapshotAccess<T>::check_compound(const Compound<T>& c) {
    // The children were checked by their shapes' constructors; the derived fields must be what
    // the Compound constructor computes from them (rebuilt here: the children are centred, so the
    // rebuilt compound agrees to round-off).
    for (std::size_t i = 0; i < c.children_.size(); ++i)
        if (!is_finite(c.children_[i].local.position) || !detail::unit_quat(c.children_[i].local.orientation))
            detail::report_corrupt("a compound child's transform is not finite with a unit orientation; child", i);
    const Compound<T> ref(c.children_);
    const T r = ref.bounding_radius();
    const T tol = T(1e-3);
    const MassProperties<T>& m = c.unit_mass_;
    bool ok = is_finite(c.shift_) && std::isfinite(c.radius_) && detail::box_ok(c.bounds_) && std::isfinite(m.mass) &&
              is_finite(m.center) && is_finite(m.inertia);
    ok = ok && std::abs(c.radius_ - r) <= tol * r && length(ref.shift()) <= tol * r && length(m.center) <= tol * r &&
         length(c.bounds_.min - ref.local_bounds().min) <= tol * r && length(c.bounds_.max - ref.local_bounds().max) <= tol * r &&
         std::abs(m.mass - ref.unit_mass_.mass) <= tol * ref.unit_mass_.mass;
    const T scale = trace(ref.unit_mass_.inertia);
    for (int i = 0; ok && i < 3; ++i) ok = length(m.inertia[i] - ref.unit_mass_.inertia[i]) <= tol * scale;
    if (!ok)
        detail::report_invalid("restore_snapshot", "a compound's mass, bounds or radius do not match its children; radius",
                               static_cast<double>(c.radius_));
}

template <class T>
void SnapshotAccess<T>::check_body(const World<T>& w, std::uint32_t slot) {
    const Body<T>& b = w.bodies_[slot];
    const auto bad = [slot](const char* what) { detail::report_corrupt(what, slot); };
    const T radius = b.bounding_radius();
    if (b.convex_shape() && length(interior_point(*b.convex_shape())) > T(1e-4) * radius)
        bad("a body's shape is not centred on its centre of mass; body slot");
    if (!is_finite(b.position_) || !detail::unit_quat(b.orientation_))
        bad("a body's pose is not finite with a unit orientation; body slot");
    if (!is_finite(b.rest_position_) || !detail::unit_quat(b.rest_orientation_))
        bad("a body's rest pose (sleeping) is not finite with a unit orientation; body slot");
    if (!is_finite(b.linear_velocity_) || !is_finite(b.angular_velocity_) || !is_finite(b.force_) || !is_finite(b.torque_))
        bad("a body's velocity, force or torque is not finite; body slot");
    if (!(b.material_.friction >= T(0) && std::isfinite(b.material_.friction) && b.material_.restitution >= T(0) &&
          b.material_.restitution <= T(1)))
        bad("a body's material is out of range; body slot");
    if (!(std::isfinite(b.linear_damping_) && b.linear_damping_ >= T(0) && std::isfinite(b.angular_damping_) &&
          b.angular_damping_ >= T(0)))
        bad("a body's damping is not finite and >= 0; body slot");
    // The gravity scale within what Body::set_gravity_scale takes (FLT_MAX made gravity × scale inf).
    if (!(std::isfinite(b.gravity_scale_) && std::abs(b.gravity_scale_) <= ScalarTraits<T>::max_size) ||
        !(std::isfinite(b.sleep_time_) && b.sleep_time_ >= T(0)))
        bad("a body's gravity scale or sleep time is out of range; body slot");
    if (std::isnan(b.density_)) bad("a body's density is not a number; body slot");  // any other value is checked when used
    if (b.type_ == BodyType::dynamic) {
        if (!(std::isfinite(b.inverse_mass_) && b.inverse_mass_ > T(0) && std::isfinite(T(1) / b.inverse_mass_)))
            bad("a dynamic body's inverse mass is not finite and > 0; body slot");
        detail::check_mass_properties(MassProperties<T>{T(1) / b.inverse_mass_, Vec3<T>::zero(), b.inertia_local_}, radius,
                                      "restore_snapshot");
        const Mat3<T>& i = b.inertia_local_;
        const T mean = trace(i) / T(3);
        const bool isotropic = length(i[0] - Vec3<T>::unit_x() * mean) + length(i[1] - Vec3<T>::unit_y() * mean) +
                                   length(i[2] - Vec3<T>::unit_z() * mean) <=
                               T(1e-6) * mean;
        if (isotropic != b.isotropic_) bad("a body's isotropic flag does not match its inertia; body slot");
        // Any finite accumulated force and torque (checked above) is accepted, as Body::accumulate
        // accepts it: the acceleration it gives may exceed max_size, or overflow after a change
        // of mass or orientation, and the step copes (World::integration_constants). A cap here
        // refused the world's own snapshot after apply_force(1e10 N) on a 1000 kg float box.
    } else {
        const Mat3<T>& i = b.inertia_local_;
        if (b.inverse_mass_ != T(0) || !(i[0] == Vec3<T>::zero() && i[1] == Vec3<T>::zero() && i[2] == Vec3<T>::zero()))
            bad("a static or kinematic body has mass; body slot");
        if (b.force_ != Vec3<T>::zero() || b.torque_ != Vec3<T>::zero()) bad("a static or kinematic body has a force; body slot");
        if (b.type_ == BodyType::static_body && (b.linear_velocity_ != Vec3<T>::zero() || b.angular_velocity_ != Vec3<T>::zero()))
            bad("a static body moves; body slot");
    }
    if (b.enabled_ && !detail::box_ok(w.bounds_[slot])) bad("a body's broad-phase box is not finite with min <= max; body slot");
    // A static body keeps its box until it is moved (World::keep_poses_and_update_bounds): one that
    // does not hold the body (a corrupt box 1 km off, or a flipped sign bit) let bodies fall through
    // the floor for good.
    if (b.enabled_ && b.type_ == BodyType::static_body && !b.moved_ && !w.bounds_[slot].contains(b.world_bounds()))
        bad("a static body's broad-phase box does not hold it; body slot");
    const Aabb<T> empty{};  // a disabled body's box stays empty so the broad phase never pairs it
    if (!b.enabled_ && std::memcmp(&w.bounds_[slot], &empty, sizeof empty) != 0)
        bad("a disabled body has a broad-phase box; body slot");
    if (!is_finite(w.previous_pose_[slot].position) || !detail::unit_quat(w.previous_pose_[slot].orientation))
        bad("a body's previous pose is not finite with a unit orientation; body slot");
}

// Warm-start impulses are caches of the solver: each must give the bodies it acts on a finite
// velocity change (m/s at their bounding radius, or rad/s). Within max_size was asked until
// 0.9.1, but a step does not keep to it: a box welded with an anchor 1e5 m out, or a distance
// joint anchored 1e20 m out on a light body, left contact and joint impulses beyond it, and the
// world's own snapshot did not restore. Beyond max_size the next step is what stepping the
// original would be: its caps and its last defence (World::discard_overflowed_solve) hold.
template <class T>
bool SnapshotAccess<T>::linear_ok(const World<T>& w, T impulse, std::uint32_t a, std::uint32_t b) {
    const auto reach = [](const Body<T>& body) { return detail::speed_per_impulse(body, detail::spin_per_impulse(body)); };
    return std::abs(impulse) * (reach(w.bodies_[a]) + reach(w.bodies_[b])) <= ScalarTraits<T>::max;
}
template <class T>
bool SnapshotAccess<T>::angular_ok(const World<T>& w, T impulse, std::uint32_t a, std::uint32_t b) {
    return std::abs(impulse) * (detail::spin_per_impulse(w.bodies_[a]) + detail::spin_per_impulse(w.bodies_[b])) <=
           ScalarTraits<T>::max;
}
/// |v| without squaring past the range (1e20 in float).
template <class T>
T SnapshotAccess<T>::magnitude(const Vec3<T>& v) {
    const T largest = max_component(abs(v));
    return largest > T(0) ? largest * length(v / largest) : T(0);
}
template <class T>
bool SnapshotAccess<T>::living(const World<T>& w, BodyId id) {
    return id.index < w.bodies_.size() && w.bodies_[id.index].alive_ && w.bodies_[id.index].generation_ == id.generation;
}

template <class T>
void SnapshotAccess<T>::check_world(const World<T>& w) {
    check_body_slots(w);
    for (std::size_t k = 0; k < w.contacts_.size(); ++k) check_contact(w, k);
    check_joints(w);
    check_pending_events(w);
}

/// The body tables and the free slots: exactly the dead slots, each once (create_body takes them
/// without looking); every living body checked, every dead slot's box empty.
template <class T>
void SnapshotAccess<T>::check_body_slots(const World<T>& w) {
    const std::size_t n = w.bodies_.size();
    if (w.bounds_.size() != n || w.previous_pose_.size() != n) detail::report_corrupt("inconsistent body tables; bodies", n);
    if (n >= BodyId::invalid_index) detail::report_corrupt("too many body slots", n);
    std::vector<std::uint8_t> listed(n, 0);
    for (const std::uint32_t f : w.free_slots_) {
        if (f >= n) detail::report_corrupt("a free slot is out of range; slot", f);
        if (w.bodies_[f].alive_) detail::report_corrupt("a free slot holds a living body; slot", f);
        if (listed[f]++) detail::report_corrupt("a free slot is listed twice; slot", f);
    }
    const Aabb<T> empty{};
    for (std::uint32_t i = 0; i < n; ++i) {
        if (w.bodies_[i].alive_) {
            check_body(w, i);
        } else {
            if (!listed[i]) detail::report_corrupt("a dead slot is not listed as free; slot", i);
            // A dead slot's box stays empty so the broad phase never pairs it.
            if (std::memcmp(&w.bounds_[i], &empty, sizeof empty) != 0)
                detail::report_corrupt("a dead slot has a broad-phase box; slot", i);
        }
    }
}

/// Contact k: between living bodies, a < b, sorted by (a, b, child a, child b) without repeats
/// (the narrow phase merges them with the sorted broad-phase pairs), 0 … 4 finite points.
template <class T>
void SnapshotAccess<T>::check_contact(const World<T>& w, std::size_t k) {
    const Contact<T>& c = w.contacts_[k];
    if (!detail::raw_bool_ok(c.touching) || !detail::raw_bool_ok(c.was_touching) || !detail::raw_bool_ok(c.sensor))
        detail::report_corrupt("a contact's bool byte is neither 0 nor 1; contact", k);
    if (!living(w, c.a) || !living(w, c.b) || !(c.a.index < c.b.index))
        detail::report_corrupt("a contact does not join two living bodies a < b; contact", k);
    if (!w.bodies_[c.a.index].enabled_ || !w.bodies_[c.b.index].enabled_)
        detail::report_corrupt("a contact has a disabled body; contact", k);
    if (c.child_a >= w.bodies_[c.a.index].child_count() || c.child_b >= w.bodies_[c.b.index].child_count())
        detail::report_corrupt("a contact's part index is out of range; contact", k);
    if (k > 0) {
        const Contact<T>& p = w.contacts_[k - 1];
        const auto key = [](const Contact<T>& x) {
            return std::array<std::uint32_t, 4>{x.a.index, x.b.index, x.child_a, x.child_b};
        };
        if (!(key(p) < key(c))) detail::report_corrupt("contacts are not sorted by body pair and part; contact", k);
    }
    // The impulses as the next step takes them: halved for a body made lighter (Body::impulse_halvings_).
    Manifold<T> m = c.manifold;
    detail::halve_impulses(m, pending_halvings(w, c.a.index, c.b.index));
    if (m.count < 0 || m.count > Manifold<T>::capacity)
        detail::report_corrupt("a manifold's point count is not 0 … 4; contact", k);
    const std::uint32_t a = c.a.index, b = c.b.index;
    bool ok = is_finite(m.normal) && (m.count == 0 || detail::unit_vector(m.normal)) && is_finite(m.friction_impulse) &&
              std::isfinite(m.twist_impulse) && std::isfinite(c.friction) && c.friction >= T(0) && c.restitution >= T(0) &&
              c.restitution <= T(1);
    for (int i = 0; ok && i < m.count; ++i) {
        const ContactPoint<T>& p = m.points[static_cast<std::size_t>(i)];
        ok = is_finite(p.local_a) && is_finite(p.local_b) && std::isfinite(p.depth) && std::isfinite(p.normal_impulse) &&
             p.normal_impulse >= T(0) && std::isfinite(p.max_normal_impulse) && p.max_normal_impulse >= T(0) &&
             std::isfinite(p.step_impulse) && p.step_impulse >= T(0) && linear_ok(w, p.normal_impulse, a, b) &&
             linear_ok(w, p.max_normal_impulse, a, b) && linear_ok(w, p.step_impulse, a, b);
    }
    ok = ok && linear_ok(w, magnitude(m.friction_impulse), a, b) && angular_ok(w, m.twist_impulse, a, b);
    // The pose the manifold was made at (World::reuse_contact): a wrong one only decides whether
    // the next step re-measures the points or collides the shapes again.
    ok = ok && is_finite(c.made_offset) && detail::unit_quat(c.made_turn) && is_finite(c.made_normal) &&
         (m.count == 0 || detail::unit_vector(c.made_normal));
    if (!ok) detail::report_corrupt("a contact's normal, points, impulses or material are out of range; contact", k);
    // The twist lever kept under its key (World::twist_lever) must be the one the points give:
    // the next step uses it without integrating the patch again.
    std::array<Vec3<T>, 4> anchors{};
    for (std::size_t i = 0; i < static_cast<std::size_t>(m.count); ++i) anchors[i] = m.points[i].local_a;
    if (!(std::isfinite(c.twist_lever) && c.twist_lever >= T(0)) ||
        (c.twist_lever_key == detail::patch_key(anchors, m.count) &&
         !(c.twist_lever == detail::patch_twist_lever(anchors, m.count))))
        detail::report_corrupt("a contact's twist lever is not the one its points give; contact", k);
}

/// Joints: types, bools, living distinct bodies, finite frames (check_joint); free joints are
/// exactly the dead joints.
template <class T>
void SnapshotAccess<T>::check_joints(const World<T>& w) {
    const std::size_t nj = w.joints_.size();
    if (nj >= JointId::invalid_index) detail::report_corrupt("too many joint slots", nj);
    for (std::size_t k = 0; k < nj; ++k) check_joint(w, k);
    std::vector<std::uint8_t> free_joint(nj, 0);
    for (const std::uint32_t f : w.free_joints_) {
        if (f >= nj || w.joints_[f].alive || free_joint[f]++)
            detail::report_corrupt("a free joint slot is out of range, alive or listed twice; slot", f);
    }
    for (std::size_t k = 0; k < nj; ++k)
        if (!w.joints_[k].alive && !free_joint[k]) detail::report_corrupt("a dead joint slot is not listed as free; slot", k);
}

template <class T>
void SnapshotAccess<T>::check_joint(const World<T>& w, std::size_t k) {
    Joint<T> j = w.joints_[k];
    if (!detail::raw_bool_ok(j.alive) || !detail::raw_bool_ok(j.enable_limit) || !detail::raw_bool_ok(j.enable_motor) ||
        !detail::raw_bool_ok(j.collide_connected))
        detail::report_corrupt("a joint's bool byte is neither 0 nor 1; joint", k);
    if (detail::raw_enum(j.type) > detail::raw_enum(JointType::swing_twist))
        detail::report_corrupt("a joint's type is not a JointType; joint", k);
    if (!j.alive) return;
    if (!living(w, j.a) || !living(w, j.b) || j.a.index == j.b.index)
        detail::report_corrupt("a joint does not join two living bodies; joint", k);
    if (w.bodies_[j.a.index].type_ == BodyType::static_body && w.bodies_[j.b.index].type_ == BodyType::static_body)
        detail::report_corrupt("a joint joins two static bodies; joint", k);
    const std::uint32_t a = j.a.index, b = j.b.index;
    detail::halve_impulses(j, pending_halvings(w, a, b));  // as the next step takes them (check_contact)
    bool ok = is_finite(j.local_anchor_a) && is_finite(j.local_anchor_b) && is_finite(j.local_axis_a) &&
              is_finite(j.local_axis_b) && is_finite(j.local_ref_a) && is_finite(j.local_ref_b) &&
              detail::unit_quat(j.relative_rotation) && std::isfinite(j.length) && std::isfinite(j.lower_angle) &&
              std::isfinite(j.upper_angle) && j.lower_angle <= j.upper_angle && std::isfinite(j.motor_speed) &&
              std::isfinite(j.max_motor_torque) && j.max_motor_torque >= T(0) && is_finite(j.linear_impulse) &&
              is_finite(j.angular_impulse) && std::isfinite(j.axial_impulse) && std::isfinite(j.motor_impulse) &&
              linear_ok(w, magnitude(j.linear_impulse), a, b) && angular_ok(w, magnitude(j.angular_impulse), a, b);
    // The axial row (limit or length) and the motor push along the axis (slider, distance) or
    // turn about it (hinge, swing-twist), each within what the solver caps it to (joint.hpp).
    ok = ok && (detail::linear_axis(j.type) ? linear_ok(w, j.axial_impulse, a, b) && linear_ok(w, j.motor_impulse, a, b)
                                            : angular_ok(w, j.axial_impulse, a, b) && angular_ok(w, j.motor_impulse, a, b));
    // The ranges World::create_joint accepts: anchors within max_joint_lever of their bodies, a
    // length within max_size, a motor speed within max_setting_length.
    ok = ok && length(j.local_anchor_a) <= detail::max_joint_lever<T>() &&
         length(j.local_anchor_b) <= detail::max_joint_lever<T>() && j.length >= T(0) && j.length <= ScalarTraits<T>::max_size &&
         std::abs(j.motor_speed) <= detail::max_setting_length<T>();
    ok = ok && j.cone_angle >= T(0) && j.cone_angle <= ScalarTraits<T>::pi && std::isfinite(j.swing_impulse) &&
         j.swing_impulse >= T(0) && angular_ok(w, j.swing_impulse, a, b);
    if (!detail::linear_axis(j.type)) ok = ok && detail::angle_limits_ok(j.lower_angle, j.upper_angle);  // as check_limits
    if (ok && (j.type == JointType::hinge || j.type == JointType::prismatic || j.type == JointType::swing_twist))
        ok = detail::unit_vector(j.local_axis_a) && detail::unit_vector(j.local_axis_b) && detail::unit_vector(j.local_ref_a) &&
             detail::unit_vector(j.local_ref_b);
    if (!ok) detail::report_corrupt("a joint's frames, limits or impulses are out of range; joint", k);
}

/// Pending events (contacts that ended since the last step): handles may be stale by design.
template <class T>
void SnapshotAccess<T>::check_pending_events(const World<T>& w) {
    for (std::size_t k = 0; k < w.events_pending_.size(); ++k) {
        const ContactEvent<T>& e = w.events_pending_[k];
        const auto kind = detail::raw_enum(e.kind);
        if (!detail::raw_bool_ok(e.sensor) || kind < detail::raw_enum(ContactEventKind::began) ||
            kind > detail::raw_enum(ContactEventKind::ended))
            detail::report_corrupt("a pending event's kind or bool byte is out of range; event", k);
        bool ok = e.count >= 0 && e.count <= 4 && is_finite(e.normal) && std::isfinite(e.impulse);
        for (const Vec3<T>& p : e.points) ok = ok && is_finite(p);
        if (!ok) detail::report_corrupt("a pending event's normal, points or impulse are out of range; event", k);
        // A part index names a part of its body while the body lives (a listener may index a
        // compound's children with it); a destroyed body's is not looked at.
        const auto part_ok = [&](BodyId id, std::uint32_t child) {
            return !living(w, id) || child < w.bodies_[id.index].child_count();
        };
        if (!part_ok(e.a, e.child_a) || !part_ok(e.b, e.child_b))
            detail::report_corrupt("a pending event's part index is out of range for its body; event", k);
    }
}

template <class T>
std::vector<std::uint8_t> save_snapshot(const World<T>& world) {
    return SnapshotAccess<T>::save(world);
}

template <class T>
void restore_snapshot(World<T>& world, const std::vector<std::uint8_t>& bytes) {
    SnapshotAccess<T>::restore(world, bytes);
}

#ifdef XENO_COMPILED_LIB
// Compiled mode (compiled.hpp): float and double are compiled once, in src/xeno_compiled.cpp.
extern template std::vector<std::uint8_t> save_snapshot<float>(const World<float>&);
extern template std::vector<std::uint8_t> save_snapshot<double>(const World<double>&);
extern template void restore_snapshot<float>(World<float>&, const std::vector<std::uint8_t>&);
extern template void restore_snapshot<double>(World<double>&, const std::vector<std::uint8_t>&);
#endif

}  // namespace xeno

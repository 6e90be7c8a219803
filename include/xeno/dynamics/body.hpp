// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Body<T>: a rigid body (the thesis's RigidBody, 3.2.2.5). Its position is its centre of mass and
// its orientation turns the shape's local frame about that point (docs/conventions.md, "Frames").
// Three kinds:
//   static     never moves (the ground); infinite mass. The thesis made a body static by not
//              computing its mass properties (Quadro 10); here it is said explicitly.
//   kinematic  moved by the user through its velocity; infinite mass, so it pushes dynamic bodies
//              and is never pushed back.
//   dynamic    moved by forces, gravity and contacts.
// Bodies live in a World and are reached through a BodyId (slot index + generation): a handle to
// a destroyed body is stale and every use of it is reported (InvalidArgument), never a dangling
// reference. Setters check their input at the door and wake the body.
#pragma once

#include "../shape/compound.hpp"
#include "../shape/mesh_shape.hpp"
#include "../shape/shape.hpp"
#include "material.hpp"
#include "settings.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>

namespace xeno {

template <class T>
class World;
template <class T>
struct SnapshotAccess;

enum class BodyType : std::uint8_t { static_body, kinematic, dynamic };

namespace detail {
/// An inertia's inverse: try_inverse, or for one stiff about one axis (diag(167, 1e25, 167) in
/// float, whose determinant scaled by the largest entry underflows) its rows scaled first. Only
/// where try_inverse fails, so every other body keeps its bits.
template <class T>
std::optional<Mat3<T>> try_inverse_inertia(const Mat3<T>& inertia) {
    if (std::optional<Mat3<T>> inv = try_inverse(inertia)) return inv;
    return try_inverse_by_rows(inertia);
}
}  // namespace detail

/// What World::set_shape does with a dynamic body's mass: density × the new shape's, or the mass
/// as it was with the new shape's inertia scaled to it (the density stays, for a later recompute).
enum class MassUpdate : std::uint8_t { recompute, keep };

/// A handle to a body: slot index and generation. Default-constructed handles are invalid.
struct BodyId {
    static constexpr std::uint32_t invalid_index = ~std::uint32_t(0);
    std::uint32_t index = invalid_index;
    std::uint32_t generation = 0;
    bool valid() const { return index != invalid_index; }
    friend bool operator==(BodyId a, BodyId b) { return a.index == b.index && a.generation == b.generation; }
    friend bool operator!=(BodyId a, BodyId b) { return !(a == b); }
};

/// Everything needed to create a body. Units SI; position is the centre of mass.
template <class T>
struct BodyDef {
    BodyType type = BodyType::dynamic;
    Vec3<T> position{};                         ///< m, world: the centre of mass
    Quat<T> orientation = Quat<T>::identity();  ///< normalised on creation; must not be zero
    Vec3<T> linear_velocity{};                  ///< m/s, world
    Vec3<T> angular_velocity{};                 ///< rad/s, world
    T density = T(1000);                        ///< kg/m³: mass = density × volume (dynamic, or on becoming dynamic)
    T mass = T(0);                              ///< kg: > 0 sets the mass directly, inertia scaled to it
    Material<T> material{};
    T linear_damping = T(0);   ///< 1/s: v decays as 1/(1 + c h) per substep h (e^(-c t) to first order)
    T angular_damping = T(0);  ///< 1/s
    T gravity_scale = T(1);
    bool fast = false;  ///< continuous collision against static and kinematic bodies; speed cap 1e6 m/s (float), 1e10 (double)
    bool allow_sleep = true;                 ///< false keeps the body (and its island) awake
    bool sensor = false;                     ///< reports overlaps, never pushes or is pushed
    std::uint32_t layer = 1;                 ///< collision layer bits of this body
    std::uint32_t mask = ~std::uint32_t(0);  ///< layers it collides with (both sides must agree)
    std::uint64_t user_data = 0;
};

/// A rigid body in a World. Read it through World::body(id); change its motion and material through
/// its setters, and what the world keeps about it (pose, shape, type, filter, flags) through
/// World's calls by ID (world_edit.hpp).
template <class T>
class Body {
public:
    using scalar_type = T;

    BodyType type() const { return type_; }
    bool is_static() const { return type_ == BodyType::static_body; }
    bool is_dynamic() const { return type_ == BodyType::dynamic; }
    /// The body's convex shape; for a compound body, its first child's shape (see child_shape).
    /// A mesh or heightfield body has none (InvalidArgument; see mesh()).
    const Shape<T>& shape() const {
        if (mesh())
            detail::report_invalid("Body::shape", "a mesh or heightfield body has no convex shape (see Body::mesh); triangles",
                                   static_cast<double>(triangle_count(*mesh())));
        return compound() ? compound()->children().front().shape : *convex_shape();
    }
    /// The body's convex shape as shared with other bodies, or null for compound and mesh bodies.
    std::shared_ptr<const Shape<T>> shared_shape() const {
        return convex_shape() ? std::shared_ptr<const Shape<T>>(geometry_, convex_shape()) : nullptr;
    }
    /// The compound, or nullptr for a body of one convex shape.
    const Compound<T>* compound() const { return geometry_as<Compound<T>>(Geometry::compound); }
    /// The triangle mesh or heightfield of a level-geometry body, or nullptr.
    const MeshShape<T>* mesh() const { return geometry_as<MeshShape<T>>(Geometry::mesh); }
    /// Convex parts: 1 for a simple body, the children of a compound, 0 for a mesh.
    std::uint32_t child_count() const { return compound() ? static_cast<std::uint32_t>(compound()->size()) : mesh() ? 0u : 1u; }
    const Shape<T>& child_shape(std::uint32_t i) const { return compound() ? compound()->children()[i].shape : *convex_shape(); }
    /// World placement of part i.
    Transform<T> child_transform(std::uint32_t i) const {
        return compound() ? transform() * compound()->children()[i].local : transform();
    }
    /// m: the radius about the centre of mass of a ball holding every part (convex and compound
    /// bodies); for a mesh or heightfield body, about its origin, of the ball holding its local
    /// bounding box.
    T bounding_radius() const {
        if (const MeshShape<T>* m = mesh()) {
            const Aabb<T> box = local_bounds(*m);
            const auto reach = [](T low, T high) { return std::max(std::abs(low), std::abs(high)); };
            return length(Vec3<T>{reach(box.min.x, box.max.x), reach(box.min.y, box.max.y), reach(box.min.z, box.max.z)});
        }
        return compound() ? compound()->bounding_radius() : xeno::bounding_radius(*convex_shape());
    }
    /// World bounding box of the whole body (every part).
    Aabb<T> world_bounds() const {
        if (mesh()) return xeno::world_bounds(*mesh(), transform());
        if (!compound()) return xeno::world_bounds(*convex_shape(), transform());
        Aabb<T> box;
        for (std::uint32_t i = 0; i < child_count(); ++i) box.merge(xeno::world_bounds(child_shape(i), child_transform(i)));
        return box;
    }

    const Vec3<T>& position() const { return position_; }  ///< m, the centre of mass
    const Quat<T>& orientation() const { return orientation_; }
    Transform<T> transform() const { return {position_, orientation_}; }
    const Vec3<T>& linear_velocity() const { return linear_velocity_; }    ///< m/s
    const Vec3<T>& angular_velocity() const { return angular_velocity_; }  ///< rad/s, world
    const Vec3<T>& force() const { return force_; }                        ///< N, accumulated for the next step
    const Vec3<T>& torque() const { return torque_; }                      ///< N·m, accumulated for the next step

    T mass() const { return inverse_mass_ > T(0) ? T(1) / inverse_mass_ : ScalarTraits<T>::infinity; }  ///< kg
    T inverse_mass() const { return inverse_mass_; }
    /// Inertia about the centre of mass in the body frame (kg·m²); zero for static/kinematic.
    const Mat3<T>& local_inertia() const { return inertia_local_; }
    /// I⁻¹ in world axes: R I_local⁻¹ Rᵀ.
    Mat3<T> inverse_inertia_world() const {
        if (inverse_mass_ == T(0)) return Mat3<T>::zero();
        const Mat3<T> r = to_matrix(orientation_);
        return r * inverse_inertia_local() * transpose(r);
    }
    /// I⁻¹ in the body frame (zero for static/kinematic), computed from the inertia: one 3×3
    /// inverse per call, cheaper than storing it in every body (docs/benchmarks.md, memory).
    Mat3<T> inverse_inertia_local() const {
        if (inverse_mass_ == T(0)) return Mat3<T>::zero();
        return detail::try_inverse_inertia(inertia_local_).value_or(Mat3<T>::zero());
    }
    const Material<T>& material() const { return material_; }
    T linear_damping() const { return linear_damping_; }
    T angular_damping() const { return angular_damping_; }
    T gravity_scale() const { return gravity_scale_; }
    bool fast() const { return fast_; }
    bool sensor() const { return sensor_; }
    bool awake() const { return awake_; }
    bool allow_sleep() const { return allow_sleep_; }
    /// False while World::set_enabled has taken the body out of the simulation.
    bool enabled() const { return enabled_; }
    /// kg/m³: the mass World::set_type and World::set_shape give it when they compute one
    /// (BodyDef::density, or the mass it was created with over its volume).
    T density() const { return density_; }
    std::uint32_t layer() const { return layer_; }
    std::uint32_t mask() const { return mask_; }
    std::uint64_t user_data() const { return user_data_; }

    /// Body frame → world.
    Vec3<T> world_point(const Vec3<T>& local) const { return rotate(orientation_, local) + position_; }
    Vec3<T> world_vector(const Vec3<T>& local) const { return rotate(orientation_, local); }
    /// World → body frame.
    Vec3<T> local_point(const Vec3<T>& world) const { return inverse_rotate(orientation_, world - position_); }
    Vec3<T> local_vector(const Vec3<T>& world) const { return inverse_rotate(orientation_, world); }
    /// Velocity (m/s) of the material point at a world position: v + ω × (p − x).
    Vec3<T> velocity_at(const Vec3<T>& world) const { return linear_velocity_ + cross(angular_velocity_, world - position_); }
    /// Kinetic energy (J): ½ m v² + ½ ωᵀ I ω.
    T kinetic_energy() const;

    // Setters: each checks its input (InvalidArgument) and wakes the body.
    void set_linear_velocity(const Vec3<T>& v);
    void set_angular_velocity(const Vec3<T>& w);
    /// Adds a force (N) at the centre of mass for the next step.
    void apply_force(const Vec3<T>& f);
    /// Adds a force (N) at a world point: also a torque (p − x) × f.
    void apply_force_at(const Vec3<T>& f, const Vec3<T>& world_point);
    void apply_torque(const Vec3<T>& t);
    /// An instantaneous impulse (N·s) at a world point: Δv = J/m, Δω = I⁻¹ (p − x) × J.
    void apply_impulse_at(const Vec3<T>& impulse, const Vec3<T>& world_point);
    void apply_linear_impulse(const Vec3<T>& impulse);
    void apply_angular_impulse(const Vec3<T>& impulse);
    /// Wakes the body, and at the next step what touches it: less friction may set a sleeper on
    /// a slope sliding, on this body or under it (a static ramp's sleepers wake too).
    void set_material(const Material<T>& m) {
        detail::validate(m, "Body::set_material");
        material_ = m;
        wake();
        moved_ = true;  // World::keep_poses_and_update_bounds: a static or kinematic body's sleepers wake
    }
    void set_damping(T linear, T angular);
    void set_gravity_scale(T scale);
    void set_user_data(std::uint64_t data) { user_data_ = data; }
    void set_allow_sleep(bool allow) {
        allow_sleep_ = allow;
        wake();
    }
    /// Mass properties set directly (dynamic bodies): mass > 0 and a positive-definite inertia
    /// about the centre of mass; `center` must be zero (the body's position is its centre).
    void set_mass_properties(const MassProperties<T>& m);
    /// Wakes the body (and, at the next step, its island).
    void wake() {
        awake_ = true;
        sleep_time_ = T(0);
    }

private:
    friend class World<T>;
    friend struct SnapshotAccess<T>;
    /// Adds to the accumulated force and torque, or rejects (leaving both unchanged) when a sum
    /// or the acceleration it gives would leave the range of T.
    void accumulate(const Vec3<T>& force, const Vec3<T>& torque, const char* where);

    enum class Geometry : std::uint8_t { convex, compound, mesh };
    /// The convex shape, or nullptr for compound and mesh bodies.
    const Shape<T>* convex_shape() const { return geometry_as<Shape<T>>(Geometry::convex); }
    template <class G>
    const G* geometry_as(Geometry kind) const {
        return geometry_kind_ == kind ? static_cast<const G*>(geometry_.get()) : nullptr;
    }
    /// Makes the body own one of a convex shape, a compound or a mesh (the one not null), or
    /// nothing (a destroyed body).
    void set_geometry(std::shared_ptr<const Shape<T>> shape, std::shared_ptr<const Compound<T>> compound,
                      std::shared_ptr<const MeshShape<T>> mesh) {
        geometry_kind_ = compound ? Geometry::compound : mesh ? Geometry::mesh : Geometry::convex;
        geometry_ = compound ? std::shared_ptr<const void>(std::move(compound))
                    : mesh   ? std::shared_ptr<const void>(std::move(mesh))
                             : std::shared_ptr<const void>(std::move(shape));
    }

    // One owner of whichever geometry the body has (its kind in geometry_kind_): 16 bytes where
    // a shared_ptr for each kind took 48 (docs/benchmarks.md, memory).
    std::shared_ptr<const void> geometry_;
    Vec3<T> position_{};
    Quat<T> orientation_ = Quat<T>::identity();
    Vec3<T> linear_velocity_{};
    Vec3<T> angular_velocity_{};
    Vec3<T> force_{};
    Vec3<T> torque_{};
    Mat3<T> inertia_local_{};  ///< kg·m², body frame; zero for static/kinematic
    T inverse_mass_{};         ///< 1/kg; zero for static/kinematic
    Material<T> material_{};
    T linear_damping_{}, angular_damping_{}, gravity_scale_{1};
    T sleep_time_{};  ///< s spent below the sleep speeds, or near the rest pose
    // The pose when the sleep clock last started (World::update_sleep): a body that swings or
    // rocks in place above the sleep speeds but stays near it still counts as resting.
    Vec3<T> rest_position_{};
    Quat<T> rest_orientation_ = Quat<T>::identity();
    T distance_from_rest() const;
    T density_{};  ///< kg/m³, for mass recomputed after a change of shape or type
    std::uint64_t user_data_{};
    std::uint32_t generation_ = 0;  ///< matches BodyId::generation while the body lives
    std::uint32_t layer_ = 1, mask_ = ~std::uint32_t(0);
    BodyType type_ = BodyType::dynamic;
    bool alive_ = false;  ///< slot in use
    bool awake_ = true;
    bool allow_sleep_ = true;
    bool fast_ = false;
    bool sensor_ = false;
    bool enabled_ = true;    ///< in the simulation (World::set_enabled)
    bool isotropic_ = true;  ///< inertia ∝ identity: no gyroscopic term
    bool moved_ = false;     ///< teleported since the last step (broad phase must see it)
    // How many times the next step halves the impulses cached in the body's contacts and joints
    // (255: drops them): the powers of two its response to an impulse grew by since they were
    // made (set_mass_properties; World::scale_lighter_impulses).
    std::uint8_t impulse_halvings_ = 0;
    Geometry geometry_kind_ = Geometry::convex;
};

// How far any point of the body is from where it was when its sleep clock started: the centre's
// move plus the chord its turn sweeps at the bounding radius, 2 r sin(θ/2), which is 2 r times
// the length of the vector part of the relative rotation. World::update_sleep compares it with
// the distance the sleep speed covers in the sleep time, so that a body that rocks or swings in
// place (small amplitude, speeds above the thresholds) sleeps, as Jolt's three-point test does.
template <class T>
T Body<T>::distance_from_rest() const {
    const Quat<T> turn = conjugate(rest_orientation_) * orientation_;
    const T chord = T(2) * std::sqrt(turn.x * turn.x + turn.y * turn.y + turn.z * turn.z);
    return length(position_ - rest_position_) + chord * bounding_radius();
}

template <class T>
void Body<T>::accumulate(const Vec3<T>& force, const Vec3<T>& torque, const char* where) {
    const Vec3<T> f = force_ + force;
    const Vec3<T> t = torque_ + torque;
    detail::require_finite_xyz(f, where, "accumulated force");
    detail::require_finite_xyz(t, where, "accumulated torque");
    // Each acceleration is checked when its sum changes: a sum accepted earlier can overflow its
    // acceleration later (the body turned its small inertia towards the torque, or its mass
    // changed), and a force must not be refused for the torque's sake (the world fuzzer's find).
    // The step copes with such an acceleration (World::integration_constants).
    if (force != Vec3<T>::zero()) detail::require_finite_xyz(f * inverse_mass_, where, "accumulated force / mass");
    if (torque != Vec3<T>::zero())
        detail::require_finite_xyz(inverse_inertia_world() * t, where, "inverse inertia * accumulated torque");
    force_ = f;
    torque_ = t;
}

template <class T>
T Body<T>::kinetic_energy() const {
    if (inverse_mass_ == T(0)) return T(0);
    const Vec3<T> w_local = inverse_rotate(orientation_, angular_velocity_);
    return T(0.5) * (length_squared(linear_velocity_) / inverse_mass_ + dot(w_local, inertia_local_ * w_local));
}

template <class T>
void Body<T>::set_linear_velocity(const Vec3<T>& v) {
    detail::require_finite_xyz(v, "Body::set_linear_velocity", "velocity");
    if (type_ == BodyType::static_body) return;
    linear_velocity_ = v;
    wake();
}

template <class T>
void Body<T>::set_angular_velocity(const Vec3<T>& w) {
    detail::require_finite_xyz(w, "Body::set_angular_velocity", "angular_velocity");
    if (type_ == BodyType::static_body) return;
    angular_velocity_ = w;
    wake();
}

template <class T>
void Body<T>::apply_force(const Vec3<T>& f) {
    detail::require_finite_xyz(f, "Body::apply_force", "force");
    if (type_ != BodyType::dynamic) return;
    accumulate(f, Vec3<T>::zero(), "Body::apply_force");
    wake();
}

template <class T>
void Body<T>::apply_force_at(const Vec3<T>& f, const Vec3<T>& world_point) {
    detail::require_finite_xyz(f, "Body::apply_force_at", "force");
    detail::require_finite_xyz(world_point, "Body::apply_force_at", "point");
    if (type_ != BodyType::dynamic) return;
    const Vec3<T> torque = cross(world_point - position_, f);
    detail::require_finite_xyz(torque, "Body::apply_force_at", "torque (point - position) x force");
    accumulate(f, torque, "Body::apply_force_at");
    wake();
}

template <class T>
void Body<T>::apply_torque(const Vec3<T>& t) {
    detail::require_finite_xyz(t, "Body::apply_torque", "torque");
    if (type_ != BodyType::dynamic) return;
    accumulate(Vec3<T>::zero(), t, "Body::apply_torque");
    wake();
}

template <class T>
void Body<T>::apply_impulse_at(const Vec3<T>& impulse, const Vec3<T>& world_point) {
    detail::require_finite_xyz(impulse, "Body::apply_impulse_at", "impulse");
    detail::require_finite_xyz(world_point, "Body::apply_impulse_at", "point");
    if (type_ != BodyType::dynamic) return;
    const Vec3<T> v = linear_velocity_ + impulse * inverse_mass_;
    const Vec3<T> w = angular_velocity_ + inverse_inertia_world() * cross(world_point - position_, impulse);
    detail::require_finite_xyz(v, "Body::apply_impulse_at", "resulting linear_velocity");
    detail::require_finite_xyz(w, "Body::apply_impulse_at", "resulting angular_velocity");
    linear_velocity_ = v;
    angular_velocity_ = w;
    wake();
}

template <class T>
void Body<T>::apply_linear_impulse(const Vec3<T>& impulse) {
    detail::require_finite_xyz(impulse, "Body::apply_linear_impulse", "impulse");
    if (type_ != BodyType::dynamic) return;
    const Vec3<T> v = linear_velocity_ + impulse * inverse_mass_;
    detail::require_finite_xyz(v, "Body::apply_linear_impulse", "resulting linear_velocity");
    linear_velocity_ = v;
    wake();
}

template <class T>
void Body<T>::apply_angular_impulse(const Vec3<T>& impulse) {
    detail::require_finite_xyz(impulse, "Body::apply_angular_impulse", "impulse");
    if (type_ != BodyType::dynamic) return;
    const Vec3<T> w = angular_velocity_ + inverse_inertia_world() * impulse;
    detail::require_finite_xyz(w, "Body::apply_angular_impulse", "resulting angular_velocity");
    angular_velocity_ = w;
    wake();
}

template <class T>
void Body<T>::set_damping(T linear, T angular) {
    detail::require_non_negative(linear, "Body::set_damping", "linear");
    detail::require_non_negative(angular, "Body::set_damping", "angular");
    linear_damping_ = linear;
    angular_damping_ = angular;
}

template <class T>
void Body<T>::set_gravity_scale(T scale) {
    detail::require_at_most(scale, ScalarTraits<T>::max_size, "Body::set_gravity_scale", "scale");
    gravity_scale_ = scale;
    wake();
}

namespace detail {
/// Bounds of what one unit of impulse does to body b: the spin (rad/s per N·m·s), |I⁻¹| taken as
/// the sum of its rows' largest components (never below its norm), and the speed at any point of
/// the body (m/s per N·s), 1/m + |I⁻¹| r² with r the bounding radius (or a farther lever).
/// restore_snapshot asks that the warm-start impulses give a finite velocity change by them; the
/// joint solver caps its impulses by the same measures (JointConstraint::max_linear_impulse).
template <class T>
T spin_per_impulse(const Mat3<T>& inverse_inertia) {
    const Mat3<T>& i = inverse_inertia;
    return max_component(abs(i[0])) + max_component(abs(i[1])) + max_component(abs(i[2]));
}
template <class T>
T spin_per_impulse(const Body<T>& b) {
    return spin_per_impulse(b.inverse_inertia_local());
}

/// `spin` is spin_per_impulse(b), taken by the caller, which needs it too (one inverse each).
template <class T>
T speed_per_impulse(const Body<T>& b, T spin, T lever = T(0)) {  ///< at `lever` (m) from the centre if farther
    const T r = std::max(b.bounding_radius(), lever);
    return b.inverse_mass() + spin * r * r;
}

/// Checks the mass properties of a dynamic body whose shape reaches `radius` from its centre:
/// mass finite and > 0 with a finite inverse (a subnormal mass has none: its body would hang
/// still, ignoring gravity, and no snapshot of its world would restore), centre at the origin,
/// inertia finite, symmetric (to round-off) and positive definite with a finite inverse. Reports
/// (InvalidArgument) naming `where`; changes nothing, so callers check before they take any
/// state (World::create_body does).
template <class T>
void check_mass_properties(const MassProperties<T>& m, T radius, const char* where) {
    require_positive(m.mass, where, "mass");
    if (m.mass > max_mass<T>())
        report_invalid(where, "mass must be at most detail::max_mass (8.5e31 kg in float, 4.5e277 in double); mass",
                       static_cast<double>(m.mass));
    if (!std::isfinite(T(1) / m.mass))
        report_invalid(where, "mass must be large enough for 1 / mass to be finite in this precision; mass",
                       static_cast<double>(m.mass));
    if (!is_finite(m.center) || length(m.center) > T(1e-6) * (T(1) + radius))
        report_invalid(where, "center must be 0 (the body's position is its centre of mass); |center|",
                       static_cast<double>(length(m.center)));
    // Symmetric (up to round-off, as R I Rᵀ leaves it) and positive definite by Sylvester's
    // criterion: the leading principal minors are positive. The minors are taken of the inertia
    // scaled by its diagonal on both sides, n_ij = I_ij / √(I_ii I_jj) (a unit diagonal), so
    // neither tiny bodies (a 0.1 mm float sphere, I ~ 1e-17, det ~ 1e-51) nor a body stiff about
    // one axis (diag(167, 1e25, 167) in float, whose minors divided by the largest entry
    // underflowed) are rejected for a determinant that rounds to 0.
    const Mat3<T>& i = m.inertia;
    bool ok = is_finite(i) && i[0].x > T(0) && i[1].y > T(0) && i[2].z > T(0);
    if (ok) {
        const Vec3<T> root{std::sqrt(i[0].x), std::sqrt(i[1].y), std::sqrt(i[2].z)};
        const auto row = [&](int r) {
            const T scale = root[r];
            return Vec3<T>{i[r].x / scale / root.x, i[r].y / scale / root.y, i[r].z / scale / root.z};
        };
        const Mat3<T> n{row(0), row(1), row(2)};
        const T asymmetry = std::max(std::abs(n[0].y - n[1].x), std::max(std::abs(n[0].z - n[2].x), std::abs(n[1].z - n[2].y)));
        const T minor2 = n[0].x * n[1].y - n[0].y * n[1].x;
        const std::optional<Mat3<T>> inv = try_inverse_inertia(i);  // as inverse_inertia_local() takes it
        ok = asymmetry <= ScalarTraits<T>::relative_tolerance * T(3) && minor2 > T(0) && determinant(n) > T(0) && inv &&
             is_finite(*inv);
    }
    if (!ok)
        report_invalid(where, "inertia must be finite, symmetric and positive definite (with a finite inverse); Ixx",
                       static_cast<double>(i[0].x));
    // What a unit impulse does to the body, as spin_per_impulse and speed_per_impulse measure it
    // (and restore_snapshot checks every stored impulse by): a 1e-307 kg ball (double) has an
    // inertia with a finite inverse of 1e308 whose rows sum to inf, and no impulse on it restored.
    if (!std::isfinite(T(1) / m.mass + spin_per_impulse(*try_inverse_inertia(i)) * radius * radius))
        report_invalid(where, "mass and inertia must be large enough that a unit impulse gives a finite speed; mass",
                       static_cast<double>(m.mass));
}

/// Whether `body`'s part `child` is a sphere (a mesh body's "part" is a triangle: never).
template <class T>
bool is_sphere(const Body<T>& body, std::uint32_t child) {
    return !body.mesh() && std::holds_alternative<Sphere<T>>(body.child_shape(child));
}

/// Where `body`'s part `child` touches along its outward normal `outward` (world, unit), if it is
/// round there: a sphere anywhere, a capsule anywhere, a cylinder on its side (its normal within
/// about 6° of square to its axis). `point` (world) comes in as the stored
/// anchor, whose height along the part's axis is kept, and goes out on the surface. False, and
/// `point` untouched, for flat and pointed parts.
template <class T>
bool rolling_point(const Body<T>& body, std::uint32_t child, const Vec3<T>& outward, Vec3<T>& point) {
    if (body.mesh()) return false;
    const Shape<T>& shape = body.child_shape(child);
    const auto* sphere = std::get_if<Sphere<T>>(&shape);
    const auto* capsule = std::get_if<Capsule<T>>(&shape);
    const auto* cylinder = std::get_if<Cylinder<T>>(&shape);
    if (!sphere && !capsule && !cylinder) return false;  // before the pose: most parts are flat
    const Transform<T> pose = body.child_transform(child);
    if (sphere) {
        point = pose.position + outward * sphere->radius();
        return true;
    }
    const Vec3<T> m = pose.inverse_apply_direction(outward);
    const T along = pose.inverse_apply(point).y;
    if (capsule) {
        const T h = capsule->half_height();
        point = pose.apply(Vec3<T>{T(0), std::clamp(along, -h, h), T(0)} + m * capsule->radius());
        return true;
    }
    // A cylinder: its side only, as Cylinder::support_face's side line. On a rim the stored
    // anchors may be a cap's polygon, which would all be moved to one rim point (a pile in a
    // bowl then never settled).
    const Vec3<T> radial{m.x, T(0), m.z};
    const T across = length(radial);
    if (!(across > T(0.995))) return false;
    const T h = cylinder->half_height();
    point = pose.apply(radial * (cylinder->radius() / across) + Vec3<T>{T(0), std::clamp(along, -h, h), T(0)});
    return true;
}

/// How `body`'s part `child` is round where it touches along the contact normal `n`, read once
/// per manifold (World::contact_row).
template <class T>
struct Roundness {
    /// m: the radius of the rounded surface it rolls on (ContactConstraint::round_a and round_b;
    /// why: rolling_rise in wide_contact_solver.hpp). A sphere and a capsule are a point and a
    /// segment swept by a ball: their radius, whichever way they turn. A cylinder is round about
    /// its axis only: r |n⊥|, with n⊥ the part of n across the axis. On its side (n ⊥ axis) that
    /// is r, exact for rolling about the axis; on a cap (n ∥ axis) 0, where it spins or tips as a
    /// flat face; on a rim between them (a leaning wheel) it takes back part of the rise, and it
    /// changes continuously as the wheel leans. 0 for hulls, boxes, cones (a cone's roundness
    /// varies along its side) and meshes.
    T rolling{};
    /// m: the radius of the flat round face it rests on (a cylinder's cap, a cone's base: the
    /// axis along n), else 0. Such a face rests as a disc, whose twist lever is 2r/3
    /// (contact/patch.hpp; World::twist_lever).
    T face{};
};

template <class T>
Roundness<T> roundness(const Body<T>& body, std::uint32_t child, const Vec3<T>& n) {
    if (body.mesh()) return {};
    const Shape<T>& shape = body.child_shape(child);
    if (const auto* sphere = std::get_if<Sphere<T>>(&shape)) return {sphere->radius(), T(0)};
    if (const auto* capsule = std::get_if<Capsule<T>>(&shape)) return {capsule->radius(), T(0)};
    const auto* cylinder = std::get_if<Cylinder<T>>(&shape);
    const auto* cone = std::get_if<Cone<T>>(&shape);
    if (!cylinder && !cone) return {};
    const T along = dot(body.child_transform(child).apply_direction(Vec3<T>::unit_y()), n);
    const T across_sq = T(1) - along * along;
    const bool on_face = !(across_sq > T(1e-6));
    if (cone) return {T(0), on_face ? cone->radius() : T(0)};
    return on_face ? Roundness<T>{T(0), cylinder->radius()} : Roundness<T>{cylinder->radius() * std::sqrt(across_sq), T(0)};
}
}  // namespace detail

template <class T>
void Body<T>::set_mass_properties(const MassProperties<T>& m) {
    const char* where = "Body::set_mass_properties";
    if (type_ != BodyType::dynamic)
        detail::report_invalid(where, "only dynamic bodies have mass; body type", static_cast<double>(type_));
    detail::check_mass_properties(m, bounding_radius(), where);
    // The impulses cached for the next step's warm start were sized for the old mass: on a body
    // made 10⁸ times lighter they threw it off the ground it rested on. They shrink by the
    // powers of two the response to an impulse grows by (linear or spin, the larger).
    const T old_spin = detail::spin_per_impulse(inverse_inertia_local());
    const T new_inverse_mass = T(1) / m.mass;
    const T new_spin = detail::spin_per_impulse(*detail::try_inverse_inertia(m.inertia));
    const T growth = std::max(new_inverse_mass / inverse_mass_, new_spin / old_spin);  // inf from no mass
    const int halvings = growth >= T(2) ? (std::isfinite(growth) ? std::ilogb(growth) : 255) : 0;
    impulse_halvings_ = static_cast<std::uint8_t>(std::min(255, impulse_halvings_ + halvings));
    inverse_mass_ = new_inverse_mass;
    inertia_local_ = m.inertia;
    const T mean = trace(m.inertia) / T(3);
    isotropic_ = length(m.inertia[0] - Vec3<T>::unit_x() * mean) + length(m.inertia[1] - Vec3<T>::unit_y() * mean) +
                     length(m.inertia[2] - Vec3<T>::unit_z() * mean) <=
                 T(1e-6) * mean;
    wake();
}

namespace f32 {
using Body = xeno::Body<float>;
using BodyDef = xeno::BodyDef<float>;
}  // namespace f32
namespace f64 {
using Body = xeno::Body<double>;
using BodyDef = xeno::BodyDef<double>;
}  // namespace f64

}  // namespace xeno

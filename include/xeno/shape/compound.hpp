// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Compound<T>: several convex shapes, each placed by a local transform, forming one rigid body
// (an L-shape, a table, a chair). Not itself convex: the world collides it child by child, each
// child pair with its own manifold. Mass properties combine the children at a uniform density:
// each child's inertia is turned into the compound's axes (R I Rᵀ) and moved to the common
// centre of mass (parallel-axis theorem), then summed. Like the hull builder, the constructor
// re-centres the children on that centre of mass and reports the shift it applied, so the body's
// position is its centre of mass (docs/conventions.md, "Frames").
#pragma once

#include "shape.hpp"

#include <vector>

namespace xeno {

/// One convex part of a compound, placed in the compound's frame.
template <class T>
struct SnapshotAccess;

template <class T>
struct CompoundChild {
    Shape<T> shape;
    Transform<T> local{};  ///< the child's frame in the compound's frame
};

/// A rigid union of convex shapes (see the file comment).
template <class T>
class Compound {
public:
    using scalar_type = T;

    /// Children in any frame; they are re-centred on their common centre of mass (uniform
    /// density), and shift() is where that centre was in the given frame. At least one child,
    /// finite positions within ±ScalarTraits<T>::max_size and non-zero orientations
    /// (InvalidArgument otherwise).
    explicit Compound(std::vector<CompoundChild<T>> children);

    const std::vector<CompoundChild<T>>& children() const { return children_; }
    std::size_t size() const { return children_.size(); }
    /// Where the centre of mass was in the children's original frame.
    const Vec3<T>& shift() const { return shift_; }
    /// Mass properties at density 1, about the centre of mass (the local origin).
    MassProperties<T> unit_mass_properties() const { return unit_mass_; }
    Aabb<T> local_bounds() const { return bounds_; }
    /// Radius about the local origin of a sphere holding every child.
    T bounding_radius() const { return radius_; }

private:
    friend struct SnapshotAccess<T>;
    Compound() = default;

    std::vector<CompoundChild<T>> children_;
    Vec3<T> shift_{};
    MassProperties<T> unit_mass_{};
    Aabb<T> bounds_{};
    T radius_{};
};

template <class T>
Compound<T>::Compound(std::vector<CompoundChild<T>> children) : children_(std::move(children)) {
    const char* where = "Compound";
    if (children_.empty()) detail::report_invalid(where, "needs at least one child; child count", 0.0);
    T mass = T(0);
    Vec3<T> weighted{};
    for (std::size_t i = 0; i < children_.size(); ++i) {
        CompoundChild<T>& c = children_[i];
        const std::string child = "child " + std::to_string(i);
        detail::require_moved_in(c.shape, where);
        // Positions within the size range (1e6 m in float), so the centre of mass, the bounds and
        // the inertia about it stay finite (a float child at 1e38 gave an infinite shift).
        detail::require_within_xyz(c.local.position, ScalarTraits<T>::max_size, where, (child + " local.position").c_str(), " m");
        detail::require_orientation(c.local.orientation, where, (child + " local.orientation").c_str());
        c.local.orientation = normalized(c.local.orientation);
        const MassProperties<T> m = mass_properties(c.shape, T(1));
        mass += m.mass;
        weighted += c.local.apply(m.center) * m.mass;
    }
    shift_ = weighted / mass;
    Mat3<T> inertia = Mat3<T>::zero();
    for (CompoundChild<T>& c : children_) {
        c.local.position -= shift_;
        const MassProperties<T> m = mass_properties(c.shape, T(1));
        const Mat3<T> rotation = to_matrix(c.local.orientation);
        inertia = inertia + shifted_inertia(rotated_inertia(m.inertia, rotation), m.mass, c.local.apply(m.center));
        const Aabb<T> box = world_bounds(c.shape, c.local);
        bounds_.merge(box);
        radius_ = std::max(radius_, length(c.local.position) + xeno::bounding_radius(c.shape));
    }
    unit_mass_ = {mass, Vec3<T>::zero(), inertia};
    if (!(is_finite(shift_) && is_finite(inertia) && std::isfinite(radius_) && is_finite(bounds_.min) && is_finite(bounds_.max)))
        detail::report_invalid(where, "children too far apart or too large for this precision; bounding radius (m)",
                               static_cast<double>(radius_));
}

namespace f32 {
using Compound = xeno::Compound<float>;
using CompoundChild = xeno::CompoundChild<float>;
}  // namespace f32
namespace f64 {
using Compound = xeno::Compound<double>;
using CompoundChild = xeno::CompoundChild<double>;
}  // namespace f64

}  // namespace xeno

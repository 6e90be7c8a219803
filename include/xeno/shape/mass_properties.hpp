// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Mass, centre of mass and inertia tensor of every shape from a density (kg/m³).
// Implicit shapes in closed form; polyhedra by signed tetrahedra, one per triangle of a fan over
// each counter-clockwise face, apexed at a reference point inside (thesis 3.3.1.6 and Apêndice B,
// corrected: faces must wind counter-clockwise seen from outside for positive volumes, and the
// inertia is moved to the centre of mass, which the thesis's listing did not do). The tetrahedron
// integrals follow Blow & Binstock, "How to find the inertia tensor (or other mass properties) of a
// 3D solid body represented by a triangle mesh" (2004): covariance of the canonical tetrahedron
// mapped by each tetrahedron's edge matrix, summed, shifted, then I = tr(C)·1 − C.
#pragma once

#include "../error.hpp"
#include "../math/mat3.hpp"

#include <cstdint>
#include <vector>

namespace xeno {

/// Mass properties of a solid: mass (kg), centre of mass (local frame, m), inertia about the
/// centre of mass in the local axes (kg·m²).
template <class T>
struct MassProperties {
    T mass{};           ///< kg, > 0
    Vec3<T> center{};   ///< metres, shape-local frame
    Mat3<T> inertia{};  ///< kg·m², about center, local axes
};

namespace detail {

/// Volume, centroid and unit-density inertia about the centroid of a closed polyhedron whose
/// faces (index lists into vertices, first/count into indices) wind counter-clockwise from outside.
template <class T, class FaceRange>
MassProperties<T> polyhedron_unit_density(const std::vector<Vec3<T>>& vertices, const std::vector<std::uint32_t>& indices,
                                          const FaceRange& faces) {
    // Integrate about a reference point near the middle to keep round-off small far from 0.
    Vec3<T> ref = Vec3<T>::zero();
    for (const Vec3<T>& v : vertices) ref += v;
    ref /= static_cast<T>(vertices.size());

    T six_volume = T(0);
    Vec3<T> weighted_centroid = Vec3<T>::zero();  // Σ det · (a + b + c)
    Mat3<T> covariance = Mat3<T>::zero();         // Σ det · A C_can Aᵀ, C_can = (1 + δij)/120
    for (const auto& face : faces) {
        const Vec3<T> a = vertices[indices[face.first]] - ref;
        for (std::uint32_t k = 1; k + 1 < face.count; ++k) {
            const Vec3<T> b = vertices[indices[face.first + k]] - ref;
            const Vec3<T> c = vertices[indices[face.first + k + 1]] - ref;
            const T det = triple(a, b, c);
            six_volume += det;
            weighted_centroid += (a + b + c) * det;
            // A C_can Aᵀ with A = [a b c] equals (Σ_i p_i p_iᵀ + s sᵀ) / 120, s = a + b + c.
            const Vec3<T> s = a + b + c;
            covariance = covariance + (outer(a, a) + outer(b, b) + outer(c, c) + outer(s, s)) * (det / T(120));
        }
    }
    MassProperties<T> m;
    m.mass = six_volume / T(6);  // unit density: mass = volume
    const Vec3<T> centroid_from_ref = weighted_centroid / (T(4) * six_volume);
    m.center = centroid_from_ref + ref;
    // Parallel-axis shift of the covariance from ref to the centroid.
    const Mat3<T> c_com = covariance - outer(centroid_from_ref, centroid_from_ref) * m.mass;
    m.inertia = Mat3<T>::identity() * trace(c_com) - c_com;
    return m;
}

}  // namespace detail

/// The mass properties of shape at the given density (kg/m³): mass = density × volume.
/// Non-positive or non-finite density is rejected (InvalidArgument).
template <class Shape>
MassProperties<typename Shape::scalar_type> mass_properties(const Shape& shape, typename Shape::scalar_type density) {
    using T = typename Shape::scalar_type;
    detail::require_positive(density, "mass_properties", "density");
    MassProperties<T> m = shape.unit_mass_properties();
    m.mass *= density;
    m.inertia = m.inertia * density;
    // Density × volume (× length² for the inertia) can leave the range of T at finite inputs.
    if (!(std::isfinite(m.mass) && m.mass > T(0) && is_finite(m.inertia) && m.inertia[0].x > T(0) && m.inertia[1].y > T(0) &&
          m.inertia[2].z > T(0)))
        detail::report_invalid("mass_properties",
                               "mass (density x volume) and inertia must be finite and > 0 in this precision; density",
                               static_cast<double>(density));
    return m;
}

/// The same properties seen from a frame where the body is rotated by q about its centre and
/// shifted by offset: inertia R I Rᵀ, centre moved. Used to combine shapes of compound bodies.
template <class T>
Mat3<T> rotated_inertia(const Mat3<T>& inertia, const Mat3<T>& rotation) {
    return rotation * inertia * transpose(rotation);
}

/// Inertia about a point displaced by d from the centre of mass (parallel-axis theorem).
template <class T>
Mat3<T> shifted_inertia(const Mat3<T>& inertia_about_center, T mass, const Vec3<T>& d) {
    return inertia_about_center + (Mat3<T>::identity() * dot(d, d) - outer(d, d)) * mass;
}

namespace f32 {
using MassProperties = xeno::MassProperties<float>;
}
namespace f64 {
using MassProperties = xeno::MassProperties<double>;
}

}  // namespace xeno

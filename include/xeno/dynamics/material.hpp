// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Material<T>: the surface properties of a body. When two bodies touch, their values combine:
//   friction     geometric mean √(µA µB): a frictionless body makes every pair frictionless,
//                and equal materials keep their value (Box2D's and Bullet's rule);
//   restitution  the larger of the two: a bouncy ball bounces on a dead floor (Box2D's rule).
// The thesis used one fixed friction of 0.05 for everything (4.1 a); here each body has its own.
#pragma once

#include "../error.hpp"

#include <cmath>

namespace xeno {

/// Friction coefficient µ (Coulomb, dimensionless, >= 0) and restitution e (0 … 1).
template <class T>
struct Material {
    T friction = T(0.6);   ///< Coulomb µ: tangential impulse <= µ · normal impulse
    T restitution = T(0);  ///< 0 = no bounce, 1 = bounces back at the approach speed
};

/// The combined friction of a touching pair: √(µA µB), or √µA √µB where the product overflows
/// (two frictions of 1e20 in float): an infinite µ made a contact's friction bound inf · 0 = NaN,
/// which froze the body.
template <class T>
T combined_friction(const Material<T>& a, const Material<T>& b) {
    const T product = a.friction * b.friction;
    return std::isfinite(product) ? std::sqrt(product) : std::sqrt(a.friction) * std::sqrt(b.friction);
}

/// The combined restitution of a touching pair: max(eA, eB).
template <class T>
T combined_restitution(const Material<T>& a, const Material<T>& b) {
    return a.restitution > b.restitution ? a.restitution : b.restitution;
}

namespace detail {
template <class T>
void validate(const Material<T>& m, const char* where) {
    require_non_negative(m.friction, where, "material.friction");
    if (!(std::isfinite(m.restitution) && m.restitution >= T(0) && m.restitution <= T(1)))
        report_invalid(where, "material.restitution must be in [0, 1]", static_cast<double>(m.restitution));
}
}  // namespace detail

namespace f32 {
using Material = xeno::Material<float>;
}
namespace f64 {
using Material = xeno::Material<double>;
}

}  // namespace xeno

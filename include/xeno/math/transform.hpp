// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Transform<T>: a rigid placement, position + unit orientation. apply() takes a point from the
// local frame to the world (rotate, then translate); apply_direction() only rotates; the inverse
// transforms undo them. Composition a * b applies b first, as for quaternions.
#pragma once

#include "quat.hpp"

namespace xeno {

/// A rigid transform: world = orientation · local + position.
template <class T>
struct Transform {
    using scalar_type = T;

    Vec3<T> position{};                         ///< metres, world frame
    Quat<T> orientation = Quat<T>::identity();  ///< unit, local → world

    static constexpr Transform identity() { return {}; }

    /// Local point → world point.
    constexpr Vec3<T> apply(const Vec3<T>& p) const { return rotate(orientation, p) + position; }
    /// Local direction → world direction (no translation).
    constexpr Vec3<T> apply_direction(const Vec3<T>& d) const { return rotate(orientation, d); }
    /// World point → local point.
    constexpr Vec3<T> inverse_apply(const Vec3<T>& p) const { return inverse_rotate(orientation, p - position); }
    /// World direction → local direction.
    constexpr Vec3<T> inverse_apply_direction(const Vec3<T>& d) const { return inverse_rotate(orientation, d); }

    template <class U>
    constexpr Transform<U> cast() const {
        return {position.template cast<U>(), orientation.template cast<U>()};
    }
};

/// The transform that undoes t.
template <class T>
constexpr Transform<T> inverse(const Transform<T>& t) {
    const Quat<T> inv = conjugate(t.orientation);
    return {rotate(inv, -t.position), inv};
}

/// a ∘ b: applies b, then a.
template <class T>
constexpr Transform<T> operator*(const Transform<T>& a, const Transform<T>& b) {
    return {a.apply(b.position), a.orientation * b.orientation};
}

/// True when the position is finite and the orientation finite and not zero.
template <class T>
bool is_finite(const Transform<T>& t) {
    return is_finite(t.position) && is_finite(t.orientation) && t.orientation != Quat<T>{T(0), T(0), T(0), T(0)};
}

namespace f32 {
using Transform = xeno::Transform<float>;
}
namespace f64 {
using Transform = xeno::Transform<double>;
}

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Mat4<T>: a 4×4 affine matrix (last row 0 0 0 1), as the thesis's Matrix4 (3.2.2.3). Points
// (w = 1) are rotated and translated, directions (w = 0) only rotated. Renderers can read it in
// column-major order for OpenGL with to_column_major().
#pragma once

#include "transform.hpp"

#include <optional>

namespace xeno {

/// An affine 4×4 matrix: [linear | translation; 0 0 0 1].
template <class T>
struct Mat4 {
    using scalar_type = T;

    Mat3<T> linear = Mat3<T>::identity();  ///< upper-left 3×3 block
    Vec3<T> translation{};                 ///< last column

    static constexpr Mat4 identity() { return {}; }
    /// The matrix that rotates by r, then translates by t.
    static constexpr Mat4 from_rotation_translation(const Mat3<T>& r, const Vec3<T>& t) { return {r, t}; }
    static constexpr Mat4 from_transform(const Transform<T>& t) { return {to_matrix(t.orientation), t.position}; }

    /// Element (row, column) of the full 4×4 matrix.
    constexpr T at(int r, int c) const {
        if (r == 3) return c == 3 ? T(1) : T(0);
        return c == 3 ? translation[r] : linear[r][c];
    }
    /// The 16 elements column after column (OpenGL's layout).
    void to_column_major(T out[16]) const {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) out[c * 4 + r] = at(r, c);
    }
};

/// Point transform: linear · p + translation.
template <class T>
constexpr Vec3<T> transform_point(const Mat4<T>& m, const Vec3<T>& p) {
    return m.linear * p + m.translation;
}
/// Direction transform: linear · d (translation ignored).
template <class T>
constexpr Vec3<T> transform_direction(const Mat4<T>& m, const Vec3<T>& d) {
    return m.linear * d;
}

/// Product a b (applies b first).
template <class T>
constexpr Mat4<T> operator*(const Mat4<T>& a, const Mat4<T>& b) {
    return {a.linear * b.linear, a.linear * b.translation + a.translation};
}

/// The inverse affine matrix, or nothing when the linear block is singular.
template <class T>
std::optional<Mat4<T>> try_inverse(const Mat4<T>& m) {
    const std::optional<Mat3<T>> inv = try_inverse(m.linear);
    if (!inv) return std::nullopt;
    return Mat4<T>{*inv, -(*inv * m.translation)};
}

namespace f32 {
using Mat4 = xeno::Mat4<float>;
}
namespace f64 {
using Mat4 = xeno::Mat4<double>;
}

}  // namespace xeno

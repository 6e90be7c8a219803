// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Optional printing of the math types, kept out of the other headers so that none of them pulls
// in <ostream>. Quaternions print as (w, x, y, z), the order of every xeno text format.
#pragma once

#include "aabb.hpp"
#include "mat4.hpp"

#include <ostream>

namespace xeno {

template <class T>
std::ostream& operator<<(std::ostream& os, const Vec3<T>& v) {
    return os << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}

template <class T>
std::ostream& operator<<(std::ostream& os, const Quat<T>& q) {
    return os << '(' << q.w << ", " << q.x << ", " << q.y << ", " << q.z << ')';
}

template <class T>
std::ostream& operator<<(std::ostream& os, const Mat3<T>& m) {
    return os << '[' << m[0] << ", " << m[1] << ", " << m[2] << ']';
}

template <class T>
std::ostream& operator<<(std::ostream& os, const Transform<T>& t) {
    return os << "{position " << t.position << ", orientation " << t.orientation << '}';
}

template <class T>
std::ostream& operator<<(std::ostream& os, const Aabb<T>& b) {
    return os << "{min " << b.min << ", max " << b.max << '}';
}

}  // namespace xeno

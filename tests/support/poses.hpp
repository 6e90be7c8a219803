// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The pose shorthand the narrow-phase tests share. One definition for every file: the test files
// are compiled in unity batches (tests/CMakeLists.txt), where each file's own copy would clash.
#pragma once

#include <xeno/math/transform.hpp>

namespace xeno::test {

/// A body at (x, y, z) with orientation q.
template <class T>
Transform<T> at(T x, T y, T z, const Quat<T>& q = Quat<T>::identity()) {
    return {Vec3<T>{x, y, z}, q};
}

}  // namespace xeno::test

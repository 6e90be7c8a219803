// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Every class template instantiated for both scalars (docs/style.md, "Every template compiled"):
// member functions no test calls still compile, with the warnings on, in float and in double.
// World and the narrow phase are not here: the tests link xeno::compiled, whose one source file
// (src/xeno_compiled.cpp) compiles them (include/xeno/compiled.hpp).
#include <xeno/xeno.hpp>

#define XENO_INSTANTIATE(T)                   \
    template struct xeno::Vec3<T>;            \
    template struct xeno::Quat<T>;            \
    template struct xeno::Mat3<T>;            \
    template struct xeno::Transform<T>;       \
    template struct xeno::Aabb<T>;            \
    template class xeno::Box<T>;              \
    template class xeno::Sphere<T>;           \
    template class xeno::Capsule<T>;          \
    template class xeno::Cylinder<T>;         \
    template class xeno::Cone<T>;             \
    template class xeno::ConvexPolyhedron<T>; \
    template class xeno::Compound<T>;         \
    template class xeno::SweepAndPrune<T>;    \
    template class xeno::AabbTree<T>;         \
    template class xeno::Body<T>;

XENO_INSTANTIATE(float)
XENO_INSTANTIATE(double)

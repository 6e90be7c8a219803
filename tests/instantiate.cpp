// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Every class template instantiated for both scalars (STYLE.md): member functions no test calls
// still compile, with the warnings on, in float and in double. Also where the World's members are
// compiled, once, for every test executable: the tests see World<float> and World<double> as
// extern templates (support/extern_templates.hpp, in their precompiled header), which cut an
// ASan + UBSan test translation unit from about 200 s to 15 s.
#include <xeno/xeno.hpp>

#define XENO_INSTANTIATE(T)                                                                                   \
    template struct xeno::Vec3<T>;                                                                             \
    template struct xeno::Quat<T>;                                                                             \
    template struct xeno::Mat3<T>;                                                                             \
    template struct xeno::Transform<T>;                                                                        \
    template struct xeno::Aabb<T>;                                                                             \
    template class xeno::Box<T>;                                                                               \
    template class xeno::Sphere<T>;                                                                            \
    template class xeno::Capsule<T>;                                                                           \
    template class xeno::Cylinder<T>;                                                                          \
    template class xeno::Cone<T>;                                                                              \
    template class xeno::ConvexPolyhedron<T>;                                                                  \
    template class xeno::Compound<T>;                                                                          \
    template class xeno::SweepAndPrune<T>;                                                                     \
    template class xeno::AabbTree<T>;                                                                          \
    template class xeno::Body<T>;                                                                              \
    template class xeno::World<T>;

XENO_INSTANTIATE(float)
XENO_INSTANTIATE(double)

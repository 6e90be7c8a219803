// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Every class template instantiated for both scalars (docs/style.md, "Every template compiled"):
// member functions no test calls still compile, with the warnings on, in float and in double. Also
// where the World's members are compiled, once, for every test executable: the tests see
// World<float> and World<double> as extern templates (support/extern_templates.hpp, in their
// precompiled header), which cut an ASan + UBSan test translation unit from about 200 s to 15 s.
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

// The narrow phase over the Shape variant: each of these visits the whole shape-pair matrix, the
// heaviest code in xeno to compile; the collide tests see them as extern templates too.
#define XENO_INSTANTIATE_NARROW_PHASE(T)                                                                                      \
    template bool xeno::intersect<T>(const xeno::Shape<T>&, const xeno::Transform<T>&, const xeno::Shape<T>&,                 \
                                     const xeno::Transform<T>&);                                                              \
    template xeno::Penetration<T> xeno::collide<T>(const xeno::Shape<T>&, const xeno::Transform<T>&, const xeno::Shape<T>&,   \
                                                   const xeno::Transform<T>&);                                                \
    template xeno::ContactManifold<T> xeno::generate_contacts<T>(const xeno::Shape<T>&, const xeno::Transform<T>&,            \
                                                                 const xeno::Shape<T>&, const xeno::Transform<T>&, T);        \
    template std::optional<xeno::RayHit<T>> xeno::raycast<T>(const xeno::Shape<T>&, const xeno::Transform<T>&, const xeno::Ray<T>&);

XENO_INSTANTIATE(float)
XENO_INSTANTIATE(double)
XENO_INSTANTIATE_NARROW_PHASE(float)
XENO_INSTANTIATE_NARROW_PHASE(double)

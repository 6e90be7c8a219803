// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// ShapeRef<T>: a Shape<T> (the variant) seen through the interface of one convex shape, so that
// the pairs the narrow phase answers with MPR compile once per scalar type instead of once per
// pair of shape kinds. Every call switches on the held kind (std::visit over one variant, which
// libstdc++ and libc++ compile to a switch) and then runs that shape's own code, so the answers
// are bit for bit those of the per-pair instantiations. Why: a translation unit that steps a
// World compiled MPR, the least-depth expansion, refinement and manifold building for all 36
// ordered pairs of the six kinds, whatever shapes the game used; that was most of its back-end
// time (docs/collision.md, "Shape-pair dispatch", has the compile and run times).
#pragma once

#include "../shape/shape.hpp"

#include <utility>

namespace xeno::detail {

/// A convex shape of any kind, by reference (the Shape<T> must outlive it).
template <class T>
class ShapeRef {
public:
    using scalar_type = T;

    explicit ShapeRef(const Shape<T>& shape) : shape_(shape) {}

    /// f(concrete shape), for the few callers that need the kind itself.
    template <class F>
    decltype(auto) visit(F&& f) const {
        return std::visit(std::forward<F>(f), shape_);
    }

    Vec3<T> support(const Vec3<T>& d) const {
        return visit([&](const auto& s) { return s.support(d); });
    }
    SupportFace<T> support_face(const Vec3<T>& d) const {
        return visit([&](const auto& s) { return s.support_face(d); });
    }
    Vec3<T> interior_point() const {
        return visit([](const auto& s) { return s.interior_point(); });
    }
    Vec3<T> inner_half_extents() const {
        return visit([](const auto& s) { return s.inner_half_extents(); });
    }
    T bounding_radius() const {
        return visit([](const auto& s) { return s.bounding_radius(); });
    }

private:
    const Shape<T>& shape_;
};

template <class S>
constexpr bool is_shape_ref = false;
template <class T>
constexpr bool is_shape_ref<ShapeRef<T>> = true;

}  // namespace xeno::detail

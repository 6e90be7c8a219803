// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Which bodies a world query sees (World::raycast, raycast_any, raycast_all, query_point,
// query_aabb, overlap_sphere, overlap_shape; dynamics/world_query.hpp): a layer mask read like
// the contact layers, the exclusions a game needs most often, and a callback for anything else.
// The default sees every body.
#pragma once

#include "body.hpp"

#include <cstdint>
#include <functional>

namespace xeno {

/// What a world query skips. A body counts when its layer shares a bit with `mask`, none of the
/// switches excludes it and `accept` (when set) returns true. The callback runs inside the query:
/// it may read the world (and query it) but not change it: a changing call made from it is
/// rejected (InvalidArgument, out of the query).
template <class T>
struct QueryFilter {
    std::uint32_t mask = ~std::uint32_t(0);              ///< layers seen: body.layer() & mask != 0
    bool ignore_static = false;                          ///< skip static bodies (a pick ray into a pile)
    bool ignore_sensors = false;                         ///< skip sensors
    BodyId ignore_body{};                                ///< skip this body (the caster itself), none by default
    std::function<bool(BodyId, const Body<T>&)> accept;  ///< when set: false skips the body

    /// Whether the filter lets the body through.
    bool passes(BodyId id, const Body<T>& body) const {
        if ((body.layer() & mask) == 0) return false;
        if (ignore_static && body.type() == BodyType::static_body) return false;
        if (ignore_sensors && body.sensor()) return false;
        if (id == ignore_body) return false;
        return !accept || accept(id, body);
    }
};

namespace f32 {
using QueryFilter = xeno::QueryFilter<float>;
}  // namespace f32
namespace f64 {
using QueryFilter = xeno::QueryFilter<double>;
}  // namespace f64

}  // namespace xeno

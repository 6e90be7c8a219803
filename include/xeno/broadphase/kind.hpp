// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Which broad phase a World uses (WorldSettings::broad_phase): its own header, so the settings
// name it without including the pair machinery.
#pragma once

namespace xeno {

/// The broad-phase strategies the world can use; see broadphase/*.hpp.
enum class BroadPhaseKind {
    brute_force,      ///< every pair's boxes compared: O(n²), the reference
    sweep_and_prune,  ///< sorted sweep on one axis, incremental re-sort (default)
    aabb_tree,        ///< dynamic tree of fattened boxes, incremental refit
};

}  // namespace xeno

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Umbrella header: every public xeno header, nothing else. `#include <xeno/xeno.hpp>` and use
// xeno::f64 (or xeno::f32) names, or the templates directly.
#pragma once

#include "config.hpp"
#include "error.hpp"
#include "math/aabb.hpp"
#include "math/mat3.hpp"
#include "math/mat4.hpp"
#include "math/quat.hpp"
#include "math/scalar.hpp"
#include "math/transform.hpp"
#include "math/vec3.hpp"
#include "shape/box.hpp"
#include "shape/capsule.hpp"
#include "shape/cone.hpp"
#include "shape/convex_polyhedron.hpp"
#include "shape/cylinder.hpp"
#include "shape/mass_properties.hpp"
#include "shape/polyhedra.hpp"
#include "shape/shape.hpp"
#include "shape/sphere.hpp"
#include "shape/support_face.hpp"
#include "debug_draw.hpp"

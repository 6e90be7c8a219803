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

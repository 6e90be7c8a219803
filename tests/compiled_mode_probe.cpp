// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A user file in compiled mode that includes single headers, not <xeno/xeno.hpp>: it steps a World
// and collides two shapes, and must leave both to the library (include/xeno/compiled.hpp). The
// test "compiled mode: ..." (tests/CMakeLists.txt) reads this object's symbols with nm: World's
// step and collide() undefined (taken from xeno::compiled), no MPR compiled here. Before each
// header declared its own templates extern, only files including <xeno/xeno.hpp> got compiled
// mode, and every test file compiled World again.
#include <xeno/collide/collide.hpp>
#include <xeno/dynamics/world.hpp>

float compiled_mode_probe_step(xeno::World<float>& world) {
    world.step(1.0f / 60.0f);
    return static_cast<float>(world.contacts().size());
}

bool compiled_mode_probe_collide(const xeno::Shape<double>& a, const xeno::Shape<double>& b) {
    return xeno::collide(a, xeno::Transform<double>{}, b, xeno::Transform<double>{}).hit;
}

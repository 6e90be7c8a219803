// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A user file, header-only, that steps a World holding a box (the convex narrow phase is
// compiled for every convex kind whatever the file makes) but makes no joint and no mesh body.
// World binds its joint stage and its mesh narrow phase when the first joint or mesh body is made
// (World::bind_joints, bind_mesh_pairs), so this file must compile neither: the test
// "header-only: ..." (tests/CMakeLists.txt) reads its symbols with nm. Before they were bound,
// every file that stepped a World compiled both: 17 % of hello_world's code.
#include <xeno/xeno.hpp>

std::size_t header_only_probe_step(xeno::World<float>& world) {
    world.create_body(xeno::Box<float>(0.5f, 0.5f, 0.5f), xeno::BodyDef<float>{});
    world.step(1.0f / 60.0f);
    return world.contacts().size();
}

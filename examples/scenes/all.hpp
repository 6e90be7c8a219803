// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The registry of scenes by name: the renderer's scenario list, and what tests and benchmarks
// build by name. Names are those of the renderer issue (thesis scenarios 1–8, then ours).
#pragma once

#include "character.hpp"
#include "compounds.hpp"
#include "features.hpp"
#include "piles.hpp"
#include "stacks.hpp"
#include "terrain.hpp"
#include "thesis.hpp"

#include <string>
#include <utility>
#include <vector>

namespace xeno::scenes {

/// Every scene: name and one-line description, in display order.
inline const std::vector<std::pair<std::string, std::string>>& scene_list() {
    static const std::vector<std::pair<std::string, std::string>> list = {
        {"vertex-vertex", "thesis 1: a cube falls corner first onto a corner-up cube"},
        {"vertex-edge", "thesis 2: a cube falls corner first onto an edge-up cube"},
        {"vertex-face", "thesis 3: a cube falls corner first onto a cube's face"},
        {"edge-edge", "thesis 4: a cube falls edge first across an edge-up cube"},
        {"edge-face", "thesis 5: a cube falls edge first onto a cube's face"},
        {"face-face", "thesis 6: a cube falls flat onto a cube's face, off-centre"},
        {"seesaw", "thesis 7: a block on a plank on a rectangular prism on the ground"},
        {"dominoes", "thesis 8: a row of 24 dominoes, the first pushed over"},
        {"pyramid", "a planar pyramid of 210 unit boxes (20 at the base)"},
        {"column", "a column of 10 unit boxes"},
        {"rain", "120 boxes and spheres rain onto the ground"},
        {"mixed-pile", "hulls, spheres, capsules, cylinders, cones and boxes dropped into a pen"},
        {"incline", "boxes with friction 0.2 ... 0.8 on a ramp of slope 0.5: the slippery ones slide"},
        {"heavy-on-light", "a box 400 times heavier resting on a light one"},
        {"sleeping-pile", "64 boxes settle and fall asleep (sleeping bodies drawn faded)"},
        {"ray-fan", "a fan of 24 rays cast every frame against a few bodies (hits drawn)"},
        {"bullet", "a 10 cm box fired at 300 m/s at a 10 cm wall: continuous detection stops it"},
        {"pendulum", "a 2 m pendulum on a ball joint, released from 30 degrees"},
        {"chain", "20 capsule links on ball joints, released horizontally"},
        {"hinged-door", "a door on a hinge swung open against its 90-degree stop"},
        {"ragdoll", "capsules joined by swing-twist joints and limited hinges, dropped on a step"},
        {"compound-stack", "compound bodies stacked: four L-shapes and three tables"},
        {"character", "a capsule moved by shape casts: up a step, along a wall, riding a platform"},
        {"terrain", "boxes, capsules and a ragdoll tumble down a heightfield hill"},
        {"mesh-bowl", "200 hulls, spheres, capsules, cylinders and boxes dropped into a triangle-mesh bowl"},
    };
    return list;
}

/// Builds the named scene into world; an unknown name is an InvalidArgument.
template <class T>
Scene build(const std::string& name, World<T>& world) {
    if (name == "vertex-vertex") return contact_kind(world, ContactKind::vertex_vertex);
    if (name == "vertex-edge") return contact_kind(world, ContactKind::vertex_edge);
    if (name == "vertex-face") return contact_kind(world, ContactKind::vertex_face);
    if (name == "edge-edge") return contact_kind(world, ContactKind::edge_edge);
    if (name == "edge-face") return contact_kind(world, ContactKind::edge_face);
    if (name == "face-face") return contact_kind(world, ContactKind::face_face);
    if (name == "seesaw") return seesaw(world);
    if (name == "dominoes") return dominoes(world);
    if (name == "pyramid") return pyramid(world, 20);
    if (name == "column") return column(world, 10);
    if (name == "rain") return rain(world);
    if (name == "mixed-pile") return mixed_pile(world);
    if (name == "incline") return incline(world);
    if (name == "heavy-on-light") return heavy_on_light(world);
    if (name == "sleeping-pile") return sleeping_pile(world);
    if (name == "ray-fan") return ray_fan(world);
    if (name == "bullet") return bullet(world);
    if (name == "pendulum") return pendulum(world);
    if (name == "chain") return chain(world);
    if (name == "hinged-door") return hinged_door(world);
    if (name == "ragdoll") return ragdoll(world);
    if (name == "compound-stack") return compound_stack(world);
    if (name == "character") return character(world);
    if (name == "terrain") return terrain(world);
    if (name == "mesh-bowl") return mesh_bowl(world);
    xeno::detail::report_invalid(("xeno::scenes::build: unknown scene '" + name + "'").c_str(), "name length",
                                 static_cast<double>(name.size()));
}

}  // namespace xeno::scenes

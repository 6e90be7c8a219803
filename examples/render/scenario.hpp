// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The interface between the scenarios and xeno_render's command line. A Scenario has a name, a
// one-line description and a factory that builds a Simulation in float or double; main.cpp steps
// it by 1/fps between frames, asks it to draw itself into a Renderer and records states() for the
// --states CSV. The registry scenarios() is defined by exactly one source file of the executable
// (examples/CMakeLists.txt, XENO_RENDER_SCENARIO_SOURCES).
#pragma once

#include "render/renderer.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace xeno::render {

/// One body's pose: position of its centre of mass (metres) and unit orientation (w, x, y, z).
struct BodyState {
    int body;
    double x, y, z, qw, qx, qy, qz;
};

/// One scenario running in one precision.
class Simulation {
public:
    virtual ~Simulation() = default;
    virtual void step(double seconds) = 0;                      // advance the simulation
    virtual void draw(Renderer& out, bool contacts) const = 0;  // bodies (and contact points/normals if asked)
    virtual std::vector<BodyState> states() const = 0;          // every body's pose, for CSV
    virtual Camera camera() const = 0;                          // the scenario's suggested view
    virtual double seconds() const = 0;                         // how long its story takes (the default length)
};

struct Scenario {
    std::string name;         // e.g. "vertex-face"
    std::string description;  // one line
    std::function<std::unique_ptr<Simulation>(bool use_float)> make;
};

const std::vector<Scenario>& scenarios();  // the registry; defined in scenarios.cpp (not by you)

}  // namespace xeno::render

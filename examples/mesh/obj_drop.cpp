// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Level geometry from a Wavefront OBJ file: reads a mesh (by default the half-pipe next to this
// file), makes it a static body, drops spheres and boxes onto its walls and steps 8 s: the boxes
// slide down until friction holds them (the walls there are gentler than atan 0.6), the spheres
// roll to and fro across the trough (nothing damps rolling). Prints where each is; exits non-zero
// if one left the pipe or sank through it, so CTest runs it as a check.
//
//   obj_drop [file.obj]
#include "mesh/obj.hpp"

#include <xeno/xeno.hpp>

#include <cstdio>
#include <exception>

#ifndef XENO_EXAMPLES_DIR
#define XENO_EXAMPLES_DIR "."
#endif

int main(int argc, char** argv) {
    namespace xs = xeno::f64;
    const std::string path = argc > 1 ? argv[1] : XENO_EXAMPLES_DIR "/mesh/halfpipe.obj";
    try {
        const xeno::examples::ObjMesh<double> obj = xeno::examples::load_obj<double>(path);
        const xs::TriangleMesh mesh(obj.vertices, obj.triangles);
        std::printf("%s: %zu vertices, %zu triangles (%zu dropped)\n", path.c_str(), obj.vertices.size(), mesh.size(),
                    mesh.dropped_triangles());
        xs::World world;
        xs::BodyDef level;
        level.type = xeno::BodyType::static_body;
        world.create_body(mesh, level);
        std::vector<xeno::BodyId> bodies;
        for (int k = 0; k < 8; ++k) {
            xs::BodyDef d;
            const double side = k % 2 == 0 ? -3.0 : 3.0;  // up each wall of the pipe
            d.position = {-4.5 + 1.3 * k, 0.15 * side * side + 0.8, side};
            bodies.push_back(k % 4 < 2 ? world.create_body(xs::Shape(xs::Sphere(0.4)), d)
                                       : world.create_body(xs::Shape(xs::Box(0.3, 0.3, 0.3)), d));
        }
        for (int step = 0; step < 480; ++step) world.step(1.0 / 60);
        int lost = 0;
        for (xeno::BodyId id : bodies) {
            const xs::Vec3 p = world.body(id).position();
            const double floor = 0.15 * p.z * p.z;  // the pipe's surface under the body
            const bool inside = std::abs(p.x) < 6 && std::abs(p.z) < 4 && p.y > floor + 0.2;
            std::printf("  body %u at (%6.2f, %5.2f, %5.2f)%s\n", id.index, p.x, p.y, p.z, inside ? "" : "  <- left the pipe");
            lost += !inside;
        }
        return lost == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "obj_drop: %s\n", e.what());
        return 2;
    }
}

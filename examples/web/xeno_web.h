// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The C interface of the browser page's WebAssembly module (xeno_web.cpp; docs/web.md). Precision
// arguments: 0 float, 1 double (xw_load also takes 2: both worlds side by side). Stats: 0 dynamic
// bodies, 1 contacts, 2 awake bodies. Arrays: triangles are 10 floats a vertex (position, normal,
// RGBA), lines 7 (position, RGBA); pointers stay valid until the next xw_draw of that precision.
// Bad arguments are refused, never thrown on (docs/web.md, "What is in it"): a pick's origin and
// a drag's target must be finite and within +-1e6 m; xw_step takes 0 to 600 steps a call (a
// larger count is cut to 600), xw_benchmark 1 to 600 (else -1).
#pragma once

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#define XW_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define XW_EXPORT
#endif

extern "C" {
XW_EXPORT int xw_scene_count();
XW_EXPORT const char* xw_scene_name(int i);
XW_EXPORT const char* xw_scene_description(int i);
XW_EXPORT int xw_load(int scene, int precision);
XW_EXPORT void xw_step(int n);
XW_EXPORT double xw_step_ms();
XW_EXPORT double xw_time();
XW_EXPORT int xw_draw(int precision, int contacts);
XW_EXPORT float* xw_triangles(int precision);
XW_EXPORT int xw_line_vertices(int precision);
XW_EXPORT float* xw_lines(int precision);
XW_EXPORT int xw_stat(int precision, int what);
XW_EXPORT double xw_max_difference();
XW_EXPORT double xw_camera(int k);
XW_EXPORT int xw_pick(double ox, double oy, double oz, double dx, double dy, double dz);
XW_EXPORT double xw_grab_point(int k);
XW_EXPORT void xw_drag(double x, double y, double z);
XW_EXPORT void xw_release();
XW_EXPORT int xw_grabbed_body();
XW_EXPORT double xw_body_position(int precision, int index, int k);
XW_EXPORT double xw_benchmark(int scene, int precision, int steps);
XW_EXPORT const char* xw_error();
}

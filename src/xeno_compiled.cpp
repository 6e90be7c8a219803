// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Compiled mode's one source file (include/xeno/compiled.hpp): the heavy templates for float and
// double, compiled once. Add this file to your own build and define XENO_COMPILED_LIB for every
// file that includes xeno, or link the CMake target xeno::compiled, which builds the same from
// its two halves (xeno_compiled_float.cpp and xeno_compiled_double.cpp) side by side.
#include <xeno/xeno.hpp>

XENO_DETAIL_COMPILED_TEMPLATES(float)
XENO_DETAIL_COMPILED_TEMPLATES(double)

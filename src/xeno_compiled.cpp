// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Compiled mode's one source file (include/xeno/compiled.hpp): the heavy templates for float and
// double, compiled once. Build it as the static library xeno::compiled (CMake), or add this file to
// your own build and define XENO_COMPILED_LIB for every file that includes xeno.
#include <xeno/xeno.hpp>

XENO_DETAIL_COMPILED_TEMPLATES(float)
XENO_DETAIL_COMPILED_TEMPLATES(double)

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Half of src/xeno_compiled.cpp: the heavy templates for float only. The CMake target
// xeno::compiled builds the float and the double half as two files, so a parallel build compiles
// them side by side (each is one long compile: about 35 s with g++ -O3); add this file alone to
// your own build if your game uses only float.
#include <xeno/xeno.hpp>

XENO_DETAIL_COMPILED_TEMPLATES(float)

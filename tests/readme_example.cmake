# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Fails unless the ```cpp block that follows the line `<!-- example: FILE -->` in README.md is
# FILE, character for character: the README shows what CI compiles and runs.
# Usage: cmake -DREADME=<README.md> -DFILE=<examples/x.cpp> -DNAME=<examples/x.cpp> -P readme_example.cmake
file(READ ${README} readme)
file(READ ${FILE} expected)
string(FIND "${readme}" "<!-- example: ${NAME} -->\n```cpp\n" start)
if(start EQUAL -1)
  message(FATAL_ERROR "README.md has no `<!-- example: ${NAME} -->` line followed by a ```cpp block")
endif()
string(LENGTH "<!-- example: ${NAME} -->\n```cpp\n" skip)
math(EXPR start "${start} + ${skip}")
string(SUBSTRING "${readme}" ${start} -1 rest)
string(FIND "${rest}" "```" end)
string(SUBSTRING "${rest}" 0 ${end} shown)
if(NOT shown STREQUAL expected)
  message(FATAL_ERROR "README.md's block for ${NAME} differs from the file")
endif()

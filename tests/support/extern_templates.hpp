// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Seen by every test translation unit through the precompiled header: World's members are
// compiled once, in tests/instantiate.cpp, instead of in each of the forty test files.
#pragma once

#include <xeno/dynamics/world.hpp>

extern template class xeno::World<float>;
extern template class xeno::World<double>;

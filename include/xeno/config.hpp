// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Version and the one place for compiler switches. XENO_ASSERT checks internal invariants (never
// user input: that is checked at the door, see error.hpp); it is on in debug builds and whenever
// XENO_ENABLE_ASSERTS is defined, and compiles to nothing otherwise.
#pragma once

#include <cstdio>
#include <cstdlib>

#define XENO_VERSION_MAJOR 0
#define XENO_VERSION_MINOR 9
#define XENO_VERSION_PATCH 0
#define XENO_VERSION "0.9.0"

#if defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND)
#define XENO_HAS_EXCEPTIONS 1
#else
#define XENO_HAS_EXCEPTIONS 0
#endif

#if !defined(NDEBUG) && !defined(XENO_ENABLE_ASSERTS)
#define XENO_ENABLE_ASSERTS
#endif

#ifdef XENO_ENABLE_ASSERTS
#define XENO_ASSERT(condition) \
    ((condition) ? static_cast<void>(0) : ::xeno::detail::assert_failed(#condition, __FILE__, __LINE__))
#else
#define XENO_ASSERT(condition) static_cast<void>(0)
#endif

namespace xeno::detail {

/// Prints the broken invariant and aborts: an assert failure is a bug in xeno, not bad input.
[[noreturn]] inline void assert_failed(const char* condition, const char* file, int line) {
    std::fprintf(stderr, "xeno: assertion failed: %s (%s:%d)\n", condition, file, line);
    std::abort();
}

}  // namespace xeno::detail

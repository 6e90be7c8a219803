// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Linked into every benchmark when XENO_BENCH_OPTIMIZATION is set (bench/CMakeLists.txt): the
// test command builds the benchmarks at -O0 only to prove they compile and link, and a time taken
// from such a program would mislead. It says so before main runs.
#include <cstdio>

namespace {
struct UnoptimisedNotice {
    UnoptimisedNotice() {
        std::fputs(
            "xeno: this benchmark was built with XENO_BENCH_OPTIMIZATION set (a compile check): its times mean "
            "nothing; build it as docs/benchmarks.md says\n",
            stderr);
    }
};
const UnoptimisedNotice notice;
}  // namespace

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Built with -fno-exceptions: the checks of xeno must call the error handler. With the argument
// "custom" a handler is installed that prints the message and exits 0; with "default" the
// default handler must print and abort. CTest checks the output (tests/CMakeLists.txt).
#include <xeno/shape/box.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {
void print_and_exit(const char* message) {
    std::printf("handled: %s\n", message);
    std::fflush(stdout);
    std::exit(0);
}
}  // namespace

int main(int argc, char** argv) {
    if (argc > 1 && std::strcmp(argv[1], "custom") == 0) xeno::set_error_handler(&print_and_exit);
    const xeno::Box<double> bad(-1.0, 1.0, 1.0);
    std::printf("continued with half extent %g\n", bad.half_extents().x);
    return 3;
}

// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The page's benchmark (xw_benchmark: the 210-box pyramid, 100 steps, sleeping off) compiled natively, so the
// browser test can print WebAssembly's time beside the native one (scripts/web.sh test).
// Prints "float <ms/step> double <ms/step>", the best of three runs each.
#include "web/xeno_web.h"

#include <algorithm>
#include <cstdio>
#include <string>

int main() {
    int pyramid = -1;
    for (int i = 0; i < xw_scene_count(); ++i)
        if (std::string(xw_scene_name(i)) == "pyramid") pyramid = i;
    if (pyramid < 0) return 1;
    double best[2] = {1e300, 1e300};
    for (int run = 0; run < 3; ++run)
        for (int precision = 0; precision < 2; ++precision)
            best[precision] = std::min(best[precision], xw_benchmark(pyramid, precision, 100));
    std::printf("float %.4f double %.4f\n", best[0], best[1]);
    return 0;
}

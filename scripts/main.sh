#!/usr/bin/env bash
# The README's first command: set up, build the examples (Release) and run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh main
build=${XENO_BUILD_DIR:-build}/main
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DXENO_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)"
"$build/examples/hello_world"
# Every scene in float and double side by side (~5 s): a table here, CSVs and PNGs in out/precision/.
"$build/examples/xeno_precision" --out out

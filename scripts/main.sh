#!/usr/bin/env bash
# The README's first command: set up, build the examples and benchmarks (Release), run the main job:
#   1. the README's example (hello_world)
#   2. every scenario rendered off-screen to out/<scenario>/frame_*.png (+ .gif/.mp4 via ffmpeg)
#   3. the N² detection benchmark: the thesis's table beside xeno's strategies (+ out/n2.png),
#      and its early-out rows from an x86-64-v3 (AVX2) build where the CPU has AVX2
#   4. every scene in float and double side by side (out/precision/)
# Takes about 5 minutes on a 2-core machine, most of it compiling and rendering.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh main
build=${XENO_BUILD_DIR:-build}/main
out=${XENO_OUT_DIR:-out}
step() { printf '\n=== %s\n' "$*"; }

step "build (Release, examples and benchmarks)"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DXENO_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" \
  --target hello_world xeno_render xeno_n2_bench xeno_precision

step "the README's example"
"$build/examples/hello_world"

step "every scenario to PNG frames in $out/"
"$build/examples/xeno_render" --out "$out" all

step "N² detection: one pass of broad + narrow phase against the thesis's Quadro 26"
"$build/bench/xeno_n2_bench" --out "$out"
# The early-out's rows again from a build for x86-64-v3 (AVX2 lanes), where this CPU runs it.
if grep -qw avx2 /proc/cpuinfo 2>/dev/null && cmake --build "$build" --target xeno_n2_bench_v3 >/dev/null 2>&1; then
  step "N² detection, the early-out's rows from the -march=x86-64-v3 build"
  "$build/bench/xeno_n2_bench_v3" --lanes
fi

step "float against double, every scene"
"$build/examples/xeno_precision" --out "$out"

step "done: frames in $out/<scenario>/, N² table in $out/n2.csv and $out/n2.png, precision in $out/precision/"

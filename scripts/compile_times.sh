#!/usr/bin/env bash
# Compile time of one user translation unit (examples/hello_world.cpp, the README's example),
# header-only at -O0 and -O2 and in compiled mode at -O2 (XENO_COMPILED_LIB: World and the narrow
# phase come from src/xeno_compiled.cpp, whose own one-time cost is printed too), with g++ and
# clang++: the median of RUNS (default 3) CPU-user+system seconds each. Prints a Markdown table
# (docs/benchmarks.md, "Compile time"). Run it on a quiet machine.
# Usage: scripts/compile_times.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
seconds() {  # compiler, flags...: median CPU seconds of compiling hello_world.cpp (or a given file)
  local cxx=$1; shift
  for _ in $(seq "$runs"); do
    /usr/bin/time -f '%U %S' -o "$work/t" "$cxx" -std=c++17 -I include "$@" -c -o "$work/o.o"
    awk '{ printf "%.2f\n", $1 + $2 }' "$work/t"
  done | median
}

echo "| compiler | header-only -O0 | header-only -O2 | compiled mode -O2 (user file) | src/xeno_compiled.cpp -O2 (once) |"
echo "|---|---:|---:|---:|---:|"
for cxx in g++ clang++; do
  command -v "$cxx" >/dev/null || continue
  version=$("$cxx" --version | head -n 1 | grep -oE '[0-9]+\.[0-9]+(\.[0-9]+)?' | head -n 1)
  o0=$(seconds "$cxx" -O0 examples/hello_world.cpp)
  o2=$(seconds "$cxx" -O2 examples/hello_world.cpp)
  user=$(seconds "$cxx" -O2 -DXENO_COMPILED_LIB examples/hello_world.cpp)
  lib=$(seconds "$cxx" -O2 -ffp-contract=off src/xeno_compiled.cpp)
  echo "| $cxx $version | $o0 s | $o2 s | $user s | $lib s |"
done

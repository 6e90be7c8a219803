#!/usr/bin/env bash
# The README's third command: the scenarios in the browser (docs/web.md).
#   scripts/web.sh          set up, build the page into build/web/ and serve it on
#                           http://localhost:8000/ (Ctrl-C stops it; XENO_WEB_PORT changes the port)
#   scripts/web.sh build    set up and build only
#   scripts/web.sh test     set up, build, and drive the page in headless Chromium
#                           (examples/web/test_page.py)
#   scripts/web.sh test-built   drive the page `build` left, without building it again
#                           (scripts/test.sh builds the page beside other work, then tests it
#                           alone, so the speed line compares WebAssembly and native on a quiet
#                           machine)
# The page is examples/web/index.html + page.js and xeno_web.js/.wasm, compiled by Debian's
# Emscripten from examples/web/xeno_web.cpp (the scenario registry and the library, -O2, no
# fast-math, WebAssembly SIMD with SSE2 intrinsics translated, as the native build uses SSE2).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
mode=${1:-serve}
scripts/setup.sh web

out=${XENO_BUILD_DIR:-$root/build}/web
mkdir -p "$out"
# Debian's emcc runs its optimizer under node and needs the acorn module from node-acorn.
export NODE_PATH=/usr/share/nodejs
if [[ "$mode" != test-built ]]; then
  printf '=== build the page (Emscripten) into %s\n' "$out"
  emcc -std=c++17 -O2 -Wall -Wextra -Werror -ffp-contract=off -msimd128 -msse2 \
       -I "$root/include" -I "$root/examples" "$root/examples/web/xeno_web.cpp" -o "$out/xeno_web.js" \
       -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=web -sEXPORTED_RUNTIME_METHODS=UTF8ToString
  cp "$root/examples/web/index.html" "$root/examples/web/page.js" "$out/"
fi

case "$mode" in
  build) ;;
  test | test-built)
    [[ -s "$out/xeno_web.wasm" ]] || { echo "no page in $out: run scripts/web.sh build first" >&2; exit 1; }
    # The same benchmark natively: xeno_web_native_bench from a CMake build when given
    # (scripts/test.sh passes its g++ Release one), else compiled here.
    native=${XENO_WEB_NATIVE_BENCH:-}
    if [[ -z "$native" ]]; then
      printf '=== native build of the same interface, for the speed comparison\n'
      native=$out/native_bench
      g++ -std=c++17 -O2 -ffp-contract=off -I "$root/include" -I "$root/examples" \
          "$root/examples/web/xeno_web.cpp" "$root/examples/web/native_bench.cpp" -o "$native"
    fi
    printf '=== the page in headless Chromium\n'
    # Debian's own Python, which python3-websocket installs into (another python3 may come first on PATH).
    /usr/bin/python3 "$root/examples/web/test_page.py" --dir "$out" --native "$native" --screenshot "$out/screenshot.png"
    ;;
  serve)
    port=${XENO_WEB_PORT:-8000}
    printf '=== open http://localhost:%s/ (Ctrl-C stops the server)\n' "$port"
    cd "$out" && exec python3 -m http.server "$port" --bind 127.0.0.1
    ;;
  *) echo "usage: scripts/web.sh [serve|build|test|test-built]" >&2; exit 2 ;;
esac

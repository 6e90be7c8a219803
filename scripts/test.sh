#!/usr/bin/env bash
# The README's second command: set up, then build and run everything xeno tests.
#   0. no file cites anything outside the repository (scripts/check_refs.sh); every C++ file is
#      formatted by .clang-format, no line over 130 characters (scripts/check_format.sh)
#   1. g++ Release at -O2 (the level of the browser build, whose speed line step 5 compares with
#      the native one; CMake's Release default is -O3), warnings as errors: tests (unit + slow;
#      the unit-test files at -O0 but four that compute references at -O1, tests/CMakeLists.txt),
#      examples built (those no test runs, and the benchmarks, only through the front end to prove
#      they compile: XENO_COMPILE_CHECK_ONLY; scripts/main.sh builds both for use)
#   2. clang++ with -fsanitize=address,undefined -fno-sanitize-recover=all (-O1, line tables; the
#      unit-test files at -O0, and run file by file: tests/CMakeLists.txt says why),
#      warnings as errors: every header alone, the unit and slow tests, and the libFuzzer targets
#      (which add -fsanitize=fuzzer) run for a bounded time
#   3. clang++ -O2: the determinism program header-only, whose scene hashes must equal g++'s
#      compiled-mode program's (on one worker and on two); and clang++ with -fsanitize=thread: the
#      tests that step worlds on several threads (tests/robustness/parallel_test.cpp, one file)
#   4. the README's example compiled by the consumer projects: plain -I include,
#      add_subdirectory(xeno) and find_package(xeno CONFIG REQUIRED) after cmake --install, each
#      header-only and in compiled mode (xeno::compiled), and in xeno::f32 with -Werror; beside
#      them, the browser page built with Emscripten (scripts/web.sh build)
#   5. the browser page driven in headless Chromium (scripts/web.sh test-built)
# One sanitizer build, with clang++, serves both the second compiler and the memory and UB checks
# (they were two full builds of the tests, a clang++ Release one and a g++ sanitizer one).
# XENO_TEST_QUICK=1 runs only step 1 without the slow label (for iterating).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
scripts/setup.sh test

jobs=$(nproc 2>/dev/null || echo 2)
build=${XENO_BUILD_DIR:-$root/build}
start=$(date +%s)
last=$start
times=()
step() {  # closes the previous step's timing and opens the next
  local now; now=$(date +%s)
  if [[ -n "${current:-}" ]]; then times+=("$(printf '%6d  %s' $((now - last)) "$current")"); fi
  current=$*; last=$now
  printf '\n=== %s (%ds elapsed)\n' "$*" $(( now - start ))
}

configure_and_test() {  # name, extra cmake args...
  local name=$1; shift
  cmake -S "$root" -B "$build/$name" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DXENO_WARNINGS_AS_ERRORS=ON "$@" >/dev/null
  cmake --build "$build/$name" -j "$jobs"
  ctest --test-dir "$build/$name" -j "$jobs" --output-on-failure ${ctest_args:-}
}

# Every public header compiled alone (XENO_BUILD_HEADER_CHECK) is proved once, in step 2: both
# compilers read the same standard library, and the tests include every header under both.
# The benchmarks (and the examples no test runs) are compiled to prove they compile, not run: front
# end only (XENO_COMPILE_CHECK_ONLY, CMakeLists.txt), not linked.
gcc_flags=(-DCMAKE_CXX_COMPILER=g++ "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG" -DXENO_BUILD_HEADER_CHECK=OFF
           -DXENO_COMPILE_CHECK_ONLY=ON)
if [[ "${XENO_TEST_QUICK:-0}" == 1 ]]; then
  step "g++ Release (quick: no slow tests)"
  ctest_args="-LE slow" configure_and_test gcc "${gcc_flags[@]}"
  exit 0
fi

step "every reference in the repository points inside it; C++ formatted by .clang-format"
scripts/check_refs.sh
scripts/check_format.sh

step "g++ Release (-O2), -Werror, all targets"
configure_and_test gcc "${gcc_flags[@]}"

step "clang++ with AddressSanitizer and UndefinedBehaviorSanitizer, -Werror: headers, tests, libFuzzer targets (label fuzz: 30 s each)"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
configure_and_test clang-asan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
  -DXENO_BUILD_BENCH=OFF -DXENO_BUILD_EXAMPLES=OFF -DXENO_BUILD_HEADER_CHECK=ON -DXENO_BUILD_FUZZ=ON -DXENO_SANITIZE=ON \
  -DXENO_UNIT_TEST_OPTIMIZATION=-O0 -DXENO_REFERENCE_TEST_OPTIMIZATION= -DXENO_TESTS_PER_FILE=ON -DXENO_COMPILE_CHECK_ONLY=ON \
  "-DCMAKE_CXX_FLAGS=-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"

step "clang++: a header-only Release build steps every scene to g++'s state hashes; ThreadSanitizer on the tests that step on several workers"
# Three files compiled directly, two at a time (each is one long compile): the determinism
# program header-only (g++'s links xeno::compiled, so the comparison also spans the two modes)
# and the TSan test program (tests/robustness/parallel_test.cpp beside the doctest main).
mkdir -p "$build/clang" "$build/tsan"
warnings=(-std=c++17 -ffp-contract=off -Wall -Wextra -Wpedantic -Wshadow -Werror -I "$root/include" -I "$root/tests" -I "$root/examples")
clang++ "${warnings[@]}" -O2 -DNDEBUG -pthread "$root/tests/robustness/determinism_main.cpp" -o "$build/clang/xeno_determinism" &
determinism=$!
tsan=(clang++ "${warnings[@]}" -Wconversion -O1 -g1 -fsanitize=thread)
"${tsan[@]}" -c "$root/tests/robustness/parallel_test.cpp" -o "$build/tsan/parallel_test.o"
"${tsan[@]}" -c "$root/tests/test_main.cpp" -o "$build/tsan/test_main.o"
wait $determinism
"$build/gcc/tests/xeno_determinism" >"$build/gcc/determinism.txt"
"$build/clang/xeno_determinism" >"$build/clang/determinism.txt"
"$build/clang/xeno_determinism" --workers 2 >"$build/clang/determinism-2.txt"
if ! diff "$build/gcc/determinism.txt" "$build/clang/determinism.txt" ||
   ! diff "$build/gcc/determinism.txt" "$build/clang/determinism-2.txt"; then
  echo "g++ and clang++ builds differ (docs/robustness.md, \"Determinism\")" >&2
  exit 1
fi
"${tsan[@]}" "$build/tsan/test_main.o" "$build/tsan/parallel_test.o" -o "$build/tsan/xeno_parallel_tests"
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" "$build/tsan/xeno_parallel_tests"

step "consumer projects compile the README's example; beside them, the browser page is built (Emscripten)"
# Both are chains of one-file compiles, so they share the two cores; the page's build output is
# shown after the consumers'.
XENO_BUILD_DIR="$build" scripts/web.sh build >"$build/web-build.log" 2>&1 &
web=$!
tests/consumers/run.sh "$build/consumers" || { kill $web 2>/dev/null; exit 1; }
if ! wait $web; then
  cat "$build/web-build.log"
  echo "the browser page did not build (scripts/web.sh build)" >&2
  exit 1
fi
cat "$build/web-build.log"

step "the browser page tested in headless Chromium (alone, so its speed line is a fair one)"
XENO_BUILD_DIR="$build" XENO_WEB_NATIVE_BENCH="$build/gcc/examples/xeno_web_native_bench" scripts/web.sh test-built

step "all passed"
printf '\nTime per step (s):\n'
printf '%s\n' "${times[@]}"
printf '%6d  total\n' $(( $(date +%s) - start ))

#!/usr/bin/env bash
# Compiles and runs the README's example (its first ```cpp block) three ways, as a user would
# consume xeno: plain -I include, add_subdirectory(xeno), find_package(xeno CONFIG REQUIRED)
# after cmake --install; each header-only (xeno::xeno) and in compiled mode (xeno::compiled, or
# src/xeno_compiled.cpp and -DXENO_COMPILED_LIB by hand). All six must print the same.
# Usage: tests/consumers/run.sh WORK_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
work=${1:?work dir}
rm -rf "$work" && mkdir -p "$work"

example=$work/readme_example.cpp
awk '/^```cpp/{inside=1; next} /^```/{if(inside){exit}} inside' "$root/README.md" > "$example"
[[ -s "$example" ]] || { echo "no \`\`\`cpp block found in README.md" >&2; exit 1; }
diff -u "$root/examples/hello_world.cpp" "$example" ||
  { echo "README.md's example and examples/hello_world.cpp differ" >&2; exit 1; }

plain() {  # the README's one-line build, header-only and compiled mode, and the f32 example
  echo "-- plain: c++ -std=c++17 -I include"
  # (No -O, as the README writes it: 7 s instead of 19 at -O2. The f32 builds below run at -O1,
  # where g++'s flow-based warnings are on.)
  ${CXX:-c++} -std=c++17 -Wall -Wextra -Werror -I "$root/include" "$example" -o "$work/plain"
  "$work/plain" > "$work/plain.out"

  echo "-- plain, the example in xeno::f32, -Werror with the project's warning set (g++ and clang++)"
  sed 's/namespace xs = xeno::f64;/namespace xs = xeno::f32;/' "$example" > "$work/readme_example_f32.cpp"
  grep -q 'xeno::f32;' "$work/readme_example_f32.cpp" || { echo "the example does not start with xeno::f64" >&2; exit 1; }
  for cxx in g++ clang++; do
    command -v "$cxx" >/dev/null || continue
    "$cxx" -std=c++17 -O1 -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror -I "$root/include" \
      "$work/readme_example_f32.cpp" -o "$work/plain_f32_$cxx"
    "$work/plain_f32_$cxx" > /dev/null
  done

  echo "-- plain, compiled mode: src/xeno_compiled.cpp and -DXENO_COMPILED_LIB"
  # (-O0: what is checked is that the two files build and link; the library file takes 100 s of
  # CPU at -O2, and the bits printed are the same at every level: no FMA contraction, no fast-math.)
  ${CXX:-c++} -std=c++17 -O0 -Wall -Wextra -Werror -DXENO_COMPILED_LIB -I "$root/include" \
    "$root/src/xeno_compiled.cpp" "$example" -o "$work/plain_compiled"
  "$work/plain_compiled" > "$work/plain_compiled.out"
}

# project (subdirectory or package), then cmake -D arguments: builds and runs it linking each of
# xeno::xeno and xeno::compiled; the output goes to $work/<project>-<xeno|compiled>.out.
consume() {
  local project=$1; shift
  for target in xeno::xeno xeno::compiled; do
    local mode=${target#xeno::}
    echo "-- $project, linking $target"
    cmake -S "$here/$project" -B "$work/$project-$mode" -DEXAMPLE_SOURCE="$example" -DXENO_TARGET="$target" "$@" >/dev/null
    cmake --build "$work/$project-$mode" >/dev/null
    "$work/$project-$mode/app" > "$work/$project-$mode.out"
  done
}

package() {  # cmake --install, then find_package(xeno CONFIG REQUIRED)
  echo "-- cmake --install, for find_package(xeno CONFIG REQUIRED)"
  cmake -S "$root" -B "$work/xeno-build" -DXENO_BUILD_TESTS=OFF -DXENO_BUILD_BENCH=OFF \
        -DXENO_BUILD_EXAMPLES=OFF -DXENO_BUILD_HEADER_CHECK=OFF -DCMAKE_INSTALL_PREFIX="$work/prefix" >/dev/null
  cmake --build "$work/xeno-build" >/dev/null  # the static library of compiled mode
  cmake --install "$work/xeno-build" >/dev/null
  consume package -DCMAKE_PREFIX_PATH="$work/prefix"
}

# The three chains are independent and each compiles one file at a time: they run side by side
# (about 200 s one after another on two cores, half that together). `wait PID` fails the script
# if a chain failed.
plain & plain_pid=$!
consume subdirectory -DXENO_SOURCE_DIR="$root" & subdirectory_pid=$!   # add_subdirectory(xeno)
package
wait $plain_pid
wait $subdirectory_pid

for out in plain_compiled subdirectory-xeno subdirectory-compiled package-xeno package-compiled; do
  cmp "$work/plain.out" "$work/$out.out"
done
echo "-- all six consumers built and printed the same:"
cat "$work/plain.out"

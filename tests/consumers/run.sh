#!/usr/bin/env bash
# Compiles and runs the README's example (its first ```cpp block) three ways, as a user would
# consume xeno: plain -I include, add_subdirectory(xeno), find_package(xeno CONFIG REQUIRED)
# after cmake --install. Usage: tests/consumers/run.sh WORK_DIR
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

echo "-- plain: c++ -std=c++17 -I include"
${CXX:-c++} -std=c++17 -O2 -Wall -Wextra -Werror -I "$root/include" "$example" -o "$work/plain"
"$work/plain" > "$work/plain.out"

echo "-- add_subdirectory(xeno)"
cmake -S "$here/subdirectory" -B "$work/subdirectory" -DXENO_SOURCE_DIR="$root" -DEXAMPLE_SOURCE="$example" >/dev/null
cmake --build "$work/subdirectory" >/dev/null
"$work/subdirectory/app" > "$work/subdirectory.out"

echo "-- find_package(xeno CONFIG REQUIRED) after cmake --install"
cmake -S "$root" -B "$work/xeno-build" -DXENO_BUILD_TESTS=OFF -DXENO_BUILD_BENCH=OFF \
      -DXENO_BUILD_EXAMPLES=OFF -DXENO_BUILD_HEADER_CHECK=OFF -DCMAKE_INSTALL_PREFIX="$work/prefix" >/dev/null
cmake --install "$work/xeno-build" >/dev/null
cmake -S "$here/package" -B "$work/package" -DCMAKE_PREFIX_PATH="$work/prefix" -DEXAMPLE_SOURCE="$example" >/dev/null
cmake --build "$work/package" >/dev/null
"$work/package/app" > "$work/package.out"

cmp "$work/plain.out" "$work/subdirectory.out"
cmp "$work/plain.out" "$work/package.out"
echo "-- all three consumers built and printed the same:"
cat "$work/plain.out"

#!/usr/bin/env bash
# Installs what xeno's tests, benchmarks and examples need on Debian/Ubuntu, only when missing:
# idempotent, and silent when everything is already there. The library itself needs none of it.
#   scripts/setup.sh test   compilers, CMake, clang-format, doctest, Catch2, OSMesa, libpng, libccd, Bullet,
#                           and what the browser page's test needs (below)
#   scripts/setup.sh main   the first list plus ffmpeg (GIF/MP4) and gnuplot (plots)
#   scripts/setup.sh web    the browser page: Emscripten (with node-acorn for its optimizer), Chromium
#                           (headless, for the test) and Python's websocket client (the test's
#                           DevTools connection)
set -euo pipefail

kind=${1:-test}
packages=(cmake ninja-build g++ clang libclang-rt-14-dev clang-format pkg-config
          doctest-dev catch2 libosmesa6-dev libpng-dev libccd-dev libbullet-dev)
web=(emscripten node-acorn chromium python3-websocket)
case "$kind" in
  main) packages+=(ffmpeg gnuplot-nox) ;;
  web) packages=(g++ python3 "${web[@]}") ;;
  test) packages+=("${web[@]}") ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

if ! command -v apt-get >/dev/null; then
  echo "setup: apt-get not found; install these by hand: ${missing[*]}" >&2
  exit 1
fi
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null

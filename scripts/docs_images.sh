#!/usr/bin/env bash
# Regenerates the README's pictures in docs/images/ (not part of the two commands):
#   scenarios.png  one small still per scenario at t = 1.5 s, tiled 6 wide, with names (ffmpeg)
#   n2.png         the N² plot, copied from a finished `xeno_n2_bench --out DIR` run (argument 1)
# Usage: scripts/docs_images.sh [N2_OUT_DIR]   (after scripts/main.sh: scripts/docs_images.sh out)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${XENO_BUILD_DIR:-build}/main
render=${XENO_RENDER:-$build/examples/xeno_render}  # XENO_RENDER=path: use that binary as it is
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[[ -n "${XENO_RENDER:-}" ]] || cmake --build "$build" --target xeno_render >/dev/null
mkdir -p docs/images
i=0
while read -r name _; do
  "$render" --frames 91 --size 192x144 --out "$tmp/frames" "$name" </dev/null 2>/dev/null
  ffmpeg -nostdin -loglevel error -y -i "$tmp/frames/$name/frame_0090.png" \
    -vf "drawtext=text='$name':x=4:y=4:fontsize=13:fontcolor=black" "$tmp/$(printf '%02d' $i).png" 2>/dev/null ||
    cp "$tmp/frames/$name/frame_0090.png" "$tmp/$(printf '%02d' $i).png"  # ffmpeg without drawtext
  i=$((i + 1))
done < <("$render" --list)
ffmpeg -nostdin -loglevel error -y -framerate 1 -i "$tmp/%02d.png" -vf "tile=6x$(( (i + 5) / 6 )):padding=2:color=white" \
  -frames:v 1 docs/images/scenarios.png
if [[ $# -ge 1 && -f "$1/n2.png" ]]; then cp "$1/n2.png" docs/images/n2.png; fi
ls -l docs/images

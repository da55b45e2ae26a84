#!/usr/bin/env bash
# paths-docs.sh: the pictures of chapter 15's walkthrough (docs/15-paths.md), made with the chapter
# programs themselves (and build/inset to set them side by side).
#
#   tools/paths-docs.sh BUILD
#
# docs/images/15-noise.png             the Cornell box at 128 x 128 with 1, 4, 16, 64 and 256 paths a pixel
# docs/images/15-whitted-and-paths.png the same room by chapter 14 (Whitted's recursion, chapter 13's soft
#                                      shadows, the lamp's light 1 1 1 and no ambient) and by chapter 15
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: tools/paths-docs.sh BUILD}
scene=scenes/15-paths.scene
work=out/paths-docs
mkdir -p "$work"

size=(--width 128 --height 128)
noise=()
for n in 1 4 16 64 256; do
    "$build/chapter-15" "$scene" --quiet "${size[@]}" --set paths.samples=$n -o "$work/noise-$n.png"
    noise+=("$work/noise-$n.png")
done
"$build/inset" docs/images/15-noise.png 0 0 128 128 1 "${noise[@]}"

size=(--width 192 --height 192)
"$build/chapter-14" "$scene" --quiet "${size[@]}" --set light.1.colour="1 1 1" -o "$work/whitted.png"
"$build/chapter-15" "$scene" --quiet "${size[@]}" -o "$work/paths.png"
"$build/inset" docs/images/15-whitted-and-paths.png 0 0 192 192 1 "$work/whitted.png" "$work/paths.png"

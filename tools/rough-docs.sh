#!/usr/bin/env bash
# rough-docs.sh: the pictures of chapter 17's walkthrough (docs/17-rough.md), made with the chapter
# program itself (and build/inset to set them side by side).
#
#   tools/rough-docs.sh BUILD
#
# docs/images/17-veach-strategies.png  Veach's plates (scenes/17-veach.scene, 64 paths a pixel) drawn by
#                                      light sampling, scattering and multiple importance sampling
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: tools/rough-docs.sh BUILD}
work=out/rough-docs
mkdir -p "$work"
pictures=()
for strategy in light scatter mis; do
    "$build/chapter-17" scenes/17-veach.scene --quiet --set paths.strategy=$strategy -o "$work/veach-$strategy.png"
    pictures+=("$work/veach-$strategy.png")
done
"$build/inset" docs/images/17-veach-strategies.png 0 0 384 256 1 "${pictures[@]}"

#!/usr/bin/env bash
# bless-references.sh BUILD: re-renders every chapter's scene into reference_images/ on purpose, and
# says for each chapter whether its picture changed (and by how much) or stayed the same. A picture whose
# pixels are the same is left as it is, byte for byte (the PNG writer may encode the same pixels in other
# bytes than it once did), so that blessing what has not changed leaves the tree as it found it.
set -eu
build=${1:-build}
mkdir -p reference_images out
# bless PROGRAM SCENE (empty: the chapter's own) NAME (reference_images/NAME.png) LABEL
bless() {
    local program=$1 scene=$2 name=$3 label=$4
    local new=out/reference-$name.png old=reference_images/$name.png
    "$program" $scene --quiet -o "$new"
    if [ -f "$old" ]; then
        if difference=$("$build"/compare "$old" "$new" 2>&1) && [ "${difference%% *}" = "max" ] &&
           [ "$(echo "$difference" | awk '{print $2}')" = "0" ]; then
            echo "$label: unchanged"
            rm -f "$new"
            return
        else
            echo "$label: CHANGED: $difference"
        fi
    else
        echo "$label: new reference"
    fi
    mv "$new" "$old"
}
for program in "$build"/chapter-[0-9][0-9]; do
    n=${program##*/chapter-}
    bless "$program" "" "chapter-$n" "chapter $n"
done
# Scenes that teach something beside a chapter's own picture.
bless "$build"/chapter-08 scenes/08-glass-of-water.scene 08-glass-of-water "chapter 8, glass of water"
bless "$build"/chapter-13 scenes/13-focus.scene 13-focus "chapter 13, depth of field"

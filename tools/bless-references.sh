#!/usr/bin/env bash
# bless-references.sh BUILD: re-renders every chapter's scene into reference_images/ on purpose, and
# says for each chapter whether its picture changed (and by how much) or stayed the same.
set -eu
build=${1:-build}
mkdir -p reference_images out
for program in "$build"/chapter-[0-9][0-9]; do
    n=${program##*/chapter-}
    new=out/reference-$n.png
    "$program" --quiet -o "$new"
    old=reference_images/chapter-$n.png
    if [ -f "$old" ]; then
        if difference=$("$build"/compare "$old" "$new" 2>&1) && [ "${difference%% *}" = "max" ] &&
           [ "$(echo "$difference" | awk '{print $2}')" = "0" ]; then
            echo "chapter $n: unchanged"
        else
            echo "chapter $n: CHANGED: $difference"
        fi
    else
        echo "chapter $n: new reference"
    fi
    mv "$new" "$old"
done

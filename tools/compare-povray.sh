#!/usr/bin/env bash
# compare-povray.sh BUILD [N...]: renders each chapter's scene with the chapter program and with
# POV-Ray at the same size and writes to out/compare/, for each chapter NN, chapter-NN-side-by-side.png
# (ours | POV-Ray) and chapter-NN-diff.png (|ours - POV-Ray| amplified x16, DIFF_GAIN in tools/compare.c:
# a 1-level difference shows as 16 of 255, identical pixels are black); prints a Markdown table and
# writes it to out/compare/table.md (and into docs/povray.md with UPDATE_DOCS=1).
set -eu
build=${1:-build}
shift || true
chapters=("$@")
if [ ${#chapters[@]} -eq 0 ]; then
    for program in "$build"/chapter-[0-9][0-9]; do chapters+=("${program##*/chapter-}"); done
fi
out=out/compare
# The options the tests use, from the one place that defines them.
povray_options=$(sed -n 's/^#define POVRAY_OPTIONS "\(.*\)"$/\1/p' common/povray.h)
mkdir -p "$out"
table=$out/table.md
{
    echo "| chapter | scene | size | max abs diff | mean abs diff | px within 1 | px within 2 | PSNR | agrees |"
    echo "|---|---|---|---|---|---|---|---|---|"
} >"$table"
status=0
for n in "${chapters[@]}"; do
    n=$(printf '%02d' "$((10#$n))")
    scene=scenes/$(basename chapters/"$n"-*).scene
    "$build/chapter-$n" "$scene" --quiet -o "$out/chapter-$n-ours.png"
    "$build/chapter-$n" "$scene" --quiet --pov "$out/chapter-$n.pov"
    size=$(awk '$1 == "image" { print $2, $3 }' "$scene")
    width=${size% *}; height=${size#* }
    # Timed in nanoseconds with bash arithmetic (64-bit), so no calculator such as bc is needed.
    start=$(date +%s%N)
    povray +I"$out/chapter-$n.pov" +O"$out/chapter-$n-povray.png" +W"$width" +H"$height" \
        $povray_options >"$out/chapter-$n-povray.log" 2>&1
    elapsed=$(( $(date +%s%N) - start ))
    povray_seconds=$(printf '%d.%03d' $((elapsed / 1000000000)) $((elapsed / 1000000 % 1000)))
    if result=$("$build/compare" "$out/chapter-$n-ours.png" "$out/chapter-$n-povray.png" \
                "$out/chapter-$n-side-by-side.png" "$out/chapter-$n-diff.png"); then
        agrees=yes
    else
        agrees=NO; status=1
    fi
    # result: max M  mean X  within1 P%  within2 Q%  psnr S dB  over2 K
    set -- $result
    echo "| $n | ${scene#scenes/} | ${width}x${height} | $2 | $4 | $6 | $8 | ${10} dB | $agrees |" >>"$table"
    echo "chapter $n: $result (POV-Ray took ${povray_seconds} s)"
done
echo
cat "$table"

# With UPDATE_DOCS=1 (make compare UPDATE_DOCS=1), also copy the table into docs/povray.md, between
# its two markers. Not by default: the walkthroughs' exercises run make compare on deliberately broken
# code, and that must not change a tracked file.
doc=docs/povray.md
if [ "${UPDATE_DOCS:-0}" = 1 ] && [ -f "$doc" ] && grep -q '^<!-- compare-table -->$' "$doc"; then
    awk -v table="$table" '
        /^<!-- compare-table -->$/ { print; while ((getline line < table) > 0) print line; skipping = 1; next }
        /^<!-- \/compare-table -->$/ { skipping = 0 }
        !skipping { print }' "$doc" >"$doc.new" && mv "$doc.new" "$doc"
    echo "updated the table in $doc"
fi
exit $status

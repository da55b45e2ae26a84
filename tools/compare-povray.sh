#!/usr/bin/env bash
# compare-povray.sh BUILD [N...]: renders each chapter's scene with the chapter program and with
# POV-Ray at the same size and writes to out/compare/, for each chapter NN, chapter-NN-side-by-side.png
# (ours | POV-Ray) and chapter-NN-diff.png (|ours - POV-Ray| amplified x16, DIFF_GAIN in tools/compare.c:
# a 1-level difference shows as 16 of 255, identical pixels are black); prints a Markdown table and
# writes it to out/compare/table.md (and into docs/povray.md with UPDATE_DOCS=1).
# A twin from chapter 12 on says how POV-Ray renders it (common/antialias.h): with its anti-aliasing
# options ("// Antialias options: ..."), or at n times the size in 16 bits, each n x n block then
# averaged ("// Antialias box: n"). Chapter 12 is also compared with its regular 3 x 3 grid that way.
# Without N, every chapter whose picture POV-Ray can draw: not chapters 15 and 17, whose path tracer
# solves the rendering equation, which POV-Ray does not (their --pov twin is only the scene's geometry
# and lights); Blender's Cycles checks them instead (make compare-cycles).
set -eu
build=${1:-build}
shift || true
chapters=("$@")
if [ ${#chapters[@]} -eq 0 ]; then
    for program in "$build"/chapter-[0-9][0-9]; do
        case ${program##*/chapter-} in
        15 | 17) ;; # path tracers
        *) chapters+=("${program##*/chapter-}") ;;
        esac
    done
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
# compare_one NN TAG [--set ...]: chapter NN's scene (with the --set changes) by the chapter and by
# POV-Ray, as its twin says; a row of the table.
compare_one() {
    local n=$1 tag=$2
    shift 2
    local scene=scenes/$(basename chapters/"$n"-*).scene
    "$build/chapter-$n" "$scene" --quiet -o "$out/$tag-ours.png" "$@"
    "$build/chapter-$n" "$scene" --quiet --pov "$out/$tag.pov" "$@"
    local size width height options box
    size=$(awk '$1 == "image" { print $2, $3 }' "$scene")
    width=${size% *}; height=${size#* }
    options=$(sed -n 's|^// Antialias options: ||p' "$out/$tag.pov")
    box=$(sed -n 's|^// Antialias box: \([0-9]*\).*|\1|p' "$out/$tag.pov")
    box=${box:-1}
    local big=$out/$tag-povray.png format=""
    if [ "$box" -gt 1 ]; then big=$out/$tag-povray-big.png; format=+FN16; fi
    # Timed in nanoseconds with bash arithmetic (64-bit), so no calculator such as bc is needed.
    local start elapsed povray_seconds result agrees
    start=$(date +%s%N)
    povray +I"$out/$tag.pov" +O"$big" +W$((box * width)) +H$((box * height)) \
        $povray_options $format $options >"$out/$tag-povray.log" 2>&1
    elapsed=$(( $(date +%s%N) - start ))
    povray_seconds=$(printf '%d.%03d' $((elapsed / 1000000000)) $((elapsed / 1000000 % 1000)))
    if result=$("$build/compare" --box "$box" "$out/$tag-ours.png" "$big" \
                "$out/$tag-side-by-side.png" "$out/$tag-diff.png"); then
        agrees=yes
    else
        agrees=NO; status=1
    fi
    # result: max M  mean X  within1 P%  within2 Q%  psnr S dB  over2 K
    set -- $result
    local label=${scene#scenes/}
    [ "$tag" = "chapter-$n" ] || label="$label, ${tag#chapter-$n-}"
    echo "| $n | $label | ${width}x${height} | $2 | $4 | $6 | $8 | ${10} dB | $agrees |" >>"$table"
    echo "chapter $n ($tag): $result (POV-Ray took ${povray_seconds} s)"
}

for n in "${chapters[@]}"; do
    n=$(printf '%02d' "$((10#$n))")
    if [ "$n" = 16 ]; then # POV-Ray 3.7 has no motion blur: the frame at its clock, shutter closed
        compare_one 16 chapter-16 --set camera.shutter=0
        continue
    fi
    compare_one "$n" "chapter-$n"
    if [ "$n" = 12 ]; then
        compare_one 12 chapter-12-grid-3 --set antialias.method=grid --set antialias.samples=3
        compare_one 12 chapter-12-recursive --set antialias.method=recursive
    fi
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

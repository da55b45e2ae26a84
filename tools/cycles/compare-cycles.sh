#!/usr/bin/env bash
# compare-cycles.sh BUILD: chapters 15's and 17's pictures against Blender's Cycles, an independent path
# tracer (make compare-cycles; docs/15-paths.md, "Checked by another renderer", and docs/17-rough.md).
#
# Two scenes: the Cornell box of scenes/15-paths.scene with its mirror and glass balls made white (Cycles'
# glass and ours differ in ways this comparison does not need), at 128 x 128 and 2048 paths a pixel, with
# Cycles finding the lamp by scattering only (render.py's `scatter`; docs/paths-notes.md says why); and
# scenes/15-daylight.scene as it is, at 160 x 120 and 512 paths a pixel, Cycles sampling its lights as it
# does by default. Each renderer draws each scene twice, with seeds 1 and 2: ours into Portable Float
# Maps, Cycles (tools/cycles/render.py, run headless by `blender -b`) into OpenEXR. tools/cycles/compare.py then measures every block's mean in
# combined standard errors and the whole picture's mean; the table goes to out/cycles/table.md, the
# pictures side by side (ours | Cycles) to out/cycles/NAME-side-by-side.png, and with UPDATE_DOCS=1 the
# table into docs/15-paths.md between its cycles-table markers. Exits 1 when a scene disagrees.
#
# Chapter 17 adds two more, drawn by build/chapter-17 at 96 x 64 and 1024 paths a pixel: its own scene
# with the gold ball made a white rough mirror (Cycles' Glossy BSDF has no metal's Fresnel), and Veach's
# plates (scenes/17-veach.scene), both with the overhead emitting rectangle replaced by a uniform sky
# (Cycles 3.4 chooses the emitting triangles it samples by their area, so that the large rectangle took
# nearly all its light samples and the small lamps' light came from rare scattered paths, too noisy to
# compare at 1024 paths). Their rows go to out/cycles/table-17.md and, with UPDATE_DOCS=1, into
# docs/17-rough.md. Cycles 3.4 writes its GGX lobes differently from chapter 17: masking by two separate
# terms G1(wo) G1(wi) (chapter 17: the height-correlated G2), and its Glass BSDF weighs reflection and
# refraction by the Fresnel of the surface's normal (chapter 17: of each microfacet), which lets about 1 %
# less light through the frosted ball. So our side of these two scenes is drawn with `--form cycles-3.4`,
# the option that exists for this comparison only.
#
# Chapter 16's motion blur (docs/16-instances.md, "Checked against Cycles"): scenes/16-blur.scene, flat
# bunnies moving under an open shutter, 256 camera samples a pixel in each renderer (jitter 16 x 16 for
# ours), Cycles' object motion blur built by tools/cycles/motion.py, compared by compare.py in blocks of
# 8 x 8; its row goes to out/cycles/table-16.md. `compare-cycles.sh BUILD blur [ARG...]` runs only that
# comparison, passing the ARGs to chapter 16 (a test plants a wrong shutter this way). CHAPTERS="15 16 17"
# (the default) names the chapters compared. CYCLES_OUT names the folder (default out/cycles).
set -euo pipefail # a pipeline fails when compare.py does (a scene that disagrees)
build=${1:-build}
only=${2:-}
out=${CYCLES_OUT:-out/cycles} # where the pictures and tables go
threads=${CYCLES_THREADS:-2}
block=16
mkdir -p "$out"
blender_run() { blender -b --factory-startup --python-exit-code 1 --python "$@"; }

# start_table TABLE: the table's head.
start_table() {
    table=$1
    {
        echo "| scene | blocks | worst \|z\| | blocks within 2 errors | mean z² | our mean | Cycles' mean | difference | verdict |"
        echo "|---|---|---|---|---|---|---|---|---|"
    } >"$table"
}
# update_doc DOC: the table into DOC between its cycles-table markers (with UPDATE_DOCS=1).
update_doc() {
    [ "${UPDATE_DOCS:-}" = 1 ] || return 0
    awk -v table="$table" '/<!-- cycles-table -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
                           /<!-- \/cycles-table -->/ { skip = 0 } !skip' "$1" >"$1.tmp" && mv "$1.tmp" "$1"
}
status=0
# compare_one NAME SCENE SAMPLES [scatter]: both renderers, both seeds, and the row of the table; ours is
# drawn by build/chapter-$chapter.
compare_one() {
    local name=$1 scene=$2 samples=$3 seed
    shift 3
    for seed in 1 2; do
        "$build/chapter-$chapter" "$scene" --quiet --threads "$threads" --set paths.samples="$samples" \
            --set paths.seed="$seed" "${ours_options[@]}" -o "$out/$name-ours-$seed.png" --hdr "$out/$name-ours-$seed.pfm"
        blender_run tools/cycles/render.py -- "$scene" "$PWD/$out/$name-cycles-$seed.exr" "$samples" "$seed" \
            "$threads" "$@" >"$out/$name-cycles-$seed.log" 2>&1 ||
            { echo "compare-cycles.sh: Blender failed on $scene (see $out/$name-cycles-$seed.log)" >&2; exit 2; }
    done
    blender_run tools/cycles/compare.py -- "$name" "$block" "$out/$name-ours-1.pfm" "$out/$name-ours-2.pfm" \
        "$out/$name-cycles-1.exr" "$out/$name-cycles-2.exr" "$PWD/$out/$name-side-by-side.png" 2>"$out/$name-compare.log" |
        grep '^|' >>"$table" || status=1
}

# compare_blur [ARG...]: chapter 16's motion blur against Cycles', the row into table-16.md.
compare_blur() {
    local name=blur scene=scenes/16-blur.scene seed table16=$out/table-16.md
    start_table "$table16"
    table=$table16
    for seed in 1 2; do
        "$build/chapter-16" "$scene" --quiet --threads "$threads" --set antialias.samples=16 \
            --set antialias.seed="$seed" "$@" -o "$out/$name-ours-$seed.png"
        blender_run tools/cycles/motion.py -- "$scene" "$PWD/$out/$name-cycles-$seed.exr" 256 "$seed" "$threads" \
            >"$out/$name-cycles-$seed.log" 2>&1 ||
            { echo "compare-cycles.sh: Blender failed on $scene (see $out/$name-cycles-$seed.log)" >&2; exit 2; }
    done
    blender_run tools/cycles/compare.py -- "$name" 8 "$out/$name-ours-1.png" "$out/$name-ours-2.png" \
        "$out/$name-cycles-1.exr" "$out/$name-cycles-2.exr" "$PWD/$out/$name-side-by-side.png" 2>"$out/$name-compare.log" |
        grep '^|' >>"$table" || status=1
    cat "$table"
}
if [ "$only" = blur ]; then
    shift 2
    compare_blur "$@"
    exit $status
fi

chapters=" ${CHAPTERS:-15 16 17} "
if [[ $chapters == *" 15 "* ]]; then
    # The Cornell box at 128 x 128 with white balls; the daylight scene at 160 x 120.
    chapter=15
    ours_options=()
    start_table "$out/table.md"
    sed -e 's/^image .*/image 128 128/' \
        -e 's/^material mirror .*/material mirror colour 0.725 0.71 0.68 ambient 0 diffuse 1/' \
        -e 's/^material glass .*/material glass  colour 0.725 0.71 0.68 ambient 0 diffuse 1/' \
        scenes/15-paths.scene >"$out/cornell.scene"
    sed -e 's/^image .*/image 160 120/' scenes/15-daylight.scene >"$out/daylight.scene"
    compare_one cornell "$out/cornell.scene" 2048 scatter
    compare_one daylight "$out/daylight.scene" 512
    cat "$table"
    update_doc docs/15-paths.md
fi
if [[ $chapters == *" 16 "* ]]; then
    compare_blur
fi
if [[ $chapters == *" 17 "* ]]; then
    # Chapter 17's scene with a white rough mirror for the gold ball, and Veach's plates, at 96 x 64, the
    # overhead light replaced by a uniform sky of 0.2 (background 0.2 0.2 0.2).
    chapter=17
    # --form cycles-3.4: our lobes written as Cycles 3.4 writes them, for this comparison only (the
    # chapter's pictures keep the chapter's form).
    ours_options=(--form cycles-3.4)
    start_table "$out/table-17.md"
    uniform_sky=(-e 's/^image .*/image 96 64/' -e 's/^background .*/background 0.2 0.2 0.2/' -e '/ material sky$/d')
    sed "${uniform_sky[@]}" -e 's/ metal gold / /' scenes/17-rough.scene >"$out/rough.scene"
    sed "${uniform_sky[@]}" scenes/17-veach.scene >"$out/plates.scene"
    compare_one rough "$out/rough.scene" 1024
    compare_one plates "$out/plates.scene" 1024
    cat "$table"
    update_doc docs/17-rough.md
fi
exit $status

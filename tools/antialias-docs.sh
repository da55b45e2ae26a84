#!/usr/bin/env bash
# antialias-docs.sh: the pictures and measurements of chapter 12's walkthrough (docs/12-antialias.md).
#
#   tools/antialias-docs.sh BUILD pictures   docs/images/12-*.png: the chapter's scene by one ray and by
#                                            each method, whole and enlarged, and the heat-maps
#   tools/antialias-docs.sh BUILD measure    docs/results/antialias.csv: for each method and n, camera rays
#                                            per pixel, processor time (one thread, best of RUNS, default
#                                            3) and the error against a reference; then plot (minutes)
#   tools/antialias-docs.sh BUILD plot       docs/results/antialias-error.svg and antialias-time.svg from
#                                            the CSV (gnuplot)
#   tools/antialias-docs.sh BUILD --check    exit 1 when a committed plot is not what plot draws now
#
# The reference is as near the true mean over each pixel as the machine can afford: 16 x 16 jittered
# rays a pixel at twice the width and height, averaged 2 x 2 (1,024 rays a pixel, noise only, no
# aliasing). The error of a picture is its mean difference from the reference, in 8-bit levels over
# every channel of every pixel, and the share of its pixels more than 2 levels off.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: tools/antialias-docs.sh BUILD pictures|measure|plot|--check}
mode=${2:?usage: tools/antialias-docs.sh BUILD pictures|measure|plot|--check}
scene=scenes/12-antialias.scene
csv=docs/results/antialias.csv
work=out/antialias
mkdir -p "$work"

# render NAME ARGS...: chapter 12 on its scene into $work/NAME.png
render() {
    local name=$1
    shift
    "$build/chapter-12" "$scene" --quiet -o "$work/$name.png" "$@"
}

pictures() {
    render none --set antialias.method=none
    render adaptive
    render grid --set antialias.method=grid --set antialias.samples=4
    render jitter --set antialias.method=jitter --set antialias.samples=4
    render recursive --set antialias.method=recursive
    # The region: the pole's top and its wire, the mirror's edge and the floor's lines at the horizon.
    local region=(138 74 80 48)
    "$build/inset" docs/images/12-one-ray-and-adaptive.png "${region[@]}" 0 "$work/none.png" "$work/adaptive.png"
    "$build/inset" docs/images/12-enlarged.png "${region[@]}" 3 "$work/none.png" "$work/grid.png" "$work/jitter.png" \
        "$work/adaptive.png"
    "$build/chapter-12" "$scene" --quiet -o "$work/adaptive.png" --heatmap docs/images/12-heatmap-adaptive.png
    "$build/chapter-12" "$scene" --quiet -o "$work/recursive.png" --set antialias.method=recursive \
        --heatmap docs/images/12-heatmap-recursive.png
}

# The methods and sizes measured: METHOD N THRESHOLD, one a line.
runs_list() {
    for n in 1 2 3 4 6 8; do echo "grid $n 0.3"; done
    for n in 1 2 3 4 6 8; do echo "jitter $n 0.3"; done
    for n in 2 3 4 6 8; do echo "adaptive $n 0.3"; done
    for n in 2 3 4 6 8; do echo "adaptive $n 0.1"; done
    for n in 2 3 4 5 6; do echo "recursive $n 0.3"; done
}

measure() {
    local repeats=${RUNS:-3}
    "$build/chapter-12" "$scene" --quiet -o "$work/reference-big.png" --width 640 --height 480 --threads 1 \
        --set antialias.method=jitter --set antialias.samples=16 --set antialias.seed=99
    mkdir -p docs/results
    echo "method,samples,threshold,camera_rays_per_pixel,cpu_best_s,mean_error,pixels_over_2_percent" >"$csv.new"
    runs_list | while read -r method n threshold; do
        local best="" rays
        for _ in $(seq "$repeats"); do
            "$build/measure" "$work/cost" "$build/chapter-12" "$scene" -o "$work/run.png" --threads 1 \
                --set antialias.method="$method" --set antialias.samples="$n" --set antialias.threshold="$threshold" \
                >"$work/run.txt"
            local cpu
            cpu=$(awk '{ print $1 }' "$work/cost")
            best=$(awk -v a="$cpu" -v b="$best" 'BEGIN { print (b == "" || a + 0 < b + 0) ? a : b }')
        done
        # one ray a pixel prints no camera-ray line: 1
        rays=$(awk '$1 == "camera" && $2 == "rays" { print $3 }' "$work/run.txt")
        local result
        result=$("$build/compare" --box 2 "$work/run.png" "$work/reference-big.png" || true)
        # result: max M  mean X  within1 P%  within2 Q%  psnr S dB  over2 K
        awk -v m="$method" -v n="$n" -v t="$threshold" -v r="${rays:-1.00}" -v c="$best" -v res="$result" 'BEGIN {
            split(res, f, " ")
            printf "%s,%s,%s,%s,%s,%s,%.3f\n", m, n, t, r, c, f[4], 100 * f[13] / (320 * 240) }' >>"$csv.new"
        echo "$method $n $threshold: $(tail -n 1 "$csv.new")"
    done
    mv "$csv.new" "$csv"
}

# plot DATA FIGURES: the two plots from DATA (the CSV) into the folder FIGURES.
plot() {
    local data=$1 figures=$2 series
    series=$(mktemp -d)
    for key in "grid 0.3" "jitter 0.3" "adaptive 0.3" "adaptive 0.1" "recursive 0.3"; do
        set -- $key
        awk -F, -v m="$1" -v t="$2" 'NR > 1 && $1 == m && $3 == t { print $4, $6, $5 }' "$data" >"$series/$1-$2"
    done
    gnuplot -e "series='$series'; figures='$figures'" tools/antialias-plots.gp
    rm -rf "$series"
}

case $mode in
pictures) pictures ;;
measure)
    measure
    plot "$csv" docs/results
    ;;
plot) plot "$csv" docs/results ;;
--check)
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    plot "$csv" "$tmp"
    status=0
    for svg in "$tmp"/*.svg; do
        if ! cmp -s "$svg" "docs/results/$(basename "$svg")"; then
            echo "docs/results/$(basename "$svg") is stale against $csv: tools/antialias-docs.sh BUILD plot redraws it" >&2
            status=1
        fi
    done
    exit $status
    ;;
*)
    echo "usage: tools/antialias-docs.sh BUILD pictures|measure|plot|--check" >&2
    exit 2
    ;;
esac

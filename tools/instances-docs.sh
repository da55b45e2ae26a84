#!/usr/bin/env bash
# instances-docs.sh: the measurements and plot of chapter 16's walkthrough (docs/16-instances.md), refit
# against rebuild over an animation.
#
#   tools/instances-docs.sh BUILD measure   docs/results/instances-refit.csv: a swarm of SIDE x SIDE
#                                           instances (default 20 x 20) that each cross the field from one
#                                           grid point to another over the clock, rendered as FRAMES frames
#                                           (default 21) with --refit, --rebuild and the default rule, one
#                                           thread; per frame the top level's SAH cost, the cost it had
#                                           when last built, the time of its refit or build and of the
#                                           frame; then plot (a minute or two)
#   tools/instances-docs.sh BUILD plot      docs/results/instances-refit.svg from the CSV (gnuplot)
#
# The swarm is written to out/instances/swarm.scene: instance k starts at grid point k and ends at grid
# point (k * 173 + 71) mod SIDE^2 (a shuffle: 173 is prime to 400), turning half a turn as it goes, so
# that by the last frame neighbours in the tree built at clock 0 are scattered over the whole field, the
# worst case for a refit. Deterministic: the same file on every machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: tools/instances-docs.sh BUILD measure|plot}
mode=${2:?usage: tools/instances-docs.sh BUILD measure|plot}
side=${SIDE:-20}
frames=${FRAMES:-21}
csv=docs/results/instances-refit.csv
work=out/instances
mkdir -p "$work"

swarm() {
    awk -v side="$side" 'BEGIN {
        n = side * side
        print "# Chapter 16 walkthrough measurement (tools/instances-docs.sh): " n " instances crossing the field."
        print "camera eye 0 34 26  target 0 0 0  fov 45"
        print "image 320 240"
        print "background 0.55 0.65 0.8"
        print "light position -10 30 20  colour 1 1 1"
        print "material ground colour 0.45 0.55 0.35 ambient 0.15 diffuse 0.75"
        print "material china colour 0.35 0.55 0.85 ambient 0.1 diffuse 0.7 phong 0.8 phong_size 120"
        print "material clay colour 0.8 0.5 0.3 ambient 0.1 diffuse 0.8"
        print "object teapot ../../scenes/models/teapot-5k.ply"
        print "object bunny ../../scenes/models/bunny.ply"
        print "plane normal 0 1 0 distance 0  material ground"
        for (k = 0; k < n; k++) {
            to = (k * 173 + 71) % n
            x0 = 2 * (k % side) - side + 1; z0 = 2 * int(k / side) - side + 1
            x1 = 2 * (to % side) - side + 1; z1 = 2 * int(to / side) - side + 1
            if (k % 2 == 0)
                printf "instance teapot material china scale 0.25 0.25 0.25 id i%d\n", k
            else
                printf "instance bunny material clay scale 0.12 0.12 0.12 id i%d\n", k
            printf "key i%d time 0 translate %d 0 %d\n", k, x0, z0
            printf "key i%d time 1 translate %d 0 %d rotate 0 180 0\n", k, x1, z1
        }
    }' >"$work/swarm.scene"
}

# run MODE OPTION: renders the frames with OPTION (--refit, --rebuild or nothing) and prints one CSV row a
# frame: mode, frame, SAH cost, SAH cost when last built, top level's time (ms), frame's time (s).
run() {
    local mode=$1 option=$2
    "$build/chapter-16" "$work/swarm.scene" --frames "$frames" $option --stats --threads 1 -o "$work/swarm-$mode.png" |
        awk -v mode="$mode" '
            /wrote .* in [0-9.]+ s$/ { frame++; seconds = $(NF - 1) }
            /^  top level  .* in [0-9.]+ ms$/ { top = $(NF - 1) }
            /^  top level SAH cost/ { cost = $5; built = $6; sub(/^\(/, "", built)
                                      printf "%s,%d,%s,%s,%s,%s\n", mode, frame, cost, built, top, seconds }'
}

measure() {
    swarm
    {
        echo "mode,frame,sah_cost,sah_cost_built,top_ms,frame_s"
        run refit --refit
        run rebuild --rebuild
        run auto ""
    } >"$csv.new"
    mv "$csv.new" "$csv"
    plot
}

plot() {
    command -v gnuplot >/dev/null || { echo "gnuplot is not installed" >&2; exit 1; }
    local series=$work/series
    mkdir -p "$series"
    for m in refit rebuild auto; do
        awk -F, -v m="$m" '$1 == m { print $2, $3, $6 }' "$csv" >"$series/$m"
    done
    gnuplot -e "series='$series'; figures='docs/results'" tools/instances-plots.gp
}

case $mode in
measure) measure ;;
plot) plot ;;
*) echo "usage: tools/instances-docs.sh BUILD measure|plot" >&2; exit 2 ;;
esac

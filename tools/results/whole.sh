#!/usr/bin/env bash
# whole.sh: the whole program against POV-Ray 3.7 on the large model, in paired runs (make results runs
# it from tools/results/run.sh; it also runs alone).
#
#   tools/results/whole.sh OUTDIR [--quick]      writes OUTDIR/whole.csv
#
# What is compared. Each side does everything a user waits for, from the command's start to its exit:
# ours (chapter 11 at its default rung) reads the scene and the binary PLY model, builds its hierarchy,
# renders and writes the PNG; POV-Ray parses the scene's twin (chapter 10's --pov: the same model as a
# mesh2 in POV-Ray's own language, which is how POV-Ray reads a mesh), builds its bounding hierarchy,
# renders and writes its PNG. The same picture (scenes/results/seed-large.scene, 800 x 600, depth 1),
# the same threads: one (POV-Ray's +WT1 against our --threads 1), then every core (+WTn against
# --threads n). The clock is the wall clock of the whole process (tools/results/measure.c): with more
# than one thread, processor time would add the threads up.
#
# Paired runs: ours, then POV-Ray's, PAIRS times, after one unpaired run of each (the files then come
# from the file cache, as they do for a user who renders twice). The ratio is POV-Ray's time over ours,
# taken pair by pair: when a shared machine slows down, it slows both sides of a pair, which the ratio
# cancels. whole.csv has one row per thread count: the median of each side's times and of the ratios,
# the smallest and largest ratio, and the load average before and after.
#
# --quick: the same at 100 x 75, one pair, no warm-up (make test-long tests the pipeline with it).
# Environment: BUILD (default build) holds chapter-10, chapter-11 and measure.
set -euo pipefail
cd "$(dirname "$0")/../.."

if [ $# -lt 1 ] || [ $# -gt 2 ] || { [ $# -eq 2 ] && [ "$2" != --quick ]; }; then
    echo "usage: tools/results/whole.sh OUTDIR [--quick]" >&2
    exit 2
fi
out=$1
quick=$([ "${2:-}" = --quick ] && echo 1 || echo 0)
build=${BUILD:-build}
scene=scenes/results/seed-large.scene
if [ "$quick" -eq 1 ]; then
    W=100 H=75 PAIRS=1 WARMUP=0
else
    W=800 H=600 PAIRS=7 WARMUP=1
fi
DEPTH=1
cores=$(getconf _NPROCESSORS_ONLN) # as the tests count them (sysconf)
thread_counts=1
[ "$cores" -gt 1 ] && thread_counts="1 $cores"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/chapter-10" "$scene" --quiet --set max_depth=$DEPTH --width $W --height $H --pov "$work/twin.pov"

# timed COMMAND...: runs COMMAND under measure, its output thrown away; prints "WALL CPU".
timed() {
    "$build/measure" "$work/cost" "$@" >/dev/null 2>"$work/errors" || {
        cat "$work/errors" >&2
        echo "whole.sh: failed: $*" >&2
        exit 1
    }
    local cpu wall
    read -r cpu wall _ <"$work/cost"
    echo "$wall $cpu"
}

# The median of numbers, one a line on standard input.
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# The median of column C of the pairs: 1 ours (wall), 2 POV-Ray's (wall), 3 ours (cpu), 4 POV-Ray's (cpu).
column() { awk -v c="$1" '{ print $c }' "$work/pairs" | median; }

csv=$out/whole.csv
mkdir -p "$out"
echo "threads,pairs,width,height,ours_wall_median_s,povray_wall_median_s,ratio_median,ratio_min,ratio_max,ours_cpu_median_s,povray_cpu_median_s,load_before,load_after" >"$csv.tmp"
for threads in $thread_counts; do
    ours=("$build/chapter-11" "$scene" --quiet --threads "$threads" --set max_depth="$DEPTH" --width "$W" --height "$H"
        -o "$work/ours.png")
    povray=(povray +I"$work/twin.pov" +O"$work/povray.png" +W"$W" +H"$H" -D -P -V -A +FN8 -UA File_Gamma=1.0
        Dither=off +Q9 -GA +GF +WT"$threads")
    load_before=$(cut -d' ' -f1 /proc/loadavg)
    for ((k = 0; k < WARMUP; k++)); do
        timed "${ours[@]}" >/dev/null
        timed "${povray[@]}" >/dev/null
    done
    : >"$work/pairs"
    for ((k = 0; k < PAIRS; k++)); do
        read -r ours_wall ours_cpu < <(timed "${ours[@]}")
        read -r pov_wall pov_cpu < <(timed "${povray[@]}")
        echo "$ours_wall $pov_wall $ours_cpu $pov_cpu" >>"$work/pairs"
    done
    ratios=$(awk '{ printf "%.6f\n", $2 / $1 }' "$work/pairs" | sort -g)
    echo "$threads,$PAIRS,$W,$H,$(column 1),$(column 2),$(median <<<"$ratios"),$(head -1 <<<"$ratios"),$(tail -1 <<<"$ratios"),$(column 3),$(column 4),$load_before,$(cut -d' ' -f1 /proc/loadavg)" >>"$csv.tmp"
    printf '  whole process, %d thread(s): POV-Ray %.3f s, ours %.3f s (medians); POV-Ray / ours %.1f x (median of %d pairs)\n' \
        "$threads" "$(column 2)" "$(column 1)" "$(median <<<"$ratios")" "$PAIRS" >&2
done
mv "$csv.tmp" "$csv"

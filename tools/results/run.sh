#!/usr/bin/env bash
# run.sh: runs the seed dissertation's experiments on this code and writes one CSV per experiment
# (make results; docs/results.md shows them).
#
#   tools/results/run.sh [--quick] OUTDIR
#
# Writes into OUTDIR:
#   scene1.csv      the seed's first scene (bunny, two spheres, plane): depths 1-5 at 200x200 and
#                   800x400, one light and two, brute force beside the kd-tree, both BVH rules, POV-Ray
#   bunny.csv       the bunny at 800x600, depths 1-5, the same structures
#   teapot-5k.csv   the 5,112-triangle teapot, the same way
#   large.csv       the 349,872-triangle teapot at depth 1 (the seed's Armadillo experiment), chapter
#                   11 too; brute force sampled on a coarser grid and scaled up
#   scaling.csv     teapots of 1,000 to 4,000,000 triangles: build time, frame time, peak memory
#   threads.csv     chapters 10 and 11 on chapter 10's scene on 1, 2 (and more) threads
#   whole.csv       chapter 11 against POV-Ray 3.7 on the large model, the whole process by the wall
#                   clock, paired runs on one thread and on every core (tools/results/whole.sh)
#   accel.csv       the acceleration benchmark against Embree (bench/bench_accel.c; full mode only)
#   machine.csv     when, where and how the numbers were taken
#   *.png           a picture of each scene (chapter 10), 400 pixels wide (50 in the quick run)
#
# Every run is one process: its processor time (user and system), peak memory and counters are taken
# by tools/results/measure.c and from the chapter's own report (--stats). Runs that would take too
# long (brute force on big models) render a coarser grid of the same picture, and their time and
# counters are scaled up by the ratio of pixels; their rows say so (measured_width, measured_height
# and scale > 1). --quick runs the same experiments on small pictures and models, once each, in about
# a minute, so the pipeline can be tested (make test-long does).
#
# Environment: BUILD (default build) holds the chapters, compare, measure and bench_accel; TEAPOT
# (default build/teapot) is the teapot generator, tools/models/teapot.c.
set -euo pipefail
cd "$(dirname "$0")/../.."

quick=0
if [ "${1:-}" = --quick ]; then
    quick=1
    shift
fi
if [ $# -ne 1 ]; then
    echo "usage: tools/results/run.sh [--quick] OUTDIR" >&2
    exit 2
fi
out=$1
build=${BUILD:-build}
teapot=${TEAPOT:-build/teapot}
mkdir -p "$out"
work=$out/work
rm -rf "$work"
mkdir -p "$work"

# ---- settings: the full run and the quick one ------------------------------------------------------
# DIV divides every picture's width and height; RUNS is how often a fast run is repeated (best and
# median kept; a run longer than LONG_RUN_S seconds is not repeated); the brute force is sampled when
# it would cost more than BRUTE_BUDGET triangle tests per frame (about 8 ns each).
if [ $quick -eq 1 ]; then
    DIV=8 RUNS=1 LARGE_RUNS=1 THREAD_RUNS=2 BRUTE_BUDGET=2e8
    SCALING_SIZES="1000 4000 16000"
    SCALING_W=80 SCALING_H=60
else
    DIV=1 RUNS=3 LARGE_RUNS=5 THREAD_RUNS=7 BRUTE_BUDGET=3e9
    SCALING_SIZES="1000 4000 16000 64000 256000 1000000 4000000"
    SCALING_W=640 SCALING_H=480
fi
LONG_RUN_S=2
DEPTHS="1 2 3 4 5"
SWEEP_STRUCTURES="none kd-sah bvh-median bvh-sah povray"
LARGE_STRUCTURES="none kd-seed kd-sah bvh-median bvh-sah fast povray"
SCALING_STRUCTURES="none kd-sah bvh-median bvh-sah fast"
# The brute force on the scaling teapots: sampled to about this many triangle tests per camera ray
# set (8 ns a test: about 8 s per size in the full run).
SCALING_BRUTE_BUDGET=$([ $quick -eq 1 ] && echo 2e7 || echo 1e9)

SWEEP_HEADER=scene,width,height,lights,depth,structure,runs,cpu_best_s,cpu_median_s,build_ms,render_s,rays,triangle_tests,peak_rss_mb,measured_width,measured_height,scale,povray_max_diff,povray_pixels_over_2

# ---- one run ----------------------------------------------------------------------------------------
# The command line of STRUCTURE for SCENE (one word a line; POV-Ray's is built where it is run).
program_for() { # program_for STRUCTURE
    case $1 in
    none) echo "$build/chapter-10 --accel none" ;;
    kd-seed) echo "$build/chapter-10 --accel kdtree --split seed" ;;
    kd-sah) echo "$build/chapter-10 --accel kdtree" ;;
    bvh-median) echo "$build/chapter-10 --split seed" ;;
    bvh-sah) echo "$build/chapter-10" ;;
    fast) echo "$build/chapter-11" ;;
    *) echo "run.sh: unknown structure $1" >&2; exit 2 ;;
    esac
}

# The value after LABEL in a chapter's report: `counter LABEL FILE` (first match; empty if none).
counter() {
    awk -v label="$1" 'index($0, "  " label " ") == 1 { print $NF; exit }' "$2"
}
build_ms_of() { awk '$1 == "build" && $3 == "ms" { print $2; exit }' "$1"; }
render_s_of() { awk '/: wrote .* in [0-9.]+ s$/ { print $(NF - 1); exit }' "$1"; }

# The best (smallest) and the median of numbers, one a line on standard input: "BEST MEDIAN".
best_and_median() {
    sort -g | awk '{ v[NR] = $1 } END { m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
                                       printf "%s %s\n", v[1], m }'
}

# repeat RUNS COMMAND...: runs COMMAND up to RUNS times under measure (a run of more than LONG_RUN_S
# seconds is not repeated: its noise is small beside it); sets CPU_BEST CPU_MEDIAN PEAK_MB RUNS_DONE,
# and keeps the best run's standard output in $work/report. Stops the script when a run fails.
repeat() {
    local runs=$1
    shift
    local cpus=() r cpu peak best=
    for ((r = 0; r < runs; r++)); do
        [ $r -gt 0 ] && awk -v a="$best" -v b="$LONG_RUN_S" 'BEGIN { exit !(a > b) }' && break
        "$build/measure" "$work/cost" "$@" >"$work/output" 2>"$work/errors" || {
            cat "$work/errors" >&2
            echo "run.sh: failed: $*" >&2
            exit 1
        }
        read -r cpu _ peak <"$work/cost"
        cpus+=("$cpu")
        if [ -z "$best" ] || awk -v a="$cpu" -v b="$best" 'BEGIN { exit !(a < b) }'; then
            best=$cpu
            mv "$work/output" "$work/report"
            PEAK_MB=$(awk -v k="$peak" 'BEGIN { printf "%.1f", k / 1024 }')
        fi
    done
    read -r CPU_BEST CPU_MEDIAN < <(printf '%s\n' "${cpus[@]}" | best_and_median)
    RUNS_DONE=${#cpus[@]}
}

# run_chapter STRUCTURE SCENE W H DEPTH RUNS [EXTRA...]: the chapter, RUNS times (see repeat); sets
# also BUILD_MS RENDER_S RAYS TESTS, from the best run's report.
run_chapter() {
    local structure=$1 scene=$2 w=$3 h=$4 depth=$5 runs=$6
    shift 6
    # shellcheck disable=SC2046
    repeat "$runs" $(program_for "$structure") "$scene" --threads 1 --stats --set max_depth="$depth" \
        --width "$w" --height "$h" -o "$work/$structure.png" "$@"
    BUILD_MS=$(build_ms_of "$work/report")
    RENDER_S=$(render_s_of "$work/report")
    RAYS=$(counter "rays (all)" "$work/report")
    TESTS=$(counter "triangle tests" "$work/report")
}

# run_povray SCENE W H DEPTH RUNS: POV-Ray 3.7 on the scene's twin, on one thread, with the command
# line the twin names (see repeat); sets also MAX_DIFF OVER_2, its picture against bvh-sah.png.
run_povray() {
    local scene=$1 w=$2 h=$3 depth=$4 runs=$5
    "$build/chapter-10" "$scene" --quiet --set max_depth="$depth" --width "$w" --height "$h" --pov "$work/twin.pov"
    repeat "$runs" povray +I"$work/twin.pov" +O"$work/povray.png" +W"$w" +H"$h" -D -P -V -A +FN8 -UA \
        File_Gamma=1.0 Dither=off +Q9 -GA +GF +WT1
    local agreement
    agreement=$("$build/compare" "$work/bvh-sah.png" "$work/povray.png")
    MAX_DIFF=$(awk '{ print $2 }' <<<"$agreement")
    OVER_2=$(awk '{ print $NF }' <<<"$agreement")
}

# The measured grid for a W x H frame of TRIANGLES triangles: W/k x H/k for the smallest whole k
# that keeps W/k * H/k * TRIANGLES within BUDGET (k = 1: the whole frame). Prints "MW MH".
sample_grid() { # sample_grid W H TRIANGLES BUDGET
    awk -v w="$1" -v h="$2" -v n="$3" -v budget="$4" 'BEGIN {
        for (k = 1; int(w / k) * int(h / k) * n > budget && int(w / k) > 4 && int(h / k) > 3; k++) ;
        printf "%d %d\n", int(w / k), int(h / k) }'
}

# The triangles of a scene's meshes, from their PLY headers.
scene_triangles() { # scene_triangles SCENE
    local dir total=0 mesh n
    dir=$(dirname "$1")
    while read -r mesh; do
        n=$(awk '/^element face/ { print $3; exit }' "$dir/$mesh")
        total=$((total + n))
    done < <(awk '$1 == "mesh" { print $2 }' "$1")
    echo $total
}

# sweep_row CSV NAME SCENE W H LIGHTS DEPTH STRUCTURE RUNS: one row of a sweep experiment.
sweep_row() {
    local csv=$1 name=$2 scene=$3 w=$4 h=$5 lights=$6 depth=$7 structure=$8 runs=$9
    local mw=$w mh=$h scale=1 max_diff= over2=
    BUILD_MS= RENDER_S= RAYS= TESTS=
    if [ "$structure" = povray ]; then
        run_povray "$scene" "$w" "$h" "$depth" "$runs"
        max_diff=$MAX_DIFF over2=$OVER_2
    else
        if [ "$structure" = none ]; then
            read -r mw mh < <(sample_grid "$w" "$h" "$(scene_triangles "$scene")" "$BRUTE_BUDGET")
            scale=$(awk -v a=$((w * h)) -v b=$((mw * mh)) 'BEGIN { printf "%.6g", a / b }')
            [ "$mw" -ne "$w" ] && runs=1 # a sampled frame is long enough to be timed once
        fi
        run_chapter "$structure" "$scene" "$mw" "$mh" "$depth" "$runs"
        if [ "$scale" != 1 ]; then
            read -r CPU_BEST CPU_MEDIAN RENDER_S RAYS TESTS < <(awk -v s="$scale" -v a="$CPU_BEST" -v b="$CPU_MEDIAN" \
                -v c="$RENDER_S" -v d="$RAYS" -v e="$TESTS" 'BEGIN { printf "%.4f %.4f %.4f %.0f %.0f\n", a * s, b * s, c * s, d * s, e * s }')
        fi
    fi
    echo "$name,$w,$h,$lights,$depth,$structure,$RUNS_DONE,$CPU_BEST,$CPU_MEDIAN,$BUILD_MS,$RENDER_S,$RAYS,$TESTS,$PEAK_MB,$mw,$mh,$scale,$max_diff,$over2" >>"$csv"
    printf '  %-18s %4dx%-4d depth %d  %-10s %10.3f s\n' "$name" "$w" "$h" "$depth" "$structure" "$CPU_BEST" >&2
}

# sweep CSV NAME SCENE W H LIGHTS STRUCTURES: every depth, every structure (bvh-sah before povray,
# which is compared with its picture).
sweep() {
    local csv=$1 name=$2 scene=$3 w=$(($4 / DIV)) h=$(($5 / DIV)) lights=$6 structures=$7 depth s
    for depth in $DEPTHS; do
        for s in $structures; do
            sweep_row "$csv" "$name" "$scene" "$w" "$h" "$lights" "$depth" "$s" "$RUNS"
        done
    done
}

started=$(date +%s)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)

# ---- 1. the seed's first scene ---------------------------------------------------------------------
echo "1. the seed's first scene: depths 1-5, two sizes, one light and two" >&2
csv=$work/scene1.csv
echo "$SWEEP_HEADER" >"$csv"
for size in "200 200" "800 400"; do
    read -r w h <<<"$size"
    sweep "$csv" scene1 scenes/results/seed-scene-1.scene "$w" "$h" 1 "$SWEEP_STRUCTURES"
    sweep "$csv" scene1-two-lights scenes/results/seed-scene-1-two-lights.scene "$w" "$h" 2 "$SWEEP_STRUCTURES"
done

# ---- 2 and 3. the bunny and the 5k teapot ------------------------------------------------------------
for model in bunny teapot-5k; do
    echo "2/3. $model at 800x600, depths 1-5" >&2
    csv=$work/$model.csv
    echo "$SWEEP_HEADER" >"$csv"
    sweep "$csv" "$model" "scenes/results/seed-$model.scene" 800 600 1 "$SWEEP_STRUCTURES"
done

# ---- 4. the large model at depth 1 -------------------------------------------------------------------
echo "4. the 349,872-triangle teapot at 800x600, depth 1" >&2
csv=$work/large.csv
echo "$SWEEP_HEADER" >"$csv"
for s in $LARGE_STRUCTURES; do
    sweep_row "$csv" teapot-346k scenes/results/seed-large.scene $((800 / DIV)) $((600 / DIV)) 1 1 "$s" "$LARGE_RUNS"
done

# ---- how cost grows with the model ---------------------------------------------------------------
echo "scaling: teapots of $SCALING_SIZES triangles at ${SCALING_W}x$SCALING_H, depth 1" >&2
csv=$work/scaling.csv
echo "triangles,structure,runs,build_ms,render_s,cpu_best_s,peak_rss_mb,rays,triangle_tests,measured_width,measured_height,scale" >"$csv"
models=out/models
mkdir -p "$models"
for size in $SCALING_SIZES; do
    ply=$models/teapot-$size.ply
    if [ ! -s "$ply" ]; then # made once, kept in out/models/ (written under a temporary name first)
        "$teapot" --triangles "$size" "$ply.tmp.ply" >/dev/null
        mv "$ply.tmp.ply" "$ply"
    fi
    triangles=$(awk '/^element face/ { print $3; exit }' "$ply")
    scene=$work/teapot-$size.scene
    printf '%s\n' '# A teapot alone under one light (make results, the scaling experiment).' \
        'camera eye 0 2.5 9  target 0 1 0  fov 36' "image $SCALING_W $SCALING_H" 'max_depth 1' \
        'light position -5 8 6  colour 1 1 1' \
        'material china colour 0.35 0.55 0.85 ambient 0.1 diffuse 0.7' \
        "mesh $(cd "$models" && pwd)/teapot-$size.ply material china" >"$scene"
    for s in $SCALING_STRUCTURES; do
        mw=$SCALING_W mh=$SCALING_H scale=1 runs=$RUNS
        if [ "$s" = none ]; then
            read -r mw mh < <(sample_grid $SCALING_W $SCALING_H "$triangles" "$SCALING_BRUTE_BUDGET")
            scale=$(awk -v a=$((SCALING_W * SCALING_H)) -v b=$((mw * mh)) 'BEGIN { printf "%.6g", a / b }')
            runs=1
        fi
        run_chapter "$s" "$scene" "$mw" "$mh" 1 "$runs"
        # A sampled run's time and counters scaled up as in sweep_row (large.csv): all but the memory.
        read -r render cpu rays tests < <(awk -v s="$scale" -v c="$RENDER_S" -v b="$CPU_BEST" -v d="$RAYS" -v e="$TESTS" \
            'BEGIN { printf "%.4f %.4f %.0f %.0f\n", c * s, b * s, d * s, e * s }')
        echo "$triangles,$s,$RUNS_DONE,$BUILD_MS,$render,$cpu,$PEAK_MB,$rays,$tests,$mw,$mh,$scale" >>"$csv"
        printf '  %9d triangles  %-10s build %8s ms  frame %9.3f s  %8s MB\n' "$triangles" "$s" "${BUILD_MS:--}" \
            "$render" "$PEAK_MB" >&2
    done
done

# ---- threads ---------------------------------------------------------------------------------------
cores=$(nproc)
echo "threads: chapter 10's scene on 1, 2 and $cores threads ($cores cores online)" >&2
csv=$work/threads.csv
echo "program,scene,width,height,threads,runs,wall_best_s,wall_median_s,render_best_s,render_median_s,cores_online" >"$csv"
thread_counts="1 2"
[ "$cores" -gt 2 ] && thread_counts="1 2 $cores"
for program in chapter-10 chapter-11; do
    for t in $thread_counts; do
        walls=() renders=()
        for ((r = 0; r < THREAD_RUNS; r++)); do
            "$build/measure" "$work/cost" "$build/$program" scenes/10-bvh.scene --threads "$t" \
                --width $((640 / DIV)) --height $((480 / DIV)) -o "$work/threads.png" >"$work/report"
            read -r _ wall _ <"$work/cost"
            walls+=("$wall")
            renders+=("$(render_s_of "$work/report")")
        done
        read -r wall_best wall_median < <(printf '%s\n' "${walls[@]}" | best_and_median)
        read -r render_best render_median < <(printf '%s\n' "${renders[@]}" | best_and_median)
        echo "$program,10-bvh,$((640 / DIV)),$((480 / DIV)),$t,$THREAD_RUNS,$wall_best,$wall_median,$render_best,$render_median,$cores" >>"$csv"
        printf '  %s  %d threads  render best %.3f s, median %.3f s\n' "$program" "$t" "$render_best" "$render_median" >&2
    done
done

# ---- the whole program against POV-Ray ------------------------------------------------------------
echo "the whole program against POV-Ray 3.7 on the large model, paired runs" >&2
BUILD=$build tools/results/whole.sh "$work" $([ $quick -eq 1 ] && echo --quick)

# ---- the benchmark against Embree ---------------------------------------------------------------------
if [ $quick -eq 0 ]; then
    echo "the acceleration benchmark (bench_accel, with Embree)" >&2
    "$build/bench_accel" --embree --repeats 3 --csv "$work/accel.csv" scenes/models/teapot-346k.ply scenes/models/bunny.ply >&2
fi

# ---- the pictures -----------------------------------------------------------------------------------
echo "pictures of the scenes (chapter 10, BVH)" >&2
picture() { # picture NAME SCENE W H DEPTH
    "$build/chapter-10" "$2" --quiet --set max_depth="$5" --width $(($3 / DIV)) --height $(($4 / DIV)) -o "$work/$1.png"
}
picture scene1-depth-1 scenes/results/seed-scene-1.scene 400 200 1
picture scene1-depth-5 scenes/results/seed-scene-1.scene 400 200 5
picture scene1-two-lights scenes/results/seed-scene-1-two-lights.scene 400 200 5
picture bunny scenes/results/seed-bunny.scene 400 300 5
picture teapot-5k scenes/results/seed-teapot-5k.scene 400 300 5
picture large scenes/results/seed-large.scene 400 300 1

# ---- the machine ------------------------------------------------------------------------------------
csv=$work/machine.csv
{
    echo "key,value"
    echo "mode,$([ $quick -eq 1 ] && echo quick || echo full)"
    echo "date,$(date -u +%Y-%m-%d)"
    echo "processor,$(awk -F': ' '/^model name/ { gsub(/,/, ""); print $2; exit }' /proc/cpuinfo)"
    echo "cores online,$cores"
    echo "memory,$(awk '/^MemTotal/ { printf "%.0f GB", $2 / 1024 / 1024 }' /proc/meminfo)"
    echo "system,$(. /etc/os-release && echo "$PRETTY_NAME" | tr -d ,)"
    echo "compiler,$(gcc --version | head -1 | tr -d ,)"
    echo "POV-Ray,$(povray --version 2>&1 | awk '/^POV-Ray/ { print $2; exit }')"
    echo "load average at the start,$load_before"
    echo "load average at the end,$(cut -d' ' -f1-3 /proc/loadavg)"
    echo "minutes,$(awk -v s=$(($(date +%s) - started)) 'BEGIN { printf "%.1f", s / 60 }')"
} >"$csv"

# Only a finished run replaces the CSVs and pictures.
mv "$work"/*.csv "$work"/scene1-*.png "$work"/bunny.png "$work"/teapot-5k.png "$work"/large.png "$out"/
rm -rf "$work"
echo "wrote $(ls "$out"/*.csv | wc -l) CSV files to $out/" >&2

#!/usr/bin/env bash
# fuzz/run.sh: runs the libFuzzer harnesses built by make fuzz, one after the other (docs/fuzzing.md).
#
#   fuzz/run.sh FUZZ_BUILD SECONDS   run each harness for SECONDS, from its corpus in out/fuzz/corpus/
#                                    (grown by every run) and its seeds
#   fuzz/run.sh --smoke FUZZ_BUILD   run each harness for SMOKE_RUNS inputs with a fixed random seed,
#                                    from its seeds only and keeping no corpus (CI)
#
# Seeds: the chapters' scenes and the saved fuzz inputs for the scene parser and the renderer; the test
# meshes (tests/data/meshes), fuzz/seeds/ and the saved inputs for the mesh readers; the tiny images
# drawn by make fuzz-build (FUZZ_BUILD/seeds/image) and the saved inputs for the image reader. A crash, a broken
# check (an abort), a leak or an input taking longer than TIMEOUT seconds is saved as a file under
# out/fuzz/HARNESS/ and named in the summary; the exit status is then 1. A harness stops at its first
# finding; the others still run.
set -u
cd "$(dirname "$0")/.."

SMOKE_RUNS=3000 # inputs per harness in the smoke run: a few seconds each, also for the renderer
TIMEOUT=10      # seconds one input may take; far above any real one (the renderer's are milliseconds)
SCENE_MAX_LEN=4096 # longest input in bytes: room for a few dozen directives, as in the chapters' scenes
MESH_MAX_LEN=8192  # the same for mesh files: the test meshes are all smaller
IMAGE_MAX_LEN=8192 # the same for image files: the tiny images are under 1,000 bytes

smoke=no
if [ "${1:-}" = --smoke ]; then
    smoke=yes
    shift
fi
if [ $# -ne $([ $smoke = yes ] && echo 1 || echo 2) ]; then
    echo "usage: fuzz/run.sh FUZZ_BUILD SECONDS | fuzz/run.sh --smoke FUZZ_BUILD" >&2
    exit 2
fi
build=$1
seconds=${2:-0}

# seeds HARNESS: the folders its inputs start from.
seeds() {
    case $1 in
    scene | render) echo scenes tests/data/fuzz/scene tests/data/fuzz/render ;;
    ply | obj) echo tests/data/meshes fuzz/seeds/ply tests/data/fuzz/ply tests/data/fuzz/obj ;;
    image) echo "$build/seeds/image" tests/data/fuzz/image ;;
    esac
}

found=()
for harness in scene ply obj render image; do
    artifacts=out/fuzz/$harness
    mkdir -p "$artifacts"
    options=(-timeout=$TIMEOUT -artifact_prefix="$artifacts/" -print_final_stats=1)
    case $harness in
    scene | render) options+=(-max_len=$SCENE_MAX_LEN -dict=fuzz/scene.dict) ;;
    image) options+=(-max_len=$IMAGE_MAX_LEN -dict=fuzz/image.dict) ;;
    *) options+=(-max_len=$MESH_MAX_LEN) ;;
    esac
    folders=()
    for f in $(seeds $harness); do [ -d "$f" ] && folders+=("$f"); done
    if [ $smoke = yes ]; then
        options+=(-runs=$SMOKE_RUNS -seed=1)
        corpus=$(mktemp -d) # libFuzzer adds new inputs to its first folder: a throw-away one
    else
        options+=(-max_total_time="$seconds")
        corpus=out/fuzz/corpus/$harness
        mkdir -p "$corpus"
    fi
    log=out/fuzz/$([ $smoke = yes ] && echo smoke-)$harness.log
    before=$(ls "$artifacts" | wc -l)
    echo "fuzz: $harness for $([ $smoke = yes ] && echo "$SMOKE_RUNS runs" || echo "$seconds s"), log in $log"
    "$build/fuzz_$harness" "${options[@]}" "$corpus" "${folders[@]}" >"$log" 2>&1
    status=$?
    [ $smoke = yes ] && rm -rf "$corpus"
    grep -E '^(#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units|stat::peak_rss_mb)' "$log" | sed 's/^/    /'
    if [ $status -ne 0 ] || [ "$(ls "$artifacts" | wc -l)" -ne "$before" ]; then
        grep -E '^(==[0-9]+==ERROR|SUMMARY|fuzz: |.*runtime error)' "$log" | head -5 | sed 's/^/    /'
        found+=("$harness")
    fi
done

if [ ${#found[@]} -gt 0 ]; then
    echo "fuzz: findings in: ${found[*]}; the inputs are in out/fuzz/HARNESS/ (docs/fuzzing.md: what to do)" >&2
    exit 1
fi
echo "fuzz: nothing found"

#!/bin/sh
# bench/profile.sh: where a ray's time goes on chapter 11's ladder: instructions, data cache misses and
# mispredicted branches per ray for rungs 1 and 5 to 9 and for Embree 3, on make bench-accel's frame
# of the teapot (800 x 600, a camera ray per pixel and a shadow ray per hit, one thread). make
# bench-profile runs it; docs/fast-notes.md shows its table.
#
# Usage: bench/profile.sh BENCH_ACCEL MODEL.ply
#
# The counts are valgrind's (callgrind): the instructions exactly, the cache misses and mispredicted
# branches from its simulation of the caches and of a simple branch predictor. The level-1 caches are
# sized as the processor reports them; the last level is set to 32 MB, 16-way (CALLGRIND_LL, one AMD
# Zen chiplet's L3), since a virtual machine may report nonsense there (ours: 512 MB, 2-way). Hardware counters (perf stat) would be the measured truth, but a virtual
# machine often does not pass them through (on ours perf stat reports instructions, cycles and misses
# as "not supported"), and perf stat counts a whole process, whose loading, builds and reference
# frame would drown the queries. callgrind counts only inside the queries themselves (--toggle-collect:
# bvh_closest and bvh_occluded for rung 1, fast_bvh_closest and fast_bvh_occluded for the others,
# rtcIntersect1 and rtcOccluded1 for Embree), so each row is exactly the frame's rays. Under valgrind
# everything runs some fifty times slower: the whole table takes ten minutes or so.
set -eu
if [ $# -ne 2 ]; then
    echo "usage: bench/profile.sh BENCH_ACCEL MODEL.ply" >&2
    exit 2
fi
bench=$1
model=$2
command -v valgrind >/dev/null || { echo "bench/profile.sh: needs valgrind (Debian's package valgrind)" >&2; exit 2; }
CALLGRIND_LL=33554432,16,64
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# profile LABEL ROW FUNCTIONS [BENCH OPTIONS]: one row of the table. ROW is the bench's row whose rays
# are counted (its CSV name), FUNCTIONS the queries counted, separated by spaces.
profile() {
    label=$1 row=$2 functions=$3
    shift 3
    toggles=""
    for f in $functions; do toggles="$toggles --toggle-collect=$f"; done
    # shellcheck disable=SC2086 # $toggles is a list of options
    valgrind --tool=callgrind --cache-sim=yes --LL=$CALLGRIND_LL --branch-sim=yes $toggles \
        --callgrind-out-file="$work/out" "$bench" --repeats 1 --csv "$work/csv" "$@" "$model" \
        >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
    # The rays: the bench's own count for that row, Mrays/s times the frame's milliseconds.
    rays=$(awk -F, -v row="$row" '$3 == row { printf "%.0f", $6 * $5 * 1000 }' "$work/csv")
    # callgrind's totals: Ir Dr Dw I1mr D1mr D1mw ILmr DLmr DLmw Bc Bcm Bi Bim, in that order.
    awk -v label="$label" -v rays="$rays" '
        /^events:/ { for (i = 2; i <= NF; i++) name[i - 1] = $i }
        /^totals:/ { for (i = 2; i <= NF; i++) total[name[i - 1]] = $i }
        END {
            printf "| %s | %.0f | %.1f | %.2f | %.2f |\n", label, total["Ir"] / rays,
                (total["D1mr"] + total["D1mw"]) / rays, (total["DLmr"] + total["DLmw"]) / rays,
                (total["Bcm"] + total["Bim"]) / rays
        }' "$work/out"
}

echo "$model, 800 x 600, one thread, per ray (camera and shadow), counted by callgrind:"
echo
echo "| | instructions | L1 data misses | last-level misses | mispredicted branches |"
echo "|---|---|---|---|---|"
profile "rung 1 plain (chapter 10)" bvh-sah "bvh_closest bvh_occluded" --only "BVH-SAH (rung 1 plain)"
profile "rung 5 build" rung-5 "fast_bvh_closest fast_bvh_occluded" --only "rung 5 build"
profile "rung 6 float" rung-6 "fast_bvh_closest fast_bvh_occluded" --only "rung 6 float"
profile "rung 7 compact" rung-7 "fast_bvh_closest fast_bvh_occluded" --only "rung 7 compact"
profile "rung 8 eight" rung-8 "fast_bvh_closest fast_bvh_occluded" --only "rung 8 eight"
profile "rung 9 lean" rung-9 "fast_bvh_closest fast_bvh_occluded" --only "rung 9 lean"
profile "Embree 3" embree "rtcIntersect1* rtcOccluded1*" --embree --only "BVH-SAH (rung 1 plain)"
echo
grep -h '^desc: \(I1\|D1\|LL\) cache' "$work/out" | sed 's/^desc: /simulated /'

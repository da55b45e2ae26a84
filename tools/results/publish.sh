#!/usr/bin/env bash
# publish.sh: draws the plots and writes the tables of docs/results.md from the CSV files of make results.
#
#   tools/results/publish.sh DATA FIGURES PAGE     draw DATA/*.csv into FIGURES/*.svg, tables into PAGE
#   tools/results/publish.sh --check [DATA FIGURES PAGE]
#                                                   fail if a plot or table is stale against its CSV
#                                                   (default: docs/results docs/results docs/results.md)
#
# The tables go between marker lines in PAGE: `<!-- results:NAME -->` and `<!-- /results:NAME -->`
# (NAME as tools/results/tables.awk knows it, with the CSV it reads: `<!-- results:sweep bunny -->`).
# The numbers the sentences quote go between inline markers, `<!--n:NAME-->VALUE<!--/n-->` on one
# line (NAME as tables.awk's table "prose" prints it). Everything else in the page is left as it is. The
# plots are gnuplot SVG, drawn by tools/results/plots.gp. --check redraws everything from the CSVs
# (committed in docs/results/) into a temporary folder and compares it byte for byte with the plots
# and page given; it names each stale file, and each stale number of the text, and exits 1.
set -euo pipefail
cd "$(dirname "$0")/../.."

if [ "${1:-}" = --check ]; then
    data=${2:-docs/results} figures=${3:-docs/results} page=${4:-docs/results.md}
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    mkdir -p "$tmp/figures"
    cp "$page" "$tmp/results.md"
    "$0" "$data" "$tmp/figures" "$tmp/results.md"
    stale=0
    for svg in "$tmp"/figures/*.svg; do
        name=$(basename "$svg")
        if ! cmp -s "$svg" "$figures/$name"; then
            echo "$figures/$name is stale against $data/*.csv: make results (or tools/results/publish.sh) redraws it" >&2
            stale=1
        fi
    done
    # The numbers of the text, NAME and VALUE a line in the page's order, before and after.
    numbers() { grep -o '<!--n:[a-z0-9-]*-->[^<]*<!--/n-->' "$1" | sed 's/^<!--n:\([a-z0-9-]*\)-->\(.*\)<!--\/n-->$/\1 \2/'; }
    numbers "$page" >"$tmp/numbers-page"
    numbers "$tmp/results.md" >"$tmp/numbers-csv"
    if ! cmp -s "$tmp/numbers-page" "$tmp/numbers-csv"; then
        paste -d '\n' "$tmp/numbers-page" "$tmp/numbers-csv" | awk -v page="$page" 'NR % 2 { was = $0; next }
            $0 != was { name = $1; sub(/^[^ ]* /, "", was); sub(/^[^ ]* /, "")
                        printf "%s: the number %s in the text is stale: %s, where %s/*.csv give %s\n", page, name, was, data, $0 }' \
            data="$data" >&2
        stale=1
    fi
    if ! cmp -s "$tmp/results.md" "$page"; then
        diff -u "$page" "$tmp/results.md" | head -20 >&2 || true
        echo "$page: a table or a number of the text is stale against $data/*.csv: make results (or tools/results/publish.sh) rewrites it" >&2
        stale=1
    fi
    exit $stale
fi

if [ $# -ne 3 ]; then
    echo "usage: tools/results/publish.sh DATA FIGURES PAGE | --check" >&2
    exit 2
fi
data=$1 figures=$2 page=$3
mkdir -p "$figures"
for f in scene1 bunny teapot-5k large scaling threads machine; do
    [ -s "$data/$f.csv" ] || { echo "publish.sh: $data/$f.csv is missing (run make results first)" >&2; exit 1; }
done

# ---- plots -------------------------------------------------------------------------------------------
# gnuplot reads per-series files made here: SERIES X Y, one per line, from the CSVs.
series=$(mktemp -d)
trap 'rm -rf "$series"' EXIT
# pick CSV COLUMN=VALUE... -- X Y: the rows matching every COLUMN=VALUE, as "X Y" (columns by name).
pick() {
    local csv=$1
    shift
    awk -F, -v spec="$*" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i
                                    n = split(spec, s, " "); next }
        { ok = 1; axis = 0
          for (k = 1; k <= n; k++) {
              if (s[k] == "--") { axis = k; break }
              split(s[k], kv, "="); if ($(col[kv[1]]) != kv[2]) ok = 0
          }
          if (ok) print $(col[s[axis + 1]]), $(col[s[axis + 2]]) }' "$csv"
}
# The scene-1 sizes as the CSV has them (smaller first): quick runs divide them.
read -r small_w small_h big_w big_h < <(awk -F, 'NR > 1 { k = $2 " " $3; if (!(k in seen)) { seen[k] = 1; printf "%s ", k } } END { print "" }' "$data/scene1.csv")
for lights in 1 2; do
    name=$([ $lights = 1 ] && echo scene1 || echo scene1-two-lights)
    for s in none bvh-sah povray; do
        pick "$data/scene1.csv" scene=$name width=$small_w structure=$s -- depth cpu_best_s >"$series/s1-small-$lights-$s"
        pick "$data/scene1.csv" scene=$name width=$big_w structure=$s -- depth cpu_best_s >"$series/s1-big-$lights-$s"
    done
done
for model in bunny teapot-5k; do
    for s in none kd-sah bvh-median bvh-sah povray; do
        pick "$data/$model.csv" structure=$s -- depth cpu_best_s >"$series/$model-time-$s"
        pick "$data/$model.csv" structure=$s -- depth triangle_tests >"$series/$model-tests-$s"
    done
done
for lights in 1 2; do # time divided by the time at depth 1
    for size in small big; do
        for s in none bvh-sah povray; do
            awk 'NR == 1 { first = $2 } { print $1, $2 / first }' "$series/s1-$size-$lights-$s" >"$series/s1-$size-$lights-$s-growth"
        done
    done
done
# The large model's bars: label, value, scaled up (1) or measured (0), colour (0xRRGGBB, in decimal);
# then the seed's, in dark grey. Processor times into large, triangle tests into large-tests (POV-Ray
# does not count its tests).
awk -F, -v times="$series/large" -v tests="$series/large-tests" '
    BEGIN { label["none"] = "brute force"; label["kd-seed"] = "kd-tree, seed rule"; label["kd-sah"] = "kd-tree, SAH"
            label["bvh-median"] = "BVH, median"; label["bvh-sah"] = "BVH, SAH"; label["fast"] = "chapter 11"
            label["povray"] = "POV-Ray 3.7"
            colour["none"] = 12597547; colour["kd-seed"] = 12292046; colour["kd-sah"] = 9323693
            colour["bvh-median"] = 15105570; colour["bvh-sah"] = 2388387; colour["fast"] = 1281397
            colour["povray"] = 8359053 }
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { s = $(col["structure"]); scaled = ($(col["scale"]) > 1)
      printf "\"%s\" %s %d %d\n", label[s], $(col["cpu_best_s"]), scaled, colour[s] >times
      if (s != "povray") printf "\"%s\" %s %d %d\n", label[s], $(col["triangle_tests"]), scaled, colour[s] >tests }
    END { print "\"seed, no structure\" 6930 0 3355443" >times; print "\"seed, its BVH\" 62 0 3355443" >times
          print "\"seed, its BVH\" 99250516 0 3355443" >tests }' "$data/large.csv"
for s in none kd-sah bvh-median bvh-sah fast; do
    [ $s = none ] || pick "$data/scaling.csv" structure=$s -- triangles build_ms >"$series/scaling-build-$s"
    pick "$data/scaling.csv" structure=$s -- triangles render_s >"$series/scaling-frame-$s"
    pick "$data/scaling.csv" structure=$s -- triangles peak_rss_mb >"$series/scaling-memory-$s"
done
# The brute force's rows with a third column, the scale: above 1, sampled on a coarser grid.
for measure in frame memory; do
    paste -d ' ' "$series/scaling-$measure-none" <(pick "$data/scaling.csv" structure=none -- triangles scale | cut -d' ' -f2) \
        >"$series/scaling-$measure-none.scaled"
    mv "$series/scaling-$measure-none.scaled" "$series/scaling-$measure-none"
done
# Guides through one point: n log n and n. Build and memory: through the BVH-SAH's smallest and largest
# model; frame: through the brute force's smallest, which is linear in n.
guides() { # guides SERIES-FILE ROW(first|last) OUT
    awk -v row="$2" 'NR == 1 || row == "last" { n0 = $1; y0 = $2 } { n[NR] = $1 }
        END { for (i = 1; i <= NR; i++) printf "%s %.6g %.6g\n", n[i], y0 * n[i] * log(n[i]) / (n0 * log(n0)), y0 * n[i] / n0 }' \
        "$1" >"$3"
}
guides "$series/scaling-build-bvh-sah" first "$series/scaling-build-guides"
guides "$series/scaling-frame-none" first "$series/scaling-frame-guides"
guides "$series/scaling-memory-bvh-sah" last "$series/scaling-memory-guides"
gnuplot -e "series='$series'; figures='$figures'; small='${small_w}×$small_h'; big='${big_w}×$big_h'" tools/results/plots.gp

# ---- tables ------------------------------------------------------------------------------------------
# Each marked section of the page is replaced by its table, read from its CSV.
tables=$(mktemp)
awk -v data="$data" -v tables_awk=tools/results/tables.awk '
    /^<!-- results:[a-z0-9-]+( [a-z0-9-]+)? -->$/ {
        print
        spec = $0; sub(/^<!-- results:/, "", spec); sub(/ -->$/, "", spec)
        n = split(spec, part, " ")
        name = part[1]; csv = (n > 1) ? part[2] : name
        if (name ~ /^scaling-/) csv = "scaling"
        if (name ~ /^accel-/) csv = "accel"
        if (name == "seed") csv = "large"
        close_marker = "<!-- /results:" name " -->"
        file = data "/" csv ".csv"
        print ""
        if (name == "seed") file = data "/scene1.csv " data "/bunny.csv " data "/teapot-5k.csv " data "/large.csv"
        if ((getline line < (data "/" csv ".csv")) <= 0) { # a quick run has no benchmark against Embree
            print "(" file " is not there: this run did not make it.)"
        } else {
            close(data "/" csv ".csv")
            cmd = "awk -F, -v table=" name " -f " tables_awk " " file
            while ((cmd | getline line) > 0) print line
            if (close(cmd) != 0) { print "publish.sh: the table " name " failed" > "/dev/stderr"; exit 1 }
        }
        print ""
        skipping = 1
        next
    }
    skipping && $0 == close_marker { skipping = 0 }
    !skipping { print }
    END { if (skipping) { print "publish.sh: no " close_marker " after its opening marker" > "/dev/stderr"; exit 1 } }
' "$page" >"$tables"

# ---- the numbers of the text ---------------------------------------------------------------------------
# Each <!--n:NAME-->VALUE<!--/n--> gets the VALUE tables.awk computes for NAME from the CSVs; an unknown
# NAME, or a marker not closed on its own line, stops the script.
values=$(mktemp)
prose_csvs="$data/machine.csv $data/scene1.csv $data/bunny.csv $data/teapot-5k.csv $data/large.csv $data/scaling.csv"
[ -s "$data/accel.csv" ] && prose_csvs="$prose_csvs $data/accel.csv" # a quick run has no benchmark
# shellcheck disable=SC2086
awk -F, -v table=prose -f tools/results/tables.awk $prose_csvs >"$values"
awk -v values="$values" -v page="$page" '
    BEGIN { while ((getline line < values) > 0) { k = index(line, " "); value[substr(line, 1, k - 1)] = substr(line, k + 1) } }
    {
        out = ""; rest = $0
        while (match(rest, /<!--n:[a-z0-9-]+-->[^<]*<!--\/n-->/)) {
            name = substr(rest, RSTART + 6); sub(/-->.*/, "", name)
            if (!(name in value)) { printf "%s:%d: no number called %s (tools/results/tables.awk, table prose)\n", page, NR, name > "/dev/stderr"; bad = 1 }
            out = out substr(rest, 1, RSTART - 1) "<!--n:" name "-->" value[name] "<!--/n-->"
            rest = substr(rest, RSTART + RLENGTH)
        }
        if (match(rest, /<!--n:[a-z0-9-]+-->/)) { printf "%s:%d: a <!--n:NAME--> marker without its <!--/n--> on the same line\n", page, NR > "/dev/stderr"; bad = 1 }
        print out rest
    }
    END { exit bad }' "$tables" >"$values.page" || { rm -f "$values" "$values.page" "$tables"; exit 1; }
rm -f "$values" "$tables"
mv "$values.page" "$page"

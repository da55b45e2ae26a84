#!/usr/bin/env bash
# gallery.sh: the gallery of wrong pictures. Each fault is a small patch in tools/gallery/NAME.patch (a
# mistake a student could plausibly make, a line or a few), with a header saying what it is:
#
#   Title, Chapter (where the mistake is made), Program (the chapter program that shows it best),
#   Scene and Args (what to render), Symptom, Cause, Look (the function to look in), Check (the tasks
#   of the student's grader, build/check, whose checks report the fault, e.g. "2.1 2.P")
#
#   tools/gallery.sh BUILD             build every fault, render it beside the right picture, write
#                                      docs/gallery/NAME-*.png and docs/gallery.md
#   tools/gallery.sh BUILD --prove N   build fault N, with its chapter program and the grader, and exit
#                                      0 when every task its Check line names fails with the fault
#                                      (`check --task ID`, the grader make check-N runs), 1 when one
#                                      passes, 2 when the fault cannot be built. It also says whether the
#                                      gallery's own picture fails the reference-image rule against the
#                                      right one (a fault may draw the right picture with more work).
#
# Faults are applied to a copy of the sources in out/gallery/work, never to the repository itself.
# The reference code stays free of switches: the patch is the fault.
set -u
cd "$(dirname "$0")/.."
build=${1:?usage: tools/gallery.sh BUILD [--prove NAME]}
shift
mode=render
only=""
if [ "${1:-}" = "--prove" ]; then
    mode=prove
    only=${2:?--prove needs a fault name}
fi

size=(--width 320 --height 240) # every gallery picture, right and wrong, at this size

field() { sed -n "s/^$2: //p" "$1" | head -n 1; }

# A private copy of what building a chapter needs, with the objects already built, so that a fault
# recompiles only the file it changes. One copy per process, so provers can run side by side.
work=out/gallery/work-$$
trap 'rm -rf "$work"' EXIT
mkdir -p "$work"
cp -r Makefile common chapters tools bench fuzz reference_images "$work"/
mkdir -p "$work/tests" "$work/out" && cp -r tests/checks tests/support "$work/tests/"
mkdir -p "$work/scenes" && cp scenes/*.scene "$work/scenes/" && cp -r scenes/models "$work/scenes/"
[ ! -d scenes/textures ] || cp -r scenes/textures "$work/scenes/" # chapter 14's pictures, drawn by make
# The copy builds the way $build was built (build/san: with the sanitizers).
san=0
case $build in */san) san=1 ;; esac
if [ -d "$build/common" ]; then
    mkdir -p "$work/$build"
    cp -rp "$build"/common "$build"/chapters "$build"/checks "$build"/tools "$work/$build/" 2>/dev/null
    cp -p "$build"/chapter-* "$work/$build/" 2>/dev/null
fi
# The programs that draw the models and textures the chapters' programs need (order-only prerequisites),
# with their times, so that the copy does not build them and draw everything again.
mkdir -p "$work/build" && cp -p build/teapot "$work/build/" 2>/dev/null
[ ! -e "$build/draw-textures" ] || cp -p "$build/draw-textures" "$work/$build/"

# Builds chapter program NN and the grader (build/check) with the fault's patch applied; prints the
# program's path (the grader is beside it).
build_fault() { # build_fault PATCH NN
    local patch=$1 nn=$2 file
    for file in $(sed -n 's|^+++ b/||p' "$patch"); do
        cp "$file" "$work/$file" # pristine again, with a new time, so make recompiles it
    done
    # The copy lies inside this repository's tree: GIT_CEILING_DIRECTORIES keeps git apply from
    # finding the repository and applies the patch to the copy as plain files.
    (cd "$work" && GIT_CEILING_DIRECTORIES=$(dirname "$PWD") git apply -p1 "$OLDPWD/$patch") || return 1
    env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS make --no-print-directory -C "$work" SAN=$san "$build/chapter-$nn" "$build/check" \
        >"$work/build.log" 2>&1 || return 1
    for file in $(sed -n 's|^+++ b/||p' "$patch"); do
        cp "$file" "$work/$file" # leave the copy pristine for the next fault
    done
    echo "$work/$build/chapter-$nn"
}

# Renders with program $1 the fault's scene and args into $2.
# Args with --frames N --frame K (chapter 16) write one frame, PNG's name with -KKKK before .png: it is
# moved to PNG.
render() { # render PROGRAM PATCH PNG
    local scene args frame
    scene=$(field "$2" Scene)
    args=$(field "$2" Args)
    eval "\"\$1\" \"\$scene\" ${args} \"\${size[@]}\" --quiet -o \"\$3\"" || return 1
    for frame in "${3%.png}"-[0-9][0-9][0-9][0-9].png; do
        [ ! -e "$frame" ] || mv "$frame" "$3"
    done
}

# Whether pictures a and b pass the reference-image rule (tests/support/image_test_support.h): at least
# 99.95 % of pixels within 1 level and a mean difference of at most 0.01 levels.
passes_regression() { # passes_regression A B
    local result
    result=$("$build/compare" "$1" "$2")
    # $6 + 0: the number before the "%"; a string, as sub() would leave it, compares as text
    # ("100.000" < "99.95"), which made identical pictures count as different.
    echo "$result" | awk '{ within1 = $6 + 0; exit !(within1 >= 99.95 && $4 + 0 <= 0.01) }'
}

# Runs the grader built with the fault on each task of the fault's Check line (in the copy, where the
# chapter programs are the fault's) and prints what each says; returns 1 when one of them does not
# fail its own checks (it passes, or reports only "needs task X first").
graded() { # graded PATCH
    local id status=0 out
    for id in $(field "$1" Check); do
        out=$(cd "$work" && WHITTED_BUILD=$build "./$build/check" --task "$id" 2>&1)
        if echo "$out" | grep -q "FAIL  $id:"; then
            echo "  make check-${id%%.*}: $id reports it: $(echo "$out" | grep -m 1 -A 1 "FAIL  $id:" | tail -n 1 | sed 's/^ *//')"
        else
            echo "  make check-${id%%.*}: $id does not fail with the fault:"
            echo "$out" | sed 's/^/    /'
            status=1
        fi
    done
    return $status
}

prove() { # prove NAME
    local patch=tools/gallery/$1.patch program nn wrong right
    [ -f "$patch" ] || { echo "no fault called $1" >&2; return 2; }
    [ -n "$(field "$patch" Check)" ] || { echo "$1: the patch names no Check task" >&2; return 2; }
    nn=$(printf '%02d' "$(field "$patch" Program)")
    program=$(build_fault "$patch" "$nn") || { echo "$1: the patch does not apply or build (see $work/build.log)" >&2; return 2; }
    wrong=$work/wrong.png
    right=$work/right.png
    render "$program" "$patch" "$wrong" || { echo "$1: the wrong program failed to render" >&2; return 2; }
    render "$build/chapter-$nn" "$patch" "$right" || { echo "$1: the right program failed to render" >&2; return 2; }
    if passes_regression "$right" "$wrong"; then
        echo "$1: the gallery's picture is within the reference-image rule ($("$build/compare" "$right" "$wrong"))"
    else
        echo "$1: the gallery's picture fails the reference-image rule ($("$build/compare" "$right" "$wrong"))"
    fi
    if ! graded "$patch"; then
        echo "$1: NOT caught by every task its Check line names"
        return 1
    fi
    echo "$1: caught by the grader"
    return 0
}

if [ "$mode" = prove ]; then
    prove "$only"
    exit
fi

# "make check-2: 2.1, 2.P": the grader's tasks that report the fault, by chapter.
caught_by() { # caught_by PATCH
    field "$1" Check | tr ' ' '\n' | awk -F. 'NF { if ($1 != last) printf "%s`make check-%s`: %s", (n++ ? "; " : ""), $1, $0; else printf ", %s", $0; last = $1 } END { print "" }'
}

# Moves the picture NEW to OLD, unless OLD already holds the same pixels: then OLD is left as it is, byte
# for byte (a PNG writer may encode the same pixels in other bytes), so that a gallery that has not
# changed leaves the tree as it found it.
keep_or_replace() { # keep_or_replace NEW OLD
    local difference
    if [ -f "$2" ] && difference=$("$build/compare" "$2" "$1" 2>/dev/null) && [ "$(echo "$difference" | awk '{ print $1, $2 }')" = "max 0" ]; then
        rm -f "$1"
    else
        mv "$1" "$2"
    fi
}

# Render mode: every fault, its pictures, and the page.
mkdir -p docs/gallery
page=docs/gallery.md
{
    echo "# A gallery of wrong pictures"
    echo
    echo "Every ray tracer course meets the same mistakes. Each one below is a real change of a line or"
    echo "two in this repository's code, the kind a student writes, with the picture it makes beside the"
    echo "right one and their difference amplified 16 times (black where they agree). Learn to read the"
    echo "symptom, and the bug is found in minutes."
    echo
    echo "The pictures are rendered by \`make gallery\` from the patches in"
    echo "[\`tools/gallery/\`](../tools/gallery/): apply one to a copy of the code to see the fault for yourself"
    echo "(\`git apply tools/gallery/NAME.patch\`, and \`git checkout common\` to undo). \`make test-long\` proves that"
    echo "the student's grader catches every one (\`tests/test_gallery.c\`): built with the fault, each task named"
    echo "under \"Caught by\" fails its checks (\`make check-N\`, see [the coursework kit](coursework.md)), where"
    echo "N.P is the chapter's picture against its reference."
    echo
    echo "| fault | chapter | symptom | caught by |"
    echo "|---|---|---|---|"
    for patch in tools/gallery/*.patch; do
        name=$(basename "$patch" .patch)
        echo "| [$(field "$patch" Title)](#$name) | $(field "$patch" Chapter) | $(field "$patch" Symptom) | $(caught_by "$patch") |"
    done
} >"$page.new"
status=0
for patch in tools/gallery/*.patch; do
    name=$(basename "$patch" .patch)
    nn=$(printf '%02d' "$(field "$patch" Program)")
    if ! program=$(build_fault "$patch" "$nn"); then
        echo "$name: the patch does not apply or build (see $work/build.log)" >&2
        status=1
        continue
    fi
    render "$program" "$patch" "$work/wrong.png" &&
        render "$build/chapter-$nn" "$patch" "$work/right.png" || { status=1; continue; }
    stats=$("$build/compare" "$work/right.png" "$work/wrong.png" "$work/side.png" "$work/diff.png")
    keep_or_replace "$work/wrong.png" "docs/gallery/$name-wrong.png"
    keep_or_replace "$work/right.png" "docs/gallery/$name-right.png"
    keep_or_replace "$work/diff.png" "docs/gallery/$name-diff.png"
    set -- $stats
    args=$(field "$patch" Args)
    {
        echo
        echo "<a id=\"$name\"></a>"
        echo "## $(field "$patch" Title)"
        echo
        echo "| right | wrong | difference ×16 |"
        echo "|---|---|---|"
        echo "| ![right](gallery/$name-right.png) | ![wrong](gallery/$name-wrong.png) | ![difference](gallery/$name-diff.png) |"
        echo
        echo "* **Symptom:** $(field "$patch" Symptom)"
        echo "* **Cause:** $(field "$patch" Cause)"
        echo "* **Look in:** \`$(field "$patch" Look | sed 's/ in /` in `/')\`."
        echo "* **Shown with:** chapter $((10#$nn))'s program on \`$(field "$patch" Scene)\`${args:+ with \`$args\`}, at 320 × 240."
        echo "* **Caught by:** $(caught_by "$patch"). The gallery's pictures differ by $2 levels at most, mean $4, $6 of pixels within 1 level (the picture rule needs 99.95 % and 0.01)."
        echo "* **The change:** [\`tools/gallery/$name.patch\`](../tools/gallery/$name.patch)"
        echo
        echo '```diff'
        sed -n '/^@@/,$p' "$patch" | grep -v '^@@'
        echo '```'
    } >>"$page.new"
    echo "$name: $stats"
done
mv "$page.new" "$page"
echo "wrote $page"
exit $status

#!/usr/bin/env bash
# gallery.sh: the gallery of wrong pictures. Each fault is a small patch in tools/gallery/NAME.patch (a
# mistake a student could plausibly make, a line or a few), with a header saying what it is:
#
#   Title, Chapter (where the mistake is made), Program (the chapter program that shows it best),
#   Scene and Args (what to render), Symptom, Cause, Look (the function to look in)
#
#   tools/gallery.sh BUILD             build every fault, render it beside the right picture, write
#                                      docs/gallery/NAME-*.png and docs/gallery.md
#   tools/gallery.sh BUILD --prove N   build fault N and exit 0 when the picture check catches it (its
#                                      picture fails the reference-image rule against the right one),
#                                      1 when it does not, 2 when the fault cannot be built
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
cp -r Makefile common chapters tools bench fuzz "$work"/
mkdir -p "$work/scenes" && cp scenes/*.scene "$work/scenes/" && cp -r scenes/models "$work/scenes/"
# The copy builds the way $build was built (build/san: with the sanitizers).
san=0
case $build in */san) san=1 ;; esac
if [ -d "$build/common" ]; then
    mkdir -p "$work/$build"
    cp -rp "$build"/common "$build"/chapters "$work/$build/" 2>/dev/null
    cp -p "$build"/chapter-* "$work/$build/" 2>/dev/null
fi

# Builds chapter program NN with the fault's patch applied; prints the program's path.
build_fault() { # build_fault PATCH NN
    local patch=$1 nn=$2 file
    for file in $(sed -n 's|^+++ b/||p' "$patch"); do
        cp "$file" "$work/$file" # pristine again, with a new time, so make recompiles it
    done
    # The copy lies inside this repository's tree: GIT_CEILING_DIRECTORIES keeps git apply from
    # finding the repository and applies the patch to the copy as plain files.
    (cd "$work" && GIT_CEILING_DIRECTORIES=$(dirname "$PWD") git apply -p1 "$OLDPWD/$patch") || return 1
    env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS make --no-print-directory -C "$work" SAN=$san "$build/chapter-$nn" \
        >"$work/build.log" 2>&1 || return 1
    for file in $(sed -n 's|^+++ b/||p' "$patch"); do
        cp "$file" "$work/$file" # leave the copy pristine for the next fault
    done
    echo "$work/$build/chapter-$nn"
}

# Renders with program $1 the fault's scene and args into $2.
render() { # render PROGRAM PATCH PNG
    local scene args
    scene=$(field "$2" Scene)
    args=$(field "$2" Args)
    eval "\"\$1\" \"\$scene\" ${args} \"\${size[@]}\" --quiet -o \"\$3\""
}

# Whether pictures a and b pass the reference-image rule (tests/image_test_support.h): at least
# 99.95 % of pixels within 1 level and a mean difference of at most 0.01 levels.
passes_regression() { # passes_regression A B
    local result
    result=$("$build/compare" "$1" "$2")
    echo "$result" | awk '{ within1 = $6; sub("%", "", within1); exit !(within1 >= 99.95 && $4 <= 0.01) }'
}

prove() { # prove NAME
    local patch=tools/gallery/$1.patch program nn wrong right
    [ -f "$patch" ] || { echo "no fault called $1" >&2; return 2; }
    nn=$(printf '%02d' "$(field "$patch" Program)")
    program=$(build_fault "$patch" "$nn") || { echo "$1: the patch does not apply or build (see $work/build.log)" >&2; return 2; }
    wrong=$work/wrong.png
    right=$work/right.png
    render "$program" "$patch" "$wrong" || { echo "$1: the wrong program failed to render" >&2; return 2; }
    render "$build/chapter-$nn" "$patch" "$right" || { echo "$1: the right program failed to render" >&2; return 2; }
    if passes_regression "$right" "$wrong"; then
        echo "$1: NOT caught: the picture check sees no difference ($("$build/compare" "$right" "$wrong"))"
        return 1
    fi
    echo "$1: caught by the picture check ($("$build/compare" "$right" "$wrong"))"
    return 0
}

if [ "$mode" = prove ]; then
    prove "$only"
    exit
fi

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
    echo "(\`git apply tools/gallery/NAME.patch\`, and \`git checkout common\` to undo). \`make test\` proves that"
    echo "the checks catch every one (\`tests/test_gallery.c\`): the wrong picture fails the reference-image"
    echo "rule against the right one."
    echo
    echo "| fault | chapter | symptom |"
    echo "|---|---|---|"
    for patch in tools/gallery/*.patch; do
        name=$(basename "$patch" .patch)
        echo "| [$(field "$patch" Title)](#$name) | $(field "$patch" Chapter) | $(field "$patch" Symptom) |"
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
    render "$program" "$patch" "docs/gallery/$name-wrong.png" &&
        render "$build/chapter-$nn" "$patch" "docs/gallery/$name-right.png" || { status=1; continue; }
    stats=$("$build/compare" "docs/gallery/$name-right.png" "docs/gallery/$name-wrong.png" \
            "$work/side.png" "docs/gallery/$name-diff.png")
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
        echo "* **Caught by:** the picture check: $2 levels at most, mean $4, $6 of pixels within 1 level (the rule needs 99.95 % and 0.01)."
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

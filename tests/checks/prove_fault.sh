#!/bin/sh
# prove_fault.sh: builds the grader with one planted fault and shows that make check reports it (the
# coursework kit's proof; tests/test_coursework.c runs it on every fault).
#
#   tests/checks/prove_fault.sh BUILD PATCH [SAYS]
#
# PATCH is a fault, tests/checks/faults/NAME.patch (or a gallery fault, tools/gallery/NAME.patch): a
# mistake in a task's body, with a header saying what must follow from it:
#
#   Check: the tasks whose checks must fail with the fault in (unit tasks, N.K), e.g. "2.1"
#   Says:  words the grader's report must contain, e.g. "sphere_normal crashed (segmentation fault"
#   Says-sanitized: what it must contain instead in a build with the sanitizers (BUILD ends in /san), when
#          that differs: AddressSanitizer reports a crash itself and stops the process with a status
#
# The fault goes into a private copy of the sources, built from BUILD's objects so that only the patched
# file is compiled again; the repository is never touched. Exits 0 when every Check task fails and the
# report says the words, 1 when not (the report is printed), 2 when the fault does not apply or build.
# SAYS, when given, stands for the Says line (for a gallery fault, which has none).
# WHITTED_CHECK_SECONDS, when set, is passed on (a fault that loops for ever is proved with a short limit).
set -u
cd "$(dirname "$0")/../.."
build=${1:?usage: tests/checks/prove_fault.sh BUILD PATCH [SAYS]}
patch=${2:?usage: tests/checks/prove_fault.sh BUILD PATCH [SAYS]}
[ -f "$patch" ] || { echo "no fault $patch" >&2; exit 2; }
field() { sed -n "s/^$1: //p" "$patch" | head -n 1; }
tasks=$(field Check)
says=${3:-$(field Says)}
case $build in */san) [ -n "$(field Says-sanitized)" ] && says=$(field Says-sanitized) ;; esac
[ -n "$tasks" ] || { echo "$patch names no Check task" >&2; exit 2; }

work=out/faults/work-$$
trap 'rm -rf "$work"' EXIT
mkdir -p "$work"
cp -rp Makefile common chapters bench fuzz tools tests "$work"/
san=0
case $build in */san) san=1 ;; esac
if [ -d "$build/common" ]; then
    mkdir -p "$work/$build"
    cp -rp "$build"/common "$build"/checks "$build"/tests "$build"/tools "$work/$build/" 2>/dev/null
fi
# The copy lies inside this repository's tree: GIT_CEILING_DIRECTORIES keeps git apply from finding the
# repository, so the patch applies to the copy as plain files (with a new time: make recompiles them).
(cd "$work" && GIT_CEILING_DIRECTORIES=$(dirname "$PWD") git apply -p1 "$OLDPWD/$patch") ||
    { echo "$patch does not apply" >&2; exit 2; }
# Built and graded as make check-N does (tests/checks/grade.sh): a fault that only makes the compiler warn
# is graded, with the warnings shown.
grade() {
    (cd "$work" && tests/checks/grade.sh "env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS make SAN=$san" "$build" "--task $1" \
        "$build/check" 2>&1)
}

status=0
report=""
for id in $tasks; do
    out=$(grade "$id")
    if [ $? -eq 2 ]; then
        printf '%s\n' "$out" >&2
        echo "$patch does not build" >&2
        exit 2
    fi
    report="$report$out
"
    if echo "$out" | grep -q "^  $id .* done "; then
        echo "$id is done with the fault in:"
        status=1
    elif ! echo "$out" | grep -q "FAIL  $id:"; then
        echo "$id does not fail its own checks with the fault in (needs another task?):"
        status=1
    fi
done
if [ -n "$says" ] && ! printf '%s' "$report" | grep -qF -- "$says"; then
    echo "the report does not say \"$says\":"
    status=1
fi
printf '%s' "$report"
exit $status

#!/bin/sh
# grade.sh: what make check-N and make check run: builds the grader and the chapters' programs, and grades
# (the coursework kit; docs/coursework.md). A compiler warning in the student's code does not stop the
# grading: the build treats warnings as errors, so when it fails, the grader builds again with warnings
# allowed, and if that works, grades with the warnings printed above and below the scoreboard.
#
#   tests/checks/grade.sh MAKE BUILD WHAT TARGET...   WHAT: the grader's arguments: a chapter's number,
#                                                     "all", or "--task 2.1"
#
# The objects of the files that warned are removed afterwards, so that the next build compiles them again
# and the warnings show until they are fixed (make chapter-N stops at them as before). Exits with the
# grader's status (0: every task done), or 2 when the code does not compile even with warnings allowed.
set -u
make=${1:?usage: tests/checks/grade.sh MAKE BUILD WHAT TARGET...}
build=${2:?usage: tests/checks/grade.sh MAKE BUILD WHAT TARGET...}
what=${3:?usage: tests/checks/grade.sh MAKE BUILD WHAT TARGET...}
shift 3
mkdir -p out/check
log=out/check/build.log
if $make --no-print-directory "$@" >"$log" 2>&1; then
    WHITTED_BUILD=$build "./$build/check" $what
    exit $?
fi
# The build failed: with warnings allowed (WERROR empty), is it only warnings?
if ! $make --no-print-directory WERROR= "$@" >"$log" 2>&1; then
    cat "$log"
    echo "make check: the code does not compile (the compiler's messages are above, and in $log): fix the first" \
         "error, then run the check again" >&2
    exit 2
fi
warnings=$(grep -E '(warning|error): ' "$log" | sed 's/ \[-Werror[^]]*\]$//')
if [ -z "$warnings" ]; then # it failed for another reason, which building again cured
    WHITTED_BUILD=$build "./$build/check" $what
    exit $?
fi
show_warnings() {
    echo "================================================================================================"
    count=$(printf '%s\n' "$warnings" | wc -l)
    [ "$count" -eq 1 ] && lines="1 line" || lines="$count lines"
    echo "COMPILER WARNINGS in your code ($lines; the compiler's whole output is in $log)."
    echo "They are graded anyway, but the copy builds with -Werror: make chapter-N stops at them until you fix"
    echo "them, and a warning is often the bug itself (an unused result, a missing return, a wrong type):"
    printf '%s\n' "$warnings" | sed 's/^/  /'
    echo "================================================================================================"
}
show_warnings
WHITTED_BUILD=$build "./$build/check" $what
status=$?
show_warnings
# Compiled again next time, so that the warnings show until they are fixed: every object whose
# dependency list (the compiler's .d file) names a file that warned.
printf '%s\n' "$warnings" | sed -n 's|^\([^:]*\.[ch]\):[0-9]*:[0-9]*: .*|\1|p' | sort -u | while IFS= read -r source; do
    grep -rlF --include='*.d' "$source" "$build" 2>/dev/null | sed 's|\.d$|.o|' | xargs -r rm -f
done
exit $status

#!/bin/sh
# student.sh: writes a student copy of the repository, the coursework kit's hand-out (make student).
#
#   tools/student.sh DIR [TASKS]    TASKS: task numbers such as "2.1 5.1", "all" (the default) or "none"
#   tools/student.sh DIR TASKS --sources-only   only the files with markers (DIR holds the rest already)
#   tools/student.sh --list         the marked tasks of this repository, one "N.K file what" a line
#
# Every file of the repository (what git tracks, plus new files not ignored) is copied to DIR; in the
# C files, the body of each function marked "/* TASK N.K: what */" whose task is chosen becomes a stub
# (tools/student_blank.awk). Files already in DIR with the same content are left untouched, so running
# it again on the same DIR with other tasks rebuilds only what changed. docs/coursework.md explains it.
set -eu
cd "$(dirname "$0")/.."

marked() {
    grep -n '^/\* TASK [0-9][0-9]*\.[0-9][0-9]*: .* \*/$' common/*.[ch] chapters/*/main.c 2>/dev/null |
        sed 's|^\([^:]*\):[0-9]*:/\* TASK \([0-9.]*\): \(.*\) \*/$|\2 \1 \3|' | sort -t. -k1,1n -k2,2n
}

if [ "${1:-}" = "--list" ]; then
    marked
    exit 0
fi
if [ $# -lt 1 ] || [ -z "$1" ]; then
    echo "usage: tools/student.sh DIR [TASKS]   (make student DIR=path TASKS=\"2.1 5.1\")" >&2
    exit 2
fi
dir=$1
tasks=${2:-all}
[ -n "$tasks" ] || tasks=all
if [ "$tasks" != all ] && [ "$tasks" != none ]; then
    known=$(marked | cut -d' ' -f1)
    for t in $tasks; do
        if ! printf '%s\n' $known | grep -qx "$t"; then
            echo "tools/student.sh: no task $t is marked in the sources (marked: $(echo $known))" >&2
            exit 2
        fi
    done
fi
case "$(cd "$(dirname "$dir")" 2>/dev/null && pwd)/$(basename "$dir")" in
"$(pwd)"|"$(pwd)"/*) echo "tools/student.sh: $dir is inside the repository; choose a folder outside it" >&2; exit 2 ;;
esac
if [ "${3:-}" = "--sources-only" ]; then
    files=$(marked | cut -d' ' -f2 | sort -u)
elif ! files=$(git ls-files --cached --others --exclude-standard 2>/dev/null); then
    echo "tools/student.sh: needs the repository's git history to know which files to copy" >&2
    exit 2
fi
mkdir -p "$dir"
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
printf '%s\n' "$files" | while IFS= read -r f; do
    [ -f "$f" ] || continue # deleted but not yet committed
    mkdir -p "$dir/$(dirname "$f")"
    case "$f" in
    common/*.[ch] | chapters/*.c) awk -v tasks="$tasks" -f tools/student_blank.awk "$f" >"$tmp" ;;
    *) cp "$f" "$tmp" ;;
    esac
    if ! cmp -s "$tmp" "$dir/$f"; then
        # A new file keeps the repository's time stamp, a changed one gets a new one (make rebuilds it).
        if [ ! -e "$dir/$f" ] && cmp -s "$tmp" "$f"; then cp -p "$f" "$dir/$f"; else cp "$tmp" "$dir/$f"; fi
        chmod --reference="$f" "$dir/$f"
    fi
done
count=$(grep -rl 'TODO (chapter ' "$dir/common" "$dir/chapters" 2>/dev/null | wc -l)
echo "student copy in $dir: tasks ${tasks}; $count file(s) with blanked functions. Build and grade with make check."

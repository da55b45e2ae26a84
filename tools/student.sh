#!/bin/sh
# student.sh: writes a student copy of the repository, the coursework kit's hand-out (make student;
# docs/coursework.md explains it).
#
#   tools/student.sh DIR [TASKS] [--answers]   TASKS: task numbers such as "2.1 5.1", "all" (the
#                                               default) or "none"; --answers: a lecturer's copy
#   tools/student.sh DIR TASKS --sources-only   (for the kit's tests) rewrite only the files with markers,
#                                               over whatever DIR holds
#   tools/student.sh --list                     the marked tasks, one "N.K file what" a line
#   tools/student.sh --files                    the files with markers (a task's, or one tied to a task)
#
# Every file of the repository (what git tracks, plus new files not ignored) goes to DIR; in the C files,
# the body of each function marked "/* TASK N.K: what */" whose task is chosen becomes a stub
# (tools/student_blank.awk). Unless --answers is given, the copy is a hand-out: the model answers are
# left out (the ★★★ exercises' solutions, the gallery's patches, the tests' mutants and the planted
# faults, and the proofs that use them), the walkthroughs show the stubs where they quote a blanked body
# (tools/student_docs.awk), and README.md is written for the student (tools/student_readme.md).
#
# A new DIR becomes a git repository with one first commit. DIR must be new, empty, or a copy this
# script made: it keeps a list of what it wrote there (.student-copy), and when run again writes only
# the files that changed in the kit and that the student has not changed, and names the others.
set -eu
cd "$(dirname "$0")/.."

# The files that hold markers: a task's own, or a second one tied to it ("/* TASK N.K ALSO: what */", on a
# function that would give the task's answer away; it is blanked with the task).
MARKER='^/\* TASK [0-9][0-9]*\.[0-9][0-9]*\( ALSO\)\{0,1\}: .* \*/$'
marker_files() {
    grep -l "$MARKER" common/*.[ch] chapters/*/main.c 2>/dev/null
}

marked() {
    grep -n '^/\* TASK [0-9][0-9]*\.[0-9][0-9]*: .* \*/$' common/*.[ch] chapters/*/main.c 2>/dev/null |
        sed 's|^\([^:]*\):[0-9]*:/\* TASK \([0-9.]*\): \(.*\) \*/$|\2 \1 \3|' | sort -t. -k1,1n -k2,2n
}

# The files no copy gets: the forge's CI, which runs the authors' whole suite (make test-long needs every
# task done and the answers), and would fail on every push of a student's copy.
is_ci() {
    case $1 in
    .github/* | .ci/*) return 0 ;;
    esac
    return 1
}

# The files a hand-out leaves out: model answers, what proves the kit with them, and the lecturer's guide.
is_answer() {
    case $1 in
    tests/exercises/solutions.[ch] | tests/exercises/test_exercise_proof.c) return 0 ;;
    tools/gallery/*.patch | tests/test_gallery.c | tests/mutants/*.patch) return 0 ;;
    tests/checks/faults/* | tests/checks/prove_fault.sh | tests/test_coursework_proof.c) return 0 ;;
    tests/checks/task_trace.awk | tests/test_coursework_long.c) return 0 ;; # they need the reference
    # tests whose oracle is a second, plain route to a task's answer: chapter 16's brute-force loop over the
    # instances, a ray carried into each (16.1), and the gallery's refit of the leaves alone (16.2)
    tests/test_instances.c | tests/test_instance_bvh.c) return 0 ;;
    docs/coursework.md) return 0 ;;
    esac
    return 1
}

if [ "${1:-}" = "--list" ]; then
    marked
    exit 0
fi
if [ "${1:-}" = "--files" ]; then
    marker_files
    exit 0
fi
dir=""
tasks=""
answers=no
sources_only=no
for arg in "$@"; do
    case $arg in
    --answers) answers=yes ;;
    --sources-only) sources_only=yes ;;
    *) if [ -z "$dir" ]; then dir=$arg; else tasks=$arg; fi ;;
    esac
done
if [ -z "$dir" ]; then
    echo "usage: tools/student.sh DIR [TASKS] [--answers]   (make student DIR=path TASKS=\"2.1 5.1\" ANSWERS=1)" >&2
    exit 2
fi
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
manifest=$dir/.student-copy
if [ -d "$dir" ] && [ -n "$(ls -A "$dir")" ] && [ ! -f "$manifest" ]; then
    echo "tools/student.sh: $dir is not empty and is not a student copy (it has no .student-copy); choose a new" \
         "or empty folder" >&2
    exit 2
fi
if [ "$sources_only" = yes ]; then
    files=$(marker_files)
elif ! files=$(git ls-files --cached --others --exclude-standard 2>/dev/null); then
    echo "tools/student.sh: needs the repository's git history to know which files to copy" >&2
    exit 2
fi

# The first chosen task's chapter is where the student starts.
case $tasks in
all) first=$(marked | head -n 1 | cut -d' ' -f1) ;;
none) first="" ;;
*) first=$(marked | cut -d' ' -f1 | while read -r id; do
       if printf ' %s ' "$tasks" | grep -qF " $id "; then echo "$id"; fi
   done | head -n 1) ;;
esac
# Everything the copy will hold, first in a staging folder: the docs are rewritten from the blanked code.
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
printf '%s\n' "$files" | while IFS= read -r f; do
    [ -f "$f" ] || continue # deleted but not yet committed
    if is_ci "$f"; then continue; fi
    if [ "$answers" = no ] && is_answer "$f"; then continue; fi
    printf '%s\n' "$f"
done | tar -cf - -T - | tar -xf - -C "$stage"
for f in $(cd "$stage" && grep -l "$MARKER" common/*.[ch] chapters/*/main.c 2>/dev/null); do
    awk -v tasks="$tasks" -f tools/student_blank.awk "$f" >"$stage/$f"
done
# A lecturer's copy gets the model answers whole: every blanked function as the reference has it (the
# walkthroughs quote only some of them, and some only in part).
if [ "$answers" = yes ] && [ "$sources_only" = no ]; then
    {
        echo "# The model answers"
        echo
        echo "Every function blanked in this copy (tasks: $tasks), as the reference has it: each task's own"
        echo "function, then those that go with it (\"TASK N.K ALSO\"), which would give its answer away."
        echo "This file is in a lecturer's copy only (\`make student ... ANSWERS=1\`); a hand-out has none."
        for f in $(marker_files); do
            awk -v tasks="$tasks" -v file="$f" '
                function chosen(id) { return tasks == "all" || (tasks != "none" && index(" " tasks " ", " " id " ") > 0) }
                match($0, /^\/\* TASK [0-9]+\.[0-9]+( ALSO)?: .* \*\/$/) {
                    id = $3; sub(/:$/, "", id)
                    if (!chosen(id)) next
                    what = $0; sub(/^\/\* TASK [0-9.]+( ALSO)?: /, "", what); sub(/ \*\/$/, "", what)
                    printf "%s\t%s\t%s%s\n", id, file, ($0 ~ / ALSO: / ? "goes with it: " : ""), what
                    body = 1; next
                }
                body { printf "%s\t%s\t\t%s\n", id, file, $0 } body && /^}$/ { body = 0 }' "$f"
        done | sort -s -t. -k1,1n -k2,2n | awk -F'\t' '
            $3 != "" { if (open) print "```"; printf "\n## Task %s: %s (`%s`)\n\n```c\n", $1, $3, $2; open = 1; next }
            { line = $0; sub(/^[^\t]*\t[^\t]*\t\t/, "", line); print line }
            END { if (open) print "```" }'
    } >"$stage/docs/model-answers.md"
fi
if [ "$answers" = no ] && [ "$sources_only" = no ]; then
    code=$(ls common/*.[ch] chapters/*/main.c tools/*.[ch] bench/*.c tests/*.[ch] scenes/*.scene 2>/dev/null | tr '\n' ' ')
    awk -v copy="$stage" -v files="$code" -v tasks="$tasks" -f tools/student_docs.awk $(ls docs/*.md | grep -vx docs/coursework.md)
    table=$(marked | while read -r id file what; do
        if [ "$tasks" = all ] || printf ' %s ' "$tasks" | grep -qF " $id "; then
            name=$(awk -v id="$id" 'found { gsub(/__attribute__\(\([^)]*\)\)/, ""); sub(/\(.*$/, ""); sub(/^.*[ *]/, "")
                                            print; exit }
                                    index($0, "/* TASK " id ": ") == 1 { found = 1 }' "$file")
            echo "| $id | $what | \`$name\` in \`$file\` | \`make check-${id%%.*}\` |"
        fi
    done)
    if [ -n "$table" ]; then
        table=$(printf '| task | what | you write | graded by |\n|---|---|---|---|\n%s' "$table")
    else
        table="No task is blanked in this copy: every function is the reference's."
    fi
    chapter=${first%%.*}
    [ -n "$chapter" ] || chapter=1
    walkthrough=$(ls docs/"$(printf '%02d' "$chapter")"-*.md | head -n 1)
    awk -v table="$table" -v chapter="$chapter" -v walkthrough="$walkthrough" '
        $0 == "@TASKS@" { print table; next }
        { gsub(/@CHAPTER@/, chapter); gsub(/@WALKTHROUGH@/, walkthrough); print }' tools/student_readme.md >"$stage/README.md"
fi

# Then into DIR: a file the student changed since this script wrote it (its checksum is not the one
# .student-copy lists) is kept, and named.
new_copy=no
[ -f "$manifest" ] || new_copy=yes
mkdir -p "$dir"
[ -f "$manifest" ] || : >"$manifest"
lists=$(mktemp -d)
trap 'rm -rf "$stage" "$lists"' EXIT
(cd "$stage" && find . -type f | sed 's|^\./||' | sort) >"$lists/staged"
(cd "$stage" && tr '\n' '\0' <"$lists/staged" | xargs -0 sha1sum) >"$lists/new"
(cd "$dir" && while IFS= read -r f; do [ -f "$f" ] && printf '%s\0' "$f"; done <"$lists/staged" | xargs -0 -r sha1sum) \
    >"$lists/old"
# For each staged file: "write" it, or leave it "same", or "keep" the student's; then the new list.
awk -v sources_only="$sources_only" -v plan="$lists/plan" -v list="$lists/list" '
    FILENAME == ARGV[1] { written[substr($0, 43)] = $0; next }
    FILENAME == ARGV[2] { old[substr($0, 43)] = $0; next }
    { f = substr($0, 43)
      if (!(f in old)) action = "write"
      else if (old[f] == $0) action = "same"
      else if (sources_only == "yes" || old[f] == written[f]) action = "write"
      else action = "keep"
      print action " " f > plan
      if (action == "keep") { if (f in written) print written[f] > list }
      else print $0 > list
      staged[f] = 1 }
    END { for (f in written) if (!(f in staged)) print written[f] > list }
' "$manifest" "$lists/old" "$lists/new"
if [ "$new_copy" = yes ]; then
    (cd "$stage" && tar -cf - .) | tar -xf - -C "$dir"
else while read -r action f; do
    [ "$action" = write ] || continue
    mkdir -p "$dir/$(dirname "$f")"
    # A new file keeps its time stamp (the repository's, for a file copied as it is), a changed one gets
    # a new one, so that make rebuilds what depends on it.
    if [ -e "$dir/$f" ]; then cp "$stage/$f" "$dir/$f"; else cp -p "$stage/$f" "$dir/$f"; fi
done <"$lists/plan"; fi
sort -k2 "$lists/list" >"$manifest"
grep '^keep ' "$lists/plan" | cut -c6- >"$lists/kept" || true

if [ "$new_copy" = yes ] && [ "$sources_only" = no ]; then
    git -C "$dir" init -q
    git -C "$dir" add -A
    if [ -z "$(git -C "$dir" config user.name || true)" ] || [ -z "$(git -C "$dir" config user.email || true)" ]; then
        set -- -c user.name="make student" -c user.email="student@localhost"
    else
        set --
    fi
    git -C "$dir" "$@" commit -q -m "The ray tracing coursework, as handed out (tasks: $tasks)"
fi
if [ -s "$lists/kept" ]; then
    echo "tools/student.sh: kept $(wc -l <"$lists/kept") file(s) changed since the copy was made; the kit's version" \
         "differs and was not written (move a file away and run make student again to get the kit's):" >&2
    sed 's/^/  /' "$lists/kept" >&2
fi
count=$(grep -rl 'TODO (chapter ' "$dir/common" "$dir/chapters" 2>/dev/null | wc -l)
if [ "$answers" = yes ]; then what="model answers kept (a lecturer's copy)"; else what="model answers left out"; fi
if [ -n "$first" ]; then
    start="Start with: cd $dir && make check-${first%%.*}"
else
    start="Every function is the reference's: cd $dir && make check grades them all"
fi
echo "student copy in $dir: tasks ${tasks}; $count file(s) with blanked functions; $what. $start"

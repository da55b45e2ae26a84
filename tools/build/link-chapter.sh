#!/usr/bin/env bash
# link-chapter.sh BUILD LINK-COMMAND...: links a chapter program. When the link fails because the
# chapter calls a function of common/ that it does not link, it says which chapter introduces that
# function: a chapter links only the modules of its own and earlier chapters (MODULES_NN in the
# Makefile), so such a call is a reach for a later chapter's idea.
set -u
build=$1
shift
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if "$@" 2>"$log"; then
    cat "$log" >&2
    exit 0
fi
cat "$log" >&2
# The module each chapter introduces, from lines such as "MODULES_05 := $(MODULES_04) aabb box world".
introduced=$(awk '/^MODULES_[0-9][0-9] :=/ {
    n = substr($1, 9) + 0
    for (k = 3; k <= NF; k++) if ($k !~ /^\$\(/) print $k, n
}' Makefile)
grep -o "undefined reference to \`[A-Za-z_0-9]*'" "$log" | sed "s/.*\`\(.*\)'/\1/" | sort -u |
while read -r name; do
    for object in "$build"/common/*.o; do
        if nm --defined-only "$object" 2>/dev/null | grep -q " [TDBR] $name\$"; then
            module=$(basename "$object" .o)
            chapter=$(echo "$introduced" | awk -v m="$module" '$1 == m { print $2; exit }')
            echo "note: $name is in common/$module.c, which chapter ${chapter:-?} introduces; this program links only the modules of its own and earlier chapters (MODULES_NN in the Makefile)" >&2
            break
        fi
    done
done
exit 1

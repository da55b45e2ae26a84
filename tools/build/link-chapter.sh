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
# What each object of common/ defines, "build/common/MODULE.o:ADDRESS TYPE NAME" a line (one nm for all).
defined=$(nm --defined-only -A "$build"/common/*.o 2>/dev/null)
grep -o "undefined reference to \`[A-Za-z_0-9]*'" "$log" | sed "s/.*\`\(.*\)'/\1/" | sort -u |
while read -r name; do
    object=$(echo "$defined" | awk -v name="$name" '$3 == name && $2 ~ /^[TDBR]$/ { sub(/:.*/, "", $1); print $1; exit }')
    [ -n "$object" ] || continue
    module=$(basename "$object" .o)
    chapter=$(echo "$introduced" | awk -v m="$module" '$1 == m { print $2; exit }')
    echo "note: $name is in common/$module.c, which chapter ${chapter:-?} introduces; this program links only the modules of its own and earlier chapters (MODULES_NN in the Makefile)" >&2
done
exit 1

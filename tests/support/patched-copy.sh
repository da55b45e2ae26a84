#!/bin/sh
# patched-copy.sh PATCH DEST DIR...: makes DEST a copy of the directories DIR... (common, chapters) with
# PATCH applied, for the tests' deliberately wrong tracers (tests/mutants/, built by the Makefile). The
# repository itself is never patched: the fault lives only in the copy.
#
# A file of DEST that already holds the right bytes is left alone, time stamp included, so make
# recompiles only what the patch or a later edit of the sources changes.
set -eu
patch=$1
dest=$2
shift 2
stage=$dest.stage
rm -rf "$stage"
mkdir -p "$stage" "$dest"
cp -rp "$@" "$stage"/
# The copy lies inside this repository's tree: GIT_CEILING_DIRECTORIES keeps git apply from finding the
# repository, so it patches the copy as plain files.
(cd "$stage" && GIT_CEILING_DIRECTORIES=$(cd .. && pwd) git apply -p1) <"$patch"
(cd "$stage" && find . -type f) | while IFS= read -r f; do
    if ! cmp -s "$stage/$f" "$dest/$f"; then
        mkdir -p "$(dirname "$dest/$f")"
        cp -p "$stage/$f" "$dest/$f"
    fi
done
rm -rf "$stage"

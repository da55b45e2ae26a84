#!/usr/bin/env bash
# fetch-bunny.sh: remakes scenes/models/bunny.ply from the npm package bunny@1.0.1.
#
#   tools/models/fetch-bunny.sh [OUTPUT.ply]      (default: scenes/models/bunny.ply)
#
# Needs node and npm, and the npm registry. The result is committed, so a build never runs this:
# run it only to check or remake the file. The package tarball is fetched with `npm pack` into a
# temporary directory, checked against its known SHA-1, unpacked, converted by
# tools/models/bunny-to-ply.js, and the temporary directory is removed again.
set -euo pipefail

VERSION=1.0.1
SHA1=86383da45ab7a99571a5a572b7be0e3564815f9e   # the registry's shasum of bunny-1.0.1.tgz

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-"$root/scenes/models/bunny.ply"}

command -v node >/dev/null 2>&1 || { echo "fetch-bunny: node is needed (apt-get install nodejs npm)" >&2; exit 1; }
command -v npm >/dev/null 2>&1 || { echo "fetch-bunny: npm is needed (apt-get install npm)" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/fetch-bunny.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

(cd "$tmp" && npm pack --silent "bunny@$VERSION" >/dev/null)
tarball="$tmp/bunny-$VERSION.tgz"
[ -f "$tarball" ] || { echo "fetch-bunny: npm pack did not produce $tarball" >&2; exit 1; }
got=$(sha1sum "$tarball" | cut -d' ' -f1)
if [ "$got" != "$SHA1" ]; then
    echo "fetch-bunny: $tarball has SHA-1 $got, expected $SHA1" >&2
    exit 1
fi
tar -xzf "$tarball" -C "$tmp"   # unpacks into $tmp/package

mkdir -p "$(dirname "$out")"
node "$here/bunny-to-ply.js" "$tmp/package" "$tmp/bunny.ply"
mv "$tmp/bunny.ply" "$out"
echo "fetch-bunny: moved it to $out" >&2

#!/usr/bin/env bash
# install-deps.sh: installs the Debian packages whitted needs, only those that are missing.
# Called by the Makefile before every build; safe to run any number of times.
# As root it runs apt-get; otherwise it prints the exact command to run and fails.
set -u

missing=()
have_pkgconfig() { command -v pkg-config >/dev/null 2>&1 && pkg-config --exists "$1"; }

command -v gcc >/dev/null 2>&1 || missing+=(gcc)
command -v pkg-config >/dev/null 2>&1 || missing+=(pkg-config)
have_pkgconfig stb || missing+=(libstb-dev)
have_pkgconfig criterion || missing+=(libcriterion-dev)
command -v povray >/dev/null 2>&1 || missing+=(povray)
# Optional: Intel Embree 3, the yardstick of `make bench`; asked for only by that target.
if [ "${WHITTED_EXTRAS:-}" = "bench" ]; then
    [ -e /usr/include/embree3/rtcore.h ] || missing+=(libembree-dev)
fi

[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ]; then
    echo "whitted needs these Debian packages: ${missing[*]}" >&2
    echo "install them with:  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
    exit 1
fi
echo "installing missing packages: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
if ! apt-get install -y -q "${missing[@]}" >&2; then
    apt-get update -q >&2 && apt-get install -y -q "${missing[@]}" >&2 || exit 1
fi

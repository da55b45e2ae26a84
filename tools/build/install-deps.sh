#!/usr/bin/env bash
# install-deps.sh: makes sure the Debian packages a make target needs are there, installing only what
# is missing. Called by the Makefile before every build; safe to run any number of times.
#
#   tools/build/install-deps.sh [NEED...]     NEED: build (the default), test, compare, cycles, results, bench,
#                                             profile, fuzz, web, test-web, farm, video
#
#   build    gcc, pkg-config and stb (libstb-dev): enough for make chapter-N
#   test     build + Criterion (libcriterion-dev), POV-Ray, gnuplot (gnuplot-nox) and ffmpeg: make test
#            and make test-long, whose tests check make results' committed plots, run its quick mode
#            and make chapter 16's film
#   compare  build + POV-Ray: make compare
#   cycles   build + Blender (blender), for its Cycles renderer: make compare-cycles (chapter 15)
#   results  build + POV-Ray and gnuplot: make results (which adds bench for its Embree table)
#   bench    build + Intel Embree 3 (libembree-dev): make bench
#   profile  bench + valgrind, whose callgrind counts instructions, cache misses and mispredicted
#            branches: make bench-profile
#   fuzz     clang with its libFuzzer and sanitizer runtimes (clang; on systems where the runtimes are
#            a package of their own, libclang-rt-N-dev for clang N): make fuzz
#   web      Emscripten (emscripten, with Debian's clang, LLVM and binaryen), to compile the chapters to
#            WebAssembly: make web and make serve
#   farm     build + Slurm (slurm-wlm) and MUNGE (munge), for the one-node cluster of make test-farm
#   test-web web + headless Chromium (chromium), its WebDriver (chromium-driver) and Selenium for the
#            system's Python (python3-selenium, so the test runs with /usr/bin/python3): make test-web
#   video    build + ffmpeg: chapter 16's --video, which makes a film of its frames
#
# How it installs: as root with apt-get; otherwise with `sudo apt-get` when sudo needs no password.
# Without either (a lab machine), the only library the chapters need, stb, is fetched into .deps/ with
# `apt-get download` and unpacked with `dpkg -x`, neither of which needs root, and the Makefile builds
# against it (a compiler must already be there). Anything else it cannot install it names, with the
# command for someone who has root, and fails. WHITTED_DEPS=local forces the .deps/ route for stb.
set -u
cd "$(dirname "$0")/../.."

needs=("$@")
[ ${#needs[@]} -eq 0 ] && needs=(build)

have_command() { command -v "$1" >/dev/null 2>&1; }
have_pkgconfig() { have_command pkg-config && pkg-config --exists "$1"; }
# stb unpacked into .deps/ by an earlier run without root.
have_local_stb() { compgen -G ".deps/root/usr/lib/*/libstb.a" >/dev/null && [ -d .deps/root/usr/include/stb ]; }
# clang links a libFuzzer program: clang is there and so are its runtimes.
have_libfuzzer() {
    have_command clang && printf 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n) { return d[0] + (int)n; }\n' |
        clang -fsanitize=fuzzer,address,undefined -x c - -o /dev/null >/dev/null 2>&1
}
have_stb() { { [ "${WHITTED_DEPS:-}" != local ] && have_pkgconfig stb; } || have_local_stb; }

missing=()
want() { # want PACKAGE: add it to the list once
    local p
    for p in "${missing[@]+"${missing[@]}"}"; do [ "$p" = "$1" ] && return; done
    missing+=("$1")
}
for need in "${needs[@]}"; do
    case $need in
    build | test | compare | cycles | results | bench | profile | farm | video)
        have_command gcc || want gcc
        have_command pkg-config || want pkg-config
        have_stb || want libstb-dev
        ;;&
    test)
        have_pkgconfig criterion || want libcriterion-dev
        have_command povray || want povray
        have_command gnuplot || want gnuplot-nox
        have_command ffmpeg || want ffmpeg
        ;;
    results)
        have_command povray || want povray
        have_command gnuplot || want gnuplot-nox
        ;;
    compare) have_command povray || want povray ;;
    video) have_command ffmpeg || want ffmpeg ;;
    cycles) have_command blender || want blender ;;
    bench | profile)
        [ -e /usr/include/embree3/rtcore.h ] || want libembree-dev
        ;;&
    profile) have_command valgrind || want valgrind ;;
    farm)
        have_command slurmctld || want slurm-wlm
        have_command munged || want munge
        ;;
    bench) ;;
    fuzz)
        if ! have_command clang; then
            want clang
        elif ! have_libfuzzer; then
            want "libclang-rt-$(clang -dumpversion | cut -d. -f1)-dev"
        fi
        ;;
    web | test-web)
        have_command emcc || [ -x /usr/bin/emcc ] || want emscripten
        ;;&
    test-web)
        have_command chromium || want chromium
        have_command chromedriver || want chromium-driver
        /usr/bin/python3 -c 'import selenium' >/dev/null 2>&1 || want python3-selenium
        ;;
    build | web) ;;
    *)
        echo "install-deps.sh: unknown need '$need' (build, test, compare, cycles, results, bench, profile, fuzz, web, test-web, farm or video)" >&2
        exit 2
        ;;
    esac
done
[ ${#missing[@]} -eq 0 ] && exit 0

apt_install() { # apt_install PREFIX...: runs PREFIX apt-get install, updating the lists if needed
    echo "installing missing packages: ${missing[*]}" >&2
    "$@" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}" >&2 && return 0
    "$@" apt-get update -q >&2 && "$@" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}" >&2
}

if [ "${WHITTED_DEPS:-}" != local ]; then
    if [ "$(id -u)" -eq 0 ]; then
        apt_install
        exit
    fi
    if have_command sudo && sudo -n true 2>/dev/null; then
        apt_install sudo -n
        exit
    fi
fi

# No root. stb can be unpacked into .deps/ without it; everything else must be installed by someone
# who has root.
others=()
for p in "${missing[@]}"; do [ "$p" != libstb-dev ] && others+=("$p"); done
if [ ${#others[@]} -eq 0 ]; then
    echo "no root: fetching libstb-dev into .deps/ (apt-get download, dpkg -x)" >&2
    rm -rf .deps/debs && mkdir -p .deps/debs .deps/root
    if (cd .deps/debs && apt-get download libstb-dev >&2) && dpkg -x .deps/debs/libstb-dev_*.deb .deps/root &&
       have_local_stb; then
        echo "stb is in .deps/root; the Makefile builds against it" >&2
        exit 0
    fi
    echo "could not fetch libstb-dev without root (apt-get download needs the package lists that" >&2
    echo "'apt-get update' makes, as root, once)." >&2
fi
echo "whitted needs these Debian packages: ${missing[*]}" >&2
echo "someone with root can install them with:  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
exit 1

#!/usr/bin/env bash
# farm.sh: renders one picture as tiles, or an animation's frames, as a Slurm job array on a cluster
# (tools/farm/render.sbatch), waits for it, and joins the tiles into the picture (build/assemble).
#
#   tools/farm/farm.sh [options] -- PROGRAM [ARGS...]
#
#   --tile-size W H   tiles of W x H pixels (default 64 64); with an adaptive antialias line, multiples
#                     of 32 (the chapter refuses tiles that cut its blocks)
#   --size W H        the picture's size as PROGRAM ARGS render it (default: asked of PROGRAM, by
#                     rendering its top-left pixel, or block, alone)
#   --frames N        render the N frames of chapter 16's animation instead, one task a frame, to
#                     DIR/frame-NNNN.png
#   --dir DIR         where the pieces and the logs go, a folder every node sees (default out/farm)
#   -o PICTURE        the joined picture (default DIR/picture.png)
#   --sbatch WORD     one more word for sbatch, e.g. --sbatch --partition=gpu (repeatable)
#
# PROGRAM ARGS is a chapter's command line, e.g. build/chapter-13 scenes/13-distributed.scene; run from
# the repository's folder (the tasks start there too). ARGS may not hold -o (each task writes to a name
# of its own), nor --frames, --frame or --video (farm.sh's --frames gives each task its frame), nor for
# tiles --heatmap or --hdr (every task would write the same file), nor --quiet when the size is asked of
# PROGRAM (its answer is what it prints): refused before anything is submitted. The sizes are held to a
# chapter's (at most 16384 pixels a side, 100000 frames), and the tiles to 100000 tasks.
# Exit status: 0 the picture or the frames are there, 1 a task or the assembly failed, 2 a bad command
# line.
set -u
here=$(cd "$(dirname "$0")" && pwd)
build=${WHITTED_BUILD:-build}
case $build in /*) ;; *) build=$here/../../$build ;; esac # a relative build folder is the repository's
assemble=${WHITTED_ASSEMBLE:-$build/assemble}

fail() { echo "farm.sh: $1" >&2; exit "${2:-2}"; } # fail MESSAGE [STATUS]
# A whole number from 1, written in decimal: no leading zero (bash's arithmetic would read 010 as octal,
# 8, and 08 not at all) and at most nine digits (so that products of two stay within its 64 bits).
whole() { [[ $1 =~ ^[1-9][0-9]{0,8}$ ]] || fail "$2 needs whole numbers from 1 to 999999999, written without leading zeros, got '$1'"; }

# within LIMIT (at most what PROGRAM takes, so that nothing is submitted that every task would refuse)
within() { [ "$1" -le "$2" ] || fail "$3 must be at most $2, got $1"; }
SIDE_MAX=16384     # a chapter's picture is at most this many pixels across and down (IMAGE_MAX_SIDE)
FRAMES_MAX=100000  # chapter 16's --frames takes at most this many
TASKS_MAX=100000   # tiles a job array is asked for, at most (Slurm's own MaxArraySize is often lower)

tile_w=64 tile_h=64 width= height= frames= dir=out/farm picture= extra=()
while [ $# -gt 0 ]; do
    case $1 in
    --tile-size) [ $# -ge 3 ] || fail "--tile-size needs W H"; whole "$2" --tile-size; whole "$3" --tile-size
        within "$2" $SIDE_MAX --tile-size; within "$3" $SIDE_MAX --tile-size; tile_w=$2 tile_h=$3; shift 3 ;;
    --size) [ $# -ge 3 ] || fail "--size needs W H"; whole "$2" --size; whole "$3" --size
        within "$2" $SIDE_MAX --size; within "$3" $SIDE_MAX --size; width=$2 height=$3; shift 3 ;;
    --frames) [ $# -ge 2 ] || fail "--frames needs N"; whole "$2" --frames; within "$2" $FRAMES_MAX --frames
        frames=$2; shift 2 ;;
    --dir) [ $# -ge 2 ] || fail "--dir needs a folder"; dir=$2; shift 2 ;;
    -o) [ $# -ge 2 ] || fail "-o needs a file name"; picture=$2; shift 2 ;;
    --sbatch) [ $# -ge 2 ] || fail "--sbatch needs a word"; extra+=("$2"); shift 2 ;;
    --) shift; break ;;
    *) fail "unknown option '$1' (the program's command line comes after --)" ;;
    esac
done
[ $# -ge 1 ] || fail "usage: farm.sh [--tile-size W H] [--size W H] [--frames N] [--dir DIR] [-o PICTURE] -- PROGRAM [ARGS...]"
# Options of PROGRAM that cannot work on a farm, refused before anything is made or submitted: each
# task writes its piece to a name render.sbatch gives it, so a file named here would be one file for
# every task, each writing over the last (a tile's heat-map or radiance is not joined; with --frames
# the chapter names each frame's files itself); and without --size the picture's size is read from
# what PROGRAM prints.
for word in "${@:2}"; do
    why=
    case $word in
    -o) why="each task writes its piece to a name of its own in $dir (tile-X-Y.png, frame-NNNN.png), given"
        why+=" after the program's arguments, so the program's -o would be overridden; name the joined picture"
        why+=" with farm.sh's -o, before --" ;;
    --heatmap | --hdr)
        what=heat-map
        [ "$word" = --hdr ] && what=radiance
        if [ -z "$frames" ]; then
            why="every task would write its tile's $what to that one file, each over the last, leaving only the"
            why+=" last task's tile (farm.sh joins only the pictures); render it on one machine"
        fi ;;
    --frames | --frame | --video)
        if [ -z "$frames" ]; then
            why="farm.sh's tiles make one picture, each task a piece of it; for an animation's frames give"
            why+=" farm.sh's --frames N, before --"
        else
            why="farm.sh's --frames N gives each task its own frame (--frames N --frame K); leave it out of the"
            why+=" program's arguments (a film is made from the frames afterwards)"
        fi ;;
    --quiet)
        if [ -z "$frames" ] && [ -z "$width" ]; then
            why="farm.sh reads the picture's size from what the program prints when it renders its top-left"
            why+=" pixel, which --quiet silences (every task runs quiet anyway); leave it out, or give --size W H"
        fi ;;
    esac
    [ -z "$why" ] || fail "the program's $word: $why"
done
command -v sbatch >/dev/null || fail "sbatch is not installed: this runs on a Slurm cluster (Debian's slurm-wlm)" 1
mkdir -p "$dir/logs" || fail "cannot make $dir" 1
picture=${picture:-$dir/picture.png}

submit() { # submit COUNT MODE ARGS...: the job array of COUNT tasks, waited for
    local count=$1
    shift
    echo "farm.sh: submitting $count tasks ($1) to Slurm" >&2
    sbatch --wait --quiet --array=0-$((count - 1)) --chdir="$PWD" --output="$dir/logs/%A_%a.log" \
        "${extra[@]+"${extra[@]}"}" "$here/render.sbatch" "$@" ||
        fail "the job array failed: the logs are in $dir/logs" 1
}

if [ -n "$frames" ]; then
    submit "$frames" frames "$dir" "$frames" "$@"
    echo "farm.sh: $frames frames in $dir" >&2
    exit 0
fi
if [ -z "$width" ]; then # the picture's size: what PROGRAM says when it renders its top-left pixel
    # (or, with an adaptive antialias line, its top-left block of 32 x 32 pixels)
    # A picture smaller than a block refuses the block's tile, and says its size in doing so.
    rendered=yes
    said=$("$@" --tile 0 0 1 1 -o /dev/null 2>&1) || said=$("$@" --tile 0 0 32 32 -o /dev/null 2>&1) || rendered=
    size=$(printf '%s\n' "$said" | sed -n 's/.* \(of\|past\) the \([0-9]*\) x \([0-9]*\) picture.*/\2 \3/p' | head -n 1)
    [ -n "$size" ] || [ -n "$rendered" ] || fail "$* could not render its top-left corner: $said; give --size W H" 1
    [ -n "$size" ] || fail "could not read the picture's size from: $said; give --size W H" 1
    read -r width height <<<"$size"
fi
across=$(((width + tile_w - 1) / tile_w)) down=$(((height + tile_h - 1) / tile_h))
[ $((across * down)) -le $TASKS_MAX ] ||
    fail "$across x $down tiles of $tile_w x $tile_h pixels are $((across * down)) tasks, more than $TASKS_MAX; give a larger --tile-size"
rm -f "$dir"/tile-*-*.png
submit $((across * down)) tiles "$dir" "$tile_w" "$tile_h" "$width" "$height" "$@"
tiles=()
for ((y = 0; y < height; y += tile_h)); do
    for ((x = 0; x < width; x += tile_w)); do tiles+=("$dir/tile-$x-$y.png"); done
done
"$assemble" --size "$width" "$height" -o "$picture" "${tiles[@]}" || fail "the tiles could not be joined" 1
echo "farm.sh: $across x $down tiles joined into $picture ($width x $height)" >&2

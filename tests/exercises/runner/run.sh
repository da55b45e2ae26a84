#!/bin/sh
# run.sh: make exercises, the checks of the walkthroughs' build exercises (★★★) on the student's own
# functions. An exercise whose function common/ does not define yet is "not started": a note says where
# to start. The others are linked, one small program each (exercise.c), and run.
#
#   tests/exercises/runner/run.sh BUILD OBJECT...   (make exercises: the objects of common/ and checks.o)
#
# CC, CFLAGS, LDFLAGS and LDLIBS come from make. Needs nothing but the compiler and nm. Exits 0 unless
# a started exercise fails its check.
set -u
cd "$(dirname "$0")/../../.."
build=${1:?usage: tests/exercises/runner/run.sh BUILD OBJECT...}
shift
mkdir -p "$build/exercises"
defined=$(nm -g --defined-only "$@" 2>/dev/null | awk 'NF == 3 { print $3 }')

# The exercises, one a line: id | title | the function (or table) that marks it started | the check
# (exercises.h) | what the check is given | where to write it | the walkthrough.
# Each check runs in well under a second; one that takes this long is caught in an endless loop
# (WHITTED_CHECK_SECONDS from the environment, as for make check-N, sets another limit).
EXERCISE_SECONDS=${WHITTED_CHECK_SECONDS:-60}
done=0 failing=0 waiting=0
while IFS='|' read -r id title marker check argument where page; do
    if ! printf '%s\n' "$defined" | grep -qx "$marker"; then
        echo "  --    exercise $id, $title: not started. Write $marker in $where ($page, Exercises)"
        waiting=$((waiting + 1))
        continue
    fi
    program=$build/exercises/exercise-$id
    if ! $CC $CFLAGS -Itests/exercises "-DEXERCISE_ID=\"$id\"" "-DEXERCISE_TITLE=\"$title\"" "-DEXERCISE_CHECK=$check" \
            "-DEXERCISE_FUNCTION=$argument" -c tests/exercises/runner/exercise.c -o "$program.o" ||
        ! $CC $LDFLAGS "$program.o" "$@" -o "$program" $LDLIBS; then
        echo "  FAIL  exercise $id, $title: its check does not build with your $marker (see the messages above)"
        failing=$((failing + 1))
    else
        # The check's own verdict, written by exercise.c once the check has run: a function that ends the
        # program (exit, a crash) or never returns leaves none, whatever the exit status says.
        rm -f "$program.verdict"
        timeout "$EXERCISE_SECONDS" "./$program" "$program.verdict" </dev/null
        status=$?
        verdict=$(cat "$program.verdict" 2>/dev/null)
        if [ "$status" -eq 0 ] && [ "$verdict" = ok ]; then
            done=$((done + 1))
        else
            failing=$((failing + 1))
            if [ "$status" -eq 124 ]; then
                echo "  FAIL  exercise $id, $title: the check did not finish within $EXERCISE_SECONDS s (an endless loop in $marker?)"
            elif [ "$status" -gt 128 ]; then
                echo "  FAIL  exercise $id, $title: the check crashed (signal SIG$(kill -l $((status - 128)))) in $marker or what it returned"
            elif [ -z "$verdict" ] && [ "$status" -eq 0 ]; then
                echo "  FAIL  exercise $id, $title: the program stopped (exit status 0) before the check finished: does $marker call exit?"
            elif [ -z "$verdict" ]; then
                echo "  FAIL  exercise $id, $title: the program stopped (exit status $status) before the check finished: $marker called exit or crashed (a sanitizer's report above would say where)"
            fi
        fi
    fi
done <<'TABLE'
2.4|a disc, a new kind of shape|disc_kind|check_disc|&disc_kind|common/disc.h and common/disc.c, and disc in MODULES_02|docs/02-sphere.md
3.4|smooth normals|mesh_vertex_normals|check_vertex_normals|mesh_vertex_normals|common/mesh_normals.c, and mesh_normals in MODULES_03|docs/03-triangle.md
4.4|a cylinder|cylinder_intersect|check_cylinder|cylinder_intersect|common/cylinder.c, and cylinder in MODULES_04|docs/04-plane.md
5.4|a bounding sphere|mesh_bounding_sphere|check_bounding_sphere|mesh_bounding_sphere|common/bounding_sphere.c, and bounding_sphere in MODULES_05|docs/05-aabb.md
6.4|Blinn's highlight|phong_blinn_highlight|check_blinn|phong_blinn_highlight|common/phong.c|docs/06-phong.md
7.4|soft shadows|shadow_area_fraction|check_area_fraction|shadow_area_fraction|common/shadow.c|docs/07-shadows.md
8.4|Fresnel by Schlick|whitted_schlick|check_schlick|whitted_schlick|common/whitted.c|docs/08-recursion.md
9.4|a uniform grid|grid_walk|check_grid_walk|grid_walk|common/grid.c, and grid in MODULES_09|docs/09-kdtree.md
10.4|the cost of a split|bvh_split_cost|check_split_cost|bvh_split_cost|common/bvh.c|docs/10-bvh.md
11.4|four children per node|bvh4_collapse|check_collapse|bvh4_collapse|common/fast_bvh_build.c|docs/11-fast.md
12.4|n rooks|supersample_rooks|check_rooks|supersample_rooks|common/supersample.c|docs/12-antialias.md
13.4|the concentric map|thin_lens_concentric|check_concentric|thin_lens_concentric|common/thin_lens.c|docs/13-distributed.md
14.4|the cylindrical map|image_map_cylindrical|check_cylindrical|image_map_cylindrical|common/image_map.c|docs/14-textures.md
15.4|the cone of a ball of light|sampling_sphere_cone|check_cone|sampling_sphere_cone|common/sampling.c|docs/15-paths.md
16.4|slerp, a turn at constant speed|keyframes_slerp|check_slerp|keyframes_slerp|common/keyframes.c|docs/16-instances.md
17.5|sampling GGX's normals|microfacet_ggx_sample_normal|check_ggx_normals|microfacet_ggx_sample_normal|common/microfacet.c|docs/17-rough.md
TABLE
echo "exercises: $done done, $failing failing, $waiting not started"
[ "$failing" -eq 0 ]

/* fast_bvh_build.h: building chapter 11's 4-wide hierarchy (fast_bvh.h), by collapsing chapter 10's
 * binary tree (rungs 2 to 4) or in float, straight into the 4-wide layout (rungs 5 to 7), or the 8-wide
 * one (rung 8) (chapter 11). */
#ifndef WHITTED_FAST_BVH_BUILD_H
#define WHITTED_FAST_BVH_BUILD_H

#include "bvh.h"
#include "fast_bvh.h"
#include "mesh.h"

/* Builds a hierarchy over the faces of m with the given split rule, at the given rung (from
 * FAST_BVH_RUNG_FIRST to FAST_BVH_RUNG_TOP, or rung 11: rung 9's tree with a float copy of its
 * triangles; others give NULL): chapter 10's bvh_build collapsed by
 * fast_bvh_collapse on rungs 2 to 4; from rung 5 on the float build by the SAH (the median split, quick
 * already, is built as on rung 4); on rung 8 with 8-wide nodes when the processor has AVX2
 * (fast_bvh_eight_available), else with rung 6's tree. Below rung 7, m is only read, and not kept: it may be changed or
 * freed afterwards. On rung 7 (compact leaves) the hierarchy reads its triangles from m: m must stay
 * as it is until the hierarchy is freed. A mesh without faces gives a hierarchy that nothing hits. From
 * rung 5 on, the SAH build runs on as many threads as OpenMP gives a parallel region (omp_get_max_threads:
 * OMP_NUM_THREADS or omp_set_num_threads) and makes the same tree, byte for byte, on any number. Returns
 * NULL when memory runs out. Free the result with fast_bvh_free. */
struct fast_bvh *fast_bvh_build(const struct mesh *m, enum bvh_split split, enum fast_bvh_rung rung);

/* Makes the 4-wide hierarchy of chapter 10's binary one (8-wide for rung 8 when the processor has AVX2),
 * to be walked at `rung` (2 to 8), and takes
 * binary's triangles and face numbers over (binary keeps its nodes, and is still to be freed with
 * bvh_free). Returns NULL, taking nothing, when memory runs out. */
struct fast_bvh *fast_bvh_collapse(struct bvh *binary, enum fast_bvh_rung rung);

#endif

/* fast_bvh_eight.h: rung 8 of chapter 11's ladder: the 8-wide tree walked with AVX2, all eight
 * children's slab tests in one instruction, and whether this processor can run it (chapter 11). */
#ifndef WHITTED_FAST_BVH_EIGHT_H
#define WHITTED_FAST_BVH_EIGHT_H

#include <stdbool.h>

#include "fast_bvh_tree.h"
#include "fast_bvh_walk.h"
#include "ray.h"

/* The environment variable that, set to anything, makes rung 8 fall back to rung 6 as on a processor
 * without AVX2: the tests run both paths with it. */
#define FAST_BVH_NO_AVX2_VARIABLE "WHITTED_NO_AVX2"

/* True when rung 8's 8-wide walk can run here: the processor has AVX2 (asked at run time, once per
 * call) and FAST_BVH_NO_AVX2_VARIABLE is not set. The build asks it, and makes rung 6's tree instead
 * when it is false. */
bool fast_bvh_eight_available(void);

/* Answers query `kind` for r with t_min < t < t_max over b, whose nodes are 8-wide (b->nodes8 is not
 * NULL, which the build makes only when fast_bvh_eight_available() is true), into *q as fast_bvh.c's
 * own walk does, with the same answers: the brute-force loop's, bit for bit. Returns q->found. Adds to
 * the calling thread's counters: node_visits, box_tests, triangle_tests. */
bool fast_bvh_eight_traverse(const struct fast_bvh *b, const ray *r, double t_min, double t_max, enum query kind,
                             struct query_state *q);

#endif

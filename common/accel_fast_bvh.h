/* accel_fast_bvh.h: plugs chapter 11's fast BVH into the world's triangle queries (chapter 11). */
#ifndef WHITTED_ACCEL_FAST_BVH_H
#define WHITTED_ACCEL_FAST_BVH_H

#include <stdbool.h>
#include <stddef.h>

#include "accel.h"

/* Builds the hierarchy over all of w's triangles with the given split rule (an enum bvh_split) at the
 * given rung (an enum fast_bvh_rung; rung 1 is chapter 10's accel_world_use_bvh) and routes the world's
 * triangle queries through it. On rung 7 the hierarchy reads its triangles from w's gathered mesh,
 * which w keeps until the hierarchy is freed. Returns false with the reason in err when memory runs out or the rung
 * does not exist. */
bool accel_world_use_fast_bvh(struct accel_world *w, int split, int rung, char *err, size_t err_size);

#endif

/* accel_fast_bvh.h: plugs chapter 11's fast BVH into the world's triangle queries (chapter 11). */
#ifndef WHITTED_ACCEL_FAST_BVH_H
#define WHITTED_ACCEL_FAST_BVH_H

#include <stdbool.h>
#include <stddef.h>

#include "accel.h"

/* Builds the hierarchy over all of w's triangles with the given split rule (an enum bvh_split) at the
 * given rung (an enum fast_bvh_rung; rung 1 is chapter 10's accel_world_use_bvh) and routes the world's
 * triangle queries through it. On rung 7 the hierarchy reads its triangles from w's gathered mesh,
 * which w keeps until the hierarchy is freed; rung 10 builds rung 9's tree (chapter 11 renders its camera rays in
 * packets over it). Returns false with the reason in err when memory runs out or the rung
 * does not exist. */
bool accel_world_use_fast_bvh(struct accel_world *w, int split, int rung, char *err, size_t err_size);

/* Builds the world over every triangle of s with the structure c chooses, as accel_world_create does,
 * and when c chooses the BVH routes its triangle queries through chapter 11's hierarchy at `rung` (an
 * enum fast_bvh_rung; chapters 12 to 15 pass FAST_BVH_RUNG_DEFAULT), built by c's split rule. Rung 7
 * reads its triangles from the world's gathered mesh and does not free the scene's meshes (chapter 11
 * does that itself). Returns the world, to be freed with accel_world_destroy, or NULL with the reason in
 * err (a bad scene, memory running out, a rung that does not exist). */
struct accel_world *accel_world_create_at_rung(struct scene *s, const struct accel_choice *c, int rung, char *err,
                                               size_t err_size);

#endif

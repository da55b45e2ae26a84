/* fast_bvh.h: the bounding volume hierarchy of chapter 10 made fast, one optimisation (a "rung") at a time
 * (chapter 11).
 *
 * The same two build rules as chapter 10's bvh.h (enum bvh_split, and its constants), the same three
 * queries and the same promise: every query gives exactly the answer of the brute-force loop over all
 * faces with triangle_intersect (same t to the last bit, same face, same tie rule). What changes is how
 * the tree is stored, walked and built: fast_bvh_tree.h stores it, fast_bvh.c walks it, fast_bvh_build.c
 * (fast_bvh_build.h) builds it, and each says what its rungs add and why they pay. All queries are safe to
 * run from several threads at once on one hierarchy; they add to the calling thread's counters (stats.h):
 * node_visits, box_tests and triangle_tests. */
#ifndef WHITTED_FAST_BVH_H
#define WHITTED_FAST_BVH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bvh.h" /* struct bvh_info */
#include "fast_bvh_tree.h"
#include "mesh.h"
#include "ray.h"

/* Frees b and everything it owns. Safe on NULL. */
void fast_bvh_free(struct fast_bvh *b);

/* Finds the nearest face hit by r with t_min < t < t_max. On a hit returns true and stores its
 * distance in *t and its index into the mesh's faces in *face; on a miss returns false and leaves both
 * alone. Among faces hit at exactly the same t, the lowest face index wins, as in a brute-force loop
 * that keeps the first nearest face. */
bool fast_bvh_closest(const struct fast_bvh *b, const ray *r, double t_min, double t_max, double *t, uint32_t *face);

/* Returns true when any face is hit with t_min < t < t_max (a shadow ray's question); stops at the
 * first such hit it meets. */
bool fast_bvh_occluded(const struct fast_bvh *b, const ray *r, double t_min, double t_max);

/* Calls visit(ctx, t, face) once for every face hit with t_min < t < t_max, in no particular order,
 * and stops as soon as visit returns false. */
void fast_bvh_for_each_hit(const struct fast_bvh *b, const ray *r, double t_min, double t_max,
                           bool (*visit)(void *ctx, double t, uint32_t face), void *ctx);

/* Fills *info with b's shape, build time and SAH cost (nodes counted in the 4-wide tree). Cannot fail. */
void fast_bvh_get_info(const struct fast_bvh *b, struct bvh_info *info);

/* The bytes b holds: its nodes, its leaves' triangles (or on rung 7 their corners' numbers, and not the
 * mesh it reads them from) and their face numbers. */
size_t fast_bvh_bytes(const struct fast_bvh *b);

/* Checks b, built from m, against its invariants: every face stored exactly once and reachable from
 * the root, every box holding its triangles' corners and its children's boxes, the depth within the
 * traversal stack. Returns true when all hold; otherwise false with the first broken one described in
 * why (why_size bytes). For tests: it walks the whole tree. */
bool fast_bvh_is_valid(const struct fast_bvh *b, const struct mesh *m, char *why, size_t why_size);

/* The rung called `name` ("plain", "wide", "simd", "prefetch", "build", "float", "compact", "eight", "lean",
 * "packet", "exact-float") or written as its number ("1" to "11"); 0 when there is none. */
int fast_bvh_rung_from_name(const char *name);

/* The name of rung r, for reports ("plain", ...); "?" for a number that is not a rung. */
const char *fast_bvh_rung_name(int r);

#endif

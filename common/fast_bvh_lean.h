/* fast_bvh_lean.h: rung 9 of chapter 11's ladder: rung 8's 8-wide tree walked with less work per ray,
 * and its leaves' triangles laid out so that four of them are tested at once in double (chapter 11). */
#ifndef WHITTED_FAST_BVH_LEAN_H
#define WHITTED_FAST_BVH_LEAN_H

#include <stdbool.h>
#include <stddef.h>

#include "fast_bvh_tree.h"
#include "fast_bvh_walk.h"
#include "ray.h"

/* Rung 9's copy of the tree's triangles (b->lean_corners): blocks of four triangles in leaf order
 * (triangles 4 j to 4 j + 3 in block j), each block the nine coordinates (corner a, b, c; axis x, y, z)
 * of its four triangles side by side, FAST_BVH_LEAN_BLOCK doubles (288 bytes, 32-byte aligned), so
 * that one aligned load gives one coordinate of four triangles and a leaf's triangles are next to each
 * other in memory. A triangle whose corners lie exactly on a line, which no ray crosses, is nine NaNs
 * instead. The last block is padded with zeros. */
#define FAST_BVH_LEAN_LANES 4
#define FAST_BVH_LEAN_BLOCK (9 * FAST_BVH_LEAN_LANES)

/* Where corner c's coordinate on axis a of the k-th triangle is in b->lean_corners. */
static inline size_t fast_bvh_lean_index(size_t k, int c, int a) {
    return k / FAST_BVH_LEAN_LANES * FAST_BVH_LEAN_BLOCK + (size_t)(3 * c + a) * FAST_BVH_LEAN_LANES +
           k % FAST_BVH_LEAN_LANES;
}

/* Makes rung 9's copy of b's triangles (b->lean_corners, from b->triangles). b is an 8-wide tree with
 * its triangles in leaf order. Returns false when out of memory (b is then unchanged). */
bool fast_bvh_lean_prepare(struct fast_bvh *b);

/* Answers query `kind` for r with t_min < t < t_max over b, built for rung 9 (b->nodes8 and
 * b->lean_corners are not NULL, which the build makes only when fast_bvh_eight_available() is true),
 * into *q with the same answers as every rung: the brute-force loop's, bit for bit. A ray that rung
 * 6's float bound does not cover is walked by rung 8 (fast_bvh_eight_traverse). Returns q->found. Adds
 * to the calling thread's counters: node_visits, box_tests, triangle_tests. */
bool fast_bvh_lean_traverse(const struct fast_bvh *b, const ray *r, double t_min, double t_max, enum query kind,
                            struct query_state *q);

/* Rung 10 on rung 9's tree: tests triangles [first, first + count) of b (built for rung 9, as for
 * fast_bvh_lean_traverse) for the nearest hit of the ray that *ready was made for (triangle_ray_make),
 * with t_min < t < t_max, four at a time as rung 9's walk does, into *q and *box_max as
 * test_leaf_triangles does (fast_bvh_walk.h). Returns true (a nearest-hit query never stops early).
 * Adds the triangles to *tests. */
bool fast_bvh_lean_leaf_closest(const struct fast_bvh *b, const struct triangle_ray *ready, uint32_t first,
                                uint32_t count, double t_min, double t_max, struct query_state *q, double *box_max,
                                uint64_t *tests);

/* As fast_bvh_lean_leaf_closest, for query QUERY_ANY: sets q->found and returns false at the first
 * triangle crossed with t_min < t < t_max; else returns true. */
bool fast_bvh_lean_leaf_any(const struct fast_bvh *b, const struct triangle_ray *ready, uint32_t first, uint32_t count,
                            double t_min, double t_max, struct query_state *q, uint64_t *tests);

#endif

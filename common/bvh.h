/* bvh.h: a bounding volume hierarchy over the triangles of one mesh (chapter 10): a binary tree of
 * boxes, built by the median split or the binned SAH, walked front to back with a small stack.
 *
 * Two ways to build it: the dissertation's object-median split (the baseline) and a binned surface area
 * heuristic (SAH) split after Wald, "On fast construction of SAH-based bounding volume hierarchies"
 * (IEEE Symposium on Interactive Ray Tracing, 2007). The caller merges every triangle of the scene
 * into one mesh first; the hierarchy copies what it needs, so the mesh may be freed after the build.
 *
 * Every query gives exactly the answer of the brute-force loop over all faces with triangle_intersect
 * (same t to the last bit, same face, same tie rule), only faster. All queries are safe to run from
 * several threads at once on one hierarchy; they add to the calling thread's counters (stats.h):
 * node_visits, box_tests and triangle_tests. */
#ifndef WHITTED_BVH_H
#define WHITTED_BVH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh.h"
#include "ray.h"

/* How a node's triangles are divided between its two children. */
enum bvh_split {
    BVH_SPLIT_MEDIAN, /* the dissertation's rule: half the triangles on each side, by centroid, along the
                         longest axis of the centroids' bounding box; leaves of at most two triangles */
    BVH_SPLIT_SAH,    /* binned surface area heuristic: the cheapest of a few candidate planes per axis,
                         or a leaf when no split is expected to pay for itself */
};

struct bvh; /* opaque */

/* What a built hierarchy looks like, for printing beside measured costs. */
struct bvh_info {
    size_t nodes;     /* interior nodes + leaves */
    size_t leaves;
    size_t max_depth; /* edges from the root to the deepest leaf (0 for a single leaf) */
    double build_ms;  /* wall-clock time bvh_build took, in milliseconds */
    double sah_cost;  /* the tree's expected cost per ray by the surface area heuristic, in units of one
                         triangle test (see BVH_COST_TRAVERSAL and BVH_COST_TRIANGLE in bvh.c) */
    size_t slivers;   /* needle-thin triangles kept out of the tree and tested by every ray (bvh.c says why);
                         0 for well-made meshes */
};

/* Builds a hierarchy over the faces of m with the given split rule. m is only read, and not kept: it
 * may be changed or freed afterwards. A mesh without faces gives a hierarchy that nothing hits.
 * Returns NULL when memory runs out. Free the result with bvh_free. */
struct bvh *bvh_build(const struct mesh *m, enum bvh_split split);

/* Frees b and everything it owns. Safe on NULL. */
void bvh_free(struct bvh *b);

/* Finds the nearest face hit by r with t_min < t < t_max. On a hit returns true and stores its
 * distance in *t and its index into the mesh's faces in *face; on a miss returns false and leaves both
 * alone. Among faces hit at exactly the same t, the lowest face index wins, as in a brute-force loop
 * that keeps the first nearest face. */
bool bvh_closest(const struct bvh *b, const ray *r, double t_min, double t_max, double *t, uint32_t *face);

/* Returns true when any face is hit with t_min < t < t_max (a shadow ray's question); stops at the
 * first such hit it meets. */
bool bvh_occluded(const struct bvh *b, const ray *r, double t_min, double t_max);

/* Calls visit(ctx, t, face) once for every face hit with t_min < t < t_max, in no particular order,
 * and stops as soon as visit returns false. */
void bvh_for_each_hit(const struct bvh *b, const ray *r, double t_min, double t_max,
                      bool (*visit)(void *ctx, double t, uint32_t face), void *ctx);

/* Fills *info with b's shape, build time and SAH cost. Cannot fail. */
void bvh_get_info(const struct bvh *b, struct bvh_info *info);

/* Checks b, built from m, against its invariants: every face stored exactly once and reachable from
 * the root, every box holding its triangles' corners and its children's boxes, the depth within the
 * traversal stack. Returns true when all hold; otherwise false with the first broken one described in
 * why (why_size bytes). For tests: it walks the whole tree. */
bool bvh_is_valid(const struct bvh *b, const struct mesh *m, char *why, size_t why_size);

/* ---- shared with chapter 11's BVH (fast_bvh.c), which keeps the same rules ------------------- */

/* Returns true for face `face` of m when its edges are so nearly parallel (BVH_SLIVER_SINE, bvh.c)
 * that no box can be trusted to hold its hits: such a face stays out of the tree and every ray tests
 * it. Zero-area faces are not slivers (they are never hit). */
bool bvh_is_sliver(const struct mesh *m, size_t face);

/* Returns the monotonic clock's reading in milliseconds, for timing builds. */
double bvh_now_ms(void);

/* The checks of bvh_is_valid and fast_bvh_is_valid that follow their walk of the tree: each of the
 * first tree_count stored triangles was reached (seen[k] nonzero), the slivers and only they are
 * stored after them, and no face number repeats in faces[0..triangle_count). The caller has checked
 * that every face number is below m's face count, which equals triangle_count. seen has
 * triangle_count + 1 bytes and is overwritten. Returns true when all hold; otherwise false with the
 * first broken one, as "what (at index)", in why (why_size bytes). */
bool bvh_check_faces(const struct mesh *m, const uint32_t *faces, size_t triangle_count, size_t tree_count,
                     unsigned char *seen, char *why, size_t why_size);

#endif

/* kdtree.h: a kd-tree over the triangles of one mesh (chapter 9): kdtree.c, kdtree_events.c, kdtree_check.c.
 *
 * Space is cut in two by an axis-aligned plane, each half again, and so on; a triangle that crosses a
 * plane belongs to both halves. Two ways to choose the planes: the dissertation's rule (the baseline)
 * and the surface area heuristic of Wald and Havran, "On building fast kd-trees for ray tracing, and on
 * doing that in O(N log N)" (IEEE RT 2006). The caller merges every triangle of the scene into one
 * mesh first; the tree copies what it needs, so the mesh may be freed after the build.
 *
 * Every query gives exactly the answer of the brute-force loop over all faces with triangle_intersect
 * (same t to the last bit, same face, same tie rule). Queries are safe to run from several threads at
 * once on one tree; they add to the calling thread's counters (stats.h): node_visits, box_tests (one
 * per ray, the root box) and triangle_tests. */
#ifndef WHITTED_KDTREE_H
#define WHITTED_KDTREE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh.h"
#include "ray.h"

/* How a node's plane is chosen. */
enum kd_split {
    KD_SPLIT_SEED, /* the dissertation's rule: on the axis that "holds the most objects" (kdtree.c says how
                      that is read), at the median of the triangles' centres */
    KD_SPLIT_SAH,  /* surface area heuristic over every triangle bound plane, with an empty-space bonus,
                      built in O(N log N) by sorted events (kdtree_events.c) */
    KD_SPLIT_SAH_PLAIN, /* the same tree as KD_SPLIT_SAH, built plainly in O(N^2) per node (kdtree.c): for
                           reading, and for the tests that prove the two equal */
};

struct kdtree; /* opaque */

/* What a built tree looks like, for printing beside measured costs. */
struct kdtree_info {
    size_t nodes;        /* interior nodes + leaves */
    size_t leaves;
    size_t empty_leaves; /* leaves without triangles: space the heuristic cut away */
    size_t max_depth;    /* edges from the root to the deepest leaf */
    size_t references;   /* triangle references in all leaves; above the face count when triangles straddle */
    double build_ms;     /* wall-clock time kdtree_build took, in milliseconds */
    double sah_cost;     /* expected cost per ray by the surface area heuristic, in units of one triangle test
                            (KD_COST_TRAVERSAL and KD_COST_TRIANGLE in kdtree.c) */
    size_t slivers;      /* needle-thin triangles kept out of the tree and tested by every ray (kdtree.c says
                            why); 0 for well-made meshes */
};

/* Builds a tree over the faces of m with the given rule. m is only read, and not kept. A mesh without
 * faces gives a tree that nothing hits. Returns NULL when memory runs out. Free with kdtree_free. */
struct kdtree *kdtree_build(const struct mesh *m, enum kd_split split);

/* Frees k and everything it owns. Safe on NULL. */
void kdtree_free(struct kdtree *k);

/* Finds the nearest face hit by r with t_min < t < t_max. On a hit returns true and stores its
 * distance in *t and its index into the mesh's faces in *face; on a miss returns false and leaves both
 * alone. Among faces hit at exactly the same t, the lowest face index wins. */
bool kdtree_closest(const struct kdtree *k, const ray *r, double t_min, double t_max, double *t, uint32_t *face);

/* Returns true when any face is hit with t_min < t < t_max; stops at the first such hit it meets. */
bool kdtree_occluded(const struct kdtree *k, const ray *r, double t_min, double t_max);

/* Calls visit(ctx, t, face) once for every face hit with t_min < t < t_max, in no particular order
 * (a face in several leaves is still reported once), and stops as soon as visit returns false. Aborts
 * the program if memory for remembering the reported faces runs out (only a ray crossing more than
 * KD_HITS_ON_STACK faces asks for any). */
void kdtree_for_each_hit(const struct kdtree *k, const ray *r, double t_min, double t_max,
                         bool (*visit)(void *ctx, double t, uint32_t face), void *ctx);

/* Fills *info with k's shape, build time and SAH cost. Cannot fail. */
void kdtree_get_info(const struct kdtree *k, struct kdtree_info *info);

/* Checks k, built from m, against its invariants: every node reachable exactly once, every face but
 * the slivers in every leaf its bounding box touches (so in at least one), the root box holding them, the
 * depth within the traversal stack. Returns true when all hold; otherwise false with the first broken
 * one described in why (why_size bytes). For tests: it walks the whole tree once per face. */
bool kdtree_is_valid(const struct kdtree *k, const struct mesh *m, char *why, size_t why_size);

/* For tests: true when a and b have the same root box, nodes and leaves (with their faces in the same
 * order), slivers, shape counts and SAH cost (build times aside). */
bool kdtree_equal(const struct kdtree *a, const struct kdtree *b);

#endif

/* bvh.h: a bounding volume hierarchy over the triangles of one mesh (chapter 10): a binary tree of
 * chapter 5's boxes, built by the median split or the binned SAH, walked front to back with a small
 * stack.
 *
 * Two ways to build it: the dissertation's object-median split (the baseline) and a binned surface area
 * heuristic (SAH) split after Wald, "On fast construction of SAH-based bounding volume hierarchies"
 * (IEEE Symposium on Interactive Ray Tracing, 2007). The caller merges every triangle of the scene
 * into one mesh first; the hierarchy copies what it needs, so the mesh may be freed after the build.
 *
 * Every query gives exactly the answer of the brute-force loop over all faces with triangle_intersect
 * (same t to the last bit, same face, same tie rule), only faster. All queries are safe to run from
 * several threads at once on one hierarchy; they add to the calling thread's counters (stats.h):
 * node_visits, box_tests and triangle_tests. Chapter 11 (fast_bvh.h) keeps these rules and constants. */
#ifndef WHITTED_BVH_H
#define WHITTED_BVH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "aabb.h"
#include "mesh.h"
#include "ray.h"

/* How a node's triangles are divided between its two children. */
enum bvh_split {
    BVH_SPLIT_MEDIAN, /* the dissertation's rule: half the triangles on each side, by centroid, along the
                         longest axis of the centroids' bounding box; leaves of at most two triangles */
    BVH_SPLIT_SAH,    /* binned surface area heuristic: the cheapest of a few candidate planes per axis,
                         or a leaf when no split is expected to pay for itself */
};

/* Centroid slots per axis for the SAH build. Wald (2007) found 16 within a few percent of testing
 * every plane; more bins build slower and help little (exercise 1). */
#define BVH_BINS 16

/* An SAH node with more triangles than this is always split, even when the heuristic would rather
 * not: a long leaf is costly for every ray that reaches it, which the heuristic's averages hide. */
#define BVH_MAX_LEAF_SIZE 8

/* The dissertation's median build stops at one or two triangles per node. */
#define BVH_MEDIAN_LEAF_SIZE 2

/* Relative costs of visiting a node (testing its children's boxes) and of one triangle test, as the
 * heuristic sees them. Measured on this code they are about equal (each is some twenty floating point
 * operations and a few branches); the program prints the predicted cost next to the measured. */
#define BVH_COST_TRAVERSAL 1.0
#define BVH_COST_TRIANGLE 1.0

/* Below this depth the SAH chooses freely; deeper nodes are halved by count, so no leaf lies deeper
 * than BVH_DEEPEST (31 more halvings take 2^31 triangles down to one), and the traversal stacks of
 * chapters 10 and 11 are sized by that. */
#define BVH_MAX_DEPTH 64
#define BVH_DEEPEST (BVH_MAX_DEPTH + 31)

/* Faces are numbered with uint32_t, and a tree of n faces has up to 2n - 1 nodes. */
#define BVH_MAX_FACES ((size_t)1 << 31)

/* A node of the tree: 64 bytes. */
struct bvh_node {
    struct aabb box;       /* holds every triangle below the node */
    uint32_t left, right;  /* an interior node's children (indices into the nodes) */
    uint32_t first, count; /* a leaf's triangles: count > 0 of them from triangles[first]; 0 for interior */
};

/* A triangle as the intersection test wants it: its three corners, copied from the mesh. */
struct bvh_triangle {
    vec3 a, b, c;
};

/* What a built hierarchy looks like, for printing beside measured costs. */
struct bvh_info {
    size_t nodes;     /* interior nodes + leaves */
    size_t leaves;
    size_t max_depth; /* edges from the root to the deepest leaf (0 for a single leaf) */
    double build_ms;  /* wall-clock time the build took, in milliseconds */
    double sah_cost;  /* the tree's expected cost per ray by the surface area heuristic, in units of one
                         triangle test (BVH_COST_TRAVERSAL and BVH_COST_TRIANGLE) */
    size_t slivers;   /* needle-thin triangles kept out of the tree and tested by every ray
                         (triangle_is_sliver, triangle.h); 0 for well-made meshes */
};

/* The hierarchy: two arrays, the nodes and the triangles in leaf order. */
struct bvh {
    struct bvh_node *nodes;         /* node_count entries; the root is nodes[0] */
    size_t node_count;
    struct bvh_triangle *triangles; /* triangle_count entries: tree_count in leaf order, then the slivers */
    uint32_t *faces;                /* faces[k] = index into the mesh's faces of triangles[k] */
    size_t triangle_count, tree_count;
    struct bvh_info info;
};

/* Builds a hierarchy over the faces of m with the given split rule. m is only read, and not kept: it
 * may be changed or freed afterwards. A mesh without faces gives a hierarchy that nothing hits.
 * Returns NULL when memory runs out. Free the result with bvh_free. */
struct bvh *bvh_build(const struct mesh *m, enum bvh_split split);

/* Frees b and everything it owns. Safe on NULL. */
void bvh_free(struct bvh *b);

/* The two steps every build of chapters 10 and 11 starts and ends with. bvh_face_box: the box of face
 * `face` of m grown by pad on every side (pad = triangle_box_pad(m), triangle.h) into *box; false,
 * leaving *box alone, for a sliver (triangle_is_sliver), which stays out of the tree. bvh_copy_triangles:
 * the corners of faces faces[0..count) of m into triangles[0..count), in that order. */
bool bvh_face_box(const struct mesh *m, size_t face, double pad, struct aabb *box);
void bvh_copy_triangles(const struct mesh *m, const uint32_t *faces, size_t count, struct bvh_triangle *triangles);

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

/* The checks of bvh_is_valid and chapter 11's fast_bvh_is_valid on the stored triangles, around and
 * in their walks of the tree. bvh_check_triangles, before the walk: there are as many as m has faces,
 * each face number is one of m's, and each triangle holds its face's corners. bvh_check_leaf, at each
 * leaf: its triangles [first, first + count) lie among the first tree_count, each is reached for the
 * first time (seen[k] was 0, and is set) and lies inside the leaf's box. bvh_check_faces, after the
 * walk: each of the first tree_count triangles was reached (seen[k] nonzero), the slivers and only they
 * are stored after them, and no face number repeats; seen has triangle_count + 1 bytes and is
 * overwritten. Each returns true when all hold; otherwise false with the first broken one, as "what (at
 * index)", in why (why_size bytes). */
bool bvh_check_triangles(const struct mesh *m, const struct bvh_triangle *triangles, const uint32_t *faces,
                         size_t triangle_count, char *why, size_t why_size);
bool bvh_check_leaf(const struct bvh_triangle *triangles, size_t tree_count, uint32_t first, uint32_t count,
                    const struct aabb *box, unsigned char *seen, char *why, size_t why_size);
bool bvh_check_faces(const struct mesh *m, const uint32_t *faces, size_t triangle_count, size_t tree_count,
                     unsigned char *seen, char *why, size_t why_size);

#endif

/* kdtree.h: a kd-tree over the triangles of one mesh (chapter 9): built in kdtree.c, checked for the
 * tests by kdtree_check.c.
 *
 * Space is cut in two by an axis-aligned plane, each half again, and so on; a triangle that crosses a
 * plane belongs to both halves. Two ways to choose the planes: the dissertation's rule (the baseline)
 * and the surface area heuristic (SAH). The caller merges every triangle of the scene into one mesh
 * first; the tree copies what it needs, so the mesh may be freed after the build.
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

#include "aabb.h"
#include "mesh.h"
#include "ray.h"

/* How a node's plane is chosen. */
enum kd_split {
    KD_SPLIT_SEED, /* the dissertation's rule: on the axis that "holds the most objects" (kdtree.c says how
                      that is read), at the median of the triangles' centres */
    KD_SPLIT_SAH,  /* the surface area heuristic over every bound of the triangles' boxes */
};

/* The walk's stack holds at most one entry per level: 64 > 8 + 1.3 * 32, the SAH's depth limit for
 * the largest mesh accepted (2^32 - 1 triangles). */
#define KD_STACK_SIZE 64

/* The most triangle references a tree holds, per triangle of the mesh: once its leaves hold this many,
 * every node still to be built is a leaf (the nodes under way add at most one copy of the mesh per level).
 * The SAH's tree of the 350,000-triangle teapot holds 5.5 a triangle and the seed's 11.5; without a
 * limit, triangles nested about one centre, which every plane cuts through, made the SAH hold 5,000 a
 * triangle (100,000 of them: 48 s and 2 GB to build). */
#define KD_MAX_REFERENCES_PER_TRIANGLE 64

/* The axis of a leaf. */
#define KD_LEAF 3

/* A node: an inner node cuts its cell at `split` on `axis`, a leaf lists its faces. The child below
 * the plane is always the next node in the array, so only the one above needs an index. */
struct kd_node {
    int axis;              /* 0, 1 or 2 (x, y, z) for an inner node; KD_LEAF for a leaf */
    float split;           /* inner node: the plane's position on its axis (the SAH's planes are box
                              bounds, which kdtree.c rounds outward to float; the seed's, float medians) */
    uint32_t above;        /* inner node: index of the child above the plane */
    uint32_t first, count; /* leaf: its faces are refs[first .. first + count) */
};

/* A triangle as the intersection test wants it: its three corners, copied from the mesh. */
struct kd_triangle {
    vec3 a, b, c;
};

/* What a built tree looks like, for printing beside measured costs. */
struct kdtree_info {
    size_t nodes;        /* inner nodes + leaves */
    size_t leaves;
    size_t empty_leaves; /* leaves without triangles: space the heuristic cut away */
    size_t max_depth;    /* edges from the root to the deepest leaf */
    size_t references;   /* triangle references in all leaves; above the face count when triangles straddle,
                            and not far above KD_MAX_REFERENCES_PER_TRIANGLE times it */
    double sah_cost;     /* expected cost per ray by the surface area heuristic, in units of one triangle test
                            (KD_COST_TRAVERSAL and KD_COST_TRIANGLE in kdtree.c) */
    size_t slivers;      /* needle-thin triangles kept out of the tree and tested by every ray (kdtree.c says
                            why); 0 for well-made meshes */
};

/* The tree. Read by kdtree_check.c; built and walked only by kdtree.c. */
struct kdtree {
    struct kd_node *nodes;         /* [0] is the root; info.nodes of them */
    uint32_t *refs;                /* the leaves' face numbers, leaf after leaf; info.references of them */
    struct kd_triangle *triangles; /* indexed by face number */
    size_t face_count;
    uint32_t *slivers;             /* faces kept out of the tree, in increasing order; info.slivers of them */
    struct aabb root;              /* the box of all padded triangle boxes */
    vec3 centre;                   /* of the root box */
    double size;                   /* length of the root box's diagonal */
    struct kdtree_info info;
};

/* Builds a tree over the faces of m with the given rule. m is only read, and not kept. A mesh without
 * faces gives a tree that nothing hits. Returns NULL for a mesh of more than 2^32 - 1 faces; when memory
 * runs out, ends the program with a message and exit status 1 (a tree that does not fit cannot be
 * traced). Free with kdtree_free. */
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
 * (a face in several leaves is still reported once), and stops as soon as visit returns false. Ends the
 * program with a message if memory for remembering the reported faces runs out. */
void kdtree_for_each_hit(const struct kdtree *k, const ray *r, double t_min, double t_max,
                         bool (*visit)(void *ctx, double t, uint32_t face), void *ctx);

/* Fills *info with k's shape and SAH cost. Cannot fail. */
void kdtree_get_info(const struct kdtree *k, struct kdtree_info *info);

/* Checks k, built from m, against its invariants (kdtree_check.c): every node reachable exactly once,
 * every face outside the sliver list in every leaf its box touches (so in at least one), the root box
 * holding them, the depth within the traversal stack. Returns true when all hold; otherwise false with
 * the first broken one described in why (why_size bytes). For tests: it walks the tree once per face. */
bool kdtree_is_valid(const struct kdtree *k, const struct mesh *m, char *why, size_t why_size);

#endif

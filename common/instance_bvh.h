/* instance_bvh.h: the top level of chapter 16's two-level hierarchy: a BVH over the instances' world
 * boxes, built by the binned SAH, refitted when they move, walked near child first (chapter 16).
 *
 * The bottom level is chapter 11's tree of each object's triangles, in the object's own space; this
 * tree knows nothing of triangles or transforms, only one box per instance (in the world, or over the
 * shutter for a moving one: keyframes_motion_box). A walk hands each instance whose leaf the ray
 * reaches to a callback, which carries the ray into the object's space and asks the bottom level.
 *
 * When the instances move, the tree can be rebuilt (a new topology, the best the SAH finds for the new
 * boxes) or refitted (the same topology, every node's box recomputed bottom-up from the new boxes:
 * much quicker, always correct, but the tree grows worse as the instances wander from where it was
 * built; instance_bvh_sah_cost measures how much). All of this is plain code over two arrays; a walk
 * only reads the tree, so threads may walk one tree at once. */
#ifndef WHITTED_INSTANCE_BVH_H
#define WHITTED_INSTANCE_BVH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "aabb.h"
#include "ray.h"

/* Centroid slots per axis for the binned SAH, as chapter 10's BVH_BINS. */
#define INSTANCE_BVH_BINS 16

/* The most instances one leaf holds: a node with more is always split. */
#define INSTANCE_BVH_LEAF_MAX 4

/* What the heuristic counts, relative to a node visit (two box tests): an instance costs a ray carried
 * into its object's space (two matrix products) and a walk of the object's own tree, many node visits.
 * The heuristic needs only the ratio roughly; at 4 it splits down to one instance a leaf wherever the
 * boxes separate, the best shape for a level whose leaves are this dear. */
#define INSTANCE_BVH_COST_TRAVERSAL 1.0
#define INSTANCE_BVH_COST_INSTANCE 4.0

/* Below this depth the SAH chooses freely; deeper nodes are halved by count (31 halvings take 2^31
 * instances to one), so no leaf lies deeper than INSTANCE_BVH_DEEPEST and the walk's stack is sized by
 * it. */
#define INSTANCE_BVH_MAX_DEPTH 64
#define INSTANCE_BVH_DEEPEST (INSTANCE_BVH_MAX_DEPTH + 31)

/* Instances are numbered with uint32_t, and a tree over n of them has at most 2n - 1 nodes. */
#define INSTANCE_BVH_MAX_INSTANCES ((size_t)1 << 31)

/* A node: an interior one (count 0) has two children; a leaf holds count instances. */
struct instance_bvh_node {
    struct aabb box;       /* holds the boxes of every instance below the node */
    uint32_t left, right;  /* an interior node's children, indices into nodes (after the node's own) */
    uint32_t first, count; /* a leaf's instances: instances[first .. first + count); count 0 for interior */
};

/* The tree: nodes in the order the build made them (a parent before its children, the root first) and
 * the instances' indices in leaf order. */
struct instance_bvh {
    struct instance_bvh_node *nodes; /* node_count entries; none when there are no instances */
    size_t node_count;
    uint32_t *instances;             /* instance_count entries, each index into the boxes once */
    size_t instance_count;
};

/* Builds the tree over boxes[0 .. count) (count may be 0: a tree that no ray enters; an empty box, an
 * instance of nothing, is never entered either). The boxes are only read: the tree keeps its own.
 * Returns NULL with a sentence in err (size err_size) when count is above INSTANCE_BVH_MAX_INSTANCES or
 * memory runs out. Free the result with instance_bvh_free. */
struct instance_bvh *instance_bvh_build(const struct aabb *boxes, size_t count, char *err, size_t err_size);

/* Frees b and everything it owns. Safe on NULL. */
void instance_bvh_free(struct instance_bvh *b);

/* Refits b to new boxes of the same instances (boxes[0 .. b->instance_count)): the topology stays,
 * every leaf's box becomes the union of its instances' boxes and every interior node's the union of
 * its children's, from the leaves up. Cannot fail. */
void instance_bvh_refit(struct instance_bvh *b, const struct aabb *boxes);

/* The callback of a walk: called with an instance's index; it may lower *t_max (to a hit's distance,
 * so that farther boxes are skipped); returns false to stop the walk (a shadow ray that found a
 * blocker), true to go on. */
typedef bool (*instance_bvh_visit)(void *context, size_t index, double t_min, double *t_max);

/* Walks b along r: every node whose box the ray enters with t in [t_min, *t_max] is visited (*t_max as
 * it is when the node's turn comes), the nearer child first, and for every leaf visited, visit is
 * called once for each of its instances, in leaf order. So visit sees every instance whose own box the
 * ray enters before *t_max (and perhaps a few more of the same leaves: it tests its own box or object).
 * Stops as soon as visit returns false. Adds one to stats_thread.instance_node_visits per node visited
 * (and aabb_hit's box tests). Safe from several threads on one tree. */
void instance_bvh_walk(const struct instance_bvh *b, const ray *r, double t_min, double *t_max,
                       instance_bvh_visit visit, void *context);

/* Returns the tree's expected cost per ray by the surface area heuristic: for each node, its box's
 * area over the root's times INSTANCE_BVH_COST_TRAVERSAL (interior) or INSTANCE_BVH_COST_INSTANCE
 * times its count (leaf); every ratio taken as 1 when the root's area is 0. Recomputed from the boxes
 * as they are, so after a refit it shows how far the tree has drifted from its build. 0 for no
 * instances. */
double instance_bvh_sah_cost(const struct instance_bvh *b);

/* Returns how many instances a ray that meets the root's box is expected to carry into their objects,
 * by the SAH's measure: the sum over the leaves of their counts times their boxes' areas over the
 * root's (every ratio 1 when the root's area is 0). About log n for instances spread apart, n for n
 * instances on top of each other. When crowded is not NULL, stores in it an instance of the leaf that
 * adds the most. 0 for no instances. */
double instance_bvh_expected_instances(const struct instance_bvh *b, uint32_t *crowded);

/* The structure checker: returns true when b is a well-formed tree over boxes[0 .. count): every node
 * reached once from the root, every child after its parent, every leaf holding 1 to
 * INSTANCE_BVH_LEAF_MAX instances, every instance index in exactly one leaf, every interior box holding
 * its children's boxes and every leaf box its instances' boxes. Otherwise returns false with the first
 * fault found, as a sentence, in why (size why_size). */
bool instance_bvh_is_valid(const struct instance_bvh *b, const struct aabb *boxes, size_t count, char *why,
                           size_t why_size);

#endif

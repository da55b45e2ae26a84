/* kdtree_private.h: what the kd-tree's files share (chapter 9): the node layout, the tree, the
 * builder's state, and the few build steps the fast SAH build (kdtree_events.c) and the checker
 * (kdtree_check.c) borrow from kdtree.c. For common/kdtree*.c only; everyone else uses kdtree.h. */
#ifndef WHITTED_KDTREE_PRIVATE_H
#define WHITTED_KDTREE_PRIVATE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "kdtree.h"
#include "kdtree_sah.h"
#include "mesh.h"
#include "vec3.h"

/* The walk's stack holds at most one entry per level: 64 > 8 + 1.3 * 30, the SAH's depth limit for
 * the largest mesh accepted (KD_MAX_FACES). */
#define KD_STACK_SIZE 64
#define KD_MAX_FACES ((size_t)1 << 30)
#define KD_MAX_NODES ((size_t)1 << 30) /* node indices share a word with the axis */

#define KD_LEAF 3u /* the axis field of a leaf */

/* A node in 8 bytes (pbrt's layout). The below child of an interior node always follows it. */
struct kd_node {
    union {
        float split;    /* interior: the plane's position on its axis */
        uint32_t first; /* leaf: index of its first entry in refs */
    };
    uint32_t bits; /* low 2 bits: axis 0-2, or KD_LEAF; the rest: the above child's index, or a leaf's count */
};

_Static_assert(sizeof(struct kd_node) == 8, "kd-tree nodes are meant to be 8 bytes");

/* A triangle as the intersection test wants it: its three corners, copied from the mesh. */
struct kd_triangle {
    vec3 a, b, c;
};

struct kdtree {
    struct kd_node *nodes;         /* [0] is the root */
    uint32_t *refs;                /* leaves' face numbers, leaf after leaf */
    struct kd_triangle *triangles; /* indexed by face number */
    size_t face_count;
    uint32_t *slivers;             /* faces kept out of the tree (KD_SLIVER_SINE), sliver_count of them */
    size_t sliver_count;
    float root_lo[3], root_hi[3];  /* box of all padded triangle boxes */
    vec3 centre;                   /* of the root box */
    double size;                   /* length of the root box's diagonal */
    struct kdtree_info info;
};

/* The state of one build. */
struct kd_builder {
    const struct fbox *boxes; /* per face, padded */
    unsigned char *sides;     /* per face, scratch: enum side of the node being split */
    float *centres;           /* per face, scratch for the dissertation's rule */
    struct kd_node *nodes;
    size_t node_count, node_capacity;
    uint32_t *refs;
    size_t ref_count, ref_capacity;
    size_t depth_limit;
    double root_area;
    struct kdtree_info info; /* counted while building */
};

/* ---- in kdtree.c ---- */

/* Whether the SAH may cut a node of `count` triangles at `depth` with region `box` at all. */
bool kd_sah_may_split(const struct kd_builder *bd, size_t count, size_t depth, const struct fbox *box);

/* Tree storage while building: appends a node (UINT32_MAX when memory runs out), counts a node into
 * bd->info, makes nodes[index] a leaf over faces[0..count) (false when memory runs out), or an interior
 * node whose below child is index + 1. */
uint32_t kd_new_node(struct kd_builder *bd);
void kd_count_node(struct kd_builder *bd, const struct fbox *box, size_t count, bool leaf, size_t depth);
bool kd_make_leaf(struct kd_builder *bd, uint32_t index, const uint32_t *faces, size_t count);
void kd_make_interior(struct kd_builder *bd, uint32_t index, int axis, float split, uint32_t above);

/* Records in bd->sides on which side(s) of the plane `split` on `axis` each of faces[0..count) goes, and
 * counts the faces going left and right (those on both sides count twice). */
void kd_mark_sides(struct kd_builder *bd, const uint32_t *faces, size_t count, int axis, float split, size_t *left,
                   size_t *right);

/* True for a face of m that KD_SLIVER_SINE keeps out of the tree. */
bool kd_is_sliver(const struct mesh *m, size_t face);

/* ---- in kdtree_events.c ---- */

/* malloc, with arrays of 2 MB or more aligned to 2 MB and the kernel asked for 2 MB pages. NULL when
 * memory runs out; release with free(). */
void *kd_alloc_big(size_t bytes);

/* Builds the SAH tree over faces[0..count) (bd->boxes, region root) the fast way: the same tree as
 * the plain build in kdtree.c, in O(N log N). False when memory runs out. */
bool kd_build_sah_events(struct kd_builder *bd, const uint32_t *faces, size_t count, const struct fbox *root);

/* Orders faces[0..count) as kd_build_sah_events lists a leaf's faces: by their boxes' lower bound on x
 * (flat boxes first at one position), then by face number. False (order unchanged) when memory runs out. */
bool kd_sort_like_events(const struct fbox *boxes, uint32_t *faces, size_t count);

#endif

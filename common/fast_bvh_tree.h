/* fast_bvh_tree.h: what chapter 11's hierarchy is in memory: the rungs of the ladder, the nodes of four
 * (and rung 8's and 9's of eight) children with their boxes side by side in float, and the hierarchy that holds
 * them (chapter 11). fast_bvh.h declares what is done with it; the walks (fast_bvh.c, fast_bvh_eight.c, fast_bvh_lean.c,
 * and what they share in fast_bvh_walk.h) and the build (fast_bvh_build.c) read this layout. */
#ifndef WHITTED_FAST_BVH_TREE_H
#define WHITTED_FAST_BVH_TREE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "aabb.h"
#include "bvh.h" /* enum bvh_split, struct bvh_triangle, struct bvh_info, the build's constants */
#include "mesh.h"

/* The rungs of chapter 11's ladder. Rung 1 is chapter 10's binary BVH (bvh.h) and is not built here;
 * each rung from 2 on keeps everything of the rung below and changes one thing. */
enum fast_bvh_rung {
    FAST_BVH_RUNG_PLAIN = 1,    /* chapter 10's bvh.c, for comparison (built by accel_fast_bvh.c) */
    FAST_BVH_RUNG_WIDE = 2,     /* chapter 10's tree collapsed to four children per node, their boxes
                                   side by side in floats; each child's box tested as in chapter 10 */
    FAST_BVH_RUNG_SIMD = 3,     /* two children's slab tests per instruction (SSE2) */
    FAST_BVH_RUNG_PREFETCH = 4, /* the children put aside are fetched from memory while the ray goes on */
    FAST_BVH_RUNG_BUILD = 5,    /* the SAH build in float, straight into the 4-wide layout: slots filled
                                   four ways at once, big pages for big arrays */
    FAST_BVH_RUNG_FLOAT = 6,    /* all four children's slab tests in one float instruction (SSE), made
                                   conservative by a bound on their rounding; triangles still in double */
    FAST_BVH_RUNG_COMPACT = 7,  /* compact leaves: a leaf's triangles read from the mesh by face number,
                                   not copied in leaf order (the mesh is kept, not copied) */
    FAST_BVH_RUNG_EIGHT = 8,    /* rung 6 on an 8-wide tree: all eight children's float slab tests in one
                                   AVX2 instruction (fast_bvh_eight.c), when the processor has AVX2;
                                   without it, rung 6's tree and walk */
    FAST_BVH_RUNG_LEAN = 9,     /* rung 8's tree, leaves priced in blocks of eight triangles, walked with
                                   less per ray (fast_bvh_lean.c): float root box,
                                   sorted entries, a stack of float entries, four triangles per test in
                                   double (AVX2); without AVX2, rung 6's tree and walk */
    FAST_BVH_RUNG_PACKET = 10,  /* rung 9's tree, the camera rays walked through it eight at a time
                                   (fast_bvh_packet.c), a leaf's triangles four at a time as on rung 9;
                                   every other ray walked as on rung 9. Not a tree of its own:
                                   fast_bvh_build makes rung 9's for it */
    FAST_BVH_RUNG_EXACT = 11,   /* rung 9's tree and walk, each leaf's triangles tested eight at a time in
                                   float with bounds on the rounding (float_triangle.h); only those the
                                   float test cannot rule out are tested in double. Built by
                                   fast_bvh_build as rung 9's tree with a float copy of its triangles;
                                   without AVX2, rung 6's tree and walk */
};
#define FAST_BVH_RUNG_FIRST FAST_BVH_RUNG_WIDE
#define FAST_BVH_RUNG_TOP FAST_BVH_RUNG_LEAN /* the top rung of its own tree (rung 11 is rung 9's, with float triangles) */
/* The last rung a chapter accepts (--rung): rung 10 renders in packets over rung 9's tree, rung 11
 * walks rung 9's tree with the float triangle test. */
#define FAST_BVH_RUNG_LAST FAST_BVH_RUNG_EXACT
/* The rung the chapters walk unless told otherwise: rung 7, which takes the least memory (80 bytes a
 * triangle at the program's peak, against rung 6's 162) and builds and walks as fast as rung 6. Rung 8
 * is faster on big meshes only (0.93 of rung 6's frame on the teapot, 1.00 on the bunny) and needs AVX2,
 * so that the counters the chapters print would depend on the processor (docs/11-fast.md). */
#define FAST_BVH_RUNG_DEFAULT FAST_BVH_RUNG_COMPACT

/* Children per node: FAST_BVH_WIDTH on every rung but 8, FAST_BVH_WIDTH_EIGHT on rung 8's tree. */
#define FAST_BVH_WIDTH 4
#define FAST_BVH_WIDTH_EIGHT 8

/* Rung 6 tests boxes in float only where its bound on the rounding holds (fast_bvh.c): origins and box
 * bounds no larger than this, and 1 / direction between its inverse and it, in magnitude. Then no float
 * step of the test can overflow (2^61 * 2^60 < FLT_MAX) or leave the normal range but by an underflow of
 * the product, which the test's slack covers. A ray or a tree outside it takes rung 5's test in double. */
#define FAST_BVH_FLOAT_RANGE 0x1p60

/* An unused child slot. */
#define FAST_BVH_NO_CHILD UINT32_MAX

/* A node: the boxes of its four children side by side, 128 bytes (two cache lines). A child is another
 * node or a leaf, a run of triangles. The bounds are floats, rounded outward from the double boxes
 * they stand for; an unused slot has the empty box (low +infinity, high -infinity). */
struct fast_bvh_node {
    float bounds[3][2][FAST_BVH_WIDTH]; /* [axis][0 = low, 1 = high][child]: the children's boxes, side by side */
    uint32_t child[FAST_BVH_WIDTH];     /* a child node's index, a leaf's first triangle, or FAST_BVH_NO_CHILD */
    uint32_t count[FAST_BVH_WIDTH];     /* 0 when the child is a node (or no child); else the leaf's triangles */
};

/* A node of rung 8's tree: the same as struct fast_bvh_node with eight children, 256 bytes (four cache
 * lines), so that one AVX2 instruction covers one bound of all eight. */
struct fast_bvh_node8 {
    float bounds[3][2][FAST_BVH_WIDTH_EIGHT]; /* [axis][0 = low, 1 = high][child] */
    uint32_t child[FAST_BVH_WIDTH_EIGHT];     /* as in struct fast_bvh_node */
    uint32_t count[FAST_BVH_WIDTH_EIGHT];
};

/* The hierarchy: the nodes, the triangles in leaf order, and how to reach the root. */
struct fast_bvh {
    enum fast_bvh_rung rung;
    struct fast_bvh_node *nodes;     /* node_count entries, 64-byte aligned; NULL when nodes8 is not */
    struct fast_bvh_node8 *nodes8;   /* rung 8 with AVX2: its node_count 8-wide nodes instead; else NULL
                                        (rung 8 without AVX2 has rung 6's nodes) */
    size_t node_count;
    struct aabb root_box;            /* the box around every triangle in the tree */
    bool float_range;                /* every bound of root_box within FAST_BVH_FLOAT_RANGE (fast_bvh.c) of 0:
                                        rung 6 may test its boxes in float */
    uint32_t root_child, root_count; /* the root, as a child is referred to in a node */
    struct bvh_triangle *triangles;  /* triangle_count entries: tree_count in leaf order, then the slivers;
                                        NULL on rung 7, which reads them from mesh */
    const struct mesh *mesh;         /* rung 7: the mesh built from, kept (not owned); else NULL */
    uint32_t *corners;               /* rung 7: corners[3 k + c] = the number in mesh's vertices of corner c
                                        of the k-th triangle in leaf order (its face's v[c]); else NULL */
    uint32_t *faces;                 /* faces[k] = index into the mesh's faces of the k-th triangle in leaf
                                        order (triangles[k]) */
    size_t triangle_count, tree_count;
    double *lean_corners;            /* rung 9 with AVX2: the tree's triangles again, in blocks of four
                                        (fast_bvh_lean.h says how); else NULL */
    float *float_corners;            /* rung 11 with AVX2: the tree's triangles in float, in blocks of eight
                                        (float_triangle.h says how); else NULL */
    struct bvh_info info;            /* nodes counted in the 4-wide tree (the 8-wide one on rung 8) */
};

#endif

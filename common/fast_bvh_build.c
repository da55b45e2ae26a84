/* fast_bvh_build.c: building chapter 11's 4-wide hierarchy, by collapsing chapter 10's tree (rungs 2 to
 * 4) or in float, straight into the 4-wide layout (rungs 5 to 7), or the 8-wide one (rung 8) (chapter 11).
 *
 * Rungs 2 to 4 change only how the tree is stored and walked (fast_bvh.c), so they take chapter 10's
 * tree as it is: bvh_build makes it, and fast_bvh_collapse gives each node four children instead of
 * two. A 4-wide node starts with its binary node's two children and, while it has room, replaces the
 * interior child with the largest surface area (the one most rays enter) by that child's own two
 * children, as Embree's BVH4 does. The double boxes are rounded outward to float (float_below,
 * float_above), so that every float box holds the padded double box it stands for.
 *
 * Rung 5 changes only the build. It makes the same kind of tree by the same binned SAH (bvh.h's rule
 * and constants), but faster:
 *  - in float, four lanes at a time (struct float_box: x, y, z and an unused lane), with half the
 *    memory traffic of chapter 10's double boxes; all three axes binned in one pass over the triangles;
 *  - a small node gets one slot per triangle instead of BVH_BINS mostly empty ones;
 *  - big nodes fill FAST_BVH_BIN_SETS sets of slots at once (see there);
 *  - straight into the 4-wide layout: a node's children are split as soon as the node is made, by the
 *    very rule fast_bvh_collapse follows, so the binary tree is never stored (40 bytes a triangle
 *    less at the build's peak);
 *  - its big arrays on 2 MB pages (big_alloc);
 *  - with more than one thread (OpenMP's, omp_get_max_threads), the children of a big node are built
 *    in parallel, each in a task of its own (build_children), into the same tree as on one thread.
 * Its tree is not chapter 10's node for node (float centroids, other slots), but as good by the SAH's
 * measure.
 *
 * Rung 7 (compact leaves) builds as rung 5, but keeps the build's boxes in 16 bytes instead of 32
 * (struct packed_box: each bound a 16-bit step on a grid over the root's box, rounded outward), because
 * they set the program's peak memory once the leaves no longer copy the triangles. Its tree is rung 5's
 * but for boxes up to one grid step larger. Where the SAH finds no plane or the tree is deeper than BVH_MAX_DEPTH, chapter 10 halves a
 * node by its median; rung 5 halves it by count as its triangles lie (all centroids at one point give
 * the same halves), so that there is one quickselect, chapter 10's. The median rule itself is built as
 * on rungs 2 to 4: it is quick already.
 *
 * Rung 8 builds as rung 5 (or collapses chapter 10's median tree) with eight children a node: the same
 * rule opens the widest child that splits until a node has eight (struct node_store says which width
 * is being written). Only when the processor has AVX2 (fast_bvh_eight_available), which its walk needs;
 * otherwise it builds rung 6's 4-wide tree, and the walk is rung 6's. Rung 9 builds rung 8's tree with
 * one change, since its walk tests a leaf's triangles four at a time from blocks of four that lie one
 * after the other: the SAH prices a leaf by its blocks of eight triangles, two tests (leaf_tests and
 * FAST_BVH_LEAN_PRICED), so that a leaf of eight costs what a leaf of one does; then it lays the
 * triangles out once more for its walk (fast_bvh_lean_prepare). */
#include "fast_bvh_build.h"

#include <math.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <stdlib.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "big_alloc.h"
#include "clock.h"
#include "fast_bvh_eight.h"
#include "fast_bvh_lean.h"
#include "float4.h"
#include "float_triangle.h"
#include "triangle.h"

/* Nodes of at least FAST_BVH_MANY_SETS_FROM triangles are binned into FAST_BVH_BIN_SETS sets of slots,
 * the prims into the sets in turn, and the sets are added up afterwards. Neighbouring prims
 * usually fall into the same slot, and with one set each update of a slot waits for the previous one
 * to be stored; with four, four updates are under way at once. It took a fifth off the build of the
 * 350k-triangle teapot. Small nodes use one set: there, clearing the extra slots costs more than it
 * saves. */
#define FAST_BVH_BIN_SETS 4
#define FAST_BVH_MANY_SETS_FROM 256

/* Returns box rounded outward to the nearest floats (widened back to double, exactly). */
static struct aabb rounded_to_float(struct aabb box) {
    return (struct aabb){{float_below(box.min.x), float_below(box.min.y), float_below(box.min.z)},
                         {float_above(box.max.x), float_above(box.max.y), float_above(box.max.z)}};
}

/* The nodes of the tree being made: 4-wide (nodes), or 8-wide for rung 8 (nodes8, when not NULL). */
struct node_store {
    struct fast_bvh_node *nodes;
    struct fast_bvh_node8 *nodes8;
};

/* Children per node in store. */
static int store_width(struct node_store store) {
    return store.nodes8 != NULL ? FAST_BVH_WIDTH_EIGHT : FAST_BVH_WIDTH;
}

/* Writes slot k of node `index` of store: the child (or leaf) and its box, rounded outward to float. */
static void set_slot(struct node_store store, uint32_t index, int k, struct aabb box, uint32_t child, uint32_t count) {
    struct aabb rounded = rounded_to_float(box);
    int width = store_width(store);
    float *bounds = store.nodes8 != NULL ? &store.nodes8[index].bounds[0][0][0] : &store.nodes[index].bounds[0][0][0];
    for (int a = 0; a < 3; a++) { /* bounds[a][h][k] is at (2 a + h) width + k */
        bounds[2 * a * width + k] = (float)vec3_axis(rounded.min, a);
        bounds[(2 * a + 1) * width + k] = (float)vec3_axis(rounded.max, a);
    }
    if (store.nodes8 != NULL) {
        store.nodes8[index].child[k] = child;
        store.nodes8[index].count[k] = count;
    } else {
        store.nodes[index].child[k] = child;
        store.nodes[index].count[k] = count;
    }
}

/* The shape and SAH cost of the 4-wide tree, added up node by node (as the collapse makes them; the
 * float build measures its finished tree, measure_node). */
struct tree_shape {
    double root_area;
    size_t node_count, leaves, max_depth;
    double sah_cost;
};

/* Counts a node or a leaf of the given box (and count of triangles, 0 for a node) at the given depth. */
static void count_child(struct tree_shape *shape, struct aabb box, uint32_t count, size_t depth) {
    double area_ratio = shape->root_area > 0.0 ? aabb_surface_area(box) / shape->root_area : 1.0;
    if (count == 0) {
        shape->sah_cost += BVH_COST_TRAVERSAL * area_ratio;
        return;
    }
    shape->leaves++;
    shape->sah_cost += BVH_COST_TRIANGLE * count * area_ratio;
    shape->max_depth = depth > shape->max_depth ? depth : shape->max_depth;
}

/* Whether rung's tree is 8-wide: rungs 8 and 9 where the processor has AVX2 (else rung 6's tree). */
static bool eight_wide(enum fast_bvh_rung rung) {
    return (rung == FAST_BVH_RUNG_EIGHT || rung == FAST_BVH_RUNG_LEAN) && fast_bvh_eight_available();
}

/* Rung 9's leaves: b's triangles laid out for its walk too (fast_bvh_lean_prepare), when b is 8-wide.
 * Returns b, or NULL (b freed) when out of memory. */
static struct fast_bvh *with_lean_leaves(struct fast_bvh *b) {
    if (b != NULL && b->rung == FAST_BVH_RUNG_LEAN && b->nodes8 != NULL && !fast_bvh_lean_prepare(b)) {
        fast_bvh_free(b);
        return NULL;
    }
    return b;
}

/* ==== rung 2: chapter 10's tree, collapsed ===================================================== */

struct collapser {
    const struct bvh *binary;
    struct node_store store; /* 4-wide, or 8-wide for rung 8 */
    struct tree_shape shape;
};

/* Makes a 4-wide node (8-wide for rung 8) out of binary node `index` and its descendants, at the given
 * depth of the wide tree, and returns its index. */
static uint32_t collapse_node(struct collapser *c, uint32_t index, size_t depth) {
    const struct bvh_node *nodes = c->binary->nodes;
    int width = store_width(c->store);
    uint32_t slots[FAST_BVH_WIDTH_EIGHT] = {nodes[index].left, nodes[index].right};
    int used = 2;
    while (used < width) {
        int widest = -1;
        double widest_area = -1.0;
        for (int k = 0; k < used; k++)
            if (nodes[slots[k]].count == 0 && aabb_surface_area(nodes[slots[k]].box) > widest_area) {
                widest = k;
                widest_area = aabb_surface_area(nodes[slots[k]].box);
            }
        if (widest < 0)
            break; /* every child is a leaf */
        const struct bvh_node *open = &nodes[slots[widest]];
        slots[widest] = open->left;
        slots[used++] = open->right;
    }
    uint32_t out = (uint32_t)c->shape.node_count++;
    count_child(&c->shape, nodes[index].box, 0, depth);
    for (int k = 0; k < width; k++) {
        if (k >= used) {
            set_slot(c->store, out, k, aabb_empty(), FAST_BVH_NO_CHILD, 0);
            continue;
        }
        const struct bvh_node *n = &nodes[slots[k]];
        uint32_t child = n->count > 0 ? n->first : collapse_node(c, slots[k], depth + 1);
        if (n->count > 0)
            count_child(&c->shape, n->box, n->count, depth + 1);
        set_slot(c->store, out, k, n->box, child, n->count);
    }
    return out;
}

struct fast_bvh *fast_bvh_collapse(struct bvh *binary, enum fast_bvh_rung rung) {
    double start = clock_seconds();
    struct fast_bvh *b = calloc(1, sizeof *b);
    size_t interior = binary->node_count - binary->info.leaves; /* the wide tree has no more nodes */
    struct node_store store = {NULL, NULL};
    if (eight_wide(rung))
        store.nodes8 = big_alloc((interior > 0 ? interior : 1) * sizeof *store.nodes8, false);
    else
        store.nodes = big_alloc((interior > 0 ? interior : 1) * sizeof *store.nodes, false);
    if (b == NULL || (store.nodes == NULL && store.nodes8 == NULL)) {
        free(b);
        free(store.nodes);
        free(store.nodes8);
        return NULL;
    }
    struct collapser c = {binary, store, {0.0, 0, 0, 0, 0.0}};
    b->rung = rung;
    b->nodes = store.nodes;
    b->nodes8 = store.nodes8;
    b->root_box = aabb_empty();
    if (binary->tree_count > 0) {
        const struct bvh_node *root = &binary->nodes[0];
        b->root_box = rounded_to_float(root->box); /* so that it holds its children's float boxes */
        c.shape.root_area = aabb_surface_area(root->box);
        b->root_count = root->count;
        b->root_child = root->count > 0 ? root->first : collapse_node(&c, 0, 0);
        if (root->count > 0)
            count_child(&c.shape, root->box, root->count, 0);
    }
    b->node_count = c.shape.node_count;
    b->triangles = binary->triangles; /* taken over: the same triangles in the same leaf order */
    b->faces = binary->faces;
    binary->triangles = NULL;
    binary->faces = NULL;
    b->triangle_count = binary->triangle_count;
    b->tree_count = binary->tree_count;
    b->info = (struct bvh_info){c.shape.node_count + c.shape.leaves, c.shape.leaves, c.shape.max_depth, 0.0,
                                c.shape.sah_cost + BVH_COST_TRIANGLE * binary->info.slivers, binary->info.slivers};
    b->info.build_ms = binary->info.build_ms + 1e3 * (clock_seconds() - start);
    return b;
}

/* ==== rung 5: the float build ================================================================== */

/* Chapter 5's box in float, four lanes at a time: x, y, z and an unused lane, 0 in both corners. The
 * bounds are rounded outward from the double box they stand for. */
struct float_box {
    float4 lo, hi;
};

static inline struct float_box float_box_empty(void) {
    return (struct float_box){{INFINITY, INFINITY, INFINITY, 0.0f}, {-INFINITY, -INFINITY, -INFINITY, 0.0f}};
}

static inline void float_box_grow(struct float_box *b, float4 lo, float4 hi) {
    b->lo = min4(b->lo, lo);
    b->hi = max4(b->hi, hi);
}

/* Half the surface area of a box that is not empty, in float: what the SAH sweeps compare. */
static inline float float_box_half_area(const struct float_box *b) {
    float4 e = b->hi - b->lo;
    return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}

/* The box as chapter 5's, in double (exactly: every float is a double). */
static struct aabb float_box_widened(const struct float_box *b) {
    return (struct aabb){{b->lo[0], b->lo[1], b->lo[2]}, {b->hi[0], b->hi[1], b->hi[2]}};
}

/* Twice the centre of a prim's box: the point the split sorts by. */
static inline float4 centroid_of(const struct float_box *p) { return p->lo + p->hi; }

/* A run of prims (see struct builder), with the box of their boxes and the box of their centroids. */
struct build_range {
    uint32_t begin, end;
    struct float_box box, centroids;
};

/* ---- rung 7: the build's boxes in 16 bytes ----
 * A box's six bounds as steps of a grid: bound = base + q * step on each axis, computed in float
 * (packed_value), q from 0 to FAST_BVH_PACKED_STEPS. base is the low corner of the root's box and the
 * grid reaches past its high corner, so every bound of the tree is on it; a low bound is rounded down
 * to the grid and a high one up (packed_below, packed_above), so that the packed box holds the float box
 * it stands for. The step is no finer than float itself can tell apart near the root's box (2^-22 of
 * its largest coordinate): then packed_value is off by less than half a step and the roundings take at
 * most a step or two to settle. */
#define FAST_BVH_PACKED_STEPS 65535
#define FAST_BVH_PACKED_FINEST 0x1p-22f /* the finest step, relative to the largest coordinate */
#define FAST_BVH_PACKED_WIDEN (1.0f + 0x1p-10f) /* how much a step too short for the grid is widened */

struct packed_box {
    uint16_t lo[4], hi[4]; /* x, y, z and an unused lane, 0 (as in struct float_box), so that a box is 16
                              bytes, read and moved in one instruction */
};

/* The grid: base and step for each axis (lane 3 is 0 in both, the unused lane of struct float_box), and
 * 1 / step in double (0 for a step of 0; finite for a step below float's normal range), which only
 * guesses a bound's step (packed_guess). */
struct packed_grid {
    float4 base, step;
    double inverse_step[3];
};

static inline float packed_value(float base, float step, uint16_t q) { return base + (float)q * step; }

/* The grid over the root's box *root; false when its bounds or the grid's extent are not finite in
 * float (a mesh beyond float's range: the build then keeps its boxes in full). */
static bool packed_grid_make(const struct float_box *root, struct packed_grid *g) {
    g->base = (float4){0, 0, 0, 0};
    g->step = (float4){0, 0, 0, 0};
    float largest = 0.0f;
    for (int a = 0; a < 3; a++) {
        if (!(isfinite(root->lo[a]) && isfinite(root->hi[a])))
            return false;
        largest = fmaxf(largest, fmaxf(fabsf(root->lo[a]), fabsf(root->hi[a])));
    }
    for (int a = 0; a < 3; a++) {
        float lo = root->lo[a], hi = root->hi[a];
        float step = fmaxf(float_above(((double)hi - (double)lo) / FAST_BVH_PACKED_STEPS), largest * FAST_BVH_PACKED_FINEST);
        while (isfinite(step) && packed_value(lo, step, FAST_BVH_PACKED_STEPS) < hi)
            step = nextafterf(step * FAST_BVH_PACKED_WIDEN, INFINITY);
        if (!isfinite(step) || !isfinite(packed_value(lo, step, FAST_BVH_PACKED_STEPS)))
            return false;
        g->base[a] = lo;
        g->step[a] = step;
        g->inverse_step[a] = step > 0.0f ? 1.0 / step : 0.0;
    }
    return true;
}

/* Where x lies on the grid, in steps from base, estimated by the grid's inverse step (0 where a step is
 * 0) and clamped to the grid: packed_below rounds it down and packed_above up, and each then walks to
 * the exact step (almost always none to walk, so that the walks' branches are foreseen). */
static inline double packed_guess(float x, float base, double inverse_step) {
    double q = ((double)x - base) * inverse_step;
    return q > 0.0 ? (q < FAST_BVH_PACKED_STEPS ? q : FAST_BVH_PACKED_STEPS) : 0.0; /* a NaN gives 0 */
}

/* The highest grid step at or below x, and the lowest at or above it, for base <= x <= the grid's end. */
static inline uint16_t packed_below(float x, float base, float step, double inverse_step) {
    uint16_t k = (uint16_t)packed_guess(x, base, inverse_step);
    while (k > 0 && packed_value(base, step, k) > x)
        k--;
    while (k < FAST_BVH_PACKED_STEPS && packed_value(base, step, (uint16_t)(k + 1)) <= x)
        k++;
    return k;
}

static inline uint16_t packed_above(float x, float base, float step, double inverse_step) {
    double q = packed_guess(x, base, inverse_step);
    uint16_t k = (uint16_t)q;
    k += (double)k < q; /* rounded up */
    while (k < FAST_BVH_PACKED_STEPS && packed_value(base, step, k) < x)
        k++;
    while (k > 0 && packed_value(base, step, (uint16_t)(k - 1)) >= x)
        k--;
    return k;
}

static struct packed_box packed_box_make(const struct float_box *box, const struct packed_grid *g) {
    struct packed_box p = {{0}, {0}};
    for (int a = 0; a < 3; a++) {
        p.lo[a] = packed_below(box->lo[a], g->base[a], g->step[a], g->inverse_step[a]);
        p.hi[a] = packed_above(box->hi[a], g->base[a], g->step[a], g->inverse_step[a]);
    }
    return p;
}

/* The float box p stands for: packed_value on all four lanes at once, the same float steps. With SSE2,
 * the box is read in one 16-byte load and each corner widened by two instructions. */
static inline struct float_box packed_box_widened(const struct packed_box *p, const struct packed_grid *g) {
#if defined(__SSE2__)
    __m128i steps = _mm_loadu_si128((const __m128i *)(const void *)p), zero = _mm_setzero_si128();
    float4 lo = _mm_cvtepi32_ps(_mm_unpacklo_epi16(steps, zero));
    float4 hi = _mm_cvtepi32_ps(_mm_unpackhi_epi16(steps, zero));
#else
    float4 lo = {p->lo[0], p->lo[1], p->lo[2], 0.0f}, hi = {p->hi[0], p->hi[1], p->hi[2], 0.0f};
#endif
    return (struct float_box){g->base + lo * g->step, g->base + hi * g->step};
}

struct builder {
    struct float_box *prims;     /* one padded box per triangle; the splits reorder them into leaf order */
    struct packed_box *packed;   /* rung 7: the same in 16 bytes, on the grid (prims is then NULL) */
    struct packed_grid grid;
    uint32_t *faces;             /* the face number of each prim, reordered along with them */
    struct node_store store;     /* the 4-wide tree, or the 8-wide one for rung 8 (on more than one thread,
                                    in the order the tasks made the nodes: order_nodes reorders them) */
    bool parallel;               /* whether big nodes build their children in tasks (more than one thread) */
    uint32_t block;              /* the SAH prices a leaf by its blocks of this many triangles
                                    (FAST_BVH_LEAN_PRICED for rung 9; else 1, by its triangles) */
    /* Nodes written to store so far: the next one's index, taken atomically. On a cache line of its own,
     * so that a task taking it does not evict the fields above, which every task reads all the time. */
    _Alignas(64) uint32_t node_count;
};

/* Prim k's box, `packed` saying whether bd's boxes are rung 7's (a constant where the caller wants a loop
 * for each kind of box), or asking bd. */
static inline __attribute__((always_inline)) struct float_box prim_box_of(const struct builder *bd, bool packed,
                                                                          uint32_t k) {
    return packed ? packed_box_widened(&bd->packed[k], &bd->grid) : bd->prims[k];
}

static inline struct float_box prim_box(const struct builder *bd, uint32_t k) {
    return prim_box_of(bd, bd->packed != NULL, k);
}

static inline void swap_prims(struct builder *bd, uint32_t i, uint32_t j) {
    if (bd->packed != NULL) {
        struct packed_box box = bd->packed[i];
        bd->packed[i] = bd->packed[j];
        bd->packed[j] = box;
    } else {
        struct float_box box = bd->prims[i];
        bd->prims[i] = bd->prims[j];
        bd->prims[j] = box;
    }
    uint32_t face = bd->faces[i];
    bd->faces[i] = bd->faces[j];
    bd->faces[j] = face;
}

/* Fills r->box and r->centroids from its prims. */
static void range_bounds(const struct builder *bd, struct build_range *r) {
    r->box = float_box_empty();
    r->centroids = float_box_empty();
    for (uint32_t k = r->begin; k < r->end; k++) {
        struct float_box p = prim_box(bd, k);
        float_box_grow(&r->box, p.lo, p.hi);
        float4 c = centroid_of(&p);
        float_box_grow(&r->centroids, c, c);
    }
}

/* Halves r by count, its prims as they lie: where the SAH cannot choose (see the file comment). */
static void halve(const struct builder *bd, const struct build_range *r, struct build_range *left,
                  struct build_range *right) {
    uint32_t mid = r->begin + (r->end - r->begin) / 2;
    left->begin = r->begin;
    left->end = mid;
    right->begin = mid;
    right->end = r->end;
    range_bounds(bd, left);
    range_bounds(bd, right);
}

struct bin {
    struct float_box box;
    uint32_t count;
};

/* The slots of a centroid on all three axes: the same expression in binning and partitioning, so both
 * agree. Slot = floor((centroid - origin) * scale), clamped to [0, slots - 1] before it is converted to
 * an integer, so that a NaN or infinite centroid (a mesh beyond float's range) lands in slot 0 or the
 * last slot instead of becoming INT_MIN and indexing outside the bins. */
static inline int4 bins_of(float4 centroid, float4 origin, float4 scale, int slots) {
    float4 last = {(float)(slots - 1), (float)(slots - 1), (float)(slots - 1), (float)(slots - 1)};
    float4 x = max4((centroid - origin) * scale, (float4){0, 0, 0, 0}); /* a NaN gives 0 */
    return __builtin_convertvector(min4(x, last), int4);
}

/* Bins the prim whose box is p into one set of bins: on each axis, the slot of its centroid (origin and
 * scale as in bins_of) counted and its box grown. The three axes are written out: as a loop, GCC kept
 * the loop. */
static inline void bin_prim(struct bin set[3][BVH_BINS], struct float_box p, float4 origin, float4 scale, int slots) {
    int4 k = bins_of(centroid_of(&p), origin, scale, slots);
    struct bin *x = &set[0][k[0]], *y = &set[1][k[1]], *z = &set[2][k[2]];
    x->count++;
    float_box_grow(&x->box, p.lo, p.hi);
    y->count++;
    float_box_grow(&y->box, p.lo, p.hi);
    z->count++;
    float_box_grow(&z->box, p.lo, p.hi);
}

/* Bins prims [begin, end) four a step, one into each of four sets, as far as whole steps go; returns
 * where it stopped. `packed` is whether bd's boxes are rung 7's (a constant where it is inlined, so
 * that each kind of box gets its own loop). */
static inline __attribute__((always_inline)) uint32_t bin_fours(const struct builder *bd, bool packed, uint32_t begin,
                                                                uint32_t end, float4 origin, float4 scale, int slots,
                                                                struct bin bins[][3][BVH_BINS]) {
    uint32_t i = begin;
    for (; i + FAST_BVH_BIN_SETS <= end; i += FAST_BVH_BIN_SETS) {
        bin_prim(bins[0], prim_box_of(bd, packed, i), origin, scale, slots);
        bin_prim(bins[1], prim_box_of(bd, packed, i + 1), origin, scale, slots);
        bin_prim(bins[2], prim_box_of(bd, packed, i + 2), origin, scale, slots);
        bin_prim(bins[3], prim_box_of(bd, packed, i + 3), origin, scale, slots);
    }
    return i;
}

/* Clears `sets` sets of bins and bins prims [begin, end) into them, the prims into the sets in turn. With
 * four sets, four prims a step, one into each set. */
static void bin_prims(const struct builder *bd, uint32_t begin, uint32_t end, float4 origin, float4 scale, int slots,
                      int sets, struct bin bins[][3][BVH_BINS]) {
    for (int set = 0; set < sets; set++)
        for (int a = 0; a < 3; a++)
            for (int k = 0; k < slots; k++)
                bins[set][a][k] = (struct bin){float_box_empty(), 0};
    uint32_t i = begin;
    if (sets == FAST_BVH_BIN_SETS && bd->packed != NULL)
        i = bin_fours(bd, true, begin, end, origin, scale, slots, bins);
    else if (sets == FAST_BVH_BIN_SETS)
        i = bin_fours(bd, false, begin, end, origin, scale, slots, bins);
    for (; i < end; i++)
        bin_prim(bins[sets == 1 ? 0 : i % FAST_BVH_BIN_SETS], prim_box(bd, i), origin, scale, slots);
}

/* With more than one thread, nodes of at least FAST_BVH_BIN_PARTS_FROM triangles are binned in
 * FAST_BVH_BIN_PARTS parts, a task each, whose bins are then added up. The bins are the same as one
 * thread's, bit for bit, in any order of the parts: a box's bounds are minima and maxima, and the counts
 * whole numbers, so no rounding depends on the order. It is the top of the tree, where there are not yet
 * enough subtrees to keep the threads busy. */
#define FAST_BVH_BIN_PARTS 4
#define FAST_BVH_BIN_PARTS_FROM 4096

/* Bins r's prims into FAST_BVH_BIN_SETS sets of bins (as bin_prims), in parallel parts. */
static void bin_in_parts(const struct builder *bd, const struct build_range *r, float4 scale, int slots,
                         struct bin bins[FAST_BVH_BIN_SETS][3][BVH_BINS]) {
    struct bin parts[FAST_BVH_BIN_PARTS - 1][FAST_BVH_BIN_SETS][3][BVH_BINS]; /* part 0 is bins itself */
    uint64_t n = r->end - r->begin;
    for (int part = 0; part < FAST_BVH_BIN_PARTS; part++) {
        uint32_t begin = r->begin + (uint32_t)(n * part / FAST_BVH_BIN_PARTS);
        uint32_t end = r->begin + (uint32_t)(n * (part + 1) / FAST_BVH_BIN_PARTS);
        struct bin (*into)[3][BVH_BINS] = part == 0 ? bins : parts[part - 1];
#pragma omp task default(none) firstprivate(bd, r, scale, slots, begin, end, into)
        bin_prims(bd, begin, end, r->centroids.lo, scale, slots, FAST_BVH_BIN_SETS, into);
    }
#pragma omp taskwait
    for (int part = 1; part < FAST_BVH_BIN_PARTS; part++)
        for (int set = 0; set < FAST_BVH_BIN_SETS; set++)
            for (int a = 0; a < 3; a++)
                for (int k = 0; k < slots; k++) {
                    bins[set][a][k].count += parts[part - 1][set][a][k].count;
                    float_box_grow(&bins[set][a][k].box, parts[part - 1][set][a][k].box.lo,
                                   parts[part - 1][set][a][k].box.hi);
                }
}

/* Rung 9's SAH prices a leaf by its blocks of this many triangles: two of its walk's tests of four, on
 * two blocks next to each other in memory, so that a leaf of up to eight costs what a leaf of one does.
 * Priced by its tests of four instead, the teapot's tree had more nodes and its build 13 % more time,
 * for a frame no faster (docs/fast-notes.md): the walk waits on memory more than on arithmetic, and a
 * leaf's second block lies next to its first. At most BVH_MAX_LEAF_SIZE, a leaf's largest. */
#define FAST_BVH_LEAN_PRICED (2 * FAST_BVH_LEAN_LANES)
_Static_assert(FAST_BVH_LEAN_PRICED <= BVH_MAX_LEAF_SIZE, "a leaf holds a priced block");

/* What the SAH counts for `count` triangles in a leaf: its blocks of bd->block triangles. */
static inline float leaf_tests(const struct builder *bd, uint32_t count) {
    return (float)((count + bd->block - 1) / bd->block);
}

/* Looks for the cheapest SAH split of r, each side and the leaf priced by their leaf_tests (one a
 * triangle, but for rung 9 one for each eight). Returns false, leaving the prims alone, when a leaf is
 * cheaper or no plane separates the centroids; otherwise partitions r into *left and *right. */
/* TASK 10.2 ALSO: the binned SAH split, in float (chapter 11's builder) */
static bool split_sah(struct builder *bd, const struct build_range *r, struct build_range *left,
                      struct build_range *right) {
    struct bin bins[FAST_BVH_BIN_SETS][3][BVH_BINS]; /* [set][axis][slot]; the sets are summed into set 0 */
    uint32_t n = r->end - r->begin;
    /* No more triangles than one block (rung 9: eight): the leaf costs one, and any split a node visit
     * plus its sides' blocks, which is no less while a visit costs no less than a block. So the test
     * below would choose the leaf: it is chosen without binning. */
    if (n <= bd->block && n <= BVH_MAX_LEAF_SIZE && BVH_COST_TRAVERSAL >= BVH_COST_TRIANGLE)
        return false;
    int slots = n < BVH_BINS ? (int)n : BVH_BINS; /* slots used per axis */
    int sets = n >= FAST_BVH_MANY_SETS_FROM ? FAST_BVH_BIN_SETS : 1;
    float4 extent = r->centroids.hi - r->centroids.lo, scale = {0, 0, 0, 0};
    for (int a = 0; a < 3; a++)
        scale[a] = extent[a] > 0.0f ? (float)slots / extent[a] : 0.0f; /* 0: one slot takes all */
    if (bd->parallel && n >= FAST_BVH_BIN_PARTS_FROM)
        bin_in_parts(bd, r, scale, slots, bins);
    else
        bin_prims(bd, r->begin, r->end, r->centroids.lo, scale, slots, sets, bins);
    for (int set = 1; set < sets; set++)
        for (int a = 0; a < 3; a++)
            for (int k = 0; k < slots; k++) {
                bins[0][a][k].count += bins[set][a][k].count;
                float_box_grow(&bins[0][a][k].box, bins[set][a][k].box.lo, bins[set][a][k].box.hi);
            }

    /* For each axis, sweep from the right to get the area and count right of every plane, then from the
     * left to price each plane. Cost: the sum of area * tests (leaf_tests of the count) over both sides. */
    float best_cost = INFINITY;
    int best_axis = -1, best_plane = 0;
    for (int a = 0; a < 3; a++) {
        if (scale[a] == 0.0f)
            continue; /* all centroids in one plane: this axis cannot separate them */
        /* right_cost[k]: half area times count of everything right of the plane between slots k - 1
         * and k (infinite while nothing is: such a plane is never chosen). Empty slots change nothing,
         * so they are skipped; small nodes leave most slots empty. */
        float right_cost[BVH_BINS];
        struct float_box side = float_box_empty();
        uint32_t count = 0;
        float cost = INFINITY;
        for (int k = slots - 1; k > 0; k--) {
            if (bins[0][a][k].count > 0) {
                float_box_grow(&side, bins[0][a][k].box.lo, bins[0][a][k].box.hi);
                count += bins[0][a][k].count;
                cost = float_box_half_area(&side) * leaf_tests(bd, count);
            }
            right_cost[k] = cost;
        }
        side = float_box_empty();
        count = 0;
        for (int k = 1; k < slots; k++) {
            if (bins[0][a][k - 1].count == 0)
                continue; /* the same split as the plane before */
            float_box_grow(&side, bins[0][a][k - 1].box.lo, bins[0][a][k - 1].box.hi);
            count += bins[0][a][k - 1].count;
            cost = float_box_half_area(&side) * leaf_tests(bd, count) + right_cost[k];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = a;
                best_plane = k;
            }
        }
    }
    if (best_axis < 0)
        return false;

    double area = aabb_surface_area(float_box_widened(&r->box));
    double split_cost = area > 0.0 ? BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * 2.0 * best_cost / area : INFINITY;
    if (n <= BVH_MAX_LEAF_SIZE && BVH_COST_TRIANGLE * leaf_tests(bd, n) <= split_cost)
        return false;

    /* Partition, gathering each side's centroid box on the way; the boxes are the unions of the slots'.
     * A prim goes left when its slot on the chosen axis is below best_plane. Its slot is x = (centroid -
     * origin) * scale clamped to [0, slots - 1] and truncated (bins_of); best_plane is a whole number
     * from 1 to slots - 1, so the slot is below it exactly when x is not at least best_plane (a negative
     * x or a NaN has slot 0, an x past the last slot is not below it): one compare on one axis, the
     * same answer as bins_of's. */
    float origin = r->centroids.lo[best_axis], axis_scale = scale[best_axis], plane = (float)best_plane;
    struct float_box left_centroids = float_box_empty(), right_centroids = float_box_empty();
    uint32_t i = r->begin, j = r->end; /* [begin,i) go left, [j,end) go right */
    while (i < j) {
        struct float_box p = prim_box(bd, i);
        float4 c = centroid_of(&p);
        float x = (c[best_axis] - origin) * axis_scale;
        if (!(x >= plane)) {
            float_box_grow(&left_centroids, c, c);
            i++;
        } else {
            float_box_grow(&right_centroids, c, c);
            swap_prims(bd, i, --j);
        }
    }
    *left = (struct build_range){r->begin, i, float_box_empty(), left_centroids};
    *right = (struct build_range){i, r->end, float_box_empty(), right_centroids};
    for (int k = 0; k < slots; k++) {
        struct build_range *side = k < best_plane ? left : right;
        float_box_grow(&side->box, bins[0][best_axis][k].box.lo, bins[0][best_axis][k].box.hi);
    }
    return true;
}

/* Splits r, at depth `depth` of the binary tree the splits make, into *left and *right by the SAH, or
 * halves it when the SAH cannot choose and r is too big for a leaf. Returns false when r is a leaf. */
static bool split(struct builder *bd, const struct build_range *r, size_t depth, struct build_range *left,
                  struct build_range *right) {
    uint32_t n = r->end - r->begin;
    if (n <= 1)
        return false;
    if (depth < BVH_MAX_DEPTH && split_sah(bd, r, left, right))
        return true;
    if (n <= BVH_MAX_LEAF_SIZE)
        return false;
    halve(bd, r, left, right); /* too deep for the heuristic, or every centroid at one point */
    return true;
}

/* A child of a node being made: its prims, its depth in the binary tree, and whether it is a leaf. */
struct slot {
    struct build_range range;
    size_t depth;
    bool leaf;
};

/* Nodes of at least FAST_BVH_TASK_FROM triangles build their children in parallel when the build has
 * more than one thread: each child's subtree in a task of its own. Smaller than this, a task costs more
 * than it saves. */
#define FAST_BVH_TASK_FROM 1024

static uint32_t build_node(struct builder *bd, const struct build_range *left, const struct build_range *right,
                           size_t depth);

/* The child a slot holds: a leaf (child = its first prim, count = its prims) or, if it splits, the node
 * built over it (child = its index in bd's store, count = 0). */
static void build_child(struct builder *bd, const struct slot *s, uint32_t *child, uint32_t *count) {
    struct build_range halves[2];
    *child = s->range.begin;
    *count = s->range.end - s->range.begin;
    if (!s->leaf && split(bd, &s->range, s->depth, &halves[0], &halves[1])) {
        *count = 0;
        *child = build_node(bd, &halves[0], &halves[1], s->depth);
    }
}

/* Builds the children of a node, whose slots are given, filling child[] and count[]: one after the other,
 * or, for a big node when there are threads, each in a task of its own. The tasks take their nodes'
 * indices as they come (build_node), so that the nodes are not in the order one thread writes them
 * until order_nodes has put them there. */
static void build_children(struct builder *bd, const struct slot *slots, int used, uint32_t *child, uint32_t *count) {
    uint32_t prims = 0;
    for (int k = 0; k < used; k++)
        prims += slots[k].range.end - slots[k].range.begin;
    bool in_tasks = bd->parallel && prims >= FAST_BVH_TASK_FROM;
    for (int k = 0; k < used; k++) {
        if (in_tasks) {
#pragma omp task default(none) firstprivate(bd, k) shared(slots, child, count)
            build_child(bd, &slots[k], &child[k], &count[k]);
        } else {
            build_child(bd, &slots[k], &child[k], &count[k]);
        }
    }
#pragma omp taskwait
}

/* Makes the 4-wide node (8-wide for rung 8) whose binary split has given left and right (at binary
 * depth `depth`) and everything below it; returns its index. As in fast_bvh_collapse, the child with
 * the largest surface area that splits is replaced by its halves while there is room; a child that
 * does not split is a leaf. */
static uint32_t build_node(struct builder *bd, const struct build_range *left, const struct build_range *right,
                           size_t depth) {
    int width = store_width(bd->store);
    struct slot slots[FAST_BVH_WIDTH_EIGHT] = {{*left, depth + 1, false}, {*right, depth + 1, false}};
    int used = 2;
    while (used < width) {
        int widest = -1;
        double widest_area = -1.0;
        for (int k = 0; k < used; k++) {
            double area = aabb_surface_area(float_box_widened(&slots[k].range.box));
            if (!slots[k].leaf && area > widest_area) {
                widest = k;
                widest_area = area;
            }
        }
        if (widest < 0)
            break; /* every child is a leaf */
        struct slot open = slots[widest];
        struct build_range halves[2];
        if (!split(bd, &open.range, open.depth, &halves[0], &halves[1])) {
            slots[widest].leaf = true;
            continue;
        }
        slots[widest] = (struct slot){halves[0], open.depth + 1, false};
        slots[used++] = (struct slot){halves[1], open.depth + 1, false};
    }
    uint32_t out;
#pragma omp atomic capture
    out = bd->node_count++;
    uint32_t child[FAST_BVH_WIDTH_EIGHT] = {0}, count[FAST_BVH_WIDTH_EIGHT] = {0};
    build_children(bd, slots, used, child, count);
    for (int k = 0; k < width; k++) {
        if (k < used)
            set_slot(bd->store, out, k, float_box_widened(&slots[k].range.box), child[k], count[k]);
        else
            set_slot(bd->store, out, k, aabb_empty(), FAST_BVH_NO_CHILD, 0);
    }
    return out;
}

/* Room for `count` nodes of the given width (8 or 4) in *store, on 2 MB pages or not (big_alloc); false
 * when memory runs out. */
static bool store_alloc(struct node_store *store, bool eight, size_t count, bool huge_pages) {
    *store = (struct node_store){NULL, NULL};
    if (eight)
        store->nodes8 = big_alloc((count > 0 ? count : 1) * sizeof *store->nodes8, huge_pages);
    else
        store->nodes = big_alloc((count > 0 ? count : 1) * sizeof *store->nodes, huge_pages);
    return store->nodes != NULL || store->nodes8 != NULL;
}

/* Numbers node `index` of store and everything below it, from *next on, in the order in which one thread
 * makes them: each node before its children's subtrees, slot by slot. Writes each node's number in
 * order[its index] and its children's numbers over their indices in it; returns its number. */
static uint32_t number_node(struct node_store store, uint32_t index, uint32_t *next, uint32_t *order) {
    uint32_t number = (*next)++;
    order[index] = number;
    uint32_t *child = store.nodes8 != NULL ? store.nodes8[index].child : store.nodes[index].child;
    const uint32_t *count = store.nodes8 != NULL ? store.nodes8[index].count : store.nodes[index].count;
    for (int k = 0; k < store_width(store); k++)
        if (count[k] == 0 && child[k] != FAST_BVH_NO_CHILD)
            child[k] = number_node(store, child[k], next, order);
    return number;
}

static void swap_nodes(struct node_store store, uint32_t i, uint32_t j) {
    if (store.nodes8 != NULL) {
        struct fast_bvh_node8 node = store.nodes8[i];
        store.nodes8[i] = store.nodes8[j];
        store.nodes8[j] = node;
    } else {
        struct fast_bvh_node node = store.nodes[i];
        store.nodes[i] = store.nodes[j];
        store.nodes[j] = node;
    }
}

/* Puts the node_count nodes of store, in the order the parallel build's tasks made them (build_children),
 * in the order one thread makes them, in place: the same array, byte for byte, as one thread's. The
 * nodes are numbered from the root, node 0 (number_node), then each is swapped to its number, cycle by
 * cycle of the renaming, so that every swap puts one node where it belongs. `order` is room for
 * node_count numbers. In place, and not copied into a second store, because fresh memory costs a page
 * fault every 4 KB or 2 MB (big_alloc.c): a second store is most of the parallel build's new memory. */
static void order_nodes(struct node_store store, uint32_t node_count, uint32_t *order) {
    uint32_t next = 0;
    number_node(store, 0, &next, order); /* every node the build made is in the tree: next == node_count */
    for (uint32_t i = 0; i < node_count; i++)
        while (order[i] != i) { /* the node at i belongs at order[i]: swap it there */
            uint32_t j = order[i];
            swap_nodes(store, i, j);
            order[i] = order[j];
            order[j] = j;
        }
}

/* The box of slot k of node `index` of store, widened back to double (exactly). */
static struct aabb slot_box(struct node_store store, uint32_t index, int k) {
    int width = store_width(store);
    const float *bounds = store.nodes8 != NULL ? &store.nodes8[index].bounds[0][0][0] : &store.nodes[index].bounds[0][0][0];
    return (struct aabb){{bounds[k], bounds[2 * width + k], bounds[4 * width + k]},
                         {bounds[width + k], bounds[3 * width + k], bounds[5 * width + k]}};
}

/* Adds the children of node `index` of store (at wide depth `depth`) and everything below them to
 * *shape, slot by slot, each node before its subtree: the order in which one thread makes them, so that
 * the SAH cost is summed in one order whatever the number of threads. */
static void measure_node(struct node_store store, uint32_t index, size_t depth, struct tree_shape *shape) {
    shape->node_count++;
    int width = store_width(store);
    for (int k = 0; k < width; k++) {
        uint32_t child = store.nodes8 != NULL ? store.nodes8[index].child[k] : store.nodes[index].child[k];
        uint32_t count = store.nodes8 != NULL ? store.nodes8[index].count[k] : store.nodes[index].count[k];
        if (child == FAST_BVH_NO_CHILD)
            continue;
        count_child(shape, slot_box(store, index, k), count, depth + 1);
        if (count == 0)
            measure_node(store, child, depth + 1, shape);
    }
}

/* A face box's bounds moved outward to float, more cheaply than float_below and float_above: the nearest
 * float, then one step outward. The nearest float is within half a step of x, so one step out is past
 * x, and a bound is at most one step looser than float_below's (a float step is 2^-24 of the
 * coordinate, the pad 2^-20 of the mesh's size). float_below must compare the nearest float with x to
 * know whether to step, and which way a double rounds is a coin toss that a branch mispredicts half the
 * time: stepping every time took about a tenth off the bunny's build. A NaN (from a corner at infinity)
 * gives the infinity on that side, as float_below and float_above do, and so does a bound past float's
 * range on that side (-1e39 as a low bound); one past the other end (-1e39 as a high bound) becomes
 * -FLT_MAX, the step in from -infinity, which is still past it. */
static inline float face_bound_below(double x) {
    float f = (float)x;
    return isnan(x) || f == -INFINITY ? -INFINITY : float_step_down(f);
}

static inline float face_bound_above(double x) {
    float f = (float)x;
    return isnan(x) || f == INFINITY ? INFINITY : float_step_up(f);
}

/* box with its bounds moved outward to float by face_bound_below and face_bound_above. */
static struct float_box face_bounds(struct aabb box) {
    return (struct float_box){
        {face_bound_below(box.min.x), face_bound_below(box.min.y), face_bound_below(box.min.z), 0.0f},
        {face_bound_above(box.max.x), face_bound_above(box.max.y), face_bound_above(box.max.z), 0.0f}};
}

/* The box of face f of m grown by pad (bvh_face_box) and moved outward to float (face_bounds), in *box;
 * false, leaving *box alone, for a sliver. */
static bool face_float_box(const struct mesh *m, size_t f, double pad, struct float_box *box) {
    struct aabb padded;
    if (!bvh_face_box(m, f, pad, &padded))
        return false;
    *box = face_bounds(padded);
    return true;
}

/* The box around the corners of some faces, as triangle_box_pad makes it (a NaN coordinate left out),
 * and whether every one of those corners is finite. */
struct corners {
    vec3 lo, hi;
    bool finite;
};

/* The corners of faces [begin, end) of m. */
static struct corners corners_of(const struct mesh *m, size_t begin, size_t end) {
    struct corners c = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}, true};
    for (size_t f = begin; f < end; f++)
        for (int k = 0; k < 3; k++) {
            vec3 p = m->vertices[m->faces[f].v[k]];
            c.finite = c.finite && vec3_is_finite(p);
            c.lo = vec3_min(p, c.lo); /* p first: a NaN coordinate of p leaves lo alone */
            c.hi = vec3_max(p, c.hi);
        }
    return c;
}

/* The faces' corners are boxed in this many parts, shared among the threads (faces_corners). */
#define FAST_BVH_CORNER_PARTS 8

/* The corners of every face of m, in one pass shared among the threads (with `parallel`): the box
 * triangle_box_pad measures, since the least and the greatest of the same numbers do not depend on the
 * order in which they are compared, and the box the grid of rung 7 spans (build_in_float). */
static struct corners faces_corners(const struct mesh *m, bool parallel) {
    (void)parallel; /* read by the pragma alone, which the browser's build (no OpenMP) leaves out */
    struct corners part[FAST_BVH_CORNER_PARTS];
    size_t n = m->face_count;
#pragma omp parallel for if (parallel) schedule(static) default(none) shared(m, part, n)
    for (int k = 0; k < FAST_BVH_CORNER_PARTS; k++)
        part[k] = corners_of(m, n * (size_t)k / FAST_BVH_CORNER_PARTS, n * (size_t)(k + 1) / FAST_BVH_CORNER_PARTS);
    struct corners all = part[0];
    for (int k = 1; k < FAST_BVH_CORNER_PARTS; k++) {
        all.lo = vec3_min(part[k].lo, all.lo);
        all.hi = vec3_max(part[k].hi, all.hi);
        all.finite = all.finite && part[k].finite;
    }
    return all;
}

/* True when the build may run in parallel: OpenMP is compiled in (not in the browser's build) and gives
 * more than one thread. */
static bool threads_to_share(void) {
#ifdef _OPENMP
    return omp_get_max_threads() > 1;
#else
    return false;
#endif
}

/* A face that is a sliver, in face_prims' first pass: no face has this number (BVH_MAX_FACES). */
#define FAST_BVH_SLIVER_MARK UINT32_MAX

/* Fills the prims of bd (bd->packed where it is not NULL, else bd->prims) and faces[] (m->face_count
 * entries) for the faces of m: the tree faces first, in order, each with its padded box rounded outward
 * (face_float_box); the slivers, which the tree leaves out, at the end of faces[] from the last entry
 * down, in order. Returns the number of tree faces and sets *slivers to the number of slivers.
 * In two passes, so that the first, where the time goes, is shared among the threads and the result is
 * the same for any number of them: each face's prim at its own index, slivers marked; then the tree
 * faces moved down over the gaps (an entry only ever moves to a lower index), and the slivers written
 * after them. */
static size_t face_prims(struct builder *bd, uint32_t *faces, const struct mesh *m, double pad, size_t *slivers) {
    ptrdiff_t n = (ptrdiff_t)m->face_count;
#pragma omp parallel for if (bd->parallel) schedule(static) default(none) shared(bd, faces, m, pad, n)
    for (ptrdiff_t f = 0; f < n; f++) {
        struct float_box box;
        if (!face_float_box(m, (size_t)f, pad, &box))
            faces[f] = FAST_BVH_SLIVER_MARK;
        else if (bd->packed != NULL) {
            bd->packed[f] = packed_box_make(&box, &bd->grid);
            faces[f] = (uint32_t)f;
        } else {
            bd->prims[f] = box;
            faces[f] = (uint32_t)f;
        }
    }
    size_t tree = 0;
    for (size_t f = 0; f < (size_t)n; f++) {
        if (faces[f] == FAST_BVH_SLIVER_MARK)
            continue;
        if (bd->packed != NULL)
            bd->packed[tree] = bd->packed[f];
        else
            bd->prims[tree] = bd->prims[f];
        faces[tree++] = (uint32_t)f;
    }
    /* The faces missing from faces[0, tree), in order, are the slivers; they go to entries tree and up,
     * which the walk along the tree faces has already left behind. */
    size_t next_tree = 0;
    *slivers = 0;
    for (size_t f = 0; f < (size_t)n; f++) {
        if (next_tree < tree && faces[next_tree] == f)
            next_tree++;
        else
            faces[(size_t)n - ++*slivers] = (uint32_t)f;
    }
    return tree;
}

/* Rung 5's build of b (its triangle_count set) over the faces of m, by the SAH: fills b's faces,
 * root, nodes and info. With `packed` (rung 7), the build's boxes are kept in 16 bytes each where the
 * mesh is within float's range (struct packed_box). With `eight` (rung 8), the nodes are 8-wide
 * (nodes8): the same splits, each node opening its widest children until it has eight. The SAH prices
 * a leaf by its blocks of `block` triangles (leaf_tests). Returns false when memory runs out. */
static bool build_in_float(struct fast_bvh *b, const struct mesh *m, bool packed, bool eight, uint32_t block) {
    size_t n = m->face_count;
    size_t most_nodes = n > 1 ? n - 1 : 1; /* a tree of n leaves has at most n - 1 interior nodes */
    struct builder bd = {NULL, NULL, {{0}, {0}, {0}}, NULL, {NULL, NULL}, threads_to_share(), block, 0};
    struct corners corners = faces_corners(m, bd.parallel);
    double pad = n > 0 ? triangle_box_pad_between(corners.lo, corners.hi) : 0.0; /* triangle_box_pad(m) */
    if (packed) { /* the grid spans every face's box: the padding and the moving to float (face_bounds) are
                   * monotonic, so the least of the faces' low bounds is the low bound of the least corner */
        struct float_box around = face_bounds(aabb_pad((struct aabb){corners.lo, corners.hi}, pad));
        packed = corners.finite && n > 0 && packed_grid_make(&around, &bd.grid);
    }
    if (packed)
        bd.packed = big_alloc((n ? n : 1) * sizeof *bd.packed, true);
    else
        bd.prims = big_alloc((n ? n : 1) * sizeof *bd.prims, true);
    struct node_store store;
    bool stored = store_alloc(&store, eight, most_nodes, true);
    b->nodes = store.nodes;
    b->nodes8 = store.nodes8;
    b->faces = big_alloc((n ? n : 1) * sizeof *b->faces, true);
    if (!stored || b->faces == NULL || (bd.prims == NULL && bd.packed == NULL)) {
        free(bd.prims);
        free(bd.packed);
        return false;
    }
    size_t slivers = 0, tree = face_prims(&bd, b->faces, m, pad, &slivers);
    b->tree_count = tree;

    bd.faces = b->faces;
    bd.store = store;
    struct build_range root = {0, (uint32_t)tree, float_box_empty(), float_box_empty()}, halves[2];
    range_bounds(&bd, &root);
    b->root_box = float_box_widened(&root.box);
    struct tree_shape shape = {aabb_surface_area(b->root_box), 0, 0, 0, 0.0};
    bool root_splits = false;
#pragma omp parallel if (bd.parallel) default(none) shared(bd, b, root, halves, root_splits, tree)
#pragma omp single
    if (tree > 0 && (root_splits = split(&bd, &root, 0, &halves[0], &halves[1])))
        b->root_child = build_node(&bd, &halves[0], &halves[1], 0);
    /* The build's boxes are done with; their memory, room for n numbers and more, is touched already (no
     * page faults), so it holds order_nodes' numbering. */
    void *boxes = bd.packed != NULL ? (void *)bd.packed : (void *)bd.prims;
    if (root_splits && bd.parallel)
        order_nodes(store, bd.node_count, boxes);
    free(bd.prims);
    free(bd.packed);
    if (root_splits) {
        count_child(&shape, b->root_box, 0, 0);
        measure_node(store, b->root_child, 0, &shape);
    } else if (tree > 0) {
        count_child(&shape, b->root_box, (uint32_t)tree, 0); /* the whole tree is one leaf */
        b->root_count = (uint32_t)tree;
    }
    b->node_count = bd.node_count;
    b->info = (struct bvh_info){shape.node_count + shape.leaves, shape.leaves, shape.max_depth, 0.0,
                                shape.sah_cost + BVH_COST_TRIANGLE * slivers, slivers};
    return true;
}

/* The triangles are copied into leaf order in parts of this many, shared among the threads. */
#define FAST_BVH_COPY_PART 65536

/* Whether every bound of box is within FAST_BVH_FLOAT_RANGE of 0 (an empty box is not). */
static bool in_float_range(struct aabb box) {
    for (int a = 0; a < 3; a++)
        if (!(fabs(vec3_axis(box.min, a)) <= FAST_BVH_FLOAT_RANGE && fabs(vec3_axis(box.max, a)) <= FAST_BVH_FLOAT_RANGE))
            return false;
    return true;
}

/* Rung 7's leaves: the corners' numbers of b's triangles in leaf order (b->corners, from m's faces by
 * b->faces), in parts shared among the threads, and m kept for its vertices. Returns false when memory
 * runs out. */
static bool with_compact_leaves(struct fast_bvh *b, const struct mesh *m) {
    b->mesh = m;
    b->corners = big_alloc((b->triangle_count ? b->triangle_count : 1) * 3 * sizeof *b->corners, true);
    if (b->corners == NULL)
        return false;
#pragma omp parallel for schedule(static) default(none) shared(b, m)
    for (size_t start = 0; start < b->triangle_count; start += FAST_BVH_COPY_PART) {
        size_t end = b->triangle_count - start < FAST_BVH_COPY_PART ? b->triangle_count : start + FAST_BVH_COPY_PART;
        for (size_t k = start; k < end; k++)
            for (int c = 0; c < 3; c++)
                b->corners[3 * k + c] = m->faces[b->faces[k]].v[c];
    }
    return true;
}

/* Rung 11's hierarchy: rung 9's, then, where that tree is 8-wide (AVX2) and within rung 6's float range
 * (its corners fit a float), the float copy of its triangles (float_triangle_prepare) in place of rung
 * 9's blocks of doubles (freed: 36 bytes a triangle instead of 72); otherwise rung 9's as it is (walked
 * by rung 9's fallbacks). */
static struct fast_bvh *exact_float_tree(const struct mesh *m, enum bvh_split split) {
    struct fast_bvh *b = fast_bvh_build(m, split, FAST_BVH_RUNG_LEAN);
    if (b == NULL)
        return NULL;
    b->rung = FAST_BVH_RUNG_EXACT;
    if (b->nodes8 == NULL || !b->float_range) /* no 8-wide walk, or none in float: rung 9 as it is */
        return b;
    if (!float_triangle_prepare(b)) {
        fast_bvh_free(b);
        return NULL;
    }
    free(b->lean_corners); /* rung 9's double blocks: rung 11 reads its float ones instead */
    b->lean_corners = NULL;
    return b;
}

struct fast_bvh *fast_bvh_build(const struct mesh *m, enum bvh_split split, enum fast_bvh_rung rung) {
    if (rung == FAST_BVH_RUNG_EXACT && m->face_count <= BVH_MAX_FACES)
        return exact_float_tree(m, split);
    if (m->face_count > BVH_MAX_FACES || rung < FAST_BVH_RUNG_FIRST || rung > FAST_BVH_RUNG_TOP)
        return NULL;
    if (rung < FAST_BVH_RUNG_BUILD || split == BVH_SPLIT_MEDIAN) {
        struct bvh *binary = bvh_build(m, split);
        struct fast_bvh *b = binary != NULL ? fast_bvh_collapse(binary, rung) : NULL;
        bvh_free(binary);
        if (b != NULL)
            b->float_range = in_float_range(b->root_box);
        if (b != NULL && rung == FAST_BVH_RUNG_COMPACT) { /* the median tree's leaves made compact */
            free(b->triangles);
            b->triangles = NULL;
            if (!with_compact_leaves(b, m)) {
                fast_bvh_free(b);
                return NULL;
            }
        }
        return with_lean_leaves(b);
    }
    double start = clock_seconds();
    struct fast_bvh *b = calloc(1, sizeof *b);
    if (b == NULL)
        return NULL;
    b->rung = rung;
    b->triangle_count = m->face_count;
    bool eight = eight_wide(rung);
    uint32_t block = rung == FAST_BVH_RUNG_LEAN && eight ? FAST_BVH_LEAN_PRICED : 1;
    if (!build_in_float(b, m, rung == FAST_BVH_RUNG_COMPACT, eight, block)) {
        fast_bvh_free(b);
        return NULL;
    }
    /* Rung 7's leaves read the triangles from m itself. Below it, the triangles in leaf order, as the
     * intersection test wants them; allocated only now that the build's boxes are freed, so that the
     * peak memory holds one or the other. */
    b->float_range = in_float_range(b->root_box);
    if (rung == FAST_BVH_RUNG_COMPACT) {
        if (!with_compact_leaves(b, m)) {
            fast_bvh_free(b);
            return NULL;
        }
        b->info.build_ms = 1e3 * (clock_seconds() - start);
        return b;
    }
    b->triangles = big_alloc((b->triangle_count ? b->triangle_count : 1) * sizeof *b->triangles, true);
    if (b->triangles == NULL) {
        fast_bvh_free(b);
        return NULL;
    }
    /* In parts, one per task at most. */
#pragma omp parallel for schedule(static) default(none) shared(b, m)
    for (size_t start = 0; start < b->triangle_count; start += FAST_BVH_COPY_PART) {
        size_t count = b->triangle_count - start < FAST_BVH_COPY_PART ? b->triangle_count - start : FAST_BVH_COPY_PART;
        bvh_copy_triangles(m, b->faces + start, count, b->triangles + start);
    }
    b = with_lean_leaves(b);
    if (b != NULL)
        b->info.build_ms = 1e3 * (clock_seconds() - start);
    return b;
}

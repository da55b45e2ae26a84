/* fast_bvh.c: chapter 10's bounding volume hierarchy made fast, rung by rung (chapter 11).
 *
 * Chapter 10's bvh.c is the algorithm; this file is the same algorithm laid out and walked for speed,
 * and the rungs of enum fast_bvh_rung switch its optimisations on one at a time, so each can be
 * measured against the one below (make bench; docs/11-fast.md):
 *  - FAST_BVH_RUNG_WIDE: the binary tree collapsed into a 4-wide one (see "Layout" below), float boxes
 *    rounded outward, each child's slab test on its own (child_hit).
 *  - FAST_BVH_RUNG_SIMD: two children's slab tests per instruction (child_pair_hit).
 *  - FAST_BVH_RUNG_PREFETCH: every child put aside on the stack is fetched while the ray goes on
 *    (prefetch_child).
 *  - FAST_BVH_RUNG_BUILD: the build bins into four sets of slots at once (BVH_BIN_SETS) and backs its
 *    big arrays with 2 MB pages (alloc_big).
 * The traversal is one function specialised at compile time for each query and rung.
 *
 * The build sorts triangles into a binary tree of axis-aligned boxes. BVH_SPLIT_MEDIAN is the
 * dissertation's rule (halve the triangles by centroid along the longest axis). BVH_SPLIT_SAH is the
 * binned surface area heuristic of Wald, "On fast construction of SAH-based bounding volume
 * hierarchies" (IEEE RT 2007): the centroids are dropped into BVH_BINS slots per axis, and of the
 * BVH_BINS - 1 planes between slots the one minimising
 *     BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * (area(L) * count(L) + area(R) * count(R)) / area(node)
 * is taken, unless a leaf (BVH_COST_TRIANGLE * count) is cheaper. The ratio of a child's area to its
 * parent's is the chance that a random ray through the parent also crosses the child (MacDonald and
 * Booth 1990), so the sum is the expected cost of a ray that reaches the node.
 *
 * Tuning constants (values below): BVH_BINS 16, BVH_BIN_SETS 4 from BVH_MANY_SETS_FROM 256 triangles,
 * BVH_MAX_LEAF_SIZE 8, BVH_MEDIAN_LEAF_SIZE 2, BVH_COST_TRAVERSAL 1.0, BVH_COST_TRIANGLE 1.0,
 * BVH_MAX_DEPTH 64, BVH_WIDTH 4, BVH_BOX_PAD 2^-20, BVH_SLIVER_SINE 1e-6. (The bench models' frame times moved by less than the noise for traversal costs
 * 0.5 to 2, leaf limits 4 and 8, and 16 or 32 bins: the tree is not what limits the speed.)
 *
 * Exact agreement with the brute-force loop. A query must return the very face and t that testing
 * every face with triangle_intersect would. Four things make sure of it:
 *  - Triangles are tested with triangle_crossing_prepared (triangle.h), the very arithmetic
 *    triangle_intersect uses (the ray made ready once per query, in struct ray_setup), on the very
 *    corners the mesh holds, so t is the same double to the last bit.
 *  - A box may only be skipped when no triangle inside can be reported hit. The triangle test rounds:
 *    it may call a ray that passes a hair outside a triangle a hit. So every triangle's box is grown by
 *    BVH_BOX_PAD times the mesh's size before it is rounded outward to float, far more than any such
 *    rounding error (about 1e-16 of the distance from the ray's origin) and far too little to cost
 *    anything measurable. The slab test itself runs in double on these float bounds.
 *  - Needle-thin triangles (BVH_SLIVER_SINE), whose rounding errors no pad covers, are kept out of the
 *    tree and tested by every ray.
 *  - Ties: a box is skipped only when it starts strictly after the best hit so far, and a triangle at
 *    the same t as the best replaces it only with a lower face index.
 * What is left: a ray starting more than about a thousand mesh sizes away, or one meeting a triangle's
 * plane at a grazing angle below about 1e-8 radians, has rounding errors the pad may not cover. Neither
 * occurs in tests/test_accel.c's hundreds of thousands of chosen rays nor, as far as we know, in a scene.
 *
 * Layout, chosen for speed. Both rules build a binary tree, which is then collapsed into a 4-wide one
 * (each node takes its widest interior child's children until it has BVH_WIDTH, as in Embree's BVH4):
 * half the depth, so half the chain of dependent "load a node, test it, choose" steps that bounds the
 * speed of one ray. A node stores the boxes of its four children side by side (128 bytes, two cache
 * lines), and a ray visiting it tests all four at once with 2-wide vector arithmetic, and sorts the
 * ones it hits by entry distance (nearest_first), without touching the children themselves. A child is
 * another node or a leaf: a run of triangles, stored in leaf order as (a, b - a, c - a) in doubles with
 * their face numbers beside them. Unused child slots have an empty box (low +infinity, high -infinity), which
 * every slab test misses. The root's box is kept in struct fast_bvh. */
#include "fast_bvh.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "stats.h"
#include "triangle.h"

/* Centroid slots per axis for the SAH build. Wald (2007) found 16 within a few percent of testing
 * every plane; more bins build slower and help little. A node of fewer triangles gets one slot per
 * triangle: most nodes are small, and clearing and sweeping 16 mostly empty slots for each of them took
 * an eighth of the build time on the 350k-triangle teapot, for the same tree (same SAH cost). */
#define BVH_BINS 16

/* Nodes of at least BVH_MANY_SETS_FROM triangles are binned into BVH_BIN_SETS sets of slots, prim i
 * into set i % BVH_BIN_SETS, and the sets are added up afterwards. Neighbouring prims usually fall into
 * the same slot, and with one set each update of a slot waits for the previous one to be stored; with
 * four, four updates are under way at once. It took a fifth off the build of the 350k-triangle teapot.
 * Small nodes use one set: there, clearing the extra slots costs more than it saves. */
#define BVH_BIN_SETS 4
#define BVH_MANY_SETS_FROM 256

/* An SAH node with more triangles than this is always split, even when the heuristic would rather
 * not: a long leaf is costly for every ray that reaches it, which the heuristic's averages hide. */
#define BVH_MAX_LEAF_SIZE 8

/* The dissertation's median build stops at one or two triangles per node. */
#define BVH_MEDIAN_LEAF_SIZE 2

/* Relative costs of visiting a node (testing both children's boxes) and of one triangle test, as the
 * heuristic sees them. Measured on this code they are about equal (each is some twenty floating point
 * operations and a few branches); bench_accel prints the predicted cost next to the measured. */
#define BVH_COST_TRAVERSAL 1.0
#define BVH_COST_TRIANGLE 1.0

/* Below this depth the SAH chooses freely; deeper nodes are halved by count, so the depth stays
 * bounded (at most BVH_MAX_DEPTH + 31 levels for 2^31 triangles), and with it the traversal stack,
 * which holds at most BVH_WIDTH - 1 entries per level. */
#define BVH_MAX_DEPTH 64
#define BVH_STACK_SIZE ((BVH_WIDTH - 1) * (BVH_MAX_DEPTH + 32))

/* Children per node after collapsing the binary tree (see the file comment). */
#define BVH_WIDTH 4

/* An unused child slot. */
#define BVH_NO_CHILD UINT32_MAX

/* Every triangle's box is grown by this fraction of the mesh's largest extent (see the file comment):
 * 2^-20, about 1e-6, is ten orders of magnitude above the triangle test's rounding for rays starting
 * within a thousand mesh sizes, and invisible in the statistics. */
#define BVH_BOX_PAD (1.0 / 1048576.0)

/* Needle-thin triangles are chapter 10's: bvh_is_sliver (bvh.h) decides, by bvh.c's BVH_SLIVER_SINE. */

/* Faces are numbered with uint32_t. */
#define BVH_MAX_FACES ((size_t)1 << 31)

struct fast_bvh_node {
    float bounds[3][2][BVH_WIDTH]; /* [axis][0 = low, 1 = high][child]: the children's boxes, side by side */
    uint32_t child[BVH_WIDTH];     /* a child node's index, a leaf's first triangle, or BVH_NO_CHILD */
    uint32_t count[BVH_WIDTH];     /* 0 when the child is a node (or no child); else the leaf's triangles */
};

_Static_assert(sizeof(struct fast_bvh_node) == 128, "a node should fill exactly two 64-byte cache lines");

/* A triangle as the intersection test wants it: its three corners, copied from the mesh. */
struct fast_bvh_triangle {
    vec3 a, b, c;
};

struct fast_bvh {
    enum fast_bvh_rung rung;
    struct fast_bvh_node *nodes;          /* node_count entries, 64-byte aligned */
    size_t node_count;
    float root_lo[3], root_hi[3];    /* the root's box */
    uint32_t root_child, root_count; /* the root, as a child is referred to in a node */
    struct fast_bvh_triangle *triangles;  /* triangle_count entries: tree_count in leaf order, then the slivers */
    uint32_t *faces;                 /* faces[k] = index into the mesh's faces of triangles[k] */
    size_t triangle_count;
    size_t tree_count;               /* triangles in the tree; the rest are slivers, tested by every ray */
    struct bvh_info info;
};

/* ==== vectors ================================================================================= */

/* GCC's vector extension: a few numbers processed by one instruction (SSE on x86-64). The build works
 * on float4 boxes (lanes x, y, z and an unused 0); the traversal on double2 pairs of children. */
typedef float float4 __attribute__((vector_size(16)));
typedef int32_t int4 __attribute__((vector_size(16)));
typedef double double2 __attribute__((vector_size(16)));
typedef int64_t long2 __attribute__((vector_size(16)));

/* Lane by lane, a < b ? a : b and a > b ? a : b (a NaN in a gives b). SSE has each as one instruction;
 * elsewhere a compare and a select. */
static inline float4 min4(float4 a, float4 b) {
#if defined(__SSE__)
    return _mm_min_ps(a, b);
#else
    int4 pick_a = a < b;
    return (float4)(((int4)a & pick_a) | ((int4)b & ~pick_a));
#endif
}

static inline float4 max4(float4 a, float4 b) {
#if defined(__SSE__)
    return _mm_max_ps(a, b);
#else
    int4 pick_a = a > b;
    return (float4)(((int4)a & pick_a) | ((int4)b & ~pick_a));
#endif
}

/* ==== memory ================================================================================== */

/* Arrays of 2 MB or more are aligned to 2 MB and the kernel is asked to back them with 2 MB pages
 * (Linux's madvise MADV_HUGEPAGE; elsewhere, or if refused, nothing changes): one page fault per 2 MB
 * instead of one per 4 KB. On the virtual machine this was measured on, first-touch page faults cost
 * 70 ms per 25 MB, most of the build time, and fewer TLB misses speed up the traversal too. The result
 * is 64-byte aligned in any case. NULL when memory runs out; release with free(). */
#define BVH_HUGE_PAGE ((size_t)1 << 21)

static void *alloc_big(size_t bytes, bool huge_pages) {
    if (bytes < BVH_HUGE_PAGE || !huge_pages)
        return aligned_alloc(64, (bytes + 63) / 64 * 64 + 64);
    size_t rounded = (bytes + BVH_HUGE_PAGE - 1) / BVH_HUGE_PAGE * BVH_HUGE_PAGE;
    void *p = aligned_alloc(BVH_HUGE_PAGE, rounded);
#if defined(MADV_HUGEPAGE)
    if (p != NULL)
        madvise(p, rounded, MADV_HUGEPAGE); /* only a hint: failure changes nothing */
#endif
    return p;
}

/* ==== building ================================================================================ */

/* A box in float, bounds rounded outward; lane 3 of both corners is 0. */
struct fbox {
    float4 lo, hi;
};

/* A run of prims (see struct builder), with the box of their boxes and the box of their centroids. */
struct build_range {
    uint32_t begin, end;
    struct fbox box, centroids;
};

/* A node of the binary tree the splits make, before it is collapsed: children as in struct fast_bvh_node. */
struct binary_node {
    struct fbox box[2];
    uint32_t child[2], count[2];
};

struct builder {
    struct fbox *prims;         /* one padded box per triangle; the splits reorder them into leaf order */
    uint32_t *faces;            /* the face number of each prim, reordered along with them */
    enum bvh_split split;
    struct binary_node *binary; /* the binary tree */
    size_t binary_count;
    struct fast_bvh_node *nodes;     /* the 4-wide tree */
    int bin_sets;               /* how many sets of SAH slots big nodes are binned into: 1 or BVH_BIN_SETS */
    size_t node_count;
    double root_area;
    size_t leaves, max_depth;
    double sah_cost;
};

static inline struct fbox fbox_empty(void) {
    return (struct fbox){{INFINITY, INFINITY, INFINITY, 0.0f}, {-INFINITY, -INFINITY, -INFINITY, 0.0f}};
}

static inline void fbox_grow(struct fbox *b, float4 lo, float4 hi) {
    b->lo = min4(b->lo, lo);
    b->hi = max4(b->hi, hi);
}

/* Half the surface area of the box [lo, hi] (not empty), in float: what the SAH sweeps compare. */
static inline float half_area(float4 lo, float4 hi) {
    float4 e = hi - lo;                                      /* lane 3 is 0 - 0 = 0 */
    float4 p = e * __builtin_shuffle(e, (int4){1, 2, 0, 3}); /* x*y, y*z, z*x, 0 */
    return p[0] + p[1] + p[2];
}

/* Surface area; 0 for an empty box. In double, for the reported cost. */
static inline double fbox_area(const struct fbox *b) {
    double ex = (double)b->hi[0] - b->lo[0], ey = (double)b->hi[1] - b->lo[1], ez = (double)b->hi[2] - b->lo[2];
    if (!(ex >= 0.0 && ey >= 0.0 && ez >= 0.0))
        return 0.0;
    return 2.0 * (ex * ey + ey * ez + ez * ex);
}

/* The largest float <= x and the smallest float >= x: a float box built from these holds the double
 * box exactly. A NaN (from a corner at infinity) gives the infinity on the safe side, so that no NaN
 * reaches a box: min4 and max4 would let it in or out depending on the order of the prims. */
static float float_below(double x) {
    if (isnan(x))
        return -INFINITY; /* a corner beyond double's range: a box open on that side holds it */
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float float_above(double x) {
    if (isnan(x))
        return INFINITY;
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* Twice the centre of a prim's box: the point the splits sort by. */
static inline float4 centroid_of(const struct fbox *p) { return p->lo + p->hi; }

static inline void swap_prims(struct builder *bd, uint32_t i, uint32_t j) {
    struct fbox box = bd->prims[i];
    bd->prims[i] = bd->prims[j];
    bd->prims[j] = box;
    uint32_t face = bd->faces[i];
    bd->faces[i] = bd->faces[j];
    bd->faces[j] = face;
}

/* Fills r->box and r->centroids from its prims. */
static void range_bounds(const struct builder *bd, struct build_range *r) {
    r->box = fbox_empty();
    r->centroids = fbox_empty();
    for (uint32_t k = r->begin; k < r->end; k++) {
        fbox_grow(&r->box, bd->prims[k].lo, bd->prims[k].hi);
        float4 c = centroid_of(&bd->prims[k]);
        fbox_grow(&r->centroids, c, c);
    }
}

/* Reorders prims [begin, end) so that prim nth has the centroid it would have if sorted along axis,
 * with no larger centroid before it and no smaller after (quickselect, Hoare's FIND, with a
 * three-way partition so that many equal centroids cost nothing extra). */
static void select_nth(struct builder *bd, uint32_t begin, uint32_t end, uint32_t nth, int axis) {
    const struct fbox *p = bd->prims;
    while (end - begin > 1) {
        float a = centroid_of(&p[begin])[axis];
        float b = centroid_of(&p[begin + (end - begin) / 2])[axis];
        float c = centroid_of(&p[end - 1])[axis];
        float pivot = a < b ? (b < c ? b : (a < c ? c : a)) : (a < c ? a : (b < c ? c : b)); /* median */
        uint32_t less = begin, i = begin, greater = end; /* [begin,less) < pivot, [greater,end) > pivot */
        while (i < greater) {
            float key = centroid_of(&p[i])[axis];
            if (key < pivot)
                swap_prims(bd, less++, i++);
            else if (key > pivot)
                swap_prims(bd, i, --greater);
            else
                i++;
        }
        if (nth < less)
            end = less;
        else if (nth >= greater)
            begin = greater;
        else
            return;
    }
}

/* Halves r by count along the longest axis of its centroids' box (the dissertation's split; also the
 * fallback when the SAH finds no plane). */
static void split_median(struct builder *bd, const struct build_range *r, struct build_range *left,
                         struct build_range *right) {
    float4 extent = r->centroids.hi - r->centroids.lo;
    int axis = extent[1] > extent[0] ? 1 : 0;
    axis = extent[2] > extent[axis] ? 2 : axis;
    uint32_t mid = r->begin + (r->end - r->begin) / 2;
    select_nth(bd, r->begin, r->end, mid, axis);
    left->begin = r->begin;
    left->end = mid;
    right->begin = mid;
    right->end = r->end;
    range_bounds(bd, left);
    range_bounds(bd, right);
}

struct bin {
    struct fbox box;
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

/* Looks for the cheapest SAH split of r. Returns false, leaving the prims alone, when a leaf is
 * cheaper or no plane separates the centroids; otherwise partitions r into *left and *right. */
static bool split_sah(struct builder *bd, const struct build_range *r, struct build_range *left,
                      struct build_range *right) {
    struct bin bins[BVH_BIN_SETS][3][BVH_BINS]; /* [set][axis][slot]; the sets are summed into set 0 */
    uint32_t n = r->end - r->begin;
    int slots = n < BVH_BINS ? (int)n : BVH_BINS; /* slots used per axis */
    int sets = n >= BVH_MANY_SETS_FROM ? bd->bin_sets : 1;
    float4 extent = r->centroids.hi - r->centroids.lo, scale = {0, 0, 0, 0};
    for (int a = 0; a < 3; a++)
        scale[a] = extent[a] > 0.0f ? (float)slots / extent[a] : 0.0f; /* 0: one slot takes all */
    for (int set = 0; set < sets; set++)
        for (int a = 0; a < 3; a++)
            for (int k = 0; k < slots; k++)
                bins[set][a][k] = (struct bin){fbox_empty(), 0};
    for (uint32_t i = r->begin; i < r->end; i++) {
        const struct fbox *p = &bd->prims[i];
        int4 k = bins_of(centroid_of(p), r->centroids.lo, scale, slots);
        struct bin (*set)[BVH_BINS] = bins[sets == 1 ? 0 : i % BVH_BIN_SETS]; /* a constant %: a mask */
        for (int a = 0; a < 3; a++) {
            struct bin *slot = &set[a][k[a]];
            slot->count++;
            fbox_grow(&slot->box, p->lo, p->hi);
        }
    }
    for (int set = 1; set < sets; set++)
        for (int a = 0; a < 3; a++)
            for (int k = 0; k < slots; k++) {
                bins[0][a][k].count += bins[set][a][k].count;
                fbox_grow(&bins[0][a][k].box, bins[set][a][k].box.lo, bins[set][a][k].box.hi);
            }

    /* For each axis, sweep from the right to get the area and count right of every plane, then from the
     * left to price each plane. Cost: the sum of area * count over both sides. */
    float best_cost = INFINITY;
    int best_axis = -1, best_plane = 0;
    for (int a = 0; a < 3; a++) {
        if (scale[a] == 0.0f)
            continue; /* all centroids in one plane: this axis cannot separate them */
        /* right_cost[k]: half area times count of everything right of the plane between slots k - 1
         * and k (infinite while nothing is: such a plane is never chosen). Empty slots change nothing,
         * so they are skipped; small nodes leave most slots empty. */
        float right_cost[BVH_BINS];
        struct fbox acc = fbox_empty();
        uint32_t count = 0;
        float cost = INFINITY;
        for (int k = slots - 1; k > 0; k--) {
            if (bins[0][a][k].count > 0) {
                fbox_grow(&acc, bins[0][a][k].box.lo, bins[0][a][k].box.hi);
                count += bins[0][a][k].count;
                cost = half_area(acc.lo, acc.hi) * (float)count;
            }
            right_cost[k] = cost;
        }
        acc = fbox_empty();
        count = 0;
        for (int k = 1; k < slots; k++) {
            if (bins[0][a][k - 1].count == 0)
                continue; /* the same split as the plane before */
            fbox_grow(&acc, bins[0][a][k - 1].box.lo, bins[0][a][k - 1].box.hi);
            count += bins[0][a][k - 1].count;
            cost = half_area(acc.lo, acc.hi) * (float)count + right_cost[k];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = a;
                best_plane = k;
            }
        }
    }
    if (best_axis < 0)
        return false;

    uint32_t count = r->end - r->begin;
    double area = fbox_area(&r->box);
    double split_cost = area > 0.0 ? BVH_COST_TRAVERSAL + BVH_COST_TRIANGLE * 2.0 * best_cost / area : INFINITY;
    if (count <= BVH_MAX_LEAF_SIZE && BVH_COST_TRIANGLE * count <= split_cost)
        return false;

    /* Partition, gathering each side's centroid box on the way; the boxes are the unions of the slots'. */
    *left = (struct build_range){r->begin, r->begin, fbox_empty(), fbox_empty()};
    *right = (struct build_range){r->end, r->end, fbox_empty(), fbox_empty()};
    uint32_t i = r->begin, j = r->end; /* [begin,i) go left, [j,end) go right */
    while (i < j) {
        float4 c = centroid_of(&bd->prims[i]);
        if (bins_of(c, r->centroids.lo, scale, slots)[best_axis] < best_plane) {
            fbox_grow(&left->centroids, c, c);
            i++;
        } else {
            fbox_grow(&right->centroids, c, c);
            swap_prims(bd, i, --j);
        }
    }
    left->end = i;
    right->begin = i;
    for (int k = 0; k < slots; k++) {
        struct build_range *side = k < best_plane ? left : right;
        fbox_grow(&side->box, bins[0][best_axis][k].box.lo, bins[0][best_axis][k].box.hi);
    }
    return true;
}

/* Builds the subtree over r and stores how its parent refers to it in *child and *count (see struct
 * fast_bvh_node): here a binary tree, collapsed later. */
static void build_subtree(struct builder *bd, const struct build_range *r, size_t depth, uint32_t *child,
                          uint32_t *count) {
    uint32_t n = r->end - r->begin;
    struct build_range left, right;
    bool split = false;
    if (bd->split == BVH_SPLIT_MEDIAN) {
        if (n > BVH_MEDIAN_LEAF_SIZE) {
            split_median(bd, r, &left, &right);
            split = true;
        }
    } else if (n > 1) {
        if (depth < BVH_MAX_DEPTH)
            split = split_sah(bd, r, &left, &right);
        /* Too deep for the heuristic, or every centroid at one point: still too many for a leaf, so
         * halve by count. */
        if (!split && n > BVH_MAX_LEAF_SIZE) {
            split_median(bd, r, &left, &right);
            split = true;
        }
    }
    if (!split) {
        *child = r->begin;
        *count = n;
        return;
    }
    uint32_t index = (uint32_t)bd->binary_count++;
    struct binary_node *node = &bd->binary[index];
    node->box[0] = left.box;
    node->box[1] = right.box;
    build_subtree(bd, &left, depth + 1, &node->child[0], &node->count[0]);
    build_subtree(bd, &right, depth + 1, &node->child[1], &node->count[1]);
    *child = index;
    *count = 0;
}

/* A child slot while collapsing. */
struct slot {
    struct fbox box;
    uint32_t child, count;
};

/* Makes a 4-wide node out of binary node `index` (whose box is *box) and its descendants, and returns
 * its index. The node starts with the binary node's two children and, while it has room, replaces the
 * interior child with the largest surface (the one most rays enter) by that child's two children.
 * Also counts the tree's shape and SAH cost. */
static uint32_t collapse(struct builder *bd, uint32_t index, const struct fbox *box, size_t depth) {
    const struct binary_node *top = &bd->binary[index];
    struct slot slots[BVH_WIDTH];
    int used = 2;
    for (int k = 0; k < 2; k++)
        slots[k] = (struct slot){top->box[k], top->child[k], top->count[k]};
    while (used < BVH_WIDTH) {
        int widest = -1;
        double widest_area = -1.0;
        for (int k = 0; k < used; k++)
            if (slots[k].count == 0 && fbox_area(&slots[k].box) > widest_area) {
                widest = k;
                widest_area = fbox_area(&slots[k].box);
            }
        if (widest < 0)
            break; /* every child is a leaf */
        const struct binary_node *open = &bd->binary[slots[widest].child];
        slots[widest] = (struct slot){open->box[0], open->child[0], open->count[0]};
        slots[used++] = (struct slot){open->box[1], open->child[1], open->count[1]};
    }

    uint32_t out = (uint32_t)bd->node_count++;
    bd->sah_cost += BVH_COST_TRAVERSAL * (bd->root_area > 0.0 ? fbox_area(box) / bd->root_area : 1.0);
    for (int k = 0; k < BVH_WIDTH; k++) {
        struct slot s = k < used ? slots[k] : (struct slot){fbox_empty(), BVH_NO_CHILD, 0};
        struct fast_bvh_node *node = &bd->nodes[out];
        for (int a = 0; a < 3; a++) {
            node->bounds[a][0][k] = s.box.lo[a];
            node->bounds[a][1][k] = s.box.hi[a];
        }
        node->count[k] = s.count;
        if (k >= used || s.count > 0) {
            node->child[k] = s.child;
            if (s.count > 0) {
                bd->leaves++;
                bd->sah_cost += BVH_COST_TRIANGLE * s.count *
                                (bd->root_area > 0.0 ? fbox_area(&s.box) / bd->root_area : 1.0);
                bd->max_depth = depth + 1 > bd->max_depth ? depth + 1 : bd->max_depth;
            }
        } else {
            uint32_t below = collapse(bd, s.child, &s.box, depth + 1);
            bd->nodes[out].child[k] = below;
        }
    }
    return out;
}

struct fast_bvh *fast_bvh_build(const struct mesh *m, enum bvh_split split, enum fast_bvh_rung rung) {
    double start = bvh_now_ms();
    size_t n = m->face_count;
    if (n > BVH_MAX_FACES || rung < FAST_BVH_RUNG_FIRST || rung > FAST_BVH_RUNG_TOP)
        return NULL;
    struct fast_bvh *b = calloc(1, sizeof *b);
    if (b == NULL)
        return NULL;
    b->rung = rung;
    bool huge = rung >= FAST_BVH_RUNG_BUILD;
    b->triangle_count = n;
    /* A tree whose leaves hold at least one triangle each has at most n - 1 interior nodes. */
    size_t most_nodes = n > 1 ? n - 1 : 1;
    struct fbox *prims = alloc_big((n ? n : 1) * sizeof *prims, huge);
    struct binary_node *binary = alloc_big(most_nodes * sizeof *binary, huge);
    b->nodes = alloc_big(most_nodes * sizeof *b->nodes, huge);
    b->faces = alloc_big((n ? n : 1) * sizeof *b->faces, huge);
    if (b->nodes == NULL || b->faces == NULL || prims == NULL || binary == NULL) {
        free(prims);
        free(binary);
        fast_bvh_free(b);
        return NULL;
    }

    /* The pad: BVH_BOX_PAD times the largest extent of the vertices the faces use. */
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t f = 0; f < n; f++)
        for (int c = 0; c < 3; c++) {
            lo = vec3_min(lo, m->vertices[m->faces[f].v[c]]);
            hi = vec3_max(hi, m->vertices[m->faces[f].v[c]]);
        }
    vec3 extent = vec3_sub(hi, lo);
    double pad = n > 0 ? BVH_BOX_PAD * fmax(extent.x, fmax(extent.y, extent.z)) : 0.0;
    /* Tree faces first (their prims), slivers at the end of faces[]. */
    size_t tree = 0, slivers = 0;
    for (size_t f = 0; f < n; f++) {
        if (bvh_is_sliver(m, f)) {
            b->faces[n - ++slivers] = (uint32_t)f;
            continue;
        }
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], bb = m->vertices[v[1]], c = m->vertices[v[2]];
        vec3 tlo = vec3_min(a, vec3_min(bb, c)), thi = vec3_max(a, vec3_max(bb, c));
        prims[tree] = (struct fbox){{float_below(tlo.x - pad), float_below(tlo.y - pad), float_below(tlo.z - pad), 0.0f},
                                    {float_above(thi.x + pad), float_above(thi.y + pad), float_above(thi.z + pad), 0.0f}};
        b->faces[tree++] = (uint32_t)f;
    }
    b->tree_count = tree;

    struct builder bd = {prims, b->faces, split, binary, 0, b->nodes, huge ? BVH_BIN_SETS : 1, 0, 0.0, 0, 0, 0.0};
    struct build_range root = {0, (uint32_t)tree, fbox_empty(), fbox_empty()};
    range_bounds(&bd, &root);
    if (tree == 0)
        root.box = (struct fbox){{0, 0, 0, 0}, {0, 0, 0, 0}};
    for (int axis = 0; axis < 3; axis++) {
        b->root_lo[axis] = root.box.lo[axis];
        b->root_hi[axis] = root.box.hi[axis];
    }
    bd.root_area = fbox_area(&root.box);
    if (tree > 0)
        build_subtree(&bd, &root, 0, &b->root_child, &b->root_count);
    if (tree > 0 && b->root_count == 0) {
        b->root_child = collapse(&bd, b->root_child, &root.box, 0);
    } else if (tree > 0) {
        bd.leaves = 1; /* the whole tree is one leaf */
        bd.sah_cost = BVH_COST_TRIANGLE * tree;
    }
    free(binary);
    free(prims);
    b->node_count = bd.node_count;
    assert((BVH_WIDTH - 1) * bd.max_depth < BVH_STACK_SIZE);

    /* The triangles in leaf order, as the intersection test wants them; allocated only now that the
     * build's boxes and binary tree are freed, so that the peak memory holds one or the other. */
    b->triangles = alloc_big((n ? n : 1) * sizeof *b->triangles, huge);
    if (b->triangles == NULL) {
        fast_bvh_free(b);
        return NULL;
    }
    for (size_t k = 0; k < n; k++) {
        const uint32_t *v = m->faces[b->faces[k]].v;
        vec3 a = m->vertices[v[0]];
        b->triangles[k] = (struct fast_bvh_triangle){a, m->vertices[v[1]], m->vertices[v[2]]};
    }

    b->info.nodes = bd.node_count + bd.leaves;
    b->info.leaves = bd.leaves;
    b->info.max_depth = bd.max_depth;
    b->info.sah_cost = bd.sah_cost + BVH_COST_TRIANGLE * slivers;
    b->info.slivers = slivers;
    b->info.build_ms = bvh_now_ms() - start;
    return b;
}

void fast_bvh_free(struct fast_bvh *b) {
    if (b == NULL)
        return;
    free(b->nodes);
    free(b->triangles);
    free(b->faces);
    free(b);
}

void fast_bvh_get_info(const struct fast_bvh *b, struct bvh_info *info) { *info = b->info; }

/* ==== checking ================================================================================ */

struct check {
    const struct fast_bvh *b;
    const struct mesh *m;
    unsigned char *seen_triangle, *seen_node;
    char *why;
    size_t why_size;
};

static bool check_fail(struct check *c, const char *message, size_t where) {
    snprintf(c->why, c->why_size, "%s (at %zu)", message, where);
    return false;
}

/* Checks the subtree referred to by (child, count) whose box is [lo, hi]. */
static bool check_subtree(struct check *c, uint32_t child, uint32_t count, const float lo[3], const float hi[3],
                          size_t depth) {
    if (depth >= BVH_STACK_SIZE)
        return check_fail(c, "deeper than the traversal stack", depth);
    if (count > 0) {
        if ((size_t)child + count > c->b->tree_count)
            return check_fail(c, "leaf runs past the triangles", child);
        for (uint32_t k = child; k < child + count; k++) {
            if (c->seen_triangle[k]++)
                return check_fail(c, "triangle in two leaves", k);
            const uint32_t *v = c->m->faces[c->b->faces[k]].v;
            for (int corner = 0; corner < 3; corner++) {
                vec3 p = c->m->vertices[v[corner]];
                for (int a = 0; a < 3; a++)
                    if (vec3_axis(p, a) < lo[a] || vec3_axis(p, a) > hi[a]) /* a NaN corner is never hit */
                        return check_fail(c, "leaf box does not hold its triangle", k);
            }
        }
        return true;
    }
    if (child >= c->b->node_count || c->seen_node[child]++)
        return check_fail(c, "node index out of range or reached twice", child);
    const struct fast_bvh_node *n = &c->b->nodes[child];
    if (n->child[0] == BVH_NO_CHILD || n->child[1] == BVH_NO_CHILD)
        return check_fail(c, "node with fewer than two children", child);
    for (int k = 0; k < BVH_WIDTH; k++) {
        if (n->child[k] == BVH_NO_CHILD) {
            for (int a = 0; a < 3; a++)
                if (!(n->bounds[a][0][k] == INFINITY && n->bounds[a][1][k] == -INFINITY && n->count[k] == 0))
                    return check_fail(c, "unused child slot without the empty box", child);
            continue;
        }
        float child_lo[3], child_hi[3];
        for (int a = 0; a < 3; a++) {
            child_lo[a] = n->bounds[a][0][k];
            child_hi[a] = n->bounds[a][1][k];
            if (child_lo[a] < lo[a] || child_hi[a] > hi[a]) /* NaN bounds (corners beyond range) hold anything */
                return check_fail(c, "child box sticks out of its parent's", child);
        }
        if (!check_subtree(c, n->child[k], n->count[k], child_lo, child_hi, depth + 1))
            return false;
    }
    return true;
}

bool fast_bvh_is_valid(const struct fast_bvh *b, const struct mesh *m, char *why, size_t why_size) {
    struct check c = {b, m, calloc(b->triangle_count + 1, 1), calloc(b->node_count + 1, 1), why, why_size};
    bool ok = c.seen_triangle != NULL && c.seen_node != NULL;
    if (!ok)
        snprintf(why, why_size, "out of memory");
    if (ok && b->triangle_count != m->face_count)
        ok = check_fail(&c, "triangle count differs from the mesh's face count", b->triangle_count);
    for (size_t k = 0; ok && k < b->triangle_count; k++) {
        uint32_t f = b->faces[k];
        if (f >= m->face_count) {
            ok = check_fail(&c, "face number out of range", k);
            break;
        }
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], b1 = m->vertices[v[1]], c2 = m->vertices[v[2]];
        const struct fast_bvh_triangle *t = &b->triangles[k];
        if (memcmp(&t->a, &a, sizeof a) != 0 || memcmp(&t->b, &b1, sizeof b1) != 0 ||
            memcmp(&t->c, &c2, sizeof c2) != 0)
            ok = check_fail(&c, "stored triangle differs from its face", k);
    }
    if (ok && b->tree_count > 0)
        ok = check_subtree(&c, b->root_child, b->root_count, b->root_lo, b->root_hi, 0);
    if (ok)
        ok = bvh_check_faces(m, b->faces, b->triangle_count, b->tree_count, c.seen_triangle, why, why_size);
    free(c.seen_triangle);
    free(c.seen_node);
    return ok;
}

/* ==== traversal =============================================================================== */

/* Lane by lane, a > b ? a : b and a < b ? a : b. A NaN in a compares false and gives b: that is how
 * the slab test ignores 0 * infinity (see box_hit). SSE2 has these as single instructions. */
static inline double2 max2(double2 a, double2 b) {
#if defined(__SSE2__)
    return _mm_max_pd(a, b);
#else
    long2 pick_a = a > b;
    return (double2)(((long2)a & pick_a) | ((long2)b & ~pick_a));
#endif
}

static inline double2 min2(double2 a, double2 b) {
#if defined(__SSE2__)
    return _mm_min_pd(a, b);
#else
    long2 pick_a = a < b;
    return (double2)(((long2)a & pick_a) | ((long2)b & ~pick_a));
#endif
}

/* What every box test of one ray shares: computed once per ray. */
struct ray_setup {
    double origin[3];
    double inverse[3];  /* 1 / direction; a zero component gives an infinity of the zero's sign */
    int near[3];        /* 0 when the ray enters a box through its low face on this axis, 1 for the high */
    double2 origin2[3]; /* origin and inverse again, each component in both lanes */
    double2 inverse2[3];
    struct triangle_ray triangle; /* the watertight triangle test's per-ray work (triangle.h) */
};

static inline struct ray_setup ray_setup_make(const ray *r) {
    struct ray_setup s;
    for (int a = 0; a < 3; a++) {
        s.origin[a] = vec3_axis(r->origin, a);
        s.inverse[a] = 1.0 / vec3_axis(r->direction, a);
        s.near[a] = s.inverse[a] < 0.0;
        s.origin2[a] = (double2){s.origin[a], s.origin[a]};
        s.inverse2[a] = (double2){s.inverse[a], s.inverse[a]};
    }
    s.triangle = triangle_ray_make(r);
    return s;
}

/* The slab test (aabb.c) on the root box, in double: true when the ray is inside it for some t in
 * [t_near, t_far]. An origin exactly on a face plane with a zero direction component gives
 * 0 * infinity = NaN, which compares false and so leaves the interval alone: a ray running in a face's
 * plane is inside. */
static inline bool root_hit(const struct fast_bvh *b, const struct ray_setup *s, double t_near, double t_far) {
    for (int a = 0; a < 3; a++) {
        double near_plane = s->near[a] ? b->root_hi[a] : b->root_lo[a];
        double far_plane = s->near[a] ? b->root_lo[a] : b->root_hi[a];
        double t0 = (near_plane - s->origin[a]) * s->inverse[a];
        double t1 = (far_plane - s->origin[a]) * s->inverse[a];
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    }
    return t_near <= t_far;
}

/* Bit k of the result is set when lane k of the comparison result m is true. */
static inline unsigned lanes_true(long2 m) {
#if defined(__SSE2__)
    return (unsigned)_mm_movemask_pd((__m128d)m);
#else
    return (unsigned)(m[0] & 1) | (unsigned)(m[1] & 2);
#endif
}

/* The two floats at p, widened to doubles: one load and one conversion on SSE2 (converting them one
 * by one, as GCC does with a plain initializer, cost 9 % of the frame time on the benchmark). */
static inline double2 float_pair(const float *p) {
#if defined(__SSE2__)
    return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64((const __m128i *)p)));
#else
    return (double2){p[0], p[1]};
#endif
}

/* The slab test on child k of n alone (FAST_BVH_RUNG_WIDE): the arithmetic of child_pair_hit, one
 * child at a time. Returns whether the ray is inside the box for some t in [t_near, t_far], and the
 * entry distance in *entry. */
static inline bool child_hit(const struct fast_bvh_node *n, int k, const struct ray_setup *s, double t_near,
                             double t_far, double *entry) {
    for (int a = 0; a < 3; a++) {
        double t0 = ((double)n->bounds[a][s->near[a]][k] - s->origin[a]) * s->inverse[a];
        double t1 = ((double)n->bounds[a][1 - s->near[a]][k] - s->origin[a]) * s->inverse[a];
        t_near = t0 > t_near ? t0 : t_near; /* a NaN t0 or t1 leaves the window alone, as in max2 */
        t_far = t1 < t_far ? t1 : t_far;
    }
    *entry = t_near;
    return t_near <= t_far;
}

/* The slab test on children 2h and 2h + 1 of n at once (lanes 0 and 1). Returns a 2-bit mask of the
 * children hit in [t_near, t_far] (bit 0 for child 2h, bit 1 for child 2h + 1) and their entry
 * distances in *entry (lane 0, lane 1). */
/* TASK 11.1: two children's slab tests at once */
static inline unsigned child_pair_hit(const struct fast_bvh_node *n, int h, const struct ray_setup *s, double t_near,
                                      double t_far, double2 *entry) {
    double2 enter = {t_near, t_near}, leave = {t_far, t_far};
    for (int a = 0; a < 3; a++) {
        const float *near_planes = &n->bounds[a][s->near[a]][2 * h];
        const float *far_planes = &n->bounds[a][1 - s->near[a]][2 * h];
        double2 t0 = (float_pair(near_planes) - s->origin2[a]) * s->inverse2[a];
        double2 t1 = (float_pair(far_planes) - s->origin2[a]) * s->inverse2[a];
        enter = max2(t0, enter);
        leave = min2(t1, leave);
    }
    *entry = enter;
    return lanes_true(enter <= leave);
}

/* Whether the line of ray r (made ready by triangle_ray_make) crosses the triangle, and where:
 * triangle_crossing_prepared (triangle.h), the arithmetic triangle_intersect uses, so t is
 * bit-identical to the brute-force loop's. Does not count. */
static inline bool triangle_hit(const struct fast_bvh_triangle *tri, const struct triangle_ray *r, double *t) {
    double u, v;
    return triangle_crossing_prepared(tri->a, tri->b, tri->c, r, t, &u, &v);
}

/* The three questions one traversal answers; the code is specialised for each at compile time. */
enum query {
    QUERY_CLOSEST, /* nearest hit: near child first, boxes beyond the best hit skipped */
    QUERY_ANY,     /* any hit: stop at the first */
    QUERY_ALL,     /* every hit: visit everything the ray crosses */
};

struct query_state {
    double t;      /* QUERY_CLOSEST: best t so far (t_max until something is found) */
    uint32_t face; /* QUERY_CLOSEST: its face */
    bool found;
    bool (*visit)(void *ctx, double t, uint32_t face); /* QUERY_ALL */
    void *ctx;
};

/* Tests triangles [first, first + count) for query q, lowering *box_max as nearer hits turn up.
 * Returns false when the walk should stop (QUERY_ANY found one, or QUERY_ALL's visit said so). */
static inline __attribute__((always_inline)) bool test_triangles(const struct fast_bvh *b, const struct triangle_ray *r, uint32_t first,
                                                                 uint32_t count, double t_min, double t_max,
                                                                 enum query kind, struct query_state *q,
                                                                 double *box_max, uint64_t *tests) {
    for (uint32_t k = first; k < first + count; k++) {
        double t;
        (*tests)++;
        if (!triangle_hit(&b->triangles[k], r, &t) || !(t > t_min && t < t_max))
            continue;
        uint32_t face = b->faces[k];
        if (kind == QUERY_ANY) {
            q->found = true;
            return false;
        }
        if (kind == QUERY_ALL) {
            q->found = true;
            if (!q->visit(q->ctx, t, face))
                return false;
            continue;
        }
        if (!q->found || t < q->t || (t == q->t && face < q->face)) {
            q->found = true;
            q->t = t;
            q->face = face;
            *box_max = t; /* from now on only boxes starting at or before t matter */
        }
    }
    return true;
}

/* Asks the memory system for a child the ray will visit later, so that it is in cache by then: a big
 * mesh's nodes and triangles do not fit in cache, and each visit otherwise waits for memory. */
static inline void prefetch_child(const struct fast_bvh *b, uint32_t child, uint32_t count) {
    if (count == 0) {
        __builtin_prefetch(&b->nodes[child]);
        __builtin_prefetch((const char *)&b->nodes[child] + 64);
    } else {
        __builtin_prefetch(&b->triangles[child]);
        __builtin_prefetch((const char *)&b->triangles[child] + 64);
    }
}

/* The children of a node that the ray hits, in the order the nearest-hit walk takes them: the slot
 * numbers k whose bit is set in `hit` (bit k for child k, as child_hit and child_pair_hit set them),
 * written into `order` nearest entry first, the entry of child k being entry[k >> 1][k & 1] (lane k & 1
 * of pair k >> 1); children entered at the same distance keep their slot order. Returns how many were
 * written (0 to BVH_WIDTH). An insertion sort: at most four children, so nothing cleverer pays. */
/* TASK 11.2: the children hit, nearest first */
static inline int nearest_first(unsigned hit, const double2 entry[2], int order[BVH_WIDTH]) {
    int hits = 0;
    for (int k = 0; k < BVH_WIDTH; k++) {
        if (!(hit >> k & 1))
            continue;
        int at = hits++;
        for (; at > 0 && entry[k >> 1][k & 1] < entry[order[at - 1] >> 1][order[at - 1] & 1]; at--)
            order[at] = order[at - 1];
        order[at] = k;
    }
    return hits;
}

/* A subtree put aside for later, with the distance at which the ray enters its box. */
struct stack_entry {
    uint32_t child, count;
    double entry;
};

/* Walks the tree for one query, after the slivers. Counters are kept in locals and added to the
 * thread's once at the end (one thread-local update per ray instead of one per node). Returns
 * q->found. */
static inline __attribute__((always_inline)) bool traverse(const struct fast_bvh *b, const ray *r, double t_min,
                                                           double t_max, enum query kind, bool simd, bool prefetch,
                                                           struct query_state *q) {
    q->found = false;
    q->t = t_max;
    /* The box tests' window: infinite ends replaced by the largest finite doubles, so that a ray
     * parallel to a slab and outside it (entry and exit both +infinity) is a miss. */
    double box_min = t_min > -DBL_MAX ? t_min : -DBL_MAX;
    double box_max = t_max < DBL_MAX ? t_max : DBL_MAX;
    uint64_t visits = 0, boxes = 0, tests = 0;
    struct ray_setup s = ray_setup_make(r); /* once per query: the box tests' and the triangle test's setup */
    bool running = test_triangles(b, &s.triangle, (uint32_t)b->tree_count,
                                  (uint32_t)(b->triangle_count - b->tree_count), t_min, t_max, kind, q, &box_max,
                                  &tests);
    struct stack_entry stack[BVH_STACK_SIZE];
    int top = 0;
    uint32_t child = b->root_child, count = b->root_count;
    if (running && b->tree_count > 0) {
        boxes++;
        running = root_hit(b, &s, box_min, box_max);
    } else {
        running = false;
    }
    while (running) {
        visits++;
        if (count == 0) {
            const struct fast_bvh_node *n = &b->nodes[child];
            double2 entry[2];
            unsigned hit = 0;
            if (simd) {
                hit = child_pair_hit(n, 0, &s, box_min, box_max, &entry[0]) |
                      child_pair_hit(n, 1, &s, box_min, box_max, &entry[1]) << 2;
            } else {
                for (int k = 0; k < BVH_WIDTH; k++)
                    hit |= (unsigned)child_hit(n, k, &s, box_min, box_max, &entry[k >> 1][k & 1]) << k;
            }
            /* Unused slots have empty boxes, which every slab test misses, except a ray with a NaN or
             * infinite origin or direction (0 * infinity and infinity - infinity are NaN, which the
             * slab test ignores): masking them out keeps such a ray from following a slot to nowhere. */
            unsigned used = 3u | (unsigned)(n->child[2] != BVH_NO_CHILD) << 2 | (unsigned)(n->child[3] != BVH_NO_CHILD) << 3;
            hit &= used;
            boxes += 2 + (used >> 2 & 1) + (used >> 3);
            /* The children hit, nearest first when the nearest hit is wanted, else in slot order; all
             * but the first are put aside, farthest deepest. */
            int order[BVH_WIDTH], hits = 0;
            if (hit != 0 && kind == QUERY_CLOSEST) {
                hits = nearest_first(hit, entry, order);
            } else if (hit != 0) {
                for (int k = 0; k < BVH_WIDTH; k++)
                    if (hit >> k & 1)
                        order[hits++] = k;
            }
            if (hits > 0) {
                for (int i = hits - 1; i > 0; i--) {
                    int k = order[i];
                    stack[top++] = (struct stack_entry){n->child[k], n->count[k], entry[k >> 1][k & 1]};
                    if (prefetch)
                        prefetch_child(b, n->child[k], n->count[k]);
                }
                child = n->child[order[0]];
                count = n->count[order[0]];
                continue;
            }
        } else if (!test_triangles(b, &s.triangle, child, count, t_min, t_max, kind, q, &box_max, &tests)) {
            break;
        }
        /* Next: the most recently put aside subtree that can still hold something at or before box_max
         * (at: a lower face at the same t would win the tie). */
        running = false;
        while (top > 0) {
            const struct stack_entry *e = &stack[--top];
            if (e->entry <= box_max) {
                child = e->child;
                count = e->count;
                running = true;
                break;
            }
        }
    }
    stats_thread.node_visits += visits;
    stats_thread.box_tests += boxes;
    stats_thread.triangle_tests += tests;
    return q->found;
}

/* traverse for query `kind`, specialised for b's rung (a constant in each branch, so each rung gets
 * its own copy of the loop, without the tests of the others). */
static inline __attribute__((always_inline)) bool traverse_rung(const struct fast_bvh *b, const ray *r, double t_min,
                                                                double t_max, enum query kind, struct query_state *q) {
    switch (b->rung) {
    case FAST_BVH_RUNG_WIDE:
        return traverse(b, r, t_min, t_max, kind, false, false, q);
    case FAST_BVH_RUNG_SIMD:
        return traverse(b, r, t_min, t_max, kind, true, false, q);
    default:
        return traverse(b, r, t_min, t_max, kind, true, true, q);
    }
}

bool fast_bvh_closest(const struct fast_bvh *b, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    struct query_state q = {0};
    if (!traverse_rung(b, r, t_min, t_max, QUERY_CLOSEST, &q))
        return false;
    *t = q.t;
    *face = q.face;
    return true;
}

bool fast_bvh_occluded(const struct fast_bvh *b, const ray *r, double t_min, double t_max) {
    struct query_state q = {0};
    return traverse_rung(b, r, t_min, t_max, QUERY_ANY, &q);
}

void fast_bvh_for_each_hit(const struct fast_bvh *b, const ray *r, double t_min, double t_max,
                           bool (*visit)(void *ctx, double t, uint32_t face), void *ctx) {
    struct query_state q = {0};
    q.visit = visit;
    q.ctx = ctx;
    traverse_rung(b, r, t_min, t_max, QUERY_ALL, &q);
}

/* ==== the rungs' names ======================================================================== */

static const char *const rung_names[] = {NULL, "plain", "wide", "simd", "prefetch", "build"};

int fast_bvh_rung_from_name(const char *name) {
    for (int r = FAST_BVH_RUNG_PLAIN; r <= FAST_BVH_RUNG_TOP; r++)
        if (strcmp(name, rung_names[r]) == 0 || (name[0] == '0' + r && name[1] == '\0'))
            return r;
    return 0;
}

const char *fast_bvh_rung_name(int r) {
    return r >= FAST_BVH_RUNG_PLAIN && r <= FAST_BVH_RUNG_TOP ? rung_names[r] : "?";
}

/* fast_bvh_packet.c: rung 10 of chapter 11's ladder: up to eight camera rays of neighbouring pixels walked
 * through the hierarchy together, a packet (chapter 11).
 *
 * Neighbouring camera rays start at the same eye and point almost the same way, so they visit almost the
 * same nodes. A packet walks the tree once for all of them: a node is visited when any of its rays enters
 * it, each ray keeps its own window, shortened by its own nearest hit so far, and a mask says which rays
 * are still in the walk of a subtree; a leaf's triangles are tested, in double, only for the rays whose
 * own box test entered it: on rung 9's tree (the one rung 10 walks) four at a time, by rung 9's own
 * test of a leaf (fast_bvh_lean_leaf_closest), elsewhere one at a time (test_leaf_triangles). The rays
 * share the walk's bookkeeping: one stack, one ordering of the children, one fetch of each node. The
 * children of a node are tested in one of two ways:
 *  - each ray tests them itself with rung 8's (rung 6's) float test, all children in one instruction
 *    (lane_hits8, lane_hits4), exactly as its single-ray walk would; on an 8-wide tree the answers are
 *    then gathered child by child in eight lanes too (rays_hit8): which rays enter each child, and the
 *    nearest of their entries;
 *  - a coherent packet (one float origin, the same signs of 1 / direction: camera rays) tests them once
 *    for all its rays by interval arithmetic on 1 / direction (packet_hits8). The walk does so at nodes
 *    whose children it may enter are all nodes, and enters them with all its rays; at a node with a leaf
 *    among them every ray tests for itself.
 * Camera rays are coherent and gain. The shadow rays of a packet's hits, towards one light, are walked
 * together too, for the query "is anything in the way" (fast_bvh_occluded_packet): they start at
 * different points, so each tests the boxes itself, but they share the walk as camera rays do, and each
 * leaves it at its first hit. The scattered rays of reflections are not packed.
 *
 * Exact per ray. A ray's own test is rung 6's float test, operation for operation: the same float
 * origin, 1 / direction, slack and window (fast_bvh_walk.h), so it never refuses a box that the exact
 * test enters in the ray's window, by rung 6's argument; the interval test refuses nothing that a ray's
 * own test would enter (packet_hits8 says why). So every ray visits every leaf its single-ray walk would
 * need, and maybe more, and tests their triangles as its single-ray walk does (rung 9's four lanes, each
 * the double test's arithmetic, or test_leaf_triangles), keeping the nearest by triangle_hit_wins, or
 * for a shadow ray stopping at the first crossing in its window. The order in which leaves are visited
 * changes, the answer cannot: the nearest hit, lowest face among equal t, is the same whatever the order,
 * and so is whether there is any. Rays the float test cannot cover (t_min < 0, coordinates beyond
 * FAST_BVH_FLOAT_RANGE) take fast_bvh_closest (fast_bvh_occluded) one by one.
 *
 * The walk is written once with GCC's vector extension: on x86 it is compiled for AVX2 (the 8-wide
 * trees of rungs 8 and 9, which are built only when the processor has AVX2; once for each kind of leaf
 * and each query)
 * and for the baseline (rung 6's 4-wide tree, tested four children per SSE instruction); elsewhere (the
 * browser's WebAssembly) only the baseline. Each loop over the three axes asks to be unrolled
 * (#pragma GCC unroll 3, which Clang honours too): at -O2 GCC unrolls a loop only where that does not
 * make the code larger, and left these rolled, an index and a branch per axis in the box tests that
 * every ray makes at every node; unrolled, the packets' frame takes about 0.92 of its time
 * (docs/fast-notes.md, rung 10). Unrolling changes no arithmetic. */
#include "fast_bvh_packet.h"

/* The helpers below pass and return 8-float vectors; GCC and Clang warn that, without AVX, such values
 * cross a function call differently than with it. They are static and inlined, so no call is ever made
 * with them: the warning does not apply. They are marked always_inline, so that they are inlined at -O1
 * too (the sanitizers' build): called from an AVX2 walk, a helper compiled without AVX2 would hand its
 * vector back where the caller does not look for it. */
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#include <float.h>
#include <math.h>
#include <stdbool.h>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "aabb.h"
#include "fast_bvh.h"
#include "fast_bvh_lean.h"
#include "float4.h"
#include "fast_bvh_walk.h"
#include "stats.h"
#include "triangle.h"

/* Eight floats processed by one instruction where the processor can (AVX2; two SSE instructions on
 * the baseline), and what comparing two of them gives (all bits set where true). They hold one float
 * per child of an 8-wide node, or one per ray of the packet. */
typedef float float8 __attribute__((vector_size(32)));
typedef int32_t int8v __attribute__((vector_size(32)));
typedef uint32_t uint8v __attribute__((vector_size(32)));

_Static_assert(FAST_BVH_PACKET_SIZE == 8 && FAST_BVH_WIDTH_EIGHT == 8, "one float8 lane per ray and per child");
_Static_assert(FAST_BVH_PACKET_COLUMNS * FAST_BVH_PACKET_ROWS == FAST_BVH_PACKET_SIZE, "a pixel for each lane");

/* At most seven subtrees put aside per level of the 8-wide tree, which is no deeper than the binary one. */
#define PACKET_STACK_SIZE ((FAST_BVH_WIDTH_EIGHT - 1) * (BVH_DEEPEST + 1))

/* Bit set in a lane mask for every ray of the packet. */
#define PACKET_ALL_LANES ((1u << FAST_BVH_PACKET_SIZE) - 1)

static inline __attribute__((always_inline)) float8 broadcast8(float x) { return (float8){x, x, x, x, x, x, x, x}; }

/* Lane by lane, a > b ? a : b and a < b ? a : b: a NaN in a gives b, as max4 and min4 (float4.h). */
static inline __attribute__((always_inline)) float8 max8(float8 a, float8 b) {
    int8v pick_a = a > b;
    return (float8)(((int8v)a & pick_a) | ((int8v)b & ~pick_a));
}

static inline __attribute__((always_inline)) float8 min8(float8 a, float8 b) {
    int8v pick_a = a < b;
    return (float8)(((int8v)a & pick_a) | ((int8v)b & ~pick_a));
}

/* The eight floats at p, which is 32-byte aligned. */
static inline __attribute__((always_inline)) float8 load8(const float *p) {
    float8 v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
}

/* Bit k set when lane k of the comparison result m is true: two SSE instructions on x86 (one lane
 * mask of each half), a loop elsewhere. */
static inline __attribute__((always_inline)) unsigned lanes8_true(int8v m) {
#if defined(__SSE__)
    __m128 low, high;
    __builtin_memcpy(&low, &m, sizeof low);
    __builtin_memcpy(&high, (const char *)&m + sizeof low, sizeof high);
    return (unsigned)_mm_movemask_ps(low) | (unsigned)_mm_movemask_ps(high) << 4;
#else
    unsigned bits = 0;
    for (int k = 0; k < 8; k++)
        bits |= (unsigned)(m[k] & 1) << k;
    return bits;
#endif
}

/* One ray of the packet, as the single-ray walk sets it up (fast_bvh_walk.h): rung 6's float origin,
 * 1 / direction and slack (in setup, four lanes wide; the 8-wide test spreads them to eight lanes as
 * it loads them), its window and reach (a struct walk_window), the triangle test's set-up and the
 * nearest hit so far. */
struct lane {
    struct float_setup setup;
    int near[3];                /* 0 when the ray enters a box through its low face on this axis, 1 for the high */
    float float_min, float_max; /* the window, rounded outward to float */
    double limit_for;           /* the box_max that float_max and the reach were made from */
    double box_max, t_min, t_max;
    struct triangle_ray ready;
    struct query_state q;
};

/* The packet: its rays, and each one's reach (walk_window's limit) in lane k of `limit`. */
struct packet {
    struct lane lane[FAST_BVH_PACKET_SIZE];
    float8 limit;
    /* A coherent packet (packet_make_interval): every ray with the same float origin and on every axis
     * the same sign of 1 / direction, finite. Then its rays' 1 / direction lie in [inverse_low,
     * inverse_high] axis by axis, and one interval test (packet_hits8) stands for all of them. */
    bool coherent;
    float8 origin8[3], inverse_low8[3], inverse_high8[3];
    int near[3];
    float float_min, float_max, slack, slack2; /* the widest window and the largest slack of its rays */
};

/* A subtree put aside: the rays that entered its box, and the nearest of their entry distances. */
struct packet_stack_entry {
    uint32_t child, count;
    unsigned lanes;
    float entry;
};

/* Ray k's window up to its box_max (window_up_to, fast_bvh_walk.h): at the start and after a nearer hit. */
static inline void packet_narrow(struct packet *p, int k) {
    struct lane *l = &p->lane[k];
    struct walk_window w = window_up_to(&l->setup, l->float_min, l->box_max);
    l->float_max = w.float_max;
    l->limit_for = w.limit_for;
    p->limit[k] = (float)w.limit; /* a float already: float_reach's */
}

/* Rung 8's float test of ray l on all eight children of n (children_hit8 in fast_bvh_eight.c, the same
 * operations): true in the lane of each child it enters in its window, their entry distances in *entry. */
/* TASK 11.1 ALSO: the slab tests of all eight children at once, in float, for one ray of a packet (rung 10) */
static inline __attribute__((always_inline)) int8v lane_hits8(const struct lane *l, const struct fast_bvh_node8 *n,
                                                             float8 *entry) {
    float8 enter = broadcast8(l->float_min), leave = broadcast8(l->float_max);
    #pragma GCC unroll 3
    for (int a = 0; a < 3; a++) {
        float8 origin = broadcast8(l->setup.origin[a][0]), inverse = broadcast8(l->setup.inverse[a][0]);
        float8 t0 = (load8(n->bounds[a][l->near[a]]) - origin) * inverse;
        float8 t1 = (load8(n->bounds[a][1 - l->near[a]]) - origin) * inverse;
        enter = max8(t0, enter);
        leave = min8(t1, leave);
    }
    *entry = enter;
    return enter <= (leave + l->setup.slack) * FAST_BVH_FLOAT_SCALE + l->setup.slack2;
}

/* Every ray of `lanes` tests the eight children of n itself (lane_hits8), and the answers are gathered
 * child by child, eight children at a time: hit_lanes[c] gets the rays that enter child c and key[c]
 * the nearest of their entry distances (infinity for a child none enters; `used` is true in the lanes
 * of the children n has). Returns the children entered. */
static inline __attribute__((always_inline)) unsigned rays_hit8(const struct packet *p, unsigned lanes,
                                                                const struct fast_bvh_node8 *n, int8v used,
                                                                unsigned hit_lanes[FAST_BVH_WIDTH_EIGHT],
                                                                float key[FAST_BVH_WIDTH_EIGHT]) {
    int8v rays_in = {0};
    float8 nearest = broadcast8(INFINITY);
    for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        float8 entry;
        int8v in = lane_hits8(&p->lane[k], n, &entry) & used;
        int32_t bit = (int32_t)(1u << k);
        rays_in |= in & (int8v){bit, bit, bit, bit, bit, bit, bit, bit};
        int8v nearer = in & (entry < nearest); /* entries are never NaN: max8 with the window's start */
        nearest = (float8)(((int8v)entry & nearer) | ((int8v)nearest & ~nearer));
    }
    __builtin_memcpy(hit_lanes, &rays_in, sizeof rays_in);
    __builtin_memcpy(key, &nearest, sizeof nearest);
    return lanes8_true(rays_in != 0);
}

/* Rung 6's float test of ray l on the four children of n (child_quad_hit in fast_bvh.c), likewise. */
/* TASK 11.1 ALSO: the slab tests of all four children at once, in float, for one ray of a packet (rung 10) */
static inline unsigned lane_hits4(const struct lane *l, const struct fast_bvh_node *n, float entry[4]) {
    const struct float_setup *f = &l->setup;
    float4 enter = {l->float_min, l->float_min, l->float_min, l->float_min};
    float4 leave = {l->float_max, l->float_max, l->float_max, l->float_max};
    #pragma GCC unroll 3
    for (int a = 0; a < 3; a++) {
        float4 t0 = (load4(n->bounds[a][l->near[a]]) - f->origin[a]) * f->inverse[a];
        float4 t1 = (load4(n->bounds[a][1 - l->near[a]]) - f->origin[a]) * f->inverse[a];
        enter = max4(t0, enter);
        leave = min4(t1, leave);
    }
    __builtin_memcpy(entry, &enter, sizeof enter);
    return lanes4_true(enter <= float_reach4(f, leave));
}

/* The interval test of a coherent packet on all eight children of n: a mask that holds every child
 * that lane_hits8 finds for any of the packet's rays, and entry distances no greater than any of theirs
 * in entry. Why: for each ray the difference bound - origin is the same float d (the same origin), its
 * product fl(d * inverse) lies between fl(d * inverse_low) and fl(d * inverse_high) because rounding is
 * monotone, and so the smaller of those two is at most its entry distance on that axis and the larger
 * at least its exit; the window here is the widest of the rays', the slack the largest, and the reach
 * (leave + s) * scale + 2 s grows with leave and with s. So a ray whose own test enters a child makes
 * this test enter it too. */
/* TASK 11.1 ALSO: the slab tests of all eight children at once, in float, for a coherent packet (rung 10) */
static inline unsigned packet_hits8(const struct packet *p, const struct fast_bvh_node8 *n, float entry[8]) {
    float8 enter = broadcast8(p->float_min), leave = broadcast8(p->float_max);
    #pragma GCC unroll 3
    for (int a = 0; a < 3; a++) {
        float8 d0 = load8(n->bounds[a][p->near[a]]) - p->origin8[a];
        float8 d1 = load8(n->bounds[a][1 - p->near[a]]) - p->origin8[a];
        enter = max8(min8(d0 * p->inverse_low8[a], d0 * p->inverse_high8[a]), enter);
        leave = min8(max8(d1 * p->inverse_low8[a], d1 * p->inverse_high8[a]), leave);
    }
    __builtin_memcpy(entry, &enter, sizeof enter);
    return lanes8_true(enter <= (leave + p->slack) * FAST_BVH_FLOAT_SCALE + p->slack2);
}

/* Asks the memory system for a subtree put aside, so that it is in cache when the walk comes back to
 * it, as the single-ray walks do (rung 4): a node's cache lines, or a leaf's first triangles (with
 * `lean`, rung 9's block that holds them). */
static inline void prefetch_subtree(const struct fast_bvh *b, uint32_t child, uint32_t count, bool eight,
                                    bool lean) {
    const char *at = count == 0 && eight ? (const char *)&b->nodes8[child]
                     : count == 0        ? (const char *)&b->nodes[child]
                     : lean ? (const char *)&b->lean_corners[fast_bvh_lean_index(child, 0, 0)]
                     : b->triangles != NULL ? (const char *)&b->triangles[child]
                                          : NULL; /* rung 7: the mesh's corners, not prefetched */
    int lines = count == 0 && eight ? 4 : 2;
    for (int k = 0; at != NULL && k < lines; k++)
        __builtin_prefetch(at + 64 * k);
}

/* The children in `entered` (bit c for child c) as slot numbers into order[0 .. hits), nearest key first
 * (equal keys in slot order). Returns hits. An insertion sort, as nearest_first's in fast_bvh.c. */
/* TASK 11.2 ALSO: the children entered, nearest first (rung 10's packets) */
static inline int children_by_key(unsigned entered, const float key[FAST_BVH_WIDTH_EIGHT],
                                  int order[FAST_BVH_WIDTH_EIGHT]) {
    int hits = 0;
    for (unsigned each = entered; each != 0; each &= each - 1) {
        int c = __builtin_ctz(each), at = hits++;
        for (; at > 0 && key[c] < key[order[at - 1]]; at--)
            order[at] = order[at - 1];
        order[at] = c;
    }
    return hits;
}

/* Walks the tree once for the rays of `lanes`, which p has set up and whose root box test passed, from
 * the root; `eight` when the tree is 8-wide (b->nodes8), `compact` for rung 7's leaves, `lean` for rung
 * 9's (b->lean_corners, an 8-wide tree). */
static inline __attribute__((always_inline)) void packet_walk(const struct fast_bvh *b, struct packet *p,
                                                              unsigned lanes, enum query kind, bool eight,
                                                              bool compact, bool lean) {
    const int width = eight ? FAST_BVH_WIDTH_EIGHT : FAST_BVH_WIDTH;
    uint64_t visits = 0, boxes = 0, tests = 0;
    struct packet_stack_entry stack[PACKET_STACK_SIZE];
    int top = 0;
    uint32_t child = b->root_child, count = b->root_count;
    bool running = lanes != 0;
    while (running) {
        visits++;
        if (count == 0) {
            const uint32_t *children = eight ? b->nodes8[child].child : b->nodes[child].child;
            const uint32_t *counts = eight ? b->nodes8[child].count : b->nodes[child].count;
            unsigned used = 0, leaves = 0;
            int8v used8 = {0};
            if (eight) { /* eight slots compared at once */
                uint8v slots, sizes;
                __builtin_memcpy(&slots, children, sizeof slots);
                __builtin_memcpy(&sizes, counts, sizeof sizes);
                used8 = (int8v)(slots != FAST_BVH_NO_CHILD);
                used = lanes8_true(used8);
                leaves = lanes8_true((int8v)(sizes != 0));
            } else {
                for (int c = 0; c < width; c++)
                    used |= (unsigned)(children[c] != FAST_BVH_NO_CHILD) << c;
            }
            /* Each ray tests the node's children; a child is entered by the rays that hit it, at the
             * nearest of their entry distances. A coherent packet first tests them all at once: when
             * no child it may enter is a leaf, it enters those children with all its rays, each ray's
             * own test being left to the nodes below (before a leaf, every ray tests its box). */
            unsigned hit_lanes[FAST_BVH_WIDTH_EIGHT] = {0}, entered = 0;
            _Alignas(32) float key[FAST_BVH_WIDTH_EIGHT];
            bool tested_at_once = false;
            if (eight && p->coherent) {
                unsigned maybe = packet_hits8(p, &b->nodes8[child], key) & used;
                if ((maybe & leaves) == 0) {
                    tested_at_once = true;
                    entered = maybe;
                    for (unsigned each = maybe; each != 0; each &= each - 1)
                        hit_lanes[__builtin_ctz(each)] = lanes;
                    boxes += (uint64_t)__builtin_popcount(used);
                }
            }
            if (eight && !tested_at_once)
                entered = rays_hit8(p, lanes, &b->nodes8[child], used8, hit_lanes, key);
            for (unsigned rest = tested_at_once || eight ? 0 : lanes; rest != 0; rest &= rest - 1) {
                int k = __builtin_ctz(rest);
                _Alignas(32) float entry[FAST_BVH_WIDTH_EIGHT];
                unsigned hit = lane_hits4(&p->lane[k], &b->nodes[child], entry) & used;
                for (unsigned each = hit; each != 0; each &= each - 1) {
                    int c = __builtin_ctz(each);
                    key[c] = entered >> c & 1 && key[c] <= entry[c] ? key[c] : entry[c];
                    hit_lanes[c] |= 1u << k;
                }
                entered |= hit;
            }
            if (!tested_at_once)
                boxes += (uint64_t)__builtin_popcount(used) * (uint64_t)__builtin_popcount(lanes);
            /* The children entered, nearest first (equal keys in slot order); all but the first put
             * aside, farthest deepest. */
            int order[FAST_BVH_WIDTH_EIGHT];
            int hits = children_by_key(entered, key, order);
            if (hits > 0) {
                for (int i = hits - 1; i > 0; i--) {
                    int c = order[i];
                    stack[top++] = (struct packet_stack_entry){children[c], counts[c], hit_lanes[c], key[c]};
                    prefetch_subtree(b, children[c], counts[c], eight, lean);
                }
                lanes = hit_lanes[order[0]];
                child = children[order[0]];
                count = counts[order[0]];
                continue;
            }
        } else {
            for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
                int k = __builtin_ctz(rest);
                struct lane *l = &p->lane[k];
                if (kind == QUERY_ANY) { /* a ray that finds a hit leaves the walk: no reach */
                    bool go_on = lean ? fast_bvh_lean_leaf_any(b, &l->ready, child, count, l->t_min, l->t_max,
                                                               &l->q, &tests)
                                      : test_leaf_triangles(b, &l->ready, child, count, l->t_min, l->t_max,
                                                            QUERY_ANY, compact, &l->q, &l->box_max, &tests);
                    if (!go_on)
                        p->limit[k] = -INFINITY;
                    continue;
                }
                if (lean)
                    fast_bvh_lean_leaf_closest(b, &l->ready, child, count, l->t_min, l->t_max, &l->q, &l->box_max,
                                               &tests);
                else
                    test_leaf_triangles(b, &l->ready, child, count, l->t_min, l->t_max, QUERY_CLOSEST, compact,
                                        &l->q, &l->box_max, &tests);
                if (l->box_max < l->limit_for) /* a nearer hit: narrow this ray's window */
                    packet_narrow(p, k);
            }
        }
        /* Next: the most recently put aside subtree that some of its rays may still enter within their
         * reach. Its entry is the nearest of its rays' entries, so a ray whose own entry is beyond its
         * reach may come along; its own box tests turn it away below. */
        running = false;
        while (top > 0 && !running) {
            const struct packet_stack_entry *e = &stack[--top];
            lanes = e->lanes & lanes8_true(broadcast8(e->entry) <= p->limit);
            child = e->child;
            count = e->count;
            running = lanes != 0;
        }
    }
    walk_counted(visits, boxes, tests);
}

#if defined(__x86_64__) || defined(__i386__)
/* The walks of the 8-wide trees, rung 8's and rung 9's (lean leaves), compiled for AVX2 (as
 * fast_bvh_eight.c and fast_bvh_lean.c are): called only when the tree is 8-wide, which the build makes
 * only when the processor has AVX2. */
#define PACKET_WALK_EIGHT __attribute__((target("avx2")))
#else
#define PACKET_WALK_EIGHT
#endif

/* The walk for query `kind` (QUERY_CLOSEST or QUERY_ANY) on b's kind of tree, each specialised. */
PACKET_WALK_EIGHT static void packet_walk_lean_closest(const struct fast_bvh *b, struct packet *p, unsigned lanes) {
    packet_walk(b, p, lanes, QUERY_CLOSEST, true, false, true);
}
PACKET_WALK_EIGHT static void packet_walk_lean_any(const struct fast_bvh *b, struct packet *p, unsigned lanes) {
    packet_walk(b, p, lanes, QUERY_ANY, true, false, true);
}
PACKET_WALK_EIGHT static void packet_walk_eight_closest(const struct fast_bvh *b, struct packet *p, unsigned lanes) {
    packet_walk(b, p, lanes, QUERY_CLOSEST, true, false, false);
}
PACKET_WALK_EIGHT static void packet_walk_eight_any(const struct fast_bvh *b, struct packet *p, unsigned lanes) {
    packet_walk(b, p, lanes, QUERY_ANY, true, false, false);
}

static void packet_walk_any_kind(const struct fast_bvh *b, struct packet *p, unsigned lanes, enum query kind) {
    bool eight = b->nodes8 != NULL, lean = eight && b->lean_corners != NULL, compact = b->triangles == NULL;
    if (lean)
        (kind == QUERY_ANY ? packet_walk_lean_any : packet_walk_lean_closest)(b, p, lanes);
    else if (eight)
        (kind == QUERY_ANY ? packet_walk_eight_any : packet_walk_eight_closest)(b, p, lanes);
    else if (compact && kind == QUERY_ANY)
        packet_walk(b, p, lanes, QUERY_ANY, false, true, false);
    else if (compact)
        packet_walk(b, p, lanes, QUERY_CLOSEST, false, true, false);
    else if (kind == QUERY_ANY)
        packet_walk(b, p, lanes, QUERY_ANY, false, false, false);
    else
        packet_walk(b, p, lanes, QUERY_CLOSEST, false, false, false);
}

/* Sets ray k of p up for ray r and query `kind`, as the single-ray walk sets itself up (fast_bvh.c's
 * traverse): the slivers tested, then the root's box in double; or, when no sliver lies outside the
 * tree, the root's box first, so that a ray that misses the model costs that one test (as on rung 9).
 * Returns false when the float test cannot cover r (the caller then asks the single-ray walk); else
 * true, with *inside telling whether r is to be walked: it enters the root's box, and QUERY_ANY has not
 * found its answer among the slivers (else the lane's answer is made). */
static bool packet_lane_make(const struct fast_bvh *b, struct packet *p, int k, const ray *r, double t_min,
                             double t_max, enum query kind, uint64_t *tests, bool *inside) {
    struct lane *l = &p->lane[k];
    bool root_first = root_box_tested_first(b);
    if (root_first && !root_box_entered(b, r, t_min, t_max)) {
        l->q = (struct query_state){.t = t_max};
        *inside = false;
        return true;
    }
    if (!float_setup_make(b, r, t_min, &l->setup))
        return false;
    #pragma GCC unroll 3
    for (int a = 0; a < 3; a++)
        l->near[a] = l->setup.inverse[a][0] < 0.0f; /* 1 / direction in double rounded: the same sign */
    l->t_min = t_min;
    l->t_max = t_max;
    l->q = (struct query_state){.t = t_max};
    l->ready = triangle_ray_make(r);
    double box_min = t_min; /* >= 0: float_setup_make checked it */
    l->box_max = t_max < DBL_MAX ? t_max : DBL_MAX;
    uint32_t slivers = (uint32_t)(b->triangle_count - b->tree_count);
    bool go_on = true; /* false when QUERY_ANY has its answer among the slivers */
    if (slivers > 0)
        go_on = test_leaf_triangles(b, &l->ready, (uint32_t)b->tree_count, slivers, t_min, t_max, kind,
                                    b->triangles == NULL, &l->q, &l->box_max, tests);
    *inside = go_on && (root_first || (b->tree_count > 0 && aabb_hit(&b->root_box, r->origin,
                                                                     aabb_inverse_direction(r->direction), box_min,
                                                                     l->box_max, NULL)));
    l->float_min = float_at_most(box_min);
    packet_narrow(p, k);
    return true;
}

/* Decides whether the rays of `lanes` make a coherent packet (struct packet) and if so sets its interval
 * up. */
static void packet_make_interval(struct packet *p, unsigned lanes) {
    p->coherent = lanes != 0;
    const struct lane *first = &p->lane[lanes != 0 ? __builtin_ctz(lanes) : 0];
    float low[3], high[3];
    for (int a = 0; a < 3 && p->coherent; a++) {
        p->near[a] = first->near[a];
        low[a] = high[a] = first->setup.inverse[a][0];
    }
    p->float_min = first->float_min;
    p->float_max = first->float_max;
    p->slack = first->setup.slack;
    p->slack2 = first->setup.slack2;
    for (unsigned rest = lanes; rest != 0 && p->coherent; rest &= rest - 1) {
        const struct lane *l = &p->lane[__builtin_ctz(rest)];
        #pragma GCC unroll 3
        for (int a = 0; a < 3; a++) {
            float inverse = l->setup.inverse[a][0];
            p->coherent = p->coherent && l->near[a] == first->near[a] && isfinite(inverse) &&
                          l->setup.origin[a][0] == first->setup.origin[a][0];
            low[a] = inverse < low[a] ? inverse : low[a];
            high[a] = inverse > high[a] ? inverse : high[a];
        }
        p->float_min = l->float_min < p->float_min ? l->float_min : p->float_min;
        p->float_max = l->float_max > p->float_max ? l->float_max : p->float_max;
        p->slack = l->setup.slack > p->slack ? l->setup.slack : p->slack;
        p->slack2 = l->setup.slack2 > p->slack2 ? l->setup.slack2 : p->slack2;
    }
    for (int a = 0; a < 3 && p->coherent; a++) {
        p->origin8[a] = broadcast8(first->setup.origin[a][0]);
        p->inverse_low8[a] = broadcast8(low[a]);
        p->inverse_high8[a] = broadcast8(high[a]);
    }
}

/* Sets the rays of `active` up for query `kind` and walks them together: into p, each answered ray's bit
 * in the result, and the others (those the float test cannot cover) in *alone, for the caller to answer
 * one by one. */
static unsigned packet_trace(const struct fast_bvh *b, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                             const double t_min[FAST_BVH_PACKET_SIZE], const double t_max[FAST_BVH_PACKET_SIZE],
                             enum query kind, struct packet *p, unsigned *alone) {
    p->limit = broadcast8(-INFINITY); /* a lane of no ray is never in a walk's mask */
    unsigned walking = 0, answered = 0;
    *alone = 0;
    uint64_t tests = 0;
    for (unsigned rest = active & PACKET_ALL_LANES; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        bool inside;
        if (!packet_lane_make(b, p, k, &rays[k], t_min[k], t_max[k], kind, &tests, &inside)) {
            *alone |= 1u << k;
            continue;
        }
        answered |= 1u << k;
        walking |= (unsigned)inside << k;
    }
    walk_counted(0, 0, tests);
    packet_make_interval(p, walking);
    if (walking != 0)
        packet_walk_any_kind(b, p, walking, kind);
    return answered;
}

unsigned fast_bvh_closest_packet(const struct fast_bvh *b, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                                 const double t_min[FAST_BVH_PACKET_SIZE], const double t_max[FAST_BVH_PACKET_SIZE],
                                 double t[FAST_BVH_PACKET_SIZE], uint32_t face[FAST_BVH_PACKET_SIZE]) {
    struct packet p;
    unsigned alone, found = 0;
    unsigned answered = packet_trace(b, rays, active, t_min, t_max, QUERY_CLOSEST, &p, &alone);
    for (unsigned rest = alone; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        found |= (unsigned)fast_bvh_closest(b, &rays[k], t_min[k], t_max[k], &t[k], &face[k]) << k;
    }
    for (unsigned rest = answered; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        if (p.lane[k].q.found) {
            t[k] = p.lane[k].q.t;
            face[k] = p.lane[k].q.face;
            found |= 1u << k;
        }
    }
    return found;
}

unsigned fast_bvh_occluded_packet(const struct fast_bvh *b, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                                  const double t_min[FAST_BVH_PACKET_SIZE],
                                  const double t_max[FAST_BVH_PACKET_SIZE]) {
    struct packet p;
    unsigned alone, occluded = 0;
    unsigned answered = packet_trace(b, rays, active, t_min, t_max, QUERY_ANY, &p, &alone);
    for (unsigned rest = alone; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        occluded |= (unsigned)fast_bvh_occluded(b, &rays[k], t_min[k], t_max[k]) << k;
    }
    for (unsigned rest = answered; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        occluded |= (unsigned)p.lane[k].q.found << k;
    }
    return occluded;
}

unsigned fast_bvh_camera_packet(const struct camera *cam, int x, int y, int right, int bottom,
                                ray rays[FAST_BVH_PACKET_SIZE], double t_min[FAST_BVH_PACKET_SIZE],
                                double t_max[FAST_BVH_PACKET_SIZE]) {
    unsigned active = 0;
    for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++) {
        int i = x + k % FAST_BVH_PACKET_COLUMNS, j = y + k / FAST_BVH_PACKET_COLUMNS;
        if (i < right && j < bottom) {
            rays[k] = camera_ray(cam, i, j);
            t_min[k] = RAY_T_MIN; /* as whitted_trace asks of a camera ray (ray.h) */
            t_max[k] = INFINITY;
            active |= 1u << k;
        }
    }
    return active;
}

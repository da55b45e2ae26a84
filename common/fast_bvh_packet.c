/* fast_bvh_packet.c: rung 10 of chapter 11's ladder: up to eight camera rays of neighbouring pixels walked
 * through the hierarchy together, a packet (chapter 11).
 *
 * Neighbouring camera rays start at the same eye and point almost the same way, so they visit almost the
 * same nodes. A packet walks the tree once for all of them: a node is visited when any of its rays enters
 * one of its children, and each child's box is tested against all the rays at once, one ray in each lane
 * of an 8-float vector (the single-ray rungs put the children in the lanes instead). Each ray keeps its
 * own window, shortened by its own nearest hit so far, and a mask says which rays are still in the walk
 * of a subtree; a leaf's triangles are tested, in double, only for the rays whose box test entered it.
 * What a packet saves is the walk's bookkeeping (one stack, one loop, one fetch of each node) shared by
 * its rays; what it costs is the box tests of rays that a sibling ray dragged into a node. Camera rays
 * are coherent and gain; the scattered rays of reflections and shadows would not, and are not packed.
 *
 * Exact per ray. Lane k's box test is rung 6's float test of ray k, operation for operation: the same
 * float origin, 1 / direction, slack and window (fast_bvh_walk.h), the same entry and exit distances,
 * rounded the same way, so it never refuses a box that the exact test enters in ray k's window, by rung
 * 6's argument. A ray is carried into a subtree only when its own test entered it (or not at all): it
 * visits every leaf its single-ray walk would need, and maybe more, and tests their triangles with
 * test_leaf_triangles, keeping the nearest by triangle_hit_wins. The order in which leaves are visited
 * changes, the answer cannot: the nearest hit, lowest face among equal t, is the same whatever the order.
 * Rays the float test cannot cover (t_min < 0, coordinates beyond FAST_BVH_FLOAT_RANGE) take
 * fast_bvh_closest one by one.
 *
 * The walk is written once with GCC's vector extension: on x86 it is compiled twice, for AVX2 (the
 * 8-wide tree of rung 8, which is built only when the processor has AVX2) and for the baseline (rung
 * 6's 4-wide tree, each 8-float operation done as two SSE ones); elsewhere (the browser's WebAssembly)
 * only the baseline, in whatever the compiler makes of 8-float vectors. */
#include "fast_bvh_packet.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>

#include "aabb.h"
#include "fast_bvh.h"
#include "fast_bvh_walk.h"
#include "stats.h"
#include "triangle.h"

/* One float per ray of the packet, and what comparing two of them gives (all bits set where true). */
typedef float float_lanes __attribute__((vector_size(4 * FAST_BVH_PACKET_SIZE)));
typedef int32_t int_lanes __attribute__((vector_size(4 * FAST_BVH_PACKET_SIZE)));

/* The helpers below pass and return 8-float vectors; GCC warns that, without AVX, such values cross a
 * function call differently than with it. They are static and inlined, so no call is ever made with
 * them: the warning does not apply. (Clang has no such warning.) */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

/* At most seven subtrees put aside per level of the 8-wide tree, which is no deeper than the binary one. */
#define PACKET_STACK_SIZE ((FAST_BVH_WIDTH_EIGHT - 1) * (BVH_DEEPEST + 1))

/* Bit set in a lane mask for every ray of the packet. */
#define PACKET_ALL_LANES ((1u << FAST_BVH_PACKET_SIZE) - 1)

static inline float_lanes lanes_of(float x) { return (float_lanes){x, x, x, x, x, x, x, x}; }

/* Lane by lane, m ? a : b. */
static inline float_lanes lanes_select(int_lanes m, float_lanes a, float_lanes b) {
    return (float_lanes)(((int_lanes)a & m) | ((int_lanes)b & ~m));
}

/* Lane by lane, a > b ? a : b and a < b ? a : b: a NaN in a gives b, as max4 and min4 (float4.h). */
static inline float_lanes lanes_max(float_lanes a, float_lanes b) { return lanes_select(a > b, a, b); }
static inline float_lanes lanes_min(float_lanes a, float_lanes b) { return lanes_select(a < b, a, b); }

/* Bit k set when lane k of the comparison result m is true. */
static inline unsigned lanes_true(int_lanes m) {
    unsigned bits = 0;
    for (int k = 0; k < FAST_BVH_PACKET_SIZE; k++)
        bits |= (unsigned)(m[k] & 1) << k;
    return bits;
}

/* What the walk knows of each ray: lane k of every vector and entry k of every array is ray k. */
struct packet {
    float_lanes origin[3], inverse[3]; /* rung 6's float origin and 1 / direction (struct float_setup) */
    int_lanes negative[3];             /* rays that enter boxes through the high face on this axis */
    float_lanes slack, slack2;
    float_lanes float_min, float_max, limit; /* each ray's window and reach (struct walk_window) */
    double limit_for[FAST_BVH_PACKET_SIZE];  /* the box_max that float_max and limit were made from */
    double box_max[FAST_BVH_PACKET_SIZE];
    double t_min[FAST_BVH_PACKET_SIZE], t_max[FAST_BVH_PACKET_SIZE];
    struct float_setup setup[FAST_BVH_PACKET_SIZE];
    struct triangle_ray ready[FAST_BVH_PACKET_SIZE];
    struct query_state q[FAST_BVH_PACKET_SIZE];
};

/* A subtree put aside: the rays that entered its box, and where each entered it. */
struct packet_stack_entry {
    float_lanes entry;
    uint32_t child, count;
    unsigned lanes;
};

/* Lane k's window up to its box_max (window_up_to, fast_bvh_walk.h): at the start and after a nearer hit. */
static inline void packet_narrow(struct packet *p, int k) {
    struct walk_window w = window_up_to(&p->setup[k], p->float_min[k], p->box_max[k]);
    p->float_max[k] = w.float_max;
    p->limit[k] = (float)w.limit; /* a float already: float_reach's */
    p->limit_for[k] = w.limit_for;
}

/* Rung 6's float test of one box, the box of child c with its bounds in `bounds` ([axis][low or high]
 * [child], `width` children a row), against every ray of p: the mask of the rays in `lanes` that enter
 * it, and their entry distances in *entry. */
static inline unsigned box_hit_lanes(const struct packet *p, const float *bounds, int width, int c, unsigned lanes,
                                     float_lanes *entry) {
    float_lanes enter = p->float_min, leave = p->float_max;
    for (int a = 0; a < 3; a++) {
        float_lanes low = lanes_of(bounds[(2 * a) * width + c]), high = lanes_of(bounds[(2 * a + 1) * width + c]);
        float_lanes t0 = (lanes_select(p->negative[a], high, low) - p->origin[a]) * p->inverse[a];
        float_lanes t1 = (lanes_select(p->negative[a], low, high) - p->origin[a]) * p->inverse[a];
        enter = lanes_max(t0, enter);
        leave = lanes_min(t1, leave);
    }
    *entry = enter;
    return lanes_true(enter <= (leave + p->slack) * FAST_BVH_FLOAT_SCALE + p->slack2) & lanes;
}

/* The smallest entry distance among the rays of `lanes`: the key by which a node's children are walked,
 * nearest first. */
static inline float nearest_entry(float_lanes entry, unsigned lanes) {
    float nearest = INFINITY;
    for (unsigned rest = lanes; rest != 0; rest &= rest - 1)
        nearest = fminf(nearest, entry[__builtin_ctz(rest)]);
    return nearest;
}

/* Walks the tree once for the rays of `lanes`, which p has set up and whose root box test passed, from
 * the root; `eight` when the tree is 8-wide (b->nodes8), `compact` for rung 7's leaves. Returns the
 * counters to add. */
static inline __attribute__((always_inline)) void packet_walk(const struct fast_bvh *b, struct packet *p,
                                                              unsigned lanes, bool eight, bool compact) {
    const int width = eight ? FAST_BVH_WIDTH_EIGHT : FAST_BVH_WIDTH;
    uint64_t visits = 0, boxes = 0, tests = 0;
    struct packet_stack_entry stack[PACKET_STACK_SIZE];
    int top = 0;
    uint32_t child = b->root_child, count = b->root_count;
    bool running = lanes != 0;
    while (running) {
        visits++;
        if (count == 0) {
            const float *bounds = eight ? &b->nodes8[child].bounds[0][0][0] : &b->nodes[child].bounds[0][0][0];
            const uint32_t *children = eight ? b->nodes8[child].child : b->nodes[child].child;
            const uint32_t *counts = eight ? b->nodes8[child].count : b->nodes[child].count;
            float_lanes entry[FAST_BVH_WIDTH_EIGHT];
            unsigned hit_lanes[FAST_BVH_WIDTH_EIGHT];
            float key[FAST_BVH_WIDTH_EIGHT];
            int order[FAST_BVH_WIDTH_EIGHT], hits = 0;
            for (int c = 0; c < width; c++) {
                if (children[c] == FAST_BVH_NO_CHILD)
                    continue;
                boxes += (uint64_t)__builtin_popcount(lanes);
                hit_lanes[c] = box_hit_lanes(p, bounds, width, c, lanes, &entry[c]);
                if (hit_lanes[c] == 0)
                    continue;
                /* nearest first by the packet's nearest entry; equal keys keep their slot order */
                key[c] = nearest_entry(entry[c], hit_lanes[c]);
                int at = hits++;
                for (; at > 0 && key[c] < key[order[at - 1]]; at--)
                    order[at] = order[at - 1];
                order[at] = c;
            }
            if (hits > 0) {
                for (int i = hits - 1; i > 0; i--) { /* all but the nearest put aside, farthest deepest */
                    int c = order[i];
                    stack[top++] = (struct packet_stack_entry){entry[c], children[c], counts[c], hit_lanes[c]};
                }
                lanes = hit_lanes[order[0]];
                child = children[order[0]];
                count = counts[order[0]];
                continue;
            }
        } else {
            for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
                int k = __builtin_ctz(rest);
                test_leaf_triangles(b, &p->ready[k], child, count, p->t_min[k], p->t_max[k], QUERY_CLOSEST, compact,
                                    &p->q[k], &p->box_max[k], &tests);
                if (p->box_max[k] < p->limit_for[k]) /* a nearer hit: narrow this ray's window */
                    packet_narrow(p, k);
            }
        }
        /* Next: the most recently put aside subtree that some of its rays still enter within their reach. */
        running = false;
        while (top > 0 && !running) {
            const struct packet_stack_entry *e = &stack[--top];
            lanes = e->lanes & lanes_true(e->entry <= p->limit);
            child = e->child;
            count = e->count;
            running = lanes != 0;
        }
    }
    walk_counted(visits, boxes, tests);
}

#if defined(__x86_64__) || defined(__i386__)
/* The walk of the 8-wide tree, compiled for AVX2 (as fast_bvh_eight.c is): called only when the tree is
 * 8-wide, which the build makes only when the processor has AVX2. */
__attribute__((target("avx2"))) static void packet_walk_eight(const struct fast_bvh *b, struct packet *p,
                                                               unsigned lanes) {
    packet_walk(b, p, lanes, true, false);
}
#else
static void packet_walk_eight(const struct fast_bvh *b, struct packet *p, unsigned lanes) {
    packet_walk(b, p, lanes, true, false);
}
#endif

static void packet_walk_four(const struct fast_bvh *b, struct packet *p, unsigned lanes) {
    packet_walk(b, p, lanes, false, false);
}

static void packet_walk_four_compact(const struct fast_bvh *b, struct packet *p, unsigned lanes) {
    packet_walk(b, p, lanes, false, true);
}

/* Sets lane k of p up for ray r, as the single-ray walk sets itself up (fast_bvh.c's traverse): the
 * slivers tested, then the root box. Returns false when the float test cannot cover r (the caller then
 * asks fast_bvh_closest); else true, with *inside telling whether r enters the root box. */
static bool packet_lane_make(const struct fast_bvh *b, struct packet *p, int k, const ray *r, double t_min,
                             double t_max, uint64_t *tests, bool *inside) {
    struct float_setup *f = &p->setup[k];
    if (!float_setup_make(b, r, t_min, f))
        return false;
    vec3 inverse = aabb_inverse_direction(r->direction);
    for (int a = 0; a < 3; a++) {
        p->origin[a][k] = f->origin[a][0];
        p->inverse[a][k] = f->inverse[a][0];
        p->negative[a][k] = vec3_axis(inverse, a) < 0.0 ? -1 : 0;
    }
    p->slack[k] = f->slack;
    p->slack2[k] = f->slack2;
    p->t_min[k] = t_min;
    p->t_max[k] = t_max;
    p->q[k] = (struct query_state){.t = t_max};
    p->ready[k] = triangle_ray_make(r);
    double box_min = t_min; /* >= 0: float_setup_make checked it */
    p->box_max[k] = t_max < DBL_MAX ? t_max : DBL_MAX;
    bool compact = b->triangles == NULL;
    if (compact)
        test_leaf_triangles(b, &p->ready[k], (uint32_t)b->tree_count, (uint32_t)(b->triangle_count - b->tree_count),
                            t_min, t_max, QUERY_CLOSEST, true, &p->q[k], &p->box_max[k], tests);
    else
        test_leaf_triangles(b, &p->ready[k], (uint32_t)b->tree_count, (uint32_t)(b->triangle_count - b->tree_count),
                            t_min, t_max, QUERY_CLOSEST, false, &p->q[k], &p->box_max[k], tests);
    double root_entry;
    *inside = b->tree_count > 0 && aabb_hit(&b->root_box, r->origin, inverse, box_min, p->box_max[k], &root_entry);
    p->float_min[k] = float_at_most(box_min);
    packet_narrow(p, k);
    return true;
}

unsigned fast_bvh_closest_packet(const struct fast_bvh *b, const ray rays[FAST_BVH_PACKET_SIZE], unsigned active,
                                 const double t_min[FAST_BVH_PACKET_SIZE], const double t_max[FAST_BVH_PACKET_SIZE],
                                 double t[FAST_BVH_PACKET_SIZE], uint32_t face[FAST_BVH_PACKET_SIZE]) {
    struct packet p = {0}; /* lanes of no ray stay zero: they are never in a walk's mask */
    p.float_min = lanes_of(INFINITY);
    p.float_max = lanes_of(-INFINITY);
    p.limit = lanes_of(-INFINITY);
    unsigned walking = 0, answered = 0, found = 0;
    uint64_t tests = 0;
    for (unsigned rest = active & PACKET_ALL_LANES; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        bool inside;
        if (!packet_lane_make(b, &p, k, &rays[k], t_min[k], t_max[k], &tests, &inside)) {
            found |= (unsigned)fast_bvh_closest(b, &rays[k], t_min[k], t_max[k], &t[k], &face[k]) << k;
            continue;
        }
        answered |= 1u << k;
        walking |= (unsigned)inside << k;
    }
    walk_counted(0, 0, tests);
    if (walking != 0 && b->nodes8 != NULL)
        packet_walk_eight(b, &p, walking);
    else if (walking != 0 && b->triangles == NULL)
        packet_walk_four_compact(b, &p, walking);
    else if (walking != 0)
        packet_walk_four(b, &p, walking);
    for (unsigned rest = answered; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest);
        if (p.q[k].found) {
            t[k] = p.q[k].t;
            face[k] = p.q[k].face;
            found |= 1u << k;
        }
    }
    return found;
}

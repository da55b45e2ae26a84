/* fast_bvh.c: walking chapter 10's bounding volume hierarchy fast, rung by rung (chapter 11).
 *
 * Chapter 10's bvh.c is the algorithm; this file walks the same kind of tree laid out for speed, and
 * the rungs of enum fast_bvh_rung switch its optimisations on one at a time, so each can be measured
 * against the one below (make bench; docs/11-fast.md):
 *  - FAST_BVH_RUNG_WIDE: the 4-wide layout (below), made from chapter 10's tree by fast_bvh_collapse
 *    (fast_bvh_build.c); each child's box tested on its own by chapter 5's slab test, as chapter 10
 *    does (child_hit).
 *  - FAST_BVH_RUNG_SIMD: two children's slab tests per instruction (child_pair_hit).
 *  - FAST_BVH_RUNG_PREFETCH: every child put aside on the stack is fetched while the ray goes on
 *    (prefetch_child).
 *  - FAST_BVH_RUNG_BUILD: only the build changes (fast_bvh_build.c); the walk is rung 4's.
 *  - FAST_BVH_RUNG_FLOAT: all four children's slab tests in one float instruction (child_quad_hit),
 *    made conservative by a bound on their rounding (float_setup_make says how); a ray the bound
 *    cannot cover takes rung 5's test instead.
 *  - FAST_BVH_RUNG_COMPACT: rung 6's tree and walk with compact leaves: a leaf's triangles are read
 *    from the mesh's vertices by their corners' numbers, kept in leaf order (test_leaf_triangles), so
 *    the 72-byte copy of each triangle in leaf order is not made, only 12 bytes of numbers; one more
 *    dependent load per triangle test.
 *  - FAST_BVH_RUNG_EIGHT: rung 6 on an 8-wide tree, walked by fast_bvh_eight.c with AVX2 when the
 *    processor has it; a tree built without it is rung 6's and walked here as rung 6.
 *  - FAST_BVH_RUNG_LEAN: rung 8's tree, its leaves priced by the SAH in blocks of eight triangles, walked
 *    with less work per ray by fast_bvh_lean.c (its leaves' triangles also laid out to be tested four
 *    at a time); without AVX2, as rung 8 without it.
 * The shared pieces (the float setup, the queries, the leaves' triangle test) are in fast_bvh_walk.h.
 * The traversal is one function specialised at compile time for each query and rung.
 *
 * Layout, chosen for speed. A binary tree is collapsed into a 4-wide one (each node takes its widest
 * interior child's children until it has FAST_BVH_WIDTH, as in Embree's BVH4): half the depth, so half
 * the chain of dependent "load a node, test it, choose" steps that bounds the speed of one ray. A node
 * stores the boxes of its four children side by side (struct fast_bvh_node, 128 bytes, two cache
 * lines), and a ray visiting it tests all four, and sorts the ones it hits by entry distance
 * (nearest_first), without touching the children themselves. A child is another node or a leaf: a run
 * of triangles, stored in leaf order with their face numbers beside them, as in chapter 10. Unused
 * child slots have an empty box (low +infinity, high -infinity), which every slab test misses. The
 * root's box is kept in struct fast_bvh, in double.
 *
 * Exact agreement with the brute-force loop: chapter 10's four rules (bvh.c) hold on every rung. The
 * float bounds are rounded outward from the padded double boxes, so a float box always holds the
 * double one, and the slab tests run in double on them. */
#include "fast_bvh.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "fast_bvh_eight.h"
#include "fast_bvh_lean.h"
#include "fast_bvh_walk.h"
#include "float4.h"
#include "stats.h"
#include "triangle.h"

/* The 4-wide tree is no deeper than the binary one (BVH_DEEPEST, bvh.h), and the traversal stack holds
 * at most FAST_BVH_WIDTH - 1 entries per level. */
#define FAST_BVH_STACK_SIZE ((FAST_BVH_WIDTH - 1) * (BVH_DEEPEST + 1))

_Static_assert(sizeof(struct fast_bvh_node) == 128, "a node should fill exactly two 64-byte cache lines");

void fast_bvh_free(struct fast_bvh *b) {
    if (b == NULL)
        return;
    free(b->nodes);
    free(b->nodes8);
    free(b->triangles);
    free(b->lean_corners);
    free(b->float_corners);
    free(b->corners);
    free(b->faces);
    free(b);
}

void fast_bvh_get_info(const struct fast_bvh *b, struct bvh_info *info) { *info = b->info; }

size_t fast_bvh_bytes(const struct fast_bvh *b) {
    size_t per_triangle = sizeof *b->faces + (b->triangles != NULL ? sizeof *b->triangles : 0) +
                          (b->corners != NULL ? 3 * sizeof *b->corners : 0);
    size_t lean_blocks = b->lean_corners != NULL ? (b->tree_count + FAST_BVH_LEAN_LANES - 1) / FAST_BVH_LEAN_LANES : 0;
    return b->node_count * (b->nodes8 != NULL ? sizeof *b->nodes8 : sizeof *b->nodes) + b->triangle_count * per_triangle +
           lean_blocks * FAST_BVH_LEAN_BLOCK * sizeof *b->lean_corners;
}

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

/* A node of either width, as the check reads it: its children's bounds ([axis][low or high][child],
 * width children per row), their child numbers and counts. */
struct node_view {
    const float *bounds;
    const uint32_t *child, *count;
    int width;
};

static struct node_view node_at(const struct fast_bvh *b, size_t index) {
    if (b->nodes8 != NULL) {
        const struct fast_bvh_node8 *n = &b->nodes8[index];
        return (struct node_view){&n->bounds[0][0][0], n->child, n->count, FAST_BVH_WIDTH_EIGHT};
    }
    const struct fast_bvh_node *n = &b->nodes[index];
    return (struct node_view){&n->bounds[0][0][0], n->child, n->count, FAST_BVH_WIDTH};
}

/* Child k's box in node n, widened back to double. */
static struct aabb child_box_of(struct node_view n, int k) {
    const float *lo = n.bounds + k, *hi = n.bounds + n.width + k; /* axis a's row pair starts at 2 a width */
    return (struct aabb){{lo[0], lo[2 * n.width], lo[4 * n.width]}, {hi[0], hi[2 * n.width], hi[4 * n.width]}};
}

/* Child k's box in 4-wide node n, widened back to double. */
static struct aabb child_box(const struct fast_bvh_node *n, int k) {
    return (struct aabb){{n->bounds[0][0][k], n->bounds[1][0][k], n->bounds[2][0][k]},
                         {n->bounds[0][1][k], n->bounds[1][1][k], n->bounds[2][1][k]}};
}

/* Checks the subtree referred to by (child, count) whose box is *box. */
static bool check_subtree(struct check *c, uint32_t child, uint32_t count, const struct aabb *box, size_t depth) {
    if (depth >= FAST_BVH_STACK_SIZE)
        return check_fail(c, "deeper than the traversal stack", depth);
    if (count > 0)
        return bvh_check_leaf(c->b->triangles, c->b->tree_count, child, count, box, c->seen_triangle, c->why,
                              c->why_size);
    if (child >= c->b->node_count || c->seen_node[child]++)
        return check_fail(c, "node index out of range or reached twice", child);
    struct node_view n = node_at(c->b, child);
    if (n.child[0] == FAST_BVH_NO_CHILD || n.child[1] == FAST_BVH_NO_CHILD)
        return check_fail(c, "node with fewer than two children", child);
    for (int k = 0; k < n.width; k++) {
        struct aabb inner = child_box_of(n, k);
        if (n.child[k] == FAST_BVH_NO_CHILD) {
            struct aabb empty = aabb_empty();
            if (memcmp(&inner, &empty, sizeof inner) != 0 || n.count[k] != 0)
                return check_fail(c, "unused child slot without the empty box", child);
            continue;
        }
        if (!aabb_holds(box, &inner))
            return check_fail(c, "child box sticks out of its parent's", child);
        if (!check_subtree(c, n.child[k], n.count[k], &inner, depth + 1))
            return false;
    }
    return true;
}

bool fast_bvh_is_valid(const struct fast_bvh *b, const struct mesh *m, char *why, size_t why_size) {
    if (b->mesh != NULL && b->mesh != m) {
        snprintf(why, why_size, "compact leaves refer to another mesh than the one checked against");
        return false;
    }
    /* Compact leaves (rung 7) are checked as the triangles they stand for, copied here from the mesh. */
    struct fast_bvh compact = *b;
    if (b->mesh != NULL) {
        compact.triangles = malloc((b->triangle_count + 1) * sizeof *compact.triangles);
        if (compact.triangles != NULL)
            bvh_copy_triangles(m, b->faces, b->triangle_count, compact.triangles);
        for (size_t k = 0; k < b->triangle_count; k++)
            if (memcmp(&b->corners[3 * k], m->faces[b->faces[k]].v, 3 * sizeof *b->corners) != 0) {
                snprintf(why, why_size, "compact leaf's corners are not its face's (at %zu)", k);
                free(compact.triangles);
                return false;
            }
    }
    struct check c = {&compact, m, calloc(b->triangle_count + 1, 1), calloc(b->node_count + 1, 1), why, why_size};
    bool ok = c.seen_triangle != NULL && c.seen_node != NULL && compact.triangles != NULL;
    if (!ok)
        snprintf(why, why_size, "out of memory");
    if (ok)
        ok = bvh_check_triangles(m, compact.triangles, b->faces, b->triangle_count, why, why_size);
    if (ok && b->tree_count > 0)
        ok = check_subtree(&c, b->root_child, b->root_count, &b->root_box, 0);
    if (ok)
        ok = bvh_check_faces(m, b->faces, b->triangle_count, b->tree_count, c.seen_triangle, why, why_size);
    free(c.seen_triangle);
    free(c.seen_node);
    if (b->mesh != NULL)
        free(compact.triangles);
    return ok;
}

/* ==== vectors ================================================================================= */

/* GCC's vector extension: a pair of doubles processed by one instruction (SSE2 on x86-64): the
 * traversal tests two children at once, one in each lane. */
typedef double double2 __attribute__((vector_size(16)));
typedef int64_t long2 __attribute__((vector_size(16)));

/* Lane by lane, a > b ? a : b and a < b ? a : b. A NaN in a compares false and gives b: that is how
 * the slab test ignores 0 * infinity (see aabb.c). SSE2 has these as single instructions. */
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

/* The four floats of e widened to doubles, two by two: lanes 0 and 1 in pair[0], 2 and 3 in pair[1]. */
static inline void float4_widened(float4 e, double2 pair[2]) {
#if defined(__SSE2__)
    pair[0] = _mm_cvtps_pd(e);
    pair[1] = _mm_cvtps_pd(_mm_movehl_ps(e, e));
#else
    pair[0] = (double2){e[0], e[1]};
    pair[1] = (double2){e[2], e[3]};
#endif
}

/* ==== traversal =============================================================================== */

/* What every box test of one ray shares: computed once per ray. */
struct ray_setup {
    vec3 inverse;       /* 1 / direction (aabb_inverse_direction) */
    int near[3];        /* 0 when the ray enters a box through its low face on this axis, 1 for the high */
    double2 origin2[3]; /* origin and inverse again, each component in both lanes */
    double2 inverse2[3];
    struct triangle_ray triangle; /* the watertight triangle test's per-ray work (triangle.h) */
};

static inline struct ray_setup ray_setup_make(const ray *r) {
    struct ray_setup s;
    s.inverse = aabb_inverse_direction(r->direction);
    for (int a = 0; a < 3; a++) {
        double origin = vec3_axis(r->origin, a), inverse = vec3_axis(s.inverse, a);
        s.near[a] = inverse < 0.0;
        s.origin2[a] = (double2){origin, origin};
        s.inverse2[a] = (double2){inverse, inverse};
    }
    s.triangle = triangle_ray_make(r);
    return s;
}

/* The slab test on child k of n alone (FAST_BVH_RUNG_WIDE): chapter 5's aabb_clip, as chapter 10 uses
 * it, on the child's box widened back to double. Returns whether the ray is inside the box for some t
 * in [t_near, t_far], and the entry distance in *entry. */
static inline bool child_hit(const struct fast_bvh_node *n, int k, const ray *r, const struct ray_setup *s,
                             double t_near, double t_far, double *entry) {
    struct aabb box = child_box(n, k);
    bool hit = aabb_clip(&box, r->origin, s->inverse, &t_near, &t_far);
    *entry = t_near;
    return hit;
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

/* The slab test on all four children of n at once, in float (lane k for child k), for entry distances
 * from t_near and exit distances up to t_far. Returns a 4-bit mask that holds every child the exact
 * test would find in the window (and maybe a few grazed ones besides), and the computed entry
 * distances in *entry. */
/* TASK 11.1 ALSO: the slab tests of all four children at once, in float (rung 6) */
static inline unsigned child_quad_hit(const struct fast_bvh_node *n, const struct ray_setup *s,
                                      const struct float_setup *f, float t_near, float t_far, float4 *entry) {
    float4 enter = {t_near, t_near, t_near, t_near}, leave = {t_far, t_far, t_far, t_far};
    for (int a = 0; a < 3; a++) {
        float4 t0 = (load4(n->bounds[a][s->near[a]]) - f->origin[a]) * f->inverse[a];
        float4 t1 = (load4(n->bounds[a][1 - s->near[a]]) - f->origin[a]) * f->inverse[a];
        enter = max4(t0, enter);
        leave = min4(t1, leave);
    }
    *entry = enter;
    return lanes4_true(enter <= float_reach4(f, leave));
}

/* Asks the memory system for a child the ray will visit later, so that it is in cache by then: a big
 * mesh's nodes and triangles do not fit in cache, and each visit otherwise waits for memory. */
static inline void prefetch_child(const struct fast_bvh *b, uint32_t child, uint32_t count, bool compact) {
    if (count == 0) {
        __builtin_prefetch(&b->nodes[child]);
        __builtin_prefetch((const char *)&b->nodes[child] + 64);
    } else if (compact) {
        __builtin_prefetch(&b->corners[3 * (size_t)child]); /* the leaf's corners' numbers */
    } else {
        __builtin_prefetch(&b->triangles[child]);
        __builtin_prefetch((const char *)&b->triangles[child] + 64);
    }
}

/* The children of a node that the ray hits, in the order the nearest-hit walk takes them: the slot
 * numbers k whose bit is set in `hit` (bit k for child k, as child_hit and child_pair_hit set them),
 * written into `order` nearest entry first, the entry of child k being entry[k >> 1][k & 1] (lane k & 1
 * of pair k >> 1); children entered at the same distance keep their slot order. Returns how many were
 * written (0 to FAST_BVH_WIDTH). An insertion sort: at most four children, so nothing cleverer pays. */
/* TASK 11.2: the children hit, nearest first */
static inline int nearest_first(unsigned hit, const double2 entry[2], int order[FAST_BVH_WIDTH]) {
    int hits = 0;
    for (int k = 0; k < FAST_BVH_WIDTH; k++) {
        if (!(hit >> k & 1))
            continue;
        int at = hits++;
        for (; at > 0 && entry[k >> 1][k & 1] < entry[order[at - 1] >> 1][order[at - 1] & 1]; at--)
            order[at] = order[at - 1];
        order[at] = k;
    }
    return hits;
}

/* Walks the tree for one query, after the slivers. Counters are kept in locals and added to the
 * thread's once at the end (one thread-local update per ray instead of one per node). Returns
 * q->found. */
static inline __attribute__((always_inline)) bool traverse(const struct fast_bvh *b, const ray *r, double t_min,
                                                           double t_max, enum query kind, bool simd, bool prefetch,
                                                           const struct float_setup *f, bool compact,
                                                           struct query_state *q) {
    q->found = false;
    q->t = t_max;
    /* The box tests' window: infinite ends replaced by the largest finite doubles, so that a ray
     * parallel to a slab and outside it (entry and exit both +infinity) is a miss. */
    double box_min = t_min > -DBL_MAX ? t_min : -DBL_MAX;
    double box_max = t_max < DBL_MAX ? t_max : DBL_MAX;
    uint64_t visits = 0, boxes = 0, tests = 0;
    struct ray_setup s = ray_setup_make(r); /* once per query: the box tests' and the triangle test's setup */
    bool running = test_leaf_triangles(b, &s.triangle, (uint32_t)b->tree_count,
                                       (uint32_t)(b->triangle_count - b->tree_count), t_min, t_max, kind, compact, q,
                                       &box_max, &tests);
    struct walk_stack_entry stack[FAST_BVH_STACK_SIZE];
    int top = 0;
    uint32_t child = b->root_child, count = b->root_count;
    running = running && b->tree_count > 0 && /* the root's box, unless traverse_rung has tested it */
              (root_box_tested_first(b) || aabb_hit(&b->root_box, r->origin, s.inverse, box_min, box_max, NULL));
    /* Rung 6: the window in float, rounded outward, and the limit a put-aside entry must be within. */
    bool in_float = f != NULL;
    struct walk_window w = window_up_to(f, in_float ? float_at_most(box_min) : 0.0f, box_max);
    while (running) {
        visits++;
        if (count == 0) {
            const struct fast_bvh_node *n = &b->nodes[child];
            double2 entry[2];
            unsigned hit = 0;
            if (in_float) {
                float4 enter;
                hit = child_quad_hit(n, &s, f, w.float_min, w.float_max, &enter);
                float4_widened(enter, entry);
            } else if (simd) {
                hit = child_pair_hit(n, 0, &s, box_min, box_max, &entry[0]) |
                      child_pair_hit(n, 1, &s, box_min, box_max, &entry[1]) << 2;
            } else {
                for (int k = 0; k < FAST_BVH_WIDTH; k++) {
                    double enter; /* a lane of a double2 has no address of its own for clang */
                    hit |= (unsigned)child_hit(n, k, r, &s, box_min, box_max, &enter) << k;
                    entry[k >> 1][k & 1] = enter;
                }
            }
            /* Unused slots have empty boxes, which every slab test misses, except a ray with a NaN or
             * infinite origin or direction (0 * infinity and infinity - infinity are NaN, which the
             * slab test ignores): masking them out keeps such a ray from following a slot to nowhere. */
            unsigned used = 3u | (unsigned)(n->child[2] != FAST_BVH_NO_CHILD) << 2 |
                            (unsigned)(n->child[3] != FAST_BVH_NO_CHILD) << 3;
            hit &= used;
            boxes += 2 + (used >> 2 & 1) + (used >> 3);
            /* The children hit, nearest first when the nearest hit is wanted, else in slot order; all
             * but the first are put aside, farthest deepest. */
            int order[FAST_BVH_WIDTH], hits = 0;
            if (hit != 0 && kind == QUERY_CLOSEST) {
                hits = nearest_first(hit, entry, order);
            } else if (hit != 0) {
                for (int k = 0; k < FAST_BVH_WIDTH; k++)
                    if (hit >> k & 1)
                        order[hits++] = k;
            }
            if (hits > 0) {
                for (int i = hits - 1; i > 0; i--) {
                    int k = order[i];
                    stack[top++] = (struct walk_stack_entry){n->child[k], n->count[k], entry[k >> 1][k & 1]};
                    if (prefetch)
                        prefetch_child(b, n->child[k], n->count[k], compact);
                }
                child = n->child[order[0]];
                count = n->count[order[0]];
                continue;
            }
        } else if (!test_leaf_triangles(b, &s.triangle, child, count, t_min, t_max, kind, compact, q, &box_max,
                                        &tests)) {
            break;
        } else if (kind == QUERY_CLOSEST && box_max < w.limit_for) { /* a nearer hit: narrow the window */
            w = window_up_to(f, w.float_min, box_max);
        }
        /* Next: the most recently put aside subtree that can still hold something at or before box_max;
         * on rung 6, whose entries are computed in float, within the same reach as its box test. */
        running = stack_pop_within(stack, &top, w.limit, &child, &count);
    }
    walk_counted(visits, boxes, tests);
    return q->found;
}

/* traverse for query `kind`, specialised for b's rung (a constant in each branch, so each rung gets
 * its own copy of the loop, without the tests of the others). Rung 5 changes only the build, and is
 * walked as rung 4; rung 6 walks rung 5's tree with its float test, and rung 7 the same over compact
 * leaves. */
static inline __attribute__((always_inline)) bool traverse_rung(const struct fast_bvh *b, const ray *r, double t_min,
                                                                double t_max, enum query kind, struct query_state *q) {
    struct float_setup f;
    /* From rung 6 on, a ray that misses the root's box, and so every triangle of the tree
     * (root_box_entered), is sent away before its set-up, the float one (float_setup_make) and the
     * double one (ray_setup_make), which cost it more than that one slab test: most rays of a frame miss
     * the model. Only when no sliver lies outside the tree (a walk tests those first). */
    if (root_box_tested_first(b) && !root_box_entered(b, r, t_min, t_max)) {
        q->found = false;
        q->t = t_max;
        return false;
    }
    switch (b->rung) {
    case FAST_BVH_RUNG_WIDE:
        return traverse(b, r, t_min, t_max, kind, false, false, NULL, false, q);
    case FAST_BVH_RUNG_SIMD:
        return traverse(b, r, t_min, t_max, kind, true, false, NULL, false, q);
    case FAST_BVH_RUNG_PREFETCH:
    case FAST_BVH_RUNG_BUILD:
        return traverse(b, r, t_min, t_max, kind, true, true, NULL, false, q);
    case FAST_BVH_RUNG_FLOAT: /* when its bound covers the ray; else rung 5's walk */
        if (float_setup_make(b, r, t_min, &f))
            return traverse(b, r, t_min, t_max, kind, true, true, &f, false, q);
        return traverse(b, r, t_min, t_max, kind, true, true, NULL, false, q);
    case FAST_BVH_RUNG_EIGHT: /* the 8-wide walk when the tree was built for it (AVX2); else rung 6's */
        if (b->nodes8 != NULL)
            return fast_bvh_eight_traverse(b, r, t_min, t_max, kind, q);
        if (float_setup_make(b, r, t_min, &f))
            return traverse(b, r, t_min, t_max, kind, true, true, &f, false, q);
        return traverse(b, r, t_min, t_max, kind, true, true, NULL, false, q);
    case FAST_BVH_RUNG_LEAN: /* rung 8's kind of tree walked leaner (AVX2); else rung 6's */
    case FAST_BVH_RUNG_EXACT: /* the same, its triangles tested in float first (b->float_corners) */
        if (b->nodes8 != NULL)
            return fast_bvh_lean_traverse(b, r, t_min, t_max, kind, q);
        if (float_setup_make(b, r, t_min, &f))
            return traverse(b, r, t_min, t_max, kind, true, true, &f, false, q);
        return traverse(b, r, t_min, t_max, kind, true, true, NULL, false, q);
    default: /* rung 7: rung 6's walk over compact leaves */
        if (float_setup_make(b, r, t_min, &f))
            return traverse(b, r, t_min, t_max, kind, true, true, &f, true, q);
        return traverse(b, r, t_min, t_max, kind, true, true, NULL, true, q);
    }
}

/* traverse_rung for each query, not inlined: their frames hold the walks' stacks, which a ray of rungs 9
 * and 11 (walked in fast_bvh_lean.c) need not pay for. */
static __attribute__((noinline)) bool traverse_rung_closest(const struct fast_bvh *b, const ray *r, double t_min,
                                                            double t_max, struct query_state *q) {
    return traverse_rung(b, r, t_min, t_max, QUERY_CLOSEST, q);
}
static __attribute__((noinline)) bool traverse_rung_any(const struct fast_bvh *b, const ray *r, double t_min,
                                                        double t_max, struct query_state *q) {
    return traverse_rung(b, r, t_min, t_max, QUERY_ANY, q);
}
static __attribute__((noinline)) bool traverse_rung_all(const struct fast_bvh *b, const ray *r, double t_min,
                                                        double t_max, struct query_state *q) {
    return traverse_rung(b, r, t_min, t_max, QUERY_ALL, q);
}

/* traverse_rung for query `kind` (a constant where this is inlined), with rungs 9 and 11 on an 8-wide
 * tree sent straight to their walk. */
static inline __attribute__((always_inline)) bool traverse_any_rung(const struct fast_bvh *b, const ray *r,
                                                                    double t_min, double t_max, enum query kind,
                                                                    struct query_state *q) {
    if ((b->rung == FAST_BVH_RUNG_LEAN || b->rung == FAST_BVH_RUNG_EXACT) && b->nodes8 != NULL)
        return fast_bvh_lean_traverse(b, r, t_min, t_max, kind, q);
    switch (kind) {
    case QUERY_CLOSEST:
        return traverse_rung_closest(b, r, t_min, t_max, q);
    case QUERY_ANY:
        return traverse_rung_any(b, r, t_min, t_max, q);
    default:
        return traverse_rung_all(b, r, t_min, t_max, q);
    }
}

bool fast_bvh_closest(const struct fast_bvh *b, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    struct query_state q = {0};
    if (!traverse_any_rung(b, r, t_min, t_max, QUERY_CLOSEST, &q))
        return false;
    *t = q.t;
    *face = q.face;
    return true;
}

bool fast_bvh_occluded(const struct fast_bvh *b, const ray *r, double t_min, double t_max) {
    struct query_state q = {0};
    return traverse_any_rung(b, r, t_min, t_max, QUERY_ANY, &q);
}

void fast_bvh_for_each_hit(const struct fast_bvh *b, const ray *r, double t_min, double t_max,
                           bool (*visit)(void *ctx, double t, uint32_t face), void *ctx) {
    struct query_state q = {0};
    q.visit = visit;
    q.ctx = ctx;
    traverse_any_rung(b, r, t_min, t_max, QUERY_ALL, &q);
}

/* ==== the rungs' names ======================================================================== */

static const char *const rung_names[FAST_BVH_RUNG_LAST + 1] = {
    NULL, "plain", "wide", "simd", "prefetch", "build", "float", "compact", "eight", "lean",
    [FAST_BVH_RUNG_PACKET] = "packet", [FAST_BVH_RUNG_EXACT] = "exact-float",
};

int fast_bvh_rung_from_name(const char *name) {
    for (int r = FAST_BVH_RUNG_PLAIN; r <= FAST_BVH_RUNG_LAST; r++) {
        char number[12];
        snprintf(number, sizeof number, "%d", r);
        if (rung_names[r] != NULL && (strcmp(name, rung_names[r]) == 0 || strcmp(name, number) == 0))
            return r;
    }
    return 0;
}

const char *fast_bvh_rung_name(int r) {
    return r >= FAST_BVH_RUNG_PLAIN && r <= FAST_BVH_RUNG_LAST && rung_names[r] != NULL ? rung_names[r] : "?";
}

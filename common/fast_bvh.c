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
 *    from the mesh by their face numbers (test_triangles), so the 72-byte copy of each triangle in
 *    leaf order is not made; one more dependent load per triangle test.
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

/* Child k's box in node n, widened back to double. */
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
    const struct fast_bvh_node *n = &c->b->nodes[child];
    if (n->child[0] == FAST_BVH_NO_CHILD || n->child[1] == FAST_BVH_NO_CHILD)
        return check_fail(c, "node with fewer than two children", child);
    for (int k = 0; k < FAST_BVH_WIDTH; k++) {
        struct aabb inner = child_box(n, k);
        if (n->child[k] == FAST_BVH_NO_CHILD) {
            struct aabb empty = aabb_empty();
            if (memcmp(&inner, &empty, sizeof inner) != 0 || n->count[k] != 0)
                return check_fail(c, "unused child slot without the empty box", child);
            continue;
        }
        if (!aabb_holds(box, &inner))
            return check_fail(c, "child box sticks out of its parent's", child);
        if (!check_subtree(c, n->child[k], n->count[k], &inner, depth + 1))
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

/* ---- rung 6: four boxes in float --------------------------------------------------------------
 * Rung 6 computes each slab distance t = (bound - origin) / direction in float, four children per
 * instruction, from the origin rounded to the nearest float o' and 1/direction rounded to float. It
 * must never miss a box the exact slab test (real numbers, the ray's own double origin) would enter
 * in the window [t_min, t_max]: the triangles behind it might hold the brute-force loop's answer. Two
 * things move a computed t away from the exact one (docs/11-fast.md writes the argument out):
 *  - rounding, relative to t: one rounding of the difference, two of 1/direction (to double, then to
 *    float) and one of the product, at most gamma(4) = 4u / (1 - 4u) of |t| with u = 2^-24, as in Ize,
 *    "Robust BVH Ray Traversal" (JCGT 2013);
 *  - the origin's rounding, a shift of the whole ray by o - o', at most s = |o - o'| / |direction| on
 *    the t axis, the same for every box, computed per ray (the slack).
 * So every computed distance lies within gamma(4) |t| + s of the exact one, and a box the exact test
 * enters at N <= F (0 <= t_min <= N) is entered by the computed test with enter <= (1 + gamma(4)) N + s
 * and leave >= (1 - gamma(4)) F - s. The test asks enter <= (leave + s) * FAST_BVH_FLOAT_SCALE + 2 s,
 * which holds then, its own three roundings included. The argument needs t_min >= 0, no overflow and
 * no loss of relative precision to tiny numbers: hence FAST_BVH_FLOAT_RANGE (fast_bvh.h). */

/* 1 + 8 FLT_EPSILON = 1 + 16u: at least (1 + gamma(4)) / ((1 - gamma(4)) (1 - u)^3) ~ 1 + 11u, the
 * relative rounding of enter and leave and of the test's own three steps. */
#define FAST_BVH_FLOAT_SCALE (1.0f + 8.0f * FLT_EPSILON)
/* The slack is taken as twice |o - o'| |1 / direction|, computed in double: the factor 2 covers the
 * (1 + gamma(4)) by which rounding can stretch the shift, and the rounding of the slack itself. */
#define FAST_BVH_FLOAT_SLACK_FACTOR 2.0

/* A float at least x and one at most x, for 0 <= x <= FAST_BVH_FLOAT_RANGE: the nearest float is within
 * a factor 1 +- 2^-24 of x in the normal range, so x stretched or shrunk by 2^-22 first rounds to the
 * safe side; below the normal range, FLT_MIN and 0 are (and above float's range, infinity is). Cheaper than float_above and float_below,
 * which rung 6 would call several times per ray. */
#define FAST_BVH_FLOAT_STRETCH 0x1p-22

static inline float float_at_least(double x) {
    return x < FLT_MIN ? FLT_MIN : (float)(x * (1.0 + FAST_BVH_FLOAT_STRETCH));
}

static inline float float_at_most(double x) { return x < FLT_MIN ? 0.0f : (float)(x * (1.0 - FAST_BVH_FLOAT_STRETCH)); }

/* What rung 6's box tests of one ray share: the origin rounded to float and 1 / direction in float,
 * each in all four lanes, and the slack s (twice it in slack2). */
struct float_setup {
    float4 origin[3], inverse[3];
    float slack, slack2;
};

/* The far end of the window that rung 6's test compares an entry distance with, for a computed leave
 * distance: (leave + s) * FAST_BVH_FLOAT_SCALE + 2 s, for four leave distances at once or one. */
static inline float4 float_reach4(const struct float_setup *f, float4 leave) {
    return (leave + f->slack) * FAST_BVH_FLOAT_SCALE + f->slack2;
}

static inline float float_reach(const struct float_setup *f, float leave) {
    return (leave + f->slack) * FAST_BVH_FLOAT_SCALE + f->slack2;
}

/* Makes *f for ray r in tree b with the window starting at t_min; returns false,
 * when the bound above does not cover this ray (t_min < 0, or the origin, b's box or 1 / direction
 * outside FAST_BVH_FLOAT_RANGE, or t_min beyond it): the ray then takes rung 5's test. A zero direction component has an
 * infinite 1 / direction, exact in float too; it is covered when the origin's component is a float,
 * and the slab of that axis is then decided as exactly as in double. */
static inline bool float_setup_make(const struct fast_bvh *b, const ray *r, double t_min, struct float_setup *f) {
    if (!b->float_range || !(t_min >= 0.0 && t_min <= FAST_BVH_FLOAT_RANGE))
        return false;
    double slack = 0.0;
    for (int a = 0; a < 3; a++) {
        double origin = vec3_axis(r->origin, a), direction = vec3_axis(r->direction, a);
        double inverse = 1.0 / direction; /* as aabb_inverse_direction has it */
        if (!(fabs(origin) <= FAST_BVH_FLOAT_RANGE))
            return false;
        float rounded = (float)origin;
        double shift = fabs(origin - (double)rounded); /* exact: both are doubles within a float step */
        if (direction == 0.0) {
            if (shift != 0.0)
                return false; /* the slab of this axis would be decided at o', not at o */
        } else if (!(fabs(inverse) >= 1.0 / FAST_BVH_FLOAT_RANGE && fabs(inverse) <= FAST_BVH_FLOAT_RANGE)) {
            return false;
        } else {
            double axis_slack = FAST_BVH_FLOAT_SLACK_FACTOR * shift * fabs(inverse);
            slack = axis_slack > slack ? axis_slack : slack;
        }
        float inverse_f = (float)inverse;
        f->origin[a] = (float4){rounded, rounded, rounded, rounded};
        f->inverse[a] = (float4){inverse_f, inverse_f, inverse_f, inverse_f};
    }
    f->slack = float_at_least(slack); /* at least FLT_MIN: the floor for a product that underflows */
    f->slack2 = 2.0f * f->slack;
    return true;
}

/* The slab test on all four children of n at once, in float (lane k for child k), for entry distances
 * from t_near and exit distances up to t_far. Returns a 4-bit mask that holds every child the exact
 * test would find in the window (and maybe a few grazed ones besides), and the computed entry
 * distances in *entry. */
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

/* Tests triangles [first, first + count) for query q with triangle_crossing_prepared (triangle.h), the
 * arithmetic triangle_intersect uses, so t is bit-identical to the brute-force loop's; lowers *box_max
 * as nearer hits turn up. With `compact` (rung 7) each triangle's corners are read from the mesh by its
 * face number, the very doubles the brute-force loop reads; else from the copy in leaf order. Returns
 * false when the walk should stop (QUERY_ANY found one, or QUERY_ALL's visit said so). */
static inline __attribute__((always_inline)) bool test_triangles(const struct fast_bvh *b,
                                                                 const struct triangle_ray *r, uint32_t first,
                                                                 uint32_t count, double t_min, double t_max,
                                                                 enum query kind, bool compact, struct query_state *q,
                                                                 double *box_max, uint64_t *tests) {
    for (uint32_t k = first; k < first + count; k++) {
        double t, u, v;
        bool crossed;
        (*tests)++;
        if (compact) {
            const uint32_t *corner = b->mesh->faces[b->faces[k]].v;
            const vec3 *vertices = b->mesh->vertices;
            crossed = triangle_crossing_prepared(vertices[corner[0]], vertices[corner[1]], vertices[corner[2]], r, &t,
                                                 &u, &v);
        } else {
            const struct bvh_triangle *tri = &b->triangles[k];
            crossed = triangle_crossing_prepared(tri->a, tri->b, tri->c, r, &t, &u, &v);
        }
        if (!crossed || !(t > t_min && t < t_max))
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
        if (triangle_hit_wins(t, face, q->t, q->face)) { /* q->t is t_max until the first hit */
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
static inline void prefetch_child(const struct fast_bvh *b, uint32_t child, uint32_t count, bool compact) {
    if (count == 0) {
        __builtin_prefetch(&b->nodes[child]);
        __builtin_prefetch((const char *)&b->nodes[child] + 64);
    } else if (compact) {
        __builtin_prefetch(&b->mesh->faces[b->faces[child]]); /* the first face's corners' numbers */
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
    bool running = test_triangles(b, &s.triangle, (uint32_t)b->tree_count,
                                  (uint32_t)(b->triangle_count - b->tree_count), t_min, t_max, kind, compact, q,
                                  &box_max, &tests);
    struct stack_entry stack[FAST_BVH_STACK_SIZE];
    int top = 0;
    uint32_t child = b->root_child, count = b->root_count;
    double root_entry;
    running = running && b->tree_count > 0 && aabb_hit(&b->root_box, r->origin, s.inverse, box_min, box_max, &root_entry);
    /* Rung 6: the window in float, rounded outward, and the limit a put-aside entry must be within. */
    bool in_float = f != NULL;
    float float_min = in_float ? float_at_most(box_min) : 0.0f, float_max = in_float ? float_at_least(box_max) : 0.0f;
    double limit = in_float ? float_reach(f, float_max) : box_max, limit_for = box_max;
    while (running) {
        visits++;
        if (count == 0) {
            const struct fast_bvh_node *n = &b->nodes[child];
            double2 entry[2];
            unsigned hit = 0;
            if (in_float) {
                float4 enter;
                hit = child_quad_hit(n, &s, f, float_min, float_max, &enter);
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
                    stack[top++] = (struct stack_entry){n->child[k], n->count[k], entry[k >> 1][k & 1]};
                    if (prefetch)
                        prefetch_child(b, n->child[k], n->count[k], compact);
                }
                child = n->child[order[0]];
                count = n->count[order[0]];
                continue;
            }
        } else if (!test_triangles(b, &s.triangle, child, count, t_min, t_max, kind, compact, q, &box_max, &tests)) {
            break;
        } else if (kind == QUERY_CLOSEST && box_max < limit_for) { /* a nearer hit: narrow the window */
            float_max = in_float ? float_at_least(box_max) : 0.0f;
            limit = in_float ? float_reach(f, float_max) : box_max;
            limit_for = box_max;
        }
        /* Next: the most recently put aside subtree that can still hold something at or before box_max
         * (at: a lower face at the same t would win the tie); on rung 6, whose entries are computed in
         * float, within the same reach as its box test. */
        running = false;
        while (top > 0) {
            const struct stack_entry *e = &stack[--top];
            if (e->entry <= limit) {
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
 * its own copy of the loop, without the tests of the others). Rung 5 changes only the build, and is
 * walked as rung 4; rung 6 walks rung 5's tree with its float test, and rung 7 the same over compact
 * leaves. */
static inline __attribute__((always_inline)) bool traverse_rung(const struct fast_bvh *b, const ray *r, double t_min,
                                                                double t_max, enum query kind, struct query_state *q) {
    struct float_setup f;
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
    default: /* rung 7: rung 6's walk over compact leaves */
        if (float_setup_make(b, r, t_min, &f))
            return traverse(b, r, t_min, t_max, kind, true, true, &f, true, q);
        return traverse(b, r, t_min, t_max, kind, true, true, NULL, true, q);
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

static const char *const rung_names[] = {NULL, "plain", "wide", "simd", "prefetch", "build", "float", "compact"};

int fast_bvh_rung_from_name(const char *name) {
    for (int r = FAST_BVH_RUNG_PLAIN; r <= FAST_BVH_RUNG_TOP; r++)
        if (strcmp(name, rung_names[r]) == 0 || (name[0] == '0' + r && name[1] == '\0'))
            return r;
    return 0;
}

const char *fast_bvh_rung_name(int r) {
    return r >= FAST_BVH_RUNG_PLAIN && r <= FAST_BVH_RUNG_TOP ? rung_names[r] : "?";
}

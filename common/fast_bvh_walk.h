/* fast_bvh_walk.h: what the walks of chapter 11's hierarchy share: rung 6's float setup of a ray, the
 * three queries and the triangle test of a leaf (chapter 11).
 *
 * Header-only, so that the 4-wide walk (fast_bvh.c) and the 8-wide AVX2 walk (fast_bvh_eight.c) inline
 * the same code into their loops, and neither file calls the other's. */
#ifndef WHITTED_FAST_BVH_WALK_H
#define WHITTED_FAST_BVH_WALK_H

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "fast_bvh_tree.h"
#include "float4.h"
#include "stats.h"
#include "triangle.h"

/* ---- rung 6: four boxes in float (rung 8: eight) ------------------------------------------------
 * Rung 6 computes each slab distance t = (bound - origin) / direction in float, four children per
 * instruction (rung 8 eight, by the same argument), from the origin rounded to the nearest float o' and 1/direction rounded to float. It
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

/* What query q does with a crossing of `face` at t: nothing outside t_min < t < t_max; else QUERY_ANY has
 * its answer, QUERY_ALL reports it, and QUERY_CLOSEST keeps it when it wins (triangle_hit_wins) and
 * lowers *box_max to it. Returns false when the walk should stop (QUERY_ANY found one, or QUERY_ALL's
 * visit said so). */
static inline __attribute__((always_inline)) bool leaf_hit_taken(enum query kind, double t, uint32_t face,
                                                                 double t_min, double t_max, struct query_state *q,
                                                                 double *box_max) {
    if (!(t > t_min && t < t_max))
        return true;
    if (kind == QUERY_ANY) {
        q->found = true;
        return false;
    }
    if (kind == QUERY_ALL) {
        q->found = true;
        return q->visit(q->ctx, t, face);
    }
    if (triangle_hit_wins(t, face, q->t, q->face)) { /* q->t is t_max until the first hit */
        q->found = true;
        q->t = t;
        q->face = face;
        *box_max = t; /* from now on only boxes starting at or before t matter */
    }
    return true;
}

/* Tests triangles [first, first + count) for query q with triangle_crossing_prepared (triangle.h), the
 * arithmetic triangle_intersect uses, so t is bit-identical to the brute-force loop's; lowers *box_max
 * as nearer hits turn up. With `compact` (rung 7) each triangle's corners are read from the mesh's
 * vertices by their numbers, kept in leaf order (b->corners), the very doubles the brute-force loop
 * reads; else from the copy of the triangles in leaf order. Returns
 * false when the walk should stop (QUERY_ANY found one, or QUERY_ALL's visit said so). */
static inline __attribute__((always_inline)) bool test_leaf_triangles(const struct fast_bvh *b,
                                                                      const struct triangle_ray *r, uint32_t first,
                                                                      uint32_t count, double t_min, double t_max,
                                                                      enum query kind, bool compact, struct query_state *q,
                                                                      double *box_max, uint64_t *tests) {
    for (uint32_t k = first; k < first + count; k++) {
        double t, u, v;
        bool crossed;
        (*tests)++;
        if (compact) {
            const uint32_t *corner = &b->corners[3 * (size_t)k];
            const vec3 *vertices = b->mesh->vertices;
            crossed = triangle_crossing_prepared(vertices[corner[0]], vertices[corner[1]], vertices[corner[2]], r, &t,
                                                 &u, &v);
        } else {
            const struct bvh_triangle *tri = &b->triangles[k];
            crossed = triangle_crossing_prepared(tri->a, tri->b, tri->c, r, &t, &u, &v);
        }
        if (crossed && !leaf_hit_taken(kind, t, b->faces[k], t_min, t_max, q, box_max))
            return false;
    }
    return true;
}

/* A subtree put aside for later, with the distance at which the ray enters its box. */
struct walk_stack_entry {
    uint32_t child, count;
    double entry;
};

/* A walk's window in float (rungs 6 and 8), and the limit that a subtree put aside must be entered
 * within: the float test's reach on those rungs, box_max itself on the others. */
struct walk_window {
    float float_min, float_max; /* the window's ends, rounded outward to float */
    double limit;
    double limit_for;           /* the box_max that float_max and limit were made from */
};

/* The window up to box_max, with its start float_min kept: at the start of a walk, and whenever a leaf
 * finds a nearer hit (box_max lowered below limit_for). f is the ray's float setup, NULL when the walk
 * tests its boxes in double. */
static inline struct walk_window window_up_to(const struct float_setup *f, float float_min, double box_max) {
    float float_max = f != NULL ? float_at_least(box_max) : 0.0f;
    return (struct walk_window){float_min, float_max, f != NULL ? float_reach(f, float_max) : box_max, box_max};
}

/* The next subtree to walk: the most recently put aside of stack[0 .. *top) whose entry is within
 * limit (at: a lower face at the same t would win the tie), into *child and *count, the ones beyond it
 * dropped on the way. Returns false when none is left. */
static inline bool stack_pop_within(const struct walk_stack_entry *stack, int *top, double limit, uint32_t *child,
                                    uint32_t *count) {
    while (*top > 0) {
        const struct walk_stack_entry *e = &stack[--*top];
        if (e->entry <= limit) {
            *child = e->child;
            *count = e->count;
            return true;
        }
    }
    return false;
}

/* Whether ray r may meet a triangle of b's tree within [t_min, t_max]: the slab test of the root's box in
 * double (aabb_hit) with which the walks begin, every window clamped to finite bounds as traverse does.
 * Counts one box test. A ray it sends away meets none of the tree's triangles; the slivers outside the
 * tree are the caller's. */
static inline bool root_box_entered(const struct fast_bvh *b, const ray *r, double t_min, double t_max) {
    return b->tree_count > 0 && aabb_hit(&b->root_box, r->origin, aabb_inverse_direction(r->direction),
                                         t_min > -DBL_MAX ? t_min : -DBL_MAX, t_max < DBL_MAX ? t_max : DBL_MAX, NULL);
}

/* Whether the walks of b begin with the root's box tested before the ray's set-up: from rung 6 on, when
 * no sliver lies outside the tree (a walk tests those first, whatever the root's box says). A ray that
 * fails root_box_entered (or rung 9's lean_root_entered, the same test) is then sent away at once, and
 * one that passes is walked from the root's children without testing the root's box again. */
static inline bool root_box_tested_first(const struct fast_bvh *b) {
    return b->rung >= FAST_BVH_RUNG_FLOAT && b->triangle_count == b->tree_count;
}

/* Adds one walk's counters to the calling thread's (stats.h): once per ray, not once per node. */
static inline void walk_counted(uint64_t visits, uint64_t boxes, uint64_t tests) {
    stats_thread.node_visits += visits;
    stats_thread.box_tests += boxes;
    stats_thread.triangle_tests += tests;
}

#endif

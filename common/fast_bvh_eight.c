/* fast_bvh_eight.c: rung 8 of chapter 11's ladder: the walk of the 8-wide tree, all eight children's
 * float slab tests in one AVX2 instruction (chapter 11).
 *
 * The walk is rung 6's (fast_bvh.c) with eight children a node instead of four: the tree is half as
 * deep again, and a node's eight boxes are tested by the same three loads, subtractions, products,
 * minima and maxima per axis, eight lanes wide, with rung 6's bound on the rounding (fast_bvh_walk.h),
 * so that no box the exact test would enter is missed. The triangles are tested in double by the same
 * test_leaf_triangles, so every answer is the brute-force loop's. A ray the bound does not cover takes chapter
 * 5's slab test in double, child by child.
 *
 * AVX2 is not in the x86-64 baseline, so its instructions must not run on a processor without it.
 * Every function of this file is compiled for AVX2 by __attribute__((target("avx2"))) (the AVX2 macro
 * below), and only they are: the rest of the program stays baseline x86-64, and fast_bvh_build.c makes
 * an 8-wide tree only when fast_bvh_eight_available() has asked the processor at run time. The attribute
 * rather than -mavx2 on this file's command line, so that every way the repository compiles common/
 * (the chapters, the sanitizer and fuzzing builds, the coursework's copies, the gallery's patched ones)
 * builds it without a special rule. The attribute does not bring FMA, and the Makefile's
 * -ffp-contract=off forbids fusing anyway: the double arithmetic of the triangle test, inlined here, is
 * the same rounding as everywhere else. */
#include "fast_bvh_eight.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "aabb.h"
#include "stats.h"
#include "triangle.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

/* This file's functions are compiled for AVX2 (see above). */
#define AVX2 __attribute__((target("avx2")))

/* Eight floats processed by one instruction, and eight 32-bit integers, what a comparison gives. */
typedef float float8 __attribute__((vector_size(32)));
typedef int32_t int8v __attribute__((vector_size(32)));
typedef uint32_t uint8v __attribute__((vector_size(32)));

/* The 8-wide tree is no deeper than the binary one (BVH_DEEPEST), and the stack holds at most seven
 * entries per level. */
#define FAST_BVH_STACK_SIZE_EIGHT ((FAST_BVH_WIDTH_EIGHT - 1) * (BVH_DEEPEST + 1))

bool fast_bvh_eight_available(void) {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && getenv(FAST_BVH_NO_AVX2_VARIABLE) == NULL;
}

static inline AVX2 float8 broadcast8(float x) { return (float8){x, x, x, x, x, x, x, x}; }

/* Lane by lane, as min4 and max4 (float4.h): a NaN in a gives b. */
static inline AVX2 float8 min8(float8 a, float8 b) { return _mm256_min_ps(a, b); }
static inline AVX2 float8 max8(float8 a, float8 b) { return _mm256_max_ps(a, b); }

/* The eight floats at p, which is 32-byte aligned: one load. */
static inline AVX2 float8 load8(const float *p) { return _mm256_load_ps(p); }

/* Bit k of the result is set when lane k of the comparison result m is true. */
static inline AVX2 unsigned lanes8_true(int8v m) { return (unsigned)_mm256_movemask_ps((__m256)m); }

/* The slab test on all eight children of n at once, in float, as child_quad_hit (fast_bvh.c) on four:
 * for entry distances from t_near and exit distances up to t_far, an 8-bit mask that holds every child
 * the exact test would find in the window, and the computed entry distances in *entry. */
/* TASK 11.1 ALSO: the slab tests of all eight children at once, in float (rung 8) */
static inline AVX2 unsigned children_hit8(const struct fast_bvh_node8 *n, const int near[3], const float8 origin[3],
                                          const float8 inverse[3], const struct float_setup *f, float t_near,
                                          float t_far, float8 *entry) {
    float8 enter = broadcast8(t_near), leave = broadcast8(t_far);
    for (int a = 0; a < 3; a++) {
        float8 t0 = (load8(n->bounds[a][near[a]]) - origin[a]) * inverse[a];
        float8 t1 = (load8(n->bounds[a][1 - near[a]]) - origin[a]) * inverse[a];
        enter = max8(t0, enter);
        leave = min8(t1, leave);
    }
    *entry = enter;
    float8 reach = (leave + f->slack) * FAST_BVH_FLOAT_SCALE + f->slack2; /* float_reach4's, eight wide */
    return lanes8_true(enter <= reach);
}

/* Child k's box in n, widened back to double. */
static inline AVX2 struct aabb child_box8(const struct fast_bvh_node8 *n, int k) {
    return (struct aabb){{n->bounds[0][0][k], n->bounds[1][0][k], n->bounds[2][0][k]},
                         {n->bounds[0][1][k], n->bounds[1][1][k], n->bounds[2][1][k]}};
}

/* The slots whose child is used: bit k for child k. */
static inline AVX2 unsigned used_children(const struct fast_bvh_node8 *n) {
    uint8v child;
    __builtin_memcpy(&child, n->child, sizeof child);
    return lanes8_true((int8v)(child != FAST_BVH_NO_CHILD));
}

/* Asks the memory system for a child the ray will visit later (prefetch_child in fast_bvh.c): a node
 * is four cache lines here. */
static inline AVX2 void prefetch_child8(const struct fast_bvh *b, uint32_t child, uint32_t count) {
    if (count == 0) {
        const char *node = (const char *)&b->nodes8[child];
        __builtin_prefetch(node);
        __builtin_prefetch(node + 64);
        __builtin_prefetch(node + 128);
        __builtin_prefetch(node + 192);
    } else {
        __builtin_prefetch(&b->triangles[child]);
        __builtin_prefetch((const char *)&b->triangles[child] + 64);
    }
}

/* The children in `hit` (bit k for child k) as slot numbers into order[0 .. hits), in the order the walk
 * takes them: nearest entry first when `nearest` (children entered at the same distance in slot order),
 * else in slot order. Returns hits. An insertion sort, as nearest_first's in fast_bvh.c. */
/* TASK 11.2 ALSO: the children hit, nearest first (rung 8's eight children) */
static inline int children_in_order8(unsigned hit, const double entry[FAST_BVH_WIDTH_EIGHT], bool nearest,
                                     int order[FAST_BVH_WIDTH_EIGHT]) {
    int hits = 0;
    for (unsigned rest = hit; rest != 0; rest &= rest - 1) {
        int k = __builtin_ctz(rest), at = hits++;
        for (; nearest && at > 0 && entry[k] < entry[order[at - 1]]; at--)
            order[at] = order[at - 1];
        order[at] = k;
    }
    return hits;
}

/* The walk of fast_bvh.c's traverse on the 8-wide tree, for one query; in_float when f covers the ray
 * (else each child's box is tested in double). */
static inline AVX2 __attribute__((always_inline)) bool traverse8(const struct fast_bvh *b, const ray *r, double t_min,
                                                                 double t_max, enum query kind,
                                                                 const struct float_setup *f, struct query_state *q) {
    q->found = false;
    q->t = t_max;
    double box_min = t_min > -DBL_MAX ? t_min : -DBL_MAX; /* as in fast_bvh.c's traverse */
    double box_max = t_max < DBL_MAX ? t_max : DBL_MAX;
    uint64_t visits = 0, boxes = 0, tests = 0;
    vec3 inverse = aabb_inverse_direction(r->direction);
    int near[3];
    float8 origin8[3], inverse8[3];
    for (int a = 0; a < 3; a++) {
        near[a] = vec3_axis(inverse, a) < 0.0;
        if (f != NULL) {
            origin8[a] = broadcast8(f->origin[a][0]);
            inverse8[a] = broadcast8(f->inverse[a][0]);
        }
    }
    struct triangle_ray ready = triangle_ray_make(r);
    bool running = test_leaf_triangles(b, &ready, (uint32_t)b->tree_count,
                                       (uint32_t)(b->triangle_count - b->tree_count),
                                       t_min, t_max, kind, false, q, &box_max, &tests);
    struct walk_stack_entry stack[FAST_BVH_STACK_SIZE_EIGHT];
    int top = 0;
    uint32_t child = b->root_child, count = b->root_count;
    running = running && b->tree_count > 0 && /* the root's box, unless the caller has tested it */
              (root_box_tested_first(b) || aabb_hit(&b->root_box, r->origin, inverse, box_min, box_max, NULL));
    bool in_float = f != NULL;
    struct walk_window w = window_up_to(f, in_float ? float_at_most(box_min) : 0.0f, box_max);
    while (running) {
        visits++;
        if (count == 0) {
            const struct fast_bvh_node8 *n = &b->nodes8[child];
            double entry[FAST_BVH_WIDTH_EIGHT];
            unsigned hit = 0, used = used_children(n);
            if (in_float) {
                float8 enter;
                hit = children_hit8(n, near, origin8, inverse8, f, w.float_min, w.float_max, &enter) & used;
                for (unsigned rest = hit; rest != 0; rest &= rest - 1)
                    entry[__builtin_ctz(rest)] = enter[__builtin_ctz(rest)];
            } else {
                for (int k = 0; k < FAST_BVH_WIDTH_EIGHT; k++) {
                    struct aabb box = child_box8(n, k);
                    double t_near = box_min, t_far = box_max;
                    hit |= (unsigned)aabb_clip(&box, r->origin, inverse, &t_near, &t_far) << k;
                    entry[k] = t_near;
                }
                hit &= used; /* as in fast_bvh.c: a NaN ray must not follow an unused slot */
            }
            boxes += (uint64_t)__builtin_popcount(used);
            /* The children hit, nearest first for the nearest hit (ties in slot order), else in slot
             * order; all but the first put aside, farthest deepest. */
            int order[FAST_BVH_WIDTH_EIGHT];
            int hits = children_in_order8(hit, entry, kind == QUERY_CLOSEST, order);
            if (hits > 0) {
                for (int i = hits - 1; i > 0; i--) {
                    int k = order[i];
                    stack[top++] = (struct walk_stack_entry){n->child[k], n->count[k], entry[k]};
                    prefetch_child8(b, n->child[k], n->count[k]);
                }
                child = n->child[order[0]];
                count = n->count[order[0]];
                continue;
            }
        } else if (!test_leaf_triangles(b, &ready, child, count, t_min, t_max, kind, false, q, &box_max, &tests)) {
            break;
        } else if (kind == QUERY_CLOSEST && box_max < w.limit_for) { /* a nearer hit: narrow the window */
            w = window_up_to(f, w.float_min, box_max);
        }
        running = stack_pop_within(stack, &top, w.limit, &child, &count); /* as in fast_bvh.c */
    }
    walk_counted(visits, boxes, tests);
    return q->found;
}

/* traverse8 specialised for each query and for the float test or the double one. */
AVX2 bool fast_bvh_eight_traverse(const struct fast_bvh *b, const ray *r, double t_min, double t_max,
                                  enum query kind, struct query_state *q) {
    struct float_setup f;
    bool in_float = float_setup_make(b, r, t_min, &f);
    switch (kind) {
    case QUERY_CLOSEST:
        return in_float ? traverse8(b, r, t_min, t_max, QUERY_CLOSEST, &f, q)
                        : traverse8(b, r, t_min, t_max, QUERY_CLOSEST, NULL, q);
    case QUERY_ANY:
        return in_float ? traverse8(b, r, t_min, t_max, QUERY_ANY, &f, q)
                        : traverse8(b, r, t_min, t_max, QUERY_ANY, NULL, q);
    default:
        return in_float ? traverse8(b, r, t_min, t_max, QUERY_ALL, &f, q)
                        : traverse8(b, r, t_min, t_max, QUERY_ALL, NULL, q);
    }
}

#else /* not x86: no AVX2, and rung 8 is always rung 6 */

bool fast_bvh_eight_available(void) { return false; }

bool fast_bvh_eight_traverse(const struct fast_bvh *b, const ray *r, double t_min, double t_max, enum query kind,
                             struct query_state *q) {
    (void)b, (void)r, (void)t_min, (void)t_max, (void)kind;
    q->found = false;
    abort(); /* never called: the build makes no 8-wide tree without AVX2 */
}

#endif

/* fast_bvh_lean.c: rung 9 of chapter 11's ladder: rung 8's 8-wide tree walked with less work per ray
 * (chapter 11).
 *
 * The tree and the float box test are rung 8's (fast_bvh_eight.c), eight children's slab tests in one
 * AVX2 instruction with rung 6's bound on the rounding (fast_bvh_walk.h). What changes is the work
 * around them:
 *  - the root's box tested first, in double, as rung 8 does, but before anything else and its three
 *    slabs at once: most rays of a frame miss the model, and they leave for that one test
 *    (lean_root_entered);
 *  - then one set-up of the ray in float for all three axes at once, with the root test's 1 / direction
 *    (lean_float_setup);
 *  - for the nearest hit, the children hit are ordered by a fixed network of eight-lane minima and
 *    maxima on integer keys made of their float entry distances (sort8), not by an insertion sort with
 *    a branch per step; the order only decides which subtree is walked first, never the answer;
 *  - the stack holds each subtree's float entry distance, and a popped subtree entered beyond the
 *    window's reach is dropped without touching its node, by the same comparison as rung 8's;
 *  - a leaf's triangles are tested four at a time in double (leaf_triangles4), on the copy of them that
 *    fast_bvh_lean_prepare lays out in blocks of four. Each lane does exactly the arithmetic of
 *    triangle_crossing_prepared (triangle.h), in its order, each product rounded on its own (AVX2
 *    brings no fused multiply-add, and the Makefile's -ffp-contract=off forbids fusing): the same
 *    sheared corners, the same three edge functions (a lane where one comes out 0 has its three redone
 *    by triangle_edge_function itself, which then finds the exact sign), the same test of their signs
 *    (zero is inside) and of det == 0, and for the lanes that cross the same t, bit for bit. The one
 *    test it leaves out, whether the corners lie exactly on a line (triangle_corners_collinear), is
 *    made once, by fast_bvh_lean_prepare, which writes such a triangle's corners as NaN: every
 *    comparison of its lane fails, and it is never crossed, as triangle_crossing_prepared never crosses
 *    it. So each lane gives triangle_crossing_prepared's answer, and its hits go to leaf_hit_taken
 *    (fast_bvh_walk.h), the code of the other rungs, which applies the window and the tie rule.
 * A ray that rung 6's bound does not cover is walked by rung 8, in double.
 *
 * Rung 11 walks the same tree in the same way; only its leaves differ: their triangles are tested eight
 * at a time in float first (leaf_triangles_float8, float_triangle.h), and in double only where the float
 * test cannot rule the double test's hit out.
 *
 * As fast_bvh_eight.c, only the functions that need AVX2 are compiled for it (the AVX2 attribute); the
 * build makes rung 9's tree only when fast_bvh_eight_available() says the processor has AVX2. The loops
 * over the three axes ask to be unrolled (#pragma GCC unroll 3), as fast_bvh_packet.c's do, for the same
 * reason: GCC's -O2 leaves them rolled; lean_ray_triangles runs at every leaf rung 10 reaches. */
#include "fast_bvh_lean.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"
#include "fast_bvh_eight.h"
#include "float4.h"
#include "float_triangle.h"
#include "stats.h"
#include "triangle.h"

bool fast_bvh_lean_prepare(struct fast_bvh *b) {
    size_t blocks = (b->tree_count + FAST_BVH_LEAN_LANES - 1) / FAST_BVH_LEAN_LANES;
    size_t bytes = (blocks > 0 ? blocks : 1) * FAST_BVH_LEAN_BLOCK * sizeof(double); /* a multiple of 32 */
    /* Aligned to 64 bytes (an AVX2 load of four doubles wants 32), and on 2 MB pages like the tree's
     * other big arrays (big_alloc.h). */
    double *corners = big_alloc(bytes, true);
    if (corners == NULL)
        return false;
    /* The lanes past the last triangle, all in the last block (zeroing the whole array first would
     * write it twice). */
    memset(corners + (bytes / sizeof(double) - FAST_BVH_LEAN_BLOCK), 0, FAST_BVH_LEAN_BLOCK * sizeof(double));
    for (size_t k = 0; k < b->tree_count; k++) {
        const struct bvh_triangle *t = &b->triangles[k];
        const vec3 corner[3] = {t->a, t->b, t->c};
        /* A triangle whose corners lie exactly on a line is never crossed (triangle_crossing_prepared):
         * its lane holds NaN, which fails every comparison of leaf_triangles4's sign test, so that the
         * walk never asks the question itself. */
        bool collinear = triangle_corners_collinear(t->a, t->b, t->c);
        for (int c = 0; c < 3; c++)
            for (int a = 0; a < 3; a++)
                corners[fast_bvh_lean_index(k, c, a)] = collinear ? NAN : vec3_axis(corner[c], a);
    }
    b->lean_corners = corners;
    return true;
}

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

/* This file's walk is compiled for AVX2 (see above). */
#define AVX2 __attribute__((target("avx2")))

/* Eight floats, eight 32-bit integers and four doubles processed by one instruction each, and four
 * 64-bit integers, what a comparison of doubles gives. */
typedef float float8 __attribute__((vector_size(32)));
typedef int32_t int8v __attribute__((vector_size(32)));
typedef uint32_t uint8v __attribute__((vector_size(32)));
typedef double double4 __attribute__((vector_size(32)));
typedef int64_t long4 __attribute__((vector_size(32)));

/* As in fast_bvh_eight.c: at most seven entries put aside per level of the 8-wide tree. */
#define LEAN_STACK_SIZE ((FAST_BVH_WIDTH_EIGHT - 1) * (BVH_DEEPEST + 1))

/* The bytes of one row of a node's bounds (one bound of one axis, all eight children). */
#define LEAN_ROW_BYTES sizeof(((const struct fast_bvh_node8 *)NULL)->bounds[0][0])
/* An axis's two rows start at a multiple of twice that, so near ^ LEAN_ROW_BYTES is the other row. */
_Static_assert(LEAN_ROW_BYTES == 32, "a row is eight floats, a power of two bytes");

/* A child slot's number fits in a key's lowest three bits (sort8). */
#define LEAN_SLOT_BITS 7u

/* A subtree put aside, with the float distance at which the ray enters its box. */
struct lean_stack_entry {
    uint32_t child, count;
    float entry;
};

/* What the walk of one ray needs, made once: rung 6's float origin and 1 / direction in eight lanes,
 * which bound of each axis is the near one, and for the triangles the ray's origin and shear in four
 * lanes, in the ray's own axes (kx, ky, kz of struct triangle_ray), and where a block holds the
 * corners' coordinates on those axes. */
struct lean_ray {
    float8 origin[3], inverse[3];
    size_t near[3]; /* each axis's near bounds' byte offset in a node; the far ones' is near ^ LEAN_ROW_BYTES */
    double4 o[3], sx, sy, sz;
    size_t axis[3]; /* where corner a's coordinates on the ray's x, y and z axes are in a block */
    struct float_triangle_ray8 exact; /* rung 11: the ray for the float triangle test */
};

static inline AVX2 float8 broadcast8(float x) { return (float8){x, x, x, x, x, x, x, x}; }
static inline AVX2 double4 broadcast4(double x) { return (double4){x, x, x, x}; }

/* The four doubles at p, which is 32-byte aligned. */
static inline AVX2 double4 load4d(const double *p) { return _mm256_load_pd(p); }

/* Bit k of the result is set when lane k of the comparison result m is true. */
static inline AVX2 unsigned lanes8_true(int8v m) { return (unsigned)_mm256_movemask_ps((__m256)m); }
static inline AVX2 unsigned lanes4d_true(long4 m) { return (unsigned)_mm256_movemask_pd((__m256d)m); }

/* One axis of children_hit: the slab's entry and exit distances of all eight children, folded into
 * *enter and *leave. */
/* TASK 11.1 ALSO: one axis of the slab tests of all eight children at once, in float (rung 9) */
static inline AVX2 __attribute__((always_inline)) void slab(const char *bounds, const struct lean_ray *l, int a,
                                                            float8 *enter, float8 *leave) {
    float8 t0 = (_mm256_load_ps((const float *)(bounds + l->near[a])) - l->origin[a]) * l->inverse[a];
    float8 t1 =
        (_mm256_load_ps((const float *)(bounds + (l->near[a] ^ LEAN_ROW_BYTES))) - l->origin[a]) * l->inverse[a];
    *enter = _mm256_max_ps(t0, *enter); /* a NaN in t0 gives enter, as in max4 */
    *leave = _mm256_min_ps(t1, *leave);
}

/* The slab test on all eight children of n, as children_hit8 in fast_bvh_eight.c: a mask holding every
 * child the exact test would find in [t_near, t_far], and the computed entry distances in *entry. */
/* TASK 11.1 ALSO: the slab tests of all eight children at once, in float (rung 9) */
static inline AVX2 unsigned children_hit(const struct fast_bvh_node8 *n, const struct lean_ray *l,
                                         const struct float_setup *f, float t_near, float t_far, float8 *entry) {
    float8 enter = broadcast8(t_near), leave = broadcast8(t_far);
    const char *bounds = (const char *)n->bounds;
    slab(bounds, l, 0, &enter, &leave); /* the three axes written out: the compiler did not unroll the loop */
    slab(bounds, l, 1, &enter, &leave);
    slab(bounds, l, 2, &enter, &leave);
    *entry = enter;
    float8 reach = (leave + f->slack) * FAST_BVH_FLOAT_SCALE + f->slack2;
    return lanes8_true(enter <= reach);
}

/* One step of sort8: each lane compared with lane partner[lane], keeping the larger where take_larger
 * is set and the smaller elsewhere. */
static inline AVX2 uint8v compare_exchange(uint8v x, uint8v partner, uint8v take_larger) {
    __m256i y = _mm256_permutevar8x32_epi32((__m256i)x, (__m256i)partner);
    __m256i smaller = _mm256_min_epu32((__m256i)x, y), larger = _mm256_max_epu32((__m256i)x, y);
    return (uint8v)_mm256_blendv_epi8(smaller, larger, (__m256i)take_larger);
}

/* The eight keys in increasing order, by Batcher's bitonic network: six fixed steps, no branch. */
static inline AVX2 uint8v sort8(uint8v x) {
    const uint8v next = {1, 0, 3, 2, 5, 4, 7, 6}, second = {2, 3, 0, 1, 6, 7, 4, 5}, fourth = {4, 5, 6, 7, 0, 1, 2, 3};
    const uint32_t L = UINT32_MAX;
    x = compare_exchange(x, next, (uint8v){0, L, L, 0, 0, L, L, 0});
    x = compare_exchange(x, second, (uint8v){0, 0, L, L, L, L, 0, 0});
    x = compare_exchange(x, next, (uint8v){0, L, 0, L, L, 0, L, 0});
    x = compare_exchange(x, fourth, (uint8v){0, 0, 0, 0, L, L, L, L});
    x = compare_exchange(x, second, (uint8v){0, 0, L, L, 0, 0, L, L});
    return compare_exchange(x, next, (uint8v){0, L, 0, L, 0, L, 0, L});
}

/* The children in `hit` (at least two) nearest first, as slot numbers into order[0 .. hits): each
 * child's key is its entry distance's bits (a float >= 0 orders as its bits do) with the slot in the
 * lowest three, children not hit the largest key. Entries within eight units in the last place of
 * each other may come in either order; the walk's answer does not depend on it. */
static inline AVX2 void children_by_entry8(float8 entry, unsigned hit, uint32_t order[FAST_BVH_WIDTH_EIGHT]) {
    const uint8v slot = {0, 1, 2, 3, 4, 5, 6, 7}, bit = {1, 2, 4, 8, 16, 32, 64, 128};
    uint8v not_hit = (uint8v)(((uint8v){hit, hit, hit, hit, hit, hit, hit, hit} & bit) == 0);
    uint8v keys = (((uint8v)entry & ~LEAN_SLOT_BITS) | slot) | not_hit;
    uint8v sorted = sort8(keys);
    __builtin_memcpy(order, &sorted, sizeof sorted);
}

/* Tests triangles [first, first + count) of the tree for query q, four at a time, each lane with
 * triangle_crossing_prepared's arithmetic (see the top of this file), and hands the hits to
 * leaf_hit_taken. Returns false when the walk should stop, as test_leaf_triangles does. */
static inline AVX2 __attribute__((always_inline)) bool leaf_triangles4(const struct fast_bvh *b,
                                                                       const struct lean_ray *l,
                                                                       uint32_t first, uint32_t count, double t_min,
                                                                       double t_max, enum query kind,
                                                                       struct query_state *q, double *box_max,
                                                                       uint64_t *tests) {
    const double4 zero = broadcast4(0.0);
    *tests += count;
    const size_t corner = fast_bvh_lean_index(0, 1, 0); /* from one corner's coordinates to the next's */
    uint32_t end = first + count;
    for (uint32_t k = first - first % FAST_BVH_LEAN_LANES; k < end; k += FAST_BVH_LEAN_LANES) {
        const double *block = b->lean_corners + fast_bvh_lean_index(k, 0, 0);
        const double *x = block + l->axis[0], *y = block + l->axis[1], *z = block + l->axis[2];
        double4 az = load4d(z) - l->o[2];
        double4 ax = (load4d(x) - l->o[0]) - l->sx * az;
        double4 ay = (load4d(y) - l->o[1]) - l->sy * az;
        double4 bz = load4d(z + corner) - l->o[2];
        double4 bx = (load4d(x + corner) - l->o[0]) - l->sx * bz;
        double4 by = (load4d(y + corner) - l->o[1]) - l->sy * bz;
        double4 cz = load4d(z + 2 * corner) - l->o[2];
        double4 cx = (load4d(x + 2 * corner) - l->o[0]) - l->sx * cz;
        double4 cy = (load4d(y + 2 * corner) - l->o[1]) - l->sy * cz;
        /* triangle_edge_function, three times, and the test of their signs. */
        double4 w_a = bx * cy - by * cx, w_b = cx * ay - cy * ax, w_c = ax * by - ay * bx;
        long4 inside_positive = (w_a >= zero) & (w_b >= zero) & (w_c >= zero);
        long4 inside_negative = (w_a <= zero) & (w_b <= zero) & (w_c <= zero);
        unsigned keep = lanes4d_true(inside_positive | inside_negative);
        if (k < first)
            keep &= ~((1u << (first - k)) - 1u); /* the lanes before the leaf */
        if (end - k < FAST_BVH_LEAN_LANES)
            keep &= (1u << (end - k)) - 1u; /* the lanes past it */
        if (keep == 0)
            continue;
        /* Where an edge function came out 0, its two products rounded alike: the lane's three are redone
         * by triangle_edge_function itself, which then finds the exact signs, and tested again. (A lane
         * outside stays outside: redoing changes only zeros.) */
        for (unsigned tied = keep & lanes4d_true((w_a == zero) | (w_b == zero) | (w_c == zero)); tied != 0;
             tied &= tied - 1) {
            int lane = __builtin_ctz(tied);
            w_a[lane] = triangle_edge_function(bx[lane], by[lane], cx[lane], cy[lane]);
            w_b[lane] = triangle_edge_function(cx[lane], cy[lane], ax[lane], ay[lane]);
            w_c[lane] = triangle_edge_function(ax[lane], ay[lane], bx[lane], by[lane]);
            bool positive = w_a[lane] >= 0.0 && w_b[lane] >= 0.0 && w_c[lane] >= 0.0;
            bool negative = w_a[lane] <= 0.0 && w_b[lane] <= 0.0 && w_c[lane] <= 0.0;
            if (!positive && !negative)
                keep &= ~(1u << lane);
        }
        double4 det = w_a + w_b + w_c;
        keep &= lanes4d_true(det != zero);
        if (keep == 0)
            continue;
        /* triangle_crossing_prepared's t, the same expression lane by lane. */
        double4 t = (w_a * az + w_b * bz + w_c * cz) * l->sz * (broadcast4(1.0) / det);
        for (; keep != 0; keep &= keep - 1) { /* the lanes that cross */
            int lane = __builtin_ctz(keep);
            if (!leaf_hit_taken(kind, t[lane], b->faces[k + (uint32_t)lane], t_min, t_max, q, box_max))
                return false;
        }
    }
    return true;
}

/* Rung 11: tests triangles [first, first + count) of the tree for query q, eight at a time in float
 * (float_triangle_test8): the triangles that the double test surely misses are dropped, and every other
 * one is tested by triangle_crossing_prepared, which decides, and taken by leaf_hit_taken, as on rung 9.
 * Adds to *counts what the float test said. Returns false when the walk should stop. */
static inline AVX2 __attribute__((always_inline)) bool leaf_triangles_float8(
    const struct fast_bvh *b, const struct lean_ray *l, const struct triangle_ray *ready, uint32_t first,
    uint32_t count, double t_min, double t_max, enum query kind, struct query_state *q, double *box_max,
    uint64_t *tests, struct float_triangle_counts *counts) {
    *tests += count;
    counts->tests += count;
    uint32_t end = first + count;
    for (uint32_t k = first - first % FLOAT_TRIANGLE_LANES; k < end; k += FLOAT_TRIANGLE_LANES) {
        struct float_triangle_verdict said =
            float_triangle_test8(b->float_corners + float_triangle_index(k, 0, 0), &l->exact);
        unsigned in_leaf = (1u << FLOAT_TRIANGLE_LANES) - 1u;
        if (k < first)
            in_leaf &= ~((1u << (first - k)) - 1u); /* the lanes before the leaf */
        if (end - k < FLOAT_TRIANGLE_LANES)
            in_leaf &= (1u << (end - k)) - 1u; /* the lanes past it */
        unsigned keep = ~said.sure_miss & in_leaf;
        counts->sure_hits += (uint64_t)__builtin_popcount(said.sure_hit & in_leaf);
        counts->too_close += (uint64_t)__builtin_popcount(keep & ~said.sure_hit);
        for (; keep != 0; keep &= keep - 1) { /* the triangles kept, tested in double */
            uint32_t j = k + (uint32_t)__builtin_ctz(keep);
            const struct bvh_triangle *tri = &b->triangles[j];
            double t, u, v;
            if (triangle_crossing_prepared(tri->a, tri->b, tri->c, ready, &t, &u, &v) &&
                !leaf_hit_taken(kind, t, b->faces[j], t_min, t_max, q, box_max))
                return false;
        }
    }
    return true;
}

/* A ray in four double lanes: x, y, z and a dummy fourth axis with origin 0 and direction 1, which
 * passes every check below, adds no slack and crosses an unbounded slab. Made once per ray for the
 * root's box and the float set-up, which both need 1 / direction. */
struct lean_start {
    double4 origin, direction, inverse;
};

/* r in four lanes, 1 / direction as aabb_inverse_direction has it. */
static inline AVX2 void lean_start_make(const ray *r, struct lean_start *s) {
    s->origin = (double4){r->origin.x, r->origin.y, r->origin.z, 0.0};
    s->direction = (double4){r->direction.x, r->direction.y, r->direction.z, 1.0};
    s->inverse = broadcast4(1.0) / s->direction;
}

/* The largest and the smallest of four doubles, none of them NaN. */
static inline AVX2 double largest4(double4 x) {
    x = _mm256_max_pd(x, _mm256_permute4x64_pd(x, 0x4E)); /* lanes 0, 1 against 2, 3 */
    return _mm256_cvtsd_f64(_mm256_max_pd(x, _mm256_permute_pd(x, 0x5)));
}
static inline AVX2 double smallest4(double4 x) {
    x = _mm256_min_pd(x, _mm256_permute4x64_pd(x, 0x4E));
    return _mm256_cvtsd_f64(_mm256_min_pd(x, _mm256_permute_pd(x, 0x5)));
}

/* root_box_entered (fast_bvh_walk.h) for the ray s, its three slabs at once: lane by lane the
 * arithmetic of clip_to_slab (aabb.h), so each axis's entry and exit are the same doubles; a NaN (an
 * origin on a slab's plane, the ray running in it) constrains nothing, as there (a maximum or minimum
 * of a NaN and a number gives the number, its second operand); and the largest entry and the smallest
 * exit do not depend on the order they are taken in. So the same answer. Counts one box test. */
static inline AVX2 bool lean_root_entered(const struct fast_bvh *b, const struct lean_start *s, double t_min,
                                          double t_max) {
    stats_thread.box_tests++;
    if (b->tree_count == 0)
        return false;
    const struct aabb *box = &b->root_box;
    double4 lo = {box->min.x, box->min.y, box->min.z, -INFINITY}, hi = {box->max.x, box->max.y, box->max.z, INFINITY};
    double4 t0 = (lo - s->origin) * s->inverse, t1 = (hi - s->origin) * s->inverse;
    long4 swapped = s->inverse < broadcast4(0.0);
    double4 enter = (double4)(((long4)t1 & swapped) | ((long4)t0 & ~swapped));
    double4 leave = (double4)(((long4)t0 & swapped) | ((long4)t1 & ~swapped));
    enter = _mm256_max_pd(enter, broadcast4(t_min > -DBL_MAX ? t_min : -DBL_MAX)); /* NaN: the window's end */
    leave = _mm256_min_pd(leave, broadcast4(t_max < DBL_MAX ? t_max : DBL_MAX));
    return largest4(enter) <= smallest4(leave);
}

/* Rung 6's float set-up (float_setup_make in fast_bvh_walk.h) of the ray s, for the three axes at once:
 * the same operations lane by lane, so the same float origin, the same float 1 / direction and the same
 * slack, written into the boxes' half of *l and into f->slack and f->slack2 (f's other fields are not
 * used by this walk). Returns false where float_setup_make would. */
static inline AVX2 bool lean_float_setup(const struct fast_bvh *b, const struct lean_start *s, double t_min,
                                         struct lean_ray *l, struct float_setup *f) {
    if (!b->float_range || !(t_min >= 0.0 && t_min <= FAST_BVH_FLOAT_RANGE))
        return false;
    const double4 zero = broadcast4(0.0), range = broadcast4(FAST_BVH_FLOAT_RANGE);
    const long4 magnitude = {INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX}; /* all bits but the sign */
    double4 origin = s->origin, direction = s->direction, inverse = s->inverse;
    __m128 rounded = _mm256_cvtpd_ps((__m256d)origin), inverse_f = _mm256_cvtpd_ps((__m256d)inverse);
    double4 shift = (double4)((long4)(origin - (double4)_mm256_cvtps_pd(rounded)) & magnitude); /* fabs */
    double4 size = (double4)((long4)inverse & magnitude);
    long4 flat = direction == zero;
    long4 fits = ((double4)((long4)origin & magnitude) <= range) &
                 ((flat & (shift == zero)) | (~flat & (size >= 1.0 / range) & (size <= range)));
    if (lanes4d_true(fits) != 0xFu)
        return false;
    double4 axis_slack = (double4)((long4)(FAST_BVH_FLOAT_SLACK_FACTOR * shift * size) & ~flat);
    double slack = 0.0;
    unsigned negative = (unsigned)_mm_movemask_ps(inverse_f); /* bit a: 1 / direction < 0 on axis a */
    #pragma GCC unroll 3
    for (int a = 0; a < 3; a++) {
        slack = axis_slack[a] > slack ? axis_slack[a] : slack;
        l->origin[a] = broadcast8(rounded[a]);
        l->inverse[a] = broadcast8(inverse_f[a]);
        l->near[a] = LEAN_ROW_BYTES * (2 * (size_t)a + (negative >> a & 1u)); /* the bound it enters by */
    }
    f->slack = float_at_least(slack); /* at least FLT_MIN: the floor for a product that underflows */
    f->slack2 = 2.0f * f->slack;
    return true;
}

/* The triangles' half of *l (rung 9's double lanes) from *ready, the ray made ready for
 * triangle_crossing_prepared. */
static inline AVX2 __attribute__((always_inline)) void lean_ray_triangles(const struct triangle_ray *ready,
                                                                          struct lean_ray *l) {
    const int axis[3] = {ready->kx, ready->ky, ready->kz};
    #pragma GCC unroll 3
    for (int a = 0; a < 3; a++) {
        l->o[a] = broadcast4(vec3_axis(ready->ray.origin, axis[a]));
        l->axis[a] = fast_bvh_lean_index(0, 0, axis[a]);
    }
    l->sx = broadcast4(ready->sx);
    l->sy = broadcast4(ready->sy);
    l->sz = broadcast4(ready->sz);
}

/* Makes *ready for r and the triangles' half of *l from it: rung 9's double lanes, or with `exact` rung
 * 11's float ray over b. */
static inline AVX2 __attribute__((always_inline)) void lean_ray_ready(const struct fast_bvh *b, const ray *r,
                                                                      bool exact, struct triangle_ray *ready,
                                                                      struct lean_ray *l) {
    *ready = triangle_ray_make(r);
    if (exact) {
        struct float_triangle_ray exact_ray;
        float_triangle_ray_make(ready, &b->root_box, &exact_ray);
        float_triangle_ray_spread(&exact_ray, &l->exact);
        return;
    }
    lean_ray_triangles(ready, l);
}

/* Where a walk is: the subtree it is at, the subtrees put aside, and how far one may be entered. */
struct lean_walk {
    uint32_t child, count;
    int top;
    float limit; /* the window's reach (struct walk_window's limit, a float) */
    struct lean_stack_entry stack[LEAN_STACK_SIZE];
};

/* Visits node s->child: tests its children's boxes and goes down into the nearest one hit (for
 * QUERY_CLOSEST; else the first in slot order), putting the others aside. Returns false when the ray
 * enters none. */
static inline AVX2 __attribute__((always_inline)) bool node_step(const struct fast_bvh *b, const struct lean_ray *l,
                                                                 const struct float_setup *f,
                                                                 const struct walk_window *w, enum query kind,
                                                                 struct lean_walk *s, uint64_t *boxes) {
    const struct fast_bvh_node8 *n = &b->nodes8[s->child];
    uint8v slots;
    __builtin_memcpy(&slots, n->child, sizeof slots);
    unsigned used = lanes8_true((int8v)(slots != FAST_BVH_NO_CHILD));
    float8 enter;
    unsigned hit = children_hit(n, l, f, w->float_min, w->float_max, &enter) & used;
    *boxes += (uint64_t)__builtin_popcount(used);
    if (hit == 0)
        return false;
    uint32_t first;
    if ((hit & (hit - 1)) == 0) { /* one child */
        first = (uint32_t)__builtin_ctz(hit);
    } else if (kind == QUERY_CLOSEST) { /* nearest first, the others put aside farthest deepest */
        uint32_t order[FAST_BVH_WIDTH_EIGHT];
        children_by_entry8(enter, hit, order);
        for (int i = __builtin_popcount(hit) - 1; i > 0; i--) {
            uint32_t k = order[i] & LEAN_SLOT_BITS;
            s->stack[s->top++] = (struct lean_stack_entry){n->child[k], n->count[k], enter[k]};
        }
        first = order[0] & LEAN_SLOT_BITS;
    } else { /* in slot order, as rung 8 */
        for (unsigned rest = hit; rest & (rest - 1); rest &= ~(1u << (31 - __builtin_clz(rest)))) {
            uint32_t k = (uint32_t)(31 - __builtin_clz(rest));
            s->stack[s->top++] = (struct lean_stack_entry){n->child[k], n->count[k], enter[k]};
        }
        first = (uint32_t)__builtin_ctz(hit);
    }
    s->child = n->child[first];
    s->count = n->count[first];
    return true;
}

/* Takes the most recent subtree put aside that the ray may still enter, dropping those beyond the
 * window's reach without touching them (as stack_pop_within in fast_bvh_walk.h). Returns false when
 * none is left. */
static inline AVX2 bool lean_pop(struct lean_walk *s) {
    while (s->top > 0) {
        const struct lean_stack_entry *e = &s->stack[--s->top];
        if (e->entry <= s->limit) {
            s->child = e->child;
            s->count = e->count;
            return true;
        }
    }
    return false;
}

/* The walk of rung 8 (fast_bvh_eight.c's traverse8) for one query, on a ray whose float set-up
 * lean_float_setup has made into the boxes' half of *l and f. */
static inline AVX2 __attribute__((always_inline)) bool traverse_lean(const struct fast_bvh *b, const ray *r,
                                                                     double t_min, double t_max, enum query kind,
                                                                     bool exact, struct lean_ray *l,
                                                                     const struct float_setup *f,
                                                                     struct query_state *q) {
    q->found = false;
    q->t = t_max;
    double box_min = t_min > -DBL_MAX ? t_min : -DBL_MAX; /* as in fast_bvh.c's traverse */
    double box_max = t_max < DBL_MAX ? t_max : DBL_MAX;
    uint64_t visits = 0, boxes = 0, tests = 0;
    bool running = true;
    if (b->triangle_count > b->tree_count) { /* the slivers, outside the tree */
        struct triangle_ray ready = triangle_ray_make(r);
        running = test_leaf_triangles(b, &ready, (uint32_t)b->tree_count, (uint32_t)(b->triangle_count - b->tree_count),
                                      t_min, t_max, kind, false, q, &box_max, &tests);
    }
    struct walk_window w = window_up_to(f, float_at_most(box_min), box_max);
    struct lean_walk s;
    s.child = b->root_child;
    s.count = b->root_count;
    s.top = 0;
    s.limit = (float)w.limit;
    /* The root's box: tested by fast_bvh_lean_traverse when no sliver lies outside the tree; else not at
     * all, the first node's test of its children's boxes deciding as much. */
    running = running && b->tree_count > 0;
    /* Down to the first leaf, before the triangles' set-up: many rays reach none. */
    while (running && s.count == 0) {
        visits++;
        running = node_step(b, l, f, &w, kind, &s, &boxes) || lean_pop(&s);
    }
    if (!running) {
        walk_counted(visits, boxes, tests);
        return q->found;
    }
    struct triangle_ray ready;
    lean_ray_ready(b, r, exact, &ready, l);
    struct float_triangle_counts counts = {0, 0, 0};
    while (running) {
        visits++;
        if (s.count == 0) {
            if (node_step(b, l, f, &w, kind, &s, &boxes))
                continue;
        } else {
            bool go_on = exact ? leaf_triangles_float8(b, l, &ready, s.child, s.count, t_min, t_max, kind, q,
                                                       &box_max, &tests, &counts)
                               : leaf_triangles4(b, l, s.child, s.count, t_min, t_max, kind, q, &box_max, &tests);
            if (!go_on)
                break;
            if (kind == QUERY_CLOSEST && box_max < w.limit_for) { /* a nearer hit: narrow the window */
                w = window_up_to(f, w.float_min, box_max);
                s.limit = (float)w.limit;
            }
        }
        running = lean_pop(&s);
    }
    walk_counted(visits, boxes, tests);
    if (exact) {
        float_triangle_thread.tests += counts.tests;
        float_triangle_thread.sure_hits += counts.sure_hits;
        float_triangle_thread.too_close += counts.too_close;
    }
    return q->found;
}

/* traverse_lean specialised for each query, and for rung 11's float triangle test when b has its float
 * copy of the triangles; a ray rung 6's bound does not cover goes to rung 8 (in double). Not inlined, so
 * that a ray fast_bvh_lean_traverse sends away does not pay for this one's frame (its stack). */
static AVX2 __attribute__((noinline)) bool lean_walk(const struct fast_bvh *b, const ray *r,
                                                     const struct lean_start *start, double t_min, double t_max,
                                                     enum query kind, struct query_state *q) {
    struct float_setup f;
    struct lean_ray l;
    if (!lean_float_setup(b, start, t_min, &l, &f))
        return fast_bvh_eight_traverse(b, r, t_min, t_max, kind, q);
    if (b->float_corners != NULL) { /* rung 11 */
        switch (kind) {
        case QUERY_CLOSEST:
            return traverse_lean(b, r, t_min, t_max, QUERY_CLOSEST, true, &l, &f, q);
        case QUERY_ANY:
            return traverse_lean(b, r, t_min, t_max, QUERY_ANY, true, &l, &f, q);
        default:
            return traverse_lean(b, r, t_min, t_max, QUERY_ALL, true, &l, &f, q);
        }
    }
    switch (kind) {
    case QUERY_CLOSEST:
        return traverse_lean(b, r, t_min, t_max, QUERY_CLOSEST, false, &l, &f, q);
    case QUERY_ANY:
        return traverse_lean(b, r, t_min, t_max, QUERY_ANY, false, &l, &f, q);
    default:
        return traverse_lean(b, r, t_min, t_max, QUERY_ALL, false, &l, &f, q);
    }
}

AVX2 bool fast_bvh_lean_leaf_closest(const struct fast_bvh *b, const struct triangle_ray *ready, uint32_t first,
                                     uint32_t count, double t_min, double t_max, struct query_state *q,
                                     double *box_max, uint64_t *tests) {
    struct lean_ray l;
    lean_ray_triangles(ready, &l);
    return leaf_triangles4(b, &l, first, count, t_min, t_max, QUERY_CLOSEST, q, box_max, tests);
}

AVX2 bool fast_bvh_lean_leaf_any(const struct fast_bvh *b, const struct triangle_ray *ready, uint32_t first,
                                 uint32_t count, double t_min, double t_max, struct query_state *q, uint64_t *tests) {
    struct lean_ray l;
    lean_ray_triangles(ready, &l);
    double box_max = t_max; /* not used by QUERY_ANY */
    return leaf_triangles4(b, &l, first, count, t_min, t_max, QUERY_ANY, q, &box_max, tests);
}

AVX2 bool fast_bvh_lean_traverse(const struct fast_bvh *b, const ray *r, double t_min, double t_max,
                                 enum query kind, struct query_state *q) {
    /* Most rays of a frame miss the model. One slab test of the root's box in double, the test rung 8 and
     * fast_bvh.c's walk begin with, sends them away for a fraction of the float set-up and the first node
     * they would otherwise pay for (when no sliver lies outside the tree). Its 1 / direction is the set-up's. */
    struct lean_start start;
    lean_start_make(r, &start);
    if (root_box_tested_first(b) && !lean_root_entered(b, &start, t_min, t_max)) {
        q->found = false;
        q->t = t_max;
        return false;
    }
    return lean_walk(b, r, &start, t_min, t_max, kind, q);
}

#else /* not x86: no AVX2, and rung 9 is always rung 6 */

bool fast_bvh_lean_leaf_closest(const struct fast_bvh *b, const struct triangle_ray *ready, uint32_t first,
                                uint32_t count, double t_min, double t_max, struct query_state *q, double *box_max,
                                uint64_t *tests) {
    (void)b, (void)ready, (void)first, (void)count, (void)t_min, (void)t_max, (void)box_max, (void)tests;
    q->found = false;
    abort(); /* never called: the build makes no 8-wide tree without AVX2 */
}

bool fast_bvh_lean_leaf_any(const struct fast_bvh *b, const struct triangle_ray *ready, uint32_t first, uint32_t count,
                            double t_min, double t_max, struct query_state *q, uint64_t *tests) {
    (void)b, (void)ready, (void)first, (void)count, (void)t_min, (void)t_max, (void)tests;
    q->found = false;
    abort(); /* never called: the build makes no 8-wide tree without AVX2 */
}

bool fast_bvh_lean_traverse(const struct fast_bvh *b, const ray *r, double t_min, double t_max, enum query kind,
                            struct query_state *q) {
    (void)b, (void)r, (void)t_min, (void)t_max, (void)kind;
    q->found = false;
    abort(); /* never called: the build makes no 8-wide tree without AVX2 */
}

#endif

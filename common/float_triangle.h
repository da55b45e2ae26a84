/* float_triangle.h: rung 11's exact float triangle filter: the watertight test in float, eight triangles
 * at once, with bounds on its rounding that say for each triangle "the double test misses it for sure",
 * "the double test hits it for sure" or "too close to call" (chapter 11).
 *
 * The tracer's triangle test (triangle_crossing_prepared, triangle.h) works in double, and every rung must
 * give its answers to the last bit. Rung 11 runs the same test in float first, on a float copy of the
 * tree's triangles: the shear of Woop, Benthin and Wald, then the three edge functions. Each float edge
 * function lies within a bound E of the double one (derived below, as pbrt derives its bounds); so an
 * edge function above E is positive in double too, and one below -E negative (the double test recomputes
 * only an edge function that comes out 0, which a float one beyond E never meets). A triangle with one edge
 * function surely positive and another surely negative is missed by the double test: it is dropped.
 * Every other triangle is tested again by triangle_crossing_prepared, which gives t, u and v: the float
 * test decides only which triangles need no double test, never an answer.
 *
 * The bound. u = 2^-24 is float's unit roundoff and gamma(n) = n u / (1 - n u); a result computed with
 * n roundings, each a factor (1 + d) with |d| <= u, is within gamma(n) of exact (Higham, and pbrt 4th
 * edition, section 6.8). Let A be, on each axis, the largest |coordinate| of the tree's corners (the
 * root box's) plus |origin|: every difference corner - origin is at most A.
 *  - A corner rounded to float and the origin rounded to float move their difference by at most
 *    u (|corner| + |origin|) <= u A together, and rounding the difference by u (1 + u) A more: the float
 *    p' = corner - origin is within gamma(2) A of exact (translation is the step pbrt need not bound:
 *    its corners are floats already; ours are doubles).
 *  - The shear x = p'x - sx p'z with sx rounded to float, its product and its difference rounded: the
 *    float x is within gamma(3) Ax + gamma(5) |sx| Az of the exact x (of the double sx); the double test
 *    is itself within gamma_double(3) (Ax + |sx| Az) of exact, less than one float unit more, so
 *        |float x - double x| <= DX = gamma(4) Ax + gamma(6) |sx| Az     (and DY likewise),
 *    as pbrt's deltaX = gamma(5) (maxX + maxZ).
 *  - An edge function w = bx cy - by cx, two products and a difference: with MX, MY the largest |x|, |y|
 *    of the triangle's float corners, each product is off by at most MX DY + DX MY + DX DY from the
 *    exact one and rounds within gamma(2) of itself; adding the double test's own error (a unit of
 *    double, again less than a float unit) gives
 *        |float w - double w| <= E = 2 gamma(3) MX MY + 2 (MX DY + DX MY) + 8 DX DY,
 *    which is pbrt's deltaE = 2 (gamma(2) maxX maxY + deltaY maxX + deltaX maxY) with the translation's
 *    and the double test's error added.
 * E is computed in float too, rounding down at worst four times per term: FLOAT_TRIANGLE_BOUND_SCALE
 * covers that. Products that underflow lose up to 2^-149 each: FLOAT_TRIANGLE_BOUND_FLOOR covers that.
 * The float values stay far from overflow: the walk takes this path only when rung 6's float range holds
 * (coordinates and origin within 2^60, so every x below 2^62 and every product below 2^125).
 *
 * t is not computed in float: the double test gives it for every triangle not dropped. (A float t
 * with pbrt's deltaT bound could skip the double test of a triangle surely behind the nearest hit so
 * far; chapter 11's lab notes, docs/fast-notes.md, say why rung 11 does not.) */
#ifndef WHITTED_FLOAT_TRIANGLE_H
#define WHITTED_FLOAT_TRIANGLE_H

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "aabb.h"
#include "fast_bvh_walk.h" /* float_at_least */
#include "fast_bvh_tree.h"
#include "triangle.h"

/* Rung 11's copy of the tree's triangles (b->float_corners): blocks of eight triangles in leaf order
 * (triangles 8 j to 8 j + 7 in block j), each block the nine coordinates (corner a, b, c; axis x, y, z)
 * of its eight triangles side by side, FLOAT_TRIANGLE_BLOCK floats (288 bytes, 32-byte aligned), each
 * the nearest float to the double corner. The last block is padded with zeros. */
#define FLOAT_TRIANGLE_LANES 8
#define FLOAT_TRIANGLE_BLOCK (9 * FLOAT_TRIANGLE_LANES)

/* Float's unit roundoff u = 2^-24, and gamma(n) = n u / (1 - n u), the bound on n roundings. */
#define FLOAT_TRIANGLE_UNIT 0x1p-24
#define FLOAT_TRIANGLE_GAMMA(n) ((n) * FLOAT_TRIANGLE_UNIT / (1.0 - (n) * FLOAT_TRIANGLE_UNIT))

/* The bound's own evaluation in float: each of its terms goes through at most four roundings (two
 * products, then the sums), each at worst a factor (1 - u): scaling by 1 + gamma(5) >= 1 / (1 - u)^4
 * keeps the computed bound at least the true one. */
#define FLOAT_TRIANGLE_BOUND_SCALE (1.0 + FLOAT_TRIANGLE_GAMMA(5))

/* Added to DX, DY and E: covers the absolute error of any float step that underflows (at most 2^-149
 * per product or conversion, a few of them), which the relative model above does not; 2^-126. */
#define FLOAT_TRIANGLE_BOUND_FLOOR FLT_MIN

/* Where corner c's coordinate on axis a of the k-th triangle is in b->float_corners. */
static inline size_t float_triangle_index(size_t k, int c, int a) {
    return k / FLOAT_TRIANGLE_LANES * FLOAT_TRIANGLE_BLOCK + (size_t)(3 * c + a) * FLOAT_TRIANGLE_LANES +
           k % FLOAT_TRIANGLE_LANES;
}

/* What the float test needs of one ray, made once (float_triangle_ray_make): the origin and the shear
 * rounded to float, on the ray's own axes (kx, ky, kz of struct triangle_ray), where a block holds the
 * corners' coordinates on those axes, and the per-ray parts of the bound E = product MX MY + y_term MX
 * + x_term MY + floor (each rounded up to float, scaled by FLOAT_TRIANGLE_BOUND_SCALE). */
struct float_triangle_ray {
    float origin[3];
    float sx, sy;
    size_t axis[3];
    float product, x_term, y_term, floor;
};

/* Makes *f for the ray prepared in *ready, over a tree whose corners all lie in box (within rung 6's
 * float range). Cannot fail; a ray with a NaN shear gives NaN bounds, with which no triangle is dropped.
 * The set-up is computed in double (a dozen roundings of 2^-53 each) and then rounded up to float: the
 * bounds it makes have far more room than that (gamma(4) where gamma(3) plus a double unit is needed: a
 * quarter of DX), so the double roundings need no term of their own. */
static inline void float_triangle_ray_make(const struct triangle_ray *ready, const struct aabb *box,
                                           struct float_triangle_ray *f) {
    const int axis[3] = {ready->kx, ready->ky, ready->kz};
    double reach[3]; /* A on the ray's x, y and z axes: the largest |corner - origin| can be */
    for (int j = 0; j < 3; j++) {
        double origin = vec3_axis(ready->ray.origin, axis[j]);
        double corner = fmax(fabs(vec3_axis(box->min, axis[j])), fabs(vec3_axis(box->max, axis[j])));
        reach[j] = corner + fabs(origin);
        f->origin[j] = (float)origin;
        f->axis[j] = float_triangle_index(0, 0, axis[j]);
    }
    f->sx = (float)ready->sx;
    f->sy = (float)ready->sy;
    double dx = FLOAT_TRIANGLE_GAMMA(4) * reach[0] + FLOAT_TRIANGLE_GAMMA(6) * fabs(ready->sx) * reach[2] +
                FLOAT_TRIANGLE_BOUND_FLOOR;
    double dy = FLOAT_TRIANGLE_GAMMA(4) * reach[1] + FLOAT_TRIANGLE_GAMMA(6) * fabs(ready->sy) * reach[2] +
                FLOAT_TRIANGLE_BOUND_FLOOR;
    /* E = 2 gamma(3) MX MY + 2 DY MX + 2 DX MY + 8 DX DY (+ the floor), each part scaled. */
    f->product = float_at_least(2.0 * FLOAT_TRIANGLE_GAMMA(3) * FLOAT_TRIANGLE_BOUND_SCALE);
    f->y_term = float_at_least(2.0 * dy * FLOAT_TRIANGLE_BOUND_SCALE);
    f->x_term = float_at_least(2.0 * dx * FLOAT_TRIANGLE_BOUND_SCALE);
    f->floor = float_at_least((8.0 * dx * dy + FLOAT_TRIANGLE_BOUND_FLOOR) * FLOAT_TRIANGLE_BOUND_SCALE);
}


/* Makes rung 11's copy of b's triangles (b->float_corners, from b->triangles). Returns false when out
 * of memory (b is then unchanged). */
bool float_triangle_prepare(struct fast_bvh *b);


/* How the float test's triangles went, counted per thread for bench_accel: tests (triangles tested in
 * float), sure_hits (the double test surely hits them: still redone in double, for t) and too_close
 * (neither sure hit nor sure miss: redone in double). The rest were dropped. */
struct float_triangle_counts {
    uint64_t tests, sure_hits, too_close;
};
extern _Thread_local struct float_triangle_counts float_triangle_thread;

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

/* Eight floats, and eight 32-bit integers, what a comparison of floats gives (GCC's vector extension;
 * the same types as fast_bvh_lean.c's). */
typedef float float8 __attribute__((vector_size(32)));
typedef int32_t int8v __attribute__((vector_size(32)));

/* A float ray's parts in all eight lanes, for float_triangle_test8. */
struct float_triangle_ray8 {
    float8 origin[3], sx, sy, product, x_term, y_term, floor;
    size_t axis[3];
};

/* The triangles of one block (eight lanes) as the float test sees them: sure_miss has bit k set when
 * the double test surely misses lane k's triangle, sure_hit when it surely crosses it (all three edge
 * functions surely of one sign). Neither: too close to call. */
struct float_triangle_verdict {
    unsigned sure_miss, sure_hit;
};

static inline __attribute__((target("avx2"), always_inline)) float8 float_triangle_abs8(float8 x) {
    return (float8)((int8v)x & 0x7fffffff);
}

static inline __attribute__((target("avx2"), always_inline)) unsigned float_triangle_lanes(int8v m) {
    return (unsigned)_mm256_movemask_ps((__m256)m);
}

/* The float test of the eight triangles of block (FLOAT_TRIANGLE_BLOCK floats, 32-byte aligned) for the
 * ray f: triangle_crossing_prepared's arithmetic in float (each product rounded on its own), then the
 * edge functions against their bound E (the top of this file). */
static inline __attribute__((target("avx2"), always_inline)) struct float_triangle_verdict
float_triangle_test8(const float *block, const struct float_triangle_ray8 *f) {
    const float8 *x = (const float8 *)(block + f->axis[0]), *y = (const float8 *)(block + f->axis[1]),
                 *z = (const float8 *)(block + f->axis[2]);
    const size_t next = 3; /* from one corner's row to the next corner's, in float8 rows */
    float8 az = z[0] - f->origin[2], bz = z[next] - f->origin[2], cz = z[2 * next] - f->origin[2];
    float8 ax = (x[0] - f->origin[0]) - f->sx * az, ay = (y[0] - f->origin[1]) - f->sy * az;
    float8 bx = (x[next] - f->origin[0]) - f->sx * bz, by = (y[next] - f->origin[1]) - f->sy * bz;
    float8 cx = (x[2 * next] - f->origin[0]) - f->sx * cz, cy = (y[2 * next] - f->origin[1]) - f->sy * cz;
    float8 w_a = bx * cy - by * cx, w_b = cx * ay - cy * ax, w_c = ax * by - ay * bx;
    float8 mx = _mm256_max_ps(_mm256_max_ps(float_triangle_abs8(ax), float_triangle_abs8(bx)), float_triangle_abs8(cx));
    float8 my = _mm256_max_ps(_mm256_max_ps(float_triangle_abs8(ay), float_triangle_abs8(by)), float_triangle_abs8(cy));
    float8 e = (f->product * mx * my + f->y_term * mx) + (f->x_term * my + f->floor);
    float8 minus_e = -e;
    int8v positive_a = w_a > e, positive_b = w_b > e, positive_c = w_c > e;
    int8v negative_a = w_a < minus_e, negative_b = w_b < minus_e, negative_c = w_c < minus_e;
    unsigned some_positive = float_triangle_lanes(positive_a | positive_b | positive_c);
    unsigned some_negative = float_triangle_lanes(negative_a | negative_b | negative_c);
    unsigned all_positive = float_triangle_lanes(positive_a & positive_b & positive_c);
    unsigned all_negative = float_triangle_lanes(negative_a & negative_b & negative_c);
    return (struct float_triangle_verdict){some_positive & some_negative, all_positive | all_negative};
}

/* f in eight lanes. */
static inline __attribute__((target("avx2"), always_inline)) void float_triangle_ray_spread(
    const struct float_triangle_ray *f, struct float_triangle_ray8 *f8) {
    for (int a = 0; a < 3; a++) {
        f8->origin[a] = (float8){0} + f->origin[a];
        f8->axis[a] = f->axis[a];
    }
    f8->sx = (float8){0} + f->sx;
    f8->sy = (float8){0} + f->sy;
    f8->product = (float8){0} + f->product;
    f8->x_term = (float8){0} + f->x_term;
    f8->y_term = (float8){0} + f->y_term;
    f8->floor = (float8){0} + f->floor;
}

#endif

#endif

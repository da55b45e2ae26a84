/* float4.h: what chapter 11's float boxes are made of: four floats processed by one instruction, and
 * doubles rounded outward to float (chapter 11).
 *
 * Header-only, so that the build (fast_bvh_build.c) and the walk (fast_bvh.c) inline the same
 * arithmetic in their hot loops. */
#ifndef WHITTED_FLOAT4_H
#define WHITTED_FLOAT4_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

/* GCC's vector extension: four floats processed by one instruction (SSE on x86-64), and four 32-bit
 * integers, what a comparison of two float4 gives (all bits set where true). */
typedef float float4 __attribute__((vector_size(16)));
typedef int32_t int4 __attribute__((vector_size(16)));

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

/* The four floats at p, which is 16-byte aligned: one load. */
static inline float4 load4(const float *p) {
#if defined(__SSE__)
    return _mm_load_ps(p);
#else
    return (float4){p[0], p[1], p[2], p[3]};
#endif
}

/* Bit k of the result is set when lane k of the comparison result m is true. */
static inline unsigned lanes4_true(int4 m) {
#if defined(__SSE__)
    return (unsigned)_mm_movemask_ps((__m128)m);
#else
    return (unsigned)(m[0] & 1) | (unsigned)(m[1] & 2) | (unsigned)(m[2] & 4) | (unsigned)(m[3] & 8);
#endif
}

/* The float one step below f and one step above it, for f not a NaN (and, below, not -infinity; above,
 * not infinity): nextafterf(f, -INFINITY) and nextafterf(f, INFINITY), without a call into the maths
 * library. A finite float's neighbours are one step of its bit pattern away: the next integer down
 * for a positive float is the next smaller float, for a negative one the next larger in size. Zero's
 * neighbours are the smallest subnormals, of either sign. */
static inline float float_step_down(float f) {
    if (f == 0.0f)
        return -FLT_TRUE_MIN;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits = f > 0.0f ? bits - 1 : bits + 1;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static inline float float_step_up(float f) {
    if (f == 0.0f)
        return FLT_TRUE_MIN;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits = f > 0.0f ? bits + 1 : bits - 1;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* The largest float <= x and the smallest float >= x: a float box built from these holds the double
 * box exactly. A NaN (from a corner at infinity) gives the infinity on the safe side, so that no NaN
 * reaches a box. */
static inline float float_below(double x) {
    if (isnan(x))
        return -INFINITY; /* a corner beyond double's range: a box open on that side holds it */
    float f = (float)x;
    return (double)f > x ? float_step_down(f) : f;
}

static inline float float_above(double x) {
    if (isnan(x))
        return INFINITY;
    float f = (float)x;
    return (double)f < x ? float_step_up(f) : f;
}

#endif

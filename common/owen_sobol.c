/* owen_sobol.c: a (0,2)-sequence with Owen's nested scrambling, by hashing (chapter 15; owen_sobol.h). */
#include "owen_sobol.h"

/* 2^-32: a 32-bit binary fraction as a number in [0, 1). */
#define OWEN_SOBOL_UNIT 0x1.0p-32

/* The bits of x in the opposite order (bit 0 to bit 31 and back). */
static inline uint32_t reverse_bits(uint32_t x) {
    x = (x >> 1 & 0x55555555u) | (x & 0x55555555u) << 1;
    x = (x >> 2 & 0x33333333u) | (x & 0x33333333u) << 2;
    x = (x >> 4 & 0x0f0f0f0fu) | (x & 0x0f0f0f0fu) << 4;
    x = (x >> 8 & 0x00ff00ffu) | (x & 0x00ff00ffu) << 8;
    return x >> 16 | x << 16;
}

/* A hash in which bit k of the result depends on the seed and on bits 0 to k of x only (a product
 * carries upwards, never down): the Laine-Karras permutation with Burley's constants. On the
 * bit-reversed fraction that is Owen's rule, each bit decided by the bits above it. */
static inline uint32_t laine_karras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

uint32_t owen_sobol_scramble(uint32_t x, uint32_t seed) { return reverse_bits(laine_karras(reverse_bits(x), seed)); }

/* Sobol's second dimension, bit-reversed: its generator matrix is Pascal's triangle modulo 2, so by
 * Lucas' theorem bit j of the result is the parity of the bits k of the index for which k contains j (k & j
 * = j), summed here over the five bits of j one at a time. (Sobol's first dimension, bit-reversed, is the
 * index itself.) */
static inline uint32_t sobol_second_reversed(uint32_t index) {
    uint32_t x = index;
    x ^= x >> 1 & 0x55555555u;
    x ^= x >> 2 & 0x33333333u;
    x ^= x >> 4 & 0x0f0f0f0fu;
    x ^= x >> 8 & 0x00ff00ffu;
    x ^= x >> 16 & 0x0000ffffu;
    return x;
}

void owen_sobol_point(uint32_t index, const struct owen_sobol_seeds *seeds, double *u, double *v) {
    uint32_t shuffled = owen_sobol_scramble(index, seeds->order);
    /* owen_sobol_scramble(reverse_bits(r)) = reverse_bits(laine_karras(r)): the two reversals cancel */
    *u = reverse_bits(laine_karras(shuffled, seeds->first)) * OWEN_SOBOL_UNIT;
    *v = reverse_bits(laine_karras(sobol_second_reversed(shuffled), seeds->second)) * OWEN_SOBOL_UNIT;
}

double owen_sobol_value(uint32_t index, const struct owen_sobol_seeds *seeds) {
    return reverse_bits(laine_karras(owen_sobol_scramble(index, seeds->order), seeds->first)) * OWEN_SOBOL_UNIT;
}

/* sample_hash.h: random numbers that depend only on where they are used (chapter 12).
 *
 * Jittered sampling needs random numbers, and a picture that is the same for any thread count needs
 * numbers that do not depend on which thread asked first. A generator with state (rand, a shared
 * seed advanced on every call) cannot give both. A counter-based generator can: the number for sample
 * `index` of pixel (x, y) under `seed` is a hash of those four numbers, computed afresh wherever it is
 * wanted, so any pixel's samples can be made alone, in any order, and always come out the same. */
#ifndef WHITTED_SAMPLE_HASH_H
#define WHITTED_SAMPLE_HASH_H

#include <stdint.h>

/* Returns 64 well-mixed bits for (x, y, index, seed): every input bit changes about half the output
 * bits. Cannot fail. */
uint64_t sample_hash(uint32_t x, uint32_t y, uint32_t index, uint32_t seed);

/* Returns a number in [0, 1) from the top 53 bits of sample_hash(x, y, index, seed): uniform over
 * the 2^53 doubles k / 2^53. Cannot fail. */
double sample_hash_unit(uint32_t x, uint32_t y, uint32_t index, uint32_t seed);

#endif

/* uniform.h: reproducible random numbers for the tests of chapter 16's geometry (transforms, motion
 * boxes, the instance BVH): the k-th number of a stream, from the counter-based hash the renderer uses
 * (sample_hash.h), so that a failing case can be rerun alone. */
#ifndef WHITTED_TEST_UNIFORM_H
#define WHITTED_TEST_UNIFORM_H

#include <stdint.h>

#include "sample_hash.h"
#include "vec3.h"

/* The seed of these streams: any fixed number. */
#define UNIFORM_SEED 16u

/* Returns the k-th number of stream `stream`, uniform in [lo, hi). */
static inline double uniform(uint32_t stream, uint32_t k, double lo, double hi) {
    return lo + (hi - lo) * sample_hash_unit(k, stream, 0, UNIFORM_SEED);
}

/* Returns the k-th vector of stream `stream`, each coordinate uniform in [lo, hi). */
static inline vec3 uniform_vec3(uint32_t stream, uint32_t k, double lo, double hi) {
    return vec3_make(uniform(stream, 3 * k, lo, hi), uniform(stream, 3 * k + 1, lo, hi),
                     uniform(stream, 3 * k + 2, lo, hi));
}

#endif

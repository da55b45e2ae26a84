/* sample_hash.c: a counter-based hash for jittered samples, two rounds of a 64-bit mixer (chapter 12). */
#include "sample_hash.h"

#define GOLDEN_GAMMA 0x9e3779b97f4a7c15u /* 2^64 / golden ratio: spreads consecutive counters apart */

/* A bijection of 64-bit words in which each input bit flips each output bit with probability close
 * to one half (the finaliser of SplitMix64, Stafford's variant 13). */
static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

uint64_t sample_hash(uint32_t x, uint32_t y, uint32_t index, uint32_t seed) {
    uint64_t where = (uint64_t)x << 32 | y, which = (uint64_t)seed << 32 | index;
    return mix(mix(which + GOLDEN_GAMMA) ^ where);
}

double sample_hash_unit(uint32_t x, uint32_t y, uint32_t index, uint32_t seed) {
    return (double)(sample_hash(x, y, index, seed) >> 11) * 0x1.0p-53;
}

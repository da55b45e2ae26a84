/* owen_sobol.h: stratified random numbers for a path tracer: the first two dimensions of Sobol's
 * sequence, a (0,2)-sequence, randomised by Owen's nested scrambling (chapter 15; docs/15-paths.md).
 *
 * Independent random points clump and leave holes: n of them estimate an integral with an error that
 * falls as 1 / sqrt(n). The first 2^m points of a (0,2)-sequence put exactly one point in every cell of
 * every grid of 2^m equal rectangles of the unit square (1 x 2^m, 2 x 2^(m-1), ..., 2^m x 1): they are
 * stratified in every such way at once, and over an integrand with edges (a lamp's border, a shadow)
 * the error falls faster. Used as it is, the sequence is the same in every pixel and the picture shows
 * its pattern; Owen's scrambling flips each bit of each coordinate by a random choice that depends on the
 * bits above it, which keeps the stratification and makes each single point uniformly distributed over
 * the square, so that an estimate from the points stays unbiased. The choices are a hash of a seed
 * (Laine and Karras' hash as Burley improved it, "Practical Hash-based Owen Scrambling", 2020): a pixel
 * and a dimension with their own seed get their own scrambled copy. The order of the points is shuffled
 * too (the index scrambled the same way), so that two copies used together along one path, say the
 * point on the lamp and the scattered direction, are not paired point for point. */
#ifndef WHITTED_OWEN_SOBOL_H
#define WHITTED_OWEN_SOBOL_H

#include <stdint.h>

/* The seeds of one scrambled copy: one for the order of its points, one for each coordinate. */
struct owen_sobol_seeds {
    uint32_t order, first, second;
};

/* Owen's nested scrambling of the 32-bit binary fraction x (bit 31 the halves, bit 30 the quarters, ...)
 * under `seed`: bit k is flipped or not by a hash of the seed and the bits above k. A bijection of the
 * 32-bit words; for a fixed x and a random seed, uniform over them. Cannot fail. */
uint32_t owen_sobol_scramble(uint32_t x, uint32_t seed);

/* Stores in *u and *v, in [0, 1), point `index` of the (0,2)-sequence scrambled with `seeds`. The first
 * 2^m indices give 2^m points, one in each cell of every grid of 2^m equal rectangles. Cannot fail. */
void owen_sobol_point(uint32_t index, const struct owen_sobol_seeds *seeds, double *u, double *v);

/* Returns, in [0, 1), value `index` of the first coordinate alone (the van der Corput sequence, one value
 * in each of 2^m equal intervals among the first 2^m) scrambled with seeds->order and seeds->first. Cannot
 * fail. */
double owen_sobol_value(uint32_t index, const struct owen_sobol_seeds *seeds);

#endif

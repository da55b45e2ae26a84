/* sampling.h: random numbers along a path and the ways of turning them into points and directions that
 * chapter 15 needs: the cosine-weighted hemisphere, a point on a triangle, a point on a sphere
 * (docs/15-paths.md).
 *
 * A path needs many random numbers, one after another, and the picture must not depend on which thread
 * draws them. So a path's numbers are a stream keyed by (pixel, sample, seed) through chapter 12's
 * sample_hash: number k of the stream is a hash of the key and k, computed afresh, never a state shared
 * between paths. Two pixels, two samples of one pixel or two seeds give unrelated streams.
 *
 * A stratified stream (sample_stream_stratified, the paths line's `sampler sobol`) keeps the key but
 * relates the samples of one pixel: number k of samples 0, 1, 2, ... of the pixel are stratified
 * (owen_sobol.h), a (0,2)-sequence over the pixel's samples with the pixel's own scrambling, so that 16
 * samples cover the pixel, the lamp and the hemisphere more evenly than 16 independent draws would. The
 * numbers are grouped as path_sample draws them (path_trace.h): numbers 0 and 1 (the point in the pixel)
 * are one 2D point; from number 2 on they come in threes, a lone number (which emitter, which lobe) and
 * a 2D point (the point on the emitter, the direction). Glass and Russian roulette draw one number more
 * and shift the grouping for the rest of the path: every number is still uniform and every path's
 * estimate unbiased, only less well stratified. Different pixels and seeds remain unrelated. */
#ifndef WHITTED_SAMPLING_H
#define WHITTED_SAMPLING_H

#include <stdbool.h>
#include <stdint.h>

#include "vec3.h"

/* The random numbers of one path: its key and how many it has drawn; a stratified stream its pixel,
 * sample and seed too, and the second coordinate of the 2D point whose first it drew last. */
struct sample_stream {
    uint64_t key;
    uint32_t drawn;
    bool stratified;
    uint32_t x, y, sample, seed;
    double second;
};

/* Returns the stream of sample `sample` of pixel (x, y) under `seed`, none drawn yet: independent numbers.
 * Cannot fail. */
struct sample_stream sample_stream_start(uint32_t x, uint32_t y, uint32_t sample, uint32_t seed);

/* Returns the stratified stream of sample `sample` of pixel (x, y) under `seed`, none drawn yet: its
 * numbers stratified with the same pixel's other samples, as the comment at the top says. Cannot fail. */
struct sample_stream sample_stream_stratified(uint32_t x, uint32_t y, uint32_t sample, uint32_t seed);

/* Returns the stream's next number, uniform in [0, 1), and counts it drawn (a stratified stream's numbers
 * are multiples of 2^-32). Cannot fail. */
double sample_stream_next(struct sample_stream *s);

/* Fills *t and *b so that (t, b, n) is a right-handed orthonormal basis for the unit vector n. */
void sampling_basis(vec3 n, vec3 *t, vec3 *b);

/* Returns a direction about the unit normal n with density cos(theta) / pi over the hemisphere (theta
 * from n), from two uniform numbers: Malley's method, a uniform point of the unit disc lifted onto the
 * hemisphere. The result has unit length and n . result >= 0. */
vec3 sampling_cosine_hemisphere(vec3 n, double u1, double u2);

/* Returns a point uniformly distributed over the triangle a, a + e1, a + e2 (density 1 / area). */
vec3 sampling_triangle(vec3 a, vec3 e1, vec3 e2, double u1, double u2);

/* Returns a unit vector uniformly distributed over the sphere's directions (density 1 / (4 pi)). */
vec3 sampling_sphere_direction(double u1, double u2);

#endif

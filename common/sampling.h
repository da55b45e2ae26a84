/* sampling.h: random numbers along a path and the ways of turning them into points and directions that
 * chapter 15 needs: the cosine-weighted hemisphere, a point on a triangle, a point on a sphere
 * (docs/15-paths.md).
 *
 * A path needs many random numbers, one after another, and the picture must not depend on which thread
 * draws them. So a path's numbers are a stream keyed by (pixel, sample, seed) through chapter 12's
 * sample_hash: number k of the stream is a hash of the key and k, computed afresh, never a state shared
 * between paths. Two pixels, two samples of one pixel or two seeds give unrelated streams. */
#ifndef WHITTED_SAMPLING_H
#define WHITTED_SAMPLING_H

#include <stdint.h>

#include "vec3.h"

/* The random numbers of one path: its key and how many it has drawn. */
struct sample_stream {
    uint64_t key;
    uint32_t drawn;
};

/* Returns the stream of sample `sample` of pixel (x, y) under `seed`, none drawn yet. Cannot fail. */
struct sample_stream sample_stream_start(uint32_t x, uint32_t y, uint32_t sample, uint32_t seed);

/* Returns the stream's next number, uniform in [0, 1), and counts it drawn. Cannot fail. */
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

/* sampling.c: a path's random numbers and the densities chapter 15 draws from (docs/15-paths.md). */
#include "sampling.h"

#include <math.h>

#include "sample_hash.h"

/* The seed word of the second hash that draws a stream's numbers: any fixed value apart from the
 * first's keeps the two hashes unrelated. */
#define SAMPLING_STREAM_SALT 0x51a7e5edu

struct sample_stream sample_stream_start(uint32_t x, uint32_t y, uint32_t sample, uint32_t seed) {
    return (struct sample_stream){sample_hash(x, y, sample, seed), 0};
}

double sample_stream_next(struct sample_stream *s) {
    return sample_hash_unit((uint32_t)s->key, (uint32_t)(s->key >> 32), s->drawn++, SAMPLING_STREAM_SALT);
}

void sampling_basis(vec3 n, vec3 *t, vec3 *b) {
    /* Any vector not parallel to n: the axis along which n is smallest. */
    vec3 other = fabs(n.x) < 0.5 ? vec3_make(1, 0, 0) : fabs(n.y) < 0.5 ? vec3_make(0, 1, 0) : vec3_make(0, 0, 1);
    *t = vec3_normalize(vec3_cross(other, n));
    *b = vec3_cross(n, *t);
}

vec3 sampling_cosine_hemisphere(vec3 n, double u1, double u2) {
    double r = sqrt(u1), phi = 2.0 * M_PI * u2;
    double x = r * cos(phi), y = r * sin(phi), z = sqrt(fmax(0.0, 1.0 - u1));
    vec3 t, b;
    sampling_basis(n, &t, &b);
    return vec3_add_scaled(vec3_add_scaled(vec3_scale(n, z), t, x), b, y);
}

vec3 sampling_triangle(vec3 a, vec3 e1, vec3 e2, double u1, double u2) {
    double root = sqrt(u1); /* the barycentric fold of a unit square onto the triangle */
    return vec3_add_scaled(vec3_add_scaled(a, e1, root * (1.0 - u2)), e2, root * u2);
}

vec3 sampling_sphere_direction(double u1, double u2) {
    double z = 1.0 - 2.0 * u1, r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * u2;
    return vec3_make(r * cos(phi), r * sin(phi), z);
}

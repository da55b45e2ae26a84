/* sampling.c: a path's random numbers and the densities chapter 15 draws from (docs/15-paths.md). */
#include "sampling.h"

#include <math.h>

#include "owen_sobol.h"
#include "sample_hash.h"

/* The seed word of the second hash that draws an independent stream's numbers: any fixed value apart
 * from the first's keeps the two hashes unrelated. */
#define SAMPLING_STREAM_SALT 0x51a7e5edu
/* A word mixed into the seed so that the hash giving a pixel's scrambling seeds is unrelated to other
 * uses of sample_hash with the same pixel and seed (any fixed value). */
#define SAMPLING_SEEDS_SALT 0x0c3a5d17u
/* An odd multiplier (2^32 / golden ratio) that spreads the hash's two halves into a third seed. */
#define SAMPLING_THIRD_SEED 0x9e3779b9u
/* Numbers 0 and 1 of a stream are its first 2D point; after them, groups of this many: a lone number,
 * then a 2D point. */
#define SAMPLING_LEAD 2
#define SAMPLING_GROUP 3

struct sample_stream sample_stream_start(uint32_t x, uint32_t y, uint32_t sample, uint32_t seed) {
    return (struct sample_stream){.key = sample_hash(x, y, sample, seed)};
}

struct sample_stream sample_stream_stratified(uint32_t x, uint32_t y, uint32_t sample, uint32_t seed) {
    return (struct sample_stream){.stratified = true, .x = x, .y = y, .sample = sample, .seed = seed};
}

/* The scrambling seeds of part `part` of the pixel's streams (part 0 the first 2D point, then a lone
 * number and a 2D point in turn), the same for all its samples. */
static struct owen_sobol_seeds part_seeds(const struct sample_stream *s, uint32_t part) {
    uint64_t h = sample_hash(s->x, s->y, part, s->seed ^ SAMPLING_SEEDS_SALT);
    uint32_t low = (uint32_t)h, high = (uint32_t)(h >> 32);
    return (struct owen_sobol_seeds){low, high, (low ^ high) * SAMPLING_THIRD_SEED};
}

double sample_stream_next(struct sample_stream *s) {
    if (!s->stratified)
        return sample_hash_unit((uint32_t)s->key, (uint32_t)(s->key >> 32), s->drawn++, SAMPLING_STREAM_SALT);
    uint32_t k = s->drawn++, part, coordinate;
    if (k < SAMPLING_LEAD)
        part = 0, coordinate = k;
    else {
        uint32_t group = (k - SAMPLING_LEAD) / SAMPLING_GROUP, place = (k - SAMPLING_LEAD) % SAMPLING_GROUP;
        if (place == 0) { /* the lone number */
            struct owen_sobol_seeds seeds = part_seeds(s, 1 + 2 * group);
            return owen_sobol_value(s->sample, &seeds);
        }
        part = 2 + 2 * group, coordinate = place - 1;
    }
    if (coordinate == 1)
        return s->second; /* drawn with the first, one call before */
    struct owen_sobol_seeds seeds = part_seeds(s, part);
    double u;
    owen_sobol_point(s->sample, &seeds, &u, &s->second);
    return u;
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

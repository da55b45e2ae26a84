/* headlight.c: diffuse shading by a white point light at the eye (chapters 2 to 5). */
#include "headlight.h"

vec3 headlight_shade(const struct scene *s, const struct hit *h, vec3 direction) {
    vec3 normal = hit_facing_normal(h, direction);
    double cosine = -vec3_dot(normal, direction); /* the light is where the ray came from: L = -D */
    return vec3_scale(s->materials[h->material].colour, cosine);
}

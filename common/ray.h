/* ray.h: a ray, origin + t * direction, and the distance tolerances every chapter shares (chapter 1).
 *
 * The tolerances are POV-Ray 3.7's, as measured (docs/povray.md), so that our images and
 * POV-Ray's agree pixel for pixel. They are absolute distances in scene units: keep scenes near unit
 * scale (the oracle saw a millimetre-scale scene disagree on 39 of 30,000 pixels). */
#ifndef WHITTED_RAY_H
#define WHITTED_RAY_H

#include "vec3.h"

/* Nearest accepted hit for camera, reflected and refracted rays. Secondary rays start exactly on the
 * surface they leave; hits closer than this are that same surface found again ("acne"). 1e-4 is the
 * value POV-Ray uses. */
#define RAY_T_MIN 1e-4

/* Shadow rays accept blockers only with SHADOW_T_MIN < t < distance_to_light - SHADOW_T_MIN: a
 * larger margin than RAY_T_MIN, again POV-Ray's value (chapter 7 explains the choice). */
#define SHADOW_T_MIN 1e-3

typedef struct ray {
    vec3 origin;
    vec3 direction; /* unit length for every ray the tracer makes */
} ray;

/* Returns the point origin + t * direction. */
static inline vec3 ray_at(ray r, double t) { return vec3_add_scaled(r.origin, r.direction, t); }

#endif

/* phong.h: ambient, diffuse and Phong highlight from point lights: POV-Ray 3.7's exact formula
 * (chapter 6; chapter 7 adds the shadow factor, chapter 8 the opacity).
 *
 * At a point P with normal N turned towards the ray D, material colour C, and for each light at
 * position Lp with colour Lc and unit direction L = (Lp - P) / |Lp - P|:
 *
 *   I = ambient * Ia * C * opacity
 *     + sum over lights with N.L >= PHONG_MIN_COSINE (none for a light at P itself: no L) of
 *           S * Lc * ( diffuse * (N.L) * opacity * C  +  phong * max(0, R.L)^phong_size )
 *
 * where Ia is the scene's ambient light, R = D - 2 (D.N) N the mirror direction of the ray, S the
 * light's shadow factor (1 when unblocked) and opacity = 1 - filter - transmit. The highlight has the
 * light's colour, not the surface's, and is not scaled by opacity: glass still shines. */
#ifndef WHITTED_PHONG_H
#define WHITTED_PHONG_H

#include "scene.h"

/* Lights grazing the surface more flatly than this cosine add nothing, neither diffuse nor highlight:
 * POV-Ray's cut-off, kept so our pictures agree with its pictures at silhouettes. */
#define PHONG_MIN_COSINE 1e-10

/* Returns how much of `light` reaches `point` (per channel, 0..1): the shadow factor S. */
typedef vec3 (*phong_shadow_fn)(const void *world, vec3 point, const struct light *light);

/* Where and what is being shaded. */
struct phong_surface {
    vec3 point;            /* P, on the surface */
    vec3 normal;           /* N, unit, turned to face the incoming ray */
    vec3 direction;        /* D, the unit direction of the incoming ray */
    const struct material *material;
    double opacity;        /* 1 - filter - transmit, or 1 where transparency is not drawn yet */
};

/* Returns the ambient plus the direct light of every light of s at surface `at`. `shadow` gives each
 * light's shadow factor (called only for lights facing the surface); NULL means no shadows. */
vec3 phong_shade(const struct scene *s, const struct phong_surface *at, phong_shadow_fn shadow,
                 const void *world);

/* Returns the colour seen along r in world w (a struct world): the nearest surface shaded with
 * phong_shade (opacity 1), or the background. `shadow` as for phong_shade. */
vec3 phong_trace_nearest(const void *world, const ray *r, phong_shadow_fn shadow);

/* Returns the mirror direction of D about the unit normal N: D - 2 (D.N) N. */
vec3 phong_reflect(vec3 direction, vec3 normal);

#endif

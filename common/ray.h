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

/* ---- limits on a tree of rays (chapter 8; docs/08-recursion.md, "Ray trees that cannot run away") --- */

/* Secondary rays may start from a point far from the origin, where the hit point itself is only known
 * to within an ulp of its coordinates: at 5e12 that is 1e-3, ten times RAY_T_MIN, and the ray would find
 * the surface it leaves again and again. So a secondary ray from point P accepts hits only from
 * ray_t_min(P) = max(RAY_T_MIN, RAY_T_MIN_RELATIVE * largest |coordinate| of P). 1e-9 is about 4.5
 * million ulps, far above any rounding of a hit point, and it equals RAY_T_MIN only at 1e5: every
 * point of a unit-scale scene keeps RAY_T_MIN exactly. */
#define RAY_T_MIN_RELATIVE 1e-9

/* A refraction into the same index (ior 1 in air, glass to glass) bends nothing and, as in POV-Ray,
 * does not use up a level: the ray just goes on. Without another bound, 10,000 clear spheres in a row
 * would be 10,000 crossings for one pixel. A ray that has gone straight through this many surfaces
 * stops (black), and stats.crossings_capped counts it. 1000 is far more than any real scene needs:
 * with transmit 0.9 the weight falls under adc_bailout's 1/255 after 53 crossings. */
#define RAY_MAX_CROSSINGS 1000

/* The most secondary rays (reflected and refracted, pass-throughs included) one camera ray may spawn,
 * the shadow rays of area lights counted among them (chapter 13: 33 x 33 a hit at most). A Whitted
 * tree doubles at every glass surface: with adc_bailout 0 and max_depth 64 it never ends. 65,536 is a
 * thousand times what the shipped scenes use per pixel; past it, rays are black and stats.budget_cut
 * counts them. */
#define RAY_TREE_BUDGET 65536

/* How many objects deep a ray can be (chapter 8's interior list). Real scenes nest two or three deep
 * (air, glass, water, ice); 16 leaves room while keeping the list small enough to copy into every ray.
 * Entering a 17th object is refracted as usual but not remembered: stats.interior_overflows counts
 * it, and its exit is later taken for an entry. */
#define RAY_INTERIOR_CAPACITY 16

typedef struct ray {
    vec3 origin;
    vec3 direction; /* unit length for every ray the tracer makes */
} ray;

/* Returns the point origin + t * direction. */
static inline vec3 ray_at(ray r, double t) { return vec3_add_scaled(r.origin, r.direction, t); }

/* Returns the nearest t a secondary ray leaving point p accepts: RAY_T_MIN, or more far from the
 * origin (RAY_T_MIN_RELATIVE above). A camera ray leaves the eye (or a point of the lens), not a
 * surface: it has no surface of its own to get away from, and takes RAY_T_MIN wherever the eye is, so
 * that a scene far from the origin keeps in view what lies within ray_t_min(eye) of the eye. */
static inline double ray_t_min(vec3 p) {
    double largest = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
    return fmax(RAY_T_MIN, RAY_T_MIN_RELATIVE * largest);
}

#endif

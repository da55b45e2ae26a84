/* aabb.h: the axis-aligned bounding box and the slab test (chapter 5).
 *
 * A box is the set of points with min <= p <= max on every axis. A ray meets it when the intervals of t
 * in which it lies between each pair of parallel planes (the "slabs") overlap. The test is written
 * with precomputed 1/direction, as every acceleration structure uses it. */
#ifndef WHITTED_AABB_H
#define WHITTED_AABB_H

#include <stdbool.h>

#include "ray.h"

struct aabb {
    vec3 min, max;
};

/* Returns the empty box (min = +infinity, max = -infinity): growing it by any point gives that point. */
struct aabb aabb_empty(void);

/* Returns the smallest box holding b and the point p. */
struct aabb aabb_grow(struct aabb b, vec3 p);

/* Returns the smallest box holding a and b. */
struct aabb aabb_union(struct aabb a, struct aabb b);

/* Returns the surface area of b (0 for an empty box); the surface area heuristic's measure. */
double aabb_surface_area(struct aabb b);

/* Returns 1 / d per component. A zero component gives +infinity or -infinity by the sign of the zero,
 * which is what the slab test wants (the ray never leaves or enters that slab). */
vec3 aabb_inverse_direction(vec3 d);

/* Narrows the interval [*t_near, *t_far] to the part in which origin + t * direction lies inside b,
 * inv_direction being aabb_inverse_direction(direction). Returns true when something is left
 * (*t_near <= *t_far). Start from [-INFINITY, INFINITY] to get the full entry and exit distances.
 * Robust as described for aabb_hit. Does not count a box test. */
bool aabb_clip(const struct aabb *b, vec3 origin, vec3 inv_direction, double *t_near, double *t_far);

/* The slab test: returns true when the ray origin + t * direction, with inv_direction =
 * aabb_inverse_direction(direction), is inside b for some t in [t_min, t_max], and stores the entry
 * distance (clamped to t_min) in *t_entry when t_entry is not NULL. Robust for zero direction
 * components and for origins exactly on a slab plane: NaN never decides the answer (a ray running
 * inside a face's plane counts as inside). Counts one box test. */
bool aabb_hit(const struct aabb *b, vec3 origin, vec3 inv_direction, double t_min, double t_max,
              double *t_entry);

/* Returns the outward unit normal of the face of b nearest to the surface point p. */
vec3 aabb_normal(const struct aabb *b, vec3 p);

#endif

/* aabb.h: the axis-aligned bounding box and the slab test (chapter 5).
 *
 * A box is the set of points with min <= p <= max on every axis. A ray meets it when the intervals of t
 * in which it lies between each pair of parallel planes (the "slabs") overlap. The test is written
 * with precomputed 1/direction, as every acceleration structure uses it. */
#ifndef WHITTED_AABB_H
#define WHITTED_AABB_H

#include <math.h>
#include <stdbool.h>

#include "ray.h"
#include "stats.h"

struct aabb {
    vec3 min, max;
};

/* The box maths below is written here in the header, so that the builds of chapters 9 to 11, which grow
 * boxes and weigh their areas millions of times, pay no function call for it. A NaN coordinate (a corner
 * beyond double's range) is never let into a box: it compares false, and the box stays as it was. */

/* Returns the empty box (min = +infinity, max = -infinity): growing it by any point gives that point. */
static inline struct aabb aabb_empty(void) {
    return (struct aabb){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

/* Returns the box of all space (min = -infinity, max = +infinity): it holds every point, and every ray
 * enters it. */
static inline struct aabb aabb_everything(void) {
    return (struct aabb){{-INFINITY, -INFINITY, -INFINITY}, {INFINITY, INFINITY, INFINITY}};
}

/* Returns the smallest box holding b and the point p (p's NaN coordinates left out). */
static inline struct aabb aabb_grow(struct aabb b, vec3 p) {
    return (struct aabb){vec3_min(p, b.min), vec3_max(p, b.max)};
}

/* Returns the smallest box holding a and b (b's NaN bounds left out). */
static inline struct aabb aabb_union(struct aabb a, struct aabb b) {
    return (struct aabb){vec3_min(b.min, a.min), vec3_max(b.max, a.max)};
}

/* Returns b grown by pad (>= 0) on every side. */
static inline struct aabb aabb_pad(struct aabb b, double pad) {
    vec3 p = {pad, pad, pad};
    return (struct aabb){vec3_sub(b.min, p), vec3_add(b.max, p)};
}

/* Returns the surface area of b (0 for an empty box); the surface area heuristic's measure. */
static inline double aabb_surface_area(struct aabb b) {
    vec3 e = vec3_sub(b.max, b.min);
    if (!(e.x >= 0.0 && e.y >= 0.0 && e.z >= 0.0))
        return 0.0;
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

/* Returns true when b holds c (a NaN bound, from a corner beyond double's range, holds anything). */
static inline bool aabb_holds(const struct aabb *b, const struct aabb *c) {
    return !(b->min.x > c->min.x || b->min.y > c->min.y || b->min.z > c->min.z || b->max.x < c->max.x ||
             b->max.y < c->max.y || b->max.z < c->max.z);
}


/* Returns 1 / d per component. A zero component gives +infinity or -infinity by the sign of the zero,
 * which is what the slab test wants (the ray never leaves or enters that slab). */
static inline vec3 aabb_inverse_direction(vec3 d) { return vec3_make(1.0 / d.x, 1.0 / d.y, 1.0 / d.z); }

/* ---- the slab test ---------------------------------------------------------------------------
 * After Kay and Kajiya (SIGGRAPH 1986), in the form of Williams, Barrus, Morley and Shirley, "An
 * efficient and robust ray-box intersection algorithm" (JGT 2005): with 1/d precomputed, a zero
 * direction component becomes an infinite 1/d and needs no special case, except one: an origin exactly
 * on a slab plane gives 0 * infinity = NaN. Every comparison below is written so that a NaN compares
 * false and leaves the interval as it was: such a ray runs inside the face's plane, and the boundary of
 * a box belongs to the box. Written here in the header too: the hierarchies of chapters 10 and 11 run
 * it millions of times a frame, and a function call each time would cost them a fifth of their speed. */

/* Narrows [*t_near, *t_far] to the t where origin + t d lies between the planes lo and hi of one axis,
 * inv being 1 / d on that axis. */
/* TASK 5.1: the slab test, one axis */
static inline void clip_to_slab(double origin, double inv, double lo, double hi, double *t_near, double *t_far) {
    double t0 = (lo - origin) * inv;
    double t1 = (hi - origin) * inv;
    if (inv < 0.0) {
        double swap = t0;
        t0 = t1;
        t1 = swap;
    }
    if (t0 > *t_near) /* false for NaN: no constraint */
        *t_near = t0;
    if (t1 < *t_far)
        *t_far = t1;
}

/* Narrows the interval [*t_near, *t_far] to the part in which origin + t * direction lies inside b,
 * inv_direction being aabb_inverse_direction(direction). Returns true when something is left
 * (*t_near <= *t_far). Start from [-INFINITY, INFINITY] to get the full entry and exit distances.
 * Robust as described for aabb_hit. Does not count a box test. */
static inline bool aabb_clip(const struct aabb *b, vec3 origin, vec3 inv_direction, double *t_near,
                             double *t_far) {
    clip_to_slab(origin.x, inv_direction.x, b->min.x, b->max.x, t_near, t_far);
    clip_to_slab(origin.y, inv_direction.y, b->min.y, b->max.y, t_near, t_far);
    clip_to_slab(origin.z, inv_direction.z, b->min.z, b->max.z, t_near, t_far);
    return *t_near <= *t_far;
}

/* The slab test: returns true when the ray origin + t * direction, with inv_direction =
 * aabb_inverse_direction(direction), is inside b for some t in [t_min, t_max], and stores the entry
 * distance (clamped to t_min) in *t_entry when t_entry is not NULL. Robust for zero direction
 * components and for origins exactly on a slab plane: NaN never decides the answer (a ray running
 * inside a face's plane counts as inside). Counts one box test. */
static inline bool aabb_hit(const struct aabb *b, vec3 origin, vec3 inv_direction, double t_min, double t_max,
                            double *t_entry) {
    stats_thread.box_tests++;
    double t_near = t_min, t_far = t_max;
    if (!aabb_clip(b, origin, inv_direction, &t_near, &t_far))
        return false;
    if (t_entry != NULL)
        *t_entry = t_near;
    return true;
}

/* Returns the outward unit normal of the face of b nearest to the surface point p. */
vec3 aabb_normal(const struct aabb *b, vec3 p);

#endif

/* aabb.c: axis-aligned boxes and the slab test (chapter 5).
 *
 * The slab test after Kay and Kajiya (SIGGRAPH 1986), in the form of Williams, Barrus, Morley and
 * Shirley, "An efficient and robust ray-box intersection algorithm" (JGT 2005): with 1/d precomputed,
 * a zero direction component becomes an infinite 1/d and needs no special case, except one: an origin
 * exactly on a slab plane gives 0 * infinity = NaN. Every comparison below is written so that a NaN
 * compares false and leaves the interval as it was: such a ray runs inside the face's plane, and the
 * boundary of a box belongs to the box. */
#include "aabb.h"

#include "stats.h"

struct aabb aabb_empty(void) {
    return (struct aabb){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

struct aabb aabb_grow(struct aabb b, vec3 p) { return (struct aabb){vec3_min(b.min, p), vec3_max(b.max, p)}; }

struct aabb aabb_union(struct aabb a, struct aabb b) {
    return (struct aabb){vec3_min(a.min, b.min), vec3_max(a.max, b.max)};
}

double aabb_surface_area(struct aabb b) {
    vec3 e = vec3_sub(b.max, b.min);
    if (!(e.x >= 0.0 && e.y >= 0.0 && e.z >= 0.0))
        return 0.0;
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

vec3 aabb_inverse_direction(vec3 d) { return vec3_make(1.0 / d.x, 1.0 / d.y, 1.0 / d.z); }

/* Narrows [*t_near, *t_far] to the t where origin + t d lies between the planes lo and hi of one axis. */
/* TASK 5.1: the slab test, one axis */
static void clip_to_slab(double origin, double inv, double lo, double hi, double *t_near, double *t_far) {
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

bool aabb_clip(const struct aabb *b, vec3 origin, vec3 inv_direction, double *t_near, double *t_far) {
    clip_to_slab(origin.x, inv_direction.x, b->min.x, b->max.x, t_near, t_far);
    clip_to_slab(origin.y, inv_direction.y, b->min.y, b->max.y, t_near, t_far);
    clip_to_slab(origin.z, inv_direction.z, b->min.z, b->max.z, t_near, t_far);
    return *t_near <= *t_far;
}

bool aabb_hit(const struct aabb *b, vec3 origin, vec3 inv_direction, double t_min, double t_max,
              double *t_entry) {
    stats_thread.box_tests++;
    double t_near = t_min, t_far = t_max;
    if (!aabb_clip(b, origin, inv_direction, &t_near, &t_far))
        return false;
    if (t_entry != NULL)
        *t_entry = t_near;
    return true;
}

vec3 aabb_normal(const struct aabb *b, vec3 p) {
    double distance[6] = {fabs(p.x - b->min.x), fabs(p.x - b->max.x), fabs(p.y - b->min.y),
                          fabs(p.y - b->max.y), fabs(p.z - b->min.z), fabs(p.z - b->max.z)};
    static const vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    int nearest = 0;
    for (int k = 1; k < 6; k++)
        if (distance[k] < distance[nearest])
            nearest = k;
    return normals[nearest];
}

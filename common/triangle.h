/* triangle.h: the triangle and the Moller-Trumbore ray intersection (chapter 3). */
#ifndef WHITTED_TRIANGLE_H
#define WHITTED_TRIANGLE_H

#include <stdbool.h>
#include <stddef.h>

#include "hit.h"
#include "mesh.h"
#include "ray.h"

struct triangle {
    vec3 a, b, c; /* corners; the winding does not matter: triangles are two-sided */
    int material; /* index into scene.materials */
};

/* The arithmetic of Moller-Trumbore on the triangle with corners a, b, c, the form the acceleration
 * structures store. It is shared by triangle_intersect and by the kd-tree and BVH, so that all of them
 * find the same t to the last bit. Returns true and stores t, u and v when the ray's line crosses the
 * triangle, at any t (the caller checks its window). A ray parallel to the plane, and a triangle with
 * two equal corners, never cross. Counts nothing. */
static inline bool triangle_crossing(vec3 a, vec3 b, vec3 c, const ray *r, double *t, double *u, double *v) {
    vec3 edge1 = vec3_sub(b, a), edge2 = vec3_sub(c, a);
    vec3 p = vec3_cross(r->direction, edge2);
    double det = vec3_dot(edge1, p);
    if (det == 0.0)
        return false;
    double inv_det = 1.0 / det;
    vec3 to_origin = vec3_sub(r->origin, a);
    double hit_u = vec3_dot(to_origin, p) * inv_det;
    if (hit_u < 0.0 || hit_u > 1.0)
        return false;
    vec3 q = vec3_cross(to_origin, edge1);
    double hit_v = vec3_dot(r->direction, q) * inv_det;
    if (hit_v < 0.0 || hit_u + hit_v > 1.0)
        return false;
    /* Two equal corners give det = 0 only in exact arithmetic: rounding can leave a tiny det and noise
     * for u and v that passes the tests above, and such a triangle has no normal to shade with. Its
     * area is checked here, on the rare path of a crossing, so the common path of a miss pays nothing. */
    vec3 area = vec3_cross(edge1, edge2);
    if (area.x == 0.0 && area.y == 0.0 && area.z == 0.0)
        return false;
    *t = vec3_dot(edge2, q) * inv_det;
    *u = hit_u;
    *v = hit_v;
    return true;
}

/* Finds where ray r meets the triangle (a, b, c) with t_min < t < t_max. On a hit returns true and
 * stores t and the barycentric coordinates u, v of the hit (P = (1-u-v)a + ub + vc); points on edges
 * and corners count as inside. Both faces are hit (two-sided). A ray parallel to the triangle's plane,
 * or a triangle of zero area, is a miss. No absolute epsilon is used, so tiny triangles are hit too.
 * Counts one triangle test. */
bool triangle_intersect(vec3 a, vec3 b, vec3 c, const ray *r, double t_min, double t_max, double *t,
                        double *u, double *v);

/* Tests r against triangles[0..count) for hits with t_min < t < h->t and keeps the nearest in *h.
 * Returns true when *h was replaced. */
bool triangle_closest(const struct triangle *triangles, size_t count, const ray *r, double t_min,
                      struct hit *h);

/* Tests r against every face of mesh m, one by one (the brute-force loop that chapters 9 and 10
 * accelerate), for hits with t_min < t < h->t; keeps the nearest in *h with the given material.
 * Returns true when *h was replaced. */
bool triangle_mesh_closest(const struct mesh *m, int material, const ray *r, double t_min, struct hit *h);

/* Returns the unit normal (b - a) x (c - a) of the triangle, by the right-hand rule on its winding. */
vec3 triangle_normal(vec3 a, vec3 b, vec3 c);

#endif

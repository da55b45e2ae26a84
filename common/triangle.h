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

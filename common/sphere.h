/* sphere.h: the sphere, the first shape of all (chapter 1 reads its scene line, sphere_syntax.c;
 * chapter 2 intersects it, sphere.c: shape.h explains the two halves of a shape's module). */
#ifndef WHITTED_SPHERE_H
#define WHITTED_SPHERE_H

#include <stdbool.h>
#include <stddef.h>

#include "ray.h"
#include "shape.h"

/* The smallest radius a scene may give (the largest is KEY_MAX_COORD, and the centre within it too): the
 * same 10^-18 a placed mesh must at least measure across, so that r^2 and an emitting sphere's area
 * 4 pi r^2, and 1 / that area, stay well inside double's range (at a radius of 1e-160 the area is a
 * subnormal number whose reciprocal is infinite). */
#define SPHERE_MIN_RADIUS 1e-18

struct sphere {
    vec3 centre;
    double radius; /* SPHERE_MIN_RADIUS .. KEY_MAX_COORD */
    int material;  /* index into scene.materials */
};

/* Finds the nearest t with t_min < t < t_max where ray r meets the surface of s. r.direction must have
 * unit length. Returns false when there is none (miss, tangent rays count as a hit at the tangent
 * point). A ray starting inside the sphere hits the far side. Counts one sphere test. */
bool sphere_intersect(const struct sphere *s, const ray *r, double t_min, double t_max, double *t);

/* Tests r against spheres[0..count) for hits with t_min < t < h->t and keeps the nearest in *h (t,
 * outward normal, material). Returns true when *h was replaced. */
bool sphere_closest(const struct sphere *spheres, size_t count, const ray *r, double t_min, struct hit *h);

/* Returns the outward unit normal of s at the surface point p. */
vec3 sphere_normal(const struct sphere *s, vec3 p);

/* The sphere's scene-file line, `sphere centre X Y Z radius R [material NAME]` (sphere_syntax.c,
 * chapter 1), and the sphere as a kind of shape (shape.h). */
extern const struct shape_syntax sphere_syntax;
extern const struct shape_kind sphere_kind;

#endif

/* plane.h: the infinite plane n . P = d and its ray intersection (chapter 1 reads its scene line,
 * plane_syntax.c; chapter 4 intersects it, plane.c: shape.h explains the two halves). */
#ifndef WHITTED_PLANE_H
#define WHITTED_PLANE_H

#include <stdbool.h>
#include <stddef.h>

#include "ray.h"
#include "shape.h"

struct plane {
    vec3 normal;     /* unit length */
    double distance; /* the plane is every P with normal . P = distance (POV-Ray's plane form);
                      * the scene parser also accepts a point and a normal, or three points */
    int material;    /* index into scene.materials */
};

/* Finds t with t_min < t < t_max where ray r meets plane p. A ray parallel to the plane misses, even
 * one lying in it; so does a ray starting on the plane (t = 0 is not > t_min). Counts one plane test. */
bool plane_intersect(const struct plane *p, const ray *r, double t_min, double t_max, double *t);

/* Tests r against planes[0..count) for hits with t_min < t < h->t and keeps the nearest in *h.
 * Returns true when *h was replaced. */
bool plane_closest(const struct plane *planes, size_t count, const ray *r, double t_min, struct hit *h);

/* The plane's scene-file line (plane_syntax.c, chapter 1), and the plane as a kind of shape (shape.h;
 * a plane has no bounds). */
extern const struct shape_syntax plane_syntax;
extern const struct shape_kind plane_kind;

#endif

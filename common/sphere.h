/* sphere.h: the sphere and its ray intersection, the first shape of all (chapter 2; its scene line,
 * at the end, is read from chapter 1 on: shape.h explains the two halves of a shape's module). */
#ifndef WHITTED_SPHERE_H
#define WHITTED_SPHERE_H

#include <stdbool.h>
#include <stddef.h>

#include "hit.h"
#include "ray.h"
#include "shape.h"

struct sphere {
    vec3 centre;
    double radius; /* > 0 */
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

/* The sphere's ray queries for the world (struct shape_behaviour, shape.h). */
extern const struct shape_behaviour sphere_behaviour;

/* ---- the scene-file line: sphere centre X Y Z radius R [material NAME] (read by chapter 1) ---- */

enum { SPHERE_CENTRE, SPHERE_RADIUS };

/* Makes the sphere from its keys (struct shape_syntax's make). */
static inline bool sphere_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
    struct sphere *s = item;
    s->centre = key_vec3(kv, SPHERE_CENTRE);
    s->radius = kv->number[SPHERE_RADIUS][0];
    if (!(s->radius > 0.0)) {
        snprintf(why, why_size, "sphere radius must be positive, got %g", s->radius);
        return false;
    }
    return true;
}

/* Writes the sphere for POV-Ray: sphere { <centre>, radius */
static inline void sphere_write_pov(FILE *out, const void *item) {
    const struct sphere *s = item;
    fprintf(out, "sphere { ");
    shape_write_vector(out, s->centre);
    fprintf(out, ", %.17g", s->radius);
}

static const struct key_spec sphere_keys[] = {{"centre", 3}, {"radius", 1}};
static const int sphere_required[] = {SPHERE_CENTRE, SPHERE_RADIUS, -1};
static const struct shape_syntax sphere_syntax = {sphere_keys, 2, sphere_required, sphere_make, sphere_write_pov};

#endif

#ifdef SHAPE_KIND /* the registration line: see shape_kinds.h */
SHAPE_KIND(sphere, spheres, SPHERES, 2)
#endif

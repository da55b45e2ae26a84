/* sphere.c: ray-sphere intersection by the quadratic formula (chapter 2).
 *
 * A point P is on the sphere when |P - C|^2 = r^2. Putting P = O + tD with |D| = 1 gives
 * t^2 + 2bt + c = 0 with b = (O - C).D and c = |O - C|^2 - r^2, so t = -b -+ sqrt(b^2 - c). This
 * "half b" form saves the factors of 2 and 4 of the textbook formula. The discriminant b^2 - c is
 * computed as r^2 - |O - C - bD|^2, the same number by Pythagoras (O - C - bD runs from the centre to the
 * line's nearest point), which keeps its digits when the sphere is small beside its distance. */
#include "sphere.h"

#include "hit.h"
#include "stats.h"

/* TASK 2.1: ray-sphere intersection, the nearest root */
bool sphere_intersect(const struct sphere *s, const ray *r, double t_min, double t_max, double *t) {
    stats_thread.sphere_tests++;
    vec3 oc = vec3_sub(r->origin, s->centre);
    double b = vec3_dot(oc, r->direction);
    vec3 across = vec3_sub(oc, vec3_scale(r->direction, b)); /* from the centre to the line's nearest point */
    double discriminant = s->radius * s->radius - vec3_dot(across, across); /* b^2 - c */
    if (discriminant < 0.0)
        return false; /* the line passes the sphere by */
    double root = sqrt(discriminant);
    double near = -b - root;
    if (near > t_min && near < t_max) {
        *t = near;
        return true;
    }
    double far = -b + root; /* the near root was behind us or too close: we may be inside */
    if (far > t_min && far < t_max) {
        *t = far;
        return true;
    }
    return false;
}

bool sphere_closest(const struct sphere *spheres, size_t count, const ray *r, double t_min, struct hit *h) {
    const struct sphere *nearest = NULL;
    for (size_t k = 0; k < count; k++)
        if (sphere_intersect(&spheres[k], r, t_min, h->t, &h->t))
            nearest = &spheres[k];
    if (nearest == NULL)
        return false;
    h->normal = sphere_normal(nearest, ray_at(*r, h->t));
    h->material = nearest->material;
    h->object = (int)(nearest - spheres); /* world_closest turns it into the object's number */
    return true;
}

/* TASK 2.2: the sphere's outward normal */
vec3 sphere_normal(const struct sphere *s, vec3 p) {
    return vec3_scale(vec3_sub(p, s->centre), 1.0 / s->radius);
}

/* ---- the sphere as one kind of shape (shape.h) -------------------------------------------------- */

static bool closest_spheres(const void *items, size_t count, const ray *r, double t_min, struct hit *h) {
    return sphere_closest(items, count, r, t_min, h);
}

/* Both crossings of each sphere: where r enters and, searching on from there, where it leaves. */
static bool sphere_crossings(const void *items, size_t count, const ray *r, double t_min, double t_max,
                             shape_crossing_visitor visit, void *context) {
    const struct sphere *spheres = items;
    for (size_t k = 0; k < count; k++) {
        double t_near, t_far;
        if (!sphere_intersect(&spheres[k], r, t_min, t_max, &t_near))
            continue;
        if (!visit(context, t_near, spheres[k].material))
            return false;
        if (sphere_intersect(&spheres[k], r, t_near, t_max, &t_far) && !visit(context, t_far, spheres[k].material))
            return false;
    }
    return true;
}

static bool sphere_bounds(const void *item, vec3 *min, vec3 *max) {
    const struct sphere *s = item;
    vec3 extent = vec3_make(s->radius, s->radius, s->radius);
    *min = vec3_sub(s->centre, extent);
    *max = vec3_add(s->centre, extent);
    return true;
}

/* Strictly inside: a point on the surface is not. */
static bool sphere_contains(const void *item, vec3 point) {
    const struct sphere *s = item;
    vec3 d = vec3_sub(point, s->centre);
    return vec3_dot(d, d) < s->radius * s->radius;
}

const struct shape_kind sphere_kind = {
    .syntax = &sphere_syntax,
    .closest = closest_spheres,
    .crossings = sphere_crossings,
    .bounds = sphere_bounds,
    .contains = sphere_contains,
};

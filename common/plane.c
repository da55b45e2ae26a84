/* plane.c: ray-plane intersection (chapter 4).
 *
 * Putting P = O + tD into n . P = d gives t = (d - n . O) / (n . D). When n . D = 0 the ray runs
 * parallel to the plane and never meets it (or lies in it, which we also call a miss: a plane seen
 * exactly edge-on covers no area of the picture). */
#include "plane.h"

#include "hit.h"
#include "stats.h"

/* A tie goes to the plane: when a plane is exactly as far as the hit found before it (a box's face or
 * a triangle lying in the plane), the plane replaces it. This is POV-Ray's rule: it tests the infinite
 * shapes before the bounded ones, and a later shape replaces the hit only when strictly nearer. Among
 * planes, the first in the scene keeps a tie, as in POV-Ray. */
bool plane_closest(const struct plane *planes, size_t count, const ray *r, double t_min, struct hit *h) {
    const struct plane *nearest = NULL;
    for (size_t k = 0; k < count; k++) {
        double t;
        if (plane_intersect(&planes[k], r, t_min, INFINITY, &t) && (t < h->t || (t == h->t && nearest == NULL))) {
            h->t = t;
            nearest = &planes[k];
        }
    }
    if (nearest == NULL)
        return false;
    h->normal = nearest->normal;
    h->material = nearest->material;
    h->object = (int)(nearest - planes); /* world_closest turns it into the object's number */
    return true;
}

/* TASK 4.1: ray-plane intersection */
bool plane_intersect(const struct plane *p, const ray *r, double t_min, double t_max, double *t) {
    stats_thread.plane_tests++;
    double denominator = vec3_dot(p->normal, r->direction);
    if (denominator == 0.0)
        return false;
    double hit_t = (p->distance - vec3_dot(p->normal, r->origin)) / denominator;
    if (!(hit_t > t_min && hit_t < t_max))
        return false;
    *t = hit_t;
    return true;
}

/* ---- the plane as one kind of shape (shape.h) --------------------------------------------------- */

static bool closest_planes(const void *items, size_t count, const ray *r, double t_min, struct hit *h) {
    return plane_closest(items, count, r, t_min, h);
}

static bool plane_crossings(const void *items, size_t count, const ray *r, double t_min, double t_max,
                            shape_crossing_visitor visit, void *context) {
    const struct plane *planes = items;
    for (size_t k = 0; k < count; k++) {
        double t;
        if (plane_intersect(&planes[k], r, t_min, t_max, &t) && !visit(context, t, planes[k].material))
            return false;
    }
    return true;
}

/* An infinite plane fits in no box. */
static bool plane_bounds(const void *item, vec3 *min, vec3 *max) {
    (void)item;
    (void)min;
    (void)max;
    return false;
}

/* The side the normal points away from: n . P < d. */
static bool plane_contains(const void *item, vec3 point) {
    const struct plane *p = item;
    return vec3_dot(point, p->normal) < p->distance;
}

const struct shape_kind plane_kind = {
    .syntax = &plane_syntax,
    .closest = closest_planes,
    .crossings = plane_crossings,
    .bounds = plane_bounds,
    .contains = plane_contains,
};

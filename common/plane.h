/* plane.h: the infinite plane n . P = d and its ray intersection (chapter 4; its scene line, at the
 * end, is read from chapter 1 on: shape.h explains the two halves of a shape's module). */
#ifndef WHITTED_PLANE_H
#define WHITTED_PLANE_H

#include <stdbool.h>
#include <stddef.h>

#include "hit.h"
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

/* The plane's ray queries for the world (struct shape_behaviour, shape.h). A plane has no bounds. */
extern const struct shape_behaviour plane_behaviour;

/* ---- the scene-file line (read by chapter 1) ---------------------------------------------------- */

enum { PLANE_NORMAL, PLANE_DISTANCE, PLANE_POINT, PLANE_A, PLANE_B, PLANE_C };

/* Makes the plane from its keys (struct shape_syntax's make). A plane comes in three forms: `normal N
 * distance d` (POV-Ray's N.P = d), `normal N point P`, or the seed's three points `a A b B c C`. All
 * are stored as a unit normal and a distance. */
static inline bool plane_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
    const bool *given = kv->present;
    bool any_point_key = given[PLANE_A] || given[PLANE_B] || given[PLANE_C];
    bool by_distance = given[PLANE_NORMAL] && given[PLANE_DISTANCE] && !given[PLANE_POINT] && !any_point_key;
    bool by_point = given[PLANE_NORMAL] && given[PLANE_POINT] && !given[PLANE_DISTANCE] && !any_point_key;
    bool by_points = given[PLANE_A] && given[PLANE_B] && given[PLANE_C] && !given[PLANE_NORMAL] &&
                     !given[PLANE_DISTANCE] && !given[PLANE_POINT];
    if (by_distance + by_point + by_points != 1) {
        snprintf(why, why_size, "plane needs 'normal' with 'distance' or 'point', or three points 'a', 'b', 'c'");
        return false;
    }
    vec3 normal;
    vec3 point = vec3_make(0, 0, 0);
    if (by_points) {
        point = key_vec3(kv, PLANE_A);
        vec3 ab = vec3_sub(key_vec3(kv, PLANE_B), point), ac = vec3_sub(key_vec3(kv, PLANE_C), point);
        /* Scale both edges to at most 1 first, so that far-apart points cannot overflow the product. */
        double ab_size = fmax(fabs(ab.x), fmax(fabs(ab.y), fabs(ab.z)));
        double ac_size = fmax(fabs(ac.x), fmax(fabs(ac.y), fabs(ac.z)));
        if (ab_size > 0.0 && ac_size > 0.0)
            normal = vec3_cross(vec3_scale(ab, 1.0 / ab_size), vec3_scale(ac, 1.0 / ac_size));
        else
            normal = vec3_make(0, 0, 0);
        if (normal.x == 0.0 && normal.y == 0.0 && normal.z == 0.0) {
            snprintf(why, why_size, "plane points a, b, c lie on one line");
            return false;
        }
    } else {
        normal = key_vec3(kv, PLANE_NORMAL);
        if (normal.x == 0.0 && normal.y == 0.0 && normal.z == 0.0) {
            snprintf(why, why_size, "plane normal must not be zero");
            return false;
        }
        point = given[PLANE_POINT] ? key_vec3(kv, PLANE_POINT) : point;
    }
    struct plane *plane = item;
    /* Divide by the largest component first: |normal| of components like 1e200 would overflow. */
    double largest = fmax(fabs(normal.x), fmax(fabs(normal.y), fabs(normal.z)));
    plane->normal = vec3_normalize(vec3_scale(normal, 1.0 / largest));
    plane->distance = by_distance ? kv->number[PLANE_DISTANCE][0] : vec3_dot(plane->normal, point);
    return true;
}

/* Writes the plane for POV-Ray: plane { <unit normal>, distance. POV-Ray normalises the normal but
 * keeps the distance, so the normal must already be a unit vector. */
static inline void plane_write_pov(FILE *out, const void *item) {
    const struct plane *p = item;
    fprintf(out, "plane { ");
    shape_write_vector(out, p->normal);
    fprintf(out, ", %.17g", p->distance);
}

static const struct key_spec plane_keys[] = {{"normal", 3}, {"distance", 1}, {"point", 3},
                                             {"a", 3},      {"b", 3},        {"c", 3}};
static const int plane_required[] = {-1}; /* plane_make checks the three forms itself */
static const struct shape_syntax plane_syntax = {plane_keys, 6, plane_required, plane_make, plane_write_pov};

#endif

#ifdef SHAPE_KIND /* the registration line: see shape_kinds.h */
SHAPE_KIND(plane, planes, PLANES, 4)
#endif

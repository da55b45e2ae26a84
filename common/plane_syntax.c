/* plane_syntax.c: the plane's scene-file line, in three forms (`plane normal N distance D`, `plane
 * normal N point P` or `plane a A b B c C`, each with [material NAME]), and its POV-Ray form (chapter
 * 1: every chapter reads every scene; shape.h explains the two halves). */
#include "plane.h"

#include <math.h>

enum { PLANE_NORMAL, PLANE_DISTANCE, PLANE_POINT, PLANE_A, PLANE_B, PLANE_C };

/* Makes the plane from its keys (struct shape_syntax's make). A plane comes in three forms: `normal N
 * distance d` (POV-Ray's N.P = d), `normal N point P`, or the seed's three points `a A b B c C`. All
 * are stored as a unit normal and a distance. */
static bool plane_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
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
        /* Scale both edges to a largest component of 1 first, so that far-apart points cannot overflow
         * the product, nor points a subnormal distance apart vanish in it (a zero edge stays zero). */
        normal = vec3_cross(vec3_unit_max(ab), vec3_unit_max(ac));
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
    /* Every point in range (and so the distance derived from it, at most sqrt(3) times as far): a plane
     * 1e300 away would make every hit point, and the shading's squares of it, overflow. */
    static const char *const point_names[] = {"plane point", "plane a", "plane b", "plane c"};
    static const int point_keys[] = {PLANE_POINT, PLANE_A, PLANE_B, PLANE_C};
    for (int k = 0; k < 4; k++)
        if (given[point_keys[k]] &&
            !key_vec3_within(key_vec3(kv, point_keys[k]), KEY_MAX_COORD, point_names[k], why, why_size))
            return false;
    if (by_distance && !(fabs(kv->number[PLANE_DISTANCE][0]) <= KEY_MAX_COORD)) {
        snprintf(why, why_size, "plane distance must stay within -%g .. %g, got " KEY_NUMBER_SHOWN, KEY_MAX_COORD,
                 KEY_MAX_COORD, KEY_NUMBER(kv->number[PLANE_DISTANCE][0]));
        return false;
    }
    struct plane *plane = item;
    /* Divide by the largest component first: |normal| of components like 1e200 would overflow, and of
     * components like 1e-310 vanish. */
    plane->normal = vec3_normalize(vec3_unit_max(normal));
    plane->distance = by_distance ? kv->number[PLANE_DISTANCE][0] : vec3_dot(plane->normal, point);
    return true;
}

/* Writes the plane for POV-Ray: plane { <unit normal>, distance. POV-Ray normalises the normal but
 * keeps the distance, so the normal must already be a unit vector. */
static void plane_write_pov(FILE *out, const void *item) {
    const struct plane *p = item;
    fprintf(out, "plane { ");
    shape_write_vector(out, p->normal);
    fprintf(out, ", %.17g", p->distance);
}

static const struct key_spec plane_keys[] = {{"normal", 3}, {"distance", 1}, {"point", 3},
                                             {"a", 3},      {"b", 3},        {"c", 3}};
static const int plane_required[] = {-1}; /* plane_make checks the three forms itself */

const struct shape_syntax plane_syntax = {
    .keyword = "plane",
    .plural = "planes",
    .size = sizeof(struct plane),
    .material_offset = offsetof(struct plane, material),
    .keys = plane_keys,
    .key_count = 6,
    .required = plane_required,
    .make = plane_make,
    .write_pov = plane_write_pov,
};

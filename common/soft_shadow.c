/* soft_shadow.c: area lights' shadows by POV-Ray 3.7's rule (chapter 13; in words: docs/13-distributed.md). */
#include "soft_shadow.h"

#include <math.h>
#include <stdbool.h>

#include "shadow.h"

/* An oriented light's first axis is made square to the direction to the light and to z, or to y when
 * that direction is closer to z than this (POV-Ray's 0.01). */
#define SOFT_SHADOW_NEAR_Z 0.01

/* The two axes of an oriented light seen from `point`: square to the direction to the centre and
 * to each other, both as long as axis1 (POV-Ray's orient). */
static void oriented_axes(const struct light *light, vec3 point, vec3 *axis1, vec3 *axis2) {
    vec3 to_light = vec3_sub(light->position, point);
    vec3 direction = vec3_scale(to_light, 1.0 / vec3_length(to_light));
    vec3 across = fabs(fabs(direction.z) - 1.0) < SOFT_SHADOW_NEAR_Z ? vec3_make(0, 1, 0) : vec3_make(0, 0, 1);
    double length = vec3_length(light->area.axis1);
    vec3 first = vec3_normalize(vec3_cross(direction, across));
    vec3 second = vec3_normalize(vec3_cross(direction, first));
    *axis1 = vec3_scale(first, length);
    *axis2 = vec3_scale(second, length);
}

/* The offset of grid point (u, v) from the centre, along axes a1 and a2. */
static vec3 grid_offset(const struct area_light *a, vec3 a1, vec3 a2, int u, int v) {
    if (a->circular) { /* each square ring of the grid pulled onto its inscribed circle (POV-Ray's) */
        double x = (double)u / (a->size1 - 1) - 0.5 + SOFT_SHADOW_CIRCULAR_NUDGE;
        double y = (double)v / (a->size2 - 1) - 0.5 + SOFT_SHADOW_CIRCULAR_NUDGE;
        double scale = fmax(fabs(x), fabs(y)) / sqrt(x * x + y * y);
        return vec3_add(vec3_scale(a1, x * scale), vec3_scale(a2, y * scale));
    }
    vec3 along1 = a->size1 > 1 ? vec3_scale(a1, (double)u / (a->size1 - 1) - 0.5) : vec3_make(0, 0, 0);
    vec3 along2 = a->size2 > 1 ? vec3_scale(a2, (double)v / (a->size2 - 1) - 0.5) : vec3_make(0, 0, 0);
    return vec3_add(along1, along2);
}

vec3 soft_shadow_light_point(const struct light *light, vec3 point, int u, int v) {
    const struct area_light *a = &light->area;
    if (!area_light_is_area(a))
        return light->position;
    vec3 a1 = a->axis1, a2 = a->axis2;
    if (a->orient)
        oriented_axes(light, point, &a1, &a2);
    return vec3_add(light->position, grid_offset(a, a1, a2, u, v));
}

/* One shadow computation: the grid points traced so far and what each let through. */
struct light_grid {
    const void *world;
    const struct light *light;
    vec3 point, axis1, axis2;
    vec3 passed[AREA_LIGHT_MAX_SIZE * AREA_LIGHT_MAX_SIZE];
    bool traced[AREA_LIGHT_MAX_SIZE * AREA_LIGHT_MAX_SIZE];
};

/* What grid point (u, v) lets through, traced the first time it is asked for. */
static vec3 grid_point(struct light_grid *g, int u, int v) {
    int k = u * g->light->area.size2 + v;
    if (!g->traced[k]) {
        vec3 target = vec3_add(g->light->position, grid_offset(&g->light->area, g->axis1, g->axis2, u, v));
        g->passed[k] = shadow_filtered_to(g->world, g->point, target);
        g->traced[k] = true;
    }
    return g->passed[k];
}

/* POV-Ray's difference test, on the light each corner lets through (the light's colour times the share). */
static bool corners_differ(const struct light_grid *g, vec3 a, vec3 b) {
    vec3 c = g->light->colour;
    double distance = fabs(c.x * a.x - c.x * b.x) + fabs(c.y * a.y - c.y * b.y) + fabs(c.z * a.z - c.z * b.z);
    return distance > SOFT_SHADOW_THRESHOLD;
}

/* The share let through by the grid rectangle [u1, u2] x [v1, v2], at `level` cuts from the whole:
 * the mean of its four corners, or, while it spans more than one step and its level is forced or two
 * neighbouring corners differ, the mean of its four quarters (the rule of soft_shadow.h). */
/* TASK 13.1: POV-Ray's area light: corners, quarters and the adaptive rule */
static vec3 rectangle(struct light_grid *g, int u1, int v1, int u2, int v2, int level) {
    vec3 corner[4] = {grid_point(g, u1, v1), grid_point(g, u2, v1), grid_point(g, u1, v2), grid_point(g, u2, v2)};
    int adaptive = g->light->area.adaptive;
    bool forced = adaptive == AREA_LIGHT_NOT_ADAPTIVE || level < adaptive;
    if ((u2 - u1 > 1 || v2 - v1 > 1) &&
        (forced || corners_differ(g, corner[0], corner[1]) || corners_differ(g, corner[1], corner[3]) ||
         corners_differ(g, corner[3], corner[2]) || corners_differ(g, corner[2], corner[0]))) {
        int u_low = (u1 + u2) / 2, u_high = (u1 + u2 + 1) / 2; /* the middle lines, one when the middle */
        int v_low = (v1 + v2) / 2, v_high = (v1 + v2 + 1) / 2; /* is a grid line, else the two beside it */
        corner[0] = rectangle(g, u1, v1, u_low, v_low, level + 1);
        corner[1] = rectangle(g, u_high, v1, u2, v_low, level + 1);
        corner[2] = rectangle(g, u1, v_high, u_low, v2, level + 1);
        corner[3] = rectangle(g, u_high, v_high, u2, v2, level + 1);
    }
    return vec3_scale(vec3_add(vec3_add(vec3_add(corner[0], corner[1]), corner[2]), corner[3]), 0.25);
}

vec3 soft_shadow_filtered(const void *world, vec3 point, const struct light *light) {
    const struct area_light *a = &light->area;
    if (!area_light_is_area(a))
        return shadow_filtered(world, point, light);
    struct light_grid g;
    g.world = world;
    g.light = light;
    g.point = point;
    g.axis1 = a->axis1;
    g.axis2 = a->axis2;
    if (a->orient)
        oriented_axes(light, point, &g.axis1, &g.axis2);
    for (int k = 0; k < a->size1 * a->size2; k++)
        g.traced[k] = false;
    return rectangle(&g, 0, 0, a->size1 - 1, a->size2 - 1, 0);
}

/* phong.c: the Phong reflection model as POV-Ray 3.7 computes it (chapter 6). */
#include "phong.h"

#include <math.h>

#include "world.h"

/* TASK 6.1: the mirror direction */
vec3 phong_reflect(vec3 direction, vec3 normal) {
    return vec3_add_scaled(direction, normal, -2.0 * vec3_dot(direction, normal));
}

/* TASK 6.2: ambient, diffuse and Phong highlight */
vec3 phong_shade(const struct scene *s, const struct phong_surface *at, phong_shadow_fn shadow,
                 const void *world) {
    const struct material *m = at->material;
    vec3 colour = vec3_scale(vec3_mul(s->ambient_light, m->colour), m->ambient * at->opacity);
    vec3 mirror = phong_reflect(at->direction, at->normal);
    for (size_t k = 0; k < s->light_count; k++) {
        const struct light *light = &s->lights[k];
        vec3 to_light = vec3_normalize(vec3_sub(light->position, at->point));
        double cosine = vec3_dot(at->normal, to_light);
        if (!(cosine >= PHONG_MIN_COSINE))
            continue; /* behind the surface, grazing it, or on the point itself (no direction: NaN) */
        vec3 reaching = light->colour;
        if (shadow != NULL) {
            reaching = vec3_mul(reaching, shadow(world, at->point, light));
            if (reaching.x == 0.0 && reaching.y == 0.0 && reaching.z == 0.0)
                continue;
        }
        vec3 diffuse = vec3_scale(m->colour, m->diffuse * cosine * at->opacity);
        /* at most 1 but for rounding, which pow would blow up to infinity when phong_size is large */
        double alignment = fmin(vec3_dot(mirror, to_light), 1.0);
        double highlight = (m->phong > 0.0 && alignment > 0.0) ? m->phong * pow(alignment, m->phong_size) : 0.0;
        vec3 shine = vec3_make(highlight, highlight, highlight); /* white: tinted only by the light */
        vec3 surface = vec3_add(diffuse, shine);
        colour = vec3_add(colour, vec3_mul(reaching, surface));
    }
    return colour;
}

vec3 phong_trace_nearest(const void *world, const ray *r, phong_shadow_fn shadow) {
    const struct world *w = world;
    struct hit h = hit_nothing(INFINITY);
    if (!world_closest(w, r, RAY_T_MIN, &h))
        return w->scene->background;
    struct phong_surface at = {ray_at(*r, h.t), hit_facing_normal(&h, r->direction), r->direction,
                               &w->scene->materials[h.material], 1.0};
    return phong_shade(w->scene, &at, shadow, w);
}

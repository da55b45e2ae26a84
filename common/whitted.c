/* whitted.c: the recursive Whitted tracer (chapter 8). */
#include "whitted.h"

#include <math.h>
#include <stdint.h>

#include "phong.h"
#include "shadow.h"
#include "stats.h"

bool whitted_refract(vec3 direction, vec3 normal, double eta, vec3 *out) {
    double c = -vec3_dot(direction, normal);
    double k = 1.0 - eta * eta * (1.0 - c * c);
    if (k < 0.0)
        return false;
    *out = vec3_add_scaled(vec3_scale(direction, eta), normal, eta * c - sqrt(k));
    return true;
}

static vec3 trace(const struct world *w, const ray *r, int level);

/* Traces a secondary ray of the given level, counting it in *counter only when it is within the depth
 * limit: a ray past the limit is black without being traced. */
static vec3 spawn(const struct world *w, ray r, int level, uint64_t *counter) {
    if (level > w->scene->max_depth)
        return vec3_make(0, 0, 0);
    (*counter)++;
    return trace(w, &r, level);
}

/* The light arriving through a transparent surface, or by total internal reflection. Sets
 * *total_reflection when the ray could not leave. */
static vec3 transmitted(const struct world *w, const ray *r, const struct hit *h, vec3 point, vec3 facing,
                        int level, bool *total_reflection) {
    const struct material *m = &w->scene->materials[h->material];
    bool entering = vec3_dot(r->direction, h->normal) < 0.0; /* against the outward normal */
    double eta = entering ? 1.0 / m->ior : m->ior;
    vec3 direction;
    *total_reflection = !whitted_refract(r->direction, facing, eta, &direction);
    if (*total_reflection) {
        ray mirror = {point, vec3_normalize(phong_reflect(r->direction, facing))};
        return spawn(w, mirror, level + 1, &stats_thread.reflected_rays);
    }
    ray through = {point, vec3_normalize(direction)};
    int next_level = m->ior == 1.0 ? level : level + 1; /* nothing bends: not a new level */
    vec3 weight = vec3_add_scaled(vec3_make(m->transmit, m->transmit, m->transmit), m->colour, m->filter);
    return vec3_mul(weight, spawn(w, through, next_level, &stats_thread.refracted_rays));
}

static vec3 trace(const struct world *w, const ray *r, int level) {
    const struct scene *s = w->scene; /* level <= max_depth: spawn checked it (max_depth >= 1) */
    struct hit h = hit_nothing(INFINITY);
    if (!world_closest(w, r, RAY_T_MIN, &h))
        return s->background;
    const struct material *m = &s->materials[h.material];
    vec3 point = ray_at(*r, h.t);
    vec3 facing = hit_facing_normal(&h, r->direction);
    struct phong_surface at = {point, facing, r->direction, m, 1.0 - m->filter - m->transmit};
    vec3 colour = phong_shade(s, &at, shadow_filtered, w);
    bool total_reflection = false;
    if (m->filter > 0.0 || m->transmit > 0.0)
        colour = vec3_add(colour, transmitted(w, r, &h, point, facing, level, &total_reflection));
    if (!total_reflection && m->reflection > 0.0) {
        ray mirror = {point, vec3_normalize(phong_reflect(r->direction, facing))};
        colour = vec3_add_scaled(colour, spawn(w, mirror, level + 1, &stats_thread.reflected_rays), m->reflection);
    }
    return colour;
}

vec3 whitted_trace(const void *world, const ray *r) { return trace(world, r, 1); }

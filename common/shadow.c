/* shadow.c: opaque and filtered shadow rays (chapters 7 and 8). */
#include "shadow.h"

#include "stats.h"

/* The shadow ray from point towards a light at `target`, and the window of t in which a blocker counts. */
static ray shadow_ray(const struct world *w, vec3 point, vec3 target, double *t_min, double *t_max) {
    vec3 to_light = vec3_sub(target, point);
    double distance = vec3_length(to_light);
    double margin = w->scene->shadow_offset ? SHADOW_T_MIN : 0.0;
    *t_min = margin;
    *t_max = distance - margin;
    stats_thread.shadow_rays++;
    return (ray){point, vec3_scale(to_light, 1.0 / distance)};
}

/* Any crossing blocks: stop at the first. */
static bool stop_at_first(void *context, double t, int material) {
    (void)t;
    (void)material;
    *(bool *)context = true;
    return false;
}

/* TASK 7.1: the shadow ray: is the light blocked? */
vec3 shadow_opaque(const void *world, vec3 point, const struct light *light) {
    const struct world *w = world;
    double t_min, t_max;
    ray r = shadow_ray(w, point, light->position, &t_min, &t_max);
    bool blocked = false;
    world_for_each_crossing(w, &r, t_min, t_max, stop_at_first, &blocked);
    return blocked ? vec3_make(0, 0, 0) : vec3_make(1, 1, 1);
}

/* Multiplies the light passed so far by what one surface lets through. */
struct filter_state {
    const struct world *world;
    const ray *r;
    vec3 passed;
};

/* Chapter 14 (scene.shadow_paint): the material of the surface that the shadow ray crosses at t, with
 * its pigment's colour, filter and transmit at the crossing, as POV-Ray filters a shadow. The
 * crossing gives only t and the material; for `map uv` the surface itself is needed (which face of
 * which mesh, which face of a box), so it is found again, as the nearest hit within a hair of t. */
static const struct material *crossed_material(const struct filter_state *state, double t, int material,
                                               struct material *painted) {
    const struct scene *s = state->world->scene;
    const struct material *m = &s->materials[material];
    if (s->shadow_paint == NULL || m->pigment < 0)
        return m;
    struct hit h = {t, {0, 0, 0}, material, -1, -1}; /* on no particular surface: enough for a pattern */
    if (s->pigments[m->pigment].uv_mapping) {
        double window = SHADOW_CROSSING_WINDOW * fmax(1.0, t);
        struct hit found = hit_nothing(t + window);
        if (world_closest(state->world, state->r, t - window, &found))
            h = found;
    }
    return s->shadow_paint(s, &h, ray_at(*state->r, t), painted);
}

static bool filter_through(void *context, double t, int material) {
    struct filter_state *state = context;
    struct material painted;
    const struct material *m = crossed_material(state, t, material, &painted);
    vec3 through = vec3_add_scaled(vec3_make(m->transmit, m->transmit, m->transmit), m->colour, m->filter);
    state->passed = vec3_mul(state->passed, through);
    return state->passed.x != 0.0 || state->passed.y != 0.0 || state->passed.z != 0.0;
}

vec3 shadow_filtered(const void *world, vec3 point, const struct light *light) {
    return shadow_filtered_to(world, point, light->position);
}

/* TASK 7.1 ALSO: the shadow ray that filters the light through what it crosses */
vec3 shadow_filtered_to(const void *world, vec3 point, vec3 target) {
    const struct world *w = world;
    double t_min, t_max;
    ray r = shadow_ray(w, point, target, &t_min, &t_max);
    struct filter_state state = {w, &r, vec3_make(1, 1, 1)};
    world_for_each_crossing(w, &r, t_min, t_max, filter_through, &state);
    return state.passed;
}

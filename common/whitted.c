/* whitted.c: the recursive Whitted tracer (chapter 8). */
#include "whitted.h"

#include <math.h>
#include <stdint.h>

#include "interior.h"
#include "phong.h"
#include "scene.h"
#include "shadow.h"
#include "stats.h"

/* POV-Ray's test for "the two indices are the same, nothing bends": |n1 / n2 - 1| below its EPSILON. */
#define WHITTED_SAME_IOR 1e-10

/* POV-Ray's weights of red, green and blue in a grey value (its RED_INTENSITY and so on), used to
 * decide whether a surface lets enough light through to be worth a refracted ray. */
#define WHITTED_GREY_RED 0.297
#define WHITTED_GREY_GREEN 0.589
#define WHITTED_GREY_BLUE 0.114

/* TASK 8.1: Snell's refraction and total internal reflection */
bool whitted_refract(vec3 direction, vec3 normal, double eta, vec3 *out) {
    double c = -vec3_dot(direction, normal);
    double k = 1.0 - eta * eta * (1.0 - c * c);
    if (k < 0.0)
        return false;
    *out = vec3_add_scaled(vec3_scale(direction, eta), normal, eta * c - sqrt(k));
    return true;
}

/* What every ray of one camera ray's tree shares. */
struct tree {
    const struct world *w;
    phong_shadow_fn shadow; /* each light's shadow: shadow_filtered, or chapter 13's soft shadows */
    int budget; /* secondary rays and area-light shadow rays this tree may still spend (RAY_TREE_BUDGET) */
};

/* Each light's shadow factor by the tree's shadow function, called by phong_shade with the tree as its
 * world. An area light's shadow rays (up to 33 x 33 a hit) are spent from the tree's budget as its
 * secondary rays are, so that they too stop a deep tree; a point light's one ray is not. */
static vec3 budgeted_shadow(const void *tree, vec3 point, const struct light *light) {
    struct tree *t = (struct tree *)tree; /* the tree trace() handed phong_shade, not const there */
    uint64_t before = stats_thread.shadow_rays;
    vec3 passed = t->shadow(t->w, point, light);
    if (area_light_is_area(&light->area)) {
        uint64_t spent = stats_thread.shadow_rays - before;
        t->budget = spent >= (uint64_t)t->budget ? 0 : t->budget - (int)spent;
    }
    return passed;
}

static vec3 trace(struct tree *t, ray r, struct interior_list inside, int level, double weight);

/* Traces a secondary ray of the given level and weight, counting it in *counter, unless it is past the
 * depth limit, its weight is under adc_bailout, or the tree's budget is spent: then it is black. */
static vec3 spawn(struct tree *t, ray r, const struct interior_list *inside, int level, double weight,
                  uint64_t *counter) {
    const struct scene *s = t->w->scene;
    if (level > s->max_depth)
        return vec3_make(0, 0, 0);
    if (weight < s->adc_bailout) {
        stats_thread.adc_saves++;
        return vec3_make(0, 0, 0);
    }
    if (t->budget == 0) {
        stats_thread.budget_cut++;
        return vec3_make(0, 0, 0);
    }
    t->budget--;
    (*counter)++;
    return trace(t, r, *inside, level, weight);
}

/* The colour seen along r, a ray of the given level and weight inside the objects of `inside`.
 * A crossing into the same index of refraction goes straight on at the same level (POV-Ray's rule):
 * the loop follows it, adding what each surface contributes times the light let through so far. */
/* TASK 8.2: the recursion: reflected and refracted rays, bounded depth */
static vec3 trace(struct tree *t, ray r, struct interior_list inside, int level, double weight) {
    const struct scene *s = t->w->scene; /* level <= max_depth: spawn checked it (max_depth >= 1) */
    vec3 sum = vec3_make(0, 0, 0), through = vec3_make(1, 1, 1);
    for (int crossings = 0;; crossings++) {
        struct hit h = hit_nothing(INFINITY);
        bool camera_ray = level == 1 && crossings == 0; /* from the eye, not from a surface (ray.h) */
        if (!world_closest(t->w, &r, camera_ray ? RAY_T_MIN : ray_t_min(r.origin), &h))
            return vec3_add(sum, vec3_mul(through, s->background));
        const struct material *m = &s->materials[h.material];
        vec3 point = ray_at(r, h.t);
        struct material painted; /* chapter 14 paints the material and smooths the normal (scene.h) */
        if (s->paint != NULL)
            m = s->paint(s, &h, point, &painted);
        vec3 facing = hit_facing_normal(&h, r.direction);
        struct phong_surface at = {point, facing, r.direction, m, 1.0 - m->filter - m->transmit};
        vec3 colour = phong_shade(s, &at, budgeted_shadow, t);

        /* Light through the surface: colour * filter + transmit per channel, refracted only when its
         * grey value passes adc_bailout; the new ray's weight is this ray's times its largest channel. */
        vec3 filter = vec3_add_scaled(vec3_make(m->transmit, m->transmit, m->transmit), m->colour, m->filter);
        double grey = WHITTED_GREY_RED * filter.x + WHITTED_GREY_GREEN * filter.y + WHITTED_GREY_BLUE * filter.z;
        double filter_weight = weight * vec3_largest(filter);
        bool total_reflection = false, straight_on = false;
        struct interior_list beyond = inside;
        if (fmin(1.0, fabs(grey)) > s->adc_bailout) {
            double eta = interior_cross(&beyond, h.object, m->ior);
            vec3 direction;
            if (fabs(eta - 1.0) < WHITTED_SAME_IOR) {
                straight_on = true; /* nothing bends: the loop goes on below */
            } else if (whitted_refract(r.direction, facing, eta, &direction)) {
                ray refracted = {point, vec3_normalize(direction)};
                vec3 seen = spawn(t, refracted, &beyond, level + 1, filter_weight, &stats_thread.refracted_rays);
                colour = vec3_add(colour, vec3_mul(filter, seen));
            } else { /* total internal reflection: all of it, unfiltered, and the ray stays inside */
                total_reflection = true;
                ray mirror = {point, vec3_normalize(phong_reflect(r.direction, facing))};
                colour = vec3_add(colour, spawn(t, mirror, &inside, level + 1, filter_weight,
                                                &stats_thread.reflected_rays));
            }
        }
        if (!total_reflection && m->reflection > 0.0) {
            ray mirror = {point, vec3_normalize(phong_reflect(r.direction, facing))};
            vec3 seen = spawn(t, mirror, &inside, level + 1, weight * m->reflection, &stats_thread.reflected_rays);
            colour = vec3_add_scaled(colour, seen, m->reflection);
        }
        sum = vec3_add(sum, vec3_mul(through, colour));
        if (!straight_on)
            return sum;

        /* Straight on through the surface: the same checks as spawn, and the crossing cap. The crossing
         * keeps its level, but at the last level it goes no further: POV-Ray checks the level before
         * every ray it traces, a crossing's too, so there the surface's far side is black. */
        if (level >= s->max_depth)
            return sum;
        if (filter_weight < s->adc_bailout) {
            stats_thread.adc_saves++;
            return sum;
        }
        if (crossings + 1 >= RAY_MAX_CROSSINGS) {
            stats_thread.crossings_capped++;
            return sum;
        }
        if (t->budget == 0) {
            stats_thread.budget_cut++;
            return sum;
        }
        t->budget--;
        stats_thread.refracted_rays++;
        through = vec3_mul(through, filter);
        weight = filter_weight;
        inside = beyond;
        r.origin = point;
    }
}

vec3 whitted_trace(const void *world, const ray *r) {
    return whitted_trace_shadowed(world, r, shadow_filtered);
}

vec3 whitted_trace_shadowed(const void *world, const ray *r, phong_shadow_fn shadow) {
    struct tree t = {world, shadow, RAY_TREE_BUDGET};
    return trace(&t, *r, interior_at_point(world, r->origin), 1, 1.0);
}

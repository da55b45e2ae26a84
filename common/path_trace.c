/* path_trace.c: the path tracer's estimator: next-event estimation, scattering, their weights, Russian
 * roulette (chapter 15; in words: docs/15-paths.md). */
#include "path_trace.h"

#include <math.h>
#include <stdbool.h>

#include "bsdf.h"
#include "phong.h"
#include "sampling.h"
#include "stats.h"
#include "whitted.h"

void path_world_init(struct path_world *pw, const struct world *world, const struct emitter_list *emitters,
                     const struct camera *camera, const struct path_settings *settings) {
    pw->world = world;
    pw->emitters = emitters;
    pw->camera = camera;
    pw->settings = *settings;
    pw->camera_inside = interior_at_point(world, camera->eye);
    pw->surface = NULL;
}

/* The power heuristic with exponent 2: the weight of an estimate drawn with density `mine` when another
 * strategy could have drawn the same light with density `other`. */
static double power_heuristic(double mine, double other) {
    return mine * mine / (mine * mine + other * other);
}

/* Stops the shadow search at the first crossing. */
static bool stop_at_first(void *context, double t, int material) {
    (void)t;
    (void)material;
    *(bool *)context = true;
    return false;
}

/* True when nothing lies between `from` and `to`. */
static bool in_view(const struct world *w, vec3 from, vec3 to) {
    vec3 d = vec3_sub(to, from);
    double distance = vec3_length(d);
    ray r = {from, vec3_scale(d, 1.0 / distance)};
    bool blocked = false;
    stats_thread.shadow_rays++;
    world_for_each_crossing(w, &r, ray_t_min(from), distance * (1.0 - PATH_SHADOW_SHORTEN), stop_at_first, &blocked);
    return !blocked;
}

/* TASK 15.1: next-event estimation, and its weight against scattering */
vec3 path_direct_light(const struct path_world *pw, struct sample_stream *rng, vec3 point, vec3 normal,
                       const struct bsdf *b) {
    double u_pick = sample_stream_next(rng), u1 = sample_stream_next(rng), u2 = sample_stream_next(rng);
    struct emitter_sample e;
    if (!emitter_sample(pw->emitters, u_pick, u1, u2, &e))
        return vec3_make(0, 0, 0);
    vec3 d = vec3_sub(e.point, point);
    double distance2 = vec3_dot(d, d);
    vec3 wi = vec3_scale(d, 1.0 / sqrt(distance2));
    double cos_here = vec3_dot(normal, wi), cos_there = fabs(vec3_dot(e.normal, wi));
    if (!(cos_here > 0.0 && cos_there > 0.0) || !in_view(pw->world, point, e.point))
        return vec3_make(0, 0, 0);
    double p_light = e.density * distance2 / cos_there;
    double weight = 1.0;
    if (pw->settings.strategy == PATH_MIS)
        weight = power_heuristic(p_light, b->p_diffuse * cos_here / M_PI);
    return vec3_scale(vec3_mul(b->albedo, e.radiance), cos_here / M_PI / p_light * weight);
}

/* Next-event estimation at `point` of a surface of pw->surface (material m, its normal facing wo): as
 * path_direct_light, with the surface's f |cos| and, under PATH_MIS, its own density to weigh against. */
/* TASK 15.1 ALSO: next-event estimation at a surface of pw->surface */
static vec3 surface_direct_light(const struct path_world *pw, struct sample_stream *rng, vec3 point, vec3 normal,
                                 const struct material *m, vec3 wo, double eta) {
    double u_pick = sample_stream_next(rng), u1 = sample_stream_next(rng), u2 = sample_stream_next(rng);
    struct emitter_sample e;
    if (!emitter_sample(pw->emitters, u_pick, u1, u2, &e))
        return vec3_make(0, 0, 0);
    vec3 d = vec3_sub(e.point, point);
    double distance2 = vec3_dot(d, d);
    vec3 wi = vec3_scale(d, 1.0 / sqrt(distance2));
    double p_scatter;
    vec3 f_cos = pw->surface->eval(m, normal, wo, wi, eta, &p_scatter);
    double cos_there = fabs(vec3_dot(e.normal, wi));
    if (!(cos_there > 0.0) || emitter_power(f_cos) == 0.0 || !in_view(pw->world, point, e.point))
        return vec3_make(0, 0, 0);
    double p_light = e.density * distance2 / cos_there;
    double weight = pw->settings.strategy == PATH_MIS ? power_heuristic(p_light, p_scatter) : 1.0;
    return vec3_scale(vec3_mul(f_cos, e.radiance), weight / p_light);
}

/* The radiance arriving along r (a camera ray, inside the objects of `inside`), by one path, drawing its
 * numbers from rng in the order path_sample's contract gives (path_trace.h). */
/* TASK 15.2: the path: emission, scattering, Russian roulette */
static vec3 radiance(const struct path_world *pw, ray r, struct interior_list inside, struct sample_stream *rng) {
    const struct scene *s = pw->world->scene;
    const struct path_settings *set = &pw->settings;
    vec3 sum = vec3_make(0, 0, 0), throughput = vec3_make(1, 1, 1);
    bool delta = true;      /* the last direction was the camera's, a mirror's or glass's */
    double p_scatter = 0.0; /* otherwise its density per solid angle */
    for (int bounce = 0;; bounce++) {
        struct hit h = hit_nothing(INFINITY);
        if (!world_closest(pw->world, &r, bounce == 0 ? RAY_T_MIN : ray_t_min(r.origin), &h)) /* ray.h */
            return vec3_add(sum, vec3_mul(throughput, s->background));
        vec3 point = ray_at(r, h.t);
        const struct material *m = &s->materials[h.material];
        struct material painted;
        if (s->paint != NULL)
            m = s->paint(s, &h, point, &painted);
        vec3 normal = hit_facing_normal(&h, r.direction);
        if (emitter_power(m->emission) > 0.0) {
            double weight = 1.0;
            if (!delta && set->strategy == PATH_LIGHT)
                weight = 0.0; /* next-event estimation counted it already */
            else if (!delta && set->strategy == PATH_MIS) {
                double cos_there = fabs(vec3_dot(h.normal, r.direction));
                double p_light = emitter_density(pw->emitters, m->emission) * h.t * h.t / cos_there;
                weight = power_heuristic(p_scatter, p_light);
            }
            sum = vec3_add(sum, vec3_scale(vec3_mul(throughput, m->emission), weight));
        }
        if (bounce > set->bounces)
            return sum;
        struct bsdf b = bsdf_of_material(m);
        vec3 direction;
        if (pw->surface != NULL && pw->surface->claims(m)) {
            struct interior_list beyond = inside;
            double eta = b.glass ? interior_cross(&beyond, h.object, b.ior) : 1.0;
            vec3 wo = vec3_scale(r.direction, -1.0);
            if (set->strategy != PATH_SCATTER)
                sum = vec3_add(sum, vec3_mul(throughput, surface_direct_light(pw, rng, point, normal, m, wo, eta)));
            double u_lobe = sample_stream_next(rng), u1 = sample_stream_next(rng), u2 = sample_stream_next(rng);
            struct path_scatter scattered;
            if (!pw->surface->sample(m, normal, wo, eta, u_lobe, u1, u2, &scattered))
                return sum;
            direction = scattered.direction;
            throughput = vec3_mul(throughput, scattered.weight);
            p_scatter = scattered.pdf;
            delta = scattered.delta;
            if (scattered.crossed) {
                inside = beyond;
                stats_thread.refracted_rays++;
            } else
                stats_thread.reflected_rays++;
        } else if (b.glass) {
            struct interior_list beyond = inside;
            double eta = interior_cross(&beyond, h.object, b.ior);
            double cos_i = -vec3_dot(r.direction, normal);
            vec3 refracted;
            if (sample_stream_next(rng) < bsdf_fresnel(cos_i, eta) ||
                !whitted_refract(r.direction, normal, eta, &refracted)) {
                direction = phong_reflect(r.direction, normal);
                stats_thread.reflected_rays++;
            } else {
                direction = refracted;
                throughput = vec3_mul(throughput, b.tint);
                inside = beyond;
                stats_thread.refracted_rays++;
            }
            delta = true;
        } else {
            if (b.p_diffuse > 0.0 && set->strategy != PATH_SCATTER)
                sum = vec3_add(sum, vec3_mul(throughput, path_direct_light(pw, rng, point, normal, &b)));
            double u_lobe = sample_stream_next(rng), u1 = sample_stream_next(rng), u2 = sample_stream_next(rng);
            if (b.p_diffuse == 0.0 && b.mirror == 0.0)
                return sum; /* black: nothing scatters */
            if (u_lobe < b.p_diffuse) {
                direction = sampling_cosine_hemisphere(normal, u1, u2);
                /* f cos / density = (albedo / pi) cos / (p_diffuse cos / pi) */
                throughput = vec3_scale(vec3_mul(throughput, b.albedo), 1.0 / b.p_diffuse);
                p_scatter = b.p_diffuse * vec3_dot(direction, normal) / M_PI;
                delta = false;
            } else {
                direction = phong_reflect(r.direction, normal);
                throughput = vec3_scale(throughput, b.mirror / (1.0 - b.p_diffuse));
                delta = true;
            }
            stats_thread.reflected_rays++;
        }
        if (bounce >= set->roulette) {
            double keep = fmin(PATH_ROULETTE_MOST, vec3_largest(throughput));
            if (!(sample_stream_next(rng) < keep))
                return sum;
            throughput = vec3_scale(throughput, 1.0 / keep);
        }
        r = (ray){point, vec3_normalize(direction)};
    }
}

vec3 path_sample(const struct path_world *pw, int i, int j, uint32_t sample) {
    struct sample_stream rng = pw->settings.sampler == PATH_SAMPLER_SOBOL
                                   ? sample_stream_stratified((uint32_t)i, (uint32_t)j, sample, pw->settings.seed)
                                   : sample_stream_start((uint32_t)i, (uint32_t)j, sample, pw->settings.seed);
    double x = i + sample_stream_next(&rng), y = j + sample_stream_next(&rng);
    ray r = camera_ray_through(pw->camera, x, y);
    stats_thread.primary_rays++;
    return radiance(pw, r, pw->camera_inside, &rng);
}

vec3 path_pixel(const struct path_world *pw, int i, int j, vec3 *variance) {
    struct path_pixel_sum sum = {vec3_make(0, 0, 0), vec3_make(0, 0, 0), 0};
    return path_pixel_resume(pw, i, j, &sum, variance);
}

vec3 path_pixel_resume(const struct path_world *pw, int i, int j, struct path_pixel_sum *sum, vec3 *variance) {
    /* Welford's running mean and sum of squared differences: steady however many paths. */
    int n = pw->settings.samples;
    if (sum->count > n)
        *sum = (struct path_pixel_sum){vec3_make(0, 0, 0), vec3_make(0, 0, 0), 0};
    vec3 mean = sum->mean, squares = sum->squares;
    for (int k = sum->count; k < n; k++) {
        vec3 x = path_sample(pw, i, j, (uint32_t)k);
        vec3 before = vec3_sub(x, mean);
        mean = vec3_add_scaled(mean, before, 1.0 / (k + 1));
        squares = vec3_add(squares, vec3_mul(before, vec3_sub(x, mean)));
    }
    *sum = (struct path_pixel_sum){mean, squares, n};
    if (variance != NULL)
        *variance = n > 1 ? vec3_scale(squares, 1.0 / (n - 1)) : vec3_make(0, 0, 0);
    return mean;
}

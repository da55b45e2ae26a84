/* path_trace.h: the rendering equation solved by Monte Carlo, one path per sample (chapter 15;
 * docs/15-paths.md).
 *
 * The radiance leaving a point x towards the eye is what x emits plus what it reflects of the light
 * arriving from every direction:
 *     L(x, wo) = Le(x) + integral over the hemisphere of f(x, wi, wo) L(y(x, wi), -wi) cos(theta_i) dwi
 * A path estimates it with one direction at each point it reaches, chosen at random, weighted by
 * f cos / density; the mean of many paths converges to L. At a Lambertian point (bsdf.h) two estimates
 * of the direct light are made and combined:
 *   - next-event estimation: a point y chosen on the emitters (emitter.h), its light taken through a
 *     shadow ray, density p_light = emitter_density * d^2 / |cos at y| per solid angle;
 *   - scattering: the direction drawn about the normal with density p_scatter = p_diffuse cos / pi,
 *     whose ray may itself hit an emitter.
 * Each counts with its power-heuristic weight, p^2 / (p_light^2 + p_scatter^2), so the two add up to the
 * light once (PATH_MIS); PATH_LIGHT keeps only the first (weight 1), PATH_SCATTER only the second. After a
 * mirror or glass (a delta direction no emitter point can be chosen for) an emitter counts in full.
 * From bounce `roulette` on, a path goes on with probability q = min(PATH_ROULETTE_MOST, largest channel
 * of its throughput) and its throughput is divided by q when it does: Russian roulette, which ends paths
 * without bias. Every random number comes from the path's stream (sampling.h), keyed by the pixel, the
 * sample and the seed, so a picture is bit-identical for any thread count. */
#ifndef WHITTED_PATH_TRACE_H
#define WHITTED_PATH_TRACE_H

#include <stdint.h>

#include "bsdf.h"
#include "camera.h"
#include "emitter.h"
#include "interior.h"
#include "path_settings.h"
#include "sampling.h"
#include "world.h"

/* Russian roulette never keeps a path with a higher probability than this, so every path ends. */
#define PATH_ROULETTE_MOST 0.95
/* A shadow ray towards a point of an emitter stops this share of the distance short of it, so that it
 * does not find the emitter's own surface at the end. */
#define PATH_SHADOW_SHORTEN 1e-7

/* A direction a surface of path_surface scattered into (chapter 17's rough surfaces). */
struct path_scatter {
    vec3 direction; /* unit length */
    vec3 weight;    /* f |cos| / pdf: what the path's throughput is multiplied by */
    double pdf;     /* the density per solid angle with which sample draws it, over all its lobes (> 0;
                     * not used when delta) */
    bool crossed;   /* the direction goes through the surface, into or out of the object */
    bool delta;     /* the only direction the surface sends the light in, as a smooth mirror's or glass's:
                     * it has no density, and an emitter it finds counts whole (no MIS) */
};

/* Surfaces this chapter does not know, plugged in by a later one: chapter 17's rough surfaces
 * (rough_surface.h). A material the surface claims is drawn through its three functions instead of
 * bsdf.h's smooth ones; directions point away from the point, `normal` is the unit normal on the side
 * of wo, and eta is the index on wo's side over the index beyond the surface (bsdf_fresnel's eta). */
struct path_surface {
    /* True when this surface draws material m. */
    bool (*claims)(const struct material *m);
    /* Returns f(wo, wi) |normal . wi|, the light going from wi to wo per unit of light arriving, and
     * stores in *pdf the density with which sample would draw wi (0 where it never does). Black and 0
     * for a direction the surface does not scatter into (wi behind a surface that lets no light through). */
    vec3 (*eval)(const struct material *m, vec3 normal, vec3 wo, vec3 wi, double eta, double *pdf);
    /* Draws a direction from three uniform numbers (the lobe, then two for the direction). Returns false
     * when the numbers give no direction (the light is absorbed: the path ends). */
    bool (*sample)(const struct material *m, vec3 normal, vec3 wo, double eta, double u_lobe, double u1,
                   double u2, struct path_scatter *out);
};

/* What a path traces through: the world, its emitters, the camera and the settings. */
struct path_world {
    const struct world *world;
    const struct emitter_list *emitters;
    const struct camera *camera;
    struct path_settings settings;
    struct interior_list camera_inside; /* the glass objects the eye is inside (chapter 8) */
    const struct path_surface *surface; /* chapter 17's rough surfaces; NULL: chapter 15's only */
};

/* Fills *pw, with no surface beyond chapter 15's (set pw->surface after to add one). The pointers are
 * kept, not copied. Cannot fail. */
void path_world_init(struct path_world *pw, const struct world *world, const struct emitter_list *emitters,
                     const struct camera *camera, const struct path_settings *settings);

/* Next-event estimation at `point` of a Lambertian surface b (its unit normal `normal` facing the path):
 * draws three numbers from rng (which emitter, then the point on it: u_pick, u1, u2, as emitter_sample
 * takes them), sends a shadow ray to the chosen point and returns the light it brings,
 *     albedo / pi * Le * cos_here / p_light * weight
 * with p_light = density * distance^2 / |cos there| the point's density per solid angle and weight the
 * power heuristic against scattering (p_diffuse cos_here / pi) under PATH_MIS, else 1. Returns black when
 * there are no emitters, the point is behind the surface or edge-on, or something is in the way. Counts
 * its shadow ray in stats_thread.shadow_rays. */
vec3 path_direct_light(const struct path_world *pw, struct sample_stream *rng, vec3 point, vec3 normal,
                       const struct bsdf *b);

/* Returns the radiance one path brings to the camera: sample `sample` of pixel (i, j), through a point of
 * the pixel drawn from its stream (sample_stream_start(i, j, sample, seed), then x and y in the pixel).
 * At each surface the path draws, in this order: at a surface of pw->surface, its next-event estimate's
 * three numbers (unless the strategy is PATH_SCATTER), then three to scatter; at glass one number
 * (reflect when under Fresnel's share); elsewhere, path_direct_light's three when the surface is Lambertian and the strategy is not
 * PATH_SCATTER, then three to scatter (the part, Lambertian or mirror, then the direction); from bounce
 * `roulette` on, one more for Russian roulette. Counts its rays in stats_thread. Safe on several threads at once. */
vec3 path_sample(const struct path_world *pw, int i, int j, uint32_t sample);

/* Returns pixel (i, j)'s estimate, the mean of settings.samples paths (samples 0, 1, ...); when variance
 * is not NULL, stores there each channel's variance of one path about that mean (divide by the samples
 * for the variance of the estimate). */
vec3 path_pixel(const struct path_world *pw, int i, int j, vec3 *variance);

/* A pixel's running sums so far (Welford's): `count` paths (samples 0 .. count - 1), their mean and the
 * sum of their squared differences from it. All zero before the first path. */
struct path_pixel_sum {
    vec3 mean, squares;
    int count;
};

/* path_pixel resumed: adds pixel (i, j)'s paths sum->count .. settings.samples - 1 to *sum (starting
 * again from zero when sum->count is past settings.samples) and returns the mean of all of them, the
 * variance as path_pixel's. The numbers equal path_pixel's at that count, bit for bit: path_pixel is this
 * with a zero sum. (The page draws a path-traced picture in passes of more and more samples this way.) */
vec3 path_pixel_resume(const struct path_world *pw, int i, int j, struct path_pixel_sum *sum, vec3 *variance);

#endif

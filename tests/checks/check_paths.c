/* check_paths.c: the coursework checks of chapter 15: next-event estimation against the light a glowing
 * ball sheds on a point, worked out by hand, and the path against the white furnace, whose answer is
 * Le / (1 - rho), with the statistical proofs of tests/support/path_proofs.c (the coursework kit). */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "path_proofs.h"

/* Standard errors a mean may be off before a check calls it wrong: 4 leaves a correct answer failing
 * once in 16,000 draws, and the numbers here are fixed, so a correct answer passes every time. */
#define PATHS_ERRORS 4.0

/* ---- 15.1 path_direct_light ------------------------------------------------------------------------ */

/* A white ball of radius 0.5 glowing with radiance 1, centred 2 above the origin, and `extra` lines. */
#define GLOW_BALL "camera eye 0 1 5 target 0 1 0 fov 40\nimage 4 4\npaths strategy light\n" \
                  "material glow colour 0 0 0 emission 1 1 1\nsphere centre 0 2 0 radius 0.5 material glow\n"

/* The mean and standard error of `count` estimates of path_direct_light at the origin with `normal`, on a
 * white Lambertian surface, in the scene GLOW_BALL + extra. */
static bool direct_mean(const char *extra, vec3 normal, double *mean, double *error, char *why, size_t why_size) {
    char text[1024];
    snprintf(text, sizeof text, "%s%s", GLOW_BALL, extra);
    struct path_setup t;
    if (!path_setup_text(&t, text, why, why_size))
        return false;
    struct bsdf white = {.albedo = {1, 1, 1}, .p_diffuse = 1.0};
    enum { COUNT = 20000 };
    double sum = 0, sum2 = 0;
    char n[64];
    check_calling("path_direct_light", "the origin, normal %s, under a glowing ball 2 above it", check_vec_text(normal, n));
    for (int k = 0; k < COUNT; k++) {
        struct sample_stream rng = sample_stream_start((uint32_t)k, 0, 0, 15);
        double x = path_direct_light(&t.paths, &rng, vec3_make(0, 0, 0), normal, &white).y;
        sum += x;
        sum2 += x * x;
    }
    path_setup_free(&t);
    *mean = sum / COUNT;
    *error = sqrt(fmax(0.0, sum2 / COUNT - *mean * *mean) / (COUNT - 1));
    return true;
}

/* A ball of radiance L seen under the half-angle alpha, wholly above the surface, sheds the irradiance
 * pi L sin^2(alpha) cos(theta) on it (theta between the normal and the ball's centre); a white Lambertian
 * surface sends 1 / pi of it on: here sin(alpha) = 0.25, so 1/16 times cos(theta). */
static bool direct_is(vec3 normal, double expected, const char *what, char *why, size_t why_size) {
    double mean, error;
    if (!direct_mean("", normal, &mean, &error, why, why_size))
        return false;
    if (fabs(mean - expected) <= PATHS_ERRORS * error + 1e-12)
        return true;
    snprintf(why, why_size, "%s: 20000 calls of path_direct_light average %.5f (standard error %.5f), expected %.5f: "
             "albedo / pi * Le * cos here / p_light, with p_light = density * d^2 / |cos there|", what, mean, error,
             expected);
    return false;
}

CHECK(check_direct_overhead) {
    return direct_is(vec3_make(0, 1, 0), 1.0 / 16, "the ball straight above a white point", why, why_size);
}

CHECK(check_direct_tilted) {
    return direct_is(vec3_make(sqrt(3) / 2, 0.5, 0), 1.0 / 32,
                     "the surface tilted by 60 degrees: half the light (the cosine at the point)", why, why_size);
}

CHECK(check_direct_blocked_or_behind) {
    /* Nothing is an answer only beside a point that does see the ball: without the triangle, facing up,
     * the same point must get its 1/16 first (an empty body would pass the two cases below). */
    if (!direct_is(vec3_make(0, 1, 0), 1.0 / 16, "before hiding it, the ball straight above a white point", why,
                   why_size))
        return false;
    double mean, error;
    if (!direct_mean("triangle a -5 1 -5 b 5 1 -5 c 0 1 5\n", vec3_make(0, 1, 0), &mean, &error, why, why_size))
        return false;
    if (mean != 0.0) {
        snprintf(why, why_size, "a triangle hides the ball from the point, but path_direct_light brings %.5f on "
                 "average: the shadow ray must stop short of the emitter and see the triangle", mean);
        return false;
    }
    if (!direct_mean("", vec3_make(0, -1, 0), &mean, &error, why, why_size))
        return false;
    if (mean != 0.0) {
        snprintf(why, why_size, "the ball is behind the surface (normal pointing down), but path_direct_light brings "
                 "%.5f on average: light from behind (cos here <= 0) counts nothing", mean);
        return false;
    }
    return true;
}

/* ---- 15.2 the path --------------------------------------------------------------------------------- */

/* The furnace of path_proofs.c for each rho, with `strategy`; the first that fails is described. */
static bool furnace_holds(const char *strategy, const char *hint, char *why, size_t why_size) {
    const double rhos[] = {0.3, 0.6, 0.8};
    for (int k = 0; k < 3; k++) {
        struct furnace_result f;
        check_calling("path_pixel", "the white furnace of albedo %g, strategy %s", rhos[k], strategy);
        if (!path_proof_furnace(rhos[k], strategy, &f, why, why_size))
            return false;
        if (!path_proof_furnace_passes(&f, PATHS_ERRORS)) {
            snprintf(why, why_size, "inside a closed sphere that glows 0.5 and reflects %g (strategy %s) every pixel "
                     "should converge to 0.5 / (1 - %g) = %.4f, but the picture's mean is %.4f (standard error %.4f): %s%s",
                     rhos[k], strategy, rhos[k], f.expected, f.mean[1], f.error[1], hint,
                     f.error[1] != 0.0 ? ""
                                       : " (every pixel came out the same, with no noise at all: does radiance return a "
                                         "constant, such as a stub's black, or do all pixels draw the same random numbers?)");
            return false;
        }
    }
    return true;
}

CHECK(check_furnace_scatter) {
    return furnace_holds("scatter", "with scattering alone the throughput is multiplied by f cos / density = albedo "
                         "(cosine-weighted directions), and divided by q when Russian roulette keeps the path", why,
                         why_size);
}

CHECK(check_furnace_light) {
    return furnace_holds("light", "with light sampling alone an emitter found by scattering counts only after a "
                         "mirror or glass (or from the camera); next-event estimation brings the rest", why, why_size);
}

CHECK(check_furnace_mis) {
    return furnace_holds("mis", "with both, an emitter found by scattering counts with the power heuristic's "
                         "weight p_scatter^2 / (p_scatter^2 + p_light^2), or the light is counted twice", why, why_size);
}

CHECK(check_pixels_uncorrelated) {
    double correlation;
    check_calling("path_pixel", "16 x 16 pixels of a white furnace, 2 paths each");
    if (!path_proof_neighbour_correlation(&correlation, why, why_size))
        return false;
    if (isnan(correlation)) {
        snprintf(why, why_size, "every pixel of the furnace came out the same value, so there is no noise at all: "
                 "radiance returns a constant (a stub?) instead of following random paths that scatter and meet "
                 "the glowing walls");
        return false;
    }
    if (fabs(correlation) < 0.25)
        return true;
    snprintf(why, why_size, "the noise of neighbouring pixels is correlated (%.2f; unrelated noise gives 0 +- 0.07): each "
             "pixel's paths need random numbers of their own, sample_stream_start(i, j, sample, seed)", correlation);
    return false;
}

CHECK(check_strategies_agree) {
    struct strategies_result r;
    check_calling("path_pixel", "a floor under a small bright ball and a large dim panel, by mis, light and scatter");
    if (!path_proof_strategies(&r, why, why_size))
        return false;
    if (r.worst_z > PATHS_ERRORS) {
        snprintf(why, why_size, "light sampling, scattering and MIS must converge to one picture, but their 6 x 6 "
                 "blocks differ by %.1f standard errors: %s", r.worst_z, r.worst);
        return false;
    }
    return true;
}

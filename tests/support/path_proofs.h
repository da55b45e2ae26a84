/* path_proofs.h: the statistical proofs that chapter 15's path tracer is right, shared by its tests
 * (tests/test_paths.c, in make test) and its coursework checks (tests/checks/check_paths.c, which the
 * gallery's faults must fail): the white furnace, uncorrelated pixels, the error falling as 1 / sqrt(N),
 * and the three strategies agreeing with MIS the least noisy. Each renders a small picture with the
 * chapter's own functions (path_pixel) and reports numbers; the callers decide what passes. */
#ifndef WHITTED_PATH_PROOFS_H
#define WHITTED_PATH_PROOFS_H

#include <stdbool.h>
#include <stddef.h>

#include "accel.h"
#include "camera.h"
#include "emitter.h"
#include "path_trace.h"
#include "scene.h"

/* Everything a path needs, built from a scene. */
struct path_setup {
    struct scene scene;
    struct accel_world *world;
    struct emitter_list emitters;
    struct camera camera;
    struct path_world paths;
};

/* Builds *t from scene text (named "paths.scene" in messages), or from a scene file changed by --set
 * specs. Returns false with the reason in err; on success free with path_setup_free. */
bool path_setup_text(struct path_setup *t, const char *text, char *err, size_t err_size);
bool path_setup_file(struct path_setup *t, const char *path, const char *const *sets, int set_count, char *err,
                     size_t err_size);
void path_setup_free(struct path_setup *t);

/* Renders t's picture: pixel (i, j)'s mean into means[j * width + i] and, when variances is not NULL, the
 * per-path variance there. */
void path_setup_render(const struct path_setup *t, vec3 *means, vec3 *variances);

/* The white furnace: inside a closed sphere that emits 0.5 and reflects a share rho, seen by 8 x 8 pixels
 * with 32 paths each by `strategy` ("mis", "light" or "scatter"). */
struct furnace_result {
    double mean[3];  /* the image mean per channel */
    double error[3]; /* its standard error: the pixels' spread over sqrt(64) */
    double expected; /* Le / (1 - rho), less the light of paths longer than the cap */
};
bool path_proof_furnace(double rho, const char *strategy, struct furnace_result *r, char *err, size_t err_size);

/* The same furnace with the paths line's `bounces` set (-1: left out, the default cap, as
 * path_proof_furnace does). The expected value is the truncated series
 * Le (1 + rho + ... + rho^(bounces + 1)) = Le (1 - rho^(bounces + 2)) / (1 - rho): the first surface,
 * `bounces` more, and the light of the one after, found by next-event estimation or by hitting it. */
bool path_proof_furnace_capped(double rho, const char *strategy, int bounces, struct furnace_result *r, char *err,
                               size_t err_size);

/* Whether every channel of r is within `errors` standard errors of the expected value (and 1e-12). */
bool path_proof_furnace_passes(const struct furnace_result *r, double errors);

/* The correlation of horizontally neighbouring pixels' values in a furnace of rho 0.5 seen by 16 x 16
 * pixels with 2 paths each: near 0 when each pixel's random numbers are its own; NaN when the pixels have no
 * spread at all (every pixel the same value: no noise to correlate). */
bool path_proof_neighbour_correlation(double *correlation, char *err, size_t err_size);

/* The same on side x side pixels: side (side - 1) pairs, whose correlation, for unrelated noise, is 0 with a
 * standard deviation of about 1 / sqrt(side (side - 1)). */
bool path_proof_neighbour_correlation_of(int side, double *correlation, char *err, size_t err_size);

/* The slope of log RMSE against log N for N = 1, 4, 16, 64, 256 paths a pixel, on 24 x 24 pixels of the
 * Cornell box of `scene` with its balls made white, seen below the lamp (fov 28 towards (278, 200, 0)),
 * against a reference of 1024 paths whose own variance is taken off the mean square; rmse[5] gets the
 * five errors. */
bool path_proof_convergence(const char *scene, double *slope, double rmse[5], char *err, size_t err_size);

/* A floor under a small bright ball and a large dim panel, rendered with mis, light and scatter
 * (index 0, 1, 2), 24 x 24 pixels of 128 paths. worst_z is the largest difference of two strategies'
 * means over a 6 x 6 block of pixels, in combined standard errors; variance[s][0] the per-path variances
 * summed under the ball (left half), [s][1] under the panel (right half). */
struct strategies_result {
    double worst_z;
    char worst[160]; /* which blocks and strategies gave it */
    double variance[3][2];
};
bool path_proof_strategies(struct strategies_result *r, char *err, size_t err_size);

#endif

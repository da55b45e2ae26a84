/* path_proofs.c: the statistical proofs of chapter 15's path tracer, for its tests and its coursework
 * checks. */
#include "path_proofs.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "box.h"
#include "plane.h"
#include "scene_set.h"
#include "sphere.h"
#include "triangle.h"

/* Every kind of shape, as chapter 15 draws them (this file is linked without Criterion, into the grader
 * too, so not test_support's list). */
static const struct shape_kind *const every_kind[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};

/* The rest of the set-up once the scene is read. */
static bool setup_from_scene(struct path_setup *t, char *err, size_t err_size) {
    t->world = NULL;
    memset(&t->emitters, 0, sizeof t->emitters);
    if (emitter_add_area_lights(&t->scene, err, err_size) < 0)
        return false;
    struct accel_choice none = {.kind = ACCEL_NONE, .sah = true};
    t->world = accel_world_create(&t->scene, &none, err, err_size);
    if (t->world == NULL || !emitter_list_build(&t->emitters, t->world, err, err_size))
        return false;
    const struct scene *s = &t->scene;
    if (!camera_init(&t->camera, s->eye, s->target, s->up, s->fov, s->width, s->height, err, err_size))
        return false;
    path_world_init(&t->paths, &t->world->world, &t->emitters, &t->camera, &s->paths);
    return true;
}

bool path_setup_text(struct path_setup *t, const char *text, char *err, size_t err_size) {
    memset(t, 0, sizeof *t);
    if (!scene_parse("paths.scene", text, every_kind, &t->scene, err, err_size))
        return false;
    if (setup_from_scene(t, err, err_size))
        return true;
    path_setup_free(t);
    return false;
}

bool path_setup_file(struct path_setup *t, const char *path, const char *const *sets, int set_count, char *err,
                     size_t err_size) {
    memset(t, 0, sizeof *t);
    bool bad_option = false;
    if (!scene_load_changed(path, sets, set_count, every_kind, &t->scene, &bad_option, err, err_size))
        return false;
    if (setup_from_scene(t, err, err_size))
        return true;
    path_setup_free(t);
    return false;
}

void path_setup_free(struct path_setup *t) {
    emitter_list_free(&t->emitters);
    if (t->world != NULL)
        accel_world_destroy(t->world);
    scene_free(&t->scene);
    t->world = NULL;
}

void path_setup_render(const struct path_setup *t, vec3 *means, vec3 *variances) {
    for (int j = 0; j < t->scene.height; j++)
        for (int i = 0; i < t->scene.width; i++) {
            vec3 v;
            means[j * t->scene.width + i] = path_pixel(&t->paths, i, j, &v);
            if (variances != NULL)
                variances[j * t->scene.width + i] = v;
        }
}

/* ---- the white furnace ---------------------------------------------------------------------------- */

#define FURNACE_LE 0.5
#define FURNACE_SIDE 8

bool path_proof_furnace_capped(double rho, const char *strategy, int bounces, struct furnace_result *r, char *err,
                               size_t err_size) {
    char text[1024], cap[32] = "";
    if (bounces >= 0)
        snprintf(cap, sizeof cap, " bounces %d", bounces);
    else
        bounces = path_settings_default().bounces;
    snprintf(text, sizeof text,
             "camera eye 0 0 0 target 0 0 -1 fov 60\nimage %d %d\npaths samples 32 seed 3%s strategy %s\n"
             "material wall colour %.17g %.17g %.17g diffuse 1 emission %g %g %g\n"
             "sphere centre 0 0 0 radius 1 material wall\n",
             FURNACE_SIDE, FURNACE_SIDE, cap, strategy, rho, rho, rho, FURNACE_LE, FURNACE_LE, FURNACE_LE);
    struct path_setup t;
    if (!path_setup_text(&t, text, err, err_size))
        return false;
    enum { PIXELS = FURNACE_SIDE * FURNACE_SIDE };
    vec3 means[PIXELS];
    path_setup_render(&t, means, NULL);
    path_setup_free(&t);
    /* The surfaces a path can reach are the first and `bounces` more, and the light of the one after
     * (found by next-event estimation or by hitting it): Le times 1 + rho + ... + rho^(bounces + 1). */
    r->expected = FURNACE_LE * (1.0 - pow(rho, bounces + 2)) / (1.0 - rho);
    for (int c = 0; c < 3; c++) {
        double sum = 0, sum2 = 0;
        for (int k = 0; k < PIXELS; k++) {
            sum += vec3_axis(means[k], c);
            sum2 += vec3_axis(means[k], c) * vec3_axis(means[k], c);
        }
        r->mean[c] = sum / PIXELS;
        double spread = sqrt(fmax(0.0, (sum2 - PIXELS * r->mean[c] * r->mean[c]) / (PIXELS - 1)));
        r->error[c] = spread / sqrt((double)PIXELS);
    }
    return true;
}

bool path_proof_furnace(double rho, const char *strategy, struct furnace_result *r, char *err, size_t err_size) {
    return path_proof_furnace_capped(rho, strategy, -1, r, err, err_size);
}

bool path_proof_furnace_passes(const struct furnace_result *r, double errors) {
    for (int c = 0; c < 3; c++)
        if (!(fabs(r->mean[c] - r->expected) <= errors * r->error[c] + 1e-12))
            return false;
    return true;
}

bool path_proof_neighbour_correlation_of(int side, double *correlation, char *err, size_t err_size) {
    char text[512];
    snprintf(text, sizeof text,
             "camera eye 0 0 0 target 0 0 -1 fov 10\nimage %d %d\npaths samples 2 seed 5 strategy scatter\n"
             "material wall colour 0.5 0.5 0.5 diffuse 1 emission 0.5 0.5 0.5\n"
             "sphere centre 0 0 0 radius 1 material wall\n",
             side, side);
    struct path_setup t;
    if (!path_setup_text(&t, text, err, err_size))
        return false;
    vec3 *means = malloc((size_t)side * (size_t)side * sizeof *means);
    if (means == NULL) {
        snprintf(err, err_size, "out of memory");
        path_setup_free(&t);
        return false;
    }
    path_setup_render(&t, means, NULL);
    path_setup_free(&t);
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    int n = 0;
    for (int j = 0; j < side; j++)
        for (int i = 0; i + 1 < side; i++, n++) {
            double a = means[j * side + i].x, b = means[j * side + i + 1].x;
            sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
        }
    free(means);
    double cov = sab / n - sa / n * sb / n, va = saa / n - sa / n * sa / n, vb = sbb / n - sb / n * sb / n;
    *correlation = va > 0 && vb > 0 ? cov / sqrt(va * vb) : NAN; /* no spread at all: every pixel alike */
    return true;
}

bool path_proof_neighbour_correlation(double *correlation, char *err, size_t err_size) {
    return path_proof_neighbour_correlation_of(16, correlation, err, err_size);
}

/* ---- convergence ---------------------------------------------------------------------------------- */

/* The Cornell box of `scene` with its two balls made white, seen below the lamp: the caustics of glass
 * and mirror come from rare bright paths, and each pixel on the lamp's edge is a coin toss between 17
 * and the ceiling's 0.05; either would make a few pixels most of the error, and the error of a few
 * samples a poor guide to the trend. Independent paths, whatever the scene says: their error falls as
 * 1 / sqrt(N), and the reference's own variance is its paths' spread over their count. */
static bool setup_cornell(struct path_setup *t, const char *scene, int side, int samples, int seed, char *err,
                          size_t err_size) {
    char image[64], set_samples[64], set_seed[64];
    snprintf(image, sizeof image, "image=%d %d", side, side);
    snprintf(set_samples, sizeof set_samples, "paths.samples=%d", samples);
    snprintf(set_seed, sizeof set_seed, "paths.seed=%d", seed);
    const char *sets[] = {image, "material.glass.transmit=0", "material.glass.diffuse=1", "material.mirror.reflection=0",
                          "material.mirror.diffuse=1", set_samples, set_seed, "paths.strategy=mis", "camera.fov=28",
                          "camera.target=278 200 0", "paths.sampler=independent"};
    return path_setup_file(t, scene, sets, 11, err, err_size);
}

bool path_proof_convergence(const char *scene, double *slope, double rmse[5], char *err, size_t err_size) {
    enum { SIDE = 24, PIXELS = SIDE * SIDE, REFERENCE = 1024 };
    vec3 *reference = malloc(3 * PIXELS * sizeof *reference), *spread = reference + PIXELS, *picture = spread + PIXELS;
    struct path_setup t;
    if (reference == NULL || !setup_cornell(&t, scene, SIDE, REFERENCE, 99, err, err_size)) {
        free(reference);
        return false;
    }
    path_setup_render(&t, reference, spread);
    path_setup_free(&t);
    /* The mean square against the reference is the estimate's variance, sigma^2 / N, plus the
     * reference's own, sigma^2 / REFERENCE, known from the reference's spread: taken off. */
    double reference_variance = 0;
    for (int p = 0; p < PIXELS; p++)
        for (int c = 0; c < 3; c++)
            reference_variance += vec3_axis(spread[p], c) / REFERENCE / (3 * PIXELS);
    const int samples[] = {1, 4, 16, 64, 256};
    double x[5], y[5];
    for (int k = 0; k < 5; k++) {
        if (!setup_cornell(&t, scene, SIDE, samples[k], k, err, err_size)) {
            free(reference);
            return false;
        }
        path_setup_render(&t, picture, NULL);
        path_setup_free(&t);
        double squares = 0;
        for (int p = 0; p < PIXELS; p++)
            for (int c = 0; c < 3; c++)
                squares += pow(vec3_axis(picture[p], c) - vec3_axis(reference[p], c), 2);
        x[k] = log((double)samples[k]);
        rmse[k] = sqrt(fmax(squares / (3 * PIXELS) - reference_variance, 1e-300));
        y[k] = log(rmse[k]);
    }
    free(reference);
    double mx = 0, my = 0, sxy = 0, sxx = 0; /* the least-squares line */
    for (int k = 0; k < 5; k++)
        mx += x[k] / 5, my += y[k] / 5;
    for (int k = 0; k < 5; k++)
        sxy += (x[k] - mx) * (y[k] - my), sxx += (x[k] - mx) * (x[k] - mx);
    *slope = sxy / sxx;
    return true;
}

/* ---- the strategies ------------------------------------------------------------------------------- */

/* Light sampling suits the ball (scattering rarely finds it), scattering suits the panel (most points
 * chosen on it are far and at a grazing angle to the floor under its edge); MIS should do well on both. */
#define TWO_LIGHTS "camera eye 0 6 0.01 target 0 0 0 fov 40\nimage 24 24\npaths samples 128 seed 11 strategy %s\n" \
                   "material floor colour 0.7 0.7 0.7 diffuse 1\nmaterial ball colour 0 0 0 emission 10 10 10\n"  \
                   "material panel colour 0 0 0 emission 1 1 1\n"                                                \
                   "plane normal 0 1 0 distance 0 material floor\n"                                              \
                   "sphere centre -1.3 0.6 0 radius 0.3 material ball\n"                                         \
                   "triangle a 0.2 0.3 -3 b 4 0.3 -3 c 4 0.3 3 material panel\n"                                 \
                   "triangle a 0.2 0.3 -3 b 4 0.3 3 c 0.2 0.3 3 material panel\n"
#define TWO_LIGHTS_SIDE 24
#define TWO_LIGHTS_SAMPLES 128
#define TWO_LIGHTS_BLOCK 6

struct strategy_picture {
    vec3 means[TWO_LIGHTS_SIDE * TWO_LIGHTS_SIDE], variances[TWO_LIGHTS_SIDE * TWO_LIGHTS_SIDE];
};

bool path_proof_strategies(struct strategies_result *r, char *err, size_t err_size) {
    static const char *const names[] = {"mis", "light", "scatter"};
    struct strategy_picture *pictures = malloc(3 * sizeof *pictures);
    if (pictures == NULL) {
        snprintf(err, err_size, "out of memory");
        return false;
    }
    for (int k = 0; k < 3; k++) {
        char text[1024];
        snprintf(text, sizeof text, TWO_LIGHTS, names[k]);
        struct path_setup t;
        if (!path_setup_text(&t, text, err, err_size)) {
            free(pictures);
            return false;
        }
        path_setup_render(&t, pictures[k].means, pictures[k].variances);
        path_setup_free(&t);
    }
    const int side = TWO_LIGHTS_SIDE, block = TWO_LIGHTS_BLOCK, count = block * block;
    r->worst_z = 0;
    r->worst[0] = '\0';
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++)
            for (int by = 0; by < side / block; by++)
                for (int bx = 0; bx < side / block; bx++) {
                    double ma = 0, mb = 0, va = 0, vb = 0;
                    for (int j = by * block; j < (by + 1) * block; j++)
                        for (int i = bx * block; i < (bx + 1) * block; i++) {
                            ma += pictures[a].means[j * side + i].y / count;
                            mb += pictures[b].means[j * side + i].y / count;
                            va += pictures[a].variances[j * side + i].y / TWO_LIGHTS_SAMPLES / ((double)count * count);
                            vb += pictures[b].variances[j * side + i].y / TWO_LIGHTS_SAMPLES / ((double)count * count);
                        }
                    /* blocks of the panel seen directly have no noise at all: any difference is infinite */
                    double z = va + vb > 0 ? fabs(ma - mb) / sqrt(va + vb) : ma == mb ? 0.0 : INFINITY;
                    if (!(z <= r->worst_z)) {
                        r->worst_z = z;
                        snprintf(r->worst, sizeof r->worst, "block (%d, %d): %s %.4f, %s %.4f, combined error %.4f", bx,
                                 by, names[a], ma, names[b], mb, sqrt(va + vb));
                    }
                }
    for (int k = 0; k < 3; k++)
        for (int half = 0; half < 2; half++) {
            double sum = 0;
            for (int j = 0; j < side; j++)
                for (int i = half * side / 2; i < (half + 1) * side / 2; i++)
                    sum += pictures[k].variances[j * side + i].y;
            r->variance[k][half] = sum;
        }
    free(pictures);
    return true;
}

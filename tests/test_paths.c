/* test_paths.c: chapter 15's path tracer: the paths line and emission read and refused, the emitters
 * gathered, the sampling densities, Fresnel's reflectance, and the proofs that the estimator is right:
 * the white furnace, error falling as 1 / sqrt(N), the three strategies agreeing with MIS the least
 * noisy, uncorrelated pixels, and the same picture for any thread count; the stratified sampler's
 * strata, and its paths unbiased and less noisy than independent ones. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bsdf.h"
#include "emitter.h"
#include "owen_sobol.h"
#include "path_image.h"
#include "path_proofs.h"
#include "path_trace.h"
#include "sampling.h"
#include "scene.h"
#include "scene_set.h"
#include "test_support.h"

#define SCENE_HEAD "camera eye 0 0 5 target 0 0 0 fov 40\nimage 16 12\n"

/* ---- the scene's lines ---------------------------------------------------------------------------- */

static bool parse_lines(const char *lines, struct scene *s, char *err, size_t err_size) {
    return parse_scene_lines("paths.scene", SCENE_HEAD, lines, test_every_kind, s, err, err_size);
}

static void expect_refused(const char *line, const char *message) {
    expect_scene_refused("paths.scene", SCENE_HEAD, line, test_every_kind, message);
}

Test(paths_line, keys_and_defaults_are_read) {
    struct scene s;
    char err[512] = "";
    cr_assert(parse_lines("material lamp emission 4 2 1", &s, err, sizeof err), "%s", err);
    cr_expect_eq(s.paths.samples, PATH_DEFAULT_SAMPLES);
    cr_expect_eq(s.paths.strategy, PATH_MIS);
    cr_expect_eq(s.paths.sampler, PATH_SAMPLER_INDEPENDENT);
    cr_expect_eq(s.paths.line, 0);
    cr_expect(s.materials[1].emission.x == 4 && s.materials[1].emission.y == 2 && s.materials[1].emission.z == 1);
    cr_expect(s.materials[0].emission.x == 0, "no emission by default");
    scene_free(&s);
    cr_assert(parse_lines("paths samples 9 seed 7 roulette 0 bounces 3 strategy scatter", &s, err, sizeof err), "%s", err);
    cr_expect(s.paths.samples == 9 && s.paths.seed == 7 && s.paths.roulette == 0 && s.paths.bounces == 3);
    cr_expect_eq(s.paths.strategy, PATH_SCATTER);
    cr_expect_eq(s.paths.line, 3);
    scene_free(&s);
    cr_assert(parse_lines("paths sampler sobol", &s, err, sizeof err), "%s", err);
    cr_expect_eq(s.paths.sampler, PATH_SAMPLER_SOBOL);
    cr_expect_str_eq(path_sampler_name(s.paths.sampler), "sobol");
    scene_free(&s);
}

Test(paths_line, bad_values_are_refused_with_file_and_line) {
    expect_refused("paths samples 0", "paths.scene:3: paths samples must be a whole number from 1 to 1048576, got 0");
    expect_refused("paths bounces 2.5", "paths.scene:3: paths bounces must be a whole number from 0 to 4096, got 2.5");
    expect_refused("paths strategy both", "paths.scene:3: unknown paths strategy 'both' (mis, light or scatter)");
    expect_refused("paths sampler halton", "paths.scene:3: unknown paths sampler 'halton' (independent or sobol)");
    expect_refused("paths samples 4\npaths samples 5", "paths.scene:4: a second paths line (a scene has one)");
    expect_refused("material lamp emission 1 -1 1",
                   "paths.scene:3: material 'lamp': emission must be finite and not negative");
}

Test(paths_line, chapters_before_15_ignore_emission_and_the_paths_line_with_a_note) {
    struct scene s;
    char err[512] = "", note[512] = "";
    cr_assert(parse_lines("paths samples 9\nmaterial lamp emission 4 2 1", &s, err, sizeof err), "%s", err);
    FILE *out = fmemopen(note, sizeof note, "w");
    scene_drop_unsupported(&s, 14, out);
    fclose(out);
    cr_expect_str_eq(note, "paths.scene: chapter 14 ignores the emission of 1 material, the paths line (not introduced yet)\n");
    cr_expect(s.materials[1].emission.x == 0 && s.paths.samples == PATH_DEFAULT_SAMPLES);
    scene_free(&s);
}

Test(paths_line, set_adds_the_line_when_the_scene_has_none) {
    const char *sets[] = {"paths.samples=3"};
    struct scene s;
    char err[512] = "";
    bool bad_option = false;
    cr_assert(scene_load_changed("scenes/14-textures.scene", sets, 1, test_every_kind, &s, &bad_option, err, sizeof err),
              "%s", err);
    cr_expect_eq(s.paths.samples, 3);
    scene_free(&s);
}

/* ---- densities ------------------------------------------------------------------------------------ */

Test(sampling, the_cosine_hemisphere_has_the_moments_of_cos_over_pi) {
    /* E[cos] = 2/3 and E[cos^2] = 1/2 under the density cos / pi; the directions are unit and above. */
    vec3 n = vec3_normalize(vec3_make(0.3, -0.5, 0.8));
    double sum = 0, sum2 = 0;
    int count = 200000;
    struct sample_stream rng = sample_stream_start(1, 2, 3, 4);
    for (int k = 0; k < count; k++) {
        vec3 d = sampling_cosine_hemisphere(n, sample_stream_next(&rng), sample_stream_next(&rng));
        cr_assert(fabs(vec3_length(d) - 1.0) < 1e-12 && vec3_dot(d, n) >= 0.0);
        sum += vec3_dot(d, n);
        sum2 += vec3_dot(d, n) * vec3_dot(d, n);
    }
    /* standard deviations of cos: sqrt(1/2 - 4/9) = 0.236; of cos^2: sqrt(1/3 - 1/4) = 0.289 */
    cr_expect(fabs(sum / count - 2.0 / 3.0) < 4 * 0.236 / sqrt(count), "E[cos] = %.5f", sum / count);
    cr_expect(fabs(sum2 / count - 0.5) < 4 * 0.289 / sqrt(count), "E[cos^2] = %.5f", sum2 / count);
}

Test(sampling, points_on_a_triangle_are_uniform) {
    /* Over the triangle (0,0,0), (1,0,0), (0,1,0) the mean point is the centroid (1/3, 1/3) and the
     * share with x + y < 1/2 is 1/4 of the area. */
    struct sample_stream rng = sample_stream_start(5, 6, 7, 8);
    double sx = 0, sy = 0;
    int inner = 0, count = 100000;
    for (int k = 0; k < count; k++) {
        vec3 p = sampling_triangle(vec3_make(0, 0, 0), vec3_make(1, 0, 0), vec3_make(0, 1, 0), sample_stream_next(&rng),
                                   sample_stream_next(&rng));
        cr_assert(p.x >= 0 && p.y >= 0 && p.x + p.y <= 1 + 1e-12);
        sx += p.x;
        sy += p.y;
        inner += p.x + p.y < 0.5;
    }
    cr_expect(fabs(sx / count - 1.0 / 3) < 0.004 && fabs(sy / count - 1.0 / 3) < 0.004, "mean %g %g", sx / count, sy / count);
    cr_expect(fabs((double)inner / count - 0.25) < 0.006, "share %g", (double)inner / count);
}

Test(sampling, fresnel_at_normal_incidence_and_total_internal_reflection) {
    cr_expect(fabs(bsdf_fresnel(1.0, 1 / 1.5) - 0.04) < 1e-12, "((n1 - n2) / (n1 + n2))^2 = 0.04");
    cr_expect(fabs(bsdf_fresnel(1.0, 1.5) - 0.04) < 1e-12, "the same leaving the glass");
    cr_expect_eq(bsdf_fresnel(0.5, 1.5), 1.0, "60 degrees inside glass: past the critical angle of 41.8");
    cr_expect(bsdf_fresnel(0.01, 1 / 1.5) > 0.9, "grazing: nearly all reflected");
    cr_expect_eq(bsdf_fresnel(0.7, 1.0), 0.0, "the same index: nothing reflected");
}

/* ---- the emitters ---------------------------------------------------------------------------------- */

Test(emitters, are_gathered_from_triangles_spheres_boxes_and_area_lights) {
    struct path_setup t;
    char err[512] = "";
    cr_assert(path_setup_text(&t, "camera eye 0 0 5 target 0 0 0 fov 40\nimage 4 4\nmaterial lamp emission 2 2 2\n"
                                  "triangle a 0 0 0 b 1 0 0 c 0 1 0 material lamp\nsphere centre 0 0 0 radius 1 material lamp\n"
                                  "box min 0 0 0 max 1 2 3 material lamp\nsphere centre 5 0 0 radius 1\n"
                                  "light position 0 4 0 colour 3 3 3 axis1 2 0 0 axis2 0 0 1 samples 2 2\n",
                              err, sizeof err),
              "%s", err);
    /* 1 triangle, 2 of the area light, 12 of the box, 1 sphere */
    cr_expect_eq(t.emitters.count, 16);
    double expected = 0.5 * 2 + 2 * 3 + 22 * 2 + 4 * M_PI * 2; /* area times mean radiance */
    cr_expect(fabs(t.emitters.total_power - expected) < 1e-9, "total power %g, expected %g", t.emitters.total_power,
              expected);
    cr_expect(fabs(emitter_density(&t.emitters, vec3_make(3, 3, 3)) - 3 / expected) < 1e-15);
    path_setup_free(&t);
}

Test(emitters, an_emissive_plane_is_refused) {
    struct path_setup t;
    char err[512] = "";
    cr_expect(!path_setup_text(&t, SCENE_HEAD "material sky emission 1 1 1\nplane normal 0 1 0 distance 0 material sky\n",
                               err, sizeof err));
    cr_expect_str_eq(err, "paths.scene:3: plane 1 has the emissive material 'sky': an infinite surface cannot be an "
                          "emitter (give the emission to a box or triangles)");
}

/* ---- the proofs ------------------------------------------------------------------------------------ */

/* Inside a closed sphere that emits Le and reflects a share rho of what reaches it, the radiance is the
 * same everywhere and in every direction: L = Le + rho L, so L = Le / (1 - rho). With either sampler. */
Test(furnace, every_strategy_converges_to_le_over_one_minus_rho) {
    const double rhos[] = {0.0, 0.3, 0.6, 0.8};
    const char *strategies[] = {"mis", "light", "scatter", "mis sampler sobol", "light sampler sobol",
                                "scatter sampler sobol"}; /* each with the stratified sampler too */
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 6; k++) {
            struct furnace_result f;
            char err[512] = "";
            cr_assert(path_proof_furnace(rhos[r], strategies[k], &f, err, sizeof err), "%s", err);
            cr_expect(path_proof_furnace_passes(&f, 3.0),
                      "rho %g, %s: image mean %.6f %.6f %.6f, Le / (1 - rho) = %.6f, standard error %.6f", rhos[r],
                      strategies[k], f.mean[0], f.mean[1], f.mean[2], f.expected, f.error[0]);
        }
}

/* A path stops after `bounces` bounces, so it gathers Le (1 + rho + ... + rho^(bounces + 1)): the cap cuts
 * the series, a bias of Le rho^(bounces + 2) / (1 - rho). Russian roulette keeps a path with probability
 * at most 0.95, so where rho is near 1 long paths keep their weight and the cut shows. */
Test(furnace, a_bounce_cap_cuts_the_series_and_the_default_keeps_the_cut_below_the_noise) {
    const char *strategies[] = {"mis", "light", "scatter"};
    for (int k = 0; k < 3; k++) {
        struct furnace_result f;
        char err[512] = "";
        /* rho 0.99 with 64 bounces: the truncated series 24.24, not Le / (1 - rho) = 50 */
        cr_assert(path_proof_furnace_capped(0.99, strategies[k], 64, &f, err, sizeof err), "%s", err);
        cr_expect_float_eq(f.expected, 0.5 * (1 - pow(0.99, 66)) / 0.01, 1e-9);
        cr_expect(path_proof_furnace_passes(&f, 3.0), "rho 0.99, 64 bounces, %s: mean %.4f, truncated series %.4f, standard error %.4f",
                  strategies[k], f.mean[0], f.expected, f.error[0]);
        cr_expect_gt(50.0 - f.mean[0], 10 * f.error[0], "the cut is far outside the noise: %.4f +- %.4f against 50",
                     f.mean[0], f.error[0]);
        /* the default cap at the brightest albedo the scene format allows for chapter 15, roulette's largest
         * chance of keeping a path (0.95, where a path's weight stops growing): the cut,
         * 10 * 0.95^(bounces + 2), is under a hundredth of the standard error */
        cr_assert(path_proof_furnace(PATH_ROULETTE_MOST, strategies[k], &f, err, sizeof err), "%s", err);
        double cut = 0.5 / (1 - PATH_ROULETTE_MOST) - f.expected;
        cr_expect_lt(cut, f.error[0] / 100, "rho %g, default cap %d: the cut %.3g against a standard error of %.3g",
                     PATH_ROULETTE_MOST, PATH_DEFAULT_BOUNCES, cut, f.error[0]);
        cr_expect(path_proof_furnace_passes(&f, 3.0), "rho %g, %s: mean %.4f, expected %.4f, standard error %.4f",
                  PATH_ROULETTE_MOST, strategies[k], f.mean[0], f.expected, f.error[0]);
    }
}

Test(furnace, neighbouring_pixels_noise_is_uncorrelated) {
    /* 100 x 100 pixels, 9,900 pairs: the correlation of unrelated noise has a standard deviation of about
     * 1 / sqrt(9900) = 0.010, and four of them are allowed; with every pixel drawing the same numbers the
     * neighbours would move together (near 1). */
    double correlation;
    char err[512] = "";
    cr_assert(path_proof_neighbour_correlation_of(100, &correlation, err, sizeof err), "%s", err);
    cr_expect(fabs(correlation) < 0.04, "neighbours' correlation %.4f", correlation);
    cr_log_info("neighbours' correlation over 100 x 100 pixels: %.4f", correlation);
}

Test(convergence, the_error_falls_as_one_over_the_square_root_of_the_samples) {
    double slope, rmse[5];
    char err[512] = "";
    cr_assert(path_proof_convergence("scenes/15-paths.scene", &slope, rmse, err, sizeof err), "%s", err);
    cr_expect(fabs(slope + 0.5) <= 0.05, "slope of log RMSE against log N: %.3f (RMSE %.4f %.4f %.4f %.4f %.4f at 1 to 256)",
              slope, rmse[0], rmse[1], rmse[2], rmse[3], rmse[4]);
}

Test(strategies, light_scatter_and_mis_converge_to_the_same_picture_and_mis_is_least_noisy) {
    struct strategies_result r;
    char err[512] = "";
    cr_assert(path_proof_strategies(&r, err, sizeof err), "%s", err);
    cr_expect(r.worst_z <= 4.0, "block means differ by %.1f combined standard errors: %s", r.worst_z, r.worst);
    cr_log_info("summed variance under the ball: MIS %.3g, light %.3g, scattering %.3g; under the panel: %.3g, %.3g, "
                "%.3g; worst block %.1f errors", r.variance[0][0], r.variance[1][0], r.variance[2][0], r.variance[0][1],
                r.variance[1][1], r.variance[2][1], r.worst_z);
    /* under the ball MIS is below scattering, under the panel below light sampling, and over the whole
     * picture below both */
    cr_expect(r.variance[0][0] < r.variance[2][0], "under the ball: MIS %.3g, scattering %.3g", r.variance[0][0],
              r.variance[2][0]);
    cr_expect(r.variance[0][1] < r.variance[1][1], "under the panel: MIS %.3g, light sampling %.3g", r.variance[0][1],
              r.variance[1][1]);
    double mis = r.variance[0][0] + r.variance[0][1], light = r.variance[1][0] + r.variance[1][1],
           scatter = r.variance[2][0] + r.variance[2][1];
    cr_expect(mis < light && mis < scatter, "whole picture: MIS %.3g, light %.3g, scattering %.3g", mis, light, scatter);
}

/* A floor under a ball of radius 0.05 about 5 away (a cone of 0.6 degrees' half-angle), out of the
 * camera's view: 24 x 24 pixels of 128 paths by `strategy`. Returns the per-path variances summed over
 * the pixels, and the picture's mean in *mean. */
static double small_lamp_variance(const char *strategy, double *mean) {
    char text[1024], err[512] = "";
    snprintf(text, sizeof text,
             "camera eye 0 6 0.01 target 0 0 0 fov 40\nimage 24 24\npaths samples 128 seed 11 strategy %s\n"
             "material floor colour 0.7 0.7 0.7 diffuse 1\nmaterial ball colour 0 0 0 emission 9000 9000 9000\n"
             "plane normal 0 1 0 distance 0 material floor\nsphere centre 0 3 -4 radius 0.05 material ball\n",
             strategy);
    struct path_setup t;
    cr_assert(path_setup_text(&t, text, err, sizeof err), "%s", err);
    enum { PIXELS = 24 * 24 };
    vec3 means[PIXELS], variances[PIXELS];
    path_setup_render(&t, means, variances);
    path_setup_free(&t);
    double variance = 0;
    *mean = 0;
    for (int k = 0; k < PIXELS; k++)
        variance += variances[k].x, *mean += means[k].x / PIXELS;
    return variance;
}

/* Where light sampling wins: a small, distant lamp, which a scattered direction from the middle of the
 * floor finds once in 17,000 tries (docs/15-paths.md). */
Test(strategies, light_sampling_wins_under_a_small_distant_lamp_and_mis_keeps_its_noise) {
    double mis_mean, light_mean, scatter_mean;
    double mis = small_lamp_variance("mis", &mis_mean), light = small_lamp_variance("light", &light_mean),
           scatter = small_lamp_variance("scatter", &scatter_mean);
    cr_log_info("small lamp: summed variance MIS %.4g, light %.4g, scattering %.4g; means %.5f %.5f %.5f", mis, light,
                scatter, mis_mean, light_mean, scatter_mean);
    cr_expect_lt(100 * light, scatter, "light sampling %.4g, scattering %.4g", light, scatter);
    cr_expect_leq(mis, 1.01 * light, "MIS %.4g, light sampling %.4g", mis, light);
    cr_expect_float_eq(mis_mean, light_mean, 1e-3 * light_mean);
}

/* ---- threads -------------------------------------------------------------------------------------- */

/* The linear frame of the Cornell box at 32 x 32 with `samples` paths a pixel under `seed` and `sampler`
 * (independent or sobol), rendered on `threads` threads. */
static float *render_cornell(int threads, int samples, int seed, const char *sampler) {
    struct path_setup t;
    char err[512] = "", set_samples[64], set_seed[64], set_sampler[64];
    snprintf(set_samples, sizeof set_samples, "paths.samples=%d", samples);
    snprintf(set_seed, sizeof set_seed, "paths.seed=%d", seed);
    snprintf(set_sampler, sizeof set_sampler, "paths.sampler=%s", sampler);
    const char *sets[] = {"image=32 32", set_samples, set_seed, set_sampler};
    cr_assert(path_setup_file(&t, "scenes/15-paths.scene", sets, 4, err, sizeof err), "%s", err);
    float *linear = calloc(32 * 32 * 3, sizeof *linear);
    struct image img;
    cr_assert(image_create(&img, 32, 32) && linear != NULL);
    struct path_picture picture = {&t.paths, linear, NULL, 32, NULL};
    struct render_job job = {.camera = &t.camera, .world = &picture, .threads = threads, .sampler = &path_sampler,
                             .antialias = &t.scene.antialias, .lens = &t.scene.lens};
    struct stats total = {0};
    render_image(&job, &img, &total);
    cr_expect_eq(total.primary_rays, (uint64_t)32 * 32 * (uint64_t)samples, "one camera ray a path");
    image_free(&img);
    path_setup_free(&t);
    return linear;
}

/* The page's passes (web/renders.js) over some pixels of chapter 15's scene drawn with `sampler`: a pixel's
 * sums taken on pass after pass, up to totals[0], totals[1], ... paths, give path_pixel's mean and variance
 * at the last total to the bit; then fewer paths than the sum holds start it again. */
static void expect_passes_are_path_pixel(const char *sampler, const int *totals, int passes) {
    struct path_setup t;
    char err[512] = "", set_sampler[64];
    snprintf(set_sampler, sizeof set_sampler, "paths.sampler=%s", sampler);
    const char *sets[] = {"image=16 16", set_sampler};
    cr_assert(path_setup_file(&t, "scenes/15-paths.scene", sets, 2, err, sizeof err), "%s", err);
    int last = totals[passes - 1];
    for (int j = 4; j < 16; j += 5)
        for (int i = 3; i < 16; i += 6) {
            vec3 variance, resumed_variance = vec3_make(-1, -1, -1);
            t.paths.settings.samples = last;
            vec3 whole = path_pixel(&t.paths, i, j, &variance);
            struct path_pixel_sum sum = {vec3_make(0, 0, 0), vec3_make(0, 0, 0), 0};
            vec3 resumed = vec3_make(0, 0, 0);
            for (int p = 0; p < passes; p++) {
                t.paths.settings.samples = totals[p];
                resumed = path_pixel_resume(&t.paths, i, j, &sum, &resumed_variance);
                cr_expect_eq(sum.count, totals[p]);
            }
            cr_expect(memcmp(&whole, &resumed, sizeof whole) == 0 && memcmp(&variance, &resumed_variance, sizeof variance) == 0,
                      "%s, pixel (%d, %d): resumed (%.17g %.17g %.17g), whole (%.17g %.17g %.17g)", sampler, i, j,
                      resumed.x, resumed.y, resumed.z, whole.x, whole.y, whole.z);
            t.paths.settings.samples = 2; /* fewer than the sum holds: from zero again */
            vec3 again = path_pixel_resume(&t.paths, i, j, &sum, NULL), two = path_pixel(&t.paths, i, j, NULL);
            cr_expect(memcmp(&again, &two, sizeof two) == 0 && sum.count == 2, "%s, pixel (%d, %d) started again",
                      sampler, i, j);
        }
    path_setup_free(&t);
}

/* Independent paths taken on from 1 to 2 to 5 paths. */
Test(paths_resume, a_pixel_resumed_pass_after_pass_is_path_pixel_to_the_bit) {
    const int totals[] = {1, 2, 5};
    expect_passes_are_path_pixel("independent", totals, 3);
}

/* Stratified paths, as chapter 15's own scene draws them, in passes of 1, 2, 4 and 1 paths (paths 0, 1 .. 2,
 * 3 .. 6 and 7): a path's numbers depend on its number in the pixel, not on the pass that draws it. */
Test(paths_resume, sobol_passes_of_1_2_4_and_1_paths_are_path_pixel_at_8_to_the_bit) {
    const int totals[] = {1, 3, 7, 8};
    expect_passes_are_path_pixel("sobol", totals, 4);
}

Test(paths_threads, one_and_two_threads_give_the_same_radiance_to_the_bit) {
    const char *samplers[] = {"independent", "sobol"};
    for (int k = 0; k < 2; k++) {
        float *one = render_cornell(1, 4, 0, samplers[k]), *two = render_cornell(2, 4, 0, samplers[k]);
        cr_expect_eq(memcmp(one, two, 32 * 32 * 3 * sizeof *one), 0, "%s", samplers[k]);
        free(one);
        free(two);
    }
}

Test(path_image, the_tone_map_clips_and_applies_the_srgb_curve) {
    cr_expect_eq(path_image_display(-1), 0.0);
    cr_expect_eq(path_image_display(NAN), 0.0);
    cr_expect(fabs(path_image_display(17) - 1.0) < 1e-15, "clipped at 1");
    cr_expect(fabs(path_image_display(0.002) - 0.02584) < 1e-12, "the linear piece");
    cr_expect(fabs(path_image_display(0.18) - 0.461356) < 1e-6, "18%% grey");
    cr_expect(fabs(path_image_display(1.0) - 1.0) < 1e-12);
}

/* ---- the stratified sampler (paths ... sampler sobol) ------------------------------------------------ */

/* Scrambling seeds for test number k: any spread of values. */
static struct owen_sobol_seeds test_seeds(uint32_t k) {
    return (struct owen_sobol_seeds){k * 2654435761u, k * 40503u + 7u, (k ^ 0x5bd1e995u) * 0x9e3779b9u};
}

/* The first 16 points of every scrambled copy put one point in each cell of every grid of 16 equal
 * rectangles (16 x 1, 8 x 2, 4 x 4, 2 x 8, 1 x 16), and the first 16 lone values one in each sixteenth. */
Test(owen_sobol, sixteen_points_fill_every_grid_of_sixteen_cells) {
    for (uint32_t k = 0; k < 200; k++) {
        struct owen_sobol_seeds seeds = test_seeds(k);
        for (int columns = 1; columns <= 16; columns *= 2) {
            int rows = 16 / columns, filled[16] = {0};
            for (uint32_t n = 0; n < 16; n++) {
                double u, v;
                owen_sobol_point(n, &seeds, &u, &v);
                cr_assert(u >= 0 && u < 1 && v >= 0 && v < 1, "point %u: %g %g", n, u, v);
                filled[(int)(u * columns) * rows + (int)(v * rows)]++;
            }
            for (int c = 0; c < 16; c++)
                cr_expect_eq(filled[c], 1, "seeds %u, %d x %d cells: cell %d holds %d points", k, columns, rows, c,
                             filled[c]);
        }
        int sixteenths[16] = {0};
        for (uint32_t n = 0; n < 16; n++)
            sixteenths[(int)(owen_sobol_value(n, &seeds) * 16)]++;
        for (int c = 0; c < 16; c++)
            cr_expect_eq(sixteenths[c], 1, "seeds %u: sixteenth %d holds %d values", k, c, sixteenths[c]);
    }
}

/* One point of a copy, over many seeds, is uniform: its quarter of the square is each quarter a quarter of
 * the time (the chi-square of 4,000 points in 16 cells, 15 degrees of freedom, under its 0.1 % point of
 * 37.7), whichever point of the sequence it is. Without the scrambling it would always be in one cell. */
Test(owen_sobol, one_point_over_the_seeds_is_uniform) {
    enum { DRAWS = 4000 };
    const uint32_t indices[] = {0, 1, 5, 1000};
    for (int i = 0; i < 4; i++) {
        int cells[16] = {0};
        for (uint32_t k = 0; k < DRAWS; k++) {
            struct owen_sobol_seeds seeds = test_seeds(k + 1);
            double u, v;
            owen_sobol_point(indices[i], &seeds, &u, &v);
            cells[(int)(u * 4) * 4 + (int)(v * 4)]++;
        }
        double chi2 = 0, expected = DRAWS / 16.0;
        for (int c = 0; c < 16; c++)
            chi2 += (cells[c] - expected) * (cells[c] - expected) / expected;
        cr_expect_lt(chi2, 37.7, "point %u: chi-square %.1f", indices[i], chi2);
    }
}

/* The Cornell box at 32 x 32 and 16 paths a pixel, drawn twice (seeds 1 and 2) by each sampler: the two
 * draws differ only by noise, so the mean of (a - b)^2 / 2 over pixels and channels is a draw's variance
 * about the exact picture. The stratified sampler's is well below the independent one's, and the two
 * samplers' pictures agree: each block of 8 x 8 pixels' mean within four combined standard errors. */
Test(strategies, the_stratified_sampler_is_less_noisy_and_converges_to_the_same_picture) {
    enum { SIDE = 32, BLOCK = 8, SAMPLES = 16 };
    float *independent[2] = {render_cornell(2, SAMPLES, 1, "independent"), render_cornell(2, SAMPLES, 2, "independent")};
    float *sobol[2] = {render_cornell(2, SAMPLES, 1, "sobol"), render_cornell(2, SAMPLES, 2, "sobol")};
    double variance[2] = {0, 0}, worst = 0;
    for (int k = 0; k < SIDE * SIDE * 3; k++) {
        variance[0] += pow(independent[0][k] - independent[1][k], 2) / 2 / (SIDE * SIDE * 3);
        variance[1] += pow(sobol[0][k] - sobol[1][k], 2) / 2 / (SIDE * SIDE * 3);
    }
    for (int by = 0; by < SIDE / BLOCK; by++)
        for (int bx = 0; bx < SIDE / BLOCK; bx++)
            for (int c = 0; c < 3; c++) {
                double mean[2] = {0, 0}, spread[2] = {0, 0}, n = BLOCK * BLOCK;
                for (int j = by * BLOCK; j < (by + 1) * BLOCK; j++)
                    for (int i = bx * BLOCK; i < (bx + 1) * BLOCK; i++) {
                        int k = 3 * (j * SIDE + i) + c;
                        mean[0] += (independent[0][k] + independent[1][k]) / (2 * n);
                        mean[1] += (sobol[0][k] + sobol[1][k]) / (2 * n);
                        /* the variance of the pixel's mean of two draws, (a - b)^2 / 4 */
                        spread[0] += pow(independent[0][k] - independent[1][k], 2) / 4 / (n * n);
                        spread[1] += pow(sobol[0][k] - sobol[1][k], 2) / 4 / (n * n);
                    }
                double error = sqrt(spread[0] + spread[1]);
                if (error > 0)
                    worst = fmax(worst, fabs(mean[0] - mean[1]) / error);
            }
    cr_log_info("Cornell box, 32 x 32, 16 paths: variance of a draw %.4g independent, %.4g sobol; worst block %.2f "
                "errors", variance[0], variance[1], worst);
    cr_expect_lt(variance[1], 0.8 * variance[0], "sobol %.4g, independent %.4g", variance[1], variance[0]);
    cr_expect_leq(worst, 4.0, "a block's means differ by %.2f combined standard errors", worst);
    for (int k = 0; k < 2; k++) {
        free(independent[k]);
        free(sobol[k]);
    }
}

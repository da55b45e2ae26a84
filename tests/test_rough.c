/* test_rough.c: chapter 17's rough surfaces on chapter 15's path tracer: the material's roughness, metal
 * and lobe read, refused and dropped before chapter 17; roughness 0 drawing chapter 15's picture exactly
 * and a tiny roughness its mirror and glass within the noise; the white furnace's energy loss against
 * the numerical integral of the model; and Veach's plates, where the three strategies agree and multiple
 * importance sampling has the least variance (rough_plates, in make test-long, prints each region's). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "microfacet.h"
#include "path_proofs.h"
#include "rough_surface.h"
#include "scene.h"
#include "test_support.h"

#define SCENE_HEAD "camera eye 0 0 5 target 0 0 0 fov 40\nimage 16 12\n"

/* ---- the material's keys ---------------------------------------------------------------------------- */

static void expect_refused(const char *line, const char *message) {
    expect_scene_refused("rough.scene", SCENE_HEAD, line, test_every_kind, message);
}

Test(rough_keys, are_read_with_their_defaults) {
    struct scene s;
    char err[512] = "";
    cr_assert(parse_scene_lines("rough.scene", SCENE_HEAD,
                                "material a reflection 1 roughness 0.25 metal gold lobe phong\nmaterial b metal colour",
                                test_every_kind, &s, err, sizeof err),
              "%s", err);
    cr_expect_eq(s.materials[0].roughness, 0.0);
    cr_expect_eq(s.materials[0].metal, SCENE_METAL_NONE);
    cr_expect_eq(s.materials[0].lobe, SCENE_LOBE_GGX);
    cr_expect_eq(s.materials[1].roughness, 0.25);
    cr_expect_eq(s.materials[1].metal, SCENE_METAL_GOLD);
    cr_expect_eq(s.materials[1].lobe, SCENE_LOBE_PHONG);
    cr_expect_eq(s.materials[2].metal, SCENE_METAL_COLOUR);
    scene_free(&s);
}

Test(rough_keys, bad_values_are_refused_with_file_and_line) {
    expect_refused("material a roughness 1.5", "rough.scene:3: material 'a': roughness must be between 0 and 1, got 1.5");
    expect_refused("material a roughness -0.1", "rough.scene:3: material 'a': roughness must be between 0 and 1, got -0.1");
    /* just past 1: 15 digits would print it as "got 1", a message that contradicts itself */
    expect_refused("material a roughness 1.0000000000000002",
                   "rough.scene:3: material 'a': roughness must be between 0 and 1, got 1.0000000000000002");
    expect_refused("material a roughness nan", "rough.scene:3: 'nan' is not a finite number (for 'roughness')");
    expect_refused("material a metal tin",
                   "rough.scene:3: material 'a': unknown metal 'tin' (none, colour, gold, silver, copper or aluminium)");
    expect_refused("material a lobe beckmann", "rough.scene:3: material 'a': unknown lobe 'beckmann' (ggx or phong)");
}

Test(rough_keys, chapters_before_17_ignore_them_with_a_note) {
    struct scene s;
    char err[512] = "", note[512] = "";
    cr_assert(parse_scene_lines("rough.scene", SCENE_HEAD, "material a reflection 1 roughness 0.3\nmaterial b lobe phong",
                                test_every_kind, &s, err, sizeof err),
              "%s", err);
    FILE *out = fmemopen(note, sizeof note, "w");
    scene_drop_unsupported(&s, 15, out);
    fclose(out);
    cr_expect_str_eq(note, "rough.scene: chapter 15 ignores the roughness of 2 materials (not introduced yet)\n");
    cr_expect(s.materials[1].roughness == 0.0 && s.materials[2].lobe == SCENE_LOBE_GGX);
    scene_free(&s);
}

/* ---- pictures ---------------------------------------------------------------------------------------- */

/* Renders scene text with the rough surfaces `surface` (chapter 15's alone when NULL): the pixels' means
 * and per-path variances, width * height each, allocated. */
static void render(const char *text, const struct path_surface *surface, vec3 **means, vec3 **variances, int *width,
                   int *height) {
    struct path_setup t;
    char err[512] = "";
    cr_assert(path_setup_text(&t, text, err, sizeof err), "%s", err);
    if (surface != NULL)
        t.paths.surface = surface;
    *width = t.scene.width;
    *height = t.scene.height;
    *means = malloc(2 * (size_t)*width * (size_t)*height * sizeof **means);
    cr_assert(*means != NULL);
    *variances = *means + (size_t)*width * (size_t)*height;
    path_setup_render(&t, *means, *variances);
    path_setup_free(&t);
}

/* A lamp over a red and a green wall and a grey floor, and a ball of material "ball" (defined by the
 * caller) in the middle: what a mirror or glass ball shows is the room. */
#define ROOM "camera eye 0 1 -4 target 0 0.8 0 fov 40\nimage 32 24\nbackground 0.1 0.1 0.2\n" \
             "paths samples %d seed %d roulette 3 bounces 16\n" \
             "material lamp colour 0 0 0 diffuse 0 emission 6 6 6\n" \
             "material red colour 0.7 0.1 0.1 diffuse 1\nmaterial green colour 0.1 0.7 0.1 diffuse 1\n" \
             "material grey colour 0.6 0.6 0.6 diffuse 1\n%s\n" \
             "sphere centre 0 0.8 0 radius 0.8 material ball\n" \
             "box min -2 -0.1 -5 max 2 0 3 material grey\nbox min -2.1 0 -5 max -2 3 3 material red\n" \
             "box min 2 0 -5 max 2.1 3 3 material green\nbox min -0.6 2.9 -0.6 max 0.6 3 0.6 material lamp\n"

/* The largest difference of two pictures' 4 x 4 block means, in combined standard errors (n paths a
 * pixel each). */
static double worst_block_z(const vec3 *a, const vec3 *va, const vec3 *b, const vec3 *vb, int width, int height, int n) {
    double worst = 0.0;
    for (int by = 0; by + 4 <= height; by += 4)
        for (int bx = 0; bx + 4 <= width; bx += 4)
            for (int c = 0; c < 3; c++) {
                double ma = 0, mb = 0, sa = 0, sb = 0;
                for (int j = by; j < by + 4; j++)
                    for (int i = bx; i < bx + 4; i++) {
                        int k = j * width + i;
                        ma += vec3_axis(a[k], c) / 16;
                        mb += vec3_axis(b[k], c) / 16;
                        sa += vec3_axis(va[k], c) / n / 256;
                        sb += vec3_axis(vb[k], c) / n / 256;
                    }
                double z = fabs(ma - mb) / sqrt(sa + sb + 1e-12);
                worst = fmax(worst, z);
            }
    return worst;
}

Test(rough_smooth, roughness_0_draws_chapter_15s_picture_exactly) {
    char text[2048];
    snprintf(text, sizeof text, ROOM, 4, 1, "material ball reflection 1 diffuse 0 roughness 0");
    vec3 *a, *va, *b, *vb;
    int w, h;
    render(text, NULL, &a, &va, &w, &h);
    render(text, &rough_surface_hook, &b, &vb, &w, &h);
    cr_expect(memcmp(a, b, 2 * (size_t)w * (size_t)h * sizeof *a) == 0, "the hook claims no smooth material");
    free(a);
    free(b);
}

Test(rough_smooth, a_rough_glass_between_equal_indices_lets_the_light_through_unbent) {
    /* A white furnace and a frosted ball of ior 1, the default: no facet bends or reflects anything, so
     * every path goes straight through, and every pixel is the background's 1 exactly (with the
     * microfacet lobe, whose half vector is 0 there, paths died in the ball: a mean of 0.9, pixels of
     * 0.19). A tint (colour 0.8, filter 0.8: transmit 0.2 + 0.8 x 0.8) is met twice, going in and out. */
    const char *tints[] = {"colour 1 1 1 transmit 1", "colour 0.8 0.8 0.8 filter 0.8 transmit 0.2"};
    const double inside[] = {1.0, (0.2 + 0.8 * 0.8) * (0.2 + 0.8 * 0.8)};
    for (int k = 0; k < 2; k++) {
        char text[1024];
        snprintf(text, sizeof text, "camera eye 0 0 6 target 0 0 0 fov 40\nimage 24 16\nbackground 1 1 1\n"
                 "paths samples 8 bounces 8\nmaterial g %s ambient 0 diffuse 0 roughness 0.5\n"
                 "sphere centre 0 0 0 radius 1.5 material g\n", tints[k]);
        vec3 *means, *variances;
        int w, h;
        render(text, &rough_surface_hook, &means, &variances, &w, &h);
        int through = 0;
        for (int i = 0; i < w * h; i++) {
            /* n of the pixel's 8 paths (jittered over it) through the ball, the others past it */
            double n = (1.0 - means[i].x) / (1.0 - inside[k]) * 8.0;
            cr_assert(k == 0 ? means[i].x == 1.0 : fabs(n - round(n)) < 1e-9, "%s, pixel %d: %.17g", tints[k], i,
                      means[i].x);
            through += means[i].x != 1.0;
        }
        cr_expect((k == 0) == (through == 0), "tint %s: %d pixels through the ball", tints[k], through);
        free(means);
    }
}

/* A roughness of 0.01 (alpha 1e-4) is a mirror or a glass for every purpose a picture has: its picture and
 * chapter 15's agree within the noise, block by block. */
static void expect_smooth_limit(const char *ball) {
    enum { PATHS = 64 };
    char smooth[2048], rough[2048], line[256];
    snprintf(line, sizeof line, "material ball %s roughness 0", ball);
    snprintf(smooth, sizeof smooth, ROOM, PATHS, 1, line);
    snprintf(line, sizeof line, "material ball %s roughness 0.01", ball);
    snprintf(rough, sizeof rough, ROOM, PATHS, 2, line);
    vec3 *a, *va, *b, *vb;
    int w, h;
    render(smooth, NULL, &a, &va, &w, &h);
    render(rough, &rough_surface_hook, &b, &vb, &w, &h);
    double z = worst_block_z(a, va, b, vb, w, h, PATHS);
    /* 48 blocks x 3 channels: the largest of 144 normal deviates is under 4.5 but for one time in 2000 */
    cr_expect_lt(z, 4.5, "%s: the worst block differs by %.2f standard errors", ball, z);
    free(a);
    free(b);
}

Test(rough_smooth, a_tiny_roughness_draws_chapter_15s_mirror_within_the_noise) {
    expect_smooth_limit("reflection 0.9 diffuse 0");
}

Test(rough_smooth, a_tiny_roughness_draws_chapter_15s_glass_within_the_noise) {
    expect_smooth_limit("transmit 1 diffuse 0 ior 1.5");
}

/* ---- the white furnace ---------------------------------------------------------------------------- */

/* A floor of rough metal of reflectance 1 under a white sky (background 1), seen from `degrees` off its
 * normal through a narrow camera, drawn with the rough surfaces `surface`: what every pixel shows is the
 * share of the sky the floor reflects once, its directional albedo (a ray that leaves an infinite plane
 * upwards never meets it again). Returns the image mean and its standard error, from 8 x 8 pixels of
 * `paths` paths. */
static void furnace_floor(const struct path_surface *surface, double roughness, double degrees, int paths, double *mean,
                          double *error) {
    char text[1024];
    double a = degrees * M_PI / 180;
    snprintf(text, sizeof text,
             "camera eye %.17g %.17g 0 target 0 0 0 up 0 0 1 fov 0.5\nimage 8 8\nbackground 1 1 1\n"
             "paths samples %d strategy scatter\nmaterial metal colour 1 1 1 diffuse 0 reflection 1 roughness %g\n"
             "plane normal 0 1 0 distance 0 material metal\n",
             10 * sin(a), 10 * cos(a), paths, roughness);
    vec3 *m, *v;
    int w, h;
    render(text, surface, &m, &v, &w, &h);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < w * h; k++) {
        sum += m[k].y;
        sum2 += m[k].y * m[k].y;
    }
    int n = w * h;
    *mean = sum / n;
    *error = sqrt(fmax(0.0, sum2 / n - *mean * *mean) / (n - 1));
    free(m);
}

Test(rough_furnace, the_energy_a_rough_metal_loses_is_the_integral_of_its_model) {
    const double roughness[] = {0.25, 0.5, 0.75, 1.0}, degrees[] = {0, 60};
    for (int r = 0; r < 4; r++)
        for (int d = 0; d < 2; d++) {
            double mean, error, a = degrees[d] * M_PI / 180;
            furnace_floor(&rough_surface_hook, roughness[r], degrees[d], 128, &mean, &error);
            struct microfacet_lobe l = microfacet_conductor_lobe(vec3_make(1, 1, 1), microfacet_alpha(roughness[r]));
            double albedo = microfacet_albedo(&l, vec3_make(sin(a), 0, cos(a)), 256).y;
            cr_expect_lt(fabs(mean - albedo), 4 * error + 1e-3,
                         "roughness %g at %g degrees: the furnace %.4f +- %.4f, the integral %.4f", roughness[r],
                         degrees[d], mean, error, albedo);
            cr_expect_lt(albedo, 1.0, "a rough metal loses energy by single scattering");
            printf("white furnace: roughness %.2f at %2.0f degrees: the furnace %.4f +- %.4f, the integral %.4f "
                   "(a loss of %.1f%%)\n", roughness[r], degrees[d], mean, error, albedo, 100 * (1 - albedo));
        }
}

/* The masking Cycles 3.4 uses, G1(wo) G1(wi), which chapter 17 draws only to compare with it (--form
 * cycles-3.4): the furnace then shows that form's albedo, below the chapter's, whose masking is larger. */
Test(rough_furnace, the_separable_masking_loses_the_energy_of_its_own_integral) {
    double mean, error, a = 75 * M_PI / 180, alpha = microfacet_alpha(0.9);
    furnace_floor(&rough_surface_hook_cycles_3_4, 0.9, 75, 128, &mean, &error);
    struct microfacet_lobe l = microfacet_conductor_lobe(vec3_make(1, 1, 1), alpha);
    double correlated = microfacet_albedo(&l, vec3_make(sin(a), 0, cos(a)), 256).y;
    l.form = MICROFACET_CYCLES_3_4;
    double separable = microfacet_albedo(&l, vec3_make(sin(a), 0, cos(a)), 256).y;
    cr_expect_lt(fabs(mean - separable), 4 * error + 1e-3, "the furnace %.4f +- %.4f, the separable integral %.4f", mean,
                 error, separable);
    cr_expect_gt(correlated - mean, 8 * error, "the furnace %.4f +- %.4f, the correlated integral %.4f", mean, error,
                 correlated);
}

/* ---- Veach's plates ----------------------------------------------------------------------------------- */

enum { PLATES = 4, LIGHTS = 4, STRATEGIES = 3 };
static const char *const strategy_names[STRATEGIES] = {"mis", "light", "scatter"};

/* Where light `l` shines in plate `p` of scenes/17-veach.scene, as shares of the picture's width and
 * height: the centre of its highlight (the mirror point of the light's centre, projected by the camera). */
static const double highlight_x[LIGHTS] = {0.323, 0.440, 0.560, 0.677};
static const double highlight_y[PLATES] = {0.426, 0.555, 0.703, 0.891};
#define HIGHLIGHT_HALF_WIDTH 0.04  /* a region is this share of the width either side of the centre */
#define HIGHLIGHT_HALF_HEIGHT 0.03 /* and this share of the height above and below */

/* One strategy's picture of the plates, by region: the mean and the mean per-path variance (both the
 * mean of the channels), and the number of pixels. */
struct plate_regions {
    double mean[PLATES][LIGHTS], variance[PLATES][LIGHTS];
    int pixels[PLATES][LIGHTS];
};

static void render_plates(const char *strategy, int width, int height, int paths, struct plate_regions *r) {
    char image[64], samples[64], strategy_set[64];
    snprintf(image, sizeof image, "image=%d %d", width, height);
    snprintf(samples, sizeof samples, "paths.samples=%d", paths);
    snprintf(strategy_set, sizeof strategy_set, "paths.strategy=%s", strategy);
    const char *sets[] = {image, samples, strategy_set};
    struct path_setup t;
    char err[512] = "";
    cr_assert(path_setup_file(&t, "scenes/17-veach.scene", sets, 3, err, sizeof err), "%s", err);
    t.paths.surface = &rough_surface_hook;
    vec3 *means = malloc(2 * (size_t)width * (size_t)height * sizeof *means);
    cr_assert(means != NULL);
    vec3 *variances = means + (size_t)width * (size_t)height;
    path_setup_render(&t, means, variances);
    memset(r, 0, sizeof *r);
    for (int p = 0; p < PLATES; p++)
        for (int l = 0; l < LIGHTS; l++) {
            int i0 = (int)ceil((highlight_x[l] - HIGHLIGHT_HALF_WIDTH) * width);
            int i1 = (int)floor((highlight_x[l] + HIGHLIGHT_HALF_WIDTH) * width);
            int j0 = (int)ceil((highlight_y[p] - HIGHLIGHT_HALF_HEIGHT) * height);
            int j1 = (int)floor((highlight_y[p] + HIGHLIGHT_HALF_HEIGHT) * height);
            for (int j = j0; j <= j1; j++)
                for (int i = i0; i <= i1; i++) {
                    vec3 m = means[j * width + i], v = variances[j * width + i];
                    r->mean[p][l] += (m.x + m.y + m.z) / 3;
                    r->variance[p][l] += (v.x + v.y + v.z) / 3;
                    r->pixels[p][l]++;
                }
            r->mean[p][l] /= r->pixels[p][l];
            r->variance[p][l] /= r->pixels[p][l];
        }
    free(means);
    path_setup_free(&t);
}

/* The three strategies converge to one picture: each region's means agree within `most` combined standard
 * errors (every pair when all_pairs is set; otherwise MIS and the better of the other two there: with
 * few paths, light sampling of the large light in the smoothest plate and scattering towards the
 * smallest light from the roughest plate have not yet found what they must find, and their spread
 * understates their error); and MIS has the least variance over all the regions together, and in every
 * region no more than `mis_most` times the better of the other two. Prints the table when `print` is set. */
static void expect_plates(int width, int height, int paths, double most, double mis_most, bool all_pairs, bool print) {
    struct plate_regions r[STRATEGIES];
    for (int s = 0; s < STRATEGIES; s++)
        render_plates(strategy_names[s], width, height, paths, &r[s]);
    double total[STRATEGIES] = {0};
    for (int p = 0; p < PLATES; p++)
        for (int l = 0; l < LIGHTS; l++) {
            for (int s = 0; s < STRATEGIES; s++)
                total[s] += r[s].variance[p][l];
            int better = r[1].variance[p][l] < r[2].variance[p][l] ? 1 : 2;
            for (int a = 0; a < STRATEGIES; a++)
                for (int b = a + 1; b < STRATEGIES; b++) {
                    if (!all_pairs && !(a == 0 && b == better))
                        continue;
                    double n = (double)paths * r[a].pixels[p][l];
                    double z = fabs(r[a].mean[p][l] - r[b].mean[p][l]) /
                               sqrt((r[a].variance[p][l] + r[b].variance[p][l]) / n + 1e-12);
                    cr_expect_lt(z, most, "plate %d, light %d: %s %.4f and %s %.4f differ by %.1f standard errors",
                                 p + 1, l + 1, strategy_names[a], r[a].mean[p][l], strategy_names[b], r[b].mean[p][l], z);
                }
            double best_other = fmin(r[1].variance[p][l], r[2].variance[p][l]);
            cr_expect_leq(r[0].variance[p][l], mis_most * best_other,
                          "plate %d, light %d: MIS's variance %.4g against light %.4g and scatter %.4g", p + 1, l + 1,
                          r[0].variance[p][l], r[1].variance[p][l], r[2].variance[p][l]);
        }
    cr_expect(total[0] < total[1] && total[0] < total[2], "variance over the plates: mis %.4g, light %.4g, scatter %.4g",
              total[0], total[1], total[2]);
    if (print) {
        printf("Veach's plates, %d x %d pixels, %d paths a pixel: each region's variance of one path (mean of the "
               "channels), light / scatter / mis\n", width, height, paths);
        for (int p = 0; p < PLATES; p++) {
            printf("plate %d (roughness %s):", p + 1, (const char *[]){"0.1", "0.18", "0.26", "0.35"}[p]);
            for (int l = 0; l < LIGHTS; l++)
                printf("  light %d %8.3g / %8.3g / %8.3g", l + 1, r[1].variance[p][l], r[2].variance[p][l],
                       r[0].variance[p][l]);
            printf("\n");
        }
        printf("over the plates: light %.4g, scatter %.4g, mis %.4g\n", total[1], total[2], total[0]);
    }
}

Test(rough_plates, strategies_agree_and_mis_has_the_least_variance) {
    expect_plates(192, 128, 64, 5.0, 2.0, false, false);
}

Test(rough_plates_long, the_table_of_each_regions_variance) {
    expect_plates(384, 256, 256, 5.0, 2.0, true, true);
}

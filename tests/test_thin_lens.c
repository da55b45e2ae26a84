/* test_thin_lens.c: chapter 13's depth of field: the camera line's lens keys and their errors, the
 * lens's hexagonal grid, where lens rays start and where they meet, the same picture for any thread
 * count, and agreement with POV-Ray's focal blur measured statistically (its random numbers are not
 * ours), with proof that the measure catches a wrong aperture and a wrong focal plane. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "image_test_support.h"
#include "scene.h"
#include "test_support.h"
#include "thin_lens.h"

#define FOCUS_SCENE "scenes/13-focus.scene"

/* ---- the camera line's lens keys ------------------------------------------------------------------ */

static bool parse_camera(const char *camera, struct scene *s, char *err, size_t err_size) {
    return parse_scene_lines("lens.scene", camera, "\nimage 64 48", NULL, s, err, err_size);
}

static void expect_refused(const char *camera, const char *message) {
    expect_scene_refused("lens.scene", camera, "\nimage 64 48", NULL, message);
}

#define CAMERA "camera eye 0 0 5 target 0 0 0 fov 40"

Test(lens_line, keys_are_read_and_a_camera_without_them_is_a_pinhole) {
    struct scene s;
    char err[512] = "";
    cr_assert(parse_camera(CAMERA " aperture 0.5 focal_point 0 0 1 blur_samples 7", &s, err, sizeof err), "%s", err);
    cr_expect(lens_is_open(&s.lens) && s.lens.aperture == 0.5 && s.lens.focal_point.z == 1 && s.lens.blur_samples == 7);
    scene_free(&s);
    cr_assert(parse_camera(CAMERA " aperture 0.5 focal_point 0 0 1", &s, err, sizeof err), "%s", err);
    cr_expect_eq(s.lens.blur_samples, LENS_DEFAULT_SAMPLES);
    scene_free(&s);
    cr_assert(parse_camera(CAMERA " aperture 0 focal_point 0 0 1", &s, err, sizeof err), "%s", err);
    cr_expect(!lens_is_open(&s.lens), "aperture 0 is a pinhole");
    scene_free(&s);
    cr_assert(parse_camera(CAMERA, &s, err, sizeof err), "%s", err);
    cr_expect(!lens_is_open(&s.lens));
    scene_free(&s);
}

Test(lens_line, bad_values_are_refused_with_file_and_line) {
    expect_refused(CAMERA " aperture -0.1 focal_point 0 0 0", "lens.scene:1: camera aperture must not be negative, got -0.1");
    expect_refused(CAMERA " aperture 0.3",
                   "lens.scene:1: camera aperture needs a focal_point (where the picture is sharp)");
    expect_refused(CAMERA " focal_point 0 0 0", "lens.scene:1: camera focal_point needs an aperture");
    expect_refused(CAMERA " blur_samples 7", "lens.scene:1: camera blur_samples needs an aperture");
    expect_refused(CAMERA " aperture 0.3 focal_point 0 0 5",
                   "lens.scene:1: camera focal_point is the eye: nothing can be in focus there");
    expect_refused(CAMERA " aperture 0.3 focal_point 0 0 0 blur_samples 0",
                   "lens.scene:1: camera blur_samples must be 7, 19 or 37 (1, 2 or 3 rings of the lens's hexagonal "
                   "grid), got 0");
    expect_refused(CAMERA " aperture 0.3 focal_point 0 0 0 blur_samples 8",
                   "lens.scene:1: camera blur_samples must be 7, 19 or 37 (1, 2 or 3 rings of the lens's hexagonal "
                   "grid), got 8");
}

Test(lens_line, bad_values_from_the_command_line_name_the_line, .timeout = 60) {
    expect_chapter_run(13, FOCUS_SCENE " --set camera.aperture=-1 -o " TEST_OUT "/lens-bad.png", 1,
                       FOCUS_SCENE ":4: camera aperture must not be negative, got -1 (the line as changed by --set)");
}

Test(lens_line, chapters_before_13_see_a_pinhole_and_the_twin_carries_the_lens, .timeout = 60) {
    expect_chapter_run(12, FOCUS_SCENE " --quiet --pov " TEST_OUT "/lens-12.pov", 0, "");
    char *twin = read_text_file(TEST_OUT "/lens-12.pov");
    cr_expect_null(strstr(twin, "aperture"), "chapter 12's twin carries the lens");
    free(twin);
    expect_chapter_run(12, FOCUS_SCENE " -o " TEST_OUT "/lens-12.png", 0,
                       FOCUS_SCENE ": chapter 12 ignores the camera's lens (not introduced yet)");
    expect_chapter_run(13, FOCUS_SCENE " --quiet --pov " TEST_OUT "/lens-13.pov", 0, "");
    twin = read_text_file(TEST_OUT "/lens-13.pov");
    cr_expect_not_null(strstr(twin, "  aperture 0.80000000000000004\n  focal_point <0, 0.5, 0>\n  blur_samples 37\n"
                                    "  variance 0\n}\n"),
                       "chapter 13's twin:\n%s", twin);
    free(twin);
}

/* ---- the lens ------------------------------------------------------------------------------------ */

/* A camera looking down -z from (0, 0, 5) with a lens of diameter 0.5 focused on `focus`. */
static void make_lens_at(struct thin_lens *t, struct camera *c, vec3 focus, int samples, uint32_t seed) {
    char err[256];
    cr_assert(camera_init(c, vec3_make(0, 0, 5), vec3_make(0, 0, 0), vec3_make(0, 1, 0), 40, 64, 48, err, sizeof err));
    struct lens l = {0.5, focus, samples};
    thin_lens_init(t, c, &l, seed);
}

/* The same, focused on the plane z = 0. */
static void make_lens(struct thin_lens *t, struct camera *c, int samples, uint32_t seed) {
    make_lens_at(t, c, vec3_make(0, 0, 0), samples, seed);
}

Test(thin_lens, the_focal_plane_is_as_far_as_the_focal_point_from_the_eye) {
    /* POV-Ray's rule: the distance from the eye, not the point's depth along the view, so a point off
     * the axis puts the plane behind itself: (1, 1, 0) is sqrt(27) away, its depth is 5. */
    struct thin_lens t;
    struct camera c;
    make_lens_at(&t, &c, vec3_make(1, 1, 0), 7, 0);
    cr_expect(fabs(t.focal_distance - sqrt(27)) < 1e-15, "focal distance %.17g", t.focal_distance);
}

Test(thin_lens, the_grid_is_rings_of_a_hexagonal_lattice_inside_the_lens) {
    const int samples[] = {7, 19, 37};
    for (int n = 0; n < 3; n++) {
        struct thin_lens t;
        struct camera c;
        make_lens(&t, &c, samples[n], 0);
        cr_expect_eq(t.samples, samples[n]);
        cr_expect(fabs(t.focal_distance - 5) < 1e-15, "the plane is as far as the focal point: %g", t.focal_distance);
        double sum_x = 0, sum_y = 0, nearest = INFINITY, farthest = 0;
        for (int k = 0; k < t.samples; k++) {
            sum_x += t.grid[k][0];
            sum_y += t.grid[k][1];
            farthest = fmax(farthest, hypot(t.grid[k][0], t.grid[k][1]));
            for (int m = 0; m < k; m++)
                nearest = fmin(nearest, hypot(t.grid[k][0] - t.grid[m][0], t.grid[k][1] - t.grid[m][1]));
        }
        int rings = n + 1;
        cr_expect(fabs(sum_x) < 1e-12 && fabs(sum_y) < 1e-12, "%d points: centred", samples[n]);
        cr_expect(fabs(nearest - t.cell) < 1e-12, "%d points: neighbours one cell apart", samples[n]);
        /* The outer ring, moved up to half a cell along an axis, reaches about the lens's edge, 1/2 of D. */
        cr_expect(fabs(farthest - rings * t.cell) < 1e-12 && farthest + t.cell / 2 > 0.43 &&
                  farthest + t.cell / 2 < 0.51, "%d points: the outer ring at %g of D", samples[n], farthest);
    }
}

Test(thin_lens, rays_leave_the_lens_and_meet_on_the_focal_plane) {
    struct thin_lens t;
    struct camera c;
    make_lens(&t, &c, 19, 0);
    double shift = 1.0 / 32; /* POV-Ray's */
    for (int k = 0; k < t.samples; k++) {
        ray r = thin_lens_ray(&t, 20.5, 10.5, k);
        /* From the lens: the plane z = 5 through the eye, no farther out than the outer ring moved by a
         * cell's corner (D = 0.5). */
        double edge = 0.5 * (2 * t.cell + t.cell / sqrt(2)) * (1 + 1e-12);
        cr_expect(r.origin.z == 5 && hypot(r.origin.x, r.origin.y) <= edge, "ray %d starts off the lens", k);
        cr_expect(fabs(vec3_length(r.direction) - 1) < 1e-15);
        /* On the focal plane z = 0 it meets the pinhole's ray through a point of the pixel-sized square
         * around (20.5, 10.5), moved by POV-Ray's 1/32. */
        double s = (0.0 - r.origin.z) / r.direction.z;
        vec3 p = ray_at(r, s);
        double x = (p.x / 5 / c.half_width + 1) * c.width / 2, y = (1 - p.y / 5 / c.half_height) * c.height / 2;
        cr_expect(x >= 20 - shift - 1e-9 && x <= 21 - shift + 1e-9 && y >= 10 - shift - 1e-9 && y <= 11 - shift + 1e-9,
                  "ray %d meets the focal plane at image point (%g, %g)", k, x, y);
    }
    ray a = thin_lens_ray(&t, 20.5, 10.5, 3), b = thin_lens_ray(&t, 20.5, 10.5, 3);
    cr_expect(memcmp(&a, &b, sizeof a) == 0, "the same sample gives the same ray");
    make_lens(&t, &c, 19, 1);
    b = thin_lens_ray(&t, 20.5, 10.5, 3);
    cr_expect(memcmp(&a, &b, sizeof a) != 0, "another seed gives another ray");
}

/* ---- whole pictures ----------------------------------------------------------------------------- */

Test(thin_lens, the_picture_is_the_same_for_1_and_2_threads, .timeout = 120) {
    const char *one = TEST_OUT "/lens-1.png", *two = TEST_OUT "/lens-2.png";
    cr_assert_eq(render_chapter(13, FOCUS_SCENE, one, "--width 160 --height 120 --threads 1"), 0);
    cr_assert_eq(render_chapter(13, FOCUS_SCENE, two, "--width 160 --height 120 --threads 2"), 0);
    struct image_difference d = compare_png(one, two);
    cr_expect_eq(d.max, 0, "1 and 2 threads differ by up to %d levels", d.max);
}

Test(reference_image, chapter_13_focus_matches_its_reference, .timeout = 120) {
    const char *png = TEST_OUT "/lens-focus.png";
    cr_assert_eq(render_chapter(13, FOCUS_SCENE, png, ""), 0);
    struct image_difference d = compare_png(png, "reference_images/13-focus.png");
    report_difference("chapter 13 focus vs reference", &d);
    cr_assert(regression_passes(&d), "max %d, mean %.4f, within 1: %.3f%%", d.max, d.mean, 100.0 * d.within_1);
}

/* How two noisy pictures differ where it matters: the mean of each channel over BLOCK x BLOCK blocks,
 * their difference's root mean square over all blocks and channels, and its mean (a bias). */
#define BLOCK 8

struct block_difference {
    double rms, bias;
};

static struct block_difference block_difference(const char *a_path, const char *b_path) {
    char err[512];
    int wa, ha, wb, hb;
    uint8_t *a = image_read_rgb(a_path, &wa, &ha, err, sizeof err), *b = image_read_rgb(b_path, &wb, &hb, err, sizeof err);
    cr_assert(a != NULL && b != NULL && wa == wb && ha == hb, "%s", err);
    double squares = 0, sum = 0;
    int blocks = 0;
    for (int top = 0; top + BLOCK <= ha; top += BLOCK)
        for (int left = 0; left + BLOCK <= wa; left += BLOCK)
            for (int channel = 0; channel < 3; channel++) {
                double d = 0;
                for (int y = top; y < top + BLOCK; y++)
                    for (int x = left; x < left + BLOCK; x++)
                        d += (double)a[3 * (y * wa + x) + channel] - b[3 * (y * wa + x) + channel];
                d /= BLOCK * BLOCK;
                squares += d * d;
                sum += d;
                blocks++;
            }
    free(a);
    free(b);
    return (struct block_difference){sqrt(squares / blocks), sum / blocks};
}

/* The agreement rule: POV-Ray's picture differs from ours, over blocks, at most LENS_NOISE_RATIO times
 * as much as ours with another seed does (the noise alone), and without a bias of LENS_MAX_BIAS levels. */
#define LENS_NOISE_RATIO 1.3
#define LENS_MAX_BIAS 0.02

/* Renders the focus scene with the --set changes `extra` by chapter 13 (seed 0 and seed 1) and its twin
 * with POV-Ray; returns the measures of ours (seed 0) against POV-Ray's in *theirs and against seed 1
 * in *noise. `pov_extra` changes the twin instead (for the controls). */
static void against_povray(const char *tag, const char *extra, const char *pov_extra, struct block_difference *theirs,
                           struct block_difference *noise) {
    char ours[256], ours_1[256], pov[256], options[256], variant[256];
    snprintf(ours, sizeof ours, TEST_OUT "/lens-%s.png", tag);
    snprintf(ours_1, sizeof ours_1, TEST_OUT "/lens-%s-seed-1.png", tag);
    snprintf(pov, sizeof pov, TEST_OUT "/lens-%s-povray.png", tag);
    cr_assert_eq(render_chapter(13, FOCUS_SCENE, ours, extra), 0);
    snprintf(options, sizeof options, "%s --set antialias.method=none --set antialias.seed=1", extra);
    cr_assert_eq(render_chapter(13, FOCUS_SCENE, ours_1, options), 0);
    /* POV-Ray renders the twin of the scene as changed by pov_extra: a variant scene file with that
     * camera line. */
    snprintf(variant, sizeof variant, FOCUS_SCENE ".%s.variant", tag);
    const char *olds[] = {"camera eye 0 2.2 9  target 0 0.5 0  fov 36  aperture 0.4  focal_point 0 0.5 0  blur_samples 37"};
    const char *news[] = {pov_extra};
    write_scene_variant(FOCUS_SCENE, variant, olds, news, 1, NULL);
    bool rendered = render_povray(13, variant, pov);
    remove(variant);
    cr_assert(rendered, "POV-Ray failed on the focus scene's twin");
    *theirs = block_difference(ours, pov);
    *noise = block_difference(ours, ours_1);
    fprintf(stderr, "lens '%s' vs POV-Ray: block rms %.4f (noise %.4f, ratio %.2f), bias %.4f\n", tag, theirs->rms,
            noise->rms, theirs->rms / noise->rms, theirs->bias);
}

#define FOCUS_CAMERA "camera eye 0 2.2 9  target 0 0.5 0  fov 36  focal_point 0 0.5 0  blur_samples 37"

Test(povray_agreement, chapter_13_depth_of_field_within_the_noise, .timeout = 300) {
    struct block_difference theirs, noise;
    against_povray("agree", "", FOCUS_CAMERA "  aperture 0.4", &theirs, &noise);
    cr_expect_leq(theirs.rms, LENS_NOISE_RATIO * noise.rms, "POV-Ray's picture differs from ours by %.4f over blocks, "
                  "%.2f times the noise %.4f", theirs.rms, theirs.rms / noise.rms, noise.rms);
    cr_expect_leq(fabs(theirs.bias), LENS_MAX_BIAS, "a bias of %.4f levels", theirs.bias);
}

/* A background on a half level (0.3 is 76.5 of 255) seen through the lens, at each of the counts of lens
 * rays: every pixel is POV-Ray's to the level, since both take the mean of a pixel's lens rays alike
 * (each colour in single precision, summed so, divided by the count). A mean of doubles wrote it a level
 * above POV-Ray's at 7 rays and a level below at 19. */
Test(povray_agreement, chapter_13_lens_over_a_background_on_a_half_level_is_povrays_level, .timeout = 120) {
    static const int counts[] = {7, 19, 37};
    for (int k = 0; k < 3; k++) {
        char scene[256], ours[256], pov[256];
        snprintf(scene, sizeof scene, TEST_OUT "/lens-half-level-%d.scene", counts[k]);
        snprintf(ours, sizeof ours, TEST_OUT "/lens-half-level-%d.png", counts[k]);
        snprintf(pov, sizeof pov, TEST_OUT "/lens-half-level-%d-povray.png", counts[k]);
        FILE *f = fopen(scene, "w");
        cr_assert(f != NULL);
        fprintf(f, "camera eye 0 1 8  target 0 1 0  fov 40  aperture 0.2  focal_point 0 1 0  blur_samples %d\n"
                "image 24 16\nbackground 0.3 0.5 0.7\nlight position 0 5 5\n", counts[k]);
        cr_assert_eq(fclose(f), 0);
        cr_assert_eq(render_chapter(13, scene, ours, ""), 0);
        cr_assert(render_povray(13, scene, pov), "POV-Ray failed on %s's twin", scene);
        struct image_difference d = compare_png(ours, pov);
        cr_expect_eq(d.max, 0, "%d lens rays: ours and POV-Ray's background differ by up to %d levels", counts[k],
                     d.max);
    }
}

/* The check can fail: POV-Ray's lens 10 % wider, or focused 0.3 farther, than ours. */
Test(povray_agreement, chapter_13_depth_of_field_check_catches_a_wrong_lens, .timeout = 300) {
    struct block_difference theirs, noise;
    against_povray("wide", "", FOCUS_CAMERA "  aperture 0.44", &theirs, &noise);
    cr_expect_gt(theirs.rms, LENS_NOISE_RATIO * noise.rms, "a lens 10 %% wider went unnoticed (ratio %.2f)",
                 theirs.rms / noise.rms);
    against_povray("far", "", "camera eye 0 2.2 9  target 0 0.5 0  fov 36  focal_point 0 0.5 -0.3  blur_samples 37"
                              "  aperture 0.4", &theirs, &noise);
    cr_expect_gt(theirs.rms, LENS_NOISE_RATIO * noise.rms, "a focal plane 0.3 farther went unnoticed (ratio %.2f)",
                 theirs.rms / noise.rms);
}

/* test_soft_shadow.c: chapter 13's area lights: the light line's area keys and their errors, where the
 * grid's points are, POV-Ray's weights and its adaptive rule on shadows whose answer is known, light
 * through glass, the shadow rays counted, the same picture for any thread count, chapters before 13
 * seeing a point light, and agreement with POV-Ray's area_light. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_test_support.h"
#include "scene.h"
#include "soft_shadow.h"
#include "stats.h"
#include "test_support.h"
#include "world.h"

#define SCENE_HEAD "camera eye 0 0 5 target 0 0 0 fov 40\nimage 64 48\n"

/* ---- the light line's area keys -------------------------------------------------------------------- */

/* Parses SCENE_HEAD followed by `lines` with every kind of shape; returns whether it parsed, the scene
 * in *s (free it) and the message in err. */
static bool parse_lines(const char *lines, struct scene *s, char *err, size_t err_size) {
    return parse_scene_lines("soft.scene", SCENE_HEAD, lines, test_every_kind, s, err, err_size);
}

static void expect_refused(const char *line, const char *message) {
    expect_scene_refused("soft.scene", SCENE_HEAD, line, test_every_kind, message);
}

Test(area_light_line, keys_are_read_and_a_light_without_them_is_a_point) {
    struct scene s;
    char err[512] = "";
    cr_assert(parse_lines("light position 0 6 0 axis1 2 0 0 axis2 0 0 1 samples 5 3 adaptive 1\n"
                          "light position 1 2 3 axis1 1 0 0 axis2 0 1 0 samples 4 4 circular on orient on\n"
                          "light position 0 9 0",
                          &s, err, sizeof err),
              "%s", err);
    cr_assert_eq(s.light_count, 3);
    const struct area_light *a = &s.lights[0].area;
    cr_expect(area_light_is_area(a));
    cr_expect(a->axis1.x == 2 && a->axis2.z == 1 && a->size1 == 5 && a->size2 == 3 && a->adaptive == 1);
    cr_expect(!a->circular && !a->orient);
    cr_expect(s.lights[1].area.circular && s.lights[1].area.orient);
    cr_expect_eq(s.lights[1].area.adaptive, AREA_LIGHT_NOT_ADAPTIVE, "no adaptive key: every point");
    cr_expect(!area_light_is_area(&s.lights[2].area));
    scene_free(&s);
}

Test(area_light_line, bad_values_are_refused_with_file_and_line) {
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 0 3",
                   "soft.scene:3: light samples must be whole numbers from 1 to 33, got 0 3");
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 3 34",
                   "soft.scene:3: light samples must be whole numbers from 1 to 33, got 3 34");
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 2.5 3",
                   "soft.scene:3: light samples must be whole numbers from 1 to 33, got 2.5 3");
    expect_refused("light position 0 6 0 axis1 0 0 0 axis2 0 0 2 samples 3 3",
                   "soft.scene:3: light axis1 is zero: the area light has no rectangle");
    expect_refused("light position 0 6 0 axis1 1 0 0 axis2 0 0 0 samples 3 3",
                   "soft.scene:3: light axis2 is zero: the area light has no rectangle");
    expect_refused("light position 0 6 0 axis1 1 0 1 axis2 -2 0 -2 samples 3 3",
                   "soft.scene:3: light axis1 and axis2 are parallel: the area light has no rectangle");
    expect_refused("light position 0 6 0 axis1 2 0 0 samples 3 3",
                   "soft.scene:3: an area light needs all of axis1, axis2 and samples");
    expect_refused("light position 0 6 0 adaptive 1",
                   "soft.scene:3: light adaptive needs an area light (axis1, axis2 and samples)");
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 3 3 adaptive -1",
                   "soft.scene:3: light adaptive must be a whole number from 0 to 16, got -1");
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 3 3 circular yes",
                   "soft.scene:3: light circular must be on or off, got 'yes'");
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 1 3 circular on",
                   "soft.scene:3: a circular light needs at least 2 samples a side, got 1 3");
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 3 3 orient on",
                   "soft.scene:3: light orient needs circular on (POV-Ray orients only circular lights)");
    expect_refused("light position 0 6 0 axis1 2 0 0 axis2 0 0 2 samples 3",
                   "soft.scene:3: 'samples' needs 2 numbers");
}

Test(area_light_line, bad_values_from_the_command_line_name_the_line, .timeout = 60) {
    expect_chapter_run(13, "--set \"light.1.samples=0 9\" -o " TEST_OUT "/soft-bad.png", 1,
                       "scenes/13-distributed.scene:9: light samples must be whole numbers from 1 to 33, got 0 9 "
                       "(the line as changed by --set)");
}

Test(area_light_line, chapters_before_13_see_a_point_light_and_their_twins_too, .timeout = 60) {
    expect_chapter_run(12, "scenes/13-distributed.scene --quiet --pov " TEST_OUT "/soft-12.pov", 0, "");
    char *twin = read_text_file(TEST_OUT "/soft-12.pov");
    cr_expect_null(strstr(twin, "area_light"), "chapter 12's twin carries the area light");
    free(twin);
    expect_chapter_run(12, "scenes/13-distributed.scene -o " TEST_OUT "/soft-12.png", 0,
                       "scenes/13-distributed.scene: chapter 12 ignores the area of 1 light (not introduced yet)");
    expect_chapter_run(13, "scenes/13-distributed.scene --quiet --pov " TEST_OUT "/soft-13.pov", 0, "");
    twin = read_text_file(TEST_OUT "/soft-13.pov");
    cr_expect_not_null(strstr(twin, "light_source { <-2, 6, 3> color rgb <0.90000000000000002, 0.88, "
                                    "0.80000000000000004> area_light <3, 0, 0>, <0, 0, 3>, 9, 9 adaptive 1 }\n"),
                       "chapter 13's twin:\n%s", twin);
    free(twin);
}

/* ---- where the points are ------------------------------------------------------------------------- */

static void expect_near(vec3 got, vec3 want, const char *what) {
    cr_expect(vec3_length(vec3_sub(got, want)) < 1e-12, "%s: got (%.17g, %.17g, %.17g), want (%g, %g, %g)", what,
              got.x, got.y, got.z, want.x, want.y, want.z);
}

Test(soft_shadow, the_grid_runs_from_edge_to_edge_of_the_rectangle) {
    struct light light = {.position = {0, 6, 0}, .colour = {1, 1, 1},
                          .area = {{2, 0, 0}, {0, 0, 4}, 3, 5, AREA_LIGHT_NOT_ADAPTIVE, false, false}};
    vec3 p = {0, 0, 0};
    expect_near(soft_shadow_light_point(&light, p, 0, 0), vec3_make(-1, 6, -2), "first corner");
    expect_near(soft_shadow_light_point(&light, p, 2, 4), vec3_make(1, 6, 2), "last corner");
    expect_near(soft_shadow_light_point(&light, p, 1, 2), vec3_make(0, 6, 0), "the middle point is the centre");
    expect_near(soft_shadow_light_point(&light, p, 1, 1), vec3_make(0, 6, -1), "a quarter along axis2");
    light.area.size1 = 1; /* a line of lights along axis2: axis1 is not used */
    expect_near(soft_shadow_light_point(&light, p, 0, 0), vec3_make(0, 6, -2), "one point along axis1");
    light.area.size1 = 0; /* a point light */
    expect_near(soft_shadow_light_point(&light, p, 0, 0), vec3_make(0, 6, 0), "a point light");
}

Test(soft_shadow, circular_lights_lie_on_an_ellipse_and_orient_faces_the_point) {
    struct light light = {.position = {0, 6, 0}, .colour = {1, 1, 1},
                          .area = {{2, 0, 0}, {0, 0, 2}, 5, 5, AREA_LIGHT_NOT_ADAPTIVE, true, false}};
    vec3 p = {0, 0, 0};
    /* POV-Ray nudges every point by 0.001 of a side, then pushes it along its ray from the centre until
     * the grid's squares become circles: a point's distance from the centre is the half-side of the
     * square it lies on, max(|x|, |y|) times the axes' length 2. */
    for (int u = 0; u < 5; u++)
        for (int v = 0; v < 5; v++) {
            double x = u / 4.0 - 0.5 + 0.001, y = v / 4.0 - 0.5 + 0.001;
            vec3 q = vec3_sub(soft_shadow_light_point(&light, p, u, v), light.position);
            cr_expect(fabs(vec3_length(q) - 2 * fmax(fabs(x), fabs(y))) < 1e-12 && fabs(q.y) < 1e-15,
                      "point (%d, %d) at %.17g from the centre", u, v, vec3_length(q));
        }
    /* Oriented, seen from (6, 6, 0) straight along -x: both axes square to x, and as long as axis1. */
    light.area.orient = true;
    light.area.axis2 = vec3_make(0, 0, 5); /* only axis1's length counts */
    vec3 from = {6, 6, 0};
    for (int u = 0; u < 5; u++) {
        vec3 q = vec3_sub(soft_shadow_light_point(&light, from, u, 0), light.position);
        cr_expect(fabs(q.x) < 1e-12, "point (%d, 0) of an oriented light leaves the plane square to the view", u);
        cr_expect(vec3_length(q) <= 1.002 + 1e-12, "point (%d, 0) is off the disc", u);
    }
}

/* ---- shadows whose answer is known ------------------------------------------------------------------ */

/* A scene and its world. */
struct fixture {
    struct scene scene;
    struct world world;
};

/* The share of the scene's first light reaching the origin, and the shadow rays it took in *rays. */
static vec3 share_at_origin(const char *lines, uint64_t *rays) {
    struct fixture f;
    char err[512] = "";
    cr_assert(parse_lines(lines, &f.scene, err, sizeof err), "%s", err);
    cr_assert(world_init(&f.world, &f.scene, err, sizeof err), "%s", err);
    stats_reset_thread();
    vec3 share = soft_shadow_filtered(&f.world, vec3_make(0, 0, 0), &f.scene.lights[0]);
    *rays = stats_thread.shadow_rays;
    world_free(&f.world);
    scene_free(&f.scene);
    return share;
}

/* The light: 10 above the origin, its grid's first column (u = 0) at x = -1. WALL, halfway up, hides
 * that column and no other of a grid of up to 9 columns (the next crosses it at x = -0.375 or more). */
#define LIGHT_3 "light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 3 3"
#define WALL "box min -0.6 4.9 -3 max -0.45 5.1 3"

Test(soft_shadow, povrays_weights_are_a_mean_of_quarters_not_of_points) {
    uint64_t rays;
    /* Nothing in the way: every point of the 3 x 3 grid is traced, and all the light arrives. */
    vec3 share = share_at_origin(LIGHT_3, &rays);
    cr_expect(share.x == 1 && share.y == 1 && share.z == 1, "open sky: %g", share.x);
    cr_expect_eq(rays, 9);
    /* One column of three hidden: POV-Ray's rule weighs the edge columns 1/4 and the middle 1/2 (a mean
     * of the four quarters' corners), so 3/4 gets through, not the 2/3 a plain mean would give. */
    share = share_at_origin(LIGHT_3 "\n" WALL, &rays);
    cr_expect(fabs(share.x - 0.75) < 1e-15, "one column of 3 hidden: %.17g, want 0.75", share.x);
    cr_expect_eq(rays, 9);
    /* 5 x 5: the columns weigh 1/8, 1/4, 1/4, 1/4, 1/8; 4 x 4: all 1/4 (the middle falls between lines). */
    share = share_at_origin("light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 5 5\n" WALL, &rays);
    cr_expect(fabs(share.x - 0.875) < 1e-15, "one column of 5 hidden: %.17g, want 0.875", share.x);
    share = share_at_origin("light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 4 4\n" WALL, &rays);
    cr_expect(fabs(share.x - 0.75) < 1e-15, "one column of 4 hidden: %.17g, want 0.75", share.x);
    cr_expect_eq(rays, 16);
}

Test(soft_shadow, adaptive_stops_where_the_corners_agree) {
    uint64_t rays;
    /* adaptive 0 on open sky: the four corners agree, so they are all that is traced, of 81 points. */
    vec3 share = share_at_origin("light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 9 9 adaptive 0", &rays);
    cr_expect(share.x == 1, "open sky: %g", share.x);
    cr_expect_eq(rays, 4, "open sky, adaptive 0: %llu shadow rays", (unsigned long long)rays);
    /* adaptive 1: the first cut is made anyway, 9 points (the corners of four quarters). */
    share_at_origin("light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 9 9 adaptive 1", &rays);
    cr_expect_eq(rays, 9);
    /* With the wall the left corners differ from the right ones, so the rectangle is cut: the quarters
     * that straddle the wall's edge are cut again, and the rest stop at their corners. */
    share = share_at_origin("light position 0 10 0 axis1 2 0 0 axis2 0 0 2 samples 9 9 adaptive 0\n" WALL, &rays);
    cr_expect(rays > 4 && rays < 81, "adaptive with an edge: %llu rays", (unsigned long long)rays);
    cr_expect(share.x > 0.7 && share.x < 0.95, "adaptive with an edge: %g", share.x);
    /* The difference is of the light each corner lets through: a dim light's corners differ by less
     * than 0.1 however the wall hides them, and nothing is cut. */
    share = share_at_origin("light position 0 10 0 colour 0.03 0.03 0.03 axis1 2 0 0 axis2 0 0 2 samples 9 9 "
                            "adaptive 0\n" WALL, &rays);
    cr_expect_eq(rays, 4, "a dim light is not refined: %llu rays", (unsigned long long)rays);
    cr_expect(fabs(share.x - 0.5) < 1e-15, "the mean of two hidden and two seen corners: %g", share.x);
}

Test(soft_shadow, light_through_glass_is_filtered_as_in_chapter_8) {
    uint64_t rays;
    /* The wall made of glass passing half the light, crossed twice: the hidden column lets 0.25 through. */
    vec3 share = share_at_origin("material glass colour 1 1 1 transmit 0.5 ior 1.5\n" LIGHT_3 "\n" WALL
                                 " material glass",
                                 &rays);
    cr_expect(fabs(share.x - (0.75 + 0.25 * 0.25)) < 1e-15, "a glass wall: %.17g, want 0.8125", share.x);
    /* A point light is chapter 8's filtered shadow ray, one ray. */
    share = share_at_origin("light position -1 10 0\n" WALL, &rays);
    cr_expect(share.x == 0 && rays == 1, "point light behind the wall: %g, %llu rays", share.x,
              (unsigned long long)rays);
}

/* ---- whole pictures ----------------------------------------------------------------------------- */

Test(soft_shadow, the_picture_is_the_same_for_1_and_2_threads, .timeout = 120) {
    const char *one = TEST_OUT "/soft-1.png", *two = TEST_OUT "/soft-2.png";
    cr_assert_eq(render_chapter(13, chapter_scene(13), one, "--threads 1"), 0);
    cr_assert_eq(render_chapter(13, chapter_scene(13), two, "--threads 2"), 0);
    struct image_difference d = compare_png(one, two);
    cr_expect_eq(d.max, 0, "1 and 2 threads differ by up to %d levels", d.max);
}

Test(soft_shadow, point_lights_draw_chapter_12s_picture, .timeout = 120) {
    const char *twelve = TEST_OUT "/soft-by-12.png", *thirteen = TEST_OUT "/soft-by-13.png";
    cr_assert_eq(render_chapter(12, chapter_scene(12), twelve, ""), 0);
    cr_assert_eq(render_chapter(13, chapter_scene(12), thirteen, ""), 0);
    struct image_difference d = compare_png(twelve, thirteen);
    cr_expect_eq(d.max, 0, "chapter 13 on chapter 12's scene differs by up to %d levels", d.max);
}

/* Chapter 13's scene with its area light's line replaced by `line`, against POV-Ray: at half the scene's
 * width and height, a quarter of the pixels (each variant costs both renderers 81 shadow rays a pixel
 * or more, and the scene itself is compared at full size). */
static void expect_agreement(const char *tag, const char *line) {
    char name[128];
    snprintf(name, sizeof name, "soft-%s", tag);
    expect_variant_agrees_with_povray(13, "light position -2 6 3   colour 0.9 0.88 0.8  axis1 3 0 0  axis2 0 0 3  "
                                          "samples 9 9  adaptive 1", line, name, 2);
}

Test(povray_agreement, chapter_13_every_point_of_the_grid, .timeout = 300) {
    expect_agreement("full-9", "light position -2 6 3 colour 0.9 0.88 0.8 axis1 3 0 0 axis2 0 0 3 samples 9 9");
}

Test(povray_agreement, chapter_13_adaptive_circular_and_oriented_lights, .timeout = 300) {
    expect_agreement("adaptive-0", "light position -2 6 3 colour 0.9 0.88 0.8 axis1 3 0 0 axis2 0 0 3 samples 17 5 "
                                   "adaptive 0");
    expect_agreement("circular", "light position -2 6 3 colour 0.9 0.88 0.8 axis1 3 0 0 axis2 0 0 3 samples 6 6 "
                                 "circular on");
    expect_agreement("orient", "light position -2 6 3 colour 0.9 0.88 0.8 axis1 3 0 0 axis2 0 0 3 samples 5 5 "
                               "circular on orient on");
}

/* The check can fail: chapter 12's hard shadow of the same scene against POV-Ray's area light. */
Test(povray_agreement, chapter_13_check_catches_a_hard_shadow, .timeout = 300) {
    const char *hard = TEST_OUT "/soft-hard-12.png", *theirs = TEST_OUT "/soft-hard-povray.png";
    cr_assert_eq(render_chapter(12, chapter_scene(13), hard, ""), 0);
    cr_assert(render_povray(13, chapter_scene(13), theirs));
    struct image_difference d = compare_png(hard, theirs);
    report_difference("chapter 12's hard shadow vs POV-Ray's area light", &d);
    cr_expect_lt(d.within_1, 0.99, "a hard shadow against POV-Ray's soft one went unnoticed");
}

/* test_cli.c: the chapter programs from the outside: options, exit codes, messages for bad input,
 * and no half-written output. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <unistd.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "image_test_support.h"
#include "ray_budget.h"
#include "ray.h"
#include "outfile.h"
#include "scene.h"
#include "sphere.h"
#include "test_support.h"

/* Writes `text` to a scene file in the test folder and returns its path. */
static const char *scene_file(const char *name, const char *text) {
    static char path[256];
    mkdir("out", 0755);
    mkdir(TEST_OUT, 0755);
    snprintf(path, sizeof path, TEST_OUT "/%s", name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
    return path;
}

Test(cli, help_lists_the_options_and_succeeds) { expect_chapter_run(10, "--help", 0, "--accel KIND"); }

Test(cli, an_unknown_option_is_a_usage_error) { expect_chapter_run(2, "--colour red", 2, "unknown option '--colour'"); }

Test(cli, a_bad_number_is_a_usage_error) {
    expect_chapter_run(2, "--width 0", 2, "--width needs a whole number from 1 to 16384, got '0'");
    expect_chapter_run(2, "--threads many", 2, "--threads needs a whole number from 1 to 256, got 'many'");
}

Test(cli, an_option_without_its_value_is_a_usage_error) { expect_chapter_run(2, "-o", 2, "-o needs a file name"); }

Test(cli, two_scenes_are_a_usage_error) {
    expect_chapter_run(2, "a.scene b.scene", 2, "only one scene file, please (got 'a.scene' and 'b.scene')");
}

Test(cli, a_wrong_accel_is_refused_with_the_choices) {
    expect_chapter_run(9, "--accel bvh", 2, "--accel needs one of: none kdtree; got 'bvh'");
    expect_chapter_run(10, "--split middle", 2, "--split needs 'sah' or 'seed' (the seed's rule), got 'middle'");
    expect_chapter_run(10, "--rung 2", 2, "unknown option '--rung'");
    expect_chapter_run(17, "--form cycles", 2, "--form needs 'chapter' (the default) or 'cycles-3.4' (to compare with it), got 'cycles'");
    expect_chapter_run(15, "--form cycles-3.4", 2, "unknown option '--form'");
    expect_chapter_run(11, "--rung 12", 2,
                       "--rung needs 1 to 11 or one of: plain wide simd prefetch build float compact eight lean packet exact-float; got '12'");
    expect_chapter_run(11, "--rung fast", 2,
                       "--rung needs 1 to 11 or one of: plain wide simd prefetch build float compact eight lean packet exact-float; got 'fast'");
}

Test(cli, a_rule_or_rung_for_a_structure_not_built_is_refused) {
    const char *split = "--split chooses how a structure is built, and --accel none builds none: give one or the other";
    expect_chapter_run(9, "--accel none --split seed", 2, split);
    expect_chapter_run(15, "--split sah --accel none", 2, split);
    expect_chapter_run(11, "--accel none --rung 3", 2,
                       "--rung picks a step of the BVH's ladder, and --accel none builds no BVH: give one or the other");
    expect_chapter_run(11, "--rung packet --accel kdtree", 2,
                       "--rung picks a step of the BVH's ladder, and --accel kdtree builds no BVH: give one or the other");
}

Test(cli, a_renders_outputs_and_frames_are_refused_with_pov) {
    const char *twin = "--pov writes the scene's POV-Ray twin instead of rendering; give one of them";
    char expected[256];
    snprintf(expected, sizeof expected, "-o names an output of the render, and %s", twin);
    expect_chapter_run(2, "--pov " TEST_OUT "/refused.pov -o " TEST_OUT "/refused.png", 2, expected);
    snprintf(expected, sizeof expected, "--heatmap names an output of the render, and %s", twin);
    expect_chapter_run(12, "--heatmap " TEST_OUT "/refused-heat.png --pov " TEST_OUT "/refused.pov", 2, expected);
    expect_chapter_run(16, "--pov " TEST_OUT "/refused.pov --frames 3", 2,
                       "--frames, --frame, --video, --refit and --rebuild are for rendering frames, and --pov writes "
                       "the scene's POV-Ray twin instead (its clock runs over POV-Ray's own frames); give one or the other");
    struct stat st;
    cr_assert(stat(TEST_OUT "/refused.pov", &st) != 0 && stat(TEST_OUT "/refused.png", &st) != 0,
              "nothing is written");
}

Test(cli, a_missing_scene_file_is_bad_input) {
    expect_chapter_run(2, "no/such.scene", 1, "no/such.scene: cannot open: No such file or directory");
}

Test(cli, a_scene_error_names_file_and_line) {
    const char *path = scene_file("bad-key.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\n"
                                                   "sphere centre 0 0 0 radus 1\n");
    char arguments[512], expected[512];
    snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/never.png", path);
    snprintf(expected, sizeof expected, "%s:3: unknown key 'radus' for sphere", path);
    expect_chapter_run(2, arguments, 1, expected);
}

Test(cli, a_mesh_error_names_the_mesh_file_and_line) {
    scene_file("bad-mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    const char *path = scene_file("bad-mesh.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\n"
                                                    "mesh bad-mesh.obj\n");
    char arguments[512];
    snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/never.png", path);
    expect_chapter_run(3, arguments, 1, TEST_OUT "/bad-mesh.obj:4: index 4 out of range (3 vertices)");
}

Test(cli, an_unwritable_output_fails_and_leaves_nothing_behind) {
    expect_chapter_run(2, "-o " TEST_OUT "/no/such/folder/x.png", 3,
               TEST_OUT "/no/such/folder/x.png: cannot create: No such file or directory");
}

Test(cli, the_default_folder_is_made_before_the_outputs_are_tried) {
    /* In a folder with no out/ yet (a fresh clone, the page's file system): the picture goes to the
     * default out/chapter-02.png, and a heat-map named into out/ too must not be refused as in a folder
     * that is not there. */
    char cwd[1024], command[4096], output[4096];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    cr_assert_eq(system("rm -rf " TEST_OUT "/fresh-folder && mkdir -p " TEST_OUT "/fresh-folder"), 0);
    snprintf(command, sizeof command, "cd " TEST_OUT "/fresh-folder && %s/%s %s/%s --heatmap out/heat.png --quiet", cwd,
             chapter_program(2), cwd, chapter_scene(2));
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    cr_assert_eq(access(TEST_OUT "/fresh-folder/out/chapter-02.png", F_OK), 0);
    cr_assert_eq(access(TEST_OUT "/fresh-folder/out/heat.png", F_OK), 0);
}

Test(cli, an_output_that_cannot_be_created_is_found_before_anything_else_is_done) {
    /* Before the scene is read, let alone rendered: its own error would come first otherwise. */
    expect_chapter_run(15, TEST_OUT "/no-such.scene -o " TEST_OUT "/x.png --hdr " TEST_OUT "/no/such/folder/x.pfm", 3,
                       TEST_OUT "/no/such/folder/x.pfm: cannot create: No such file or directory");
    expect_chapter_run(2, TEST_OUT "/no-such.scene -o " TEST_OUT, 3, TEST_OUT ": cannot create: Is a directory");
    /* Only the outputs that will be written: with --pov, the default picture's is not. */
    expect_chapter_run(2, "--pov " TEST_OUT "/early.pov --quiet", 0, "");
    /* The trial leaves nothing behind in the folder it tried. */
    cr_assert_eq(system("rm -rf " TEST_OUT "/trial"), 0);
    mkdir(TEST_OUT "/trial", 0755);
    char err[256];
    cr_assert(outfile_can_create(TEST_OUT "/trial/x.png", err, sizeof err), "%s", err);
    DIR *folder = opendir(TEST_OUT "/trial");
    cr_assert_not_null(folder);
    struct dirent *entry;
    int entries = 0;
    while ((entry = readdir(folder)) != NULL)
        entries += strcmp(entry->d_name, ".") != 0 && strcmp(entry->d_name, "..") != 0;
    closedir(folder);
    cr_assert_eq(entries, 0, "the trial left %d files", entries);
}

Test(cli, a_failed_render_keeps_the_previous_picture) {
    /* A picture from an earlier run must survive a later run that fails on a bad scene. */
    const char *picture = TEST_OUT "/kept.png";
    cr_assert_eq(render_chapter(2, chapter_scene(2), picture, ""), 0);
    struct stat before, after;
    cr_assert_eq(stat(picture, &before), 0);
    const char *bad = scene_file("truncated.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 8\nsphere centre 0 0\n");
    cr_assert_eq(render_chapter(2, bad, picture, ""), 1);
    cr_assert_eq(stat(picture, &after), 0);
    cr_assert_eq(before.st_size, after.st_size);
    cr_assert_eq(before.st_mtime, after.st_mtime);
}

Test(cli, a_chapter_ignores_shapes_it_does_not_know_and_says_so_once) {
    char arguments[256];
    snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/ignoring.png", chapter_scene(8));
    expect_chapter_run(2, arguments, 0, "scenes/08-recursion.scene: chapter 2 ignores 1 mesh, 2 planes (not introduced yet)");
}

Test(cli, a_scene_that_nothing_lights_is_refused_with_why) {
    /* Veach's plates are lit only by emitting spheres, which chapters before 15 (and 16) do not draw: no
     * light line, no ambient and a black background would make a black picture with exit 0. */
    for (int chapter = 6; chapter <= 16; chapter++) {
        if (chapter == 9 || chapter == 10 || chapter == 11 || chapter == 15)
            continue; /* 9 to 11 draw as 8 does; 15 draws the emission */
        char expected[512];
        snprintf(expected, sizeof expected, "scenes/17-veach.scene: nothing lights the scene, so the picture would be "
                 "black: no light line with a colour above 0, no ambient light (ambient_light not above 0, or no "
                 "material drawn with an ambient) and no background above 0 (chapter %d ignores the emission of 5 materials: chapters 15 and 17 draw it)",
                 chapter);
        expect_chapter_run(chapter, "scenes/17-veach.scene --quiet -o " TEST_OUT "/unlit.png", 1, expected);
    }
    /* One ambient term on a drawn shape is light enough; so is a light, or a background to reflect. */
    expect_chapter_run(8, "scenes/17-veach.scene --quiet -o " TEST_OUT "/unlit.png --set material.backdrop.ambient=0.1 "
                       "--set 'ambient_light=1 1 1'", 0, "");
    expect_chapter_run(8, "scenes/17-veach.scene --quiet -o " TEST_OUT "/unlit.png --set 'background=0 0 0.1'", 0, "");
    /* chapter 2 lights every surface from the eye */
    expect_chapter_run(2, "scenes/17-veach.scene --quiet -o " TEST_OUT "/unlit.png", 0, "");
    /* a scene with nothing in it draws its black background, as it says */
    FILE *f = fopen(TEST_OUT "/empty.scene", "w");
    cr_assert_not_null(f);
    fprintf(f, "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 6\nbackground 0 0 0\nambient_light 0 0 0\n");
    fclose(f);
    expect_chapter_run(8, TEST_OUT "/empty.scene --quiet -o " TEST_OUT "/unlit.png", 0, "");
}

/* A light, an ambient light or a background none of whose channels is above 0 lights nothing: a light
 * line of colour 0 0 0 drew a black picture with exit 0 (a negative light takes light away, as in
 * POV-Ray, and is fine beside one that adds some). */
Test(cli, lights_and_backgrounds_of_no_colour_above_0_light_nothing) {
    static const char *const unlit[] = {
        "ambient_light 0 0 0\nlight position -4 6 5 colour 0 0 0\n",
        "ambient_light 0 0 0\nlight position -4 6 5 colour -1 -1 -1\n",
        "ambient_light -1 -1 -1\nlight position -4 6 5 colour -0.5 0 0\n",
        "ambient_light 0 0 0\nbackground -1 -1 -1\nlight position -4 6 5 colour 0 -1 0\n",
    };
    static const char *const lit[] = {
        "ambient_light 0 0 0\nlight position -4 6 5 colour 0 0 0.01\n",
        "ambient_light 0 0 0\nlight position -4 6 5 colour -1 -1 -1\nlight position 4 6 5 colour 2 2 2\n",
        "ambient_light 0 0.2 0\nlight position -4 6 5 colour -1 -1 -1\n",
    };
    const char *scene = TEST_OUT "/unlit-lights.scene";
    char arguments[256], expected[512];
    snprintf(arguments, sizeof arguments, "%s --quiet -o " TEST_OUT "/unlit-lights.png", scene);
    snprintf(expected, sizeof expected, "%s: nothing lights the scene, so the picture would be black: no light line "
             "with a colour above 0, no ambient light (ambient_light not above 0, or no material drawn with an "
             "ambient) and no background above 0", scene);
    for (int k = 0; k < 4 + 3; k++) {
        FILE *f = fopen(scene, "w");
        cr_assert_not_null(f);
        fprintf(f, "camera eye 0 1 5 target 0 0.5 0 fov 40\nimage 32 24\n%ssphere centre 0 1 0 radius 1\n",
                k < 4 ? unlit[k] : lit[k - 4]);
        fclose(f);
        for (int chapter = 6; chapter <= 16; chapter += 2)
            if (k < 4)
                expect_chapter_run(chapter, arguments, 1, expected);
            else
                expect_chapter_run(chapter, arguments, 0, "");
    }
}

Test(cli, the_counters_are_printed) {
    char arguments[256];
    snprintf(arguments, sizeof arguments, "-o " TEST_OUT "/counted.png");
    expect_chapter_run(2, arguments, 0, "sphere tests              384000");
}

Test(cli, no_progress_line_for_a_render_shorter_than_the_interval) {
    char command[512], output[8192];
    snprintf(command, sizeof command, "%s --width 64 --height 48 -o " TEST_OUT "/quiet-progress.png", chapter_program(3));
    cr_assert_eq(run_capturing(command, output, sizeof output), 0);
    cr_assert_null(strstr(output, "rendering:"), "a progress line for a render of less than 5 s:\n%s", output);
}

/* A render of chapter 15 that takes a good part of a second, with a line due every 20 ms. */
#define CLI_SLOW_PATHS "WHITTED_PROGRESS_SECONDS=0.02 %s scenes/15-paths.scene --width 64 --height 64 " \
                       "--set paths.samples=64 --threads 2 -o " TEST_OUT "/progress.png"

Test(cli, progress_lines_reach_a_pipe_at_every_interval) {
    char command[512], output[16384];
    snprintf(command, sizeof command, CLI_SLOW_PATHS, chapter_program(15));
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    /* Lines, not a bar: each ends in a newline, the first ones may come before any block is done. */
    cr_assert_null(strchr(output, '\r'), "%s", output);
    const char *line = strstr(output, "rendering: ");
    cr_assert_not_null(line, "no progress line went to the pipe:\n%s", output);
    cr_assert(strstr(output, " of 4 blocks after ") != NULL, "%s", output);
    cr_assert(strstr(output, " s left\n") != NULL || strstr(output, "the time left is known once one is done\n"),
              "%s", output);
    cr_assert_not_null(strstr(output, "rendering: done in "), "%s", output);
    /* --quiet: nothing at all. */
    snprintf(command, sizeof command, CLI_SLOW_PATHS " --quiet", chapter_program(15));
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    cr_assert_str_eq(output, "");
}

/* Chapters 10 and 11 on chapter 9's scene (8,786 triangles): what is tested is the line naming the
 * structure, not the 353,546-triangle teapot's build. */
Test(cli, stats_adds_the_structure_and_the_predicted_cost) {
    expect_chapter_run(9, "--stats --width 64 --height 48 -o " TEST_OUT "/stats.png", 0, "predicted by the SAH:");
    expect_chapter_run(10, "scenes/09-kdtree.scene --accel bvh --split seed --stats --width 64 --height 48 -o " TEST_OUT
                       "/stats.png", 0, "acceleration: BVH (median split) over 8786 triangles");
    expect_chapter_run(11, "scenes/09-kdtree.scene --rung simd --stats --width 64 --height 48 -o " TEST_OUT "/stats.png",
                       0, "acceleration: fast BVH, rung 3 simd (binned SAH) over 8786 triangles");
    expect_chapter_run(11, "scenes/09-kdtree.scene --rung 1 --stats --width 64 --height 48 -o " TEST_OUT "/stats.png", 0,
                       "acceleration: BVH (binned SAH) over 8786 triangles");
}

/* ---- the rays a scene asks for (common/ray_budget.h) -------------------------------------------- */

/* A 640 x 480 picture whose keys multiply: recursive anti-aliasing at depth 6, a lens of 37 rays, a
 * 33 x 33 area light, max_depth 64. Its only sphere is behind the camera, so that rendering it (at a
 * smaller size, with --no-limit) takes one ray a lens point. */
static const char *const multiplying_scene =
    "camera eye 0 0 5 target 0 0 0 fov 40 aperture 0.1 focal_point 0 0 0 blur_samples 37\n"
    "image 640 480\n"
    "max_depth 64\n"
    "antialias method recursive samples 6\n"
    "light position 0 5 5 colour 1 1 1 axis1 1 0 0 axis2 0 0 1 samples 33 33\n"
    "material glass reflection 0.1 transmit 0.9 ior 1.5\n"
    "sphere centre 0 0 20 radius 1 material glass\n";

/* Fails unless chapter n refuses `scene` (exit 1) with "<scene><where>: the scene asks for up to about
 * <rays> rays (<factors>), over the limit of 1e+12; pass --no-limit to render it anyway". */
static void expect_over_budget(int n, const char *scene, const char *where, const char *rays, const char *factors) {
    char arguments[512], expected[1024];
    snprintf(arguments, sizeof arguments, "%s -o " TEST_OUT "/never.png", scene);
    snprintf(expected, sizeof expected, "%s%s: the scene asks for up to about %s rays (%s), over the limit of 1e+12; "
             "pass --no-limit to render it anyway\n", scene, where, rays, factors);
    expect_chapter_run(n, arguments, 1, expected);
}

Test(budget, a_scene_whose_keys_multiply_past_the_limit_is_refused_naming_them) {
    const char *scene = scene_file("multiplying.scene", multiplying_scene);
    expect_over_budget(13, scene, "", "8.2e+14",
                       "640 x 480 pixels, antialias recursive depth 6: up to 1089 rays a pixel, blur_samples 37, "
                       "1 light (area light 33 x 33): 1089 shadow rays a hit, max_depth 64: up to 66626 rays a camera ray");
    /* Chapter 12 draws neither the lens nor the area: the same scene asks for less, still too much. */
    expect_over_budget(12, scene, "", "4.4e+13",
                       "640 x 480 pixels, antialias recursive depth 6: up to 1089 rays a pixel, 1 light: 1 shadow ray "
                       "a hit, max_depth 64: up to 131074 rays a camera ray");
    /* --quiet does not hide a refusal. */
    char arguments[512];
    snprintf(arguments, sizeof arguments, "%s --quiet -o " TEST_OUT "/never.png", scene);
    expect_chapter_run(13, arguments, 1, "over the limit of 1e+12");
}

Test(budget, paths_that_multiply_past_the_limit_point_at_the_paths_line) {
    const char *scene = scene_file("many-paths.scene", "camera eye 0 0 5 target 0 0 0 fov 40\nimage 640 480\n"
                                                       "paths samples 1048576 bounces 4096\n"
                                                       "material lamp emission 1 1 1\n"
                                                       "sphere centre 0 0 0 radius 1 material lamp\n");
    expect_over_budget(15, scene, ":3", "2.6e+15",
                       "640 x 480 pixels, paths samples 1048576 bounces 4096 strategy mis: up to 8195 rays a path");
}

Test(budget, no_limit_renders_it_and_says_it_is_large) {
    const char *scene = scene_file("multiplying-small.scene", multiplying_scene);
    char arguments[512], expected[1024];
    /* 100 x 100 pixels: still over the limit by its keys, one ray a lens point in fact. */
    snprintf(arguments, sizeof arguments, "%s --width 100 --height 100 --no-limit -o " TEST_OUT "/no-limit.png", scene);
    snprintf(expected, sizeof expected,
             "%s: note: the scene asks for up to about 2.7e+13 rays (100 x 100 pixels, antialias recursive depth 6: "
             "up to 1089 rays a pixel, blur_samples 37, 1 light (area light 33 x 33): 1089 shadow rays a hit, "
             "max_depth 64: up to 66626 rays a camera ray); this may take a while\n", scene);
    expect_chapter_run(13, arguments, 0, expected);
    /* With --quiet, nothing at all. */
    char command[1024], output[4096];
    snprintf(command, sizeof command, "%s %s --width 100 --height 100 --no-limit --quiet -o " TEST_OUT "/no-limit.png",
             chapter_program(13), scene);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    cr_assert_str_eq(output, "");
    /* The POV-Ray twin renders nothing here, so it is never refused. */
    snprintf(arguments, sizeof arguments, "%s --pov " TEST_OUT "/multiplying.pov --quiet", scene);
    expect_chapter_run(13, arguments, 0, "");
}

/* Reads scene text as a chapter does (its kinds of shape do not matter here) and returns the bound. */
static double bound_of(const char *text, int chapter, struct ray_budget *b) {
    struct scene s;
    char err[1024];
    cr_assert(scene_parse("bound.scene", text, NULL, &s, err, sizeof err), "%s", err);
    scene_drop_unsupported(&s, chapter, NULL);
    double rays = ray_budget_estimate(&s, chapter, b);
    scene_free(&s);
    return rays;
}

Test(budget, the_bound_multiplies_what_each_chapter_draws) {
    const char *text = "camera eye 0 0 5 target 0 0 0 fov 40 aperture 0.1 focal_point 0 0 0 blur_samples 7\n"
                       "image 10 10\nmax_depth 3\nantialias method grid samples 4\n"
                       "light position 0 5 5 colour 1 1 1\n"
                       "light position 0 5 5 colour 1 1 1 axis1 1 0 0 axis2 0 0 1 samples 5 5\n"
                       "material glass reflection 0.1 filter 0.9 ior 1.5\n";
    struct ray_budget b;
    cr_assert_float_eq(bound_of(text, 6, &b), 100.0, 0); /* one ray a pixel, no shadows */
    cr_assert_float_eq(bound_of(text, 7, &b), 100.0 * 3, 0); /* two point lights' shadow rays */
    cr_assert_float_eq(bound_of(text, 8, &b), 100.0 * 7 * 3, 0); /* 2^3 - 1 rays a tree */
    cr_assert_float_eq(bound_of(text, 12, &b), 100.0 * 16 * 7 * 3, 0); /* 4 x 4 camera rays a pixel */
    cr_assert_float_eq(bound_of(text, 13, &b), 100.0 * 16 * 7 * 7 * 27, 0); /* the lens; 1 + 25 shadow rays */
    cr_assert_float_eq(b.shadow_per_hit, 26, 0);
    /* The adaptive methods' worst case, with the rays each block takes beyond its edges (40 x 40 pixels
     * are 2 x 2 blocks). */
    const char *adaptive = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 40 40\nmax_depth 1\n"
                           "antialias method adaptive samples 3\n";
    cr_assert_float_eq(bound_of(adaptive, 12, &b), 1600.0 * 10 + 2 * 40 + 2 * 40, 0);
    const char *recursive = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 40 40\nmax_depth 1\n"
                            "antialias method recursive samples 2\n";
    cr_assert_float_eq(bound_of(recursive, 12, &b), 1600.0 * (9 - 4) + 1600 + 2 * 40 + 2 * 40 + 4, 0);
    /* Chapter 15: samples x (bounces + 2 rays and bounces + 1 shadow rays), none for scatter. */
    const char *paths = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 10 10\npaths samples 4 bounces 10\n";
    cr_assert_float_eq(bound_of(paths, 15, &b), 100.0 * 4 * 23, 0);
    const char *scatter = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 10 10\npaths samples 4 bounces 10 "
                          "strategy scatter\n";
    cr_assert_float_eq(bound_of(scatter, 15, &b), 100.0 * 4 * 12, 0);
    cr_assert_eq(b.line, 3);
}

Test(budget, the_tree_grows_only_as_far_as_the_materials_let_it) {
    /* A tree branches in two only where a material both reflects and lets light through; a material
     * that does one of them makes a chain of max_depth rays; none of them, the camera ray alone. */
    const char *head = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 10 10\nmax_depth 10\n"
                       "light position 0 5 5 colour 1 1 1\n";
    static const struct {
        const char *material;
        double rays_a_tree;
    } cases[] = {
        {"material matte colour 1 1 1 diffuse 0.7\n", 1},
        {"material mirror reflection 1\n", 10},
        {"material pane transmit 1 ior 1.5\n", 10},
        {"material tinted filter 0.5 ior 1.5\n", 10},
        {"material mirror reflection 1\nmaterial pane transmit 1 ior 1.5\n", 10},
        {"material glass reflection 0.1 transmit 0.9 ior 1.5\n", 1023},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char text[512];
        snprintf(text, sizeof text, "%s%s", head, cases[k].material);
        struct ray_budget b;
        /* Each ray of the tree with its one shadow ray. */
        cr_assert_float_eq(bound_of(text, 8, &b), 100.0 * cases[k].rays_a_tree * 2, 0, "%s", cases[k].material);
    }
}

Test(budget, the_tree_budget_caps_the_bound_and_nothing_overflows) {
    /* max_depth 64 alone would be 2^64 - 1 rays a tree: the budget holds it to 1 + 65536 rays, each
     * with its point light's shadow ray. */
    const char *deep = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 1 1\nmax_depth 64\n"
                       "light position 0 5 5 colour 1 1 1\nmaterial glass reflection 0.1 transmit 0.9 ior 1.5\n";
    struct ray_budget b;
    cr_assert_float_eq(bound_of(deep, 8, &b), 2.0 * (1 + RAY_TREE_BUDGET), 0);
    /* Every key at its largest: finite, and far over the limit. */
    static char text[1 << 16];
    int used = snprintf(text, sizeof text, "camera eye 0 0 5 target 0 0 0 fov 40 aperture 1 focal_point 0 0 0 "
                        "blur_samples 37\nimage 16384 16384\nmax_depth 64\nantialias method recursive samples 6\n"
                        "material glass reflection 0.1 transmit 0.9 ior 1.5\n");
    for (int k = 0; k < 100; k++)
        used += snprintf(text + used, sizeof text - (size_t)used, "light position 0 5 5 colour 1 1 1 axis1 1 0 0 "
                         "axis2 0 0 1 samples 33 33\n");
    double rays = bound_of(text, 14, &b);
    cr_assert(isfinite(rays) && rays > RAY_BUDGET_LIMIT, "%g", rays);
    /* The shipped scene that asks for the most, chapter 15's Cornell box (256 x 256 pixels, 256 paths of
     * at most 64 bounces: 2.2e9), stays under the note. */
    struct scene s;
    char err[1024];
    cr_assert(scene_load("scenes/15-paths.scene", NULL, &s, err, sizeof err), "%s", err);
    rays = ray_budget_estimate(&s, 15, &b);
    scene_free(&s);
    cr_assert_float_eq(rays, 256.0 * 256 * 256 * (64 + 2 + 65), 0);
    cr_assert(rays < RAY_BUDGET_LARGE, "%g", rays);
}

Test(budget, every_ray_tests_the_shapes_no_structure_holds) {
    /* Two spheres, a box and a plane, each tested by every ray; the triangle line too until chapter 9
     * gathers it into its tree. */
    const char *text = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 10 10\nmax_depth 1\n"
                       "sphere centre 0 0 0 radius 1\nsphere centre 2 0 0 radius 1\nbox min 0 0 0 max 1 1 1\n"
                       "plane normal 0 1 0 distance -1\ntriangle a 0 0 0 b 1 0 0 c 0 1 0\n";
    static const struct shape_kind *const spheres_only[] = {&sphere_kind, NULL}; /* as chapter 2 draws */
    static const struct {
        int chapter;
        const struct shape_kind *const *kinds;
        double shapes;
    } cases[] = {{2, spheres_only, 2}, {8, test_every_kind, 5}, {9, test_every_kind, 4}, {15, test_every_kind, 4}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        struct scene s;
        char err[1024];
        cr_assert(scene_parse("shapes.scene", text, cases[k].kinds, &s, err, sizeof err), "%s", err);
        scene_drop_unsupported(&s, cases[k].chapter, NULL);
        struct ray_budget b;
        double rays = ray_budget_estimate(&s, cases[k].chapter, &b);
        scene_free(&s);
        cr_assert_float_eq(b.shapes_per_ray, cases[k].shapes, 0, "chapter %d: %g", cases[k].chapter, b.shapes_per_ray);
        cr_assert_float_eq(b.tests, rays * cases[k].shapes, 0);
    }
    struct ray_budget b;
    bound_of("camera eye 0 0 5 target 0 0 0 fov 40\nimage 10 10\n", 8, &b); /* nothing: the ray itself */
    cr_assert_float_eq(b.shapes_per_ray, 1, 0);
}

Test(budget, a_hundred_thousand_spheres_under_an_area_light_are_refused_by_their_tests) {
    /* 640 x 480 camera rays, each with 1089 shadow rays, each ray testing 100,000 spheres: 3.3e13 tests,
     * weeks of work, though its 3.3e8 rays are well within the rays' limit. */
    size_t size = 200 + 100000 * 48, used = 0;
    char *text = malloc(size);
    cr_assert_not_null(text);
    used += (size_t)snprintf(text, size, "camera eye 50 50 120 target 50 50 0 fov 60\nimage 640 480\n"
                                         "light position 50 50 150 axis1 10 0 0 axis2 0 10 0 samples 33 33\n");
    for (int k = 0; k < 100000; k++)
        used += (size_t)snprintf(text + used, size - used, "sphere centre %d %d %d radius 0.3\n", k % 100,
                                 k / 100 % 100, -(k / 10000));
    FILE *out = fopen(TEST_OUT "/spheres.scene", "w");
    cr_assert_not_null(out);
    fputs(text, out);
    fclose(out);
    free(text);
    expect_chapter_run(13, TEST_OUT "/spheres.scene -o " TEST_OUT "/spheres.png", 1,
                       TEST_OUT "/spheres.scene: the scene asks for up to about 3.3e+08 rays (640 x 480 pixels, 1 "
                       "light (area light 33 x 33): 1089 shadow rays a hit, max_depth 5: up to 1090 rays a camera "
                       "ray), each testing 100000 shapes that no structure holds: about 3.3e+13 tests, over the "
                       "limit of 3e+13; pass --no-limit to render it anyway");
    /* At 64 x 48 pixels, a hundredth of the tests: a note, and the run goes on (cut short here by --tile
     * to one pixel, whose rays the bound does not know). */
    expect_chapter_run(13, TEST_OUT "/spheres.scene --width 64 --height 48 --tile 0 0 1 1 -o " TEST_OUT
                           "/spheres.png", 0,
                       "each testing 100000 shapes that no structure holds: about 3.3e+11 tests; this may take a "
                       "while");
}

/* A deep tree of glass panes lit by a 33 x 33 area light: every hit sends 1089 shadow rays. They are
 * spent from the tree's budget (RAY_TREE_BUDGET), so four pixels are quick; before, more than 30 s. */
Test(budget, area_light_shadow_rays_are_spent_from_the_tree_budget, .timeout = 60) {
    static char text[4096];
    int used = snprintf(text, sizeof text, "camera eye 0 0 10 target 0 0 0 fov 30\nimage 2 2\n"
                        "light position 0 10 10 colour 1 1 1 axis1 1 0 0 axis2 0 1 0 samples 33 33\n"
                        "max_depth 64\nadc_bailout 0\n"
                        "material glass colour 1 1 1 ambient 0 diffuse 0.5 reflection 0.5 transmit 0.5 ior 1.5\n");
    for (int k = 0; k < 20; k++)
        used += snprintf(text + used, sizeof text - (size_t)used, "plane normal 0 0 1 distance %g material glass\n",
                         -0.5 * k);
    const char *scene = scene_file("lit-panes.scene", text);
    char arguments[512];
    snprintf(arguments, sizeof arguments, "%s --threads 1 -o " TEST_OUT "/lit-panes.png", scene);
    expect_chapter_run(13, arguments, 0, "their camera ray had spent 65536 already (RAY_TREE_BUDGET: secondary rays "
                                         "and area-light shadow rays)");
    /* Every camera ray stops within its budget and one more hit's shadow rays. */
    expect_chapter_run(13, arguments, 0, "rays (all)                266316");
}

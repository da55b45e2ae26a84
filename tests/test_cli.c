/* test_cli.c: the chapter programs from the outside: options, exit codes, messages for bad input,
 * and no half-written output. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "image_test_support.h"
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
    expect_chapter_run(11, "--rung 11", 2,
                       "--rung needs 1 to 10 or one of: plain wide simd prefetch build float compact eight lean packet; got '11'");
    expect_chapter_run(11, "--rung fast", 2,
                       "--rung needs 1 to 10 or one of: plain wide simd prefetch build float compact eight lean packet; got 'fast'");
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

Test(cli, the_counters_are_printed) {
    char arguments[256];
    snprintf(arguments, sizeof arguments, "-o " TEST_OUT "/counted.png");
    expect_chapter_run(2, arguments, 0, "sphere tests              384000");
}

Test(cli, no_progress_line_when_stderr_is_not_a_terminal) {
    char command[512], output[8192];
    snprintf(command, sizeof command, "%s --width 64 --height 48 -o " TEST_OUT "/quiet-progress.png", chapter_program(3));
    cr_assert_eq(run_capturing(command, output, sizeof output), 0);
    cr_assert_null(strstr(output, "rendering:"), "a progress line went to a pipe:\n%s", output);
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

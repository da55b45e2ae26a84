/* test_figures.c: the walkthroughs' figures are what tools/figures draws now, and every walkthrough
 * shows its own; the heat-map's colour bar marks the fixed scale with readable numbers. */
#include <criterion/criterion.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "heatmap.h"
#include "image.h"
#include "test_support.h"

static const char *build_dir(void) {
    const char *build = getenv("WHITTED_BUILD");
    return build != NULL ? build : "build";
}

Test(figures, the_committed_figures_are_what_the_program_draws_now, .timeout = 60) {
    char command[512];
    snprintf(command, sizeof command, "rm -rf out/test/figures && mkdir -p out/test/figures && ./%s/figures out/test/figures",
             build_dir());
    cr_assert_eq(run_logged(command, "out/test/figures.log"), 0, "the figure program failed: see out/test/figures.log");
    glob_t drawn, committed;
    cr_assert_eq(glob("out/test/figures/*.svg", 0, NULL, &drawn), 0, "the program drew no figure");
    cr_assert_eq(glob("docs/figures/*.svg", 0, NULL, &committed), 0, "docs/figures/ holds no figure: run make figures");
    cr_expect_geq(drawn.gl_pathc, 10, "one figure or more per chapter 1-10");
    cr_expect_eq(drawn.gl_pathc, committed.gl_pathc, "the program draws %zu figures, docs/figures/ holds %zu: run make figures",
                 drawn.gl_pathc, committed.gl_pathc);
    for (size_t k = 0; k < drawn.gl_pathc; k++) {
        const char *name = strrchr(drawn.gl_pathv[k], '/') + 1;
        char path[512];
        snprintf(path, sizeof path, "docs/figures/%s", name);
        cr_expect(access(path, R_OK) == 0, "%s is missing: run make figures", path);
        if (access(path, R_OK) != 0)
            continue;
        size_t new_size = 0, old_size = 0;
        char *now = read_file(drawn.gl_pathv[k], &new_size), *before = read_file(path, &old_size);
        cr_expect(new_size == old_size && memcmp(now, before, new_size) == 0,
                  "%s differs from what tools/figures draws now: run make figures (and look at it)", path);
        free(now);
        free(before);
    }
    globfree(&drawn);
    globfree(&committed);
}

Test(figures, every_figure_is_shown_by_a_walkthrough) {
    glob_t committed, walkthroughs;
    cr_assert_eq(glob("docs/figures/*.svg", 0, NULL, &committed), 0);
    cr_assert_eq(glob("docs/[01][0-9]-*.md", 0, NULL, &walkthroughs), 0);
    for (size_t k = 0; k < committed.gl_pathc; k++) {
        const char *name = strrchr(committed.gl_pathv[k], '/') + 1;
        char link[256];
        snprintf(link, sizeof link, "](figures/%s)", name);
        bool shown = false;
        for (size_t w = 0; w < walkthroughs.gl_pathc && !shown; w++) {
            char *text = read_text_file(walkthroughs.gl_pathv[w]);
            shown = strstr(text, link) != NULL;
            free(text);
        }
        cr_expect(shown, "no walkthrough shows docs/figures/%s", name);
    }
    globfree(&committed);
    globfree(&walkthroughs);
}

Test(figures, a_bad_command_line_or_an_unwritable_folder_is_refused) {
    char command[512];
    snprintf(command, sizeof command, "./%s/figures", build_dir());
    cr_expect_eq(run_logged(command, "out/test/figures-errors.log"), 2, "no folder given: exit status 2");
    snprintf(command, sizeof command, "./%s/figures out/test/no-such-folder/figures", build_dir());
    cr_expect_eq(run_logged(command, "out/test/figures-errors.log"), 3, "unwritable folder: exit status 3");
    char *log = read_text_file("out/test/figures-errors.log");
    cr_expect_not_null(strstr(log, "out/test/no-such-folder/figures/01-camera.svg: cannot write: No such file or directory"),
                       "the message names the file and the reason:\n%s", log);
    free(log);
}

/* A heat-map of width x height pixels, every one costing `cost`, with its colour bar, as the chapter
 * programs draw it; returns its RGB levels (the caller frees them). */
static uint8_t *heatmap_with_bar(int width, int height, uint32_t cost, int *full_height) {
    struct image img;
    *full_height = height + heatmap_bar_height(width, height);
    cr_assert(image_create(&img, width, *full_height));
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++)
            image_set(&img, i, j, heatmap_colour(cost));
    heatmap_draw_bar(&img, height);
    return img.rgb;
}

static bool is_black(const uint8_t *p) { return p[0] == 0 && p[1] == 0 && p[2] == 0; }
static bool is_white(const uint8_t *p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

Test(heatmap, the_colour_bar_is_added_under_the_picture_and_shows_the_scale) {
    int width = 320, height = 0;
    uint8_t *rgb = heatmap_with_bar(320, 240, 100, &height);
    cr_assert_gt(height, 240, "the bar adds rows under the picture");
    vec3 expected = heatmap_colour(100);
    const uint8_t *corner = rgb + ((size_t)239 * 320 + 319) * 3;
    cr_expect(corner[0] == image_quantize(expected.x) && corner[1] == image_quantize(expected.y) &&
                  corner[2] == image_quantize(expected.z),
              "the picture keeps every one of its rows");
    int scale = heatmap_bar_scale(320);
    int bar_row = 240 + 8 * scale, tick_row = 240 + 15 * scale;
    for (int k = 0; k < HEATMAP_TICKS; k++) {
        /* the bar has the colour of the cost its tick marks (within rounding of the column) */
        int x = heatmap_bar_x(320, heatmap_ticks[k]);
        const uint8_t *bar = rgb + ((size_t)bar_row * 320 + x) * 3;
        vec3 want = heatmap_colour(heatmap_ticks[k]);
        cr_expect(abs(bar[0] - image_quantize(want.x)) <= 8 && abs(bar[1] - image_quantize(want.y)) <= 8 &&
                      abs(bar[2] - image_quantize(want.z)) <= 8,
                  "the bar at the tick for %u has colour (%d, %d, %d)", heatmap_ticks[k], bar[0], bar[1], bar[2]);
        cr_expect(is_black(rgb + ((size_t)tick_row * 320 + x) * 3), "a tick marks %u", heatmap_ticks[k]);
    }
    cr_expect(is_white(rgb + ((size_t)tick_row * 320 + (heatmap_bar_x(320, 10) + heatmap_bar_x(320, 100)) / 2) * 3),
              "no tick between 10 and 100");
    /* Below the bar there are only the ticks (6 of 3 pixels) and the numbers 0 1 10 100 1000 8192,
     * whose digits in the 5 x 7 font have 229 pixels set: a missing, extra or garbled digit changes
     * the count. */
    int black = 0;
    for (int j = 240 + 14 * scale; j < height; j++)
        for (int i = 0; i < width; i++)
            black += is_black(rgb + ((size_t)j * 320 + i) * 3);
    cr_expect_eq(black, (6 * 3 + 229) * scale * scale, "black pixels under the bar: %d", black);
    free(rgb);
}

Test(heatmap, a_picture_too_narrow_for_the_numbers_gets_the_bar_alone) {
    int width = 20, height = 0;
    uint8_t *rgb = heatmap_with_bar(20, 10, 0, &height);
    cr_assert_gt(height, 10);
    int black_below_bar = 0;
    for (int j = 10 + 14; j < height; j++)
        for (int i = 0; i < width; i++)
            black_below_bar += is_black(rgb + ((size_t)j * 20 + i) * 3);
    cr_expect_eq(black_below_bar, 0, "no ticks or numbers squeezed in");
    const uint8_t *right_end = rgb + ((size_t)(10 + 8) * 20 + 19) * 3;
    cr_expect(is_white(right_end), "the bar ends at white (cost %d and more)", HEATMAP_MAX_COST);
    free(rgb);
}

Test(heatmap, a_chapter_writes_its_heat_map_with_the_bar_and_a_picture_at_the_limit_without) {
    char command[512];
    snprintf(command, sizeof command, "./%s/chapter-01 --quiet --width 320 --height 240 -o out/test/heatmap-picture.png "
             "--heatmap out/test/heatmap-chapter-01.png", build_dir());
    cr_assert_eq(run_logged(command, "out/test/heatmap.log"), 0, "see out/test/heatmap.log");
    char err[256];
    int width = 0, height = 0;
    uint8_t *rgb = image_read_rgb("out/test/heatmap-chapter-01.png", &width, &height, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    cr_expect_eq(width, 320);
    cr_expect_eq(height, 240 + heatmap_bar_height(320, 240), "the heat-map is the picture and its bar");
    cr_expect(is_black(rgb + ((size_t)(240 + 15 * heatmap_bar_scale(320)) * 320 + heatmap_bar_x(320, 1000)) * 3),
              "the tick for 1000 is there");
    free(rgb);
    cr_expect_eq(heatmap_bar_height(4, IMAGE_MAX_SIDE), 0, "a picture as tall as allowed gets no bar");
    cr_expect_gt(heatmap_bar_height(4, IMAGE_MAX_SIDE - heatmap_bar_height(4, 1)), 0, "one with room for it does");
}

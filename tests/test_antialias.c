/* test_antialias.c: chapter 12's anti-aliasing: the antialias line and its errors, the counter-based
 * random numbers, each sampling method on pictures whose answer is known, POV-Ray's two rules down to
 * the block boundary, the same picture for any thread count, and agreement with POV-Ray for the grid
 * (against POV-Ray at n times the size, averaged down) and both adaptive rules, and jitter's noise
 * against the grid's aliasing. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "image_test_support.h"
#include "scene.h"
#include "scene_set.h"
#include "sample_hash.h"
#include "supersample.h"
#include "test_support.h"

#define SCENE_HEAD "camera eye 0 0 5 target 0 0 0 fov 40\nimage 64 48\n"

/* ---- the antialias line --------------------------------------------------------------------------- */

/* Parses SCENE_HEAD followed by `line`; returns whether it parsed, the scene in *s (free it) and the
 * message in err. */
static bool parse_line(const char *line, struct scene *s, char *err, size_t err_size) {
    return parse_scene_lines("aa.scene", SCENE_HEAD, line, NULL, s, err, err_size);
}

static void expect_refused(const char *line, const char *message) {
    expect_scene_refused("aa.scene", SCENE_HEAD, line, NULL, message);
}

Test(antialias_line, keys_are_read_and_defaults_are_povrays) {
    struct scene s;
    char err[512] = "";
    cr_assert(parse_line("antialias method recursive samples 4 threshold 0.1", &s, err, sizeof err), "%s", err);
    cr_expect_eq(s.antialias.method, ANTIALIAS_RECURSIVE);
    cr_expect_eq(s.antialias.samples, 4);
    cr_expect_eq(s.antialias.threshold, 0.1);
    cr_expect_eq(s.antialias.line, 3);
    scene_free(&s);
    cr_assert(parse_line("antialias seed 4294967295", &s, err, sizeof err), "%s", err);
    cr_expect_eq(s.antialias.method, ANTIALIAS_GRID, "a line without a method is a grid");
    cr_expect_eq(s.antialias.samples, 3, "POV-Ray's default +R3");
    cr_expect_eq(s.antialias.threshold, 0.3, "POV-Ray's default +A0.3");
    cr_expect_eq(s.antialias.seed, 4294967295u);
    scene_free(&s);
    cr_assert(scene_parse("aa.scene", SCENE_HEAD, NULL, &s, err, sizeof err), "%s", err);
    cr_expect_eq(s.antialias.method, ANTIALIAS_NONE, "no line: one ray through each pixel centre");
    cr_expect_eq(s.antialias.line, 0);
    scene_free(&s);
}

Test(antialias_line, bad_values_are_refused_with_file_and_line) {
    expect_refused("antialias method grid samples 0",
                   "aa.scene:3: antialias samples must be a whole number from 1 to 16 for method grid, got 0");
    expect_refused("antialias method adaptive samples 10",
                   "aa.scene:3: antialias samples must be a whole number from 1 to 9 for method adaptive, got 10");
    expect_refused("antialias method recursive samples 7",
                   "aa.scene:3: antialias samples must be a whole number from 1 to 6 for method recursive, got 7");
    expect_refused("antialias samples 2.5",
                   "aa.scene:3: antialias samples must be a whole number from 1 to 16 for method grid, got 2.5");
    expect_refused("antialias method stochastic",
                   "aa.scene:3: unknown antialias method 'stochastic' (none, grid, jitter, adaptive or recursive)");
    expect_refused("antialias method adaptive threshold -0.1",
                   "aa.scene:3: antialias threshold must be between 0 and 1, got -0.1");
    expect_refused("antialias threshold 1.5", "aa.scene:3: antialias threshold must be between 0 and 1, got 1.5");
    expect_refused("antialias threshold 1.0000000000000002",
                   "aa.scene:3: antialias threshold must be between 0 and 1, got 1.0000000000000002");
    expect_refused("antialias method jitter seed -1",
                   "aa.scene:3: antialias seed must be a whole number from 0 to 4294967295, got -1");
    expect_refused("antialias method grid\nantialias method jitter", "aa.scene:4: a second antialias line (a scene has one)");
    expect_refused("antialias samples", "aa.scene:3: 'samples' needs a value");
    expect_refused("antialias colour 1 1 1", "aa.scene:3: unknown key 'colour' for antialias");
}

Test(antialias_line, set_adds_the_line_to_a_scene_without_one) {
    char *text = strdup(SCENE_HEAD), err[256];
    cr_assert(scene_set_apply(&text, "antialias.samples=4", err, sizeof err), "%s", err);
    cr_assert(scene_set_apply(&text, "antialias.method=jitter", err, sizeof err), "%s", err);
    cr_expect_str_eq(text, SCENE_HEAD "antialias samples 4 method jitter\n");
    cr_expect(!scene_set_apply(&text, "antialias.2.samples=4", err, sizeof err), "a second antialias line");
    free(text);
}

Test(antialias_line, chapters_before_12_ignore_it_and_their_twins_do_not_carry_it, .timeout = 60) {
    expect_chapter_run(11, "scenes/12-antialias.scene --quiet --pov " TEST_OUT "/aa-11.pov", 0, "");
    char *twin = read_text_file(TEST_OUT "/aa-11.pov");
    cr_expect_null(strstr(twin, "Antialias"), "chapter 11's twin carries the antialias line");
    free(twin);
    expect_chapter_run(11, "scenes/12-antialias.scene -o " TEST_OUT "/aa-11.png", 0,
                       "scenes/12-antialias.scene: chapter 11 ignores the antialias line (not introduced yet)");
}

Test(antialias_line, the_twin_says_how_povray_renders_it) {
    struct scene s;
    char err[512] = "", options[512];
    cr_assert(parse_line("antialias method adaptive samples 4 threshold 0.125", &s, err, sizeof err), "%s", err);
    antialias_povray_options(&s.antialias, options, sizeof options);
    cr_expect_str_eq(options, "Antialias=on Sampling_Method=1 Antialias_Threshold=0.125 Antialias_Depth=4 Jitter=off "
                              "Antialias_Gamma=2.5 Render_Block_Size=32");
    cr_expect_eq(antialias_box(&s.antialias), 1);
    s.antialias.method = ANTIALIAS_RECURSIVE;
    antialias_povray_options(&s.antialias, options, sizeof options);
    cr_expect_not_null(strstr(options, "Sampling_Method=2 "), "%s", options);
    s.antialias.method = ANTIALIAS_JITTER;
    antialias_povray_options(&s.antialias, options, sizeof options);
    cr_expect_str_eq(options, "");
    cr_expect_eq(antialias_box(&s.antialias), 4, "jitter is compared with the grid's twin");
    scene_free(&s);
}

Test(antialias_line, bad_values_from_the_command_line_name_the_line, .timeout = 60) {
    expect_chapter_run(12, "--set antialias.samples=0 -o " TEST_OUT "/aa-bad.png", 1,
                       "scenes/12-antialias.scene:10: antialias samples must be a whole number from 1 to 9 for "
                       "method adaptive, got 0 (the line as changed by --set)");
    expect_chapter_run(12, "--set antialias.method=box -o " TEST_OUT "/aa-bad.png", 1,
                       "unknown antialias method 'box'");
    expect_chapter_run(12, "--set antialias.threshold=-1 -o " TEST_OUT "/aa-bad.png", 1,
                       "antialias threshold must be between 0 and 1, got -1");
}

/* ---- the random numbers -------------------------------------------------------------------------- */

Test(sample_hash, depends_only_on_its_four_inputs) {
    cr_expect_eq(sample_hash(3, 4, 5, 6), sample_hash(3, 4, 5, 6));
    uint64_t base = sample_hash(3, 4, 5, 6);
    cr_expect_neq(base, sample_hash(4, 4, 5, 6));
    cr_expect_neq(base, sample_hash(3, 5, 5, 6));
    cr_expect_neq(base, sample_hash(3, 4, 6, 6));
    cr_expect_neq(base, sample_hash(3, 4, 5, 7));
    cr_expect_neq(sample_hash(1, 2, 0, 0), sample_hash(2, 1, 0, 0), "x and y are not interchangeable");
}

Test(sample_hash, each_input_bit_flips_about_half_the_output_bits) {
    /* Over many inputs and each of the 128 input bits: the average number of output bits that change. */
    for (int input = 0; input < 4; input++)
        for (int bit = 0; bit < 32; bit++) {
            double flipped = 0;
            for (uint32_t k = 0; k < 200; k++) {
                uint32_t v[4] = {k * 7919u, k * 104729u + 1, k, k * 31u + 5};
                uint64_t before = sample_hash(v[0], v[1], v[2], v[3]);
                v[input] ^= 1u << bit;
                flipped += __builtin_popcountll(before ^ sample_hash(v[0], v[1], v[2], v[3]));
            }
            flipped /= 200;
            cr_assert(flipped > 28 && flipped < 36, "input %d, bit %d flips %.1f of 64 output bits on average", input,
                      bit, flipped);
        }
}

Test(sample_hash, numbers_are_uniform_and_neighbours_unrelated) {
    enum { BINS = 16, SIDE = 256 };
    long count[BINS] = {0};
    double sum = 0, product = 0, squares = 0;
    for (uint32_t y = 0; y < SIDE; y++)
        for (uint32_t x = 0; x < SIDE; x++) {
            double u = sample_hash_unit(x, y, 0, 1), right = sample_hash_unit(x + 1, y, 0, 1);
            cr_assert(u >= 0.0 && u < 1.0);
            count[(int)(u * BINS)]++;
            sum += u;
            squares += (u - 0.5) * (u - 0.5);
            product += (u - 0.5) * (right - 0.5);
        }
    double n = SIDE * SIDE, expected = n / BINS, chi2 = 0;
    for (int b = 0; b < BINS; b++)
        chi2 += (count[b] - expected) * (count[b] - expected) / expected;
    cr_expect_lt(chi2, 37.7, "chi-square %.1f over %d bins (37.7: 1 in 1000 for a uniform source)", chi2, BINS);
    cr_expect_lt(fabs(sum / n - 0.5), 0.005, "mean %.4f", sum / n);
    cr_expect_lt(fabs(product / squares), 0.02, "correlation of horizontal neighbours %.4f", product / squares);
}

/* ---- the methods on pictures with a known answer ------------------------------------------------- */

/* A picture that is white left of x = edge and black from there on, and records where it was looked at. */
struct edge_view {
    double edge;
    int looks;
    double x[64], y[64];
};

static vec3 edge_colour(const void *context, double x, double y) {
    struct edge_view *v = (struct edge_view *)context;
    if (v->looks < 64) {
        v->x[v->looks] = x;
        v->y[v->looks] = y;
    }
    v->looks++;
    return x < v->edge ? vec3_make(1, 1, 1) : vec3_make(0, 0, 0);
}

Test(supersample, the_grid_is_the_mean_of_the_cell_centres) {
    struct edge_view e = {.edge = 7.3};
    struct sample_view view = {edge_colour, &e};
    vec3 c = supersample_grid(&view, 7, 2, 10);
    cr_expect_eq(e.looks, 100);
    cr_expect_float_eq(c.x, 0.3, 1e-12, "an edge 0.3 across the pixel covers 3 columns of 10: got %g", c.x);
    cr_expect_float_eq(e.x[0], 7.05, 1e-12);
    cr_expect_float_eq(e.y[0], 2.05, 1e-12);
    cr_expect_float_eq(e.x[11], 7.15, 1e-12, "sample 11 is column 1 of row 1");
    cr_expect_float_eq(e.y[11], 2.15, 1e-12);
    e.looks = 0;
    c = supersample_grid(&view, 7, 2, 1);
    cr_expect(e.looks == 1 && e.x[0] == 7.5 && e.y[0] == 2.5, "n = 1 is the centre");
    cr_expect_eq(c.x, 0.0);
}

Test(supersample, differ_is_povrays_rule_on_gamma_encoded_channels) {
    cr_expect(supersample_differ(vec3_make(0, 0, 0), vec3_make(1, 0, 0), 0.3));
    cr_expect(!supersample_differ(vec3_make(0.5, 0.5, 0.5), vec3_make(0.5, 0.5, 0.5), 0.01));
    cr_expect(supersample_differ(vec3_make(0.5, 0.5, 0.5), vec3_make(0.5, 0.5, 0.5), 0.0), "at least the threshold");
    /* 0.01 is 0.01^(1/2.5) = 0.1585 encoded: a dark step counts 16 times its linear size. */
    double encoded = pow(0.01, 0.4);
    cr_expect(supersample_differ(vec3_make(0.01, 0, 0), vec3_make(0, 0, 0), encoded - 1e-9));
    cr_expect(!supersample_differ(vec3_make(0.01, 0, 0), vec3_make(0, 0, 0), encoded + 1e-9));
    /* The channels add up; a negative channel counts as 0. */
    double three = 3 * (pow(0.2, 0.4) - pow(0.1, 0.4));
    cr_expect(supersample_differ(vec3_make(0.2, 0.2, 0.2), vec3_make(0.1, 0.1, 0.1), three - 1e-9));
    cr_expect(!supersample_differ(vec3_make(0.2, 0.2, 0.2), vec3_make(0.1, 0.1, 0.1), three + 1e-9));
    cr_expect(!supersample_differ(vec3_make(-5, 0, 0), vec3_make(0, 0, 0), 1e-12));
}

/* Samples a block of a picture through `view` with the given settings. */
static void sample(enum antialias_method method, int n, const struct sample_view *view, int left, int top, int right,
                   int bottom, vec3 *colours, int *rays, uint64_t *total) {
    struct antialias a = {method, n, 0.3, 7, 1};
    *total = supersample_block(&a, view, left, top, right, bottom, colours, rays);
}

/* A picture of one colour everywhere. */
static vec3 flat_colour(const void *context, double x, double y) {
    (void)x, (void)y;
    return *(const vec3 *)context;
}

static bool same_colour(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/* n x n equal colours average to that colour, to the last bit, on the grid and with jitter: a colour on
 * a half level (0.3 is 76.5 of 255) is otherwise written a level lower than its single ray (a sum of
 * nine 0.3s times a ninth is 0.29999999999999993). */
Test(supersample, equal_samples_average_to_their_colour_to_the_last_bit) {
    double values[10 + 256];
    int count = 0;
    for (int k = 1; k <= 9; k++)
        values[count++] = k / 10.0;
    values[count++] = 1.0 / 3.0;
    for (int k = 0; k < 256; k++)
        values[count++] = k / 255.0;
    for (int v = 0; v < count; v++)
        for (int n = 1; n <= 8; n++) {
            vec3 flat = vec3_make(values[v], 1.0 - values[v], 0.5 * values[v]);
            struct sample_view view = {flat_colour, &flat};
            vec3 grid = supersample_grid(&view, 3, 4, n), jitter;
            int rays;
            uint64_t total;
            sample(ANTIALIAS_JITTER, n, &view, 3, 4, 4, 5, &jitter, &rays, &total);
            cr_assert(same_colour(grid, flat), "%d x %d samples of (%.17g, %.17g, %.17g) on the grid average to "
                      "(%.17g, %.17g, %.17g)", n, n, flat.x, flat.y, flat.z, grid.x, grid.y, grid.z);
            cr_assert(same_colour(jitter, flat), "%d x %d jittered samples of (%.17g, %.17g, %.17g) average to "
                      "(%.17g, %.17g, %.17g)", n, n, flat.x, flat.y, flat.z, jitter.x, jitter.y, jitter.z);
        }
}

/* Chapter 12's grid over a background on a half level: every background pixel is the level of one ray
 * a pixel (77 128 179), as in POV-Ray's picture at three times the size, box-averaged. */
Test(antialias, a_grid_over_a_background_on_a_half_level_keeps_its_level, .timeout = 60) {
    const char *scene = TEST_OUT "/aa-half-level.scene";
    FILE *f = fopen(scene, "w");
    cr_assert(f != NULL);
    fputs("camera eye 0 0 5  target 0 0 0  fov 30\nimage 40 30\nbackground 0.3 0.5 0.7\nlight position 3 5 5\n"
          "material m colour 0.9 0.1 0.1\nsphere centre 0 0 0 radius 0.5 material m\n",
          f);
    cr_assert_eq(fclose(f), 0);
    cr_assert_eq(render_chapter(12, scene, TEST_OUT "/aa-half-level-1.png", "--set antialias.method=none"), 0);
    for (int n = 2; n <= 5; n++) {
        char png[256], options[64];
        snprintf(png, sizeof png, TEST_OUT "/aa-half-level-%d.png", n);
        snprintf(options, sizeof options, "--set antialias.method=grid --set antialias.samples=%d", n);
        cr_assert_eq(render_chapter(12, scene, png, options), 0);
        char err[512];
        int w, h;
        uint8_t *rgb = image_read_rgb(png, &w, &h, err, sizeof err);
        cr_assert(rgb != NULL, "%s", err);
        cr_expect(rgb[0] == 77 && rgb[1] == 128 && rgb[2] == 179, "grid %d: the corner's background is %d %d %d, "
                  "one ray's is 77 128 179", n, rgb[0], rgb[1], rgb[2]);
        free(rgb);
    }
}

Test(supersample, jitter_puts_one_sample_in_each_cell_and_repeats_itself) {
    struct edge_view e = {.edge = 100}, again = {.edge = 100};
    struct sample_view view = {edge_colour, &e}, view_again = {edge_colour, &again};
    vec3 colour;
    int rays;
    uint64_t total;
    sample(ANTIALIAS_JITTER, 4, &view, 5, 9, 6, 10, &colour, &rays, &total);
    sample(ANTIALIAS_JITTER, 4, &view_again, 5, 9, 6, 10, &colour, &rays, &total);
    cr_assert_eq(e.looks, 16);
    cr_expect_eq(rays, 16);
    bool moved = false;
    for (int k = 0; k < 16; k++) {
        int a = k % 4, b = k / 4;
        cr_expect(e.x[k] >= 5 + a / 4.0 && e.x[k] < 5 + (a + 1) / 4.0 && e.y[k] >= 9 + b / 4.0 &&
                      e.y[k] < 9 + (b + 1) / 4.0,
                  "sample %d at (%g, %g) is outside its cell", k, e.x[k], e.y[k]);
        cr_expect(e.x[k] == again.x[k] && e.y[k] == again.y[k], "sample %d moved between two runs", k);
        moved = moved || fabs(e.x[k] - (5 + (a + 0.5) / 4)) > 1e-3;
    }
    cr_expect(moved, "every sample sits at its cell's centre: no jitter");
}

/* The adaptive rule on a vertical edge at x = 10.3 across a 32 x 32 block: column 10's centre (10.5) is
 * black and differs from column 9's, so both are refined, and so is column 11, whose left neighbour is
 * now a refined grey. Column 10 takes its centre (black) and its 9 grid samples, 3 of them white: 3 / 10. */
Test(supersample, adaptive_refines_both_sides_of_an_edge_and_the_grey_it_makes) {
    struct edge_view e = {.edge = 10.3};
    struct sample_view view = {edge_colour, &e};
    static vec3 colours[32 * 32];
    static int rays[32 * 32];
    uint64_t total;
    sample(ANTIALIAS_ADAPTIVE, 3, &view, 0, 0, 32, 32, colours, rays, &total);
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++) {
            int want = x >= 9 && x <= 11 ? 10 : 1;
            cr_assert_eq(rays[y * 32 + x], want, "pixel (%d, %d) took %d rays, not %d", x, y, rays[y * 32 + x], want);
        }
    cr_expect_float_eq(colours[10].x, 0.3, 1e-12);
    cr_expect_eq(colours[9].x, 1.0);
    cr_expect_eq(colours[11].x, 0.0);
    cr_expect_eq(total, 32 * 32 + 3 * 32 * 9 + 32 + 32, "the row above and the column to the left: 64 more rays");
}

/* A picture white above y = edge and black below. */
static vec3 row_edge_colour(const void *context, double x, double y) {
    (void)x;
    return y < *(const double *)context ? vec3_make(1, 1, 1) : vec3_make(0, 0, 0);
}

/* POV-Ray renders blocks of 32 x 32 on their own: an edge between rows 15 and 16 refines both rows; an
 * edge between rows 31 and 32 (two blocks) refines only row 32, whose block traces row 31 again and
 * may not refine it. */
Test(supersample, adaptive_keeps_povrays_block_boundaries) {
    static vec3 colours[32 * 32];
    static int rays[32 * 32];
    uint64_t total;
    double inside = 16.0, between = 32.0;
    struct sample_view view = {row_edge_colour, &inside};
    sample(ANTIALIAS_ADAPTIVE, 2, &view, 0, 0, 32, 32, colours, rays, &total);
    for (int y = 0; y < 32; y++)
        cr_expect_eq(rays[y * 32 + 5], y == 15 || y == 16 ? 5 : 1, "row %d, edge inside the block", y);
    view.context = &between;
    sample(ANTIALIAS_ADAPTIVE, 2, &view, 0, 0, 32, 32, colours, rays, &total);
    for (int y = 0; y < 32; y++)
        cr_expect_eq(rays[y * 32 + 5], 1, "row %d of the upper block, edge below it", y);
    sample(ANTIALIAS_ADAPTIVE, 2, &view, 0, 32, 32, 64, colours, rays, &total);
    for (int y = 0; y < 32; y++)
        cr_expect_eq(rays[y * 32 + 5], y == 0 ? 5 : 1, "row %d of the lower block", 32 + y);
}

Test(supersample, recursive_quarters_only_where_corners_differ) {
    static vec3 colours[32 * 32];
    static int rays[32 * 32];
    uint64_t total;
    double far = 1000;
    struct sample_view view = {row_edge_colour, &far};
    sample(ANTIALIAS_RECURSIVE, 3, &view, 0, 0, 8, 4, colours, rays, &total);
    cr_expect_eq(total, 9 * 5, "a plain picture takes the corners only");
    for (int k = 0; k < 32; k++)
        cr_expect_eq(rays[k], 1, "pixel %d: its top-left corner", k);
    /* A vertical edge at x = 3.3 crosses column 3. Its corners differ, so it takes the middles of its
     * sides and its centre (5 rays); of its quarters, the two on the left (x 3 .. 3.5) hold the edge and
     * are quartered again, 5 rays for the upper and 4 for the lower, which shares the upper's bottom
     * middle. With its top-left corner: 15. */
    struct edge_view e = {.edge = 3.3};
    view = (struct sample_view){edge_colour, &e};
    sample(ANTIALIAS_RECURSIVE, 3, &view, 0, 0, 8, 4, colours, rays, &total);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 8; x++) {
            int want = x == 3 ? 1 + 5 + 5 + 4 : 1;
            cr_expect_eq(rays[y * 8 + x], want, "pixel (%d, %d) took %d rays, not %d", x, y, rays[y * 8 + x], want);
        }
    /* Its colour: a left quarter's left half (x 3 .. 3.25) is white, its right half (3.25 .. 3.5) has
     * one white and one black side, 0.5: the quarter is 0.75, the right quarters 0, the pixel 0.375
     * where the edge covers 0.3. */
    cr_expect_eq(colours[3].x, 0.375, "got %.17g", colours[3].x);
}

/* ---- whole pictures -------------------------------------------------------------------------------- */

static const char *const methods[] = {"none", "grid", "jitter", "adaptive", "recursive"};

/* At half the scene's width and height: the rows two threads share out are as many as the pixels' rows. */
Test(antialias, the_picture_is_the_same_for_1_and_2_threads_by_every_method, .timeout = 300) {
    for (int m = 0; m < 5; m++) {
        char one[256], two[256], extra[128];
        snprintf(one, sizeof one, TEST_OUT "/aa-%s-1.png", methods[m]);
        snprintf(two, sizeof two, TEST_OUT "/aa-%s-2.png", methods[m]);
        snprintf(extra, sizeof extra, "--width 160 --height 120 --set antialias.method=%s --threads 1", methods[m]);
        cr_assert_eq(render_chapter(12, chapter_scene(12), one, extra), 0);
        snprintf(extra, sizeof extra, "--width 160 --height 120 --set antialias.method=%s --threads 2", methods[m]);
        cr_assert_eq(render_chapter(12, chapter_scene(12), two, extra), 0);
        struct image_difference d = compare_png(one, two);
        cr_expect_eq(d.max, 0, "method %s: 1 and 2 threads differ by up to %d levels", methods[m], d.max);
    }
}

Test(antialias, one_ray_a_pixel_is_chapter_11s_picture, .timeout = 120) {
    const char *eleven = TEST_OUT "/aa-by-11.png", *none = TEST_OUT "/aa-by-12-none.png";
    cr_assert_eq(render_chapter(11, chapter_scene(12), eleven, "--width 160 --height 120"), 0);
    cr_assert_eq(render_chapter(12, chapter_scene(12), none, "--width 160 --height 120 --set antialias.method=none"), 0);
    struct image_difference d = compare_png(eleven, none);
    cr_expect_eq(d.max, 0, "method none differs from chapter 11 by up to %d levels", d.max);
    cr_expect_eq(render_chapter(12, chapter_scene(8), none, "--width 200 --height 150"), 0);
    cr_assert_eq(render_chapter(8, chapter_scene(8), eleven, "--width 200 --height 150"), 0);
    d = compare_png(eleven, none);
    cr_expect_eq(d.max, 0, "chapter 12 on chapter 8's scene (no antialias line) differs by %d levels", d.max);
}

/* The mean signed and the mean absolute difference of two pictures of the same size, in levels. */
static void signed_difference(const char *a_path, const char *b_path, double *bias, double *mean) {
    char err[256];
    int wa, ha, wb, hb;
    uint8_t *a = image_read_rgb(a_path, &wa, &ha, err, sizeof err);
    uint8_t *b = image_read_rgb(b_path, &wb, &hb, err, sizeof err);
    cr_assert(a != NULL && b != NULL && wa == wb && ha == hb, "%s", err);
    double sum = 0, absolute = 0;
    for (long k = 0; k < 3L * wa * ha; k++) {
        sum += (double)a[k] - b[k];
        absolute += abs(a[k] - b[k]);
    }
    *bias = sum / (3.0 * wa * ha);
    *mean = absolute / (3.0 * wa * ha);
    free(a);
    free(b);
}

/* Jitter turns aliasing into noise. Against a jittered 16 x 16 (another seed: as near the true mean
 * over each pixel as a test can afford, and off it by noise alone), the 4 x 4 grid is off the same way
 * wherever the floor's lines repeat, a bias; the jittered 4 x 4 is off both ways, by less, and
 * unbiased. (A 16 x 16 grid would not do as the reference: at this size it is biased itself, by 0.1
 * level.) Jittered rays are not POV-Ray's (its jitter comes from a table of its own), so this is their
 * check; the grid is POV-Ray's. */
Test(antialias, jitter_is_unbiased_where_the_grid_aliases, .timeout = 300) {
    const char *size = "--width 160 --height 120 --set antialias.method";
    char extra[128];
    snprintf(extra, sizeof extra, "%s=jitter --set antialias.samples=16 --set antialias.seed=99", size);
    cr_assert_eq(render_chapter(12, chapter_scene(12), TEST_OUT "/aa-jitter-16.png", extra), 0);
    snprintf(extra, sizeof extra, "%s=grid --set antialias.samples=4", size);
    cr_assert_eq(render_chapter(12, chapter_scene(12), TEST_OUT "/aa-grid-4.png", extra), 0);
    snprintf(extra, sizeof extra, "%s=jitter --set antialias.samples=4 --set antialias.seed=1", size);
    cr_assert_eq(render_chapter(12, chapter_scene(12), TEST_OUT "/aa-jitter-4.png", extra), 0);
    double grid_bias, grid_mean, jitter_bias, jitter_mean;
    signed_difference(TEST_OUT "/aa-grid-4.png", TEST_OUT "/aa-jitter-16.png", &grid_bias, &grid_mean);
    signed_difference(TEST_OUT "/aa-jitter-4.png", TEST_OUT "/aa-jitter-16.png", &jitter_bias, &jitter_mean);
    fprintf(stderr, "against jittered 16 x 16: grid 4 x 4 bias %.3f, mean %.3f; jitter 4 x 4 bias %.3f, mean %.3f\n",
            grid_bias, grid_mean, jitter_bias, jitter_mean);
    cr_expect_lt(fabs(jitter_bias), 0.05, "the jittered picture is %.3f levels brighter on average", jitter_bias);
    cr_expect_gt(fabs(grid_bias), 2 * fabs(jitter_bias), "the grid's bias %.3f is no larger than jitter's %.3f",
                 grid_bias, jitter_bias);
    cr_expect_lt(jitter_mean, grid_mean, "jitter's mean error %.3f is not below the grid's %.3f", jitter_mean,
                 grid_mean);
}

Test(antialias, counters_and_heatmap_show_the_camera_rays_per_pixel, .timeout = 120) {
    expect_chapter_run(12, "--set antialias.method=grid --set antialias.samples=2 -o " TEST_OUT "/aa-count.png", 0,
                       "  camera rays                 4.00\n  most camera rays               4\n");
    expect_chapter_run(12, "-o " TEST_OUT "/aa-count.png", 0, "  most camera rays              10\n");
    expect_chapter_run(12, "--set antialias.method=grid --set antialias.samples=2 -o " TEST_OUT "/aa-count.png "
                       "--heatmap " TEST_OUT "/aa-heat.png", 0, "heat-map: " TEST_OUT "/aa-heat.png");
    char err[256];
    int w, h;
    uint8_t *heat = image_read_rgb(TEST_OUT "/aa-heat.png", &w, &h, err, sizeof err);
    cr_assert_not_null(heat, "%s", err);
    vec3 four = heatmap_colour_on(&supersample_ray_scale, 4);
    uint8_t want[3] = {image_quantize(four.x), image_quantize(four.y), image_quantize(four.z)};
    for (int k = 0; k < 320 * 240; k += 97)
        cr_assert(memcmp(heat + 3 * k, want, 3) == 0, "pixel %d of the heat-map is not the colour of 4 rays", k);
    free(heat);
    /* Chapters 1 to 11 print no camera-ray lines: every pixel has one. */
    char output[4096];
    char command[256];
    snprintf(command, sizeof command, "%s -o " TEST_OUT "/aa-11-count.png", chapter_program(11));
    run_capturing(command, output, sizeof output);
    cr_expect_null(strstr(output, "camera rays"), "%s", output);
}

Test(antialias, the_committed_plots_are_what_their_csv_file_draws, .timeout = 120) {
    const char *build = getenv("WHITTED_BUILD");
    char command[256];
    snprintf(command, sizeof command, "tools/antialias-docs.sh %s --check", build != NULL ? build : "build");
    cr_expect_eq(run_logged(command, TEST_OUT "/aa-plots.log"), 0,
                 "docs/results/antialias-*.svg are stale against docs/results/antialias.csv: see " TEST_OUT
                 "/aa-plots.log");
}

/* ---- agreement with POV-Ray ----------------------------------------------------------------------- */

/* Renders chapter 12 on its scene with the antialias line replaced by `line`, and its twin with POV-Ray
 * as the twin says; returns their difference. */
static struct image_difference against_povray(const char *tag, const char *line) {
    char name[128];
    snprintf(name, sizeof name, "aa-%s", tag);
    return variant_against_povray(12, "antialias method adaptive samples 3 threshold 0.3", line, name, 1);
}

/* The agreement the chapter promises: 99.99 % of pixels within one level; at half the scene's width and
 * height (the scene itself is compared at full size). */
static void expect_agreement(const char *tag, const char *line) {
    char name[128];
    snprintf(name, sizeof name, "aa-%s", tag);
    expect_variant_agrees_with_povray(12, "antialias method adaptive samples 3 threshold 0.3", line, name, 2);
}

Test(povray_agreement, chapter_12_grid_is_povray_at_3_times_the_size_averaged, .timeout = 300) {
    expect_agreement("grid-3", "antialias method grid samples 3");
}

Test(povray_agreement, chapter_12_grid_of_2_and_of_4, .timeout = 300) {
    expect_agreement("grid-2", "antialias method grid samples 2");
    expect_agreement("grid-4", "antialias method grid samples 4");
}

Test(povray_agreement, chapter_12_adaptive_with_other_settings, .timeout = 300) {
    expect_agreement("adaptive-2", "antialias method adaptive samples 2 threshold 0.1");
    expect_agreement("adaptive-4", "antialias method adaptive samples 4 threshold 0.6");
}

Test(povray_agreement, chapter_12_recursive_is_povrays_method_2, .timeout = 300) {
    expect_agreement("recursive-3", "antialias method recursive samples 3 threshold 0.3");
    expect_agreement("recursive-2", "antialias method recursive samples 2 threshold 0.1");
}

/* Renders chapter 12's scene with the antialias line `line` to TEST_OUT/aa-TAG.png. */
static void render_with_line(const char *tag, const char *line) {
    const char *olds[] = {"antialias method adaptive samples 3 threshold 0.3"}, *news[] = {line};
    char variant[256], png[256];
    snprintf(variant, sizeof variant, "scenes/12-antialias.scene.%s.variant", tag);
    snprintf(png, sizeof png, TEST_OUT "/aa-%s.png", tag);
    write_scene_variant(chapter_scene(12), variant, olds, news, 1, NULL);
    int status = render_chapter(12, variant, png, "");
    remove(variant);
    cr_assert_eq(status, 0, "chapter 12 failed on '%s'", line);
}

/* The checks can fail: a 3 x 3 grid against POV-Ray's 2 x 2, and a threshold of 0.2 against 0.3. */
Test(povray_agreement, chapter_12_checks_catch_a_wrong_grid_and_a_wrong_threshold, .timeout = 300) {
    cr_assert(render_povray(12, chapter_scene(12), TEST_OUT "/aa-default-povray.png"));
    render_with_line("t02", "antialias method adaptive samples 3 threshold 0.2");
    struct image_difference d = compare_png(TEST_OUT "/aa-t02.png", TEST_OUT "/aa-default-povray.png");
    report_difference("threshold 0.2 vs POV-Ray's 0.3", &d);
    cr_expect_lt(d.within_1, 0.9999, "a threshold of 0.2 against POV-Ray's 0.3 went unnoticed");
    struct image_difference two = against_povray("control-grid-2", "antialias method grid samples 2");
    (void)two;
    render_with_line("control-grid-3", "antialias method grid samples 3");
    d = compare_png(TEST_OUT "/aa-control-grid-3.png", TEST_OUT "/aa-control-grid-2-povray.png");
    report_difference("grid 3 vs POV-Ray's grid 2", &d);
    cr_expect_lt(d.within_1, 0.9999, "a 3 x 3 grid against POV-Ray's 2 x 2 went unnoticed");
}

/* ---- the measurements the pages quote ------------------------------------------------------------- */

/* One row of docs/results/antialias.csv (tools/antialias-docs.sh measure). */
struct measured_row {
    char method[16];
    int n;
    double threshold, rays, seconds, error, over_2;
};

/* Reads the CSV into rows (at most `most`); returns how many. */
static int read_measurements(struct measured_row *rows, int most) {
    FILE *f = fopen("docs/results/antialias.csv", "r");
    cr_assert_not_null(f, "cannot open docs/results/antialias.csv");
    char line[256];
    int count = 0;
    cr_assert_not_null(fgets(line, sizeof line, f), "the CSV has no header");
    while (count < most && fgets(line, sizeof line, f) != NULL) {
        struct measured_row *r = &rows[count];
        if (sscanf(line, "%15[^,],%d,%lf,%lf,%lf,%lf,%lf", r->method, &r->n, &r->threshold, &r->rays, &r->seconds,
                   &r->error, &r->over_2) == 7)
            count++;
    }
    fclose(f);
    return count;
}

static const struct measured_row *measured(const struct measured_row *rows, int count, const char *method, int n,
                                           double threshold) {
    for (int k = 0; k < count; k++)
        if (strcmp(rows[k].method, method) == 0 && rows[k].n == n && fabs(rows[k].threshold - threshold) < 1e-9)
            return &rows[k];
    cr_assert_fail("docs/results/antialias.csv has no row for %s %d at threshold %g", method, n, threshold);
    return NULL;
}

/* Reads a page with every run of blanks and line breaks made one space, so that a sentence is found
 * however it is wrapped. */
static char *read_page(const char *path) {
    char *text = read_text_file(path);
    cr_assert_not_null(text, "cannot read %s", path);
    size_t o = 0;
    for (size_t k = 0; text[k] != '\0'; k++) {
        bool blank = text[k] == ' ' || text[k] == '\n';
        if (!blank || (o > 0 && text[o - 1] != ' '))
            text[o++] = blank ? ' ' : text[k];
    }
    text[o] = '\0';
    return text;
}

static void expect_quoted(const char *page, const char *name, const char *wanted) {
    cr_expect_not_null(strstr(page, wanted), "%s does not say \"%s\", which docs/results/antialias.csv gives", name,
                       wanted);
}

Test(antialias, the_chapters_table_and_claims_are_the_measured_numbers) {
    struct measured_row rows[64];
    int count = read_measurements(rows, 64);
    char *chapter = read_page("docs/12-antialias.md"), *results = read_page("docs/results.md");
    static const struct {
        const char *label, *method;
        int n;
        double threshold;
    } table[] = {{"one ray (grid 1)", "grid", 1, 0.3},    {"grid", "grid", 2, 0.3},
                 {"grid", "grid", 4, 0.3},                {"grid", "grid", 8, 0.3},
                 {"jitter", "jitter", 4, 0.3},            {"jitter", "jitter", 8, 0.3},
                 {"adaptive, threshold 0.3", "adaptive", 3, 0.3}, {"adaptive, threshold 0.3", "adaptive", 8, 0.3},
                 {"adaptive, threshold 0.1", "adaptive", 8, 0.1}, {"recursive, threshold 0.3", "recursive", 3, 0.3},
                 {"recursive, threshold 0.3", "recursive", 6, 0.3}};
    char wanted[256];
    for (size_t k = 0; k < sizeof table / sizeof table[0]; k++) {
        const struct measured_row *r = measured(rows, count, table[k].method, table[k].n, table[k].threshold);
        snprintf(wanted, sizeof wanted, "| %s | %d | %.2f | %.2f s | %.2f | %.1f %% |", table[k].label, r->n, r->rays,
                 r->seconds, r->error, r->over_2);
        expect_quoted(chapter, "docs/12-antialias.md's table", wanted);
    }
    const struct measured_row *adaptive = measured(rows, count, "adaptive", 3, 0.3),
                              *grid2 = measured(rows, count, "grid", 2, 0.3), *grid3 = measured(rows, count, "grid", 3, 0.3),
                              *grid4 = measured(rows, count, "grid", 4, 0.3), *grid8 = measured(rows, count, "grid", 8, 0.3),
                              *jitter4 = measured(rows, count, "jitter", 4, 0.3),
                              *jitter8 = measured(rows, count, "jitter", 8, 0.3);
    snprintf(wanted, sizeof wanted,
             "With %.2f rays a pixel its error is %.0f %% above a 3 × 3 grid's (%.2f against %.2f, for 9 rays) and "
             "well below a 2 × 2 grid's (%.2f, for 4 rays)",
             adaptive->rays, 100 * (adaptive->error / grid3->error - 1), adaptive->error, grid3->error, grid2->error);
    expect_quoted(chapter, "docs/12-antialias.md", wanted);
    cr_expect_gt(grid2->error, adaptive->error);
    snprintf(wanted, sizeof wanted, "from n = 4 to 8 the grid's error falls from %.2f to %.2f, jitter's from %.2f to %.2f",
             grid4->error, grid8->error, jitter4->error, jitter8->error);
    expect_quoted(chapter, "docs/12-antialias.md", wanted);
    snprintf(wanted, sizeof wanted, "the grid's from %.2f to %.2f levels, jitter's from %.2f to %.2f", grid4->error,
             grid8->error, jitter4->error, jitter8->error);
    expect_quoted(results, "docs/results.md", wanted);
    cr_expect_gt(grid4->error / grid8->error, 2.0, "the grid's error falls rather than stalls");
    cr_expect_gt(jitter4->error / jitter8->error, grid4->error / grid8->error, "jitter's falls faster");
    /* the one measured time of the chapter's picture, quoted by the chapter and by the results page */
    snprintf(wanted, sizeof wanted, "This picture's measured time is the table's above: %.2f s", adaptive->seconds);
    expect_quoted(chapter, "docs/12-antialias.md's Run it", wanted);
    snprintf(wanted, sizeof wanted, "chapter 12's scene, 551,955 rays in %.2f s", adaptive->seconds);
    expect_quoted(results, "docs/results.md", wanted);
    free(chapter);
    free(results);
}

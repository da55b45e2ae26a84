/* test_results.c: make results, the seed's experiments redone (docs/results.md). The committed plots
 * and tables are what their committed CSVs draw (and a changed number makes them stale), and the quick
 * mode runs every experiment end to end on small inputs: CSVs with the right columns and rows, counts
 * that say what the structures are for, plots and a page with every table filled in. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_support.h"

#define COMMAND_MAX 4096
#define OUTPUT_MAX (1 << 16)
#define QUICK_DIR "out/test/results-quick"
#define SWEEP_HEADER                                                                                           \
    "scene,width,height,lights,depth,structure,runs,cpu_best_s,cpu_median_s,build_ms,render_s,rays,"           \
    "triangle_tests,peak_rss_mb,measured_width,measured_height,scale,povray_max_diff,povray_pixels_over_2"

/* The number of lines of a text. */
static size_t count_lines(const char *text) {
    size_t n = 0;
    for (const char *p = text; *p != '\0'; p++)
        n += *p == '\n';
    return n;
}

/* The first line of a file equals `header` and the file has `rows` lines after it; returns the text. */
static char *expect_csv(const char *name, const char *header, size_t rows) {
    char path[256];
    snprintf(path, sizeof path, QUICK_DIR "/%s", name);
    char *text = read_text_file(path);
    cr_assert_not_null(text, "%s was not written", path);
    cr_assert_eq(strncmp(text, header, strlen(header)), 0, "%s: header is not %s", path, header);
    cr_assert_eq(text[strlen(header)], '\n', "%s: header has more columns than %s", path, header);
    cr_assert_eq(count_lines(text), rows + 1, "%s: %zu rows, expected %zu", path, count_lines(text) - 1, rows);
    return text;
}

/* Field `column` (0-based) of the row of `csv` whose fields 0..4 start with `row_start` and whose
 * field 5 (the structure) is `structure`, as a number; fails when there is no such row. */
static double sweep_field(const char *csv, const char *row_start, const char *structure, int column) {
    char start[256];
    snprintf(start, sizeof start, "\n%s,%s,", row_start, structure);
    const char *row = strstr(csv, start);
    cr_assert_not_null(row, "no row %s,%s", row_start, structure);
    row++;
    for (int k = 0; k < column; k++) {
        row = strchr(row, ',');
        cr_assert_not_null(row);
        row++;
    }
    return atof(row);
}

Test(results, the_committed_plots_and_tables_are_what_their_csv_files_draw, .timeout = 120) {
    /* The plots in docs/results/ and the tables of docs/results.md, redrawn from the CSV files there. */
    char output[OUTPUT_MAX];
    int status = run_capturing("tools/results/publish.sh --check 2>&1", output, sizeof output);
    cr_assert_eq(status, 0, "a committed plot or table is stale:\n%s", output);
}

Test(results, a_changed_number_in_a_csv_makes_its_plot_and_table_stale, .timeout = 120) {
    /* The check can fail: a copy of the data with one brute-force time doubled. */
    char command[COMMAND_MAX];
    snprintf(command, sizeof command,
             "rm -rf out/test/results-stale && mkdir -p out/test/results-stale && cp docs/results/* docs/results.md "
             "out/test/results-stale/ && awk -F, -v OFS=, 'NR > 1 && $6 == \"none\" && $5 == 3 { $8 = $8 * 2 } { print }' "
             "docs/results/bunny.csv >out/test/results-stale/bunny.csv");
    cr_assert_eq(system(command), 0);
    char output[OUTPUT_MAX];
    int status = run_capturing("tools/results/publish.sh --check out/test/results-stale out/test/results-stale "
                               "out/test/results-stale/results.md 2>&1",
                               output, sizeof output);
    cr_assert_eq(status, 1, "the check passed a changed CSV:\n%s", output);
    cr_assert_not_null(strstr(output, "out/test/results-stale/bunny-time.svg is stale"), "%s", output);
    cr_assert_not_null(strstr(output, "out/test/results-stale/results.md: a table or a number of the text is stale"), "%s", output);
    cr_assert_null(strstr(output, "scene1-depth.svg is stale"), "an unchanged plot was called stale:\n%s", output);
}

/* Copies the committed data and page into out/test/NAME/, runs the shell command `edit` there, then
 * publish.sh --check on the copy, which must fail; leaves its messages in `output`. */
static void check_fails_after(const char *name, const char *edit, char *output, size_t size) {
    char command[COMMAND_MAX];
    snprintf(command, sizeof command,
             "rm -rf out/test/%s && mkdir -p out/test/%s && cp docs/results/* docs/results.md out/test/%s/ && cd out/test/%s && %s",
             name, name, name, name, edit);
    cr_assert_eq(system(command), 0, "%s", command);
    snprintf(command, sizeof command, "tools/results/publish.sh --check out/test/%s out/test/%s out/test/%s/results.md 2>&1",
             name, name, name);
    cr_assert_neq(run_capturing(command, output, size), 0, "the check passed after %s:\n%s", edit, output);
}

Test(results, a_changed_number_in_a_csv_makes_the_numbers_of_the_text_stale, .timeout = 120) {
    /* The large model's brute-force time doubled: the sentences that quote what follows from it (the
     * factor over the seed's brute force, the time a triangle test takes) are named, with both values,
     * as tables.awk computes them from the committed large.csv (the seed's 6,930 s over ours; our time
     * over our triangle tests), so that a new make results does not need this test rewritten. */
    char *csv = read_text_file("docs/results/large.csv");
    cr_assert_not_null(csv);
    double brute_s = sweep_field(csv, "teapot-346k,800,600,1,1", "none", 7);
    double tests = sweep_field(csv, "teapot-346k,800,600,1,1", "none", 12);
    free(csv);
    cr_assert(brute_s > 0 && tests > 0);
    char output[OUTPUT_MAX];
    check_fails_after("results-prose", "awk -F, -v OFS=, '$6 == \"none\" { $8 = $8 * 2 } { print }' large.csv >x && mv x large.csv",
                      output, sizeof output);
    char expected[256];
    snprintf(expected, sizeof expected,
             "the number large-brute-over-seed in the text is stale: %.1f, where out/test/results-prose/*.csv give %.1f",
             6930 / brute_s, 6930 / (2 * brute_s));
    cr_assert_not_null(strstr(output, expected), "expected: %s\n%s", expected, output);
    snprintf(expected, sizeof expected,
             "the number large-ns-per-test in the text is stale: %.1f, where out/test/results-prose/*.csv give %.1f",
             1e9 * brute_s / tests, 1e9 * 2 * brute_s / tests);
    cr_assert_not_null(strstr(output, expected), "expected: %s\n%s", expected, output);
    cr_assert_null(strstr(output, "the number large-cull-factor"), "a number that did not change was named:\n%s", output);
}

Test(results, a_number_of_the_text_typed_over_or_unknown_is_caught, .timeout = 120) {
    /* The CSVs as committed: one number of a sentence typed over is named; a name tables.awk does not
     * compute is refused. */
    char *page = read_text_file("docs/results.md");
    cr_assert_not_null(page);
    const char *marker = strstr(page, "<!--n:large-cull-factor-->");
    cr_assert_not_null(marker);
    marker += strlen("<!--n:large-cull-factor-->");
    char committed[32];
    snprintf(committed, sizeof committed, "%.*s", (int)strcspn(marker, "<"), marker);
    free(page);
    cr_assert_str_neq(committed, "99.5", "the value typed over must differ from the committed one");
    char output[OUTPUT_MAX];
    check_fails_after("results-typed",
                      "sed -i 's|<!--n:large-cull-factor-->[^<]*<!--/n-->|<!--n:large-cull-factor-->99.5<!--/n-->|' results.md",
                      output, sizeof output);
    char expected[256];
    snprintf(expected, sizeof expected,
             "the number large-cull-factor in the text is stale: 99.5, where out/test/results-typed/*.csv give %s",
             committed);
    cr_assert_not_null(strstr(output, expected), "expected: %s\n%s", expected, output);
    check_fails_after("results-unknown", "printf 'A <!--n:no-such-number-->1<!--/n--> here.\\n' >>results.md", output,
                      sizeof output);
    cr_assert_not_null(strstr(output, "no number called no-such-number"), "%s", output);
}

Test(results, sampled_scaling_rows_scale_the_process_time_as_the_large_table_does) {
    /* A sampled brute-force row multiplies its processor time by the scale, as large.csv does, so the
     * whole process costs at least its render (before, scaling.csv left it unscaled: 1.5 s beside a
     * 6.0 s render). Columns: triangles,structure,runs,build_ms,render_s,cpu_best_s,...,scale. */
    char *csv = read_text_file("docs/results/scaling.csv");
    cr_assert_not_null(csv);
    int sampled = 0;
    char *line = strchr(csv, '\n'); /* after the header */
    while (line != NULL && line[1] != '\0') {
        line++;
        char *end = strchr(line, '\n');
        if (end != NULL)
            *end = '\0';
        char *field[16];
        int n = 0;
        for (char *f = line; n < 16; f++) {
            field[n++] = f;
            f = strchr(f, ',');
            if (f == NULL)
                break;
            *f = '\0';
        }
        cr_assert_eq(n, 12, "a row of %d fields: %s", n, line);
        if (atof(field[11]) > 1) {
            sampled++;
            cr_assert_geq(atof(field[5]), atof(field[4]), "%s triangles: process %s s, render %s s (scale %s)", field[0],
                          field[5], field[4], field[11]);
        }
        line = end;
    }
    cr_assert_gt(sampled, 0, "no sampled row in docs/results/scaling.csv");
    free(csv);
}

/* The brute force's triangle tests on the bunny scene at depth 1, at width x height. */
static double brute_force_tests(int width, int height) {
    const char *build = getenv("WHITTED_BUILD") != NULL ? getenv("WHITTED_BUILD") : "build";
    char command[COMMAND_MAX], output[OUTPUT_MAX];
    snprintf(command, sizeof command,
             "%s/chapter-10 scenes/results/seed-bunny.scene --threads 1 --accel none --set max_depth=1 --width %d "
             "--height %d -o out/test/results-sampling.png",
             build, width, height);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s failed:\n%s", command, output);
    const char *line = strstr(output, "\n  triangle tests ");
    cr_assert_not_null(line, "no triangle tests in:\n%s", output);
    return atof(line + strlen("\n  triangle tests "));
}

Test(results, a_coarser_grid_scaled_up_estimates_the_whole_frame, .timeout = 120) {
    /* What make results does where the brute force would take too long: the same picture on a grid
     * five times coarser each way, its counts multiplied by 25, against the whole frame. */
    double whole = brute_force_tests(200, 150), sampled = 25 * brute_force_tests(40, 30);
    cr_assert_gt(whole, 1e7, "the brute force did not run: %g triangle tests", whole);
    cr_assert_lt(fabs(sampled - whole), 0.03 * whole, "sampled %g against %g measured", sampled, whole);
}

Test(results, the_quick_mode_runs_every_experiment_and_draws_every_plot_and_table, .timeout = 900) {
    const char *build = getenv("WHITTED_BUILD") != NULL ? getenv("WHITTED_BUILD") : "build";
    char command[COMMAND_MAX];
    snprintf(command, sizeof command,
             "BUILD=%s TEAPOT=build/teapot tools/results/run.sh --quick " QUICK_DIR " && cp docs/results.md " QUICK_DIR "/results.md && "
             "tools/results/publish.sh " QUICK_DIR " " QUICK_DIR " " QUICK_DIR "/results.md",
             build);
    cr_assert_eq(run_logged(command, "out/test/results-quick.log"), 0, "see out/test/results-quick.log");

    /* Scene 1: 2 sizes x 2 light set-ups x 5 depths x 5 structures; the bunny and the teapot 5 x 5; the
     * large model 7 structures; the scaling 3 teapots x 5 structures. */
    char *scene1 = expect_csv("scene1.csv", SWEEP_HEADER, 100);
    char *bunny = expect_csv("bunny.csv", SWEEP_HEADER, 25);
    char *teapot = expect_csv("teapot-5k.csv", SWEEP_HEADER, 25);
    char *large = expect_csv("large.csv", SWEEP_HEADER, 7);
    char *scaling = expect_csv("scaling.csv",
                               "triangles,structure,runs,build_ms,render_s,cpu_best_s,peak_rss_mb,rays,triangle_tests,"
                               "measured_width,measured_height,scale",
                               15);
    /* The whole program against POV-Ray: one thread, then every core (one row on a one-core machine);
     * POV-Ray, which parses the model as text, takes longer than chapter 11 on both rows, and the ratio of
     * the quick run's one pair is its two times' quotient. */
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    char *whole = expect_csv("whole.csv",
                             "threads,pairs,width,height,ours_wall_median_s,povray_wall_median_s,ratio_median,"
                             "ratio_min,ratio_max,ours_cpu_median_s,povray_cpu_median_s,load_before,load_after",
                             cores > 1 ? 2 : 1);
    for (const char *row = strchr(whole, '\n'); row != NULL && row[1] != '\0'; row = strchr(row + 1, '\n')) {
        int threads, pairs;
        double ours, povray, ratio;
        cr_assert_eq(sscanf(row + 1, "%d,%d,100,75,%lf,%lf,%lf,", &threads, &pairs, &ours, &povray, &ratio), 5,
                     "whole.csv: a row that does not read: %.80s", row + 1);
        cr_assert(threads == 1 || threads == cores, "whole.csv: %d threads", threads);
        cr_assert(ours > 0 && povray > ours && fabs(ratio - povray / ours) < 1e-3 * ratio,
                  "whole.csv: ours %g s, POV-Ray %g s, ratio %g", ours, povray, ratio);
    }
    char *machine = read_text_file(QUICK_DIR "/machine.csv");
    cr_assert_not_null(machine);
    cr_assert_not_null(strstr(machine, "\nmode,quick\n"));

    /* What the structures are for: at every depth the BVH tests far fewer triangles than the brute force,
     * the brute force tests more as the depth grows (reflected rays), and POV-Ray's picture agrees. */
    const char *const models[] = {"bunny,100,75,1", "teapot-5k,100,75,1"};
    const char *const texts[] = {bunny, teapot};
    for (int m = 0; m < 2; m++) {
        for (int depth = 1; depth <= 5; depth++) {
            char row[64];
            snprintf(row, sizeof row, "%s,%d", models[m], depth);
            double brute = sweep_field(texts[m], row, "none", 12), bvh = sweep_field(texts[m], row, "bvh-sah", 12);
            cr_assert_gt(brute, 20 * bvh, "%s: brute force %g triangle tests, BVH %g", row, brute, bvh);
            cr_assert_leq(sweep_field(texts[m], row, "povray", 17), 8, "%s: POV-Ray's picture differs", row);
        }
        char first[64], last[64];
        snprintf(first, sizeof first, "%s,1", models[m]);
        snprintf(last, sizeof last, "%s,5", models[m]);
        cr_assert_gt(sweep_field(texts[m], last, "none", 11), sweep_field(texts[m], first, "none", 11),
                     "%s: no more rays at depth 5 than at depth 1", models[m]);
    }
    /* Scene 1 with two lights casts more shadow rays than with one. */
    cr_assert_gt(sweep_field(scene1, "scene1-two-lights,100,50,2,1", "none", 11),
                 sweep_field(scene1, "scene1,100,50,1,1", "none", 11));
    /* The large model's brute force is sampled and scaled up, and says so. */
    cr_assert_gt(sweep_field(large, "teapot-346k,100,75,1,1", "none", 16), 1);
    cr_assert_eq(sweep_field(large, "teapot-346k,100,75,1,1", "bvh-sah", 16), 1);
    /* The scaling rows: the kd-tree and the BVHs report a build time. */
    cr_assert_not_null(strstr(scaling, "\n16256,bvh-sah,1,"));

    const char *const pictures[] = {"scene1-depth-1", "scene1-depth-5", "scene1-two-lights", "bunny", "teapot-5k", "large"};
    for (size_t k = 0; k < sizeof pictures / sizeof pictures[0]; k++) {
        char path[256];
        snprintf(path, sizeof path, QUICK_DIR "/%s.png", pictures[k]);
        size_t size = 0;
        char *png = read_file(path, &size);
        cr_assert_not_null(png, "%s was not rendered", path);
        cr_assert(size > 8 && memcmp(png, "\x89PNG", 4) == 0, "%s is not a PNG file", path);
        free(png);
    }
    const char *const plots[] = {"scene1-depth", "scene1-growth", "bunny-time", "bunny-tests", "teapot-5k-time",
                                 "teapot-5k-tests", "large", "large-tests", "scaling-build", "scaling-frame", "scaling-memory"};
    for (size_t k = 0; k < sizeof plots / sizeof plots[0]; k++) {
        char path[256];
        snprintf(path, sizeof path, QUICK_DIR "/%s.svg", plots[k]);
        char *svg = read_text_file(path);
        cr_assert_not_null(svg, "%s was not drawn", path);
        cr_assert_not_null(strstr(svg, "</svg>"), "%s is not a whole SVG file", path);
        free(svg);
    }
    /* Every table of the page is filled in from the quick CSVs (the Embree benchmark is not run). */
    char *page = read_text_file(QUICK_DIR "/results.md");
    cr_assert_not_null(page);
    cr_assert_not_null(strstr(page, "| mode | quick |"), "the machine table was not rewritten");
    for (const char *at = strstr(page, "<!-- results:"); at != NULL; at = strstr(at + 1, "<!-- results:")) {
        const char *body = strstr(at, "-->\n\n");
        cr_assert_not_null(body);
        body += 5;
        cr_assert(body[0] == '|' || strncmp(body, "Brute force", 11) == 0 || strncmp(body, "(" QUICK_DIR "/accel.csv", 30) == 0,
                  "an empty table after %.40s", at);
    }
    free(scene1);
    free(bunny);
    free(teapot);
    free(large);
    free(scaling);
    free(whole);
    free(machine);
    free(page);
}

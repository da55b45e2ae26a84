/* test_bench_csv.c: bench_accel --csv FILE (the benchmark of chapters 9 to 11, bench/bench_accel.c)
 * writes one line per structure, with the header scripts expect, numbers that agree with the printed
 * table and with what the structures must do, and no file at all when FILE cannot be written. The
 * benchmark runs on the bunny at 80 x 60 pixels, once, without Embree, so each run takes well under a
 * second. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image_test_support.h"
#include "mesh.h"
#include "mesh_load.h"
#include "test_support.h"

#define BENCH_CSV_MODEL "scenes/models/bunny.ply"
#define BENCH_CSV_HEIGHT 60 /* rows of the small frame: few enough that the brute-force loop traces all */
#define BENCH_CSV_HEADER                                                                                  \
    "model,triangles,structure,build_ms,frame_ms,mrays_per_s,tri_per_ray,nodes_per_ray,tri_per_camera_ray," \
    "sah_cost,frame_over_embree,build_over_embree,frame_over_below,build_over_below,sampled_rows,"        \
    "pixels_differing"
#define BENCH_CSV_FIELDS 16
#define BENCH_CSV_STRUCTURES 15 /* without Embree */

/* The columns the tests read, by their place in the header. */
enum {
    FIELD_MODEL,
    FIELD_TRIANGLES,
    FIELD_STRUCTURE,
    FIELD_BUILD_MS,
    FIELD_TRI_PER_CAMERA_RAY = 8,
    FIELD_SAMPLED_ROWS = 14,
    FIELD_PIXELS_DIFFERING = 15,
};

static const char *const structures[BENCH_CSV_STRUCTURES] = {
    "naive", "kd-seed", "kd-sah", "bvh-median", "bvh-sah", "rung-2", "rung-3", "rung-4", "rung-5", "rung-6", "rung-7",
    "rung-8", "rung-9", "rung-10", "rung-11"};

/* The benchmark program of the build under test, e.g. "build/bench_accel". */
static const char *bench_program(void) {
    static char path[256];
    const char *build = getenv("WHITTED_BUILD");
    snprintf(path, sizeof path, "%s/bench_accel", build != NULL ? build : "build");
    return path;
}

/* Runs the benchmark on the bunny with --csv csv_path, its standard output into table_path; fails the
 * test unless it succeeds. */
static void run_bench(const char *csv_path, const char *table_path) {
    char command[1024];
    snprintf(command, sizeof command,
             "timeout 60 %s --repeats 1 --size 80x%d --csv %s " BENCH_CSV_MODEL " >%s 2>/dev/null", bench_program(),
             BENCH_CSV_HEIGHT, csv_path, table_path);
    remove(csv_path);
    cr_assert_eq(system(command), 0, "%s failed", command);
}

/* Splits text into lines in place (at most max); returns how many. */
static int split_lines(char *text, char **lines, int max) {
    int count = 0;
    for (char *line = strtok(text, "\n"); line != NULL && count < max; line = strtok(NULL, "\n"))
        lines[count++] = line;
    return count;
}

/* Splits one CSV line into its fields in place, empty ones included; returns how many (at most max). */
static int split_fields(char *line, char **fields, int max) {
    int count = 0;
    for (char *next = line; next != NULL && count < max;) {
        fields[count++] = next;
        next = strchr(next, ',');
        if (next != NULL)
            *next++ = '\0';
    }
    return count;
}

/* The bunny's real triangle count. */
static size_t model_triangles(void) {
    struct mesh m;
    char err[512];
    cr_assert(mesh_load(BENCH_CSV_MODEL, &m, err, sizeof err), "%s", err);
    size_t count = m.face_count;
    mesh_free(&m);
    return count;
}

Test(bench_csv, writes_the_header_and_one_line_per_structure_with_what_each_must_do, .timeout = 120) {
    run_bench(TEST_OUT "/bench-csv-lines.csv", TEST_OUT "/bench-csv-lines.txt");
    cr_assert(access(TEST_OUT "/bench-csv-lines.csv.tmp", F_OK) != 0, "the .tmp file was left behind");
    char *text = read_text_file(TEST_OUT "/bench-csv-lines.csv");
    char *lines[BENCH_CSV_STRUCTURES + 2];
    int count = split_lines(text, lines, BENCH_CSV_STRUCTURES + 2);
    cr_assert_eq(count, 1 + BENCH_CSV_STRUCTURES, "%d lines, expected the header and %d structures", count,
                 BENCH_CSV_STRUCTURES);
    cr_assert_str_eq(lines[0], BENCH_CSV_HEADER);

    size_t triangles = model_triangles();
    char triangles_text[32];
    snprintf(triangles_text, sizeof triangles_text, "%zu", triangles);
    char height_text[16];
    snprintf(height_text, sizeof height_text, "%d", BENCH_CSV_HEIGHT);
    double naive_tri_per_camera_ray = -1, bvh_sah_tri_per_camera_ray = -1;
    for (int k = 0; k < BENCH_CSV_STRUCTURES; k++) {
        char *fields[BENCH_CSV_FIELDS + 1];
        int n = split_fields(lines[1 + k], fields, BENCH_CSV_FIELDS + 1);
        cr_assert_eq(n, BENCH_CSV_FIELDS, "line %d has %d fields", k + 2, n);
        cr_assert_str_eq(fields[FIELD_MODEL], "bunny");
        cr_assert_str_eq(fields[FIELD_TRIANGLES], triangles_text);
        cr_assert_str_eq(fields[FIELD_STRUCTURE], structures[k]);
        bool naive = strcmp(structures[k], "naive") == 0, reference = strcmp(structures[k], "bvh-sah") == 0;
        /* The brute-force loop builds nothing; every other structure takes some time to build. */
        if (naive)
            cr_expect_str_empty(fields[FIELD_BUILD_MS]);
        else
            cr_expect_gt(strtod(fields[FIELD_BUILD_MS], NULL), 0.0, "%s: build_ms '%s'", structures[k],
                         fields[FIELD_BUILD_MS]);
        cr_expect_str_eq(fields[FIELD_SAMPLED_ROWS], naive ? height_text : "", "%s", structures[k]);
        /* Every structure finds exactly the brute-force answer; the reference has nothing to differ from. */
        cr_expect_str_eq(fields[FIELD_PIXELS_DIFFERING], reference ? "" : "0", "%s", structures[k]);
        if (naive)
            naive_tri_per_camera_ray = strtod(fields[FIELD_TRI_PER_CAMERA_RAY], NULL);
        if (reference)
            bvh_sah_tri_per_camera_ray = strtod(fields[FIELD_TRI_PER_CAMERA_RAY], NULL);
    }
    /* Brute force tests every triangle for every camera ray; the BVH tests a handful. */
    cr_expect_eq(naive_tri_per_camera_ray, (double)triangles, "naive: %g triangle tests per camera ray",
                 naive_tri_per_camera_ray);
    cr_expect_gt(bvh_sah_tri_per_camera_ray, 0.0);
    cr_expect_lt(bvh_sah_tri_per_camera_ray, naive_tri_per_camera_ray);
    free(text);
}

/* The table's first column is this wide, after two spaces (bench_accel.c's print_table). */
#define TABLE_LABEL_END 28
#define TABLE_NUMBERS 11

Test(bench_csv, holds_the_numbers_the_table_prints, .timeout = 120) {
    static const int decimals[TABLE_NUMBERS] = {1, 1, 2, 2, 2, 2, 1, 2, 2, 2, 2};
    run_bench(TEST_OUT "/bench-csv-table.csv", TEST_OUT "/bench-csv-table.txt");
    char *csv = read_text_file(TEST_OUT "/bench-csv-table.csv");
    char *table = read_text_file(TEST_OUT "/bench-csv-table.txt");
    char *csv_lines[BENCH_CSV_STRUCTURES + 2];
    cr_assert_eq(split_lines(csv, csv_lines, BENCH_CSV_STRUCTURES + 2), 1 + BENCH_CSV_STRUCTURES);
    char *table_lines[64];
    int table_count = split_lines(table, table_lines, 64);
    int first = 0;
    while (first < table_count && strncmp(table_lines[first], "  structure ", 12) != 0)
        first++;
    cr_assert_lt(first + BENCH_CSV_STRUCTURES, table_count, "no table in the output");
    for (int k = 0; k < BENCH_CSV_STRUCTURES; k++) {
        char *printed = table_lines[first + 1 + k];
        cr_assert_gt(strlen(printed), TABLE_LABEL_END, "%s", printed);
        char *fields[BENCH_CSV_FIELDS];
        cr_assert_eq(split_fields(csv_lines[1 + k], fields, BENCH_CSV_FIELDS), BENCH_CSV_FIELDS);
        char *words = printed + TABLE_LABEL_END;
        for (int c = 0; c < TABLE_NUMBERS; c++) {
            char *word = strtok(c == 0 ? words : NULL, " ");
            cr_assert_not_null(word, "%s: short row", fields[FIELD_STRUCTURE]);
            const char *value = fields[FIELD_BUILD_MS + c];
            char expected[64];
            if (value[0] == '\0')
                snprintf(expected, sizeof expected, "-");
            else
                snprintf(expected, sizeof expected, "%.*f", decimals[c], strtod(value, NULL));
            cr_expect_str_eq(word, expected, "%s, column %d: the CSV's %s prints as %s, the table says %s",
                             fields[FIELD_STRUCTURE], FIELD_BUILD_MS + c + 1, value, expected, word);
        }
        char *verdict = strtok(NULL, "");
        cr_assert_not_null(verdict);
        cr_expect_not_null(strstr(verdict, fields[FIELD_PIXELS_DIFFERING][0] == '\0' ? "(the reference)" : "all equal"),
                           "%s: '%s'", fields[FIELD_STRUCTURE], verdict);
    }
    free(csv);
    free(table);
}

Test(bench_csv, a_file_that_cannot_be_written_is_exit_status_3_before_any_work) {
    char command[512], output[1024];
    snprintf(command, sizeof command, "timeout 60 %s --csv " TEST_OUT "/no-such-folder/bench.csv " BENCH_CSV_MODEL,
             bench_program());
    int status = run_capturing(command, output, sizeof output);
    cr_expect_eq(status, 3, "exit status %d: %s", status, output);
    cr_expect_str_eq(output, "bench_accel: " TEST_OUT "/no-such-folder/bench.csv: No such file or directory\n");
}

Test(bench_csv, a_failing_model_leaves_no_file) {
    char command[512], output[1024];
    remove(TEST_OUT "/bench-csv-failed.csv");
    snprintf(command, sizeof command, "timeout 60 %s --csv " TEST_OUT "/bench-csv-failed.csv " TEST_OUT
             "/no-such-model.ply", bench_program());
    int status = run_capturing(command, output, sizeof output);
    cr_expect_eq(status, 1, "exit status %d: %s", status, output);
    cr_expect_not_null(strstr(output, "bench-csv-failed.csv: not written, since a model failed"), "%s", output);
    cr_expect(access(TEST_OUT "/bench-csv-failed.csv", F_OK) != 0, "the CSV of a failed run was written");
    cr_expect(access(TEST_OUT "/bench-csv-failed.csv.tmp", F_OK) != 0, "the .tmp file was left behind");
}

Test(bench_csv, a_bad_size_is_a_usage_error) {
    char command[512], output[1024];
    snprintf(command, sizeof command, "timeout 60 %s --size 80 " BENCH_CSV_MODEL, bench_program());
    int status = run_capturing(command, output, sizeof output);
    cr_expect_eq(status, 2, "exit status %d: %s", status, output);
    cr_expect_str_eq(output, "bench_accel: --size '80': expected WIDTHxHEIGHT, each from 1 to 16384, e.g. 800x600\n");
}

/* check_picture.c: the coursework's picture checks: a chapter's program renders its scene, and the
 * picture is compared with the reference; a difference is described and drawn (the coursework kit). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "image.h"
#include "image_compare.h"

extern char **environ;

/* The regression rule of the image tests: at most 1 pixel in 2000 more than 1 level off, and a mean
 * difference of at most 0.01 levels. Noise from rounding passes, a real change does not. */
#define PICTURE_MIN_WITHIN_1 0.9995
#define PICTURE_MAX_MEAN 0.01

/* A pixel "differs" when a channel is more than this many levels off. */
#define PICTURE_DIFFERS 2

/* The difference picture is amplified this many times, so that a few levels show. */
#define PICTURE_GAIN 16

/* Below this largest channel value (of 255) a picture counts as black. */
#define PICTURE_BLACK 3

/* A differing pixel is "isolated" when at most this many of its 8 neighbours differ too; a picture
 * whose differing pixels are mostly isolated is speckled. */
#define PICTURE_ISOLATED_NEIGHBOURS 2

/* Chapter 15's picture takes its program 256 paths for each of 256 x 256 pixels, half a minute: its check
 * renders the same scene at 128 x 128 pixels with 16 paths each, 64 times fewer paths, and compares it
 * with a reference of that size. The random numbers are keyed by pixel, sample and seed, so the smaller
 * picture is as exact a test: any change to what a path computes changes it. Chapter 17's the same, at its
 * own shape. The references are made by the reference programs with these options (tests/test_images.c
 * checks that they are current):
 *   ./build/chapter-15 --width 128 --height 128 --set paths.samples=16 -o reference_images/chapter-15-check.png
 *   ./build/chapter-17 --width 128 --height 85 --set paths.samples=16 -o reference_images/chapter-17-check.png */
#define PATHS_CHECK_OPTIONS_15 "--width", "128", "--height", "128", "--set", "paths.samples=16"
#define PATHS_CHECK_OPTIONS_17 "--width", "128", "--height", "85", "--set", "paths.samples=16"

/* Whether chapter n's picture check renders the smaller picture of a path tracer. */
static bool paths_chapter(int n) { return n == 15 || n == 17; }

static int level_difference(const uint8_t *a, const uint8_t *b) {
    int worst = 0;
    for (int c = 0; c < 3; c++)
        worst = abs(a[c] - b[c]) > worst ? abs(a[c] - b[c]) : worst;
    return worst;
}

/* Whether got is expected flipped left-right (flip_x) or upside down (flip_y), within 2 levels on
 * 99 % of pixels. */
static bool flipped(const uint8_t *expected, const uint8_t *got, int w, int h, bool flip_x, bool flip_y) {
    long same = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            int fi = flip_x ? w - 1 - i : i, fj = flip_y ? h - 1 - j : j;
            same += level_difference(&expected[3 * ((size_t)fj * w + fi)], &got[3 * ((size_t)j * w + i)]) <= 2;
        }
    return same >= 0.99 * w * h;
}

/* Describes how got differs from expected: where, how much, and the usual symptom when one fits. */
static void describe(const uint8_t *expected, const uint8_t *got, int w, int h, char *out, size_t size) {
    long differing = 0, isolated = 0, brighter = 0, darker = 0, darker_in_bright = 0;
    int x0 = w, y0 = h, x1 = -1, y1 = -1, worst = 0, got_max = 0;
    double sum_expected = 0, sum_got = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const uint8_t *e = &expected[3 * ((size_t)j * w + i)], *g = &got[3 * ((size_t)j * w + i)];
            int se = e[0] + e[1] + e[2], sg = g[0] + g[1] + g[2];
            sum_expected += se;
            sum_got += sg;
            for (int c = 0; c < 3; c++)
                got_max = g[c] > got_max ? g[c] : got_max;
            int d = level_difference(e, g);
            if (d <= PICTURE_DIFFERS)
                continue;
            differing++;
            worst = d > worst ? d : worst;
            x0 = i < x0 ? i : x0, x1 = i > x1 ? i : x1, y0 = j < y0 ? j : y0, y1 = j > y1 ? j : y1;
            brighter += sg > se;
            darker += sg < se;
            darker_in_bright += sg < se && e[0] > 200 && e[1] > 200 && e[2] > 200;
            int neighbours = 0;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++) {
                    int ni = i + di, nj = j + dj;
                    if ((di || dj) && ni >= 0 && nj >= 0 && ni < w && nj < h &&
                        level_difference(&expected[3 * ((size_t)nj * w + ni)], &got[3 * ((size_t)nj * w + ni)]) >
                            PICTURE_DIFFERS)
                        neighbours++;
                }
            isolated += neighbours <= PICTURE_ISOLATED_NEIGHBOURS;
        }
    int n = snprintf(out, size, "%ld of %d pixels differ by more than %d levels, in x %d..%d, y %d..%d (y down from "
                     "the top), by up to %d levels", differing, w * h, PICTURE_DIFFERS, x0, x1, y0, y1, worst);
    const char *symptom = NULL;
    double ratio = sum_expected > 0 ? sum_got / sum_expected : 1.0;
    if (got_max <= PICTURE_BLACK)
        symptom = "all black: no ray hits anything (or every colour is 0)";
    else if (flipped(expected, got, w, h, true, false))
        symptom = "mirrored left to right: the camera's x runs the wrong way";
    else if (flipped(expected, got, w, h, false, true))
        symptom = "upside down: the camera's y runs the wrong way (row 0 is the top)";
    else if (differing > 0.5 * w * h && ratio < 0.9 && darker > 0.9 * differing)
        symptom = "too dark everywhere";
    else if (differing > 0.5 * w * h && ratio > 1.1 && brighter > 0.9 * differing)
        symptom = "too bright everywhere";
    else if (differing > 50 && isolated > 0.5 * differing)
        symptom = "speckled surfaces: shadow acne? (a shadow ray meeting its own surface)";
    else if (darker_in_bright > 0.5 * differing)
        symptom = "missing highlights: the brightest spots are dimmer";
    else if (brighter > 0.9 * differing)
        symptom = "brighter where the reference is dark: missing shadows?";
    if (symptom != NULL && n > 0 && (size_t)n < size)
        snprintf(out + n, size - (size_t)n, "; it looks %s", symptom);
}

/* Runs ./BUILD/chapter-NN --quiet -o got_path (with chapter n's smaller picture's options when it is a
 * path tracer's) with its messages in log_path. Returns its wait status, or -1 when it could not be
 * started. */
static int render(const char *program, int n, const char *got_path, const char *log_path) {
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log_path, O_WRONLY | O_CREAT | O_TRUNC, 0666);
    posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
    char *const args[] = {(char *)program, "--quiet", "-o", (char *)got_path, NULL};
    char *const paths_15[] = {(char *)program, "--quiet", "-o", (char *)got_path, PATHS_CHECK_OPTIONS_15, NULL};
    char *const paths_17[] = {(char *)program, "--quiet", "-o", (char *)got_path, PATHS_CHECK_OPTIONS_17, NULL};
    pid_t pid;
    int started = posix_spawn(&pid, program, &files, NULL, n == 15 ? paths_15 : n == 17 ? paths_17 : args, environ);
    posix_spawn_file_actions_destroy(&files);
    int status;
    if (started != 0 || waitpid(pid, &status, 0) != pid)
        return -1;
    return status;
}

/* Renders chapter n with the student's program into out/check/ and compares it with its reference. */
static bool picture(int n, char *why, size_t why_size) {
    const char *build = getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build";
    char got_path[256], ref_path[256], panel_path[256], program[256], log_path[256], err[512];
    mkdir("out", 0777);
    mkdir("out/check", 0777);
    snprintf(got_path, sizeof got_path, "out/check/chapter-%02d-got.png", n);
    if (paths_chapter(n))
        snprintf(ref_path, sizeof ref_path, "reference_images/chapter-%02d-check.png", n);
    else
        snprintf(ref_path, sizeof ref_path, "reference_images/chapter-%02d.png", n);
    snprintf(panel_path, sizeof panel_path, "out/check/chapter-%02d-expected-got-difference.png", n);
    snprintf(program, sizeof program, "./%s/chapter-%02d", build, n);
    snprintf(log_path, sizeof log_path, "out/check/chapter-%02d.log", n);
    remove(got_path);
    check_calling(program, "its own scene%s (its messages go to %s)",
                  n == 15 ? " at 128 x 128 pixels, 16 paths each" : n == 17 ? " at 128 x 85 pixels, 16 paths each" : "",
                  log_path);
    int status = render(program, n, got_path, log_path);
    if (status == -1) {
        snprintf(why, why_size, "%s could not be started; is it built? make check-%d builds it", program, n);
        return false;
    }
    if (WIFSIGNALED(status)) {
        snprintf(why, why_size, "%s crashed (%s) rendering its own scene (its messages are in %s): run it yourself, "
                 "or build with the sanitizers (make SAN=1 check-%d), to see where", program,
                 strsignal(WTERMSIG(status)), log_path, n);
        return false;
    }
    if (WEXITSTATUS(status) != 0) {
        snprintf(why, why_size, "%s failed (exit status %d; its messages are in %s)", program, WEXITSTATUS(status),
                 log_path);
        return false;
    }
    int w, h, gw, gh;
    uint8_t *expected = image_read_rgb(ref_path, &w, &h, err, sizeof err);
    uint8_t *got = expected ? image_read_rgb(got_path, &gw, &gh, err, sizeof err) : NULL;
    if (expected == NULL || got == NULL || gw != w || gh != h) {
        snprintf(why, why_size, "cannot compare %s with %s: %s", got_path, ref_path,
                 got == NULL ? err : "the sizes differ");
        free(expected);
        free(got);
        return false;
    }
    struct image_difference d = image_compare(expected, got, w, h);
    bool passes = d.within_1 >= PICTURE_MIN_WITHIN_1 && d.mean <= PICTURE_MAX_MEAN;
    if (!passes) {
        uint8_t *panel = malloc((size_t)w * h * 9);
        uint8_t *difference = malloc((size_t)w * h * 3);
        if (panel != NULL && difference != NULL) {
            image_compare_difference(expected, got, w, h, PICTURE_GAIN, difference);
            for (int j = 0; j < h; j++) {
                uint8_t *row = panel + (size_t)j * w * 9;
                memcpy(row, expected + (size_t)j * w * 3, (size_t)w * 3);
                memcpy(row + (size_t)w * 3, got + (size_t)j * w * 3, (size_t)w * 3);
                memcpy(row + (size_t)w * 6, difference + (size_t)j * w * 3, (size_t)w * 3);
            }
            image_write_png_bytes(panel, 3 * w, h, panel_path, err, sizeof err);
        }
        free(panel);
        free(difference);
        char description[1024];
        describe(expected, got, w, h, description, sizeof description);
        snprintf(why, why_size, "chapter %d's picture differs from %s: %s. Expected, yours and the difference (x%d) "
                 "side by side: %s", n, ref_path, description, PICTURE_GAIN, panel_path);
    }
    free(expected);
    free(got);
    return passes;
}

CHECK(check_picture_1) { return picture(1, why, why_size); }
CHECK(check_picture_2) { return picture(2, why, why_size); }
CHECK(check_picture_3) { return picture(3, why, why_size); }
CHECK(check_picture_4) { return picture(4, why, why_size); }
CHECK(check_picture_5) { return picture(5, why, why_size); }
CHECK(check_picture_6) { return picture(6, why, why_size); }
CHECK(check_picture_7) { return picture(7, why, why_size); }
CHECK(check_picture_8) { return picture(8, why, why_size); }
CHECK(check_picture_9) { return picture(9, why, why_size); }
CHECK(check_picture_10) { return picture(10, why, why_size); }
CHECK(check_picture_11) { return picture(11, why, why_size); }
CHECK(check_picture_12) { return picture(12, why, why_size); }
CHECK(check_picture_13) { return picture(13, why, why_size); }
CHECK(check_picture_14) { return picture(14, why, why_size); }
CHECK(check_picture_15) { return picture(15, why, why_size); }
CHECK(check_picture_16) { return picture(16, why, why_size); }
CHECK(check_picture_17) { return picture(17, why, why_size); }

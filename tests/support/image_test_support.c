/* image_test_support.c: helpers for the image regression and POV-Ray agreement tests. */
#include "image_test_support.h"

#include <criterion/criterion.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "box_filter.h"
#include "image.h"
#include "povray.h"
#include "scene.h"
#include "test_support.h"

#define COMMAND_MAX 2048

static const char *const scene_names[] = {
    NULL, "01-camera", "02-sphere", "03-triangle", "04-plane", "05-aabb",
    "06-phong", "07-shadows", "08-recursion", "09-kdtree", "10-bvh", "11-fast", "12-antialias",
    "13-distributed", "14-textures", "15-paths", "16-instances", "17-rough",
};

const char *chapter_scene(int n) {
    static _Thread_local char path[256];
    snprintf(path, sizeof path, "scenes/%s.scene", scene_names[n]);
    return path;
}

const char *chapter_program(int n) {
    static _Thread_local char path[256];
    const char *build = getenv("WHITTED_BUILD");
    snprintf(path, sizeof path, "%s/chapter-%02d", build != NULL ? build : "build", n);
    return path;
}

/* Runs a shell command with its output sent to the shared log; returns its exit status or -1. */
static int run(const char *command) { return run_logged(command, TEST_OUT "/commands.log"); }

/* Prints the last lines of the log file `log` to stderr, to say why a command failed. */
static void print_log_tail(const char *log) {
    char command[COMMAND_MAX];
    snprintf(command, sizeof command, "tail -n 15 %s >&2", log);
    if (system(command) != 0)
        fprintf(stderr, "(could not read %s)\n", log);
}

int render_with(const char *program, const char *scene, const char *png, const char *extra) {
    char command[COMMAND_MAX];
    snprintf(command, sizeof command, "%s %s -o %s --quiet %s", program, scene, png, extra);
    return run(command);
}

/* A bound for a chapter run that must not hang: far above what any of them needs, sanitizers included. */
#define CHAPTER_RUN_TIMEOUT "timeout 300"

void expect_chapter_run(int n, const char *arguments, int status, const char *expected) {
    static char command[16384], output[16384];
    snprintf(command, sizeof command, CHAPTER_RUN_TIMEOUT " %s %s", chapter_program(n), arguments);
    int got = run_capturing(command, output, sizeof output);
    cr_assert_eq(got, status, "'%s' exited with %d, not %d:\n%s", command, got, status, output);
    cr_assert_not_null(strstr(output, expected), "'%s' did not say '%s':\n%s", command, expected, output);
}

int render_chapter(int n, const char *scene, const char *png, const char *extra) {
    return render_with(chapter_program(n), scene, png, extra);
}

/* Whether the file at `path` holds exactly the text `text`. */
static bool file_holds(const char *path, const char *text) {
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return false;
    char held[128];
    size_t length = fread(held, 1, sizeof held - 1, f);
    fclose(f);
    held[length] = '\0';
    return strcmp(held, text) == 0;
}

int render_own_scene(int n, char *png, size_t size) {
    snprintf(png, size, TEST_OUT "/chapter-%02d.png", n);
    const char *run_id = test_run_id();
    if (run_id == NULL) /* a run that named itself nothing shares nothing */
        return render_chapter(n, chapter_scene(n), png, "");
    char lock_path[256], mark_path[256];
    snprintf(lock_path, sizeof lock_path, "%s.lock", png);
    snprintf(mark_path, sizeof mark_path, "%s.run", png);
    int lock = open(lock_path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    cr_assert(lock >= 0 && flock(lock, LOCK_EX) == 0, "cannot lock %s", lock_path);
    int status = 0;
    if (!file_holds(mark_path, run_id) || access(png, F_OK) != 0) {
        remove(mark_path);
        status = render_chapter(n, chapter_scene(n), png, "");
        FILE *mark = status == 0 ? fopen(mark_path, "w") : NULL;
        if (mark != NULL) {
            fputs(run_id, mark);
            fclose(mark);
        }
    }
    close(lock); /* and with it the lock */
    return status;
}

const char *mutant_program(const char *name) {
    static _Thread_local char path[256];
    const char *build = getenv("WHITTED_BUILD");
    snprintf(path, sizeof path, "%s/mutant-%s", build != NULL ? build : "build", name);
    return path;
}

/* Copies the rest of the twin's line that starts with `label` (a comment, "// Antialias box: ", ...)
 * into out; "" when the twin has no such line. */
static void twin_line(const char *pov, const char *label, char *out, size_t size) {
    char *text = read_text_file(pov);
    char *at = strstr(text, label);
    out[0] = '\0';
    if (at != NULL)
        snprintf(out, size, "%.*s", (int)strcspn(at + strlen(label), "\n"), at + strlen(label));
    free(text);
}

bool render_povray(int n, const char *scene, const char *png) {
    char pov[512], command[COMMAND_MAX];
    snprintf(pov, sizeof pov, "%s.pov", png);
    snprintf(command, sizeof command, "%s %s --pov %s --quiet", chapter_program(n), scene, pov);
    if (run(command) != 0)
        return false;
    struct scene s;
    char err[512];
    if (!scene_load(scene, NULL, &s, err, sizeof err))
        return false;
    /* Chapter 12's twin says how it is rendered: with POV-Ray's anti-aliasing options, or one ray a
     * pixel at `box` times the size (in 16 bits), each box x box block averaged afterwards. */
    char options[512], box_line[64], big[600];
    twin_line(pov, "// Antialias options: ", options, sizeof options);
    twin_line(pov, "// Antialias box: ", box_line, sizeof box_line);
    int box = box_line[0] != '\0' ? atoi(box_line) : 1;
    snprintf(big, sizeof big, "%s%s", png, box > 1 ? ".big.png" : "");
    /* One thread: the oracle measured identical pixels for any thread count, and the test suite
     * already runs several tests at once. */
    snprintf(command, sizeof command, "povray +I%s +O%s +W%d +H%d +WT1 %s %s %s", pov, big, box * s.width,
             box * s.height, POVRAY_OPTIONS, box > 1 ? "+FN16" : "", options);
    scene_free(&s);
    /* POV-Ray is another program on a shared machine: a run that fails once (seen once in hundreds, its
     * output lost among the parallel tests' logs) is tried once more, and both runs' output is kept in
     * the twin's own log. The twin is the same file both times, so a real fault in it fails twice. */
    char log[512];
    snprintf(log, sizeof log, "%s.log", png);
    remove(log);
    int status = run_logged(command, log);
    if (status != 0) {
        fprintf(stderr, "POV-Ray exited with %d on %s; trying once more. Its output:\n", status, pov);
        print_log_tail(log);
        status = run_logged(command, log);
        if (status != 0)
            print_log_tail(log);
    }
    if (status != 0 || box == 1)
        return status == 0;
    int w, h;
    uint8_t *small = box_filter_png(big, box, &w, &h, err, sizeof err);
    bool written = small != NULL && image_write_png_bytes(small, w, h, png, err, sizeof err);
    if (!written)
        fprintf(stderr, "%s\n", err);
    free(small);
    return written;
}

struct image_difference compare_png(const char *a, const char *b) {
    char err[512];
    int wa = 0, ha = 0, wb = 0, hb = 0;
    uint8_t *pa = image_read_rgb(a, &wa, &ha, err, sizeof err);
    cr_assert_not_null(pa, "%s", err);
    uint8_t *pb = image_read_rgb(b, &wb, &hb, err, sizeof err);
    cr_assert_not_null(pb, "%s", err);
    cr_assert(wa == wb && ha == hb, "%s is %dx%d but %s is %dx%d", a, wa, ha, b, wb, hb);
    struct image_difference d = image_compare(pa, pb, wa, ha);
    free(pa);
    free(pb);
    return d;
}

bool regression_passes(const struct image_difference *d) {
    return d->within_1 >= REGRESSION_MIN_WITHIN_1 && d->mean <= REGRESSION_MAX_MEAN;
}

void write_scene_variant(const char *from, const char *to, const char *const *olds, const char *const *news,
                         int count, const char *camera_line) {
    char *text = read_text_file(from);
    FILE *out = fopen(to, "wb");
    cr_assert_not_null(out, "cannot write %s", to);
    for (int k = 0; k < count; k++)
        cr_assert_not_null(strstr(text, olds[k]), "'%s' not found in %s", olds[k], from);
    char *line = text;
    while (line != NULL && *line != '\0') {
        char *end = strchr(line, '\n');
        size_t length = end != NULL ? (size_t)(end - line) : strlen(line);
        char *copy = strndup(line, length);
        if (camera_line != NULL && strncmp(copy, "camera", 6) == 0) {
            fprintf(out, "%s\n", camera_line);
        } else {
            for (int k = 0; k < count; k++) {
                char *found = strstr(copy, olds[k]);
                if (found == NULL)
                    continue;
                fprintf(out, "%.*s%s", (int)(found - copy), copy, news[k]);
                memmove(copy, found + strlen(olds[k]), strlen(found + strlen(olds[k])) + 1);
            }
            fprintf(out, "%s\n", copy);
        }
        free(copy);
        line = end != NULL ? end + 1 : NULL;
    }
    fclose(out);
    free(text);
}

const char *shifted_camera_line(const char *path, double pixels) {
    static _Thread_local char line[512];
    struct scene s;
    char err[512];
    cr_assert(scene_load(path, NULL, &s, err, sizeof err), "%s", err);
    vec3 view = vec3_sub(s.target, s.eye);
    vec3 right = vec3_normalize(vec3_cross(view, s.up));
    double pixel_width = 2.0 * vec3_length(view) * tan(s.fov * M_PI / 360.0) / s.height;
    vec3 shift = vec3_scale(right, pixels * pixel_width);
    vec3 eye = vec3_add(s.eye, shift), target = vec3_add(s.target, shift);
    snprintf(line, sizeof line, "camera eye %.17g %.17g %.17g target %.17g %.17g %.17g up %.17g %.17g %.17g fov %.17g",
             eye.x, eye.y, eye.z, target.x, target.y, target.z, s.up.x, s.up.y, s.up.z, s.fov);
    scene_free(&s);
    return line;
}

void report_difference(const char *what, const struct image_difference *d) {
    fprintf(stderr, "%s: max %d, mean %.4f, within 1: %.3f%%, within 2: %.3f%%\n", what, d->max, d->mean,
            100.0 * d->within_1, 100.0 * d->within_2);
}

struct image_difference variant_against_povray(int n, const char *old_line, const char *new_line, const char *name,
                                              int divisor) {
    char variant[512], ours[256], theirs[256], what[512], size[64], smaller[64];
    snprintf(variant, sizeof variant, "%s.%s.variant", chapter_scene(n), name);
    snprintf(ours, sizeof ours, TEST_OUT "/%s-ours.png", name);
    snprintf(theirs, sizeof theirs, TEST_OUT "/%s-povray.png", name);
    struct scene s;
    char err[512];
    cr_assert(scene_load(chapter_scene(n), NULL, &s, err, sizeof err), "%s", err);
    snprintf(size, sizeof size, "image %d %d", s.width, s.height);
    snprintf(smaller, sizeof smaller, "image %d %d", s.width / divisor, s.height / divisor);
    scene_free(&s);
    const char *olds[] = {old_line, size}, *news[] = {new_line, smaller};
    write_scene_variant(chapter_scene(n), variant, olds, news, divisor > 1 ? 2 : 1, NULL);
    int status = render_chapter(n, variant, ours, "");
    bool rendered = render_povray(n, variant, theirs);
    remove(variant);
    cr_assert_eq(status, 0, "chapter %d failed on '%s'", n, new_line);
    cr_assert(rendered, "POV-Ray failed on the twin of '%s'", new_line);
    struct image_difference d = compare_png(ours, theirs);
    snprintf(what, sizeof what, "chapter %d '%s' vs POV-Ray", n, new_line);
    report_difference(what, &d);
    return d;
}

void expect_variant_agrees_with_povray(int n, const char *old_line, const char *new_line, const char *name,
                                       int divisor) {
    struct image_difference d = variant_against_povray(n, old_line, new_line, name, divisor);
    cr_expect_geq(d.within_1, VARIANT_AGREEMENT_MIN_WITHIN_1, "'%s': %.4f %% of pixels within 1 level of POV-Ray, max %d",
                  new_line, 100 * d.within_1, d.max);
}

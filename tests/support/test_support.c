/* test_support.c: small helpers shared by the test files (see test_support.h). */
#include "test_support.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "box.h"
#include "plane.h"
#include "scene.h"
#include "sphere.h"
#include "triangle.h"

const struct shape_kind *const test_every_kind[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};

char *read_file(const char *path, size_t *size) {
    struct stat info;
    cr_assert(stat(path, &info) == 0 && S_ISREG(info.st_mode), "%s is not a file", path);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long length = ftell(f);
    rewind(f);
    char *data = malloc((size_t)length + 1);
    cr_assert_not_null(data, "out of memory reading %s", path);
    cr_assert(fread(data, 1, (size_t)length, f) == (size_t)length, "cannot read %s", path);
    data[length] = '\0';
    fclose(f);
    if (size != NULL)
        *size = (size_t)length;
    return data;
}

char *read_text_file(const char *path) { return read_file(path, NULL); }

int run_capturing(const char *command, char *output, size_t size) {
    size_t length = strlen(command) + sizeof " 2>&1";
    char *line = malloc(length);
    cr_assert_not_null(line);
    snprintf(line, length, "%s 2>&1", command);
    FILE *pipe = popen(line, "r");
    free(line);
    cr_assert_not_null(pipe);
    size_t used = fread(output, 1, size - 1, pipe);
    output[used] = '\0';
    int status = pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* Every test writes its scratch files under out/test/ (TEST_OUT); the tests run in parallel, so the
 * directory is made once, before any of them starts, rather than by whichever test happens to need it
 * first. The run is named too (TEST_RUN_VARIABLE), for what its tests share (test_run_id). */
ReportHook(PRE_ALL)(struct criterion_test_set *tests) {
    (void)tests;
    mkdir("out", 0755);
    mkdir("out/test", 0755);
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    char id[64];
    snprintf(id, sizeof id, "%ld.%lld.%09ld", (long)getpid(), (long long)now.tv_sec, now.tv_nsec);
    setenv(TEST_RUN_VARIABLE, id, 1);
}

const char *test_run_id(void) { return getenv(TEST_RUN_VARIABLE); }

int run_logged(const char *command, const char *log) {
    FILE *l = fopen(log, "a");
    if (l != NULL) {
        fprintf(l, "$ %s\n", command);
        fclose(l);
    }
    size_t size = strlen(command) + strlen(log) + 32;
    char *line = malloc(size);
    cr_assert_not_null(line);
    snprintf(line, size, "{ %s ; } >>%s 2>&1", command, log);
    int status = system(line);
    free(line);
    return status == -1 || !WIFEXITED(status) ? -1 : WEXITSTATUS(status);
}

bool parse_scene_lines(const char *name, const char *head, const char *lines, const struct shape_kind *const *kinds,
                       struct scene *s, char *err, size_t err_size) {
    char text[4096];
    int length = snprintf(text, sizeof text, "%s%s\n", head, lines);
    cr_assert(length > 0 && (size_t)length < sizeof text, "scene text too long");
    return scene_parse(name, text, kinds, s, err, err_size);
}

void expect_scene_refused(const char *name, const char *head, const char *lines, const struct shape_kind *const *kinds,
                          const char *message) {
    struct scene s;
    char err[512] = "";
    bool parsed = parse_scene_lines(name, head, lines, kinds, &s, err, sizeof err);
    cr_expect(!parsed, "'%s' was accepted", lines);
    if (parsed)
        scene_free(&s);
    cr_expect_str_eq(err, message, "for '%s'", lines);
}

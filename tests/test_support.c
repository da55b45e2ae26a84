/* test_support.c: small helpers shared by the test files (see test_support.h). */
#include "test_support.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

char *read_text_file(const char *path) {
    struct stat info;
    cr_assert(stat(path, &info) == 0 && S_ISREG(info.st_mode), "%s is not a file", path);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    rewind(f);
    char *text = malloc((size_t)size + 1);
    cr_assert_not_null(text, "out of memory reading %s", path);
    cr_assert(fread(text, 1, (size_t)size, f) == (size_t)size, "cannot read %s", path);
    text[size] = '\0';
    fclose(f);
    return text;
}

/* Every test writes its scratch files under out/test/ (TEST_OUT); the tests run in parallel, so the
 * directory is made once, before any of them starts, rather than by whichever test happens to need it
 * first. */
ReportHook(PRE_ALL)(struct criterion_test_set *tests) {
    (void)tests;
    mkdir("out", 0755);
    mkdir("out/test", 0755);
}

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

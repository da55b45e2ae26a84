/* test_build.c: the Makefile itself. make help lists every target; make help and make clean install
 * nothing, while the goals that build do (through the `deps` step, never while the Makefile is only
 * read); and make bench after make test links bench_accel with Embree, although make test linked it
 * without (the order a fresh clone follows: make chapter-10, make test, make bench). */
#include <criterion/criterion.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_support.h"

#define COMMAND_MAX 4096
#define OUTPUT_MAX (1 << 20)

/* make, as a test runs it: not a part of the make that runs the tests (whose jobs and flags it would
 * otherwise inherit). */
#define MAKE "env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS make --no-print-directory"

static const char *build_dir(void) {
    const char *build = getenv("WHITTED_BUILD");
    return build != NULL ? build : "build";
}

/* A scratch directory /tmp/whitted-build-XXXXXX holding the given paths of the repository (files or
 * folders, copied with their times); `dir` receives its name. */
static void make_copy(char *dir, size_t size, const char *paths) {
    snprintf(dir, size, "/tmp/whitted-build-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
    char command[COMMAND_MAX];
    snprintf(command, sizeof command, "cp -rp --parents %s %s/", paths, dir);
    cr_assert_eq(system(command), 0, "%s failed", command);
}

static void remove_copy(const char *dir) {
    char command[COMMAND_MAX];
    snprintf(command, sizeof command, "rm -rf %s", dir);
    cr_expect_eq(system(command), 0);
}

/* The makefiles, enough for make to read them. */
#define MAKEFILES "Makefile tools/build tools/models/models.mk bench/bench.mk fuzz/fuzz.mk tools/results/results.mk"

Test(build, help_lists_every_target) {
    static char phony[OUTPUT_MAX], help[OUTPUT_MAX];
    cr_assert_eq(run_capturing(MAKE " -pq help | sed -n 's/^\\.PHONY: //p'", phony, sizeof phony), 0);
    cr_assert_eq(run_capturing(MAKE " help", help, sizeof help), 0, "make help failed:\n%s", help);
    size_t targets = 0;
    for (char *target = strtok(phony, " \n"); target != NULL; target = strtok(NULL, " \n"), targets++) {
        /* chapter-1 to chapter-11 are listed once, as chapter-N; check-N likewise. */
        char listed[128];
        size_t n = strlen(target);
        while (n > 0 && isdigit((unsigned char)target[n - 1]))
            n--;
        if (n > 0 && n < strlen(target) && target[n - 1] == '-')
            snprintf(listed, sizeof listed, "\nmake %.*sN ", (int)n, target);
        else
            snprintf(listed, sizeof listed, "\nmake %s ", target);
        char with_newline[OUTPUT_MAX + 1];
        snprintf(with_newline, sizeof with_newline, "\n%s", help);
        cr_expect_not_null(strstr(with_newline, listed), "make help does not list %s (looked for '%s'):\n%s", target,
                           listed + 1, help);
    }
    cr_assert_gt(targets, 30, "only %zu phony targets found", targets);
}

Test(build, help_and_clean_install_nothing_while_deps_installs, .timeout = 60) {
    /* In a copy whose installer only writes down that it ran. */
    char dir[64], command[COMMAND_MAX], log[128], output[4096];
    make_copy(dir, sizeof dir, MAKEFILES);
    snprintf(log, sizeof log, "%s/installed", dir);
    snprintf(command, sizeof command,
             "printf '#!/bin/sh\\necho \"$*\" >>%s\\n' >%s/tools/build/install-deps.sh && mkdir -p %s/build %s/out",
             log, dir, dir, dir);
    cr_assert_eq(system(command), 0);
    snprintf(command, sizeof command, "cd %s && " MAKE " help >/dev/null && " MAKE " clean", dir);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s failed:\n%s", command, output);
    cr_expect_neq(access(log, F_OK), 0, "make help or make clean ran tools/build/install-deps.sh");
    snprintf(command, sizeof command, "cd %s && test ! -e build && test ! -e out", dir);
    cr_expect_eq(system(command), 0, "make clean left build/ or out/");
    /* The same installer is what the packages step runs, so the check above can see it. */
    snprintf(command, sizeof command, "cd %s && " MAKE " deps && cat installed", dir);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s failed:\n%s", command, output);
    cr_expect_str_eq(output, "build\n");
    remove_copy(dir);

    /* In this repository, dry runs: each goal's packages are installed as a step of the build. */
    static const struct {
        const char *goal, *needs;
    } goals[] = {{"test", "build test"}, {"test-long", "build test"}, {"compare", "build compare"}};
    for (size_t k = 0; k < sizeof goals / sizeof goals[0]; k++) {
        static char dry[OUTPUT_MAX];
        snprintf(command, sizeof command, MAKE " -n %s", goals[k].goal);
        cr_assert_eq(run_capturing(command, dry, sizeof dry), 0, "%s failed:\n%s", command, dry);
        char expected[128];
        snprintf(expected, sizeof expected, "tools/build/install-deps.sh %s", goals[k].needs);
        cr_expect_not_null(strstr(dry, expected), "make %s does not run '%s' first", goals[k].goal, expected);
    }
}

/* Runs `command` in `dir`, with its output appended to `log`; returns its exit status. */
static int run_in(const char *dir, const char *command, const char *log) {
    char line[COMMAND_MAX + 128];
    snprintf(line, sizeof line, "cd %s && %s", dir, command);
    return run_logged(line, log);
}

Test(build, make_bench_after_make_test_links_bench_accel_with_embree, .timeout = 300) {
    if (access("/usr/include/embree3/rtcore.h", F_OK) != 0)
        cr_skip_test("needs Embree (libembree-dev), which make bench installs");
    const char *build = build_dir();
    const char *san = strstr(build, "san") != NULL ? "SAN=1" : "";
    char dir[64], command[COMMAND_MAX], log[128];
    make_copy(dir, sizeof dir,
              "Makefile tools/build tools/models/models.mk bench fuzz/fuzz.mk tools/results/results.mk common "
              "tests/support scenes/models/bunny.ply");
    snprintf(log, sizeof log, "%s.log", dir);
    remove(log);
    /* This build's objects of common/, older than nothing they were made from, so that only the
     * benchmark's own files are compiled in the copy. */
    snprintf(command, sizeof command, "mkdir -p %s/%s && cp -rp %s/common %s/%s/", dir, build, build, dir, build);
    cr_assert_eq(system(command), 0);
    const char *embree_run = "%s/bench_accel --embree --repeats 1 --size 8x6 --only embree scenes/models/bunny.ply";
    char run[256];
    snprintf(run, sizeof run, embree_run, build);

    /* make test on a machine without Embree: the plain program (BENCH_EMBREE= stands for the missing
     * header), which refuses --embree. */
    snprintf(command, sizeof command, MAKE " %s BENCH_EMBREE= %s/bench_accel", san, build);
    cr_assert_eq(run_in(dir, command, log), 0, "the plain build failed: see %s", log);
    cr_assert_eq(run_in(dir, run, log), 2, "the plain program ran --embree: see %s", log);
    /* make bench, once Embree is installed: its second make builds the program again, with Embree. */
    snprintf(command, sizeof command, MAKE " %s %s/bench_accel", san, build);
    cr_assert_eq(run_in(dir, command, log), 0, "the Embree build failed: see %s", log);
    cr_assert_eq(run_in(dir, run, log), 0, "make bench after make test kept the program without Embree: see %s", log);
    /* And back: the plain program again when Embree goes. */
    snprintf(command, sizeof command, MAKE " %s BENCH_EMBREE= %s/bench_accel", san, build);
    cr_assert_eq(run_in(dir, command, log), 0, "the second plain build failed: see %s", log);
    cr_assert_eq(run_in(dir, run, log), 2, "the program kept Embree after it went: see %s", log);
    remove_copy(dir);
    remove(log);
}

Test(build, test_long_builds_every_mutant_first) {
    /* make test-long runs the deliberately wrong tracers of tests/mutants/, so it must build them: read
     * its prerequisites from make's database (make -p, which builds nothing here). A list defined after
     * the rule that names it would be empty there, and a fresh clone would run tests on programs that
     * do not exist. */
    static char database[OUTPUT_MAX];
    cr_assert_eq(run_capturing(MAKE " -pq help 2>/dev/null | grep '^test-long:'", database, sizeof database), 0);
    char patches[4096];
    cr_assert_eq(run_capturing("cd tests/mutants && ls *.patch | sed 's/\\.patch$//'", patches, sizeof patches), 0);
    size_t mutants = 0;
    for (char *name = strtok(patches, "\n"); name != NULL; name = strtok(NULL, "\n")) {
        char program[256];
        snprintf(program, sizeof program, " %s/mutant-%s", build_dir(), name);
        cr_expect_not_null(strstr(database, program), "make test-long does not build%s:\n%s", program, database);
        mutants++;
    }
    cr_assert_geq(mutants, 2, "tests/mutants/ holds %zu patches", mutants);
}

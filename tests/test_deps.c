/* test_deps.c: what each make target asks tools/build/install-deps.sh for, and the route for a student
 * without root: `make chapter-1` on a machine where stb is not installed fetches it into .deps/ and
 * builds against it, with no root and no sudo. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "test_support.h"

#define COMMAND_MAX 4096

static bool file_contains(const char *path, const char *text) {
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return false;
    static char buffer[1 << 20];
    size_t n = fread(buffer, 1, sizeof buffer - 1, f);
    fclose(f);
    buffer[n] = '\0';
    return strstr(buffer, text) != NULL;
}

Test(deps, the_installer_names_what_each_target_needs) {
    /* Everything is installed on a machine that runs the tests, so each need is satisfied: exit 0. An
     * unknown need is a usage error, exit 2, with a message naming the valid ones. */
    const char *log = "out/test/deps-needs.log";
    remove(log);
    cr_assert_eq(run_logged("tools/build/install-deps.sh build test compare results video", log), 0);
    cr_assert_eq(run_logged("tools/build/install-deps.sh everything", log), 2);
    cr_assert(file_contains(log, "install-deps.sh: unknown need 'everything' (build, test, compare, cycles, results, "
                                 "bench, profile, fuzz, web, test-web or video)"));
}

Test(deps, without_root_and_without_stb_make_chapter_1_fetches_stb_and_renders, .timeout = 300) {
    if (geteuid() != 0)
        cr_skip_test("needs root to create the unprivileged user's copy (CI runs as root)");
    /* A copy of the repository owned by the unprivileged user `nobody`, who may not use apt-get
     * install or sudo. PKG_CONFIG_LIBDIR pointing nowhere hides the system's stb, as on a machine that
     * never installed it. apt-get download needs the package lists, which root makes once. */
    char dir[] = "/tmp/whitted-noroot-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char log[256], command[COMMAND_MAX];
    snprintf(log, sizeof log, "%s.log", dir);
    remove(log);
    snprintf(command, sizeof command,
             "cp -r --parents Makefile common chapters tools tests/support scenes bench fuzz %s/ && rm -rf %s/scenes/models/teapot-* && "
             "chown -R nobody:nogroup %s",
             dir, dir, dir);
    cr_assert_eq(run_logged(command, log), 0, "could not make the copy (see %s)", log);
    if (run_logged("apt-cache show libstb-dev >/dev/null", log) != 0)
        run_logged("apt-get update -q", log);
    snprintf(command, sizeof command,
             "cd %s && runuser -u nobody -- env HOME=%s PKG_CONFIG_LIBDIR=/nonexistent make chapter-1", dir, dir);
    int status = run_logged(command, log);
    char png[512];
    snprintf(png, sizeof png, "%s/out/chapter-01.png", dir);
    bool rendered = access(png, F_OK) == 0;
    bool fetched = file_contains(log, "no root: fetching libstb-dev into .deps/");
    snprintf(command, sizeof command, "rm -rf %s", dir);
    run_logged(command, log);
    cr_assert_eq(status, 0, "make chapter-1 as nobody failed (see %s)", log);
    cr_assert(fetched, "stb was not fetched into .deps/ (see %s)", log);
    cr_assert(rendered, "no picture was written (see %s)", log);
    remove(log);
}

/* test_layering.c: a chapter can only use what it and earlier chapters introduced. The Makefile links
 * each chapter with its own module list; here a program calling chapter 4's plane_intersect must fail
 * to link with chapter 3's list and link with chapter 4's. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Runs `make` on the probe linked against chapter `chapter`'s modules; returns its exit status and the
 * first bytes of its output in `output`. */
static int link_probe(const char *chapter, char *output, size_t size) {
    const char *build = getenv("WHITTED_BUILD");
    bool sanitized = build != NULL && strstr(build, "san") != NULL;
    char command[512];
    snprintf(command, sizeof command,
             "rm -f %s/layering-probe-%s && env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS "
             "make --no-print-directory SAN=%d %s/layering-probe-%s 2>&1",
             build != NULL ? build : "build", chapter, sanitized ? 1 : 0, build != NULL ? build : "build", chapter);
    FILE *pipe = popen(command, "r");
    cr_assert_not_null(pipe);
    size_t length = fread(output, 1, size - 1, pipe);
    output[length] = '\0';
    int status = pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

Test(layering, chapter_3_cannot_use_chapter_4s_plane) {
    static char output[65536];
    cr_assert_neq(link_probe("03", output, sizeof output), 0, "the probe linked with chapter 3's modules");
    cr_assert_not_null(strstr(output, "undefined reference to `plane_intersect'"), "unexpected output:\n%s", output);
}

Test(layering, chapter_4_can_use_its_plane) {
    static char output[65536];
    cr_assert_eq(link_probe("04", output, sizeof output), 0, "the probe failed with chapter 4's modules:\n%s", output);
}

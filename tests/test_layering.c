/* test_layering.c: a chapter can only use what it and earlier chapters introduced. The Makefile links
 * each chapter with its own module list (MODULES_NN); here every chapter's program, linked with the
 * list of the chapter before it, must fail to link for want of the very idea the chapter introduces,
 * and link with its own list. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Runs `make` to link chapter `chapter`'s program with chapter `modules`' module list; returns make's
 * exit status and the first bytes of its output in `output`. */
static int link_chapter(int chapter, int modules, char *output, size_t size) {
    const char *build = getenv("WHITTED_BUILD");
    build = build != NULL ? build : "build";
    bool sanitized = strstr(build, "san") != NULL;
    char target[256], command[768];
    snprintf(target, sizeof target, "%s/layering-%02d-with-%02d", build, chapter, modules);
    snprintf(command, sizeof command,
             "rm -f %s && env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS make --no-print-directory SAN=%d %s 2>&1",
             target, sanitized ? 1 : 0, target);
    FILE *pipe = popen(command, "r");
    cr_assert_not_null(pipe);
    size_t length = fread(output, 1, size - 1, pipe);
    output[length] = '\0';
    int status = pclose(pipe);
    remove(target);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* For each chapter from 2 on, a function its main.c uses from a module that chapter introduces. */
static const struct {
    int chapter;
    const char *symbol;
} new_ideas[] = {
    {2, "sphere_closest"},   {3, "triangle_closest"}, {4, "plane_closest"},
    {5, "world_closest"},    {6, "phong_trace_nearest"}, {7, "shadow_opaque"},
    {8, "whitted_trace"},    {9, "accel_world_create"},  {10, "accel_world_use_bvh"},
    {11, "accel_world_use_fast_bvh"}, {12, "supersample_sampler"}, {13, "soft_shadow_filtered"},
    {14, "texture_paint"},
};

Test(layering, no_chapter_links_with_the_previous_chapters_modules, .timeout = 300) {
    static char output[65536];
    for (size_t k = 0; k < sizeof new_ideas / sizeof new_ideas[0]; k++) {
        int n = new_ideas[k].chapter;
        char expected[128];
        snprintf(expected, sizeof expected, "undefined reference to `%s'", new_ideas[k].symbol);
        cr_assert_neq(link_chapter(n, n - 1, output, sizeof output), 0,
                      "chapter %d linked with chapter %d's modules", n, n - 1);
        cr_assert_not_null(strstr(output, expected), "chapter %d with chapter %d's modules: no \"%s\" in:\n%s", n,
                           n - 1, expected, output);
        /* And the student is told where the missing function comes from. */
        char note[256];
        snprintf(note, sizeof note, "note: %s is in common/", new_ideas[k].symbol);
        char *at = strstr(output, note);
        cr_assert_not_null(at, "chapter %d with chapter %d's modules: no \"%s\" in:\n%s", n, n - 1, note, output);
        char introduced[64];
        snprintf(introduced, sizeof introduced, "which chapter %d introduces", n);
        cr_assert_not_null(strstr(at, introduced), "the note for %s does not name chapter %d:\n%s",
                           new_ideas[k].symbol, n, at);
    }
}

Test(layering, every_chapter_links_with_its_own_modules, .timeout = 300) {
    static char output[65536];
    for (int n = 1; n <= 14; n++)
        cr_assert_eq(link_chapter(n, n, output, sizeof output), 0,
                     "chapter %d failed to link with its own modules:\n%s", n, output);
}

/* Chapter 1 reads every scene (each kind of shape brings the syntax of its line in its _syntax.c file,
 * which the scene reader knows) without linking any intersection code (the kind's .c file, which holds
 * its table of ray queries, X_kind). */
Test(layering, chapter_1_reads_every_scene_without_any_intersection_code, .timeout = 120) {
    const char *build = getenv("WHITTED_BUILD");
    build = build != NULL ? build : "build";
    char command[1024];
    snprintf(command, sizeof command, "nm %s/chapter-01", build);
    FILE *pipe = popen(command, "r");
    cr_assert_not_null(pipe);
    char line[512];
    size_t symbols = 0;
    while (fgets(line, sizeof line, pipe) != NULL) {
        symbols++;
        char type = '\0', name[256] = "";
        if (sscanf(line, "%*s %c %255s", &type, name) != 2)
            continue; /* an undefined symbol: no address */
        size_t length = strlen(name);
        bool kind_table = length >= 5 && strcmp(name + length - 5, "_kind") == 0;
        cr_assert(strstr(name, "_intersect") == NULL && strstr(name, "_closest") == NULL && !kind_table,
                  "chapter 1 contains %s: it should link no shape's intersection code", name);
    }
    cr_assert_eq(pclose(pipe), 0);
    cr_assert_gt(symbols, 100, "nm printed too little: is %s/chapter-01 built?", build);
    snprintf(command, sizeof command,
             "for s in scenes/*.scene; do %s/chapter-01 \"$s\" --quiet --width 4 --height 3 -o out/test/layering-01.png "
             "|| exit 1; done",
             build);
    cr_assert_eq(system(command), 0, "chapter 1 refused a scene (see above)");
    remove("out/test/layering-01.png");
}

/* test_cycles_motion.c: chapter 16's motion blur against Blender's Cycles (tools/cycles/motion.py and
 * compare-cycles.sh's `blur` part): the flat bunnies of scenes/16-blur.scene agree block by block within
 * noise, and a shutter 2 % short is caught. Long tests (make test-long): about 20 s each. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

/* Runs compare-cycles.sh's motion blur comparison into the folder `out` (the tests run at once, each in
 * its own) with `extra` passed to chapter 16, its output into out.log; returns its exit status and leaves
 * the table's text in *table (the caller frees it). */
static int compare_blur(const char *out, const char *extra, char **table) {
    const char *build = getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build";
    char command[1024], log[256], path[256];
    snprintf(log, sizeof log, "%s.log", out);
    snprintf(path, sizeof path, "%s/table-16.md", out);
    snprintf(command, sizeof command, "mkdir -p %s && rm -f %s && CYCLES_OUT=%s CYCLES_THREADS=2 "
             "tools/cycles/compare-cycles.sh %s blur %s", out, path, out, build, extra);
    remove(log);
    int status = run_logged(command, log);
    *table = read_text_file(path);
    return status;
}

Test(cycles_motion, chapter_16s_blur_agrees_with_cycles_object_motion_blur, .timeout = 300) {
    char *table;
    cr_assert_eq(compare_blur("out/test/cycles-motion", "", &table), 0, "see out/test/cycles-motion.log");
    cr_assert(strstr(table, "| blur | 20 x 15 blocks of 8 x 8, 3 channels |") != NULL, "%s", table);
    cr_assert(strstr(table, "| agrees |") != NULL, "%s", table);
    free(table);
}

Test(cycles_motion, catches_a_shutter_two_percent_short, .timeout = 300) {
    char *table;
    cr_assert_eq(compare_blur("out/test/cycles-motion-short", "--set camera.shutter=0.49", &table), 1,
                 "see out/test/cycles-motion-short.log");
    cr_assert(strstr(table, "| DISAGREES |") != NULL, "%s", table);
    free(table);
}

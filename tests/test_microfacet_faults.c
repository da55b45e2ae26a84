/* test_microfacet_faults.c: each of chapter 17's faults in common/microfacet.c (the gallery's patches)
 * breaks the test of tests/test_microfacet.c that its patch names (make test-long: it compiles). The
 * test programs run here are Criterion's too: BXFI_MAP, the variable by which a Criterion program finds
 * its own workers, is taken from their environment. */
#include <criterion/criterion.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

/* Each of chapter 17's faults in microfacet.c (a patch of the gallery, tools/gallery/17-*.patch, with a
 * "Fails:" line naming the test of tests/test_microfacet.c that it breaks): that file and the lobes'
 * modules are built again with the patch applied to a copy of common/, and the test must fail there
 * while it passes here. */
Test(microfacet_long, every_fault_of_the_lobes_fails_the_test_it_names, .timeout = 600) {
    glob_t found;
    int count = 0;
    glob("tools/gallery/17-*.patch", 0, NULL, &found);
    for (size_t k = 0; k < found.gl_pathc; k++) {
        const char *patch = found.gl_pathv[k];
        char *text = read_text_file(patch);
        char *fails = strstr(text, "\nFails: ");
        if (fails == NULL || strstr(text, "common/microfacet.c") == NULL) {
            free(text);
            continue;
        }
        fails += strlen("\nFails: ");
        *strchr(fails, '\n') = '\0';
        char name[128], dir[256], log[320], command[4096];
        const char *base = strrchr(patch, '/') + 1;
        snprintf(name, sizeof name, "%.*s", (int)(strlen(base) - strlen(".patch")), base);
        snprintf(dir, sizeof dir, "out/test/microfacet-%s", name);
        snprintf(log, sizeof log, "%s.log", dir);
        remove(log);
        snprintf(command, sizeof command,
                 "tests/support/patched-copy.sh %s %s common && "
                 "${CC:-gcc} -std=c11 -D_DEFAULT_SOURCE -O2 -I%s/common tests/test_microfacet.c "
                 "%s/common/microfacet.c %s/common/bsdf.c %s/common/sampling.c %s/common/owen_sobol.c "
                 "%s/common/sample_hash.c -o %s/run $(pkg-config --cflags --libs criterion) -lm",
                 patch, dir, dir, dir, dir, dir, dir, dir, dir);
        cr_assert_eq(run_logged(command, log), 0, "%s: the patched copy does not build (see %s)", name, log);
        snprintf(command, sizeof command, "env -u BXFI_MAP %s/run --filter '%s'", dir, fails);
        cr_expect_neq(run_logged(command, log), 0, "%s: %s passes with the fault (see %s)", name, fails, log);
        const char *build = getenv("WHITTED_BUILD");
        snprintf(command, sizeof command, "env -u BXFI_MAP WHITTED_BUILD=%s ./%s/run-tests --filter '%s'", build ? build : "build",
                 build ? build : "build", fails);
        cr_expect_eq(run_logged(command, log), 0, "%s: %s fails without the fault (see %s)", name, fails, log);
        count++;
        free(text);
    }
    globfree(&found);
    cr_expect_geq(count, 3, "only %d faults of microfacet.c found", count);
}

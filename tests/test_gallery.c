/* test_gallery.c: every fault of the gallery of wrong pictures (the patches in tools/gallery/) is caught, and
 * docs/gallery.md shows every fault with its pictures.
 *
 * tools/gallery.sh --prove builds the chapter program with the fault applied (to a copy of the
 * sources), renders the fault's scene with it and with the right program, and succeeds only when the
 * wrong picture fails the reference-image rule against the right one. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

#define GALLERY_MAX 64

struct fault {
    char name[64];
};

static struct fault faults[GALLERY_MAX];

/* The faults, from the patch files' names. */
static size_t find_faults(void) {
    glob_t found;
    size_t count = 0;
    if (glob("tools/gallery/*.patch", 0, NULL, &found) != 0)
        return 0;
    for (size_t k = 0; k < found.gl_pathc && count < GALLERY_MAX; k++) {
        const char *base = strrchr(found.gl_pathv[k], '/') + 1;
        snprintf(faults[count++].name, sizeof faults[0].name, "%.*s", (int)(strlen(base) - strlen(".patch")), base);
    }
    globfree(&found);
    return count;
}

ParameterizedTestParameters(gallery, every_fault_is_caught_by_the_picture_check) {
    size_t count = find_faults();
    return cr_make_param_array(struct fault, faults, count);
}

ParameterizedTest(struct fault *f, gallery, every_fault_is_caught_by_the_picture_check, .timeout = 300) {
    const char *build = getenv("WHITTED_BUILD");
    char command[512], log[256];
    snprintf(log, sizeof log, "out/test/gallery-%s.log", f->name);
    remove(log);
    snprintf(command, sizeof command, "tools/gallery.sh %s --prove %s", build != NULL ? build : "build", f->name);
    int status = run_logged(command, log);
    cr_assert_eq(status, 0, "fault %s: %s (see %s)", f->name,
                 status == 1 ? "no check catches it: add one" : "it could not be built or rendered", log);
}

Test(gallery, there_are_at_least_twelve_faults) {
    cr_assert_geq(find_faults(), 12, "the gallery should show at least 12 faults");
}

Test(gallery, the_page_shows_every_fault_with_its_three_pictures) {
    size_t count = find_faults();
    char *page = read_text_file("docs/gallery.md");
    for (size_t k = 0; k < count; k++) {
        char anchor[128];
        snprintf(anchor, sizeof anchor, "<a id=\"%s\"></a>", faults[k].name);
        cr_expect_not_null(strstr(page, anchor), "docs/gallery.md has no section for %s: run make gallery",
                           faults[k].name);
        static const char *const kinds[] = {"right", "wrong", "diff"};
        for (int i = 0; i < 3; i++) {
            char png[256];
            snprintf(png, sizeof png, "docs/gallery/%s-%s.png", faults[k].name, kinds[i]);
            FILE *file = fopen(png, "rb");
            cr_expect_not_null(file, "%s is missing: run make gallery", png);
            if (file != NULL)
                fclose(file);
        }
        /* The page quotes the fault's title and symptom as the patch has them now. */
        char patch[256];
        snprintf(patch, sizeof patch, "tools/gallery/%s.patch", faults[k].name);
        char *text = read_text_file(patch);
        char *symptom = strstr(text, "Symptom: ");
        cr_assert_not_null(symptom, "%s has no Symptom line", patch);
        symptom += strlen("Symptom: ");
        *strchr(symptom, '\n') = '\0';
        cr_expect_not_null(strstr(page, symptom), "docs/gallery.md is stale for %s: run make gallery", faults[k].name);
        free(text);
    }
    free(page);
}

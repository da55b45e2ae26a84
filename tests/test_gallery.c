/* test_gallery.c: every fault of the gallery of wrong pictures (the patches in tools/gallery/) is caught by
 * the student's grader, and docs/gallery.md shows every fault with its pictures.
 *
 * tools/gallery.sh --prove builds the chapter program and the grader (build/check) with the fault
 * applied (to a copy of the sources), renders the fault's scene with it and with the right program, and
 * succeeds only when every task the patch's Check line names fails its own checks with the fault. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <glob.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

#define GALLERY_MAX 64

/* The chapters the student's grader covers (make check-1 to check-13), and so the chapters whose
 * faults --prove can show it catches: every chapter. */
#define GALLERY_GRADED_CHAPTERS 13

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

ParameterizedTestParameters(gallery, every_fault_is_caught_by_the_grader) {
    size_t count = find_faults();
    return cr_make_param_array(struct fault, faults, count);
}

ParameterizedTest(struct fault *f, gallery, every_fault_is_caught_by_the_grader, .timeout = 300) {
    const char *build = getenv("WHITTED_BUILD");
    char command[512], log[256];
    snprintf(log, sizeof log, "out/test/gallery-%s.log", f->name);
    remove(log);
    snprintf(command, sizeof command, "tools/gallery.sh %s --prove %s", build != NULL ? build : "build", f->name);
    int status = run_logged(command, log);
    cr_assert_eq(status, 0, "fault %s: %s (see %s)", f->name,
                 status == 1 ? "a task its Check line names does not catch it: add a check" : "it could not be built or rendered", log);
}

Test(gallery, there_are_at_least_twelve_faults) {
    cr_assert_geq(find_faults(), 12, "the gallery should show at least 12 faults");
}

Test(gallery, every_chapter_has_a_fault) {
    size_t count = find_faults();
    bool shown[100] = {false};
    for (size_t k = 0; k < count; k++) {
        char patch[256];
        snprintf(patch, sizeof patch, "tools/gallery/%s.patch", faults[k].name);
        char *text = read_text_file(patch);
        char *chapter = strstr(text, "\nChapter: ");
        cr_assert_not_null(chapter, "%s has no Chapter line", patch);
        int n = atoi(chapter + strlen("\nChapter: "));
        if (n > 0 && n < 100)
            shown[n] = true;
        free(text);
    }
    glob_t found;
    cr_assert_eq(glob("chapters/[0-9][0-9]-*", 0, NULL, &found), 0, "no chapters found");
    for (size_t k = 0; k < found.gl_pathc; k++) {
        int n = atoi(found.gl_pathv[k] + strlen("chapters/"));
        if (n <= GALLERY_GRADED_CHAPTERS)
            cr_expect(shown[n], "no fault of the gallery is made in chapter %d (%s)", n, found.gl_pathv[k]);
    }
    globfree(&found);
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
        /* Every fault names the grader's tasks that report it, and the page says them. */
        char *check = strstr(text + (symptom - text) + strlen(symptom) + 1, "Check: ");
        cr_assert_not_null(check, "%s has no Check line (after its Symptom line)", patch);
        check += strlen("Check: ");
        *strchr(check, '\n') = '\0';
        char first[16], said[64];
        cr_assert_eq(sscanf(check, "%15s", first), 1, "%s: the Check line names no task", patch);
        snprintf(said, sizeof said, "`make check-%d`: %s", atoi(first), first);
        cr_expect_not_null(strstr(page, said), "docs/gallery.md does not say that %s reports %s: run make gallery",
                           first, faults[k].name);
        free(text);
    }
    free(page);
}

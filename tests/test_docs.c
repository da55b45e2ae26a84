/* test_docs.c: the walkthroughs quote the code as it is. Every ```c block in the docs must appear,
 * character for character, in one of the files it could come from; a quote that drifted from its code
 * fails here, naming the doc and the block's first line. */
#include <criterion/criterion.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "test_support.h"

#define FENCE_OPEN "```c\n"
#define FENCE_CLOSE "```"

/* Where quoted code may come from. */
static const char *const code_patterns[] = {"common/*.[ch]", "chapters/*/main.c", "tools/*.[ch]", "bench/*.c",
                                            "tests/*.[ch]", "scenes/*.scene"};

/* All code files, read once. */
struct corpus {
    char **texts;
    size_t count;
};

static struct corpus read_code(void) {
    struct corpus c = {NULL, 0};
    for (size_t p = 0; p < sizeof code_patterns / sizeof code_patterns[0]; p++) {
        glob_t found;
        if (glob(code_patterns[p], 0, NULL, &found) != 0)
            continue;
        c.texts = realloc(c.texts, (c.count + found.gl_pathc) * sizeof *c.texts);
        for (size_t k = 0; k < found.gl_pathc; k++)
            c.texts[c.count++] = read_text_file(found.gl_pathv[k]);
        globfree(&found);
    }
    return c;
}

static bool quoted_somewhere(const struct corpus *c, const char *block) {
    for (size_t k = 0; k < c->count; k++)
        if (strstr(c->texts[k], block) != NULL)
            return true;
    return false;
}

Test(docs, every_c_listing_in_the_walkthroughs_is_the_current_code) {
    struct corpus code = read_code();
    cr_assert_gt(code.count, 20, "found only %zu code files: not run from the repository root?", code.count);
    glob_t docs;
    cr_assert_eq(glob("docs/*.md", 0, NULL, &docs), 0);
    size_t listings = 0, stale = 0;
    for (size_t d = 0; d < docs.gl_pathc; d++) {
        char *text = read_text_file(docs.gl_pathv[d]);
        for (char *open = strstr(text, FENCE_OPEN); open != NULL; open = strstr(open, FENCE_OPEN)) {
            char *start = open + strlen(FENCE_OPEN);
            char *close = strstr(start, FENCE_CLOSE);
            cr_assert_not_null(close, "%s: a ```c block is never closed", docs.gl_pathv[d]);
            *close = '\0';
            listings++;
            if (!quoted_somewhere(&code, start)) {
                stale++;
                fprintf(stderr, "%s: listing not found in the code, starting: %.70s\n", docs.gl_pathv[d], start);
            }
            open = close + strlen(FENCE_CLOSE);
        }
        free(text);
    }
    globfree(&docs);
    for (size_t k = 0; k < code.count; k++)
        free(code.texts[k]);
    free(code.texts);
    cr_assert_gt(listings, 30, "only %zu listings found", listings);
    cr_assert_eq(stale, 0, "%zu of %zu listings no longer match the code (see above)", stale, listings);
}

/* Everything a reader of the repository can open: the docs, the code, the scenes and the tools. */
static const char *const readable_patterns[] = {"README.md", "docs/*.md", "scenes/*.scene", "scenes/results/*.scene",
                                                "scenes/models/README.md",
                                                "common/*.[ch]", "chapters/*/main.c", "tools/*.*", "tools/*/*",
                                                "bench/*", "fuzz/*.*", "tests/*.[ch]", "tests/*/*.[ch]", "Makefile", ".ci/run"};

Test(docs, nothing_cites_a_file_outside_the_repository) {
    /* The project's private notes sit beside the repository during development; a public reader has
     * only the repository, so no page or comment may send them there. Spelled in two pieces so that
     * this file does not match itself. */
    const char *outside = "../" "shared";
    size_t files = 0, citing = 0;
    for (size_t p = 0; p < sizeof readable_patterns / sizeof readable_patterns[0]; p++) {
        glob_t found;
        if (glob(readable_patterns[p], 0, NULL, &found) != 0)
            continue;
        for (size_t k = 0; k < found.gl_pathc; k++) {
            char *text = read_text_file(found.gl_pathv[k]);
            files++;
            if (strstr(text, outside) != NULL) {
                citing++;
                fprintf(stderr, "%s cites %s/, which is not part of the repository\n", found.gl_pathv[k], outside);
            }
            free(text);
        }
        globfree(&found);
    }
    cr_assert_gt(files, 50, "found only %zu files: not run from the repository root?", files);
    cr_assert_eq(citing, 0, "%zu files cite a folder outside the repository (see above)", citing);
}

Test(docs, every_page_links_to_pages_that_exist) {
    /* A relative link in a walkthrough, [text](name.md) or [text](../path), must name a file that is
     * there; anchors (#...) and web addresses are not checked. */
    glob_t docs;
    cr_assert_eq(glob("docs/*.md", 0, NULL, &docs), 0);
    size_t links = 0, broken = 0;
    for (size_t d = 0; d < docs.gl_pathc; d++) {
        char *text = read_text_file(docs.gl_pathv[d]);
        for (char *at = strstr(text, "]("); at != NULL; at = strstr(at + 2, "](")) {
            char *target = at + 2, *end = strpbrk(target, ")# \n");
            if (end == NULL || end == target || strncmp(target, "http", 4) == 0 || *end == ' ' || *end == '\n')
                continue;
            char path[512];
            snprintf(path, sizeof path, "docs/%.*s", (int)(end - target), target);
            links++;
            FILE *f = fopen(path, "rb");
            if (f == NULL) {
                broken++;
                fprintf(stderr, "%s links to %.*s, which does not exist\n", docs.gl_pathv[d], (int)(end - target), target);
            } else {
                fclose(f);
            }
        }
        free(text);
    }
    globfree(&docs);
    cr_assert_gt(links, 50, "only %zu links found", links);
    cr_assert_eq(broken, 0, "%zu links point at missing files (see above)", broken);
}

Test(docs, every_walkthrough_from_chapter_2_has_a_build_exercise_with_its_check) {
    /* A ★★★ exercise whose supplied check make exercises runs (its table in tests/exercises/runner/run.sh),
     * and the page says so. */
    char *checks = read_text_file("tests/exercises/runner/run.sh");
    glob_t pages;
    cr_assert_eq(glob("docs/[0-9][0-9]-*.md", 0, NULL, &pages), 0);
    size_t seen = 0;
    for (size_t k = 0; k < pages.gl_pathc; k++) {
        int chapter = atoi(pages.gl_pathv[k] + strlen("docs/"));
        if (chapter < 2 || chapter > 13)
            continue;
        seen++;
        char *text = read_text_file(pages.gl_pathv[k]);
        char exercise[64], row[64];
        snprintf(exercise, sizeof exercise, "grades exercise %d.4", chapter);
        snprintf(row, sizeof row, "\n%d.4|", chapter); /* a line of run.sh's table */
        cr_expect_not_null(strstr(text, "★★★"), "%s has no build exercise (★★★)", pages.gl_pathv[k]);
        cr_expect(strstr(text, "`make exercises`") != NULL && strstr(text, exercise) != NULL,
                  "%s does not say that make exercises %s", pages.gl_pathv[k], exercise);
        cr_expect(strstr(checks, row) != NULL,
                  "chapter %d has no supplied check in tests/exercises/runner/run.sh", chapter);
        free(text);
    }
    globfree(&pages);
    free(checks);
    cr_assert_eq(seen, 12, "expected the walkthroughs of chapters 2 to 13");
}

/* A walkthrough is read in one sitting: at most this many lines. What a chapter's reader can do without
 * (the history of its measurements, the steps that got there, its engineering) goes to a page of notes
 * the chapter links, as chapter 11's lab notes (docs/fast-notes.md). */
#define WALKTHROUGH_MAX_LINES 500

static size_t count_lines(const char *text) {
    size_t lines = 0;
    for (const char *c = text; *c != '\0'; c++)
        lines += *c == '\n';
    return lines;
}

Test(docs, every_walkthrough_reads_in_one_sitting) {
    glob_t pages;
    cr_assert_eq(glob("docs/[0-9][0-9]-*.md", 0, NULL, &pages), 0);
    size_t too_long = 0;
    for (size_t k = 0; k < pages.gl_pathc; k++) {
        char *text = read_text_file(pages.gl_pathv[k]);
        size_t lines = count_lines(text);
        free(text);
        if (lines > WALKTHROUGH_MAX_LINES) {
            too_long++;
            fprintf(stderr, "%s has %zu lines, more than %d: move what a reader can do without to a page of notes\n",
                    pages.gl_pathv[k], lines, WALKTHROUGH_MAX_LINES);
        }
    }
    cr_assert_geq(pages.gl_pathc, 15, "expected the walkthroughs of chapters 1 to 15");
    globfree(&pages);
    cr_assert_eq(too_long, 0, "%zu walkthroughs are too long to read in one sitting (see above)", too_long);
}

/* Appends to `out` (a set of anchors, each followed by a newline) the anchor GitHub gives the heading
 * `heading` (n bytes): lower case, spaces as hyphens, other punctuation dropped. Bytes beyond ASCII are
 * dropped too, here and in the links compared with it, so that a heading's "×" or "–" cannot matter. */
static void add_heading_anchor(char *out, size_t size, const char *heading, size_t n) {
    size_t o = strlen(out);
    for (size_t k = 0; k < n && o + 2 < size; k++) {
        unsigned char c = (unsigned char)heading[k];
        if (c >= 'A' && c <= 'Z')
            out[o++] = (char)(c - 'A' + 'a');
        else if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_')
            out[o++] = (char)c;
        else if (c == ' ')
            out[o++] = '-';
    }
    out[o++] = '\n';
    out[o] = '\0';
}

/* The anchors of the page at `path` (its headings outside code blocks, and its <a id="...">), one a
 * line, into `out`. */
static void page_anchors(const char *path, char *out, size_t size) {
    char *text = read_text_file(path);
    out[0] = '\0';
    bool in_code = false;
    for (char *line = text; *line != '\0';) {
        char *end = strchr(line, '\n');
        size_t n = end != NULL ? (size_t)(end - line) : strlen(line);
        if (strncmp(line, "```", 3) == 0)
            in_code = !in_code;
        else if (!in_code && line[0] == '#') {
            size_t hashes = strspn(line, "#");
            if (hashes < n && line[hashes] == ' ')
                add_heading_anchor(out, size, line + hashes + 1, n - hashes - 1);
        }
        for (char *id = strstr(line, "<a id=\""); id != NULL && id < line + n; id = strstr(id + 1, "<a id=\"")) {
            char *close = strchr(id + 7, '"');
            if (close != NULL && strlen(out) + (size_t)(close - id) + 2 < size) {
                strncat(out, id + 7, (size_t)(close - id - 7));
                strcat(out, "\n");
            }
        }
        line += n + (end != NULL);
    }
    free(text);
}

Test(docs, every_link_to_a_section_names_a_heading_that_is_there) {
    /* [text](page.md#anchor) and [text](#anchor) in the docs and README.md: the page must have a heading
     * whose anchor that is, so that moving a section to another page cannot leave links behind. */
    glob_t docs;
    cr_assert_eq(glob("docs/*.md", 0, NULL, &docs), 0);
    static char anchors[1 << 16], wanted[256];
    size_t links = 0, broken = 0;
    for (size_t d = 0; d <= docs.gl_pathc; d++) {
        const char *page = d < docs.gl_pathc ? docs.gl_pathv[d] : "README.md";
        const char *folder = d < docs.gl_pathc ? "docs/" : "";
        char *text = read_text_file(page);
        for (char *at = strstr(text, "]("); at != NULL; at = strstr(at + 2, "](")) {
            char *target = at + 2, *hash = strpbrk(target, "#) \n");
            if (hash == NULL || *hash != '#' || strncmp(target, "http", 4) == 0)
                continue;
            char *end = strpbrk(hash, ") \n");
            if (end == NULL || *end != ')')
                continue;
            char path[512];
            if (hash == target)
                snprintf(path, sizeof path, "%s", page);
            else
                snprintf(path, sizeof path, "%s%.*s", folder, (int)(hash - target), target);
            size_t length = strlen(path);
            if (length < 3 || strcmp(path + length - 3, ".md") != 0)
                continue;
            FILE *f = fopen(path, "rb");
            if (f == NULL)
                continue; /* every_page_links_to_pages_that_exist names it */
            fclose(f);
            page_anchors(path, anchors, sizeof anchors);
            wanted[0] = '\n';
            size_t w = 1;
            for (char *c = hash + 1; c < end && w + 2 < sizeof wanted; c++)
                if ((unsigned char)*c < 0x80)
                    wanted[w++] = *c;
            wanted[w++] = '\n';
            wanted[w] = '\0';
            links++;
            bool found = strncmp(anchors, wanted + 1, w - 1) == 0 || strstr(anchors, wanted) != NULL;
            if (!found) {
                broken++;
                fprintf(stderr, "%s links to %.*s, but %s has no such heading\n", page, (int)(end - target), target,
                        path);
            }
        }
        free(text);
    }
    globfree(&docs);
    cr_assert_gt(links, 50, "only %zu links to sections found", links);
    cr_assert_eq(broken, 0, "%zu links name a section that is not there (see above)", broken);
}

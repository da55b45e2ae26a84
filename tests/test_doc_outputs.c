/* test_doc_outputs.c: the program output that the walkthroughs quote is what the programs print now.
 *
 * A quoted output block is marked by the line `<!-- output of: COMMAND -->` just above its fence.
 * The test runs COMMAND from the repository root (./build/ stands for the build under test) and
 * requires every line of the block to be a line of what it printed, after blanking durations
 * ("in 0.293 s", "25.9 ms") and the padding before them, which vary from run to run where the counters
 * do not. Lines "..." (a cut)
 * and lines starting with "$ " (the command, shown as typed) are not compared. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "test_support.h"

#define MARKER "<!-- output of: "
#define COMMAND_MAX 2048
#define OUTPUT_MAX (1 << 20)

/* Copies the line `line` (length n) into `out`, with every number that is followed by " s" or " ms"
 * replaced by "#" and the blanks before it by one (a right-aligned duration pads to its width: 25.9 ms
 * and 1234.5 ms in one column differ in padding too), and trailing blanks removed. */
static void normalise(const char *line, size_t n, char *out, size_t size) {
    size_t o = 0;
    for (size_t k = 0; k < n && o + 2 < size;) {
        if (isdigit((unsigned char)line[k]) && (k == 0 || !isalnum((unsigned char)line[k - 1]))) {
            size_t end = k;
            while (end < n && (isdigit((unsigned char)line[end]) || line[end] == '.'))
                end++;
            bool duration = (end + 2 <= n && strncmp(line + end, " s", 2) == 0 &&
                             (end + 2 == n || !isalpha((unsigned char)line[end + 2]))) ||
                            (end + 3 <= n && strncmp(line + end, " ms", 3) == 0);
            if (duration) {
                bool padded = o > 0 && out[o - 1] == ' ';
                while (o > 0 && out[o - 1] == ' ')
                    o--;
                if (padded)
                    out[o++] = ' ';
                out[o++] = '#';
                k = end;
                continue;
            }
        }
        out[o++] = line[k++];
    }
    while (o > 0 && (out[o - 1] == ' ' || out[o - 1] == '\r'))
        o--;
    out[o] = '\0';
}

/* True when some line of `output`, normalised, equals the normalised `wanted`. */
static bool printed(const char *output, const char *wanted) {
    char mine[1024];
    for (const char *line = output; *line != '\0';) {
        const char *end = strchr(line, '\n');
        size_t n = end != NULL ? (size_t)(end - line) : strlen(line);
        normalise(line, n, mine, sizeof mine);
        if (strcmp(mine, wanted) == 0)
            return true;
        if (end == NULL)
            break;
        line = end + 1;
    }
    return false;
}

/* Runs `command` with ./build/ replaced by the build under test; returns what it printed. */
static char *run_quoted(const char *command) {
    const char *build = getenv("WHITTED_BUILD");
    build = build != NULL ? build : "build";
    char line[COMMAND_MAX], *o = line;
    for (const char *c = command; *c != '\0' && o < line + sizeof line - 64;) {
        if (strncmp(c, "./build/", 8) == 0) {
            o += snprintf(o, (size_t)(line + sizeof line - o), "./%s/", build);
            c += 8;
        } else {
            *o++ = *c++;
        }
    }
    *o = '\0';
    strncat(line, " 2>&1", sizeof line - strlen(line) - 1);
    FILE *pipe = popen(line, "r");
    cr_assert_not_null(pipe);
    char *output = malloc(OUTPUT_MAX);
    size_t length = fread(output, 1, OUTPUT_MAX - 1, pipe);
    output[length] = '\0';
    pclose(pipe);
    return output;
}

static void check_page(const char *page) {
    char *text = read_text_file(page);
    size_t blocks = 0, stale = 0;
    for (char *at = strstr(text, MARKER); at != NULL; at = strstr(at + 1, MARKER)) {
        char *command = at + strlen(MARKER);
        char *command_end = strstr(command, " -->");
        cr_assert_not_null(command_end, "%s: an output marker is not closed", page);
        char *fence = strstr(command_end, "```\n");
        cr_assert_not_null(fence, "%s: no block after the marker", page);
        char *block = fence + 4, *block_end = strstr(block, "```");
        cr_assert_not_null(block_end, "%s: a block is never closed", page);
        *command_end = '\0';
        char *output = run_quoted(command);
        blocks++;
        for (char *line = block; line < block_end;) {
            char *end = strchr(line, '\n');
            size_t n = (size_t)(end - line);
            char wanted[1024];
            normalise(line, n, wanted, sizeof wanted);
            bool skipped = wanted[0] == '\0' || strcmp(wanted, "...") == 0 || strncmp(wanted, "$ ", 2) == 0;
            if (!skipped && !printed(output, wanted)) {
                stale++;
                fprintf(stderr, "%s: `%s` no longer prints: %s\n", page, command, wanted);
            }
            line = end + 1;
        }
        free(output);
        *command_end = ' ';
    }
    free(text);
    cr_assert_gt(blocks, 0, "%s has no marked output block", page);
    cr_assert_eq(stale, 0, "%s: %zu quoted output lines differ from what the programs print (see above)", page,
                 stale);
}

/* The pages with quoted output, one test each so that they run side by side. The names are held in
 * the array itself, not pointed to: each test runs in a fresh process, where addresses differ. */
struct page {
    char path[64];
};
static struct page pages[] = {
    {"docs/01-camera.md"}, {"docs/02-sphere.md"}, {"docs/03-triangle.md"}, {"docs/04-plane.md"},
    {"docs/05-aabb.md"},   {"docs/06-phong.md"},  {"docs/07-shadows.md"},  {"docs/08-recursion.md"},
    {"docs/09-kdtree.md"}, {"docs/10-bvh.md"}, {"docs/11-fast.md"}, {"docs/12-antialias.md"},
    {"docs/13-distributed.md"}, {"docs/14-textures.md"}, {"docs/15-paths.md"},
};

ParameterizedTestParameters(doc_outputs, quoted_output_is_what_the_program_prints) {
    return cr_make_param_array(struct page, pages, sizeof pages / sizeof pages[0]);
}

ParameterizedTest(struct page *page, doc_outputs, quoted_output_is_what_the_program_prints, .timeout = 300) {
    check_page(page->path);
}

Test(doc_outputs, a_changed_counter_is_noticed) {
    /* The check must be able to fail: a block quoting a counter one higher than the program prints. */
    char *output = run_quoted("./build/chapter-01 -o out/test/doc-outputs-01.png");
    char wanted[256];
    const char *wrong = "  primary rays               76801", *right = "  primary rays               76800";
    const char *other_time = "chapter 1 (camera): wrote out/test/doc-outputs-01.png (320 x 240) in 9.999 s";
    normalise(wrong, strlen(wrong), wanted, sizeof wanted);
    cr_assert(!printed(output, wanted), "a wrong counter matched");
    normalise(right, strlen(right), wanted, sizeof wanted);
    cr_assert(printed(output, wanted), "the right counter did not match:\n%s", output);
    normalise(other_time, strlen(other_time), wanted, sizeof wanted);
    cr_assert(printed(output, wanted), "a different duration should not matter:\n%s", output);
    /* nor a wider one, whose right-aligned column starts earlier (a build of over a second) */
    char narrow[64], wide[64];
    normalise("  build                    84.2 ms", strlen("  build                    84.2 ms"), narrow, sizeof narrow);
    normalise("  build                  1084.2 ms", strlen("  build                  1084.2 ms"), wide, sizeof wide);
    cr_assert_str_eq(narrow, wide);
    free(output);
}

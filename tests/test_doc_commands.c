/* test_doc_commands.c: every command the docs give a reader runs as written.
 *
 * The commands are taken from the pages in their order: each line of a plain ``` block that starts
 * with `make `, `./build/` or `$ ` (a prompt, dropped), and each inline `./build/...` command of the
 * text. They run one after another, page by page, in a fresh copy of the repository as the README's quick
 * start leaves it (programs built, an empty out/), so they can write where they like without touching
 * this checkout; ./build/ stands for the build under test.
 * A command must exit with status 0, unless the text right after it says "exit status N" or "exits
 * with status N". Not run: `make` targets that run the test suite or other long jobs (test, compare,
 * references, bench, results, fuzz), which have tests of their own, and commands with a placeholder in
 * capitals (SCENE, FILE). */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "test_support.h"

#define COMMAND_MAX 2048
#define COMMANDS_MAX 64
#define STATUS_WINDOW 200 /* characters after a command searched for its expected exit status */

struct command {
    char text[COMMAND_MAX];
    int expected_status;
};

/* The make targets that are not run here. */
static bool is_long_make(const char *command) {
    static const char *const long_targets[] = {"test", "compare", "references", "bench", "results", "fuzz",
                                               "check", "student", "gallery", "figures"};
    if (strncmp(command, "make ", 5) != 0)
        return false;
    const char *target = command + 5;
    for (size_t k = 0; k < sizeof long_targets / sizeof long_targets[0]; k++) {
        size_t n = strlen(long_targets[k]);
        if (strncmp(target, long_targets[k], n) == 0 && (target[n] == '\0' || target[n] == ' ' || target[n] == '-'))
            return true;
    }
    return false;
}

/* True when the command has a placeholder: a word of two or more capitals, such as SCENE or FILE. */
static bool has_placeholder(const char *command) {
    for (const char *c = command; *c != '\0'; c++)
        if (isupper((unsigned char)c[0]) && isupper((unsigned char)c[1]) && (c == command || !isalnum((unsigned char)c[-1])))
            return true;
    return false;
}

/* The status that `text` (at most STATUS_WINDOW characters of it, and with `up_to_code` only up to the
 * next code span or block) says a command ends with, or 0. */
static int expected_status_in(const char *text, bool up_to_code) {
    char window[STATUS_WINDOW + 1];
    snprintf(window, sizeof window, "%s", text);
    char *tick = strchr(window, '`');
    if (up_to_code && tick != NULL)
        *tick = '\0';
    char *newline = strchr(window, '\n');
    if (!up_to_code && newline != NULL)
        *newline = '\0';
    static const char *const phrases[] = {"exit status ", "exits with status "};
    for (size_t k = 0; k < 2; k++) {
        const char *at = strstr(window, phrases[k]);
        if (at != NULL && isdigit((unsigned char)at[strlen(phrases[k])]))
            return atoi(at + strlen(phrases[k]));
    }
    return 0;
}

static void add(struct command *list, int *count, const char *start, size_t n, int expected_status) {
    while (n > 0 && isspace((unsigned char)start[n - 1]))
        n--;
    if (strncmp(start, "$ ", 2) == 0) {
        start += 2;
        n -= 2;
    }
    char text[COMMAND_MAX];
    snprintf(text, sizeof text, "%.*s", (int)n, start);
    char *comment = strstr(text, "  #"); /* "make chapter-1    # or, after ..." */
    if (comment != NULL)
        *comment = '\0';
    for (size_t len = strlen(text); len > 0 && text[len - 1] == ' '; len--)
        text[len - 1] = '\0';
    if (text[0] == '\0' || is_long_make(text) || has_placeholder(text) || strcmp(text, "./build/compare") == 0)
        return;
    cr_assert_lt(*count, COMMANDS_MAX, "too many commands on one page");
    snprintf(list[*count].text, sizeof list[*count].text, "%s", text);
    list[*count].expected_status = expected_status;
    (*count)++;
}

/* Collects the commands of `text` in page order. */
static int collect(const char *text, struct command *list) {
    int count = 0, block_status = 0;
    bool in_block = false, plain_block = false;
    const char *previous = NULL; /* the last line of text before this one */
    for (const char *line = text; *line != '\0';) {
        const char *end = strchr(line, '\n');
        size_t n = end != NULL ? (size_t)(end - line) : strlen(line);
        const char *next = end != NULL ? end + 1 : line + n;
        if (strncmp(line, "```", 3) == 0) {
            plain_block = !in_block && n == 3;
            /* A block's commands end as the sentence that introduces it says ("..., with exit status 1:"). */
            block_status = previous != NULL && !in_block ? expected_status_in(previous, false) : 0;
            in_block = !in_block;
        } else if (in_block && plain_block) {
            if (strncmp(line, "make ", 5) == 0 || strncmp(line, "./build/", 8) == 0 ||
                strncmp(line, "$ ", 2) == 0)
                add(list, &count, line, n, block_status);
        } else if (!in_block) {
            for (const char *tick = memchr(line, '`', n); tick != NULL && tick < line + n;) {
                const char *close = memchr(tick + 1, '`', (size_t)(line + n - tick - 1));
                if (close == NULL)
                    break;
                if (strncmp(tick + 1, "./build/", 8) == 0)
                    add(list, &count, tick + 1, (size_t)(close - tick - 1), expected_status_in(close + 1, true));
                tick = memchr(close + 1, '`', (size_t)(line + n - close - 1));
            }
        }
        if (n > 0 && strncmp(line, "<!--", 4) != 0) /* blank lines and markers do not introduce a block */
            previous = line;
        line = next;
    }
    return count;
}

/* Runs `command` in `dir` with ./build/ replaced by the build under test; returns its exit status. */
static int run_in(const char *dir, const char *command, const char *log) {
    const char *build = getenv("WHITTED_BUILD");
    build = build != NULL ? build : "build";
    char line[COMMAND_MAX * 2], *o = line;
    o += snprintf(o, sizeof line, "cd %s && env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS timeout 300 sh -c '", dir);
    for (const char *c = command; *c != '\0' && o < line + sizeof line - 256;) {
        if (strncmp(c, "./build/", 8) == 0) {
            o += snprintf(o, (size_t)(line + sizeof line - o), "./%s/", build);
            c += 8;
        } else if (*c == '\'') {
            o += snprintf(o, (size_t)(line + sizeof line - o), "'\\''");
            c++;
        } else {
            *o++ = *c++;
        }
    }
    snprintf(o, (size_t)(line + sizeof line - o), "' >>%s 2>&1", log);
    int status = system(line);
    return status == -1 || !WIFEXITED(status) ? -1 : WEXITSTATUS(status);
}

struct page {
    char path[64];
};
static struct page pages[] = {
    {"docs/01-camera.md"}, {"docs/02-sphere.md"},   {"docs/03-triangle.md"}, {"docs/04-plane.md"},
    {"docs/05-aabb.md"},   {"docs/06-phong.md"},    {"docs/07-shadows.md"},  {"docs/08-recursion.md"},
    {"docs/09-kdtree.md"}, {"docs/povray.md"},      {"docs/scene-format.md"}, {"docs/gallery.md"},
    {"docs/seed.md"},      {"docs/10-bvh.md"},     {"docs/fuzzing.md"},     {"docs/11-fast.md"},
    {"docs/12-antialias.md"}, {"docs/13-distributed.md"}, {"docs/14-textures.md"}, {"docs/15-paths.md"},
    {"docs/kdtree-notes.md"}, {"docs/16-instances.md"},
};

ParameterizedTestParameters(doc_commands, every_command_runs_as_written) {
    return cr_make_param_array(struct page, pages, sizeof pages / sizeof pages[0]);
}

ParameterizedTest(struct page *page, doc_commands, every_command_runs_as_written, .timeout = 600) {
    char *text = read_text_file(page->path);
    static struct command commands[COMMANDS_MAX];
    int count = collect(text, commands);
    free(text);
    /* A copy of the repository as a reader has it: sources, scenes, models and the built programs. */
    char dir[] = "/tmp/whitted-doc-commands-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char log[256], copy[COMMAND_MAX];
    snprintf(log, sizeof log, "%s.log", dir);
    remove(log);
    /* What the commands need, copied file by file: other tests write into build/ and scenes/ while
     * this one runs, and an archiver would stop at a file that changes under it. */
    snprintf(copy, sizeof copy,
             "cd %s && mkdir out scenes build && cd - >/dev/null && "
             "cp -rp --parents Makefile common chapters tools tests/support bench fuzz docs %s/ && cp -p scenes/*.scene %s/scenes/ && "
             "cp -rp scenes/models scenes/textures %s/scenes/ && "
             "for b in build build/san; do [ -d $b/common ] || continue; mkdir -p %s/$b && "
             "cp -rp $b/common $b/chapters $b/tools %s/$b/ && cp -p $b/chapter-* $b/compare $b/assemble %s/$b/ && { [ ! -e $b/inset ] || cp -p $b/inset %s/$b/; }; "
             "done >>%s 2>&1",
             dir, dir, dir, dir, dir, dir, dir, dir, log);
    cr_assert_eq(system(copy), 0, "could not copy the repository (see %s)", log);
    int failed = 0;
    for (int k = 0; k < count; k++) {
        FILE *l = fopen(log, "a");
        if (l != NULL) {
            fprintf(l, "$ %s\n", commands[k].text);
            fclose(l);
        }
        int status = run_in(dir, commands[k].text, log);
        if (status != commands[k].expected_status) {
            failed++;
            fprintf(stderr, "%s: `%s` exited with %d, the text expects %d (output in %s)\n", page->path,
                    commands[k].text, status, commands[k].expected_status, log);
        }
    }
    snprintf(copy, sizeof copy, "rm -rf %s", dir);
    cr_assert_eq(system(copy), 0);
    cr_assert_eq(failed, 0, "%s: %d of its %d commands do not run as written (see above)", page->path, failed, count);
    if (failed == 0)
        remove(log);
}

Test(doc_commands, commands_and_their_statuses_are_found) {
    /* The collector on a page written for the purpose: a plain block with a prompt, a comment and a long
     * make target, a C block (ignored), and inline commands, one of them expected to fail. */
    const char *page = "Run it:\n\n```\n$ make chapter-1      # or ./build/chapter-01\nmake test\n```\n\n"
                       "```c\n./build/not-a-command\n```\n\n"
                       "Then `./build/compare a.png b.png` (it exits with status 1: they differ), and "
                       "`./build/chapter-02 SCENE` with your own scene.\n";
    static struct command found[COMMANDS_MAX];
    int count = collect(page, found);
    cr_assert_eq(count, 2);
    cr_assert_str_eq(found[0].text, "make chapter-1");
    cr_assert_eq(found[0].expected_status, 0);
    cr_assert_str_eq(found[1].text, "./build/compare a.png b.png");
    cr_assert_eq(found[1].expected_status, 1);
}

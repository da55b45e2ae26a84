/* test_coursework_long.c: the coursework kit on student copies made by make student (docs/coursework.md),
 * the long proofs (make test-long): each builds a copy, starting from this build's objects so that only
 * what the copy changes is compiled again.
 *
 *  - A fresh hand-out copy is a git repository with one first commit and a README for the student, holds
 *    no model answer (no answer file, no line of a blanked body anywhere, the gallery without its diffs),
 *    builds, grades every task todo, says where each build exercise starts without POV-Ray, passes its own
 *    make test, and prints the scoreboard docs/coursework.md quotes. make student refuses a folder that
 *    is not a copy, and keeps a file the student changed.
 *  - In a copy, a crash and an endless loop planted in two task bodies each give a FAIL line and the
 *    whole scoreboard within a minute, and make check goes on to the next chapters; a slab test that lets
 *    a NaN win, a forgotten test counter and forgotten slivers are each not done.
 *  - Every marked task's checks fail on its stub and pass with its reference body (and those of the
 *    tasks it needs); a picture mirrored outside every task is named by the picture check.
 *  - Each picture check needs exactly the tasks its chapter's program runs on its scene. */
#include <criterion/criterion.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "test_support.h"

/* The time a planted crash and a planted endless loop may take, from make check-2 to its scoreboard. */
#define COURSEWORK_PLANTED_SECONDS 60

static const char *build(void) { return getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build"; }
static int san(void) { return strstr(build(), "san") != NULL; }

/* Runs the shell command made from format with its output appended to log; returns its exit status. */
static int run(const char *log, const char *format, ...) __attribute__((format(printf, 2, 3)));
static int run(const char *log, const char *format, ...) {
    char command[8192];
    va_list args;
    va_start(args, format);
    vsnprintf(command, sizeof command, format, args);
    va_end(args);
    return run_logged(command, log);
}

/* The output of the shell command made from format (standard output and error), malloc'd. */
static char *output_of(int *status, const char *format, ...) __attribute__((format(printf, 2, 3)));
static char *output_of(int *status, const char *format, ...) {
    char command[8192];
    va_list args;
    va_start(args, format);
    command[0] = '(';
    vsnprintf(command + 1, sizeof command - 3, format, args);
    strcat(command, ")");
    va_end(args);
    char *out = malloc(1 << 20);
    int s = run_capturing(command, out, 1 << 20);
    if (status != NULL)
        *status = s;
    return out;
}

/* make in `dir`, alone: not a sub-make of make test, and not inside a Criterion worker (BXFI_MAP would
 * make the copy's own run-tests take itself for one, and abort). */
#define MAKE_IN "env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS -u BXFI_MAP make --no-print-directory -C"

/* The lines of the code block that follows the paragraph ending in `intro` in docs/coursework.md
 * (between its fences), malloc'd. */
static char *quoted_block(const char *intro) {
    return output_of(NULL, "awk -v intro='%s' 'index($0, intro) && index($0, intro) == length($0) - length(intro) + 1 "
                           "{ on = 1; next } on && /^```$/ { if (++fences == 2) exit; next } on && fences == 1' "
                           "docs/coursework.md", intro);
}

/* Makes a new empty folder *dir, /tmp/whitted-coursework-NAME-XXXXXX (outside the repository, as make
 * student requires), and names its log *log under out/test/. */
static void new_folder(char dir[static 64], char log[static 80], const char *name) {
    snprintf(dir, 64, "/tmp/whitted-coursework-%s-XXXXXX", name);
    cr_assert_not_null(mkdtemp(dir));
    snprintf(log, 80, "out/test/%s.log", strrchr(dir, '/') + 1);
    remove(log);
}

/* Makes a student copy of the repository with `tasks` blanked (options: "--answers") in a new folder
 * *dir (outside the repository, as make student requires), its log in *log (under out/test/), and
 * seeds its build with this build's objects, generated models and chapter 14's drawn pictures: older
 * than the blanked files, so that only those are compiled again. */
static void make_copy(char dir[static 64], char log[static 80], const char *tasks, const char *options) {
    new_folder(dir, log, "copy");
    cr_assert_eq(run(log, "tools/student.sh %s '%s' %s", dir, tasks, options), 0,
                 "make student failed: see %s", log);
    cr_assert_eq(run(log, "mkdir -p %1$s/%2$s && cp -rp %2$s/common %2$s/chapters %2$s/tools %2$s/checks %2$s/tests "
                          "%1$s/%2$s/ && (cp -p build/teapot %1$s/build/ 2>/dev/null; cp -p scenes/models/teapot-*.ply "
                          "%1$s/scenes/models/ 2>/dev/null; cp -rp scenes/textures %1$s/scenes/ 2>/dev/null; "
                          "cp -rp %2$s/fuzz %1$s/%2$s/ 2>/dev/null; true)",
                     dir, build()),
                 0, "cannot seed the copy's build: see %s", log);
}

/* Removes the copy; its log stays, for a failure to point at. */
static void remove_copy(const char *dir, const char *log) { run(log, "rm -rf %s", dir); }

/* Builds the grader and chapter `chapter`'s program in the copy. */
static void build_in(const char *dir, const char *log, int chapter) {
    cr_assert_eq(run(log, MAKE_IN " %s SAN=%d -j2 %s/check %s/chapter-%02d", dir, san(), build(), build(), chapter), 0,
                 "the copy does not build: see %s", log);
}

/* The marked tasks, "1.1 1.P ..." without the pictures: "1.1 2.1 2.2 ...". */
static char *marked_tasks(void) {
    char *list = output_of(NULL, "tools/student.sh --list | cut -d' ' -f1 | tr '\\n' ' '");
    return list;
}

/* Every marked task but those in `except` (space-separated), for student.sh: the tasks to blank. */
static void all_but(const char *except, char *out, size_t size) {
    char *all = marked_tasks();
    out[0] = '\0';
    char id[16];
    int used;
    for (const char *p = all; sscanf(p, "%15s%n", id, &used) == 1; p += used) {
        char padded[20];
        snprintf(padded, sizeof padded, " %s ", id);
        char wanted[1024];
        snprintf(wanted, sizeof wanted, " %s ", except);
        if (strstr(wanted, padded) == NULL)
            snprintf(out + strlen(out), size - strlen(out), "%s ", id);
    }
    free(all);
    if (out[0] == '\0')
        snprintf(out, size, "none");
}

/* Lines of a blanked body that may stay elsewhere in a hand-out: idioms that say nothing of the answer (a
 * loop over the three axes, a zero colour, a counter), each found in code that is no task's. Anything
 * else of a body that the copy holds gives the answer away. */
static const char *const idioms[] = {
    "for (int a = 0; a < 3; a++)", "for (int a = 0; a < 3; a++) {", "for (int axis = 0; axis < 3; axis++) {",
    "for (int a = 0; a < n; a++)", "for (int b = 0; b < n; b++)", "for (int k = 0; k < FAST_BVH_WIDTH; k++) {",
    "for (int k = 0; k < slots; k++) {", "for (size_t k = 0; k < t->count; k++)",
    "for (size_t k = 0; k < t->count; k++) {", "for (size_t k = 0; k < s->light_count; k++) {",
    "return vec3_make(0, 0, 0);", "return vec3_make(0.0, 0.0, 0.0);", "if (!(vec3_length(h) > 0.0))",
    "vec3 sum = vec3_make(0, 0, 0);", "struct hit h = hit_nothing(INFINITY);",
    "struct material painted;", "struct bsdf b = bsdf_of_material(m);", "const struct world *w = world;", "const struct kd_node *n = &k->nodes[index];",
    "stats_thread.box_tests++;", "stats_thread.adc_saves++;", "stats_thread.budget_cut++;",
    "uint32_t n = r->end - r->begin;", "float4 c = centroid_of(&p);", "struct aabb bounds = {b->min, b->max};",
    /* the watertight test of common/triangle.h, which chapter 3 has the student read (docs/coursework.md) */
    "double inv_det = 1.0 / det;", "if (area.x == 0.0 && area.y == 0.0 && area.z == 0.0)",
    "if (!(hit_t > t_min && hit_t < t_max))",
    /* chapter 11's walks, the same idea as 10.3 made 4- and 8-wide, which chapter 11 teaches after it */
    "uint32_t slivers = (uint32_t)(b->triangle_count - b->tree_count);",
    /* chapter 16's declarations and loops, which say nothing of how its tasks are done */
    "const uint32_t *c = m->faces[face].v;",
    "for (uint32_t i = node->first; i < node->first + node->count; i++)", "struct aabb box = aabb_empty();",
    "struct instance_bvh_node *node = &b->nodes[k];", "vec3 point = ray_at(r, h.t);",
    "const struct instance *it = &in->items[k];",
};

Test(coursework_long, no_line_of_a_blanked_body_is_left_in_a_hand_out, .timeout = 600) {
    /* Every task blanked: each line of 24 characters or more of a blanked body (a task's, or one that
     * goes with it), after its signature and but for comments, must appear nowhere in the copy: not in
     * another function, a figure, a test or a page. */
    char dir[64], log[80];
    new_folder(dir, log, "leak");
    cr_assert_eq(run(log, "tools/student.sh %s all", dir), 0, "make student failed: see %s", log);
    char allowed[] = "/tmp/whitted-coursework-idioms-XXXXXX";
    int fd = mkstemp(allowed);
    cr_assert_geq(fd, 0);
    FILE *to = fdopen(fd, "w");
    for (size_t k = 0; k < sizeof idioms / sizeof idioms[0]; k++)
        fprintf(to, "%s\n", idioms[k]);
    fclose(to);
    char *bodies = output_of(NULL,
        "for f in $(tools/student.sh --files); do "
        "awk '/^\\/\\* TASK [0-9]+\\.[0-9]+( ALSO)?: .* \\*\\/$/ { signature = 1; next } "
        "signature { if ($0 ~ /\\{[ \\t]*$/) { signature = 0; body = 1 } next } "
        "body && /^}$/ { body = 0 } "
        "body { sub(/^[ \\t]+/, \"\"); if (length($0) >= 24 && $0 !~ /^(\\/\\*|\\*)/) print }' $f; done | "
        "sort -u | grep -vxF -f %s | wc -l", allowed);
    cr_expect_gt(atoi(bodies), 100, "only %s lines of blanked bodies to look for", bodies);
    free(bodies);
    char *leaks = output_of(NULL,
        "for f in $(tools/student.sh --files); do "
        "awk '/^\\/\\* TASK [0-9]+\\.[0-9]+( ALSO)?: .* \\*\\/$/ { id = $3; sub(/:$/, \"\", id); signature = 1; next } "
        "signature { if ($0 ~ /\\{[ \\t]*$/) { signature = 0; body = 1 } next } "
        "body && /^}$/ { body = 0 } "
        "body { sub(/^[ \\t]+/, \"\"); if (length($0) >= 24 && $0 !~ /^(\\/\\*|\\*)/) print id \"\\t\" $0 }' $f; "
        "done | sort -u | while IFS=\"$(printf '\\t')\" read -r id line; do "
        "  printf '%%s\\n' \"$line\" | grep -qxF -f %2$s && continue; "
        "  grep -rlF --exclude-dir=.git -- \"$line\" %1$s | "
        "  while IFS= read -r file; do printf 'task %%s %%s  in %%s\\n' \"$id\" \"$line\" \"${file#%1$s/}\"; done; "
        "done", dir, allowed);
    cr_expect_str_eq(leaks, "", "lines of blanked bodies found in the hand-out (blank what gives the answer away "
                     "with a /* TASK N.K ALSO: */ marker, or rewrite it):\n%s", leaks);
    free(leaks);
    remove(allowed);
    remove_copy(dir, log);
}

Test(coursework_long, a_lecturers_copy_holds_every_blanked_function_whole, .timeout = 600) {
    /* ANSWERS=1, every task blanked: docs/model-answers.md holds each blanked function (a task's, or one
     * that goes with it) whole, as the reference has it; the lecturer's guide is there, the CI is not. */
    char dir[64], log[80];
    new_folder(dir, log, "answers");
    cr_assert_eq(run(log, "tools/student.sh %s all --answers", dir), 0, "make student ANSWERS=1 failed: see %s", log);
    int status;
    char *missing = output_of(&status,
        "awk 'FNR == NR { answers = answers $0 \"\\n\"; next } "
        "/^\\/\\* TASK [0-9]+\\.[0-9]+( ALSO)?: .* \\*\\/$/ { body = 1; text = \"\"; functions++; next } "
        "body { text = text $0 \"\\n\"; if ($0 == \"}\") { body = 0; "
        "if (!index(answers, text)) print FILENAME \": \" substr(text, 1, index(text, \"(\")) } } "
        "END { print \"functions=\" functions }' %1$s/docs/model-answers.md $(tools/student.sh --files) && "
        "ls %1$s/docs/coursework.md && ! ls -d %1$s/.ci %1$s/.github 2>/dev/null", dir);
    char expected[96];
    snprintf(expected, sizeof expected, "%s/docs/coursework.md", dir);
    const char *count = strstr(missing, "functions=");
    cr_expect(status == 0 && strstr(missing, ": ") == NULL && strstr(missing, expected) != NULL && count != NULL &&
              atoi(count + strlen("functions=")) >= 28,
              "the lecturer's copy (status %d): functions missing from docs/model-answers.md, then the count:\n%s",
              status, missing);
    free(missing);
    remove_copy(dir, log);
}

Test(coursework_long, a_fresh_copy_is_a_hand_out_that_builds_and_passes_its_make_test, .timeout = 1800) {
    char dir[64], log[80];
    make_copy(dir, log, "all", "");

    /* A git repository with one first commit, nothing left over. */
    char *count = output_of(NULL, "git -C %s rev-list --count HEAD && git -C %s status --porcelain", dir, dir);
    cr_expect_str_eq(count, "1\n", "the copy's history, then its status:\n%s", count);
    free(count);

    /* A README for the student. */
    char readme[128];
    snprintf(readme, sizeof readme, "%s/README.md", dir);
    char *text = read_text_file(readme);
    cr_expect(strstr(text, "make check-1") != NULL && strstr(text, "## How grading works") != NULL &&
              strstr(text, "make exercises") != NULL && strstr(text, "| 2.1 | ray-sphere intersection") != NULL,
              "the copy's README is not the student's:\n%s", text);
    free(text);

    /* No model answer: no answer file, and the gallery without its diffs (no line of a blanked body
     * anywhere: the next test). */
    static const char *const answers[] = {"tests/exercises/solutions.c", "tests/exercises/solutions.h",
                                          "tests/exercises/test_exercise_proof.c", "tools/gallery", "tests/checks/faults",
                                          "tests/mutants",
                                          "tests/test_gallery.c", "tests/test_coursework_proof.c",
                                          "tests/test_coursework_long.c"};
    for (size_t k = 0; k < sizeof answers / sizeof answers[0]; k++) {
        char path[256];
        snprintf(path, sizeof path, "%s/%s", dir, answers[k]);
        struct stat st;
        cr_expect_neq(stat(path, &st), 0, "the hand-out holds %s", answers[k]);
    }
    int status;
    char *diffs = output_of(NULL, "grep -c '^```diff' %s/docs/gallery.md", dir);
    cr_expect_str_eq(diffs, "0\n", "the hand-out's gallery shows the faults' diffs");
    free(diffs);

    /* It builds; every task is todo; the build exercises say where to start, needing no POV-Ray. */
    char *graded = output_of(&status, MAKE_IN " %s SAN=%d -j2 check", dir, san());
    cr_expect(status != 0 && strstr(graded, "\nscoreboard\n") != NULL && strstr(graded, "0 of ") != NULL &&
              strstr(graded, " done ") == NULL, "make check in the hand-out (status %d):\n%s", status, graded);
    free(graded);
    char *exercises = output_of(&status, MAKE_IN " %s SAN=%d exercises", dir, san());
    cr_expect(status == 0 && strstr(exercises, "exercises: 0 done, 0 failing, ") != NULL &&
              strstr(exercises, " not started") != NULL,
              "make exercises in the hand-out (status %d):\n%s", status, exercises);
    free(exercises);
    char *dry = output_of(NULL, MAKE_IN " %s SAN=%d -n exercises | grep -E '(^|[;&|] *)povray |criterion|run-tests'",
                          dir, san());
    cr_expect_str_eq(dry, "", "make exercises would run POV-Ray or the test suite:\n%s", dry);
    free(dry);

    /* The scoreboard docs/coursework.md quotes for a fresh copy, line for line. */
    char *quoted = quoted_block("In a fresh student copy, `make check-2` ends with:");
    char *fresh = output_of(NULL, MAKE_IN " %s SAN=%d check-2 2>&1 | sed -n '/^scoreboard$/,/tasks done$/p'", dir, san());
    cr_expect(strlen(quoted) > 20 && strcmp(quoted, fresh) == 0,
              "docs/coursework.md quotes\n%s\nbut make check-2 in a fresh copy ends with\n%s", quoted, fresh);
    free(quoted);
    free(fresh);

    /* Its own make test passes. */
    cr_expect_eq(run(log, MAKE_IN " %s SAN=%d -j2 test", dir, san()), 0, "make test fails in the hand-out: see %s",
                 log);

    /* make student again: a file the student changed is kept and named; one the student did not change
     * is brought back to the kit's version (docs/seed.md, which a hand-out copies as it is). */
    char *again = output_of(&status, "echo '/* mine */' >>%1$s/common/sphere.c && echo 'x' >%1$s/docs/seed.md && "
                                     "sed -i \"s|^[0-9a-f]*  docs/seed.md$|$(sha1sum <%1$s/docs/seed.md | cut -c1-40)  "
                                     "docs/seed.md|\" %1$s/.student-copy && tools/student.sh %1$s all && "
                                     "tail -n 1 %1$s/common/sphere.c && cmp %1$s/docs/seed.md docs/seed.md && echo same",
                            dir);
    cr_expect(status == 0 && strstr(again, "kept 1 file(s)") != NULL && strstr(again, "  common/sphere.c\n") != NULL &&
              strstr(again, "/* mine */\n") != NULL && strstr(again, "\nsame\n") != NULL,
              "make student run again over the copy (status %d):\n%s", status, again);
    free(again);

    /* ANSWERS=1: a lecturer's copy keeps the model answers, the patches and the walkthroughs' quotes. */
    char *lecturer = output_of(&status, "tools/student.sh %1$s.answers all --answers >/dev/null && "
                                        "ls %1$s.answers/tests/exercises/solutions.c %1$s.answers/tools/gallery/*.patch | "
                                        "wc -l && cmp docs/02-sphere.md %1$s.answers/docs/02-sphere.md && echo same; "
                                        "rm -rf %1$s.answers", dir);
    cr_expect(status == 0 && atoi(lecturer) >= 13 && strstr(lecturer, "\nsame\n") != NULL,
              "make student ANSWERS=1 (status %d):\n%s", status, lecturer);
    free(lecturer);

    /* It refuses a folder that is not empty and is not a copy. */
    char *refused = output_of(&status, "mkdir -p %1$s.other && touch %1$s.other/notes.txt && tools/student.sh %1$s.other; "
                                       "refused=$?; rm -rf %1$s.other; exit $refused", dir);
    cr_expect(status != 0 && strstr(refused, "is not empty and is not a student copy") != NULL,
              "make student into a folder of other files (status %d):\n%s", status, refused);
    free(refused);
    remove_copy(dir, log);
}

/* Restores the bodies of `tasks` in the copy (the others stay blanked) and applies the fault patches. */
static void plant(const char *dir, const char *log, const char *tasks, const char *patches) {
    char blank[1024];
    all_but(tasks, blank, sizeof blank);
    cr_assert_eq(run(log, "tools/student.sh %s '%s' --sources-only && for p in %s; do git -C %s apply $PWD/$p || "
                          "exit 1; done", dir, blank, patches, dir),
                 0, "cannot plant %s: see %s", patches, log);
}

static double seconds_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

Test(coursework_long, a_planted_crash_and_endless_loop_leave_a_full_scoreboard_within_a_minute, .timeout = 1800) {
    char dir[64], log[80];
    make_copy(dir, log, "all", "");
    plant(dir, log, "2.1 2.2", "tests/checks/faults/02-normal-crashes.patch tests/checks/faults/02-sphere-never-returns.patch");
    build_in(dir, log, 2);
    double start = seconds_now();
    int status;
    char *report = output_of(&status, MAKE_IN " %s SAN=%d check-2", dir, san());
    double took = seconds_now() - start;
    cr_expect_lt(took, COURSEWORK_PLANTED_SECONDS, "make check-2 took %.0f s:\n%s", took, report);
    const char *crashed = san() ? "sphere_normal stopped the program" : "sphere_normal crashed (segmentation fault";
    cr_expect(strstr(report, "  FAIL  2.2: the unit outward normal\n        ") != NULL && strstr(report, crashed) != NULL,
              "no FAIL line for the crash:\n%s", report);
    cr_expect_not_null(strstr(report, "sphere_intersect did not finish within 5 s on a ray starting at the centre"),
                       "no FAIL line for the endless loop:\n%s", report);
    if (!san()) { /* docs/coursework.md quotes the crash's FAIL line */
        char *quoted = quoted_block("so a crash names them:");
        cr_expect(strlen(quoted) > 20 && strstr(report, quoted) != NULL,
                  "docs/coursework.md quotes\n%s\nbut make check-2 with the crash planted says\n%s", quoted, report);
        free(quoted);
    }
    cr_expect(strstr(report, "\nscoreboard\n  2.1   todo ") != NULL && strstr(report, "\n  2.P   todo ") != NULL &&
              strstr(report, "\n0 of 3 tasks done") != NULL, "no whole scoreboard:\n%s", report);
    free(report);
    /* make check goes on to the next chapters: every task has its line, the last chapter's picture too. */
    char *last = output_of(NULL, "cd %s && ./%s/check --list | tail -n 1 | tr -d '\\n'", dir, build());
    char *tasks = output_of(NULL, "cd %s && ./%s/check --list | wc -l | tr -d ' \\n'", dir, build());
    char last_line[64], count_line[64];
    snprintf(last_line, sizeof last_line, "\n  %-5s todo ", last);
    snprintf(count_line, sizeof count_line, "\n0 of %s tasks done", tasks);
    report = output_of(&status, MAKE_IN " %s SAN=%d -j2 check", dir, san());
    cr_expect(strstr(report, last_line) != NULL && strstr(report, count_line) != NULL,
              "make check with the crash and the loop planted (expected \"%s\" and \"%s\"):\n%s", last_line + 1,
              count_line + 1, report);
    free(report);
    free(last);
    free(tasks);
    remove_copy(dir, log);
}

Test(coursework_long, a_nan_slab_a_forgotten_counter_and_forgotten_slivers_are_not_done_in_a_copy, .timeout = 1800) {
    char dir[64], log[80];
    make_copy(dir, log, "all", "");
    static const struct {
        const char *task, *restore, *patch, *says;
    } planted[] = {
        {"5.1", "5.1", "tests/checks/faults/05-slab-nan-wins.patch", "it said the ray misses: a NaN?"},
        {"2.1", "2.1", "tests/checks/faults/02-sphere-test-not-counted.patch", "the line that counts it is missing"},
        {"10.3", "5.1 10.2 10.3", "tests/checks/faults/10-bvh-slivers-forgotten.patch", "Needle-thin triangles"},
    };
    for (size_t k = 0; k < sizeof planted / sizeof planted[0]; k++) {
        plant(dir, log, planted[k].restore, planted[k].patch);
        build_in(dir, log, atoi(planted[k].task));
        int status;
        char *report = output_of(&status, "cd %s && WHITTED_BUILD=%s ./%s/check --task %s", dir, build(), build(),
                                 planted[k].task);
        cr_expect(status != 0 && strstr(report, " todo ") != NULL && strstr(report, planted[k].says) != NULL,
                  "%s with %s planted (status %d):\n%s", planted[k].task, planted[k].patch, status, report);
        free(report);
    }
    remove_copy(dir, log);
}

Test(coursework_long, every_task_fails_on_its_stub_and_passes_with_its_reference_body, .timeout = 3600) {
    char dir[64], log[80];
    make_copy(dir, log, "all", "");
    cr_assert_eq(run(log, MAKE_IN " %s SAN=%d -j2 %s/check", dir, san(), build()), 0, "the copy does not build: see %s",
                 log);
    char *all = marked_tasks();
    size_t tasks = 0;
    char id[16];
    int used;
    for (const char *p = all; sscanf(p, "%15s%n", id, &used) == 1; p += used, tasks++)
        cr_expect_neq(run(log, "cd %s && WHITTED_BUILD=%s ./%s/check --task %s", dir, build(), build(), id), 0,
                      "task %s's checks pass on its stub", id);
    cr_assert_geq(tasks, 20, "only %zu tasks are marked", tasks);
    char *waiting = output_of(NULL, "cd %s && WHITTED_BUILD=%s ./%s/check --task 7.1", dir, build(), build());
    cr_expect_not_null(strstr(waiting, "7.1: a blocker in between: needs task 2.1 (ray-sphere intersection"),
                       "a task whose needs fail should say so; the report was:\n%s", waiting);
    free(waiting);

    /* Each task, and each picture, with its reference body and those of the tasks it needs. */
    char *every = output_of(NULL, "cd %s && ./%s/check --list", dir, build());
    for (const char *p = every; sscanf(p, "%15s%n", id, &used) == 1; p += used) {
        char *needs = output_of(NULL, "cd %s && ./%s/check --needs %s | tr '\\n' ' '", dir, build(), id);
        char restore[1024];
        snprintf(restore, sizeof restore, "%s %s", strstr(id, ".P") ? "" : id, needs);
        free(needs);
        plant(dir, log, restore, "");
        cr_assert_eq(run(log, MAKE_IN " %s SAN=%d -j2 %s/check %s/chapter-%02d", dir, san(), build(), build(),
                         atoi(id)), 0, "rebuilding for task %s failed: see %s", id, log);
        cr_expect_eq(run(log, "cd %s && WHITTED_BUILD=%s ./%s/check --task %s", dir, build(), build(), id), 0,
                     "task %s's checks fail with its reference body (and those it needs) restored: see %s", id, log);
    }
    free(every);
    free(all);

    /* Pixels stored mirrored left to right (render.c, not a task, so the unit checks pass): the picture
     * check draws and names the difference. */
    plant(dir, log, "1.1", "");
    cr_assert_eq(run(log, "sed -i 's|image_set(img, i, j, colour)|image_set(img, img->width - 1 - i, j, colour)|' "
                          "%1$s/common/render.c && grep -q 'width - 1 - i' %1$s/common/render.c", dir),
                 0, "cannot mirror the picture: see %s", log);
    build_in(dir, log, 1);
    char *report = output_of(NULL, "cd %s && WHITTED_BUILD=%s ./%s/check --task 1.P", dir, build(), build());
    cr_expect_not_null(strstr(report, "it looks mirrored left to right"), "the report was:\n%s", report);
    cr_expect_not_null(strstr(report, "out/check/chapter-01-expected-got-difference.png"), "the report was:\n%s", report);
    free(report);
    char panel[128];
    snprintf(panel, sizeof panel, "%s/out/check/chapter-01-expected-got-difference.png", dir);
    struct stat st;
    cr_expect_eq(stat(panel, &st), 0, "%s was not written", panel);
    remove_copy(dir, log);
}

Test(coursework_long, each_picture_check_needs_exactly_the_tasks_its_program_runs, .timeout = 1800) {
    /* A copy of the repository in which every marked function records that it ran
     * (tests/checks/task_trace.awk); each chapter's program then renders its own scene. */
    char dir[64], log[80];
    new_folder(dir, log, "trace");
    cr_assert_eq(run(log, "cp -rp Makefile common chapters bench fuzz tools tests reference_images %1$s/ && mkdir -p "
                          "%1$s/scenes %1$s/%2$s && cp -rp scenes/*.scene scenes/models scenes/textures %1$s/scenes/ && cp -rp "
                          "%2$s/common %2$s/chapters %2$s/tools %2$s/checks %2$s/tests %1$s/%2$s/ && "
                          "for f in $(tools/student.sh --files); do "
                          "awk -f tests/checks/task_trace.awk $f >%1$s/$f || exit 1; done",
                     dir, build()),
                 0, "cannot make the traced copy: see %s", log);
    cr_assert_eq(run(log, MAKE_IN " %1$s SAN=%2$d -j2 %3$s/check $(cd %1$s && ls -d chapters/[0-9][0-9]-* | "
                          "sed 's|^chapters/\\([0-9]*\\)-.*|%3$s/chapter-\\1|')", dir, san(), build()),
                 0, "the traced copy does not build: see %s", log);
    /* The chapters with a picture check, "1 2 ... 15 17": not every number need have one. */
    char *pictures = output_of(NULL, "cd %s && ./%s/check --list | sed -n 's/[.]P$//p' | tr '\\n' ' '", dir, build());
    int chapters = 0;
    for (const char *c = pictures; *c != '\0'; c++)
        chapters += *c == ' ';
    cr_assert_geq(chapters, 11, "the grader has only %d picture checks", chapters);
    char *next = pictures, *end;
    for (int chapter = (int)strtol(next, &end, 10); end != next; chapter = (int)strtol(next, &end, 10)) {
        next = end;
        char *ran = output_of(NULL, "cd %1$s && rm -f ran && WHITTED_TASK_TRACE=ran ./%2$s/chapter-%3$02d --quiet "
                                    "--threads 2 -o out.png && sort -t. -k1,1n -k2,2n -u ran | tr '\\n' ' '",
                              dir, build(), chapter);
        char *needs = output_of(NULL, "cd %1$s && ./%2$s/check --needs %3$d.P | sort -t. -k1,1n -k2,2n -u | "
                                      "tr '\\n' ' '", dir, build(), chapter);
        cr_expect_str_eq(needs, ran, "picture check %d.P needs [%s] but chapter %d's program runs [%s]", chapter, needs,
                         chapter, ran);
        free(ran);
        free(needs);
    }
    free(pictures);
    run(log, "rm -rf %s", dir);
}

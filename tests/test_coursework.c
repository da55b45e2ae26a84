/* test_coursework.c: the coursework kit works (docs/coursework.md): a student copy builds, every marked
 * task's checks fail on its stub, restoring the one reference body (with the tasks it needs) makes them
 * pass, a flipped sign is named in the student's terms, and the reference passes every check.
 * All in one temporary copy, rebuilt incrementally from this build's objects. */
#include <criterion/criterion.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Runs a shell command and returns its exit status; its output goes to `log` (appended). */
static int run(const char *log, const char *format, ...) {
    char command[4096];
    va_list args;
    va_start(args, format);
    vsnprintf(command, sizeof command, format, args);
    va_end(args);
    char full[4400];
    snprintf(full, sizeof full, "( %s ) >>%s 2>&1", command, log);
    int status = system(full);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The output of a command, malloc'd (empty on failure). */
static char *output_of(const char *command) {
    FILE *p = popen(command, "r");
    size_t size = 0, capacity = 4096;
    char *text = malloc(capacity);
    size_t got;
    while (p != NULL && (got = fread(text + size, 1, capacity - size - 1, p)) > 0) {
        size += got;
        if (size + 1 == capacity)
            text = realloc(text, capacity *= 2);
    }
    text[size] = '\0';
    if (p != NULL)
        pclose(p);
    return text;
}

Test(coursework, student_copy_fails_on_stubs_and_passes_with_each_reference_body, .timeout = 600) {
    const char *build = getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build";
    const char *san = strstr(build, "san") != NULL ? "SAN=1" : "";
    char dir[] = "/tmp/whitted-student-XXXXXX", log[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(log, sizeof log, "%s.log", dir);
    remove(log);
    cr_assert_eq(run(log, "tools/student.sh %s", dir), 0, "make student failed: see %s", log);
    /* This build's objects, older than the blanked files, so that only those are compiled again. */
    cr_assert_eq(run(log, "mkdir -p %s/%s && cp -rp %s/common %s/tools %s/checks %s/chapters %s/%s/ && touch $(grep -l "
                          "'TODO (chapter' %s/common/*.[ch])", dir, build, build, build, build, build, dir, build, dir), 0,
                 "cannot seed the copy's build: see %s", log);
    cr_assert_eq(run(log, "make -C %s %s -j2 %s/check", dir, san, build), 0, "the student copy does not build: see %s", log);

    char *marked = output_of("tools/student.sh --list | cut -d' ' -f1");
    size_t tasks = 0;
    char all[1024] = "";
    for (char *id = strtok(marked, "\n"); id != NULL; id = strtok(NULL, "\n"), tasks++) {
        cr_expect_neq(run(log, "cd %s && WHITTED_BUILD=%s ./%s/check --task %s", dir, build, build, id), 0,
                      "task %s's checks pass on the blank stub", id);
        strncat(all, id, sizeof all - strlen(all) - 2);
        strcat(all, " ");
    }
    cr_assert_geq(tasks, 12, "only %zu tasks are marked", tasks);
    char command[256];
    snprintf(command, sizeof command, "cd %s && WHITTED_BUILD=%s ./%s/check --task 7.1", dir, build, build);
    char *waiting = output_of(command);
    cr_expect_not_null(strstr(waiting, "7.1: a blocker in between: needs task 2.1 (ray-sphere intersection"),
                       "a task whose needs fail should say so; the report was:\n%s", waiting);
    free(waiting);

    /* Each task with its reference body (and those of the tasks it needs): its checks pass. */
    for (char *id = all; *id != '\0';) {
        char task[16];
        int used;
        sscanf(id, "%15s %n", task, &used);
        id += used;
        snprintf(command, sizeof command, "%s/check --needs %s", build, task);
        char *listed = output_of(command), needs[1024], blank[1024] = "";
        snprintf(needs, sizeof needs, "\n%s", listed); /* every task on a line of its own, "\nN.K\n" */
        free(listed);
        for (char *other = all; *other != '\0';) {
            char t[16], pattern[20];
            int n;
            sscanf(other, "%15s %n", t, &n);
            other += n;
            snprintf(pattern, sizeof pattern, "\n%s\n", t);
            bool needed = strcmp(t, task) == 0 || strstr(needs, pattern) != NULL;
            if (!needed) {
                strcat(blank, t);
                strcat(blank, " ");
            }
        }
        cr_assert_eq(run(log, "tools/student.sh %s '%s' --sources-only && make -C %s %s -j2 %s/check", dir,
                         blank[0] ? blank : "none", dir, san, build), 0, "rebuilding for task %s failed: see %s", task, log);
        cr_expect_eq(run(log, "cd %s && WHITTED_BUILD=%s ./%s/check --task %s", dir, build, build, task), 0,
                     "task %s's checks fail with its reference body restored: see %s", task, log);
    }
    free(marked);

    /* The far root first: the check says so in the student's terms. */
    cr_assert_eq(run(log, "tools/student.sh %s none --sources-only && sed -i 's/double near = -b - root;/double near = "
                          "-b + root;/' %s/common/sphere.c && make -C %s %s -j2 %s/check", dir, dir, dir, san, build), 0);
    snprintf(command, sizeof command, "cd %s && WHITTED_BUILD=%s ./%s/check --task 2.1", dir, build, build);
    char *report = output_of(command);
    cr_expect_not_null(strstr(report, "sphere_intersect: the hit is 4.0 along the ray for a sphere 5 away with radius 1; "
                                      "your code returned 6.0: the far root?"), "the report was:\n%s", report);
    free(report);

    /* Pixels stored mirrored left to right (render.c, not a task, so the unit checks pass): the picture
     * check draws and names the difference. */
    cr_assert_eq(run(log, "tools/student.sh %s none --sources-only && sed -i 's|image_set(img, i, j, job|"
                          "image_set(img, img->width - 1 - i, j, job|' %s/common/render.c && grep -q 'width - 1 - i' "
                          "%s/common/render.c && make -C %s %s -j2 %s/check %s/chapter-01", dir, dir, dir, dir, san, build,
                     build), 0, "cannot build the mirrored picture: see %s", log);
    snprintf(command, sizeof command, "cd %s && WHITTED_BUILD=%s ./%s/check --task 1.P", dir, build, build);
    report = output_of(command);
    cr_expect_not_null(strstr(report, "it looks mirrored left to right"), "the report was:\n%s", report);
    cr_expect_not_null(strstr(report, "out/check/chapter-01-expected-got-difference.png"), "the report was:\n%s", report);
    free(report);
    char panel[128];
    snprintf(panel, sizeof panel, "%s/out/check/chapter-01-expected-got-difference.png", dir);
    FILE *drawn = fopen(panel, "rb");
    cr_expect_not_null(drawn, "%s was not written", panel);
    if (drawn != NULL)
        fclose(drawn);
    char cleanup[128];
    snprintf(cleanup, sizeof cleanup, "rm -rf %s %s.log", dir, dir);
    cr_expect_eq(system(cleanup), 0);
}

Test(coursework, the_reference_passes_every_check, .timeout = 600) {
    const char *build = getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build";
    char command[256];
    snprintf(command, sizeof command, "WHITTED_BUILD=%s ./%s/check all 2>&1", build, build);
    char *report = output_of(command);
    const char *last = strstr(report, "\nscoreboard\n");
    int done = -1, total = -2;
    for (const char *line = last; line != NULL; line = strchr(line + 1, '\n'))
        if (sscanf(line + 1, "%d of %d tasks done", &done, &total) == 2)
            break;
    cr_expect(done == total && total >= 28, "the reference's scoreboard is not full:\n%s", report);
    free(report);
}

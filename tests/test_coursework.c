/* test_coursework.c: the coursework kit runs, wherever it is (docs/coursework.md): the grader grades every
 * task of every chapter and ends with a scoreboard, and make exercises says of every build exercise where
 * to start or how it went. These tests apply in a student copy too (its make test runs them); in the
 * repository, every task is also done. The proofs that the checks catch planted faults are in
 * test_coursework_proof.c, those about student copies in test_coursework_copy.c. */
#include <criterion/criterion.h>
#include <glob.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "checks/check.h"
#include "test_support.h"

/* Room for the grader's whole report. */
#define REPORT_SIZE (1 << 20)

/* The tasks of chapters 1 to 12 (unit tasks and pictures): each has a line of the scoreboard. */
#define TASKS_AT_LEAST 34

/* The build exercises (★★★), one in each walkthrough from chapter 2 on (the chapters there are). */
#define EXERCISES 16

static const char *build(void) { return getenv("WHITTED_BUILD") ? getenv("WHITTED_BUILD") : "build"; }

/* Whether this is a student copy (tools/student.sh leaves .student-copy in it). */
static bool in_a_student_copy(void) { return access(".student-copy", F_OK) == 0; }

Test(coursework, the_grader_ends_every_run_with_a_scoreboard_of_every_task, .timeout = 600) {
    char command[256];
    snprintf(command, sizeof command, "WHITTED_BUILD=%s ./%s/check all", build(), build());
    char *report = malloc(REPORT_SIZE);
    int status = run_capturing(command, report, REPORT_SIZE);
    cr_assert(status == 0 || status == 1, "check all ended with status %d:\n%s", status, report);
    const char *board = strstr(report, "\nscoreboard\n");
    cr_assert_not_null(board, "no scoreboard:\n%s", report);
    int lines = 0, done = -1, total = -2;
    for (const char *line = strchr(board + 1, '\n'); line != NULL; line = strchr(line + 1, '\n')) {
        char id[16], state[8];
        if (sscanf(line + 1, " %15s %7s", id, state) == 2 && (strcmp(state, "done") == 0 || strcmp(state, "todo") == 0))
            lines++;
        if (sscanf(line + 1, "%d of %d tasks done", &done, &total) == 2)
            break;
    }
    cr_expect_geq(lines, TASKS_AT_LEAST, "the scoreboard has %d task lines:\n%s", lines, board);
    cr_expect_eq(total, lines, "the scoreboard counts %d tasks but lists %d:\n%s", total, lines, board);
    if (!in_a_student_copy())
        cr_expect(done == total && status == 0, "the reference does not pass every check:\n%s", report);
    free(report);
}

Test(coursework, the_grader_says_how_to_call_it) {
    char command[256], output[4096];
    snprintf(command, sizeof command, "./%s/check 99", build());
    cr_expect_eq(run_capturing(command, output, sizeof output), 2);
    cr_expect_not_null(strstr(output, "usage: "), "the grader printed:\n%s", output);
}

Test(coursework, make_exercises_says_where_each_build_exercise_starts, .timeout = 300) {
    char command[256], output[65536];
    snprintf(command, sizeof command, "env -u MAKEFLAGS -u MAKELEVEL -u MFLAGS make --no-print-directory exercises SAN=%d",
             strstr(build(), "san") ? 1 : 0);
    int status = run_capturing(command, output, sizeof output);
    /* In a student copy, an exercise started and not yet right fails make exercises; it still runs. */
    cr_assert(status == 0 || in_a_student_copy(), "make exercises failed:\n%s", output);
    int done = -1, failing = -1, waiting = -1;
    const char *summary = strstr(output, "exercises: ");
    cr_assert(summary != NULL && sscanf(summary, "exercises: %d done, %d failing, %d not started", &done, &failing,
                                        &waiting) == 3, "no summary:\n%s", output);
    cr_expect_eq(done + failing + waiting, EXERCISES, "make exercises knows %d exercises, not the %d of chapters 2 "
                 "on:\n%s", done + failing + waiting, EXERCISES, output);
    /* Each chapter from 2 on has one: exercise N.4, or N.5 where the walkthrough has four before it. */
    glob_t chapters;
    cr_assert_eq(glob("chapters/[0-9][0-9]-*", 0, NULL, &chapters), 0, "no chapters found");
    for (size_t k = 0; k < chapters.gl_pathc; k++) {
        int chapter = atoi(chapters.gl_pathv[k] + strlen("chapters/"));
        char id4[32], id5[32];
        snprintf(id4, sizeof id4, "exercise %d.4,", chapter);
        snprintf(id5, sizeof id5, "exercise %d.5,", chapter);
        if (chapter >= 2)
            cr_expect(strstr(output, id4) != NULL || strstr(output, id5) != NULL,
                      "make exercises says nothing of chapter %d's build exercise:\n%s", chapter, output);
    }
    globfree(&chapters);
    if (!in_a_student_copy())
        cr_expect_eq(waiting, EXERCISES, "in the repository no build exercise is started:\n%s", output);
}

Test(coursework, every_suite_a_student_copy_runs_exists) {
    /* tests/student-suites names the suites make test runs in a student copy: a suite renamed or removed
     * would silently drop out of it. */
    char *list = read_text_file("tests/student-suites");
    size_t size = 1 << 23, got = 0;
    char *tests = malloc(size);
    FILE *p = popen("cat tests/*.c tests/*/*.c", "r");
    cr_assert_not_null(p);
    got = fread(tests, 1, size - 1, p);
    tests[got] = '\0';
    pclose(p);
    size_t suites = 0;
    for (char *line = strtok(list, "\n"); line != NULL; line = strtok(NULL, "\n")) {
        if (line[0] == '#')
            continue;
        char plain[128], parameterized[128];
        snprintf(plain, sizeof plain, "Test(%s, ", line);
        snprintf(parameterized, sizeof parameterized, ", %s, ", line);
        cr_expect(strstr(tests, plain) != NULL || strstr(tests, parameterized) != NULL,
                  "tests/student-suites names %s, which no test file defines", line);
        suites++;
    }
    cr_expect_geq(suites, 10, "tests/student-suites names only %zu suites", suites);
    free(tests);
    free(list);
}

/* ---- what a check leaves behind ---------------------------------------------------------------- */

/* Where the check below tells the test the number of the process it forked. */
static int forked_pipe[2];

/* A check whose code, as a student's task body might, forks a process that never ends, and passes. */
static CHECK(check_that_forks_a_process_that_never_ends) {
    (void)why, (void)why_size;
    pid_t child = fork();
    if (child == 0)
        for (;;)
            pause();
    return write(forked_pipe[1], &child, sizeof child) == (ssize_t)sizeof child;
}

/* The same, as a daemon is made: the forked process leaves the check's process group (setsid), forks
 * the process that never ends and exits, so that what is left belongs to no process the check knows. */
static CHECK(check_that_leaves_a_daemon) {
    (void)why, (void)why_size;
    int reported[2];
    if (pipe(reported) != 0)
        return false;
    pid_t child = fork();
    if (child == 0) {
        setsid();
        pid_t daemon = fork();
        if (daemon == 0)
            for (;;)
                pause();
        _exit(write(reported[1], &daemon, sizeof daemon) == (ssize_t)sizeof daemon ? 0 : 1);
    }
    pid_t daemon = 0;
    bool told = read(reported[0], &daemon, sizeof daemon) == (ssize_t)sizeof daemon;
    waitpid(child, NULL, 0);
    return told && write(forked_pipe[1], &daemon, sizeof daemon) == (ssize_t)sizeof daemon;
}

/* Whether process `pid` still runs: it exists and is not a zombie, dead and waiting for its parent. */
static bool still_running(pid_t pid) {
    char path[64], stat[512] = "";
    snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return false;
    size_t got = fread(stat, 1, sizeof stat - 1, f);
    fclose(f);
    stat[got] = '\0';
    const char *state = strrchr(stat, ')'); /* "pid (name) S ...": the state follows the name */
    return state != NULL && state[1] == ' ' && state[2] != 'Z' && state[2] != 'X';
}

/* Runs check c through check_run_isolated, which must pass, and requires the process its code reports
 * through forked_pipe to be gone (or dead, waiting for its parent) when check_run_isolated returns. */
static void expect_nothing_left_by(const struct check *c) {
    cr_assert_eq(pipe(forked_pipe), 0);
    struct check_verdict v;
    check_run_isolated(c, CHECK_SECONDS, &v);
    cr_assert(v.passed, "%s", v.why);
    pid_t child = 0;
    cr_assert_eq(read(forked_pipe[0], &child, sizeof child), (ssize_t)sizeof child);
    bool running = still_running(child);
    for (int tries = 0; running && tries < 100; tries++) { /* SIGKILL is sent; its delivery may take a moment */
        nanosleep(&(struct timespec){0, 10000000}, NULL);
        running = still_running(child);
    }
    if (running)
        kill(child, SIGKILL);
    cr_assert_not(running, "process %d, which the check forked, still runs after the check", (int)child);
    close(forked_pipe[0]);
    close(forked_pipe[1]);
}

/* The grader runs each check in a process group of its own and ends the whole group when the check is
 * done: a process the student's code forked kept running after make check-N had printed its scoreboard
 * (six of them after one run, with a fork in a task's body). */
Test(coursework, a_process_a_check_forks_does_not_outlive_the_check) {
    const struct check c = {"2.1", "forks a process that never ends", check_that_forks_a_process_that_never_ends};
    expect_nothing_left_by(&c);
}

/* A process that left the check's group (setsid) escaped the group's kill; the grader, its subreaper,
 * ends it as its own child. */
Test(coursework, a_daemon_a_check_leaves_outside_its_process_group_does_not_outlive_it) {
    const struct check c = {"2.1", "leaves a daemon", check_that_leaves_a_daemon};
    expect_nothing_left_by(&c);
}

/* check_process.c: runs one coursework check in a process of its own, with a time limit, so that a
 * crash or an endless loop in the student's code fails that one check with a message in the student's
 * terms instead of taking the grader, and the scoreboard, down (the coursework kit; docs/coursework.md).
 *
 * The check's process and the grader share one small record (an anonymous shared mapping): what the
 * check is calling now (check_calling) and, when it returns, its verdict. The grader waits for the
 * process until the time limit and then kills it with its process group (a picture check's chapter
 * program included). What ended the process decides the message: its verdict when it finished, the
 * signal that killed it, the limit, or the exit status it stopped with before finishing (the sanitizers,
 * make SAN=1, print their report and stop the process that way).
 *
 * A process the student's code forks may leave the group (setsid) and so escape the group's kill. On
 * Linux the grader is made a subreaper (prctl): such a process, once its parent has ended, becomes the
 * grader's child, and the grader ends every child it has left after a check (end_strays). */
#include <dirent.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#if defined(__linux__)
#include <sys/prctl.h>
#endif

#include "check.h"

/* A check's process whose grader has gone (interrupted, say) still ends by itself: its own alarm rings
 * this many seconds after the grader's limit. */
#define CHECK_ORPHAN_GRACE 5

/* end_strays looks for children left this many times at most: each look kills every child it finds, and
 * the children those leave behind become the grader's for the next look. */
#define CHECK_STRAY_LOOKS 100

/* What the check's process tells the grader. */
struct check_record {
    char function[128];          /* the student's function it called last ("sphere_normal"); "" before */
    char inputs[1024];           /* on what, in the student's terms */
    bool finished, passed;       /* the check returned, and its verdict */
    char why[CHECK_WHY_SIZE];    /* the check's explanation when it failed */
};

static struct check_record *shared; /* the record, while a check's process runs; NULL in the grader */
static volatile pid_t running;      /* the check's process (and process group), 0 when none runs */

void check_calling(const char *function, const char *format, ...) {
    if (shared == NULL)
        return;
    snprintf(shared->function, sizeof shared->function, "%s", function);
    va_list args;
    va_start(args, format);
    vsnprintf(shared->inputs, sizeof shared->inputs, format, args);
    va_end(args);
}

/* Interrupted (Ctrl-C) while a check runs: the check's process group has a group of its own and does
 * not get the terminal's signal, so end it here, then end the grader as the signal would have. */
static void stop_running_check(int signal_number) {
    if (running > 0)
        kill(-running, SIGKILL);
    signal(signal_number, SIG_DFL);
    raise(signal_number);
}

/* What a signal that killed a check's process usually means in a student's code. */
static const char *signal_meaning(int signal_number) {
    switch (signal_number) {
    case SIGSEGV:
        return "segmentation fault: a pointer that points nowhere, an array used past its end, or a recursion "
               "that never stops";
    case SIGBUS:
        return "bus error: a pointer that points nowhere";
    case SIGFPE:
        return "arithmetic exception: an integer division by zero";
    case SIGABRT:
        return "abort: an assert that failed, or memory written past the end of an allocation";
    case SIGILL:
        return "illegal instruction: often the compiler's trap for a null pointer it could see";
    default:
        return strsignal(signal_number);
    }
}

/* Seconds since an arbitrary start, from the monotonic clock. */
static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The check's process: run the check, leave the verdict in the record, and end without running exit
 * handlers (the leak checker's among them: a check's process ends in the middle of the grader). */
static void run_child(const struct check *c, int seconds, const sigset_t *mask) {
    setpgid(0, 0);
    sigprocmask(SIG_SETMASK, mask, NULL);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    alarm((unsigned)(seconds + CHECK_ORPHAN_GRACE));
    bool passed = c->run(shared->why, sizeof shared->why);
    shared->passed = passed;
    shared->finished = true;
    fflush(stdout);
    fflush(stderr);
    _exit(0);
}

/* Kills the processes whose parent is the grader and reaps them; returns how many there were. The
 * grader's only children after a check are what the check left: its own process has been reaped. Reads
 * each process's parent in /proc (Linux; elsewhere finds none). */
static int kill_children(void) {
    int found = 0;
#if defined(__linux__)
    DIR *all = opendir("/proc");
    if (all == NULL)
        return 0;
    pid_t self = getpid();
    for (struct dirent *e; (e = readdir(all)) != NULL;) {
        char *end;
        long pid = strtol(e->d_name, &end, 10);
        if (*end != '\0' || pid <= 0)
            continue;
        char path[64], stat[512] = "";
        snprintf(path, sizeof path, "/proc/%ld/stat", pid);
        FILE *f = fopen(path, "r");
        if (f == NULL)
            continue; /* it ended while we looked */
        size_t got = fread(stat, 1, sizeof stat - 1, f);
        fclose(f);
        stat[got] = '\0';
        const char *after_name = strrchr(stat, ')'); /* "pid (name) S ppid ...": the name may hold anything */
        int parent = 0;
        if (after_name != NULL && sscanf(after_name + 1, " %*c %d", &parent) == 1 && parent == (int)self) {
            kill((pid_t)pid, SIGKILL);
            waitpid((pid_t)pid, NULL, 0);
            found++;
        }
    }
    closedir(all);
#endif
    return found;
}

/* Ends what the check left that escaped its group's kill: processes that called setsid, orphaned and so
 * made the grader's children (it is their subreaper), and theirs in turn. */
static void end_strays(void) {
    for (int look = 0; look < CHECK_STRAY_LOOKS && kill_children() > 0; look++)
        continue;
}

/* Writes "sphere_normal crashed ... on the point ..." or, before the check called the student's code,
 * "the check crashed ...", then `then`: a message about what the check's process was doing. */
static void describe_doing(struct check_verdict *v, const char *what_happened, const char *then) {
    if (shared->function[0] != '\0')
        snprintf(v->why, sizeof v->why, "%s %s on %s%s", shared->function, what_happened, shared->inputs, then);
    else
        snprintf(v->why, sizeof v->why, "the check %s before it called your code%s", what_happened, then);
}

void check_run_isolated(const struct check *c, int seconds, struct check_verdict *v) {
    v->passed = false;
    v->why[0] = '\0';
    struct check_record *record =
        mmap(NULL, sizeof *record, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (record == MAP_FAILED) {
        snprintf(v->why, sizeof v->why, "the grader could not share memory with the check's process (mmap failed)");
        return;
    }
    memset(record, 0, sizeof *record);
    shared = record;
#if defined(__linux__)
    prctl(PR_SET_CHILD_SUBREAPER, 1L, 0L, 0L, 0L); /* once is enough; see end_strays */
#endif

    /* SIGCHLD is blocked around the fork, so that the wait below can sleep until it arrives. */
    sigset_t child_ended, mask;
    sigemptyset(&child_ended);
    sigaddset(&child_ended, SIGCHLD);
    sigprocmask(SIG_BLOCK, &child_ended, &mask);
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid == 0)
        run_child(c, seconds, &mask);
    if (pid < 0) {
        sigprocmask(SIG_SETMASK, &mask, NULL);
        snprintf(v->why, sizeof v->why, "the grader could not start a process for the check (fork failed)");
        shared = NULL;
        munmap(record, sizeof *record);
        return;
    }
    setpgid(pid, pid); /* also done by the child: whichever runs first */
    running = pid;
    struct sigaction stop = {.sa_handler = stop_running_check}, old_int, old_term;
    sigaction(SIGINT, &stop, &old_int);
    sigaction(SIGTERM, &stop, &old_term);

    int status = 0;
    bool timed_out = false;
    double deadline = now() + seconds;
    /* Waits for the check's process to end without reaping it (WNOWAIT): until it is reaped, its number
     * is no other process's, so its group can still be named safely below. */
    for (;;) {
        siginfo_t ended = {.si_pid = 0};
        if (waitid(P_PID, (id_t)pid, &ended, WEXITED | WNOHANG | WNOWAIT) == 0 && ended.si_pid == pid)
            break;
        double left = deadline - now();
        if (left <= 0) {
            timed_out = true;
            break;
        }
        struct timespec wait = {(time_t)left, (long)((left - (double)(time_t)left) * 1e9)};
        sigtimedwait(&child_ended, NULL, &wait);
    }
    /* The whole group: the process itself when it ran out of time, and whatever it left running (a process
     * the student's code forked, which outlived the check and kept the grader's folder busy). */
    kill(-pid, SIGKILL);
    waitpid(pid, &status, 0);
    end_strays();
    running = 0;
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    sigprocmask(SIG_SETMASK, &mask, NULL);

    char what[256];
    if (record->finished) {
        v->passed = record->passed;
        snprintf(v->why, sizeof v->why, "%s", record->why);
    } else if (timed_out) {
        snprintf(what, sizeof what, "did not finish within %d s", seconds);
        describe_doing(v, what, ": an endless loop? (a loop whose condition never changes, or a recursion without "
                                "its limit)");
    } else if (WIFSIGNALED(status)) {
        snprintf(what, sizeof what, "crashed (%s)", signal_meaning(WTERMSIG(status)));
        describe_doing(v, what, "");
    } else {
        snprintf(what, sizeof what, "stopped the program (exit status %d)", WEXITSTATUS(status));
        describe_doing(v, what, " before the check could finish: a call to exit, or a sanitizer's report, printed "
                                "above (make SAN=1 check-N)");
    }
    shared = NULL;
    munmap(record, sizeof *record);
}

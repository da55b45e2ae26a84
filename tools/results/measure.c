/* measure.c: runs one command and writes what it cost, for make results (tools/results/run.sh).
 *
 *     measure REPORT COMMAND [ARGUMENT...]
 *
 * Runs COMMAND with its standard input, output and error untouched, waits for it, and writes one line
 * to the file REPORT:
 *
 *     cpu_s wall_s peak_rss_kb
 *
 * cpu_s is the processor time the command used (user and system, all its threads; getrusage of the
 * finished child), wall_s the time from start to end by the monotonic clock, and peak_rss_kb the most
 * memory it held at once (ru_maxrss). On a shared machine processor time is the steadier clock: it
 * does not count the time the command waited for a core. Exits with the command's exit status (and
 * writes no REPORT when that is not 0), 2 when the command cannot be run or REPORT cannot be written. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* Seconds on the monotonic clock. */
static double seconds_now(void) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

/* Seconds in a struct timeval. */
static double seconds_of(struct timeval t) {
    return (double)t.tv_sec + 1e-6 * (double)t.tv_usec;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: measure REPORT COMMAND [ARGUMENT...]\n");
        return 2;
    }
    double started = seconds_now();
    pid_t child = fork();
    if (child < 0) {
        fprintf(stderr, "measure: cannot fork: %s\n", strerror(errno));
        return 2;
    }
    if (child == 0) {
        execvp(argv[2], argv + 2);
        fprintf(stderr, "measure: cannot run %s: %s\n", argv[2], strerror(errno));
        _exit(127);
    }
    int status;
    struct rusage usage;
    if (wait4(child, &status, 0, &usage) != child) {
        fprintf(stderr, "measure: wait failed: %s\n", strerror(errno));
        return 2;
    }
    double wall = seconds_now() - started;
    if (!WIFEXITED(status))
        return 2;
    if (WEXITSTATUS(status) != 0)
        return WEXITSTATUS(status);
    FILE *report = fopen(argv[1], "w");
    if (report == NULL) {
        fprintf(stderr, "measure: %s: %s\n", argv[1], strerror(errno));
        return 2;
    }
    fprintf(report, "%.4f %.4f %ld\n", seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime), wall,
            usage.ru_maxrss);
    if (fclose(report) != 0) {
        fprintf(stderr, "measure: %s: %s\n", argv[1], strerror(errno));
        return 2;
    }
    return 0;
}

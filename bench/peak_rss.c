/* peak_rss.c: runs a command and prints its peak resident memory, in all and per triangle (make
 * bench-memory, for chapters 10 and 11), or in kilobytes alone (make bench-instances, chapter 16).
 *
 *     peak_rss TRIANGLES LABEL COMMAND [ARGUMENT...]
 *     peak_rss --kilobytes COMMAND [ARGUMENT...]
 *
 * With --kilobytes the command's standard output is thrown away and the peak is printed as a whole
 * number of kilobytes, for a script to compute with.
 * The peak is what the kernel reports for the finished child (getrusage's ru_maxrss, in kilobytes): the
 * most memory the command ever held at once, the scene, the gathered triangles, the structure and the
 * build's temporaries together. Exits with the command's status, or 2 when it cannot be run. */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char **argv) {
    bool kilobytes = argc >= 3 && strcmp(argv[1], "--kilobytes") == 0;
    if (!kilobytes && (argc < 4 || atof(argv[1]) <= 0)) {
        fprintf(stderr, "usage: peak_rss TRIANGLES LABEL COMMAND [ARGUMENT...]\n"
                        "       peak_rss --kilobytes COMMAND [ARGUMENT...]\n");
        return 2;
    }
    double triangles = kilobytes ? 1.0 : atof(argv[1]);
    char **command = argv + (kilobytes ? 2 : 3);
    fflush(stdout);
    pid_t child = fork();
    if (child < 0) {
        fprintf(stderr, "peak_rss: cannot fork: %s\n", strerror(errno));
        return 2;
    }
    if (child == 0) {
        if (kilobytes && !freopen("/dev/null", "w", stdout)) {
            fprintf(stderr, "peak_rss: cannot open /dev/null: %s\n", strerror(errno));
            _exit(127);
        }
        execvp(command[0], command);
        fprintf(stderr, "peak_rss: cannot run %s: %s\n", command[0], strerror(errno));
        _exit(127);
    }
    int status;
    struct rusage usage;
    if (wait4(child, &status, 0, &usage) != child) {
        fprintf(stderr, "peak_rss: wait failed: %s\n", strerror(errno));
        return 2;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "peak_rss: %s failed\n", command[0]);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 2;
    }
    if (kilobytes) {
        printf("%ld\n", usage.ru_maxrss);
        return 0;
    }
    double bytes = 1024.0 * (double)usage.ru_maxrss;
    printf("  %-40s peak RSS %8.1f MB  %6.1f bytes per triangle\n", argv[2], bytes / 1048576.0, bytes / triangles);
    return 0;
}

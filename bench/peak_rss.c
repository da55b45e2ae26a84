/* peak_rss.c: runs a command and prints its peak resident memory, in all and per triangle (make
 * bench-memory, for chapters 10 and 11).
 *
 *     peak_rss TRIANGLES LABEL COMMAND [ARGUMENT...]
 *
 * The peak is what the kernel reports for the finished child (getrusage's ru_maxrss, in kilobytes): the
 * most memory the command ever held at once, the scene, the gathered triangles, the structure and the
 * build's temporaries together. Exits with the command's status, or 2 when it cannot be run. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char **argv) {
    if (argc < 4 || atof(argv[1]) <= 0) {
        fprintf(stderr, "usage: peak_rss TRIANGLES LABEL COMMAND [ARGUMENT...]\n");
        return 2;
    }
    double triangles = atof(argv[1]);
    pid_t child = fork();
    if (child < 0) {
        fprintf(stderr, "peak_rss: cannot fork: %s\n", strerror(errno));
        return 2;
    }
    if (child == 0) {
        execvp(argv[3], argv + 3);
        fprintf(stderr, "peak_rss: cannot run %s: %s\n", argv[3], strerror(errno));
        _exit(127);
    }
    int status;
    struct rusage usage;
    if (wait4(child, &status, 0, &usage) != child) {
        fprintf(stderr, "peak_rss: wait failed: %s\n", strerror(errno));
        return 2;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "peak_rss: %s failed\n", argv[3]);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 2;
    }
    double bytes = 1024.0 * (double)usage.ru_maxrss;
    printf("  %-40s peak RSS %8.1f MB  %6.1f bytes per triangle\n", argv[2], bytes / 1048576.0, bytes / triangles);
    return 0;
}

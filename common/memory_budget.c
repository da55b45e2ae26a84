/* memory_budget.c: the memory a scene's meshes may take (chapter 3).
 *
 * Linux lends memory before it has it: malloc succeeds for far more than the machine holds, and a
 * program that then touches it all is killed (SIGKILL, no message) when the memory runs out. A scene
 * that names the 350,000-triangle teapot a thousand times asks for 8 GB of meshes, and chapter 11 then
 * three times as much again for their gathered copy and their tree: malloc would not refuse it. So
 * scene_load_meshes adds up what the meshes it has read take and stops, naming the line, once that passes
 * a share of the memory the program may use. */
#include "memory_budget.h"

#include <stdint.h>
#include <stdio.h>
#include <sys/resource.h>
#include <unistd.h>

size_t memory_budget_limit(void) {
    size_t limit = 0;
    long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page_size > 0)
        limit = (size_t)pages > SIZE_MAX / (size_t)page_size ? SIZE_MAX : (size_t)pages * (size_t)page_size;
#ifndef __EMSCRIPTEN__ /* the browser's page has no ulimit (and its C library warns on the console when asked) */
    struct rlimit data;
    if (getrlimit(RLIMIT_DATA, &data) == 0 && data.rlim_cur != RLIM_INFINITY && (limit == 0 || data.rlim_cur < limit))
        limit = data.rlim_cur > SIZE_MAX ? SIZE_MAX : (size_t)data.rlim_cur;
#endif
    return limit;
}

size_t memory_budget_share(double share) {
    size_t limit = memory_budget_limit();
    if (limit == 0)
        return SIZE_MAX;
    double bytes = share * (double)limit;
    return bytes >= (double)SIZE_MAX ? SIZE_MAX : (size_t)bytes;
}

void memory_budget_explain(char *out, size_t size, const char *what, size_t taken, double share) {
    snprintf(out, size, "the scene's %s take %.1f MB up to this line, more than %g%% of the %.1f MB of memory "
             "this program may use (the machine's, or ulimit -d's)", what, taken / 1e6, 100 * share,
             memory_budget_limit() / 1e6);
}

/* memory_budget.h: how much memory a scene's meshes may take before the program refuses them, so that a
 * scene naming too many stops at the line that goes over instead of being killed by the kernel when the
 * machine runs out (chapter 3). */
#ifndef WHITTED_MEMORY_BUDGET_H
#define WHITTED_MEMORY_BUDGET_H

#include <stddef.h>

/* The memory this program may use, in bytes: the machine's physical memory, or the limit on the
 * process's address space (`ulimit -v`) when that is lower; 0 when neither can be told (nothing is then
 * checked against it). */
size_t memory_budget_limit(void);

/* The bytes a share (0 < share <= 1) of memory_budget_limit() comes to, or SIZE_MAX when the limit cannot
 * be told: models taking more than this are refused. */
size_t memory_budget_share(double share);

#endif

/* memory_budget.h: how much memory a scene's meshes may take before the program refuses them, so that a
 * scene naming too many stops at the line that goes over instead of being killed by the kernel when the
 * machine runs out (chapter 3). */
#ifndef WHITTED_MEMORY_BUDGET_H
#define WHITTED_MEMORY_BUDGET_H

#include <stddef.h>

/* A scene's meshes (its mesh lines' and, in chapter 16, its objects') may take at most this share of the
 * memory the program may use: what the chapters build from them takes more, up to about 14 times the
 * meshes' own memory (chapter 9: the gathered copy and the kd-tree, at its peak, of four teapots of
 * 350,000 triangles; chapters 12 to 17 4.4 times, chapter 11 3.4, chapters 3 to 8 none). On a machine of
 * 8 GB, half a gigabyte of meshes: about 20 million triangles. */
#define MEMORY_BUDGET_MESH_SHARE 0.0625

/* The memory this program may use, in bytes: the machine's physical memory, or the limit on the data
 * the process may hold (`ulimit -d`) when that is lower; 0 when neither can be told (nothing is then
 * checked against it). Not the limit on its address space (`ulimit -v`), which also counts what is
 * reserved and never touched (libraries, the slack of arrays aligned to 2 MB), so that under it malloc
 * fails first and says so, at the line whose mesh or tree did not fit. */
size_t memory_budget_limit(void);

/* The bytes a share (0 < share <= 1) of memory_budget_limit() comes to, or SIZE_MAX when the limit cannot
 * be told: models taking more than this are refused. */
size_t memory_budget_share(double share);

/* Room for memory_budget_explain's sentence. */
#define MEMORY_BUDGET_EXPLAIN_SIZE 256

/* Writes into out (size bytes, always terminated) why a scene line is refused: "the scene's WHAT take
 * X MB up to this line, more than P% of the Y MB of memory this program may use (...)", where WHAT names
 * what is counted ("meshes", "images"), taken its bytes so far and share the share they went over. The
 * caller puts "FILE:LINE: what the line names: " before it. */
void memory_budget_explain(char *out, size_t size, const char *what, size_t taken, double share);

#endif

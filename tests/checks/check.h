/* check.h: the coursework checks (make check-N): the task table, one check per behaviour, each saying in
 * the student's terms what is wrong (the coursework kit; docs/coursework.md). Not part of make test's
 * suite: these run against a student's code, and expect only analytic values and reference pictures. */
#ifndef WHITTED_CHECK_H
#define WHITTED_CHECK_H

#include <stdbool.h>
#include <stddef.h>

#include "vec3.h"

/* Room for one check's explanation. */
#define CHECK_WHY_SIZE 2048

/* Runs one check. Returns true when it passes; otherwise false with what is wrong in why. */
typedef bool (*check_fn)(char *why, size_t why_size);

struct check {
    const char *task; /* "2.1"; "2.P" for chapter 2's picture */
    const char *name; /* what it checks, one line */
    check_fn run;
};

struct task {
    const char *id;       /* "N.K", as in the marker in the source; "N.P" is chapter N's picture */
    const char *title;
    const char *function; /* what the student writes, and where */
    const char *needs;    /* tasks whose checks must pass first, space-separated ("" for none) */
};

extern const struct task check_tasks[];
extern const size_t check_task_count;
extern const struct check check_list[];
extern const size_t check_count;

/* The checks of each file, in check_list order (check_geometry.c, check_shading.c, check_accel.c,
 * check_antialias.c, check_distributed.c, check_picture.c); defined with CHECK() below. */
#define CHECK(fn) bool fn(char *why, size_t why_size)

/* For the checks: whether a and b agree within tolerance (per coordinate), and a vector as text. */
bool check_near(double a, double b, double tolerance);
bool check_vec_near(vec3 a, vec3 b, double tolerance);
const char *check_vec_text(vec3 v, char buffer[static 64]);

#endif

/* check.h: the coursework checks (make check-N): the task table, one check per behaviour, each saying in
 * the student's terms what is wrong (the coursework kit; docs/coursework.md). Not part of make test's
 * suite: these run against a student's code, and expect only analytic values and reference pictures.
 * Each check runs in a process of its own with a time limit (check_process.c), so a crash or an endless
 * loop fails that check and names what it was doing. */
#ifndef WHITTED_CHECK_H
#define WHITTED_CHECK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "ray.h"
#include "vec3.h"

/* Room for one check's explanation. */
#define CHECK_WHY_SIZE 2048

/* How long one check may run: a unit check takes milliseconds, so CHECK_SECONDS is only there to stop an
 * endless loop (the environment variable WHITTED_CHECK_SECONDS sets another limit, for the tests that
 * plant one); a picture check renders the chapter's scene, the slowest under the sanitizers. */
#define CHECK_SECONDS 5
#define CHECK_PICTURE_SECONDS 300

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
 * check_antialias.c, check_distributed.c, check_textures.c, check_paths.c, check_instances.c,
 * check_picture.c); defined with CHECK()
 * below. */
#define CHECK(fn) bool fn(char *why, size_t why_size)

/* Says which of the student's functions the check calls next, and on what, in the student's terms
 * ("sphere_normal", "the point (2.155, 0.8453, 4.155) of the sphere of radius 2 around (1, 2, 3)"): when
 * the call crashes or never returns, the check's FAIL line names them. Does nothing outside a check's
 * process. */
void check_calling(const char *function, const char *format, ...) __attribute__((format(printf, 2, 3)));

/* How one check went: passed, or not with what is wrong in why. */
struct check_verdict {
    bool passed;
    char why[CHECK_WHY_SIZE];
};

/* Runs check c in a process of its own, stopped after `seconds`, and fills *v: the check's own verdict
 * when it returns; otherwise a failure saying what ended it (a signal, the limit, an early exit) and what
 * the check was calling (check_calling). */
void check_run_isolated(const struct check *c, int seconds, struct check_verdict *v);

/* For the checks: whether a and b agree within tolerance (per coordinate), and a vector as text. */
bool check_near(double a, double b, double tolerance);
bool check_vec_near(vec3 a, vec3 b, double tolerance);
const char *check_vec_text(vec3 v, char buffer[static 64]);

/* Whether one call added exactly 1 to a counter (`added`), as a contract that says "Counts one sphere
 * test" asks. When not, fails with why saying so: `function` called how ("sphere_intersect on a ray that
 * hits"), `what` it counts ("one sphere test") and `shown`, the counter's name in the chapter program's
 * output ("sphere tests"). */
bool check_counted_once(uint64_t added, const char *function, const char *what, const char *shown, char *why,
                        size_t why_size);

/* Parses `text`, the check's own scene, as the file check.scene with the shapes of `kinds`, into *s, and
 * makes its world *w. Returns false with the reason in why when either fails (a framework problem, not
 * the student's: the message says so), and then leaves nothing to free; else free both when done. */
struct scene;
struct world;
struct shape_kind;
bool check_scene_world(const char *text, const struct shape_kind *const *kinds, struct scene *s, struct world *w,
                       char *why, size_t why_size);

/* "a ray from (0, 0, 5) along (0, 0, -1)", for a check's messages. */
const char *check_ray_text(const ray *r, char buffer[static 160]);

#endif

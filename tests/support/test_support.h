/* test_support.h: small helpers shared by the test files: reading a text file, running a command with
 * its output kept in a log, parsing scene text that a test writes. */
#ifndef WHITTED_TEST_SUPPORT_H
#define WHITTED_TEST_SUPPORT_H

#include <stdbool.h>
#include <stddef.h>

struct shape_kind;
struct scene;

/* Every kind of shape (sphere, triangle, plane, box), as chapters 5 to 11 draw them, ending with NULL:
 * the kinds the tests give the scene reader when they build a world. */
extern const struct shape_kind *const test_every_kind[];

/* Reads the whole file at `path` into a new NUL-terminated buffer (the caller frees it). Fails the
 * current test if it is not a regular file or cannot be read. */
char *read_text_file(const char *path);

/* Reads the whole file at `path` as read_text_file does, and sets *size (when not NULL) to its length,
 * for files that may hold zero bytes. */
char *read_file(const char *path, size_t *size);

/* The environment variable that names this run of the tests, set before any test starts. */
#define TEST_RUN_VARIABLE "WHITTED_TEST_RUN"

/* Returns a name of this run of run-tests that no other run has (its process and start time), the same
 * in every test of the run; NULL if the run did not set one. */
const char *test_run_id(void);

/* Runs the shell command `command` with its standard output and error together into `output` (size
 * bytes, NUL-terminated, cut if longer). Returns its exit status, or -1 if it was killed. */
int run_capturing(const char *command, char *output, size_t size);

/* Runs the shell command `command` with its standard output and error appended to the file `log`,
 * after a line "$ command". Returns its exit status, or -1 if it could not run or was killed. */
int run_logged(const char *command, const char *log);

/* Parses `head` followed by `lines` and a newline as the scene file `name`, with the kinds of shape
 * `kinds` (as scene_parse takes them). Returns whether it parsed, the scene in *s (free it with
 * scene_free) and the message in err. */
bool parse_scene_lines(const char *name, const char *head, const char *lines, const struct shape_kind *const *kinds,
                       struct scene *s, char *err, size_t err_size);

/* Expects parse_scene_lines to refuse `lines` with exactly `message` (a failure of the current test
 * otherwise, naming the lines). */
void expect_scene_refused(const char *name, const char *head, const char *lines, const struct shape_kind *const *kinds,
                          const char *message);

#endif

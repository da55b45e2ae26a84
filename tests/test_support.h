/* test_support.h: small helpers shared by the test files: reading a text file, running a command with
 * its output kept in a log. */
#ifndef WHITTED_TEST_SUPPORT_H
#define WHITTED_TEST_SUPPORT_H

/* Reads the whole file at `path` into a new NUL-terminated buffer (the caller frees it). Fails the
 * current test if it is not a regular file or cannot be read. */
char *read_text_file(const char *path);

/* Runs the shell command `command` with its standard output and error appended to the file `log`,
 * after a line "$ command". Returns its exit status, or -1 if it could not run or was killed. */
int run_logged(const char *command, const char *log);

#endif

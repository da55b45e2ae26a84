/* outfile.h: output files that appear complete or not at all (chapter 1).
 *
 * The data goes to a temporary file beside the target ("name.tmpXXXXXX"), which is renamed over the
 * target only when everything was written. A crash, a full disk or an error therefore never leaves a
 * half-written picture or scene behind. */
#ifndef WHITTED_OUTFILE_H
#define WHITTED_OUTFILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

struct outfile {
    FILE *file;       /* write here */
    char *temp_path;  /* owned; the temporary file's name */
    const char *path; /* the target, borrowed from the caller */
};

/* Opens a temporary file for `path`. Returns false and writes "path: cannot create: reason" into err
 * on failure (e.g. the folder does not exist). */
bool outfile_open(struct outfile *f, const char *path, char *err, size_t err_size);

/* Closes the file and renames it to its target. If anything failed, now or while writing, removes the
 * temporary file, returns false and writes "path: cannot write: reason" into err. */
bool outfile_commit(struct outfile *f, char *err, size_t err_size);

/* Closes and removes the temporary file, leaving any existing target untouched. */
void outfile_abandon(struct outfile *f);

#endif

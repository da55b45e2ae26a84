/* outfile.h: output files that appear complete or not at all (chapter 1).
 *
 * A regular file (or a name that does not exist yet) is written to a temporary file beside it
 * ("name.tmpXXXXXX"), which is renamed over the target only when everything was written. A crash, a
 * full disk or an error therefore never leaves a half-written picture or scene behind. A symbolic link
 * is followed: the file it points to is replaced and the link stays a link.
 *
 * Anything else that exists (a FIFO, a device such as /dev/null or /dev/full) cannot be replaced by a
 * rename and is written directly; a write error there is still reported. The name "-" means standard
 * output, written directly too. */
#ifndef WHITTED_OUTFILE_H
#define WHITTED_OUTFILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* What outfile_open adds to a name for its temporary file; a name must leave room for it within
 * PATH_MAX (see outfile_name_fits). */
#define OUTFILE_TEMP_SUFFIX ".tmpXXXXXX"

struct outfile {
    FILE *file;       /* write here */
    char *temp_path;  /* owned; the temporary file's name, NULL when writing directly */
    char *target;     /* owned; the file that is replaced (symbolic links followed) */
    const char *path; /* the name given, borrowed from the caller, for messages */
    int error;        /* errno of the first failed outfile_write, 0 if none */
};

/* Opens `path` for writing as described above. Returns false and writes "path: cannot create: reason"
 * into err on failure (e.g. the folder does not exist). Opening a FIFO waits for its reader, as any
 * writer to a FIFO does. */
bool outfile_open(struct outfile *f, const char *path, char *err, size_t err_size);

/* Writes `size` bytes to the file, remembering why the first failed write failed (for the message of
 * outfile_commit). Returns false when the bytes could not be written. */
bool outfile_write(struct outfile *f, const void *data, size_t size);

/* Closes the file and (for a temporary file) renames it to its target. If anything failed, now or while
 * writing, removes the temporary file, returns false and writes "path: cannot write: reason" into err. */
bool outfile_commit(struct outfile *f, char *err, size_t err_size);

/* Closes and removes the temporary file, leaving any existing target untouched. (What was written
 * directly to a FIFO, device or standard output cannot be taken back.) */
void outfile_abandon(struct outfile *f);

/* Returns true when outfile_open could create `path` now: "-", an existing FIFO or device, or a name
 * whose folder takes a temporary file (one is made and removed at once). Otherwise returns false with
 * outfile_open's message, "path: cannot create: reason", in err: so that a program can say so before it
 * renders rather than after. A FIFO is not opened, which would wait for its reader. */
bool outfile_can_create(const char *path, char *err, size_t err_size);

/* Returns true when `path` is short enough to be written: its temporary name fits in PATH_MAX. A longer
 * name would be cut by the system, so callers refuse it before any work is done. */
bool outfile_name_fits(const char *path);

/* Returns true when `a` and `b` name one file: "-" twice, the same device and inode when both exist,
 * otherwise the same name once symbolic links and the folder are resolved. */
bool outfile_same_file(const char *a, const char *b);

/* Sets standard output aside for the file "-": later writes to "-" go to what standard output is now,
 * and standard output itself is pointed at standard error, so that everything else a program prints
 * (its counters) stays out of the data. Call it once, before anything is printed. Returns false (and
 * changes nothing) when the descriptors cannot be duplicated. */
bool outfile_reserve_stdout(void);

#endif

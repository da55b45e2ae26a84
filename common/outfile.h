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

/* Not a position: what outfile_index_find returns when no name of the index names the file. */
#define OUTFILE_INDEX_NONE ((size_t)-1)

/* A list of file names (the files a program reads), each looked at once, so that many other names (the
 * files it will write) can each be checked against all of them at the cost of one look at that name,
 * not one at every name of the list: a chapter 16 run of thousands of frames and thousands of object
 * files took minutes before it drew its first frame when every frame's name was compared with every
 * input by outfile_same_file. outfile_index_find's answer is outfile_same_file's, for the files as they
 * were when the index was built. */
struct outfile_index {
    struct outfile_index_file *files; /* owned; the names that exist, by device and inode */
    size_t file_count;
    struct outfile_index_name *names; /* owned; every name, by its text */
    size_t name_count;
    struct outfile_index_name *absent; /* owned; the names that do not exist (not "-"), links and folder resolved */
    size_t absent_count;
};

/* Builds the index of the `count` names at `names` (a NULL name names no file and is never found):
 * one stat of each, and for one that does not exist its name with links and folder resolved. The
 * names are borrowed: they must outlive the index. Returns false when memory runs out (the index is
 * then empty). Free it with outfile_index_free. */
bool outfile_index_build(struct outfile_index *index, const char *const *names, size_t count);

/* Returns the position (in the list given to outfile_index_build) of the first name for which
 * outfile_same_file(path, name) holds, or OUTFILE_INDEX_NONE when there is none; one stat of `path`,
 * and when it does not exist (and the index holds names that do not either) its name resolved. */
size_t outfile_index_find(const struct outfile_index *index, const char *path);

/* Frees the index and leaves it empty. */
void outfile_index_free(struct outfile_index *index);

/* Sets standard output aside for the file "-": later writes to "-" go to what standard output is now,
 * and standard output itself is pointed at standard error, so that everything else a program prints
 * (its counters) stays out of the data. Call it once, before anything is printed. Returns false (and
 * changes nothing) when the descriptors cannot be duplicated. */
bool outfile_reserve_stdout(void);

#endif

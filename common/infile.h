/* infile.h: opening an input file without ever waiting for it (chapter 1).
 *
 * Scene and mesh files are read whole, so they must be regular files. Anything else is refused before
 * a byte is read: opening a FIFO that has no writer would wait forever, and a device such as
 * /dev/zero never ends. */
#ifndef WHITTED_INFILE_H
#define WHITTED_INFILE_H

#include <stddef.h>
#include <stdio.h>

/* Opens the regular file `path` for reading. On failure returns NULL and writes into err either
 * "path: cannot open: reason" (missing, no permission) or "path: not a regular file (a FIFO)" (or a
 * directory, a device, a socket). Never blocks: the file is checked with stat, then opened with
 * O_NONBLOCK and checked again with fstat, so a FIFO put in its place in between is refused too. The
 * caller closes the FILE. */
FILE *infile_open(const char *path, char *err, size_t err_size);

/* Reads the whole regular file `path` (opened by infile_open) into a malloc'd buffer of its bytes and one
 * more, which the caller frees, and sets *size to their number. On failure returns NULL and writes into
 * err infile_open's message, "path: larger than N bytes" when the file holds more than max_bytes,
 * "path: cannot read" or "path: out of memory". */
unsigned char *infile_read_whole(const char *path, size_t max_bytes, size_t *size, char *err, size_t err_size);

#endif

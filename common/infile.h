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

#endif

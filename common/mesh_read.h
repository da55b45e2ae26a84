/* mesh_read.h: what the mesh readers share (chapter 3): the file in memory, messages, lines and words,
 * numbers, growing arrays. For mesh.c and the readers (mesh_ply.c, mesh_obj.c), not for other modules.
 *
 * mesh_load (mesh_load.c) reads the whole file into memory, followed by a NUL byte, and hands it to one
 * reader. The readers parse from that buffer with the functions below, grow the mesh with
 * mesh_reserve and mesh_add_triangle, and report problems with mesh_fail_*. On failure they may leave
 * a half-built mesh: mesh_load frees it, and it also refuses a successful read that found no faces.
 * mesh_read.c calls no reader, so the calls go one way: mesh.c, then a reader, then these helpers. */
#ifndef WHITTED_MESH_READ_H
#define WHITTED_MESH_READ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

/* Limits. A face has 3 to MESH_MAX_POLYGON_CORNERS corners; indices are uint32_t, so no more vertices
 * than MESH_MAX_VERTICES; files longer than MESH_MAX_FILE_BYTES are refused (which also stops reading
 * an endless file such as /dev/zero). */
#define MESH_MAX_POLYGON_CORNERS 1000
#define MESH_MAX_VERTICES ((size_t)UINT32_MAX)
#define MESH_MAX_FILE_BYTES ((size_t)1 << 30)

/* The file being read. data[size] is a NUL byte (not part of the file), so strtod and strtoll always
 * stop inside the buffer. */
struct mesh_input {
    const char *path;
    const char *data;
    size_t size;
    char *err;
    size_t err_size;
    struct mesh_corners *corners; /* where normals and texture coordinates go; NULL: read past them */
};

/* A run of characters inside the input buffer; not NUL-terminated (print it with "%.*s"). */
struct mesh_token {
    const char *text;
    int length;
};

/* How many characters of a token an error message shows. */
#define MESH_SHOWN_CHARS 40

/* The length to print a token with in messages: "'%.*s'", mesh_shown(t), t.text. */
static inline int mesh_shown(struct mesh_token token) {
    return token.length < MESH_SHOWN_CHARS ? token.length : MESH_SHOWN_CHARS;
}

/* Walks the input line by line. `line` is the 1-based number of the line last returned. */
struct mesh_lines {
    const char *data;
    size_t size;
    size_t next; /* offset of the first byte not yet returned */
    size_t line;
    const char *end; /* end of the line last returned (its '\n', or the end of the data) */
};

/* U+FEFF, the byte-order mark, as UTF-8: some editors start a text file with it. */
#define MESH_UTF8_BOM "\xef\xbb\xbf"

/* Each writes "path<location>: <message>" into in->err and returns false, so readers can write
 * `return mesh_fail_line(in, line, "...")`. The locations are ":LINE" (1-based), ": byte N" (0-based
 * offset) or nothing. */
bool mesh_fail_line(const struct mesh_input *in, size_t line, const char *format, ...)
    __attribute__((format(printf, 3, 4)));
bool mesh_fail_byte(const struct mesh_input *in, size_t byte, const char *format, ...)
    __attribute__((format(printf, 3, 4)));
bool mesh_fail_file(const struct mesh_input *in, const char *format, ...) __attribute__((format(printf, 2, 3)));

/* Starts walking `size` bytes of `data` from offset `start`, which is the first byte of line
 * `first_line`. */
void mesh_lines_begin(struct mesh_lines *lines, const char *data, size_t size, size_t start, size_t first_line);

/* Moves to the next line and returns a pointer to its first byte, or NULL at the end of the data. The
 * line ends at lines->end; a '\r' before the '\n' counts as white space. */
const char *mesh_lines_next(struct mesh_lines *lines);

/* Reads the next white-space separated word from *cursor up to `end`, moving *cursor past it. Returns
 * false (and leaves *token empty) when only white space is left. */
bool mesh_next_token(const char **cursor, const char *end, struct mesh_token *token);

/* Returns true when the token is exactly the NUL-terminated word `word`. */
bool mesh_token_is(struct mesh_token token, const char *word);

/* Reads the whole token as a number (strtod syntax, so also "nan" and "inf"). Returns false if any of
 * it is not part of the number. */
bool mesh_parse_double(struct mesh_token token, double *value);

/* Reads the whole token as a decimal integer. Returns false if it is not one or does not fit. */
bool mesh_parse_integer(struct mesh_token token, long long *value);

/* Makes room for `wanted` items of `item_size` bytes in *array (allocated length *capacity items):
 * twice the capacity (16 at first), or `wanted` exactly when that is more; an array of 1 MB or more is
 * moved to 2 MB pages (big_alloc.h), and any is released with free(). Returns false, leaving the array
 * as it was, when out of memory. Callers pass the address of a void pointer:
 * `void *a = m->faces; ok = mesh_reserve(&a, ...); m->faces = a;`, or use the wrapper below. */
bool mesh_reserve(void **array, size_t *capacity, size_t wanted, size_t item_size);

/* mesh_reserve for m->faces. */
bool mesh_reserve_faces(struct mesh *m, size_t *capacity, size_t wanted);

/* Appends the triangle (a, b, c), growing the face array when it is full; false when out of memory. */
bool mesh_add_triangle(struct mesh *m, size_t *capacity, uint32_t a, uint32_t b, uint32_t c);

#endif

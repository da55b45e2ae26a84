/* mesh_load.c: loading a triangle mesh from a PLY or OBJ file (chapter 3).
 *
 * mesh_load reads the whole file into memory with a NUL byte after it, looks at its first line to
 * choose the reader (mesh_ply.c or mesh_obj.c) and makes sure a failed load leaves nothing behind.
 * What both readers share (messages, lines and words, numbers, growing arrays) is in mesh_read.c. */
#include "mesh_load.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "infile.h"
#include "mesh_obj.h"
#include "mesh_ply.h"
#include "mesh_read.h"

#define READ_CHUNK_BYTES ((size_t)1 << 16) /* first buffer size when the file's size is unknown */

/* The size to allocate first: the file's own size plus one byte, so that the first read already meets
 * the end of the file; a guess if its size cannot be known. */
static bool initial_capacity(const struct mesh_input *in, FILE *file, size_t *capacity) {
    struct stat info;
    *capacity = READ_CHUNK_BYTES;
    if (fstat(fileno(file), &info) != 0 || !S_ISREG(info.st_mode))
        return true;
    if ((uintmax_t)info.st_size > MESH_MAX_FILE_BYTES)
        return mesh_fail_file(in, "file too large (%jd bytes; the limit is %zu)", (intmax_t)info.st_size,
                              MESH_MAX_FILE_BYTES);
    *capacity = (size_t)info.st_size + 1;
    return true;
}

/* Doubles the buffer, up to one byte more than MESH_MAX_FILE_BYTES (a file that fills that is too
 * long). Keeps room for a NUL after the last byte. */
static bool grow_buffer(const struct mesh_input *in, char **buffer, size_t *capacity) {
    if (*capacity > MESH_MAX_FILE_BYTES)
        return mesh_fail_file(in, "file too large (more than %zu bytes)", MESH_MAX_FILE_BYTES);
    size_t new_capacity = *capacity * 2;
    if (new_capacity > MESH_MAX_FILE_BYTES + 1)
        new_capacity = MESH_MAX_FILE_BYTES + 1;
    char *grown = realloc(*buffer, new_capacity + 1);
    if (grown == NULL)
        return mesh_fail_file(in, "out of memory reading the file");
    *buffer = grown;
    *capacity = new_capacity;
    return true;
}

/* Reads the whole file into a new buffer with a NUL after its last byte. Refuses anything but a regular
 * file (infile.h), and more than MESH_MAX_FILE_BYTES even if the file grows while it is read. */
static bool read_file(const char *path, char **data, size_t *size, char *err, size_t err_size) {
    struct mesh_input in = {.path = path, .err = err, .err_size = err_size};
    *data = NULL;
    *size = 0;
    FILE *file = infile_open(path, err, err_size); /* a regular file, or refused without waiting */
    if (file == NULL)
        return false;
    size_t capacity, used = 0;
    char *buffer = NULL;
    bool ok = initial_capacity(&in, file, &capacity);
    if (ok && (buffer = malloc(capacity + 1)) == NULL) /* + 1 for the final NUL */
        ok = mesh_fail_file(&in, "out of memory reading the file");
    while (ok) {
        errno = 0;
        used += fread(buffer + used, 1, capacity - used, file);
        if (ferror(file))
            ok = mesh_fail_file(&in, "cannot read: %s", strerror(errno != 0 ? errno : EIO));
        else if (feof(file))
            break;
        else if (used == capacity)
            ok = grow_buffer(&in, &buffer, &capacity);
    }
    fclose(file);
    if (!ok) {
        free(buffer);
        return false;
    }
    buffer[used] = '\0';
    *data = buffer;
    *size = used;
    return true;
}

/* A PLY file's first line is exactly "ply" (LF or CRLF). */
static bool starts_as_ply(const char *data, size_t size) {
    return (size >= 4 && memcmp(data, "ply\n", 4) == 0) || (size >= 5 && memcmp(data, "ply\r\n", 5) == 0);
}

bool mesh_load(const char *path, struct mesh *m, char *err, size_t err_size) {
    return mesh_load_with_corners(path, m, NULL, err, err_size);
}

bool mesh_load_with_corners(const char *path, struct mesh *m, struct mesh_corners *corners, char *err,
                            size_t err_size) {
    *m = (struct mesh){0};
    if (corners != NULL)
        *corners = (struct mesh_corners){0};
    char *data;
    size_t size;
    if (!read_file(path, &data, &size, err, err_size))
        return false;
    struct mesh_input in = {.path = path, .data = data, .size = size, .err = err, .err_size = err_size,
                            .corners = corners};
    bool ok;
    if (size == 0)
        ok = mesh_fail_file(&in, "empty file");
    else if (starts_as_ply(data, size))
        ok = mesh_read_ply(&in, m);
    else
        ok = mesh_read_obj(&in, m);
    if (ok && m->face_count == 0)
        ok = mesh_fail_file(&in, "no faces");
    free(data);
    if (!ok) {
        mesh_free(m);
        if (corners != NULL)
            mesh_corners_free(corners);
    }
    return ok;
}

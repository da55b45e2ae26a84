/* mesh.c: loading, freeing and placing triangle meshes (chapter 3).
 *
 * mesh_load reads the whole file into memory with a NUL byte after it, looks at its first line to
 * choose the reader (mesh_ply.c or mesh_obj.c) and makes sure a failed load leaves nothing behind.
 * This file also holds what both readers share: error messages, splitting text into lines and words,
 * strict number parsing and growing the vertex and face arrays. */
#include "mesh.h"

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "infile.h"
#include "mesh_private.h"

#define READ_CHUNK_BYTES ((size_t)1 << 16) /* first buffer size when the file's size is unknown */

/* ---- error messages ------------------------------------------------------------------------- */

/* Writes "<path><location>: <message>" into in->err; returns false. */
static bool fail(const struct mesh_input *in, const char *location, const char *format, va_list args) {
    if (in->err == NULL || in->err_size == 0)
        return false;
    int used = snprintf(in->err, in->err_size, "%s%s: ", in->path, location);
    if (used >= 0 && (size_t)used < in->err_size)
        vsnprintf(in->err + used, in->err_size - (size_t)used, format, args);
    return false;
}

bool mesh_fail_line(const struct mesh_input *in, size_t line, const char *format, ...) {
    char location[32];
    snprintf(location, sizeof location, ":%zu", line);
    va_list args;
    va_start(args, format);
    fail(in, location, format, args);
    va_end(args);
    return false;
}

bool mesh_fail_byte(const struct mesh_input *in, size_t byte, const char *format, ...) {
    char location[40];
    snprintf(location, sizeof location, ": byte %zu", byte);
    va_list args;
    va_start(args, format);
    fail(in, location, format, args);
    va_end(args);
    return false;
}

bool mesh_fail_file(const struct mesh_input *in, const char *format, ...) {
    va_list args;
    va_start(args, format);
    fail(in, "", format, args);
    va_end(args);
    return false;
}

/* ---- lines, words and numbers ----------------------------------------------------------------- */

/* White space inside a line; '\r' is included so that CRLF files read like LF files. */
static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

void mesh_lines_begin(struct mesh_lines *lines, const char *data, size_t size, size_t start, size_t first_line) {
    *lines = (struct mesh_lines){.data = data, .size = size, .next = start, .line = first_line - 1, .end = NULL};
}

const char *mesh_lines_next(struct mesh_lines *lines) {
    if (lines->next >= lines->size)
        return NULL;
    const char *start = lines->data + lines->next;
    const char *newline = memchr(start, '\n', lines->size - lines->next);
    lines->end = newline != NULL ? newline : lines->data + lines->size;
    lines->next = (size_t)(lines->end - lines->data) + 1;
    lines->line++;
    return start;
}

bool mesh_next_token(const char **cursor, const char *end, struct mesh_token *token) {
    const char *p = *cursor;
    while (p < end && is_blank(*p))
        p++;
    const char *start = p;
    while (p < end && !is_blank(*p))
        p++;
    *cursor = p;
    /* A line cannot be longer than the file, but a token length must fit an int for "%.*s". */
    size_t length = (size_t)(p - start);
    *token = (struct mesh_token){start, length > INT_MAX ? INT_MAX : (int)length};
    return p > start;
}

bool mesh_token_is(struct mesh_token token, const char *word) {
    return strlen(word) == (size_t)token.length && memcmp(token.text, word, (size_t)token.length) == 0;
}

/* The token ends at white space, at '\n' or at the buffer's final NUL, none of which can continue a
 * number, so strtod and strtoll never read past it; they stop early exactly when the token is bad. */
bool mesh_parse_double(struct mesh_token token, double *value) {
    if (token.length == 0)
        return false;
    char *end;
    *value = strtod(token.text, &end);
    return end == token.text + token.length;
}

bool mesh_parse_integer(struct mesh_token token, long long *value) {
    if (token.length == 0 || is_blank(token.text[0]))
        return false;
    char *end;
    errno = 0;
    *value = strtoll(token.text, &end, 10);
    return errno == 0 && end == token.text + token.length;
}

/* ---- growing arrays --------------------------------------------------------------------------- */

bool mesh_reserve(void **array, size_t *capacity, size_t wanted, size_t item_size) {
    if (wanted <= *capacity)
        return true;
    size_t new_capacity = *capacity < 16 ? 16 : *capacity;
    while (new_capacity < wanted)
        new_capacity = new_capacity > SIZE_MAX / 2 ? wanted : new_capacity * 2;
    if (new_capacity > SIZE_MAX / item_size)
        return false;
    void *grown = realloc(*array, new_capacity * item_size);
    if (grown == NULL)
        return false;
    *array = grown;
    *capacity = new_capacity;
    return true;
}

bool mesh_reserve_faces(struct mesh *m, size_t *capacity, size_t wanted) {
    void *array = m->faces;
    bool ok = mesh_reserve(&array, capacity, wanted, sizeof *m->faces);
    m->faces = array;
    return ok;
}

bool mesh_add_triangle(struct mesh *m, size_t *capacity, uint32_t a, uint32_t b, uint32_t c) {
    if (!mesh_reserve_faces(m, capacity, m->face_count + 1))
        return false;
    m->faces[m->face_count++] = (struct mesh_face){{a, b, c}};
    return true;
}

/* ---- loading ---------------------------------------------------------------------------------- */

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
    *m = (struct mesh){0};
    char *data;
    size_t size;
    if (!read_file(path, &data, &size, err, err_size))
        return false;
    struct mesh_input in = {.path = path, .data = data, .size = size, .err = err, .err_size = err_size};
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
    if (!ok)
        mesh_free(m);
    return ok;
}

void mesh_free(struct mesh *m) {
    free(m->vertices);
    free(m->faces);
    *m = (struct mesh){0};
}

/* ---- placing ---------------------------------------------------------------------------------- */

/* Sine and cosine of an angle in degrees, exact for multiples of 90 so that axis-aligned meshes stay
 * exactly axis-aligned (cos(pi / 2) is 6e-17 in floating point, not 0). */
static void sin_cos_degrees(double degrees, double *s, double *c) {
    double turn = fmod(degrees, 360.0);
    if (turn < 0)
        turn += 360.0;
    if (turn == 0.0 || turn == 90.0 || turn == 180.0 || turn == 270.0) {
        static const double quarter_sin[4] = {0, 1, 0, -1}, quarter_cos[4] = {1, 0, -1, 0};
        int quarter = (int)(turn / 90.0);
        *s = quarter_sin[quarter];
        *c = quarter_cos[quarter];
        return;
    }
    double radians = turn * (M_PI / 180.0);
    *s = sin(radians);
    *c = cos(radians);
}

void mesh_transform(struct mesh *m, double scale, vec3 rotate_degrees, vec3 translate) {
    double sx, cx, sy, cy, sz, cz;
    sin_cos_degrees(rotate_degrees.x, &sx, &cx);
    sin_cos_degrees(rotate_degrees.y, &sy, &cy);
    sin_cos_degrees(rotate_degrees.z, &sz, &cz);
    for (size_t k = 0; k < m->vertex_count; k++) {
        vec3 p = vec3_scale(m->vertices[k], scale);
        p = (vec3){p.x, p.y * cx - p.z * sx, p.y * sx + p.z * cx}; /* about x: (y, z) turn */
        p = (vec3){p.z * sy + p.x * cy, p.y, p.z * cy - p.x * sy}; /* about y: (z, x) turn */
        p = (vec3){p.x * cz - p.y * sz, p.x * sz + p.y * cz, p.z}; /* about z: (x, y) turn */
        m->vertices[k] = vec3_add(p, translate);
    }
}

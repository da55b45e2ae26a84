/* mesh_read.c: what the mesh readers share (chapter 3): error messages that name the file and the line
 * or byte, splitting text into lines and words, strict number parsing, and growing the vertex and face
 * arrays. mesh_ply.c and mesh_obj.c call these; this file calls neither of them (see mesh_read.h). */
#include "mesh_read.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

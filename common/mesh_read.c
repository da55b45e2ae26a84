/* mesh_read.c: what the mesh readers share (chapter 3): error messages that name the file and the line
 * or byte, splitting text into lines and words, strict number parsing, and growing the vertex and face
 * arrays. mesh_ply.c and mesh_obj.c call these; this file calls neither of them (see mesh_read.h). */
#include "mesh_read.h"

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"

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

/* ---- numbers ----------------------------------------------------------------------------------- */

/* A decimal number m x 10^e is exact in one multiplication or division when m and 10^|e| are both
 * exact doubles (m up to 2^53, |e| up to 22): the one rounding of that operation is then the correct
 * rounding of the decimal, which is what strtod gives (Clinger's fast path, 1990). Most numbers in mesh
 * files ("0.0312", "-1.25e-3") are such numbers; the rest (more digits, far exponents, nan, inf, hex)
 * go to strtod. Only where double arithmetic rounds each operation to double (FLT_EVAL_METHOD 0, as on
 * x86-64, ARM and WebAssembly); elsewhere every number goes to strtod. */
#define FAST_MAX_MANTISSA ((uint64_t)1 << 53)
#define FAST_MAX_DIGITS 19   /* decimal digits that always fit in a uint64_t */
#define FAST_MAX_EXPONENT 22 /* the largest power of ten that is an exact double */
#define FAST_MAX_EXPONENT_DIGITS 4

/* The exact doubles 10^0 .. 10^FAST_MAX_EXPONENT. */
static const double POWERS_OF_TEN[FAST_MAX_EXPONENT + 1] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                            1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                            1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static bool is_digit(char c) { return c >= '0' && c <= '9'; }

/* Reads the whole token as [+-]digits[.digits][(e|E)[+-]digits] by the fast path above; false when the
 * token is anything else or the fast path cannot give the correctly rounded value (then strtod must). */
static bool parse_simple_decimal(struct mesh_token token, double *value) {
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    const char *p = token.text, *end = token.text + token.length;
    bool negative = p < end && *p == '-';
    if (p < end && (*p == '-' || *p == '+'))
        p++;
    uint64_t mantissa = 0;
    int digits = 0, exponent = 0;
    for (; p < end && is_digit(*p); p++, digits++)
        mantissa = mantissa * 10 + (uint64_t)(*p - '0');
    if (p < end && *p == '.')
        for (p++; p < end && is_digit(*p); p++, digits++, exponent--)
            mantissa = mantissa * 10 + (uint64_t)(*p - '0');
    if (digits == 0 || digits > FAST_MAX_DIGITS)
        return false;
    if (p < end && (*p == 'e' || *p == 'E')) {
        p++;
        bool negative_exponent = p < end && *p == '-';
        if (p < end && (*p == '-' || *p == '+'))
            p++;
        int written = 0, e = 0;
        for (; p < end && is_digit(*p) && written < FAST_MAX_EXPONENT_DIGITS; p++, written++)
            e = e * 10 + (*p - '0');
        if (written == 0)
            return false;
        exponent += negative_exponent ? -e : e;
    }
    if (p != end || mantissa > FAST_MAX_MANTISSA || exponent < -FAST_MAX_EXPONENT || exponent > FAST_MAX_EXPONENT)
        return false;
    double m = (double)mantissa; /* exact: at most 2^53 */
    double magnitude = exponent >= 0 ? m * POWERS_OF_TEN[exponent] : m / POWERS_OF_TEN[-exponent];
    *value = negative ? -magnitude : magnitude;
    return true;
#else
    (void)token;
    (void)value;
    return false;
#endif
}

/* The token ends at white space, at '\n' or at the buffer's final NUL, none of which can continue a
 * number, so strtod and strtoll never read past it; they stop early exactly when the token is bad.
 * strtod would also read C's hexadecimal (0x1p1 as 2), which neither format has, and which the scene
 * format refuses too. */
bool mesh_parse_double(struct mesh_token token, double *value) {
    if (token.length == 0)
        return false;
    if (parse_simple_decimal(token, value))
        return true;
    if (memchr(token.text, 'x', token.length) != NULL || memchr(token.text, 'X', token.length) != NULL)
        return false;
    char *end;
    *value = strtod(token.text, &end);
    return end == token.text + token.length;
}

/* Decimal digits that always fit in a long long, read without strtoll. */
#define FAST_MAX_INTEGER_DIGITS 18

bool mesh_parse_integer(struct mesh_token token, long long *value) {
    if (token.length == 0 || is_blank(token.text[0]))
        return false;
    const char *p = token.text, *end = token.text + token.length;
    bool negative = *p == '-';
    if (*p == '-' || *p == '+')
        p++;
    if (p < end && end - p <= FAST_MAX_INTEGER_DIGITS) { /* the common case: a few digits */
        long long magnitude = 0;
        while (p < end && is_digit(*p))
            magnitude = magnitude * 10 + (*p++ - '0');
        if (p == end) {
            *value = negative ? -magnitude : magnitude;
            return true;
        }
    }
    char *stop;
    errno = 0;
    *value = strtoll(token.text, &stop, 10);
    return errno == 0 && stop == token.text + token.length;
}

/* ---- growing arrays --------------------------------------------------------------------------- */

/* The room an empty array gets first, in items: enough for a small model's first lines. */
#define MESH_FIRST_CAPACITY 16

bool mesh_reserve(void **array, size_t *capacity, size_t wanted, size_t item_size) {
    if (wanted <= *capacity)
        return true;
    /* Twice the room, for an array grown an item at a time; or, asked for more than that at once (a
     * PLY reader knows its counts), exactly what is wanted: a power of two above it would leave up to
     * half the array unused, and the 2 MB page it ends in resident all the same. */
    size_t new_capacity = *capacity == 0 ? MESH_FIRST_CAPACITY : *capacity <= SIZE_MAX / 2 ? 2 * *capacity : SIZE_MAX;
    if (new_capacity < wanted)
        new_capacity = wanted;
    if (new_capacity > SIZE_MAX / item_size)
        return false;
    void *grown = big_alloc(new_capacity * item_size, true); /* a big model's arrays on 2 MB pages */
    if (grown == NULL)
        return false;
    if (*capacity > 0)
        memcpy(grown, *array, *capacity * item_size);
    free(*array);
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

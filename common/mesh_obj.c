/* mesh_obj.c: the Wavefront OBJ reader.
 *
 * Only two statements matter for a triangle mesh:
 *
 *     v x y z [w]        a vertex (w, or the r g b colours some programs append, are ignored)
 *     f c1 c2 c3 ...     a face; each corner is i, i/t, i//n or i/t/n, where i is a vertex index
 *
 * Indices count from 1 in the order the vertices appear; a negative index counts back from the last
 * vertex read so far (-1 is the latest). Texture (t) and normal (n) indices are checked for syntax
 * only. Everything after '#' is a comment, and every other statement (vt, vn, g, o, s, usemtl, mtllib,
 * l, p, ...) is ignored. Positive indices may refer to vertices that come later in the file, so their
 * range is checked once the whole file is read. Errors read "file:LINE: what is wrong". */
#include <math.h>
#include <stdlib.h>

#include "mesh_obj.h"

#define OBJ_INDEX_SATURATION 1000000000000LL /* larger digit strings stop growing: no overflow */

struct obj_reader {
    const struct mesh_input *in;
    struct mesh *mesh;
    size_t vertex_capacity, face_capacity;
    size_t line;
    long long highest_index;        /* the largest absolute (1-based) index used so far */
    struct mesh_token highest_text; /* how it was written, and where, for the message */
    size_t highest_line;
};

/* Reads the next word of a statement, stopping at a comment. */
static bool next_word(const char **cursor, const char *end, struct mesh_token *word) {
    return mesh_next_token(cursor, end, word) && word->text[0] != '#';
}

/* Reads "v x y z ...", the statement's words from *cursor. */
static bool read_vertex(struct obj_reader *r, const char *cursor, const char *end) {
    static const char *const axis_names[] = {"x", "y", "z"};
    double xyz[3];
    int count = 0;
    struct mesh_token word;
    for (; next_word(&cursor, end, &word); count++) {
        double value;
        if (!mesh_parse_double(word, &value))
            return mesh_fail_line(r->in, r->line, "'%.*s' is not a number", mesh_shown(word), word.text);
        if (count < 3 && !isfinite(value))
            return mesh_fail_line(r->in, r->line, "%s is not a finite number (%g)", axis_names[count], value);
        if (count < 3)
            xyz[count] = value;
    }
    if (count < 3)
        return mesh_fail_line(r->in, r->line, "a vertex needs x, y and z (found %d numbers)", count);
    struct mesh *m = r->mesh;
    if (m->vertex_count == MESH_MAX_VERTICES)
        return mesh_fail_line(r->in, r->line, "more than %zu vertices", MESH_MAX_VERTICES);
    void *array = m->vertices;
    bool ok = mesh_reserve(&array, &r->vertex_capacity, m->vertex_count + 1, sizeof *m->vertices);
    m->vertices = array;
    if (!ok)
        return mesh_fail_line(r->in, r->line, "out of memory");
    m->vertices[m->vertex_count++] = (vec3){xyz[0], xyz[1], xyz[2]};
    return true;
}

/* Reads an optionally signed decimal integer from *p (before end), moving *p past it. */
static bool scan_integer(const char **p, const char *end, long long *value) {
    const char *s = *p;
    bool negative = s < end && *s == '-';
    if (s < end && (*s == '-' || *s == '+'))
        s++;
    const char *digits = s;
    long long v = 0;
    for (; s < end && *s >= '0' && *s <= '9'; s++)
        if (v < OBJ_INDEX_SATURATION)
            v = v * 10 + (*s - '0');
    if (s == digits)
        return false;
    *p = s;
    *value = negative ? -v : v;
    return true;
}

/* Splits a corner i, i/t, i//n or i/t/n; returns its vertex index and how it was written. */
static bool parse_corner(struct mesh_token corner, long long *index, struct mesh_token *index_text) {
    const char *p = corner.text, *end = corner.text + corner.length;
    long long ignored;
    if (!scan_integer(&p, end, index))
        return false;
    *index_text = (struct mesh_token){corner.text, (int)(p - corner.text)};
    if (p == end)
        return true; /* i */
    if (*p++ != '/')
        return false;
    bool has_texture = scan_integer(&p, end, &ignored);
    if (p == end)
        return has_texture; /* i/t */
    if (*p++ != '/' || !scan_integer(&p, end, &ignored))
        return false;
    return p == end; /* i/t/n or i//n */
}

/* Turns a corner's index into a 0-based vertex index. */
static bool resolve_corner(struct obj_reader *r, struct mesh_token corner, uint32_t *vertex) {
    long long index;
    struct mesh_token text;
    if (!parse_corner(corner, &index, &text))
        return mesh_fail_line(r->in, r->line, "'%.*s' is not a face corner (expected i, i/t, i//n or i/t/n)",
                              mesh_shown(corner), corner.text);
    size_t so_far = r->mesh->vertex_count;
    if (index == 0)
        return mesh_fail_line(r->in, r->line, "index 0 is invalid (OBJ indices start at 1)");
    if (index < 0) {
        if (-index > (long long)so_far)
            return mesh_fail_line(r->in, r->line,
                                  "index %.*s reaches before the first vertex (%zu vertices so far)",
                                  mesh_shown(text), text.text, so_far);
        *vertex = (uint32_t)((long long)so_far + index);
        return true;
    }
    if (index > r->highest_index) {
        r->highest_index = index;
        r->highest_text = text;
        r->highest_line = r->line;
    }
    *vertex = (uint32_t)(index - 1); /* checked against the vertex count at the end of the file */
    return true;
}

/* Reads "f c1 c2 c3 ...", the statement's words from *cursor, as a fan of triangles. */
static bool read_face(struct obj_reader *r, const char *cursor, const char *end) {
    struct mesh_token corner;
    size_t corners = 0;
    for (const char *counter = cursor; next_word(&counter, end, &corner);)
        corners++;
    if (corners < 3 || corners > MESH_MAX_POLYGON_CORNERS)
        return mesh_fail_line(r->in, r->line, "%zu corners (a face needs 3 to %d)", corners,
                              MESH_MAX_POLYGON_CORNERS);
    uint32_t first = 0, previous = 0;
    for (size_t k = 0; k < corners; k++) {
        uint32_t vertex = 0;
        next_word(&cursor, end, &corner);
        if (!resolve_corner(r, corner, &vertex))
            return false;
        if (k >= 2 && !mesh_add_triangle(r->mesh, &r->face_capacity, first, previous, vertex))
            return mesh_fail_line(r->in, r->line, "out of memory");
        if (k == 0)
            first = vertex;
        previous = vertex;
    }
    return true;
}

bool mesh_read_obj(const struct mesh_input *in, struct mesh *m) {
    struct obj_reader r = {.in = in, .mesh = m};
    struct mesh_lines lines;
    mesh_lines_begin(&lines, in->data, in->size, 0, 1);
    const char *cursor;
    while ((cursor = mesh_lines_next(&lines)) != NULL) {
        r.line = lines.line;
        struct mesh_token keyword;
        if (!next_word(&cursor, lines.end, &keyword))
            continue; /* blank or comment */
        bool ok = true;
        if (mesh_token_is(keyword, "v"))
            ok = read_vertex(&r, cursor, lines.end);
        else if (mesh_token_is(keyword, "f"))
            ok = read_face(&r, cursor, lines.end);
        if (!ok)
            return false;
    }
    if (r.highest_index > (long long)m->vertex_count)
        return mesh_fail_line(in, r.highest_line, "index %.*s out of range (%zu vertices)",
                              mesh_shown(r.highest_text), r.highest_text.text, m->vertex_count);
    return true;
}

/* mesh_obj.c: the Wavefront OBJ reader (chapter 3).
 *
 * Four statements matter for a triangle mesh (vt, vn and the t and n of the corners only when the caller
 * keeps them, mesh_load_with_corners; otherwise they are read past, t and n checked for syntax only):
 *
 *     v x y z [w]        a vertex (w, or the r g b colours some programs append, are ignored)
 *     vt u [v [w]]       a texture coordinate (v is 0 when missing; w is ignored)
 *     vn x y z           a normal (made unit length when the mesh is drawn smooth)
 *     f c1 c2 c3 ...     a face; each corner is i, i/t, i//n or i/t/n, where i is a vertex index, t a
 *                        texture coordinate's and n a normal's
 *
 * Each kind of index counts from 1 in the order its statements appear; a negative index counts back
 * from the last one read so far (-1 is the latest). Either every corner of the file gives a texture
 * index or none does, and the same for normals, so that every face can be drawn alike. Everything after
 * '#' is a comment, and every other statement (g, o, s, usemtl, mtllib, l, p, ...) is ignored. Positive
 * indices may refer to statements that come later in the file, so their range is checked once the
 * whole file is read. Errors read "file:LINE: what is wrong". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_obj.h"

#define OBJ_INDEX_SATURATION 1000000000000LL /* larger digit strings stop growing: no overflow */

/* The three kinds of index a corner holds. */
enum obj_index { OBJ_VERTEX, OBJ_TEXTURE, OBJ_NORMAL, OBJ_INDEX_KINDS };

/* For messages: what each kind of index points at, one and many. */
static const char *const obj_index_one[OBJ_INDEX_KINDS] = {"vertex", "texture coordinate", "normal"};
static const char *const obj_index_many[OBJ_INDEX_KINDS] = {"vertices", "texture coordinates", "normals"};
static const char *const obj_index_name[OBJ_INDEX_KINDS] = {"index", "vt index", "vn index"};

struct obj_reader {
    const struct mesh_input *in;
    struct mesh *mesh;
    size_t vertex_capacity, face_capacity, normal_capacity, uv_capacity, normal_face_capacity, uv_face_capacity;
    size_t line;
    /* For each kind of index: the largest absolute (1-based) index used so far, how it was written and
     * where, for the message if it turns out to be out of range. */
    long long highest_index[OBJ_INDEX_KINDS];
    struct mesh_token highest_text[OBJ_INDEX_KINDS];
    size_t highest_line[OBJ_INDEX_KINDS];
    int corners_with[OBJ_INDEX_KINDS]; /* texture and normal: -1 before the first corner, then 0 or 1 */
};

/* How many statements of each kind have been read so far. */
static size_t so_far(const struct obj_reader *r, enum obj_index kind) {
    const struct mesh_corners *c = r->in->corners;
    return kind == OBJ_VERTEX ? r->mesh->vertex_count : kind == OBJ_TEXTURE ? c->uv_count : c->normal_count;
}

/* Reads the next word of a statement, stopping at a comment. */
static bool next_word(const char **cursor, const char *end, struct mesh_token *word) {
    return mesh_next_token(cursor, end, word) && word->text[0] != '#';
}

/* Reads the numbers of a statement from *cursor into values[0..needed) (at least `needed` of them, at
 * most `wanted`, the rest ignored; values[needed..wanted) are 0 when missing), each finite. */
static bool read_numbers(struct obj_reader *r, const char *cursor, const char *end, const char *const *names,
                         int needed, int wanted, const char *what, double *values) {
    int count = 0;
    struct mesh_token word;
    for (int k = 0; k < wanted; k++)
        values[k] = 0.0;
    for (; next_word(&cursor, end, &word); count++) {
        double value;
        if (!mesh_parse_double(word, &value))
            return mesh_fail_line(r->in, r->line, "'%.*s' is not a number", mesh_shown(word), word.text);
        if (count < wanted && !isfinite(value))
            return mesh_fail_line(r->in, r->line, "%s is not a finite number (%g)", names[count], value);
        if (count < wanted)
            values[count] = value;
    }
    if (count < needed)
        return mesh_fail_line(r->in, r->line, "%s (found %d numbers)", what, count);
    return true;
}

/* Reads "vt u [v [w]]" into the texture coordinates. */
static bool read_uv(struct obj_reader *r, const char *cursor, const char *end) {
    static const char *const names[] = {"u", "v"};
    double uv[2];
    if (!read_numbers(r, cursor, end, names, 1, 2, "a texture coordinate needs u", uv))
        return false;
    struct mesh_corners *m = r->in->corners;
    void *array = m->uvs;
    bool ok = m->uv_count < MESH_MAX_VERTICES && mesh_reserve(&array, &r->uv_capacity, m->uv_count + 1, sizeof *m->uvs);
    m->uvs = array;
    if (!ok)
        return mesh_fail_line(r->in, r->line, "out of memory");
    m->uvs[m->uv_count++] = (struct mesh_uv){uv[0], uv[1]};
    return true;
}

/* Reads "vn x y z" into the normals. */
static bool read_normal(struct obj_reader *r, const char *cursor, const char *end) {
    static const char *const names[] = {"x", "y", "z"};
    double xyz[3];
    if (!read_numbers(r, cursor, end, names, 3, 3, "a normal needs x, y and z", xyz))
        return false;
    struct mesh_corners *m = r->in->corners;
    void *array = m->normals;
    bool ok = m->normal_count < MESH_MAX_VERTICES &&
              mesh_reserve(&array, &r->normal_capacity, m->normal_count + 1, sizeof *m->normals);
    m->normals = array;
    if (!ok)
        return mesh_fail_line(r->in, r->line, "out of memory");
    m->normals[m->normal_count++] = (vec3){xyz[0], xyz[1], xyz[2]};
    return true;
}

/* Reads "v x y z ...", the statement's words from *cursor. */
static bool read_vertex(struct obj_reader *r, const char *cursor, const char *end) {
    static const char *const axis_names[] = {"x", "y", "z"};
    double xyz[3];
    if (!read_numbers(r, cursor, end, axis_names, 3, 3, "a vertex needs x, y and z", xyz))
        return false;
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

/* Splits a corner i, i/t, i//n or i/t/n into its indices (0 where one is not given) and how each was
 * written (an empty text where one is not given: an index written 0 is given, and invalid). */
static bool parse_corner(struct mesh_token corner, long long index[OBJ_INDEX_KINDS],
                         struct mesh_token text[OBJ_INDEX_KINDS]) {
    const char *p = corner.text, *end = corner.text + corner.length;
    for (int k = 0; k < OBJ_INDEX_KINDS; k++) {
        index[k] = 0;
        text[k] = (struct mesh_token){end, 0}; /* not given */
    }
    if (!scan_integer(&p, end, &index[OBJ_VERTEX]))
        return false;
    text[OBJ_VERTEX] = (struct mesh_token){corner.text, (int)(p - corner.text)};
    if (p == end)
        return true; /* i */
    if (*p++ != '/')
        return false;
    const char *t = p;
    bool has_texture = scan_integer(&p, end, &index[OBJ_TEXTURE]);
    text[OBJ_TEXTURE] = (struct mesh_token){t, (int)(p - t)};
    if (p == end)
        return has_texture; /* i/t */
    if (*p++ != '/')
        return false;
    const char *n = p;
    if (!scan_integer(&p, end, &index[OBJ_NORMAL]))
        return false;
    text[OBJ_NORMAL] = (struct mesh_token){n, (int)(p - n)};
    return p == end; /* i/t/n or i//n */
}

/* Turns a corner's index of one kind (not 0: resolve_corner refuses it) into a 0-based index. */
static bool resolve_index(struct obj_reader *r, enum obj_index kind, long long index, struct mesh_token text,
                          uint32_t *out) {
    size_t count = so_far(r, kind);
    if (index < 0) {
        if (-index > (long long)count)
            return mesh_fail_line(r->in, r->line, "%s %.*s reaches before the first %s (%zu %s so far)",
                                  obj_index_name[kind], mesh_shown(text), text.text, obj_index_one[kind], count,
                                  obj_index_many[kind]);
        *out = (uint32_t)((long long)count + index);
        return true;
    }
    if (index > r->highest_index[kind]) {
        r->highest_index[kind] = index;
        r->highest_text[kind] = text;
        r->highest_line[kind] = r->line;
    }
    *out = (uint32_t)(index - 1); /* checked against the count at the end of the file */
    return true;
}

/* Turns a corner into 0-based indices: its vertex's, and when the corners are kept its texture
 * coordinate's and normal's where the file's corners give them (which must be all corners or none). */
static bool resolve_corner(struct obj_reader *r, struct mesh_token corner, uint32_t out[OBJ_INDEX_KINDS]) {
    long long index[OBJ_INDEX_KINDS];
    struct mesh_token text[OBJ_INDEX_KINDS];
    if (!parse_corner(corner, index, text))
        return mesh_fail_line(r->in, r->line, "'%.*s' is not a face corner (expected i, i/t, i//n or i/t/n)",
                              mesh_shown(corner), corner.text);
    bool given[OBJ_INDEX_KINDS];
    for (int kind = 0; kind < OBJ_INDEX_KINDS; kind++) {
        given[kind] = text[kind].length > 0;
        if (given[kind] && index[kind] == 0)
            return mesh_fail_line(r->in, r->line, "%s 0 is invalid (OBJ indices start at 1)", obj_index_name[kind]);
    }
    if (r->in->corners == NULL) /* only the vertices are kept: the other indices are read past */
        given[OBJ_TEXTURE] = given[OBJ_NORMAL] = false;
    for (int kind = OBJ_TEXTURE; kind <= OBJ_NORMAL && r->in->corners != NULL; kind++) {
        int has = given[kind];
        if (r->corners_with[kind] < 0)
            r->corners_with[kind] = has;
        if (has != r->corners_with[kind])
            return mesh_fail_line(r->in, r->line, "corner '%.*s' %s %s index and earlier corners %s",
                                  mesh_shown(corner), corner.text, has ? "gives a" : "has no", obj_index_one[kind],
                                  has ? "do not" : "do");
    }
    out[OBJ_TEXTURE] = out[OBJ_NORMAL] = 0;
    for (int kind = 0; kind < OBJ_INDEX_KINDS; kind++)
        if (given[kind] &&
            !resolve_index(r, (enum obj_index)kind, index[kind], text[kind], &out[kind]))
            return false;
    return true;
}

/* Appends the triangle (a, b, c) to one of the per-face index arrays (normal_faces or uv_faces), which
 * holds face_count - 1 faces so far. */
static bool add_corner_face(struct mesh_face **faces, size_t *capacity, size_t count, uint32_t a, uint32_t b,
                            uint32_t c) {
    void *array = *faces;
    bool ok = mesh_reserve(&array, capacity, count, sizeof **faces);
    *faces = array;
    if (ok)
        (*faces)[count - 1] = (struct mesh_face){{a, b, c}};
    return ok;
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
    uint32_t first[OBJ_INDEX_KINDS] = {0}, previous[OBJ_INDEX_KINDS] = {0};
    struct mesh *m = r->mesh;
    struct mesh_corners *c = r->in->corners;
    for (size_t k = 0; k < corners; k++) {
        uint32_t index[OBJ_INDEX_KINDS];
        next_word(&cursor, end, &corner);
        if (!resolve_corner(r, corner, index))
            return false;
        if (k >= 2) {
            bool ok = mesh_add_triangle(m, &r->face_capacity, first[0], previous[0], index[0]);
            if (ok && r->corners_with[OBJ_TEXTURE] == 1)
                ok = add_corner_face(&c->uv_faces, &r->uv_face_capacity, m->face_count, first[OBJ_TEXTURE],
                                     previous[OBJ_TEXTURE], index[OBJ_TEXTURE]);
            if (ok && r->corners_with[OBJ_NORMAL] == 1)
                ok = add_corner_face(&c->normal_faces, &r->normal_face_capacity, m->face_count, first[OBJ_NORMAL],
                                     previous[OBJ_NORMAL], index[OBJ_NORMAL]);
            if (!ok)
                return mesh_fail_line(r->in, r->line, "out of memory");
        }
        for (int kind = 0; kind < OBJ_INDEX_KINDS; kind++) {
            if (k == 0)
                first[kind] = index[kind];
            previous[kind] = index[kind];
        }
    }
    return true;
}

bool mesh_read_obj(const struct mesh_input *in, struct mesh *m) {
    struct obj_reader r = {.in = in, .mesh = m, .corners_with = {1, -1, -1}};
    struct mesh_lines lines;
    /* A byte-order mark, which some editors start a UTF-8 file with, is no part of the first line's
     * keyword: read as one, it made the first vertex an unknown line, skipped. */
    bool marked = in->size >= 3 && memcmp(in->data, MESH_UTF8_BOM, 3) == 0;
    mesh_lines_begin(&lines, in->data, in->size, marked ? 3 : 0, 1);
    const char *cursor;
    while ((cursor = mesh_lines_next(&lines)) != NULL) {
        r.line = lines.line;
        struct mesh_token keyword;
        if (!next_word(&cursor, lines.end, &keyword))
            continue; /* blank or comment */
        bool ok = true;
        if (mesh_token_is(keyword, "v"))
            ok = read_vertex(&r, cursor, lines.end);
        else if (in->corners != NULL && mesh_token_is(keyword, "vt"))
            ok = read_uv(&r, cursor, lines.end);
        else if (in->corners != NULL && mesh_token_is(keyword, "vn"))
            ok = read_normal(&r, cursor, lines.end);
        else if (mesh_token_is(keyword, "f"))
            ok = read_face(&r, cursor, lines.end);
        if (!ok)
            return false;
    }
    if (r.highest_index[OBJ_VERTEX] > (long long)m->vertex_count)
        return mesh_fail_line(in, r.highest_line[OBJ_VERTEX], "index %.*s out of range (%zu vertices)",
                              mesh_shown(r.highest_text[OBJ_VERTEX]), r.highest_text[OBJ_VERTEX].text, m->vertex_count);
    for (int kind = OBJ_TEXTURE; kind <= OBJ_NORMAL && in->corners != NULL; kind++)
        if (r.highest_index[kind] > (long long)so_far(&r, (enum obj_index)kind))
            return mesh_fail_line(in, r.highest_line[kind], "%s %.*s out of range (%zu %s)", obj_index_name[kind],
                                  mesh_shown(r.highest_text[kind]), r.highest_text[kind].text,
                                  so_far(&r, (enum obj_index)kind), obj_index_many[kind]);
    return true;
}

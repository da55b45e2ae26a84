/* mesh_ply.c: the PLY reader (chapter 3): Greg Turk's polygon file format, as written by the Stanford 3D
 * Scanning Repository, MeshLab, Blender and most scanners.
 *
 * A PLY file is a text header, then the data of each element the header declares, in the header's
 * order. For example:
 *
 *     ply
 *     format binary_little_endian 1.0
 *     element vertex 8
 *     property float x                 (any scalar type; more properties may follow, and are read past,
 *     property float y                  but for normals nx ny nz and texture coordinates u v, also
 *     property float z                  spelt s t or texture_u texture_v, which mesh_load_with_corners keeps)
 *     element face 6
 *     property list uchar int vertex_indices
 *     end_header
 *
 * The reader walks every element, including ones it does not use, so that what follows is read from
 * the right place. In ascii files each entry of an element is one line; in binary files each value
 * takes the size of its type, in the declared byte order, and a list starts with its length.
 *
 * Before reading any data the header's counts are checked against the bytes left in the file (every
 * entry needs at least a few bytes), so a lying header cannot make us allocate much more memory than
 * the file's own size. Errors in the data name the entry: "file:LINE: face 3: ..." in ascii files and
 * "file: byte N: face 3: ..." in binary ones (entries are numbered from 0, as PLY indices are). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"
#include "mesh_ply.h"

#define PLY_MIN_LINE_BYTES 2 /* an ascii value needs a digit and a separator after it */

/* ---- the header --------------------------------------------------------------------------------- */

enum ply_type {
    PLY_NOT_A_TYPE,
    PLY_INT8,
    PLY_UINT8,
    PLY_INT16,
    PLY_UINT16,
    PLY_INT32,
    PLY_UINT32,
    PLY_FLOAT32,
    PLY_FLOAT64
};

struct ply_type_info {
    const char *name; /* the classic name, for messages */
    size_t size;      /* bytes in a binary file */
    bool is_integer;
    double min, max; /* range of an integer type */
};

static const struct ply_type_info TYPES[] = {
    [PLY_INT8] = {"char", 1, true, -128.0, 127.0},
    [PLY_UINT8] = {"uchar", 1, true, 0.0, 255.0},
    [PLY_INT16] = {"short", 2, true, -32768.0, 32767.0},
    [PLY_UINT16] = {"ushort", 2, true, 0.0, 65535.0},
    [PLY_INT32] = {"int", 4, true, -2147483648.0, 2147483647.0},
    [PLY_UINT32] = {"uint", 4, true, 0.0, 4294967295.0},
    [PLY_FLOAT32] = {"float", 4, false, 0.0, 0.0},
    [PLY_FLOAT64] = {"double", 8, false, 0.0, 0.0},
};

/* Both spellings of every type: the classic names and the sized ones of later PLY writers. */
static const struct {
    const char *name;
    enum ply_type type;
} TYPE_NAMES[] = {
    {"char", PLY_INT8},     {"int8", PLY_INT8},       {"uchar", PLY_UINT8},    {"uint8", PLY_UINT8},
    {"short", PLY_INT16},   {"int16", PLY_INT16},     {"ushort", PLY_UINT16},  {"uint16", PLY_UINT16},
    {"int", PLY_INT32},     {"int32", PLY_INT32},     {"uint", PLY_UINT32},    {"uint32", PLY_UINT32},
    {"float", PLY_FLOAT32}, {"float32", PLY_FLOAT32}, {"double", PLY_FLOAT64}, {"float64", PLY_FLOAT64},
};

enum ply_format { PLY_NO_FORMAT, PLY_ASCII, PLY_BINARY_LITTLE_ENDIAN, PLY_BINARY_BIG_ENDIAN };

/* What a property means to us; everything else is read past. */
enum ply_role { ROLE_SKIPPED, ROLE_X, ROLE_Y, ROLE_Z, ROLE_NX, ROLE_NY, ROLE_NZ, ROLE_U, ROLE_V, ROLE_CORNERS };

/* A vertex's values by role, ROLE_X .. ROLE_V, and their names in messages. */
#define PLY_VERTEX_VALUES (ROLE_V - ROLE_X + 1)
static const char *const vertex_value_names[PLY_VERTEX_VALUES] = {"x", "y", "z", "nx", "ny", "nz", "u", "v"};

/* The names a vertex property goes by (texture coordinates have three spellings in the wild). */
static const struct {
    const char *name;
    enum ply_role role;
} vertex_roles[] = {{"x", ROLE_X},   {"y", ROLE_Y},   {"z", ROLE_Z},         {"nx", ROLE_NX},
                    {"ny", ROLE_NY}, {"nz", ROLE_NZ}, {"u", ROLE_U},         {"v", ROLE_V},
                    {"s", ROLE_U},   {"t", ROLE_V},   {"texture_u", ROLE_U}, {"texture_v", ROLE_V}};

struct ply_property {
    enum ply_type type;       /* of the value, or of a list's items */
    enum ply_type count_type; /* of a list's length; PLY_NOT_A_TYPE for a single value */
    enum ply_role role;
};

enum ply_kind { KIND_OTHER, KIND_VERTEX, KIND_FACE };

struct ply_element {
    struct mesh_token name;
    enum ply_kind kind;
    size_t count;
    size_t line;                           /* of its "element" line */
    size_t first_property, property_count; /* its properties in ply_header.properties */
};

struct ply_header {
    enum ply_format format;
    size_t body;     /* offset of the first byte after the end_header line */
    size_t end_line; /* line number of end_header */
    struct ply_element *elements;
    size_t element_count, element_capacity;
    struct ply_property *properties;
    size_t property_count, property_capacity;
};

#define NO_ELEMENT SIZE_MAX

static enum ply_type type_named(struct mesh_token token) {
    for (size_t k = 0; k < sizeof TYPE_NAMES / sizeof TYPE_NAMES[0]; k++)
        if (mesh_token_is(token, TYPE_NAMES[k].name))
            return TYPE_NAMES[k].type;
    return PLY_NOT_A_TYPE;
}

/* Reads "format ascii|binary_little_endian|binary_big_endian 1.0". */
static bool parse_format(const struct mesh_input *in, size_t line, const struct mesh_token *words, int count,
                         struct ply_header *h) {
    if (h->format != PLY_NO_FORMAT)
        return mesh_fail_line(in, line, "second format line");
    if (count != 3)
        return mesh_fail_line(in, line, "malformed format line (expected 'format <kind> 1.0')");
    if (mesh_token_is(words[1], "ascii"))
        h->format = PLY_ASCII;
    else if (mesh_token_is(words[1], "binary_little_endian"))
        h->format = PLY_BINARY_LITTLE_ENDIAN;
    else if (mesh_token_is(words[1], "binary_big_endian"))
        h->format = PLY_BINARY_BIG_ENDIAN;
    else
        return mesh_fail_line(in, line,
                              "unknown format '%.*s' (expected ascii, binary_little_endian or binary_big_endian)",
                              mesh_shown(words[1]), words[1].text);
    if (!mesh_token_is(words[2], "1.0"))
        return mesh_fail_line(in, line, "unsupported PLY version '%.*s' (expected 1.0)", mesh_shown(words[2]),
                              words[2].text);
    return true;
}

/* Reads "element <name> <count>". */
static bool parse_element(const struct mesh_input *in, size_t line, const struct mesh_token *words, int count,
                          struct ply_header *h) {
    if (count != 3)
        return mesh_fail_line(in, line, "malformed element line (expected 'element <name> <count>')");
    long long entries;
    if (!mesh_parse_integer(words[2], &entries) || entries < 0 || (unsigned long long)entries > SIZE_MAX)
        return mesh_fail_line(in, line, "bad element count '%.*s'", mesh_shown(words[2]), words[2].text);
    enum ply_kind kind = mesh_token_is(words[1], "vertex") ? KIND_VERTEX
                         : mesh_token_is(words[1], "face") ? KIND_FACE
                                                           : KIND_OTHER;
    /* Only a vertex or face element looks back, and there is at most one of each: a header of many other
     * elements is read in time in proportion to them, not to their square. */
    for (size_t k = 0; kind != KIND_OTHER && k < h->element_count; k++)
        if (h->elements[k].kind == kind)
            return mesh_fail_line(in, line, "second element %.*s", mesh_shown(words[1]), words[1].text);
    void *array = h->elements;
    bool ok = mesh_reserve(&array, &h->element_capacity, h->element_count + 1, sizeof *h->elements);
    h->elements = array;
    if (!ok)
        return mesh_fail_line(in, line, "out of memory");
    h->elements[h->element_count++] = (struct ply_element){.name = words[1],
                                                           .kind = kind,
                                                           .count = (size_t)entries,
                                                           .line = line,
                                                           .first_property = h->property_count};
    return true;
}

/* What a property named `name` of element e is for; fails on a second x, y, z or vertex_indices, and on
 * one that is a list where a single value is expected or the other way round. */
static bool property_role(const struct mesh_input *in, size_t line, const struct ply_header *h,
                          const struct ply_element *e, struct mesh_token name, bool is_list, enum ply_role *role) {
    *role = ROLE_SKIPPED;
    if (e->kind == KIND_VERTEX) {
        for (size_t k = 0; k < sizeof vertex_roles / sizeof vertex_roles[0]; k++)
            if (mesh_token_is(name, vertex_roles[k].name) && (vertex_roles[k].role <= ROLE_Z || in->corners != NULL))
                *role = vertex_roles[k].role; /* normals and (u, v) only when the caller keeps them */
    } else if (e->kind == KIND_FACE &&
             (mesh_token_is(name, "vertex_indices") || mesh_token_is(name, "vertex_index")))
        *role = ROLE_CORNERS;
    if (*role == ROLE_SKIPPED)
        return true;
    for (size_t k = 0; k < e->property_count; k++)
        if (h->properties[e->first_property + k].role == *role)
            return mesh_fail_line(in, line, "second %.*s property", mesh_shown(name), name.text);
    if (*role == ROLE_CORNERS && !is_list)
        return mesh_fail_line(in, line, "%.*s must be a list", mesh_shown(name), name.text);
    if (*role != ROLE_CORNERS && is_list)
        return mesh_fail_line(in, line, "property %.*s must be a single value, not a list", mesh_shown(name),
                              name.text);
    return true;
}

/* Reads "property <type> <name>" or "property list <count type> <item type> <name>". */
static bool parse_property(const struct mesh_input *in, size_t line, const struct mesh_token *words, int count,
                           struct ply_header *h) {
    if (h->element_count == 0)
        return mesh_fail_line(in, line, "property before any element");
    bool is_list = count >= 2 && mesh_token_is(words[1], "list");
    if (count != (is_list ? 5 : 3))
        return mesh_fail_line(in, line,
                              "malformed property line (expected 'property <type> <name>' or "
                              "'property list <count type> <item type> <name>')");
    struct ply_property p = {.count_type = PLY_NOT_A_TYPE};
    for (int k = is_list ? 2 : 1; k < count - 1; k++) {
        enum ply_type type = type_named(words[k]);
        if (type == PLY_NOT_A_TYPE)
            return mesh_fail_line(in, line, "unknown property type '%.*s'", mesh_shown(words[k]), words[k].text);
        if (is_list && k == 2)
            p.count_type = type;
        else
            p.type = type;
    }
    if (is_list && !TYPES[p.count_type].is_integer)
        return mesh_fail_line(in, line, "list length type must be an integer type, not %s",
                              TYPES[p.count_type].name);
    struct ply_element *e = &h->elements[h->element_count - 1];
    struct mesh_token name = words[count - 1];
    if (!property_role(in, line, h, e, name, is_list, &p.role))
        return false;
    if (p.role == ROLE_CORNERS && !TYPES[p.type].is_integer)
        return mesh_fail_line(in, line, "vertex index type must be an integer type, not %s", TYPES[p.type].name);
    void *array = h->properties;
    bool ok = mesh_reserve(&array, &h->property_capacity, h->property_count + 1, sizeof *h->properties);
    h->properties = array;
    if (!ok)
        return mesh_fail_line(in, line, "out of memory");
    h->properties[h->property_count++] = p;
    e->property_count++;
    return true;
}

/* Reads the header's lines up to end_header into h. */
static bool parse_header_lines(const struct mesh_input *in, struct ply_header *h) {
    enum { MAX_WORDS = 6 }; /* one more than the longest line, to notice extra words */
    struct mesh_lines lines;
    mesh_lines_begin(&lines, in->data, in->size, 0, 1);
    mesh_lines_next(&lines); /* "ply", checked by mesh_load */
    const char *cursor;
    while ((cursor = mesh_lines_next(&lines)) != NULL) {
        struct mesh_token words[MAX_WORDS];
        int count = 0;
        while (count < MAX_WORDS && mesh_next_token(&cursor, lines.end, &words[count]))
            count++;
        if (count == 0 || mesh_token_is(words[0], "comment") || mesh_token_is(words[0], "obj_info"))
            continue;
        if (mesh_token_is(words[0], "end_header")) {
            h->body = lines.next < in->size ? lines.next : in->size;
            h->end_line = lines.line;
            return true;
        }
        bool ok;
        if (mesh_token_is(words[0], "format"))
            ok = parse_format(in, lines.line, words, count, h);
        else if (mesh_token_is(words[0], "element"))
            ok = parse_element(in, lines.line, words, count, h);
        else if (mesh_token_is(words[0], "property"))
            ok = parse_property(in, lines.line, words, count, h);
        else
            ok = mesh_fail_line(in, lines.line, "unknown header keyword '%.*s'", mesh_shown(words[0]),
                                words[0].text);
        if (!ok)
            return false;
    }
    return mesh_fail_line(in, lines.line, "missing end_header");
}

static size_t find_element(const struct ply_header *h, enum ply_kind kind) {
    for (size_t k = 0; k < h->element_count; k++)
        if (h->elements[k].kind == kind)
            return k;
    return NO_ELEMENT;
}

static bool has_role(const struct ply_header *h, const struct ply_element *e, enum ply_role role) {
    for (size_t k = 0; k < e->property_count; k++)
        if (h->properties[e->first_property + k].role == role)
            return true;
    return false;
}

/* Checks that the header declares what a mesh needs: a format, vertices with x, y and z, and faces. */
static bool check_header(const struct mesh_input *in, const struct ply_header *h) {
    if (h->format == PLY_NO_FORMAT)
        return mesh_fail_line(in, h->end_line, "no format line before end_header");
    size_t vertex = find_element(h, KIND_VERTEX), face = find_element(h, KIND_FACE);
    if (vertex == NO_ELEMENT)
        return mesh_fail_line(in, h->end_line, "no vertex element before end_header");
    const struct ply_element *v = &h->elements[vertex];
    static const char *const axis_names[] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; axis++)
        if (!has_role(h, v, (enum ply_role)(ROLE_X + axis)))
            return mesh_fail_line(in, v->line, "element vertex has no %s property", axis_names[axis]);
    /* Normals and texture coordinates come whole or not at all: nx with ny and nz, u with v. */
    static const enum ply_role groups[][3] = {{ROLE_NX, ROLE_NY, ROLE_NZ}, {ROLE_U, ROLE_V, ROLE_V}};
    for (int g = 0; g < 2; g++)
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++)
                if (has_role(h, v, groups[g][k]) && !has_role(h, v, groups[g][j]))
                    return mesh_fail_line(in, v->line, "element vertex has %s but no %s",
                                          vertex_value_names[groups[g][k] - ROLE_X],
                                          vertex_value_names[groups[g][j] - ROLE_X]);
    if (v->count > MESH_MAX_VERTICES)
        return mesh_fail_line(in, v->line, "more than %zu vertices", MESH_MAX_VERTICES);
    if (face == NO_ELEMENT || h->elements[face].count == 0)
        return mesh_fail_file(in, "no faces");
    if (!has_role(h, &h->elements[face], ROLE_CORNERS))
        return mesh_fail_line(in, h->elements[face].line, "element face has no vertex_indices list");
    return true;
}

/* The fewest bytes one entry of e can take: in binary files the size of its values with every list
 * empty (a face's index list has at least 3 items); in ascii files PLY_MIN_LINE_BYTES per value. */
static size_t min_entry_bytes(const struct ply_header *h, const struct ply_element *e) {
    size_t bytes = 0, values = 0;
    for (size_t k = 0; k < e->property_count; k++) {
        const struct ply_property *p = &h->properties[e->first_property + k];
        size_t items = p->role == ROLE_CORNERS ? 3 : 0;
        if (p->count_type == PLY_NOT_A_TYPE) {
            bytes += TYPES[p->type].size;
            values += 1;
        } else {
            bytes += TYPES[p->count_type].size + items * TYPES[p->type].size;
            values += 1 + items;
        }
    }
    return h->format == PLY_ASCII ? values * PLY_MIN_LINE_BYTES : bytes;
}

/* Refuses counts that the rest of the file is too short to hold, before anything is allocated. */
static bool check_counts_fit(const struct mesh_input *in, const struct ply_header *h) {
    size_t available = in->size - h->body;
    /* The last ascii value needs no separator after it. */
    size_t budget = h->format == PLY_ASCII ? available + 1 : available;
    size_t needed = 0;
    for (size_t k = 0; k < h->element_count; k++) {
        const struct ply_element *e = &h->elements[k];
        size_t per_entry = min_entry_bytes(h, e);
        if (per_entry == 0)
            continue;
        bool faces = false; /* a list of corners, counted at its least, 3 (a face of fewer is refused) */
        for (size_t j = 0; j < e->property_count; j++)
            faces = faces || h->properties[e->first_property + j].role == ROLE_CORNERS;
        if (e->count > (budget - needed) / per_entry)
            return mesh_fail_line(in, e->line, "element %.*s %zu does not fit in the %zu bytes after the header (at "
                                  "least %zu bytes each%s)", mesh_shown(e->name), e->name.text, e->count, available, per_entry,
                                  faces ? ", a face holding 3 corners or more" : "");
        needed += e->count * per_entry;
    }
    return true;
}

static bool parse_header(const struct mesh_input *in, struct ply_header *h) {
    return parse_header_lines(in, h) && check_header(in, h) && check_counts_fit(in, h);
}

/* ---- the data ---------------------------------------------------------------------------------- */

struct ply_reader {
    const struct mesh_input *in;
    const struct ply_header *header;
    size_t value_start;                /* binary: offset of the value being read, for messages */
    size_t next;                       /* binary: offset of the next value */
    struct mesh_lines lines;           /* ascii */
    const char *cursor;                /* ascii: the rest of the current line */
    const struct ply_element *element; /* the entry being read, for messages */
    size_t index;
    struct mesh *mesh;
    size_t face_capacity;
};

/* Fails with "file:LINE: <element> <index>: <message>" (ascii) or "file: byte N: ..." (binary). */
static bool reader_fail(const struct ply_reader *r, const char *format, ...) __attribute__((format(printf, 2, 3)));
static bool reader_fail(const struct ply_reader *r, const char *format, ...) {
    char message[200];
    va_list args;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    const struct mesh_token name = r->element->name;
    if (r->header->format == PLY_ASCII)
        return mesh_fail_line(r->in, r->lines.line, "%.*s %zu: %s", mesh_shown(name), name.text, r->index,
                              message);
    return mesh_fail_byte(r->in, r->value_start, "%.*s %zu: %s", mesh_shown(name), name.text, r->index, message);
}

/* Converts the bits of a binary value (already in host order) to a double; every PLY type fits. */
static double binary_value(enum ply_type type, uint64_t bits) {
    if (type == PLY_FLOAT32) {
        uint32_t narrow = (uint32_t)bits;
        float f;
        memcpy(&f, &narrow, sizeof f);
        return f;
    }
    if (type == PLY_FLOAT64) {
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    double range = TYPES[type].max - TYPES[type].min + 1.0; /* 2^bits */
    double value = (double)bits;
    return value > TYPES[type].max ? value - range : value; /* two's complement for signed types */
}

static bool read_binary_value(struct ply_reader *r, enum ply_type type, double *value) {
    size_t size = TYPES[type].size;
    r->value_start = r->next;
    if (size > r->in->size - r->next)
        return reader_fail(r, "file ends early");
    const unsigned char *bytes = (const unsigned char *)r->in->data + r->next;
    bool big_endian = r->header->format == PLY_BINARY_BIG_ENDIAN;
    uint64_t bits = 0;
    for (size_t k = 0; k < size; k++)
        bits = bits << 8 | bytes[big_endian ? k : size - 1 - k];
    r->next += size;
    *value = binary_value(type, bits);
    return true;
}

static bool read_ascii_value(struct ply_reader *r, enum ply_type type, double *value) {
    struct mesh_token token;
    if (!mesh_next_token(&r->cursor, r->lines.end, &token))
        return reader_fail(r, "too few values");
    if (!TYPES[type].is_integer) {
        if (!mesh_parse_double(token, value))
            return reader_fail(r, "'%.*s' is not a number", mesh_shown(token), token.text);
        return true;
    }
    long long integer;
    if (!mesh_parse_integer(token, &integer))
        return reader_fail(r, "'%.*s' is not an integer", mesh_shown(token), token.text);
    if (integer < TYPES[type].min || integer > TYPES[type].max)
        return reader_fail(r, "%lld does not fit in %s", integer, TYPES[type].name);
    *value = (double)integer;
    return true;
}

static bool read_value(struct ply_reader *r, enum ply_type type, double *value) {
    if (r->header->format == PLY_ASCII)
        return read_ascii_value(r, type, value);
    return read_binary_value(r, type, value);
}

/* Starts entry `index` of element e: in ascii files, moves to its line, skipping blank ones. */
static bool begin_entry(struct ply_reader *r, const struct ply_element *e, size_t index) {
    r->element = e;
    r->index = index;
    r->value_start = r->next;
    if (r->header->format != PLY_ASCII)
        return true;
    struct mesh_token first;
    do {
        r->cursor = mesh_lines_next(&r->lines);
        if (r->cursor == NULL)
            return reader_fail(r, "file ends early");
        const char *peek = r->cursor;
        mesh_next_token(&peek, r->lines.end, &first);
    } while (first.length == 0);
    return true;
}

/* Ends an entry: in ascii files nothing may be left on its line. */
static bool end_entry(struct ply_reader *r) {
    struct mesh_token extra;
    if (r->header->format == PLY_ASCII && mesh_next_token(&r->cursor, r->lines.end, &extra))
        return reader_fail(r, "unexpected extra value '%.*s'", mesh_shown(extra), extra.text);
    return true;
}

/* Reads a list length and checks it is not negative. */
static bool read_list_length(struct ply_reader *r, const struct ply_property *p, double *length) {
    if (!read_value(r, p->count_type, length))
        return false;
    if (*length < 0)
        return reader_fail(r, "negative list length %.0f", *length);
    return true;
}

/* Reads past a list nobody uses. */
static bool skip_list(struct ply_reader *r, const struct ply_property *p) {
    double length;
    if (!read_list_length(r, p, &length))
        return false;
    size_t items = (size_t)length; /* a whole number from 0 to 2^32 - 1 */
    if (r->header->format == PLY_ASCII) {
        double ignored;
        for (size_t k = 0; k < items; k++)
            if (!read_value(r, p->type, &ignored))
                return false;
        return true;
    }
    size_t size = TYPES[p->type].size;
    if (items > (r->in->size - r->next) / size) {
        r->value_start = r->next;
        return reader_fail(r, "file ends early");
    }
    r->next += items * size;
    return true;
}

/* Reads a face's corner list and adds its fan of triangles to the mesh. */
static bool read_corners(struct ply_reader *r, const struct ply_property *p, size_t vertex_count) {
    double length;
    if (!read_value(r, p->count_type, &length))
        return false;
    if (length < 3 || length > MESH_MAX_POLYGON_CORNERS)
        return reader_fail(r, "%.0f corners (a face needs 3 to %d)", length, MESH_MAX_POLYGON_CORNERS);
    uint32_t first = 0, previous = 0;
    for (int k = 0; k < (int)length; k++) {
        double index;
        if (!read_value(r, p->type, &index))
            return false;
        if (index < 0 || index >= (double)vertex_count)
            return reader_fail(r, "index %.0f out of range (%zu vertices)", index, vertex_count);
        uint32_t corner = (uint32_t)index;
        if (k >= 2 && !mesh_add_triangle(r->mesh, &r->face_capacity, first, previous, corner))
            return reader_fail(r, "out of memory");
        if (k == 0)
            first = corner;
        previous = corner;
    }
    return true;
}

/* Reads one property of the current entry; a vertex's values go into values, by role from ROLE_X. */
static bool read_property(struct ply_reader *r, const struct ply_property *p, size_t vertex_count,
                          double values[PLY_VERTEX_VALUES]) {
    if (p->role == ROLE_CORNERS)
        return read_corners(r, p, vertex_count);
    if (p->count_type != PLY_NOT_A_TYPE)
        return skip_list(r, p);
    double value = 0;
    if (!read_value(r, p->type, &value))
        return false;
    if (p->role == ROLE_SKIPPED)
        return true;
    int which = (int)(p->role - ROLE_X);
    if (!isfinite(value))
        return reader_fail(r, "%s is not a finite number (%g)", vertex_value_names[which], value);
    values[which] = value;
    return true;
}

/* Reads every entry of element e. */
static bool read_element(struct ply_reader *r, const struct ply_element *e, size_t vertex_count) {
    if (e->property_count == 0)
        return true; /* nothing to read, however many entries it claims */
    const struct ply_property *properties = &r->header->properties[e->first_property];
    for (size_t index = 0; index < e->count; index++) {
        if (!begin_entry(r, e, index))
            return false;
        double values[PLY_VERTEX_VALUES] = {0};
        for (size_t k = 0; k < e->property_count; k++)
            if (!read_property(r, &properties[k], vertex_count, values))
                return false;
        struct mesh_corners *c = r->in->corners;
        if (e->kind == KIND_VERTEX) {
            r->mesh->vertices[index] = (vec3){values[0], values[1], values[2]};
            if (c != NULL && c->normals != NULL)
                c->normals[index] = (vec3){values[3], values[4], values[5]};
            if (c != NULL && c->uvs != NULL)
                c->uvs[index] = (struct mesh_uv){values[6], values[7]};
        }
        if (!end_entry(r))
            return false;
    }
    return true;
}

/* ---- the fast path: binary entries whose layout is known in advance ------------------------------ */

/* The general reader above reads every value through one function that asks the format, the type and
 * the byte order each time, which costs more than the value. Most models are binary with a fixed
 * layout: a vertex is the same few scalars at the same offsets every time, and a face is a corner count
 * and its indices. read_vertices_fast and read_faces_fast read such elements straight from the bytes,
 * checking what the general reader checks. They never report a fault themselves: at the first thing
 * they do not expect (a value that is not finite, an index out of range, the file ending early, a
 * layout they do not handle) they decline, and the general reader reads the element again from its
 * start and reports the fault with its usual message. So the two agree by construction on every file,
 * good or bad (tests/test_mesh.c compares them on every model, and fuzz/fuzz_ply.c on anything). */

/* Whether a binary file's byte order differs from this machine's, so each value must be reversed. */
static bool must_swap(enum ply_format format) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    return format == PLY_BINARY_LITTLE_ENDIAN;
#else
    return format == PLY_BINARY_BIG_ENDIAN;
#endif
}

static uint16_t load_u16(const unsigned char *p, bool swap) {
    uint16_t v;
    memcpy(&v, p, sizeof v);
    return swap ? (uint16_t)(v << 8 | v >> 8) : v;
}

static uint32_t load_u32(const unsigned char *p, bool swap) {
    uint32_t v;
    memcpy(&v, p, sizeof v);
    return swap ? __builtin_bswap32(v) : v;
}

static uint64_t load_u64(const unsigned char *p, bool swap) {
    uint64_t v;
    memcpy(&v, p, sizeof v);
    return swap ? __builtin_bswap64(v) : v;
}

/* The value of type `type` at p, as binary_value gives it. */
static double load_binary(const unsigned char *p, enum ply_type type, bool swap) {
    switch (type) {
    case PLY_INT8:
        return (double)(int8_t)p[0];
    case PLY_UINT8:
        return (double)p[0];
    case PLY_INT16:
        return (double)(int16_t)load_u16(p, swap);
    case PLY_UINT16:
        return (double)load_u16(p, swap);
    case PLY_INT32:
        return (double)(int32_t)load_u32(p, swap);
    case PLY_UINT32:
        return (double)load_u32(p, swap);
    case PLY_FLOAT32: {
        uint32_t bits = load_u32(p, swap);
        float f;
        memcpy(&f, &bits, sizeof f);
        return (double)f;
    }
    case PLY_FLOAT64: {
        uint64_t bits = load_u64(p, swap);
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    case PLY_NOT_A_TYPE:
        break;
    }
    return 0.0;
}

/* The commonest vertex of all: x, y and z as float32 in the machine's byte order, one after the other. */
static bool is_plain_float_xyz(const enum ply_type types[], const size_t offsets[], size_t wanted, bool swap) {
    return wanted == 3 && !swap && types[0] == PLY_FLOAT32 && types[1] == PLY_FLOAT32 && types[2] == PLY_FLOAT32 &&
           offsets[1] == offsets[0] + 4 && offsets[2] == offsets[0] + 8;
}

/* Reads every vertex of a binary file whose vertex properties are all single values (no lists); false
 * (declined, r untouched) otherwise or at the first fault. */
static bool read_vertices_fast(struct ply_reader *r, const struct ply_element *e) {
    const struct ply_property *properties = &r->header->properties[e->first_property];
    size_t stride = 0, offsets[PLY_VERTEX_VALUES] = {0};
    enum ply_type types[PLY_VERTEX_VALUES] = {PLY_NOT_A_TYPE};
    for (size_t k = 0; k < e->property_count; k++) {
        const struct ply_property *p = &properties[k];
        if (p->count_type != PLY_NOT_A_TYPE)
            return false;
        if (p->role != ROLE_SKIPPED) {
            offsets[p->role - ROLE_X] = stride;
            types[p->role - ROLE_X] = p->type;
        }
        stride += TYPES[p->type].size;
    }
    if (e->count > (r->in->size - r->next) / stride)
        return false;
    /* The values wanted, in role order: x y z, then the normals and (u, v) when the caller keeps them. */
    struct mesh_corners *c = r->in->corners;
    size_t wanted = 3 + (c != NULL && c->normals != NULL ? 3 : 0);
    size_t roles[PLY_VERTEX_VALUES] = {0, 1, 2, 3, 4, 5};
    if (c != NULL && c->uvs != NULL) {
        roles[wanted++] = ROLE_U - ROLE_X;
        roles[wanted++] = ROLE_V - ROLE_X;
    }
    enum ply_type wanted_types[PLY_VERTEX_VALUES];
    size_t wanted_offsets[PLY_VERTEX_VALUES];
    for (size_t k = 0; k < wanted; k++) {
        wanted_types[k] = types[roles[k]];
        wanted_offsets[k] = offsets[roles[k]];
    }
    bool swap = must_swap(r->header->format);
    const unsigned char *entry = (const unsigned char *)r->in->data + r->next;
    vec3 *vertices = r->mesh->vertices;
    if (is_plain_float_xyz(wanted_types, wanted_offsets, wanted, swap)) {
        for (size_t index = 0; index < e->count; index++, entry += stride) {
            float xyz[3];
            memcpy(xyz, entry + wanted_offsets[0], sizeof xyz);
            if (!(isfinite(xyz[0]) && isfinite(xyz[1]) && isfinite(xyz[2])))
                return false;
            vertices[index] = (vec3){xyz[0], xyz[1], xyz[2]};
        }
    } else {
        for (size_t index = 0; index < e->count; index++, entry += stride) {
            double values[PLY_VERTEX_VALUES] = {0};
            for (size_t k = 0; k < wanted; k++) {
                values[roles[k]] = load_binary(entry + wanted_offsets[k], wanted_types[k], swap);
                if (!isfinite(values[roles[k]]))
                    return false;
            }
            vertices[index] = (vec3){values[0], values[1], values[2]};
            if (c != NULL && c->normals != NULL)
                c->normals[index] = (vec3){values[3], values[4], values[5]};
            if (c != NULL && c->uvs != NULL)
                c->uvs[index] = (struct mesh_uv){values[6], values[7]};
        }
    }
    r->next += e->count * stride;
    return true;
}

/* Appends the fan (0,1,2), (0,2,3), ... of a face whose `corners` indices, of type `type`, are at p
 * (each already checked to be below the vertex count); false when memory runs out. */
static bool add_fan(struct ply_reader *r, const unsigned char *p, size_t corners, enum ply_type type, bool swap) {
    size_t size = TYPES[type].size;
    uint32_t first = (uint32_t)load_binary(p, type, swap), previous = (uint32_t)load_binary(p + size, type, swap);
    for (size_t k = 2; k < corners; k++) {
        uint32_t corner = (uint32_t)load_binary(p + k * size, type, swap);
        if (!mesh_add_triangle(r->mesh, &r->face_capacity, first, previous, corner))
            return false;
        previous = corner;
    }
    return true;
}

/* The commonest face of all, as is_plain_float_xyz's is the commonest vertex: the corner list alone, a
 * uint8 count and int32 or uint32 corners in the machine's byte order (13 bytes a triangle). */
#define PLY_PLAIN_TRIANGLE_SIZE 13

static bool is_plain_triangle_list(const struct ply_property *properties, size_t count, bool swap) {
    return count == 1 && !swap && properties[0].role == ROLE_CORNERS && properties[0].count_type == PLY_UINT8 &&
           (properties[0].type == PLY_INT32 || properties[0].type == PLY_UINT32);
}

/* Reads the faces of a plain triangle list, each a triangle; false (declined: r and the mesh's faces as
 * they were) at a face of other than three corners, a corner out of range or the file's end, which
 * read_faces_fast's loop then reads, or the general reader reports. A corner copied as uint32: an int32
 * below zero becomes 2^31 or more, above any vertex count. */
static bool read_plain_triangles(struct ply_reader *r, const struct ply_element *e, size_t vertex_count) {
    const unsigned char *p = (const unsigned char *)r->in->data + r->next;
    struct mesh *m = r->mesh;
    if (e->count > (r->in->size - r->next) / PLY_PLAIN_TRIANGLE_SIZE ||
        !mesh_reserve_faces(m, &r->face_capacity, m->face_count + e->count))
        return false;
    struct mesh_face *out = m->faces + m->face_count;
    for (size_t f = 0; f < e->count; f++, p += PLY_PLAIN_TRIANGLE_SIZE) {
        uint32_t corner[3];
        memcpy(corner, p + 1, sizeof corner);
        if (p[0] != 3 || corner[0] >= vertex_count || corner[1] >= vertex_count || corner[2] >= vertex_count)
            return false;
        out[f] = (struct mesh_face){{corner[0], corner[1], corner[2]}};
    }
    m->face_count += e->count;
    r->next += e->count * PLY_PLAIN_TRIANGLE_SIZE;
    return true;
}

/* Reads every face of a binary file whose face properties are the corner list and single values; false
 * (declined: r and the mesh's faces as they were) otherwise or at the first fault. */
static bool read_faces_fast(struct ply_reader *r, const struct ply_element *e, size_t vertex_count) {
    const struct ply_property *properties = &r->header->properties[e->first_property];
    if (is_plain_triangle_list(properties, e->property_count, must_swap(r->header->format)) &&
        read_plain_triangles(r, e, vertex_count))
        return true;
    for (size_t k = 0; k < e->property_count; k++)
        if (properties[k].count_type != PLY_NOT_A_TYPE && properties[k].role != ROLE_CORNERS)
            return false;
    bool swap = must_swap(r->header->format);
    const unsigned char *start = (const unsigned char *)r->in->data + r->next;
    const unsigned char *p = start, *end = (const unsigned char *)r->in->data + r->in->size;
    size_t faces_before = r->mesh->face_count;
    for (size_t index = 0; index < e->count; index++) {
        for (size_t k = 0; k < e->property_count; k++) {
            const struct ply_property *property = &properties[k];
            if (property->role != ROLE_CORNERS) {
                if (TYPES[property->type].size > (size_t)(end - p))
                    goto decline; /* the general reader says where the file ends */
                p += TYPES[property->type].size;
                continue;
            }
            size_t count_size = TYPES[property->count_type].size, item_size = TYPES[property->type].size;
            if (count_size > (size_t)(end - p))
                goto decline;
            double length = load_binary(p, property->count_type, swap);
            if (!(length >= 3 && length <= MESH_MAX_POLYGON_CORNERS))
                goto decline;
            size_t corners = (size_t)length;
            p += count_size;
            if (corners > (size_t)(end - p) / item_size)
                goto decline;
            for (size_t j = 0; j < corners; j++) {
                double index_value = load_binary(p + j * item_size, property->type, swap);
                if (!(index_value >= 0 && index_value < (double)vertex_count))
                    goto decline;
            }
            if (!add_fan(r, p, corners, property->type, swap))
                goto decline;
            p += corners * item_size;
        }
    }
    r->next += (size_t)(p - start);
    return true;
decline:
    r->mesh->face_count = faces_before;
    return false;
}

/* Reads element e through the fast path where it applies, else (or when it declines) the general one. */
static bool read_element_fastest(struct ply_reader *r, const struct ply_element *e, size_t vertex_count) {
    if (r->header->format != PLY_ASCII && e->property_count > 0 && e->count > 0) {
        if (e->kind == KIND_VERTEX && read_vertices_fast(r, e))
            return true;
        if (e->kind == KIND_FACE && read_faces_fast(r, e, vertex_count))
            return true;
    }
    return read_element(r, e, vertex_count);
}

/* Allocates the vertex array (and the normals and texture coordinates the vertices have) and room for
 * one triangle per face; their counts fit in the file. */
static bool allocate(const struct mesh_input *in, const struct ply_header *h, struct ply_reader *r) {
    const struct ply_element *v = &h->elements[find_element(h, KIND_VERTEX)];
    size_t vertex_count = v->count, room = vertex_count > 0 ? vertex_count : 1;
    size_t face_count = h->elements[find_element(h, KIND_FACE)].count;
    struct mesh *m = r->mesh;
    struct mesh_corners *c = in->corners; /* has_role finds normals and (u, v) only when it is not NULL */
    m->vertices = big_alloc(room * sizeof *m->vertices, true); /* at most MESH_MAX_VERTICES */
    bool ok = m->vertices != NULL;
    if (ok)
        memset(m->vertices, 0, room * sizeof *m->vertices);
    if (ok && has_role(h, v, ROLE_NX)) {
        c->normals = calloc(room, sizeof *c->normals);
        c->normal_count = vertex_count;
        ok = c->normals != NULL;
    }
    if (ok && has_role(h, v, ROLE_U)) {
        c->uvs = calloc(room, sizeof *c->uvs);
        c->uv_count = vertex_count;
        ok = c->uvs != NULL;
    }
    if (!ok || !mesh_reserve_faces(m, &r->face_capacity, face_count))
        return mesh_fail_file(in, "out of memory for %zu vertices and %zu faces", vertex_count, face_count);
    m->vertex_count = vertex_count;
    return true;
}

/* Each face's normals and texture coordinates are its vertices': copies of the faces' indices. */
static bool index_corners(const struct mesh_input *in, const struct mesh *m) {
    struct mesh_corners *c = in->corners;
    if (c == NULL)
        return true;
    size_t bytes = (m->face_count > 0 ? m->face_count : 1) * sizeof *m->faces;
    if (c->normals != NULL && (c->normal_faces = malloc(bytes)) != NULL)
        memcpy(c->normal_faces, m->faces, m->face_count * sizeof *m->faces);
    if (c->uvs != NULL && (c->uv_faces = malloc(bytes)) != NULL)
        memcpy(c->uv_faces, m->faces, m->face_count * sizeof *m->faces);
    if ((c->normals != NULL && c->normal_faces == NULL) || (c->uvs != NULL && c->uv_faces == NULL))
        return mesh_fail_file(in, "out of memory for %zu faces", m->face_count);
    return true;
}

/* The reader, with the fast path (fast == true) or without it. */
static bool read_ply(const struct mesh_input *in, struct mesh *m, bool fast) {
    struct ply_header h = {0};
    bool ok = parse_header(in, &h);
    struct ply_reader r = {.in = in, .header = &h, .next = h.body, .mesh = m};
    if (ok)
        ok = allocate(in, &h, &r);
    if (ok) {
        mesh_lines_begin(&r.lines, in->data, in->size, h.body, h.end_line + 1);
        for (size_t k = 0; ok && k < h.element_count; k++)
            ok = fast ? read_element_fastest(&r, &h.elements[k], m->vertex_count)
                      : read_element(&r, &h.elements[k], m->vertex_count);
    }
    if (ok)
        ok = index_corners(in, m);
    free(h.elements);
    free(h.properties);
    return ok;
}

bool mesh_read_ply(const struct mesh_input *in, struct mesh *m) { return read_ply(in, m, true); }

bool mesh_read_ply_general(const struct mesh_input *in, struct mesh *m) { return read_ply(in, m, false); }

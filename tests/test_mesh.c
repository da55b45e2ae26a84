/* test_mesh.c: loading PLY and OBJ meshes, refusing bad ones with exact messages, and placing meshes.
 *
 * Text files live in tests/data/meshes/ (written by hand; .gitattributes there keeps their CRLF line
 * endings). Binary PLY files are built byte by byte below, so every byte is visible in the code, and
 * written to out/test/meshes/. The tests run with the repository as working directory. */
#include <criterion/criterion.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "big_alloc.h"
#include "mesh.h"
#include "mesh_load.h"
#include "mesh_read.h"

#define DATA "tests/data/meshes/"
#define SCRATCH "out/test/meshes/"

/* ---- helpers ------------------------------------------------------------------------------------ */

static void load_ok(const char *path, struct mesh *m) {
    char err[512] = "";
    cr_assert(mesh_load(path, m, err, sizeof err), "%s should load, but: %s", path, err);
}

/* Loading `path` must fail with exactly `expected` and leave the mesh empty. */
static void expect_error(const char *path, const char *expected) {
    struct mesh m;
    memset(&m, 0xab, sizeof m); /* whatever the caller had, a failed load leaves it empty */
    char err[512] = "";
    cr_assert_not(mesh_load(path, &m, err, sizeof err), "%s should be refused", path);
    cr_assert_str_eq(err, expected);
    cr_assert(m.vertices == NULL && m.faces == NULL && m.vertex_count == 0 && m.face_count == 0,
              "a failed load must leave the mesh empty");
}

static void assert_vertex(const struct mesh *m, size_t k, double x, double y, double z) {
    cr_assert_lt(k, m->vertex_count);
    vec3 v = m->vertices[k];
    cr_assert(v.x == x && v.y == y && v.z == z, "vertex %zu is (%g, %g, %g), expected (%g, %g, %g)", k, v.x, v.y,
              v.z, x, y, z);
}

static void assert_face(const struct mesh *m, size_t k, uint32_t a, uint32_t b, uint32_t c) {
    cr_assert_lt(k, m->face_count);
    const uint32_t *v = m->faces[k].v;
    cr_assert(v[0] == a && v[1] == b && v[2] == c, "face %zu is (%u, %u, %u), expected (%u, %u, %u)", k, v[0],
              v[1], v[2], a, b, c);
}

static void assert_near(vec3 v, double x, double y, double z) {
    cr_assert(fabs(v.x - x) < 1e-12 && fabs(v.y - y) < 1e-12 && fabs(v.z - z) < 1e-12,
              "got (%.17g, %.17g, %.17g), expected (%g, %g, %g)", v.x, v.y, v.z, x, y, z);
}

/* ---- building binary PLY files ------------------------------------------------------------------ */

struct bytes {
    unsigned char data[8192];
    size_t size;
    bool big_endian;
};

static void put_text(struct bytes *b, const char *text) {
    size_t length = strlen(text);
    cr_assert_leq(b->size + length, sizeof b->data);
    memcpy(b->data + b->size, text, length);
    b->size += length;
}

/* Writes the low `size` bytes of `bits` at `offset`, in the file's byte order. */
static void poke_bits(struct bytes *b, size_t offset, uint64_t bits, size_t size) {
    cr_assert_leq(offset + size, sizeof b->data);
    for (size_t k = 0; k < size; k++)
        b->data[offset + (b->big_endian ? size - 1 - k : k)] = (unsigned char)(bits >> (8 * k));
}

static const struct {
    const char *name;
    size_t size;
    char kind; /* 'i' signed, 'u' unsigned, 'f' floating */
} PLY_TYPES[] = {
    {"char", 1, 'i'},  {"int8", 1, 'i'},    {"uchar", 1, 'u'},  {"uint8", 1, 'u'},
    {"short", 2, 'i'}, {"int16", 2, 'i'},   {"ushort", 2, 'u'}, {"uint16", 2, 'u'},
    {"int", 4, 'i'},   {"int32", 4, 'i'},   {"uint", 4, 'u'},   {"uint32", 4, 'u'},
    {"float", 4, 'f'}, {"float32", 4, 'f'}, {"double", 8, 'f'}, {"float64", 8, 'f'},
};

static size_t type_index(const char *type) {
    for (size_t k = 0; k < sizeof PLY_TYPES / sizeof PLY_TYPES[0]; k++)
        if (strcmp(PLY_TYPES[k].name, type) == 0)
            return k;
    cr_assert_fail("unknown type %s in a test", type);
    return 0;
}

/* Writes `value` as PLY type `type` at `offset`. */
static void poke_value(struct bytes *b, size_t offset, const char *type, double value) {
    size_t t = type_index(type), size = PLY_TYPES[t].size;
    uint64_t bits;
    if (PLY_TYPES[t].kind == 'f' && size == 4) {
        float f = (float)value;
        uint32_t narrow;
        memcpy(&narrow, &f, sizeof narrow);
        bits = narrow;
    } else if (PLY_TYPES[t].kind == 'f') {
        memcpy(&bits, &value, sizeof bits);
    } else {
        bits = (uint64_t)(int64_t)value; /* two's complement; poke_bits keeps the low bytes */
    }
    poke_bits(b, offset, bits, size);
}

static void put_value(struct bytes *b, const char *type, double value) {
    poke_value(b, b->size, type, value);
    b->size += PLY_TYPES[type_index(type)].size;
}

/* The test square-ish mesh: 4 vertices, a triangle (3 2 1) and a quad (0 1 2 3) that becomes the fan
 * (0 1 2), (0 2 3). All coordinates fit in every PLY type. */
static const double TEST_VERTICES[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 2}};

struct ply_spec {
    bool big_endian;
    const char *coordinate; /* type of x, y and z */
    const char *count;      /* type of a face's corner count */
    const char *index;      /* type of a face's vertex indices */
    bool vertex_extras;     /* intensity before x; normals, colours, confidence after z */
    bool edge_element;      /* an "edge" element, with a list, between vertex and face */
    bool face_extras;       /* flags before the corner list; texture coordinates and material after */
    const char *declared_vertices, *declared_faces; /* header counts, when not the true ones */
};

/* The default binary file: little endian, float coordinates, uchar counts, int indices. Header lines:
 * 1 ply, 2 format, 3 element vertex, 4-6 x y z, 7 element face, 8 property list, 9 end_header. Its data:
 * 4 vertices of 12 bytes (offset 0), face 0 (offset 48: count, 3 indices), face 1 (offset 61: count at
 * 61, indices at 62, 66, 70, 74), 78 bytes in all. */
static const struct ply_spec DEFAULT_SPEC = {.coordinate = "float", .count = "uchar", .index = "int"};

static void put_header(struct bytes *b, const struct ply_spec *s) {
    char line[200];
    put_text(b, "ply\n");
    put_text(b, s->big_endian ? "format binary_big_endian 1.0\n" : "format binary_little_endian 1.0\n");
    snprintf(line, sizeof line, "element vertex %s\n", s->declared_vertices ? s->declared_vertices : "4");
    put_text(b, line);
    if (s->vertex_extras)
        put_text(b, "property float intensity\n");
    for (const char *axis = "xyz"; *axis != '\0'; axis++) {
        snprintf(line, sizeof line, "property %s %c\n", s->coordinate, *axis);
        put_text(b, line);
    }
    if (s->vertex_extras)
        put_text(b,
                 "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n"
                 "property uchar green\nproperty uchar blue\nproperty uchar alpha\nproperty double confidence\n");
    if (s->edge_element)
        put_text(b,
                 "element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty list uchar int crease\n");
    snprintf(line, sizeof line, "element face %s\n", s->declared_faces ? s->declared_faces : "2");
    put_text(b, line);
    if (s->face_extras)
        put_text(b, "property uchar flags\n");
    snprintf(line, sizeof line, "property list %s %s vertex_indices\n", s->count, s->index);
    put_text(b, line);
    if (s->face_extras)
        put_text(b, "property list uchar float texcoord\nproperty int material\n");
    put_text(b, "end_header\n");
}

static void put_face(struct bytes *b, const struct ply_spec *s, int corners, const int *indices) {
    if (s->face_extras)
        put_value(b, "uchar", 3);
    put_value(b, s->count, corners);
    for (int k = 0; k < corners; k++)
        put_value(b, s->index, indices[k]);
    if (s->face_extras) {
        put_value(b, "uchar", 2);
        put_value(b, "float", 0.25);
        put_value(b, "float", 0.75);
        put_value(b, "int", 7);
    }
}

/* Builds the test mesh as a binary PLY file; *body is set to the offset of the first byte of data. */
static void binary_ply(const struct ply_spec *s, struct bytes *b, size_t *body) {
    memset(b, 0, sizeof *b);
    b->big_endian = s->big_endian;
    put_header(b, s);
    *body = b->size;
    for (int v = 0; v < 4; v++) {
        if (s->vertex_extras)
            put_value(b, "float", 0.5);
        for (int axis = 0; axis < 3; axis++)
            put_value(b, s->coordinate, TEST_VERTICES[v][axis]);
        if (s->vertex_extras) {
            put_value(b, "float", 0);
            put_value(b, "float", 0);
            put_value(b, "float", 1);
            for (int channel = 0; channel < 4; channel++)
                put_value(b, "uchar", 200);
            put_value(b, "double", 0.875);
        }
    }
    if (s->edge_element) {
        put_value(b, "int", 0), put_value(b, "int", 1), put_value(b, "uchar", 0);
        put_value(b, "int", 1), put_value(b, "int", 2), put_value(b, "uchar", 3);
        put_value(b, "int", 7), put_value(b, "int", 8), put_value(b, "int", 9);
    }
    put_face(b, s, 3, (const int[]){3, 2, 1});
    put_face(b, s, 4, (const int[]){0, 1, 2, 3});
}

/* Writes the first `size` bytes of `data` to out/test/meshes/<name> and returns that path. */
static const char *write_scratch(const char *name, const void *data, size_t size) {
    static char path[256];
    mkdir("out", 0777);
    mkdir("out/test", 0777);
    mkdir(SCRATCH, 0777);
    snprintf(path, sizeof path, SCRATCH "%s", name);
    FILE *file = fopen(path, "wb");
    cr_assert_not_null(file, "cannot write %s: %s", path, strerror(errno));
    cr_assert_eq(fwrite(data, 1, size, file), size);
    cr_assert_eq(fclose(file), 0);
    return path;
}

static const char *write_ply(const char *name, const struct ply_spec *s, size_t *body) {
    struct bytes b;
    size_t ignored;
    binary_ply(s, &b, body != NULL ? body : &ignored);
    return write_scratch(name, b.data, b.size);
}

/* The triangles of the test mesh, in file order. */
static void assert_test_mesh(const struct mesh *m) {
    cr_assert_eq(m->vertex_count, 4);
    for (size_t v = 0; v < 4; v++)
        assert_vertex(m, v, TEST_VERTICES[v][0], TEST_VERTICES[v][1], TEST_VERTICES[v][2]);
    cr_assert_eq(m->face_count, 3);
    assert_face(m, 0, 3, 2, 1);
    assert_face(m, 1, 0, 1, 2);
    assert_face(m, 2, 0, 2, 3);
}

static void check_binary_spec(const struct ply_spec *s, const char *name) {
    struct mesh m;
    load_ok(write_ply(name, s, NULL), &m);
    assert_test_mesh(&m);
    mesh_free(&m);
}

/* ---- PLY files that load -------------------------------------------------------------------------- */

Test(mesh_ply, ascii_triangle_loads) {
    struct mesh m;
    load_ok(DATA "ascii-triangle.ply", &m);
    cr_assert_eq(m.vertex_count, 3);
    assert_vertex(&m, 0, 0, 0, 0);
    assert_vertex(&m, 1, 1, 0, 0);
    assert_vertex(&m, 2, 0, 1, 0);
    cr_assert_eq(m.face_count, 1);
    assert_face(&m, 0, 0, 1, 2);
    mesh_free(&m);
}

Test(mesh_ply, ascii_quad_and_pentagon_become_triangle_fans) {
    struct mesh m;
    load_ok(DATA "ascii-polygons.ply", &m);
    cr_assert_eq(m.vertex_count, 5);
    assert_vertex(&m, 4, -1, 0.5, 0);
    cr_assert_eq(m.face_count, 5);
    assert_face(&m, 0, 0, 1, 2);
    assert_face(&m, 1, 0, 2, 3);
    assert_face(&m, 2, 0, 1, 2);
    assert_face(&m, 3, 0, 2, 3);
    assert_face(&m, 4, 0, 3, 4);
    mesh_free(&m);
}

Test(mesh_ply, ascii_stanford_confidence_and_intensity_are_read_past) {
    struct mesh m;
    load_ok(DATA "ascii-stanford.ply", &m);
    cr_assert_eq(m.vertex_count, 4);
    assert_vertex(&m, 0, -0.0378297, 0.12794, 0.00447467);
    assert_vertex(&m, 3, -0.00228741, 0.13015, 0.0232201);
    cr_assert_eq(m.face_count, 2);
    assert_face(&m, 0, 1, 0, 2);
    assert_face(&m, 1, 0, 3, 2);
    mesh_free(&m);
}

/* Each element line once looked back over all the elements before it, for a second vertex or face
 * element: 400,000 empty elements in a 5 MB header took minutes. Read in proportion to them, they take
 * a moment; the timeout catches the square. */
Test(mesh_ply, a_header_of_many_elements_is_read_in_proportion_to_them, .timeout = 30) {
    static const char element[] = "element empty 0\nproperty float unused\n";
    static const char head[] = "ply\nformat ascii 1.0\n";
    static const char tail[] = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const size_t elements = 400000, size = sizeof head - 1 + elements * (sizeof element - 1) + sizeof tail - 1;
    char *text = malloc(size), *at = text;
    cr_assert_not_null(text);
    memcpy(at, head, sizeof head - 1);
    at += sizeof head - 1;
    for (size_t k = 0; k < elements; k++) {
        memcpy(at, element, sizeof element - 1);
        at += sizeof element - 1;
    }
    memcpy(at, tail, sizeof tail - 1);
    struct mesh m;
    load_ok(write_scratch("many-elements.ply", text, size), &m);
    free(text);
    cr_assert_eq(m.vertex_count, 3);
    cr_assert_eq(m.face_count, 1);
    mesh_free(&m);
}

Test(mesh_ply, ascii_normals_colours_lists_edges_and_face_extras_are_read_past) {
    struct mesh m;
    load_ok(DATA "ascii-extras.ply", &m);
    cr_assert_eq(m.vertex_count, 4);
    assert_vertex(&m, 1, 1, 0, 0);
    assert_vertex(&m, 3, 0, 1, 0);
    cr_assert_eq(m.face_count, 3);
    assert_face(&m, 0, 0, 1, 2);
    assert_face(&m, 1, 0, 2, 3);
    assert_face(&m, 2, 0, 3, 1);
    mesh_free(&m);
}

Test(mesh_ply, ascii_crlf_line_endings_load) {
    struct mesh m;
    load_ok(DATA "ascii-crlf.ply", &m);
    cr_assert_eq(m.vertex_count, 4);
    assert_vertex(&m, 2, 2, 2, 0);
    cr_assert_eq(m.face_count, 2);
    assert_face(&m, 1, 0, 2, 3);
    mesh_free(&m);
}

Test(mesh_ply, ascii_face_element_before_vertex_element_loads) {
    struct mesh m;
    load_ok(DATA "ascii-face-first.ply", &m);
    cr_assert_eq(m.vertex_count, 3);
    assert_vertex(&m, 1, 1, 0, 0);
    cr_assert_eq(m.face_count, 1);
    assert_face(&m, 0, 2, 1, 0);
    mesh_free(&m);
}

Test(mesh_ply, ascii_sized_type_names_integer_coordinates_and_blank_lines_load) {
    struct mesh m;
    load_ok(DATA "ascii-sized-types.ply", &m);
    cr_assert_eq(m.vertex_count, 3);
    assert_vertex(&m, 0, -3, 0.5, 2.25);
    assert_vertex(&m, 1, 4, 1.5, -2);
    assert_vertex(&m, 2, 0, -100, 1e-3);
    assert_face(&m, 0, 0, 1, 2);
    mesh_free(&m);
}

Test(mesh_ply, binary_little_endian_loads) { check_binary_spec(&DEFAULT_SPEC, "little-endian.ply"); }

Test(mesh_ply, binary_big_endian_loads) {
    struct ply_spec s = DEFAULT_SPEC;
    s.big_endian = true;
    check_binary_spec(&s, "big-endian.ply");
}

Test(mesh_ply, binary_big_endian_with_normals_colours_and_intensity_loads) {
    struct ply_spec s = DEFAULT_SPEC;
    s.big_endian = true;
    s.vertex_extras = true;
    check_binary_spec(&s, "big-endian-extras.ply");
}

Test(mesh_ply, binary_little_endian_with_normals_colours_and_intensity_loads) {
    struct ply_spec s = DEFAULT_SPEC;
    s.vertex_extras = true;
    check_binary_spec(&s, "little-endian-extras.ply");
}

Test(mesh_ply, binary_edge_element_between_vertex_and_face_is_skipped) {
    for (int big = 0; big <= 1; big++) {
        struct ply_spec s = DEFAULT_SPEC;
        s.big_endian = big;
        s.edge_element = true;
        check_binary_spec(&s, big ? "edge-be.ply" : "edge-le.ply");
    }
}

Test(mesh_ply, binary_face_properties_before_and_after_the_corner_list_are_skipped) {
    for (int big = 0; big <= 1; big++) {
        struct ply_spec s = DEFAULT_SPEC;
        s.big_endian = big;
        s.face_extras = true;
        s.vertex_extras = true;
        s.edge_element = true;
        check_binary_spec(&s, big ? "everything-be.ply" : "everything-le.ply");
    }
}

Test(mesh_ply, binary_every_list_count_type_loads) {
    static const char *const counts[] = {"uchar", "ushort", "int", "uint", "char", "short", "uint8", "int32"};
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; k++)
        for (int big = 0; big <= 1; big++) {
            struct ply_spec s = DEFAULT_SPEC;
            s.big_endian = big;
            s.count = counts[k];
            cr_log_info("count type %s, %s endian", counts[k], big ? "big" : "little");
            check_binary_spec(&s, "count-type.ply");
        }
}

Test(mesh_ply, binary_every_index_type_loads) {
    static const char *const indices[] = {"int", "uint", "ushort", "short", "uchar", "char", "uint32", "int16"};
    for (size_t k = 0; k < sizeof indices / sizeof indices[0]; k++)
        for (int big = 0; big <= 1; big++) {
            struct ply_spec s = DEFAULT_SPEC;
            s.big_endian = big;
            s.index = indices[k];
            cr_log_info("index type %s, %s endian", indices[k], big ? "big" : "little");
            check_binary_spec(&s, "index-type.ply");
        }
}

Test(mesh_ply, binary_every_coordinate_type_loads) {
    for (size_t k = 0; k < sizeof PLY_TYPES / sizeof PLY_TYPES[0]; k++)
        for (int big = 0; big <= 1; big++) {
            struct ply_spec s = DEFAULT_SPEC;
            s.big_endian = big;
            s.coordinate = PLY_TYPES[k].name;
            cr_log_info("coordinate type %s, %s endian", PLY_TYPES[k].name, big ? "big" : "little");
            check_binary_spec(&s, "coordinate-type.ply");
        }
}

/* Two's complement and the full range of each integer type. */
Test(mesh_ply, binary_integer_coordinates_cover_their_whole_range) {
    static const struct {
        const char *type;
        double low, high;
    } ranges[] = {{"char", -128, 127},
                  {"uchar", 0, 255},
                  {"short", -32768, 32767},
                  {"ushort", 0, 65535},
                  {"int", -2147483648.0, 2147483647.0},
                  {"uint", 0, 4294967295.0}};
    for (size_t k = 0; k < sizeof ranges / sizeof ranges[0]; k++)
        for (int big = 0; big <= 1; big++) {
            struct ply_spec s = DEFAULT_SPEC;
            s.big_endian = big;
            s.coordinate = ranges[k].type;
            struct bytes b;
            size_t body;
            binary_ply(&s, &b, &body);
            size_t size = PLY_TYPES[type_index(ranges[k].type)].size;
            poke_value(&b, body, ranges[k].type, ranges[k].low);             /* vertex 0 x */
            poke_value(&b, body + 2 * size, ranges[k].type, ranges[k].high); /* vertex 0 z */
            poke_value(&b, body + size, ranges[k].type, -1);                 /* vertex 0 y: 0xff... */
            struct mesh m;
            load_ok(write_scratch("ranges.ply", b.data, b.size), &m);
            double minus_one = ranges[k].low < 0 ? -1 : ranges[k].high;
            assert_vertex(&m, 0, ranges[k].low, minus_one, ranges[k].high);
            mesh_free(&m);
        }
}

Test(mesh_ply, binary_header_with_crlf_line_endings_loads) {
    struct bytes b;
    size_t body;
    binary_ply(&DEFAULT_SPEC, &b, &body);
    struct bytes crlf = {.size = 0};
    for (size_t k = 0; k < b.size; k++) {
        if (k < body && b.data[k] == '\n')
            crlf.data[crlf.size++] = '\r';
        crlf.data[crlf.size++] = b.data[k];
    }
    struct mesh m;
    load_ok(write_scratch("crlf-header.ply", crlf.data, crlf.size), &m);
    assert_test_mesh(&m);
    mesh_free(&m);
}

Test(mesh_ply, binary_pentagon_becomes_a_fan_of_three_triangles) {
    struct bytes b = {.size = 0};
    put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar uint vertex_index\nend_header\n");
    for (int v = 0; v < 5; v++)
        put_value(&b, "float", v), put_value(&b, "float", 0), put_value(&b, "float", v % 2);
    put_value(&b, "uchar", 5);
    for (int v = 0; v < 5; v++)
        put_value(&b, "uint", 4 - v);
    struct mesh m;
    load_ok(write_scratch("pentagon.ply", b.data, b.size), &m);
    cr_assert_eq(m.face_count, 3);
    assert_face(&m, 0, 4, 3, 2);
    assert_face(&m, 1, 4, 2, 1);
    assert_face(&m, 2, 4, 1, 0);
    assert_vertex(&m, 3, 3, 0, 1);
    mesh_free(&m);
}

/* ---- OBJ files that load ---------------------------------------------------------------------------- */

Test(mesh_obj, quad_becomes_two_triangles) {
    struct mesh m;
    load_ok(DATA "square.obj", &m);
    cr_assert_eq(m.vertex_count, 4);
    assert_vertex(&m, 2, 1, 1, 0);
    cr_assert_eq(m.face_count, 2);
    assert_face(&m, 0, 0, 1, 2);
    assert_face(&m, 1, 0, 2, 3);
    mesh_free(&m);
}

Test(mesh_obj, every_corner_form_loads_and_other_statements_are_ignored) {
    struct mesh m;
    load_ok(DATA "corner-forms.obj", &m);
    cr_assert_eq(m.vertex_count, 4);
    assert_vertex(&m, 1, 1, 0, 0); /* "v 1 0 0 1.0": w ignored */
    assert_vertex(&m, 2, 1, 1, 0); /* "v 1 1 0 0.5 0.25 0.125": colours ignored */
    cr_assert_eq(m.face_count, 4);
    assert_face(&m, 0, 0, 1, 2);
    assert_face(&m, 1, 0, 2, 3);
    assert_face(&m, 2, 0, 1, 3);
    assert_face(&m, 3, 1, 2, 3);
    mesh_free(&m);
}

Test(mesh_obj, negative_indices_count_back_from_the_latest_vertex) {
    struct mesh m;
    load_ok(DATA "negative.obj", &m);
    cr_assert_eq(m.vertex_count, 4);
    cr_assert_eq(m.face_count, 2);
    assert_face(&m, 0, 0, 1, 2);
    assert_face(&m, 1, 0, 2, 3);
    mesh_free(&m);
}

Test(mesh_obj, crlf_line_endings_load) {
    struct mesh m;
    load_ok(DATA "crlf.obj", &m);
    cr_assert_eq(m.vertex_count, 4);
    assert_vertex(&m, 3, 0, 2, 0);
    cr_assert_eq(m.face_count, 2);
    assert_face(&m, 1, 0, 2, 3);
    mesh_free(&m);
}

/* A byte-order mark before the first line (some editors write one) is no part of its keyword: read as
 * one, the first vertex was an unknown line, skipped, and face 1 2 3 was out of range. */
Test(mesh_obj, a_byte_order_mark_before_the_first_vertex_is_skipped) {
    struct mesh m;
    load_ok(DATA "byte-order-mark.obj", &m);
    cr_assert_eq(m.vertex_count, 3);
    assert_vertex(&m, 0, 0, 0, 0);
    assert_vertex(&m, 2, 0, 2, 0);
    assert_face(&m, 0, 0, 1, 2);
    mesh_free(&m);
}

Test(mesh_obj, faces_may_name_vertices_that_come_later) {
    struct mesh m;
    load_ok(DATA "forward-reference.obj", &m);
    cr_assert_eq(m.vertex_count, 3);
    assert_face(&m, 0, 0, 1, 2);
    mesh_free(&m);
}

Test(mesh_obj, first_word_starting_with_ply_is_still_obj) {
    struct mesh m;
    load_ok(DATA "ply-lookalike.obj", &m);
    cr_assert_eq(m.face_count, 1);
    mesh_free(&m);
}

/* ---- bad files: every message exactly ------------------------------------------------------------ */

Test(mesh_errors, missing_file_says_cannot_open) {
    expect_error(DATA "does-not-exist.ply", DATA "does-not-exist.ply: cannot open: No such file or directory");
}

Test(mesh_errors, directory_is_not_a_regular_file) {
    expect_error("tests/data", "tests/data: not a regular file (a directory)");
}

Test(mesh_errors, file_larger_than_the_limit_is_refused_before_reading) {
    const char *path = write_scratch("huge.ply", "ply\n", 4);
    cr_assert_eq(truncate(path, ((off_t)1 << 30) + 1), 0, "cannot make a sparse file: %s", strerror(errno));
    char expected[512];
    snprintf(expected, sizeof expected, "%s: file too large (1073741825 bytes; the limit is 1073741824)", path);
    expect_error(path, expected);
    remove(path);
}

Test(mesh_errors, empty_file) { expect_error(DATA "empty.obj", DATA "empty.obj: empty file"); }

Test(mesh_errors, ply_missing_end_header) {
    expect_error(DATA "bad-missing-end-header.ply", DATA "bad-missing-end-header.ply:6: missing end_header");
}

Test(mesh_errors, ply_unknown_format) {
    expect_error(DATA "bad-unknown-format.ply",
                 DATA "bad-unknown-format.ply:2: unknown format 'binary_middle_endian' (expected ascii, "
                      "binary_little_endian or binary_big_endian)");
}

Test(mesh_errors, ply_unsupported_version) {
    expect_error(DATA "bad-version.ply", DATA "bad-version.ply:2: unsupported PLY version '2.0' (expected 1.0)");
}

Test(mesh_errors, ply_no_format_line) {
    expect_error(DATA "bad-no-format.ply", DATA "bad-no-format.ply:8: no format line before end_header");
}

Test(mesh_errors, ply_unknown_property_type) {
    expect_error(DATA "bad-unknown-type.ply", DATA "bad-unknown-type.ply:4: unknown property type 'float16'");
}

Test(mesh_errors, ply_unknown_header_keyword) {
    expect_error(DATA "bad-unknown-keyword.ply",
                 DATA "bad-unknown-keyword.ply:3: unknown header keyword 'elements'");
}

Test(mesh_errors, ply_property_before_any_element) {
    expect_error(DATA "bad-property-before-element.ply",
                 DATA "bad-property-before-element.ply:3: property before any element");
}

Test(mesh_errors, ply_bad_element_count) {
    expect_error(DATA "bad-element-count.ply", DATA "bad-element-count.ply:3: bad element count 'three'");
}

Test(mesh_errors, ply_no_vertex_element) {
    expect_error(DATA "bad-no-vertex-element.ply",
                 DATA "bad-no-vertex-element.ply:5: no vertex element before end_header");
}

Test(mesh_errors, ply_missing_z_property) {
    expect_error(DATA "bad-missing-z.ply", DATA "bad-missing-z.ply:3: element vertex has no z property");
}

Test(mesh_errors, ply_second_x_property) {
    expect_error(DATA "bad-second-x.ply", DATA "bad-second-x.ply:5: second x property");
}

Test(mesh_errors, ply_coordinate_declared_as_a_list) {
    expect_error(DATA "bad-list-coordinate.ply",
                 DATA "bad-list-coordinate.ply:4: property x must be a single value, not a list");
}

Test(mesh_errors, ply_face_without_vertex_indices) {
    expect_error(DATA "bad-no-vertex-indices.ply",
                 DATA "bad-no-vertex-indices.ply:7: element face has no vertex_indices list");
}

Test(mesh_errors, ply_float_list_length_type) {
    expect_error(DATA "bad-float-list-length.ply",
                 DATA "bad-float-list-length.ply:8: list length type must be an integer type, not float");
}

Test(mesh_errors, ply_float_vertex_index_type) {
    expect_error(DATA "bad-float-index-type.ply",
                 DATA "bad-float-index-type.ply:8: vertex index type must be an integer type, not float");
}

Test(mesh_errors, ply_without_face_element_has_no_faces) {
    expect_error(DATA "bad-no-face-element.ply", DATA "bad-no-face-element.ply: no faces");
}

Test(mesh_errors, ply_with_zero_faces_has_no_faces) {
    expect_error(DATA "bad-zero-faces.ply", DATA "bad-zero-faces.ply: no faces");
}

Test(mesh_errors, ply_ascii_vertex_count_larger_than_the_file_can_hold) {
    expect_error(DATA "bad-lying-vertex-count.ply",
                 DATA "bad-lying-vertex-count.ply:3: element vertex 100000000 does not fit in the 44 bytes after "
                      "the header (at least 6 bytes each)");
}

Test(mesh_errors, ply_ascii_face_count_larger_than_the_file_can_hold) {
    expect_error(DATA "bad-lying-face-count.ply",
                 DATA "bad-lying-face-count.ply:7: element face 4000000000 does not fit in the 44 bytes after the "
                      "header (at least 8 bytes each, a face holding 3 corners or more)");
}

/* A face of no corners: the file is too short for the faces its header counts at their least, and the
 * message says what that least is (it said only "does not fit", though the bytes were all there); in a
 * file long enough, the face itself is refused. */
Test(mesh_errors, ply_face_of_no_corners_is_refused_saying_a_face_holds_three) {
    const char *header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    char text[512];
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n0\n", header);
    expect_error(write_scratch("face-of-no-corners.ply", text, strlen(text)),
                 SCRATCH "face-of-no-corners.ply:7: element face 1 does not fit in the 20 bytes after the header (at "
                         "least 8 bytes each, a face holding 3 corners or more)");
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n0          \n", header);
    char expected[512];
    snprintf(expected, sizeof expected, SCRATCH "face-of-no-corners.ply:13: face 0: 0 corners (a face needs 3 to %d)",
             MESH_MAX_POLYGON_CORNERS);
    expect_error(write_scratch("face-of-no-corners.ply", text, strlen(text)), expected);
}

Test(mesh_errors, ply_ascii_line_with_too_few_values) {
    expect_error(DATA "bad-too-few-values.ply", DATA "bad-too-few-values.ply:11: vertex 1: too few values");
}

Test(mesh_errors, ply_ascii_file_with_too_few_lines) {
    expect_error(DATA "bad-too-few-lines.ply", DATA "bad-too-few-lines.ply:12: face 0: file ends early");
}

Test(mesh_errors, ply_ascii_line_with_an_extra_value) {
    expect_error(DATA "bad-extra-value.ply", DATA "bad-extra-value.ply:11: vertex 1: unexpected extra value '5'");
}

Test(mesh_errors, ply_ascii_word_that_is_not_a_number) {
    expect_error(DATA "bad-not-a-number.ply", DATA "bad-not-a-number.ply:10: vertex 0: 'abc' is not a number");
}

Test(mesh_errors, ply_ascii_fractional_index) {
    expect_error(DATA "bad-fractional-index.ply",
                 DATA "bad-fractional-index.ply:13: face 0: '1.5' is not an integer");
}

Test(mesh_errors, ply_ascii_value_outside_its_type) {
    expect_error(DATA "bad-count-out-of-type-range.ply",
                 DATA "bad-count-out-of-type-range.ply:13: face 0: 300 does not fit in uchar");
}

Test(mesh_errors, ply_ascii_index_out_of_range) {
    expect_error(DATA "bad-index-out-of-range.ply",
                 DATA "bad-index-out-of-range.ply:13: face 0: index 3 out of range (3 vertices)");
}

Test(mesh_errors, ply_ascii_negative_index) {
    expect_error(DATA "bad-negative-index.ply",
                 DATA "bad-negative-index.ply:13: face 0: index -1 out of range (3 vertices)");
}

Test(mesh_errors, ply_ascii_face_with_two_corners) {
    expect_error(DATA "bad-two-corners.ply",
                 DATA "bad-two-corners.ply:13: face 0: 2 corners (a face needs 3 to 1000)");
}

Test(mesh_errors, ply_ascii_face_with_too_many_corners) {
    expect_error(DATA "bad-too-many-corners.ply",
                 DATA "bad-too-many-corners.ply:13: face 0: 1001 corners (a face needs 3 to 1000)");
}

Test(mesh_errors, ply_ascii_nan_coordinate) {
    expect_error(DATA "bad-nan.ply", DATA "bad-nan.ply:10: vertex 0: y is not a finite number (nan)");
}

Test(mesh_errors, ply_ascii_infinite_coordinate) {
    expect_error(DATA "bad-inf.ply", DATA "bad-inf.ply:10: vertex 0: x is not a finite number (inf)");
}

Test(mesh_errors, ply_ascii_negative_list_length) {
    expect_error(DATA "bad-negative-list-length.ply",
                 DATA "bad-negative-list-length.ply:11: vertex 0: negative list length -1");
}

/* Binary errors: see DEFAULT_SPEC for where each value of the test mesh lies. */

static void expect_binary_error(struct bytes *b, const char *name, const char *message_after_path) {
    const char *path = write_scratch(name, b->data, b->size);
    char expected[512];
    snprintf(expected, sizeof expected, "%s%s", path, message_after_path);
    expect_error(path, expected);
}

Test(mesh_errors, ply_binary_file_ending_inside_a_face) {
    struct bytes b;
    size_t body;
    binary_ply(&DEFAULT_SPEC, &b, &body);
    /* Face 1's last index (bytes 74 to 77) is cut short. Cut any earlier and the header's counts no
     * longer fit in the file, which is refused before any data is read (see the fuzz tests). */
    b.size = body + 76;
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: face 1: file ends early", body + 74);
    expect_binary_error(&b, "truncated.ply", message);
}

Test(mesh_errors, ply_binary_file_ending_inside_a_skipped_list) {
    struct ply_spec s = DEFAULT_SPEC;
    s.edge_element = true;
    struct bytes b;
    size_t body;
    binary_ply(&s, &b, &body);
    /* Edge 0 is 9 bytes at 48; edge 1's list length is at 48 + 9 + 8: say 255 ints, more than is left. */
    poke_value(&b, body + 65, "uchar", 255);
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: edge 1: file ends early", body + 66);
    expect_binary_error(&b, "truncated-list.ply", message);
}

Test(mesh_errors, ply_binary_index_out_of_range) {
    struct bytes b;
    size_t body;
    binary_ply(&DEFAULT_SPEC, &b, &body);
    poke_value(&b, body + 70, "int", 4);
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: face 1: index 4 out of range (4 vertices)", body + 70);
    expect_binary_error(&b, "index-out-of-range.ply", message);
}

Test(mesh_errors, ply_binary_negative_index) {
    struct bytes b;
    size_t body;
    binary_ply(&DEFAULT_SPEC, &b, &body);
    poke_value(&b, body + 62, "int", -1);
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: face 1: index -1 out of range (4 vertices)", body + 62);
    expect_binary_error(&b, "negative-index.ply", message);
}

Test(mesh_errors, ply_binary_huge_unsigned_index) {
    struct ply_spec s = DEFAULT_SPEC;
    s.index = "uint";
    struct bytes b;
    size_t body;
    binary_ply(&s, &b, &body);
    poke_value(&b, body + 74, "uint", 4294967295.0);
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: face 1: index 4294967295 out of range (4 vertices)", body + 74);
    expect_binary_error(&b, "huge-index.ply", message);
}

Test(mesh_errors, ply_binary_face_with_two_corners) {
    struct bytes b;
    size_t body;
    binary_ply(&DEFAULT_SPEC, &b, &body);
    poke_value(&b, body + 48, "uchar", 2);
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: face 0: 2 corners (a face needs 3 to 1000)", body + 48);
    expect_binary_error(&b, "two-corners.ply", message);
}

Test(mesh_errors, ply_binary_absurd_corner_counts) {
    static const struct {
        const char *type;
        double count;
        const char *shown;
    } cases[] = {{"ushort", 1001, "1001"}, {"uint", 4294967295.0, "4294967295"},
                 {"int", -5, "-5"},        {"char", -1, "-1"},
                 {"uchar", 0, "0"},        {"int", 2147483647.0, "2147483647"}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        struct ply_spec s = DEFAULT_SPEC;
        s.count = cases[k].type;
        struct bytes b;
        size_t body;
        binary_ply(&s, &b, &body);
        poke_value(&b, body + 48, cases[k].type, cases[k].count);
        char message[100];
        snprintf(message, sizeof message, ": byte %zu: face 0: %s corners (a face needs 3 to 1000)", body + 48,
                 cases[k].shown);
        expect_binary_error(&b, "absurd-corners.ply", message);
    }
}

Test(mesh_errors, ply_binary_nan_coordinate) {
    struct bytes b;
    size_t body;
    binary_ply(&DEFAULT_SPEC, &b, &body);
    poke_value(&b, body + 2 * 12 + 4, "float", NAN); /* vertex 2's y */
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: vertex 2: y is not a finite number (nan)", body + 28);
    expect_binary_error(&b, "nan.ply", message);
}

Test(mesh_errors, ply_binary_infinite_coordinate) {
    struct ply_spec s = DEFAULT_SPEC;
    s.coordinate = "double";
    s.big_endian = true;
    struct bytes b;
    size_t body;
    binary_ply(&s, &b, &body);
    poke_value(&b, body + 24 + 16, "double", -INFINITY); /* vertex 1's z */
    char message[100];
    snprintf(message, sizeof message, ": byte %zu: vertex 1: z is not a finite number (-inf)", body + 40);
    expect_binary_error(&b, "infinite.ply", message);
}

Test(mesh_errors, ply_binary_vertex_count_larger_than_the_file_can_hold) {
    struct ply_spec s = DEFAULT_SPEC;
    s.declared_vertices = "1000000000";
    struct bytes b;
    size_t body;
    binary_ply(&s, &b, &body);
    expect_binary_error(&b, "lying-vertices.ply",
                        ":3: element vertex 1000000000 does not fit in the 78 bytes after the header (at least 12 bytes "
                        "each)");
}

Test(mesh_errors, ply_binary_face_count_larger_than_the_file_can_hold) {
    struct ply_spec s = DEFAULT_SPEC;
    s.declared_faces = "4294967295";
    struct bytes b;
    size_t body;
    binary_ply(&s, &b, &body);
    expect_binary_error(&b, "lying-faces.ply",
                        ":7: element face 4294967295 does not fit in the 78 bytes after the header (at least 13 bytes "
                        "each, a face holding 3 corners or more)");
}

Test(mesh_errors, ply_binary_count_beyond_64_bits) {
    struct ply_spec s = DEFAULT_SPEC;
    s.declared_vertices = "99999999999999999999999";
    struct bytes b;
    size_t body;
    binary_ply(&s, &b, &body);
    expect_binary_error(&b, "huge-count.ply", ":3: bad element count '99999999999999999999999'");
}

Test(mesh_errors, obj_index_zero) {
    expect_error(DATA "bad-index-zero.obj",
                 DATA "bad-index-zero.obj:5: index 0 is invalid (OBJ indices start at 1)");
}

Test(mesh_errors, obj_relative_index_before_the_first_vertex) {
    expect_error(DATA "bad-relative-before-first.obj", DATA
                 "bad-relative-before-first.obj:5: index -4 reaches before the first vertex (3 vertices so far)");
}

Test(mesh_errors, obj_index_out_of_range) {
    expect_error(DATA "bad-index-out-of-range.obj",
                 DATA "bad-index-out-of-range.obj:4: index 4 out of range (3 vertices)");
}

Test(mesh_errors, obj_word_that_is_not_a_number) {
    expect_error(DATA "bad-not-a-number.obj", DATA "bad-not-a-number.obj:3: 'zero' is not a number");
}

/* C's hexadecimal, which strtod reads (0x1p1 as 2) and neither format has, as the scene format refuses it */
Test(mesh_errors, hexadecimal_numbers_are_refused) {
    expect_error(DATA "bad-hexadecimal.obj", DATA "bad-hexadecimal.obj:3: '0x1p1' is not a number");
    expect_error(DATA "bad-hexadecimal.ply", DATA "bad-hexadecimal.ply:11: vertex 1: '0x1p0' is not a number");
}

/* A PLY file with a byte-order mark before 'ply' was read as an OBJ file and refused as "no faces". */
Test(mesh_errors, a_byte_order_mark_before_ply_is_named) {
    static const char text[] = "\xef\xbb\xbfply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
                               "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const char *path = write_scratch("marked.ply", text, sizeof text - 1);
    char expected[512];
    snprintf(expected, sizeof expected, "%s:1: a byte-order mark before 'ply': a PLY file starts with the bytes 'ply' "
             "(save it without the mark)", path);
    expect_error(path, expected);
}

Test(mesh_errors, obj_vertex_with_two_coordinates) {
    expect_error(DATA "bad-two-coordinates.obj",
                 DATA "bad-two-coordinates.obj:2: a vertex needs x, y and z (found 2 numbers)");
}

Test(mesh_errors, obj_face_with_two_corners) {
    expect_error(DATA "bad-two-corners.obj", DATA "bad-two-corners.obj:4: 2 corners (a face needs 3 to 1000)");
}

Test(mesh_errors, obj_face_with_too_many_corners) {
    static char text[16384];
    size_t used = (size_t)snprintf(text, sizeof text, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for (int k = 0; k < 1001; k++)
        used += (size_t)snprintf(text + used, sizeof text - used, " %d", 1 + k % 3);
    used += (size_t)snprintf(text + used, sizeof text - used, "\n");
    cr_assert_lt(used, sizeof text);
    const char *path = write_scratch("too-many-corners.obj", text, used);
    char expected[512];
    snprintf(expected, sizeof expected, "%s:4: 1001 corners (a face needs 3 to 1000)", path);
    expect_error(path, expected);
}

Test(mesh_errors, obj_bad_corner_syntax) {
    expect_error(DATA "bad-corner-syntax.obj",
                 DATA "bad-corner-syntax.obj:4: '1/1/1/1' is not a face corner (expected i, i/t, i//n or i/t/n)");
    expect_error(DATA "bad-corner-trailing-slash.obj", DATA
                 "bad-corner-trailing-slash.obj:4: '1/' is not a face corner (expected i, i/t, i//n or i/t/n)");
}

Test(mesh_errors, obj_nan_coordinate) {
    expect_error(DATA "bad-nan.obj", DATA "bad-nan.obj:3: z is not a finite number (nan)");
}

Test(mesh_errors, obj_infinite_coordinate) {
    expect_error(DATA "bad-inf.obj", DATA "bad-inf.obj:1: x is not a finite number (-inf)");
}

Test(mesh_errors, obj_without_faces) { expect_error(DATA "no-faces.obj", DATA "no-faces.obj: no faces"); }

Test(mesh_errors, message_is_cut_to_the_buffer_and_null_buffer_is_allowed) {
    struct mesh m;
    char err[8];
    cr_assert_not(mesh_load(DATA "no-faces.obj", &m, err, sizeof err));
    cr_assert_str_eq(err, "tests/d");
    cr_assert_not(mesh_load(DATA "no-faces.obj", &m, NULL, 0));
    cr_assert_null(m.vertices);
}

/* ---- robustness: cut and damaged files ----------------------------------------------------------- */

/* Loads the file and checks that the outcome is coherent: a mesh whose indices are in range and whose
 * vertices are finite, or a message naming the file. */
static void load_anything(const char *path) {
    struct mesh m;
    char err[512] = "";
    if (mesh_load(path, &m, err, sizeof err)) {
        cr_assert_gt(m.face_count, 0);
        for (size_t k = 0; k < m.face_count; k++)
            for (int c = 0; c < 3; c++)
                cr_assert_lt(m.faces[k].v[c], m.vertex_count);
        for (size_t k = 0; k < m.vertex_count; k++)
            cr_assert(vec3_is_finite(m.vertices[k]));
        mesh_free(&m);
    } else {
        size_t length = strlen(path);
        cr_assert(strncmp(err, path, length) == 0 && err[length] == ':', "message without the file name: %s", err);
    }
}

static void read_whole(const char *path, struct bytes *b) {
    FILE *file = fopen(path, "rb");
    cr_assert_not_null(file);
    b->size = fread(b->data, 1, sizeof b->data, file);
    fclose(file);
}

Test(mesh_fuzz, every_truncation_of_a_binary_ply_is_refused) {
    for (int big = 0; big <= 1; big++) {
        struct ply_spec s = DEFAULT_SPEC;
        s.big_endian = big;
        s.vertex_extras = s.edge_element = s.face_extras = true;
        struct bytes b;
        size_t body;
        binary_ply(&s, &b, &body);
        for (size_t size = 0; size < b.size; size++) {
            const char *path = write_scratch("cut.ply", b.data, size);
            struct mesh m;
            char err[512];
            cr_assert_not(mesh_load(path, &m, err, sizeof err), "%zu of %zu bytes should not load", size, b.size);
            cr_assert(strncmp(err, path, strlen(path)) == 0, "%s", err);
        }
    }
}

Test(mesh_fuzz, every_truncation_of_text_files_is_handled) {
    static const char *const files[] = {DATA "ascii-extras.ply", DATA "ascii-crlf.ply", DATA "corner-forms.obj",
                                        DATA "negative.obj"};
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        struct bytes b;
        read_whole(files[f], &b);
        for (size_t size = 0; size <= b.size; size++)
            load_anything(write_scratch("cut.txt", b.data, size));
    }
}

/* A small deterministic generator (Knuth's MMIX LCG), so failures can be replayed. */
static uint32_t next_random(uint64_t *state) {
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (uint32_t)(*state >> 33);
}

static void damage_and_load(const struct bytes *original, const char *name, int cases, uint64_t seed) {
    uint64_t state = seed;
    for (int k = 0; k < cases; k++) {
        struct bytes b = *original;
        int changes = 1 + (int)(next_random(&state) % 3);
        for (int c = 0; c < changes; c++) {
            size_t at = next_random(&state) % b.size;
            uint32_t how = next_random(&state);
            /* Mostly single bit flips; sometimes bytes that matter to parsers. */
            static const unsigned char special[] = {0x00, 0xff, 0x80, 0x7f, '\n', ' ', '-', '9', '/'};
            b.data[at] = how % 4 != 0 ? (unsigned char)(b.data[at] ^ (1u << (how >> 8) % 8))
                                      : special[(how >> 8) % sizeof special];
        }
        load_anything(write_scratch(name, b.data, b.size));
    }
}

Test(mesh_fuzz, damaged_binary_plys_never_crash) {
    for (int big = 0; big <= 1; big++) {
        struct ply_spec s = DEFAULT_SPEC;
        s.big_endian = big;
        s.vertex_extras = s.edge_element = s.face_extras = true;
        s.count = big ? "ushort" : "uchar";
        s.index = big ? "short" : "uint";
        struct bytes b;
        size_t body;
        binary_ply(&s, &b, &body);
        damage_and_load(&b, "damaged.ply", 1000, 12345 + (uint64_t)big);
    }
}

Test(mesh_fuzz, damaged_text_files_never_crash) {
    static const char *const files[] = {DATA "ascii-extras.ply", DATA "ascii-sized-types.ply",
                                        DATA "corner-forms.obj", DATA "negative.obj"};
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        struct bytes b;
        read_whole(files[f], &b);
        damage_and_load(&b, "damaged.txt", 400, 777 + f);
    }
}

/* ---- freeing and placing ------------------------------------------------------------------------- */

Test(mesh_free, empties_the_mesh_and_is_safe_twice) {
    struct mesh m;
    load_ok(DATA "square.obj", &m);
    mesh_free(&m);
    cr_assert(m.vertices == NULL && m.faces == NULL && m.vertex_count == 0 && m.face_count == 0);
    mesh_free(&m);
}

/* A mesh of one vertex at p, for watching where the transform puts it. */
static vec3 transformed(vec3 p, double scale, vec3 rotate, vec3 translate) {
    vec3 vertex = p;
    struct mesh m = {.vertices = &vertex, .vertex_count = 1};
    mesh_transform(&m, scale, rotate, translate);
    return vertex;
}

Test(mesh_transform, scale_multiplies_every_coordinate) {
    assert_near(transformed(vec3_make(1, -2, 3), 2.5, vec3_make(0, 0, 0), vec3_make(0, 0, 0)), 2.5, -5, 7.5);
}

Test(mesh_transform, rotate_90_about_x_maps_y_to_z) {
    assert_near(transformed(vec3_make(0, 1, 0), 1, vec3_make(90, 0, 0), vec3_make(0, 0, 0)), 0, 0, 1);
}

Test(mesh_transform, rotate_90_about_y_maps_x_to_minus_z) {
    vec3 p = transformed(vec3_make(1, 0, 0), 1, vec3_make(0, 90, 0), vec3_make(0, 0, 0));
    cr_assert(p.x == 0 && p.y == 0 && p.z == -1, "quarter turns are exact: got (%.17g, %.17g, %.17g)", p.x, p.y,
              p.z);
}

Test(mesh_transform, rotate_90_about_z_maps_x_to_y) {
    assert_near(transformed(vec3_make(1, 0, 0), 1, vec3_make(0, 0, 90), vec3_make(0, 0, 0)), 0, 1, 0);
}

Test(mesh_transform, quarter_turns_of_any_sign_and_size_are_exact) {
    vec3 p = transformed(vec3_make(1, 0, 0), 1, vec3_make(0, 0, -90), vec3_make(0, 0, 0));
    cr_assert(p.x == 0 && p.y == -1 && p.z == 0);
    p = transformed(vec3_make(1, 0, 0), 1, vec3_make(0, 0, 450), vec3_make(0, 0, 0));
    cr_assert(p.x == 0 && p.y == 1 && p.z == 0);
    p = transformed(vec3_make(1, 2, 3), 1, vec3_make(180, 0, 0), vec3_make(0, 0, 0));
    cr_assert(p.x == 1 && p.y == -2 && p.z == -3);
}

Test(mesh_transform, other_angles_use_sine_and_cosine) {
    double c = cos(M_PI / 6), s = sin(M_PI / 6);
    assert_near(transformed(vec3_make(1, 0, 0), 1, vec3_make(0, 0, 30), vec3_make(0, 0, 0)), c, s, 0);
    assert_near(transformed(vec3_make(0, 0, 1), 1, vec3_make(0, 30, 0), vec3_make(0, 0, 0)), s, 0, c);
    assert_near(transformed(vec3_make(0, 1, 0), 1, vec3_make(30, 0, 0), vec3_make(0, 0, 0)), 0, c, s);
}

Test(mesh_transform, rotations_apply_about_x_then_y_then_z) {
    /* x first: (0,1,0) -> (0,0,1); then y: (0,0,1) -> (1,0,0); then z: (1,0,0) -> (0,1,0). Any other
     * order ends elsewhere. */
    assert_near(transformed(vec3_make(0, 1, 0), 1, vec3_make(90, 90, 90), vec3_make(0, 0, 0)), 0, 1, 0);
    /* x then y only: (0,1,0) -> (0,0,1) -> (1,0,0); y first would give (0,0,1). */
    assert_near(transformed(vec3_make(0, 1, 0), 1, vec3_make(90, 90, 0), vec3_make(0, 0, 0)), 1, 0, 0);
}

Test(mesh_transform, scale_then_rotate_then_translate) {
    /* (1,0,0) scaled by 2 is (2,0,0), turned 90 about z is (0,2,0), moved by (1,2,3) is (1,4,3). */
    assert_near(transformed(vec3_make(1, 0, 0), 2, vec3_make(0, 0, 90), vec3_make(1, 2, 3)), 1, 4, 3);
}

Test(mesh_transform, applies_to_every_vertex_of_a_loaded_mesh) {
    struct mesh m;
    load_ok(DATA "square.obj", &m);
    mesh_transform(&m, 3, vec3_make(0, 0, 0), vec3_make(10, 0, -1));
    assert_vertex(&m, 0, 10, 0, -1);
    assert_vertex(&m, 2, 13, 3, -1);
    assert_face(&m, 1, 0, 2, 3);
    mesh_free(&m);
}

Test(mesh_transform, empty_mesh_is_left_alone) {
    struct mesh m = {0};
    mesh_transform(&m, 2, vec3_make(10, 20, 30), vec3_make(1, 2, 3));
    cr_assert_null(m.vertices);
}

/* ---- growing arrays (mesh_read.c) and big_alloc ------------------------------------------------ */

Test(mesh_arrays, grow_keep_their_items_across_the_move_to_big_pages) {
    /* From 16 items to past 2 MB (big_alloc asks for 2 MB pages from 1 MB on), one at a time as a reader
     * grows them: every item written stays in place across each move. */
    void *array = NULL;
    size_t capacity = 0, count = 300000; /* 300,000 faces of 12 bytes: 3.6 MB */
    for (size_t k = 0; k < count; k++) {
        cr_assert(mesh_reserve(&array, &capacity, k + 1, sizeof(struct mesh_face)));
        ((struct mesh_face *)array)[k] = (struct mesh_face){{(uint32_t)k, (uint32_t)(k + 1), (uint32_t)(k + 2)}};
    }
    cr_assert_geq(capacity, count);
    const struct mesh_face *faces = array;
    for (size_t k = 0; k < count; k++)
        cr_assert(faces[k].v[0] == k && faces[k].v[2] == k + 2, "item %zu moved wrong", k);
    free(array);
}

Test(mesh_arrays, double_when_grown_by_one_and_take_exactly_what_is_asked_at_once) {
    /* Item by item the capacity doubles (16, 32, 64); a reader that asks for all its items at once
     * (the PLY reader's faces) gets exactly that many, not the next power of two (349,872 faces would
     * have taken room for 524,288, and the model two more megabytes resident). */
    void *array = NULL;
    size_t capacity = 0;
    size_t seen[3] = {0};
    for (size_t k = 0; k < 40; k++) {
        cr_assert(mesh_reserve(&array, &capacity, k + 1, 12));
        if (k == 0 || k == 16 || k == 32)
            seen[k / 16] = capacity;
    }
    cr_assert(seen[0] == 16 && seen[1] == 32 && seen[2] == 64, "capacities %zu %zu %zu", seen[0], seen[1], seen[2]);
    cr_assert(mesh_reserve(&array, &capacity, 349872, 12));
    cr_assert_eq(capacity, 349872);
    cr_assert(mesh_reserve(&array, &capacity, 349873, 12)); /* one more: doubled again */
    cr_assert_eq(capacity, 2 * 349872);
    free(array);
}

/* The kernel's word on the mapping that holds address a (/proc/self/smaps): 1 when it may back it with
 * 2 MB pages (THPeligible), 0 when not, -1 when smaps does not say. */
static int big_pages_eligible(const void *a) {
    FILE *f = fopen("/proc/self/smaps", "r");
    if (f == NULL)
        return -1;
    char line[512];
    bool inside = false;
    int eligible = -1;
    while (fgets(line, sizeof line, f) != NULL) {
        unsigned long start, end;
        if (sscanf(line, "%lx-%lx ", &start, &end) == 2 && strchr(line, '-') < strchr(line, ' '))
            inside = start <= (uintptr_t)a && (uintptr_t)a < end;
        else if (inside && sscanf(line, "THPeligible: %d", &eligible) == 1)
            break;
    }
    fclose(f);
    return eligible;
}

Test(mesh_arrays, big_arrays_and_last_parts_of_half_a_big_page_or_more_are_on_big_pages) {
    /* big_alloc asks for 2 MB pages from 1 MB on, over the whole big pages an array fills and over its last
     * part when that fills half a big page or more; a shorter last part stays in small pages. Only where
     * the kernel gives 2 MB pages when asked (transparent_hugepage [madvise]) can it be seen. */
    FILE *mode = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
    char modes[128] = "";
    if (mode != NULL) {
        if (fgets(modes, sizeof modes, mode) == NULL)
            modes[0] = 0;
        fclose(mode);
    }
    if (strstr(modes, "[madvise]") == NULL)
        cr_skip("2 MB pages are not given on request here (%s)", modes[0] ? modes : "no transparent_hugepage");
    const size_t MB = (size_t)1 << 20;
    char *long_tail = big_alloc(3 * MB + MB / 2, true), *short_tail = big_alloc(2 * MB + MB / 4, true);
    char *one = big_alloc(MB + MB / 4, true), *small = big_alloc(MB / 2, true);
    cr_assert(long_tail && short_tail && one && small);
    if (big_pages_eligible(long_tail) < 0)
        cr_skip("/proc/self/smaps does not say THPeligible");
    cr_assert_eq((uintptr_t)long_tail % (2 * MB), 0);
    cr_assert_eq((uintptr_t)one % (2 * MB), 0);
    cr_assert_eq(big_pages_eligible(long_tail), 1);
    cr_assert_eq(big_pages_eligible(long_tail + 3 * MB), 1, "a last part of 1.5 MB in small pages");
    cr_assert_eq(big_pages_eligible(short_tail), 1);
    cr_assert_eq(big_pages_eligible(short_tail + 2 * MB), 0, "a last part of 0.25 MB on a big page");
    cr_assert_eq(big_pages_eligible(one), 1, "an array of 1.25 MB in small pages");
    cr_assert_eq(big_pages_eligible(small), 0, "an array of 0.5 MB on a big page");
    free(long_tail);
    free(short_tail);
    free(one);
    free(small);
}

Test(mesh_arrays, refuse_sizes_no_machine_has_instead_of_wrapping_around) {
    void *array = NULL;
    size_t capacity = 0;
    cr_assert_not(mesh_reserve(&array, &capacity, SIZE_MAX / 12 - 1, 12));
    cr_assert_null(array);
    cr_assert_eq(capacity, 0);
    cr_assert_null(big_alloc(SIZE_MAX, true));
    cr_assert_null(big_alloc(SIZE_MAX - 63, false)); /* rounded up to 64 bytes it would wrap to 0 */
}

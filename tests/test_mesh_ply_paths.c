/* test_mesh_ply_paths.c: the PLY reader's fast path for binary files against its general reader, the
 * same model written as ascii, binary little-endian and binary big-endian read alike, and the mesh
 * readers' numbers read as strtod and strtoll read them.
 *
 * mesh_read_ply reads binary vertices and faces straight from the bytes and hands anything unusual to
 * the general reader (mesh_read_ply_general, common/mesh_ply.c). Here both read every model of
 * scenes/models/, copies of a model in the three formats, and thousands of damaged copies of a small
 * binary file: the vertices, faces, normals and texture coordinates must be the same to the bit, and a
 * refused file must be refused with the same message. The tests run with the repository as working
 * directory; the copies are written to out/test/meshes/. */
#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mesh.h"
#include "mesh_load.h"
#include "mesh_ply.h"
#include "mesh_read.h"

#define SCRATCH "out/test/meshes/"

/* The committed model and those make builds (the tests run after it). */
static const char *const MODELS[] = {"scenes/models/bunny.ply", "scenes/models/teapot-5k.ply",
                                     "scenes/models/teapot-5k-uv.ply", "scenes/models/teapot-346k.ply"};

/* Damaged copies of the small binary file tried in reads_alike_when_damaged, and the seed of the bytes. */
#define DAMAGED_COPIES 4000
#define DAMAGE_SEED 20261129u

/* A file's bytes with a NUL after them, as mesh_load hands them to a reader. */
static char *read_whole(const char *path, size_t *size) {
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "%s is missing (make builds the models)", path);
    cr_assert_eq(fseek(f, 0, SEEK_END), 0);
    long length = ftell(f);
    cr_assert_geq(length, 0);
    rewind(f);
    char *data = malloc((size_t)length + 1);
    cr_assert_not_null(data);
    cr_assert_eq(fread(data, 1, (size_t)length, f), (size_t)length);
    fclose(f);
    data[length] = '\0';
    *size = (size_t)length;
    return data;
}

/* What one read gave: the mesh, the corners, whether it loaded and its message. */
struct reading {
    bool ok;
    char err[512];
    struct mesh mesh;
    struct mesh_corners corners;
};

static void read_with(bool fast, const char *name, const char *data, size_t size, bool corners,
                      struct reading *out) {
    memset(out, 0, sizeof *out);
    struct mesh_input in = {.path = name, .data = data, .size = size, .err = out->err, .err_size = sizeof out->err,
                            .corners = corners ? &out->corners : NULL};
    out->ok = fast ? mesh_read_ply(&in, &out->mesh) : mesh_read_ply_general(&in, &out->mesh);
}

static void reading_free(struct reading *r) {
    mesh_free(&r->mesh);
    mesh_corners_free(&r->corners);
}

/* Asserts that `count` items of `size` bytes at a and b are the same bits (both NULL counts as the same). */
static void assert_same_bits(const void *a, const void *b, size_t count, size_t size, const char *what,
                             const char *name) {
    cr_assert((a == NULL) == (b == NULL), "%s: %s kept by one read and not the other", name, what);
    if (a != NULL)
        cr_assert(memcmp(a, b, count * size) == 0, "%s: the %s differ", name, what);
}

/* Asserts that two reads of one file agree entirely: loaded or not, message, and every array. */
static void assert_alike(const struct reading *a, const struct reading *b, const char *name) {
    cr_assert_eq(a->ok, b->ok, "%s: one read loads it, the other says: %s%s", name, a->err, b->err);
    cr_assert_str_eq(a->err, b->err, "%s: the two reads refuse it differently", name);
    if (!a->ok)
        return;
    cr_assert_eq(a->mesh.vertex_count, b->mesh.vertex_count, "%s: vertex counts differ", name);
    cr_assert_eq(a->mesh.face_count, b->mesh.face_count, "%s: face counts differ", name);
    assert_same_bits(a->mesh.vertices, b->mesh.vertices, a->mesh.vertex_count, sizeof(vec3), "vertices", name);
    assert_same_bits(a->mesh.faces, b->mesh.faces, a->mesh.face_count, sizeof(struct mesh_face), "faces", name);
    cr_assert_eq(a->corners.normal_count, b->corners.normal_count, "%s: normal counts differ", name);
    cr_assert_eq(a->corners.uv_count, b->corners.uv_count, "%s: texture coordinate counts differ", name);
    assert_same_bits(a->corners.normals, b->corners.normals, a->corners.normal_count, sizeof(vec3), "normals", name);
    assert_same_bits(a->corners.uvs, b->corners.uvs, a->corners.uv_count, sizeof(struct mesh_uv), "(u, v)", name);
    assert_same_bits(a->corners.normal_faces, b->corners.normal_faces, a->mesh.face_count, sizeof(struct mesh_face),
                     "normal indices", name);
    assert_same_bits(a->corners.uv_faces, b->corners.uv_faces, a->mesh.face_count, sizeof(struct mesh_face),
                     "(u, v) indices", name);
}

/* Reads data both ways, with and without the corners, and asserts they agree; returns whether it loaded. */
static bool both_paths_agree(const char *name, const char *data, size_t size) {
    bool loaded = false;
    for (int corners = 0; corners < 2; corners++) {
        struct reading fast, general;
        read_with(true, name, data, size, corners, &fast);
        read_with(false, name, data, size, corners, &general);
        assert_alike(&fast, &general, name);
        loaded = fast.ok;
        reading_free(&fast);
        reading_free(&general);
    }
    return loaded;
}

Test(mesh_ply_paths, every_model_reads_the_same_on_the_fast_path_as_on_the_general_one) {
    for (size_t k = 0; k < sizeof MODELS / sizeof MODELS[0]; k++) {
        size_t size;
        char *data = read_whole(MODELS[k], &size);
        cr_assert(both_paths_agree(MODELS[k], data, size), "%s should load", MODELS[k]);
        /* mesh_load maps the big models into memory rather than reading them (mesh_load.c): the same */
        struct reading copied, loaded = {.ok = true};
        read_with(true, MODELS[k], data, size, false, &copied);
        cr_assert(mesh_load(MODELS[k], &loaded.mesh, loaded.err, sizeof loaded.err), "%s", loaded.err);
        assert_alike(&copied, &loaded, MODELS[k]);
        reading_free(&copied);
        reading_free(&loaded);
        free(data);
    }
}

/* ---- one model in three formats ------------------------------------------------------------------ */

/* Writes m as a PLY file of the given format ("ascii", "binary_little_endian", "binary_big_endian"):
 * vertices as float (each of m's coordinates is one, as the model was read from floats), and in ascii
 * with 17 significant digits, which read back as exactly the same double. The header carries a comment
 * of `padding` characters. */
static void write_ply(const char *path, const struct mesh *m, const char *format, size_t padding) {
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot write %s", path);
    fprintf(f, "ply\nformat %s 1.0\ncomment %*s\nelement vertex %zu\nproperty float x\nproperty float y\n"
               "property float z\nelement face %zu\nproperty list uchar int vertex_indices\nend_header\n",
            format, (int)padding, "", m->vertex_count, m->face_count);
    bool ascii = strcmp(format, "ascii") == 0, big = strcmp(format, "binary_big_endian") == 0;
    for (size_t k = 0; k < m->vertex_count; k++) {
        double xyz[3] = {m->vertices[k].x, m->vertices[k].y, m->vertices[k].z};
        for (int axis = 0; axis < 3; axis++) {
            float value = (float)xyz[axis];
            cr_assert_eq((double)value, xyz[axis], "the model's coordinates should all be floats");
            uint32_t bits;
            memcpy(&bits, &value, sizeof bits);
            if (ascii)
                fprintf(f, axis < 2 ? "%.17g " : "%.17g\n", xyz[axis]);
            for (int byte = 0; !ascii && byte < 4; byte++)
                fputc((int)(bits >> (8 * (big ? 3 - byte : byte))) & 0xff, f);
        }
    }
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *v = m->faces[k].v;
        if (ascii)
            fprintf(f, "3 %u %u %u\n", v[0], v[1], v[2]);
        else {
            fputc(3, f);
            for (int c = 0; c < 3; c++)
                for (int byte = 0; byte < 4; byte++)
                    fputc((int)(v[c] >> (8 * (big ? 3 - byte : byte))) & 0xff, f);
        }
    }
    cr_assert_eq(fclose(f), 0);
}

/* Loads the model at `path` and makes the folder its copies are written to. */
static void load_model_for_copies(const char *path, struct mesh *model) {
    mkdir("out", 0755);
    mkdir("out/test", 0755);
    mkdir(SCRATCH, 0755);
    char err[512] = "";
    cr_assert(mesh_load(path, model, err, sizeof err), "%s", err);
}

/* Asserts that the file at `path` loads as exactly `model`'s vertices and faces. */
static void assert_loads_as(const char *path, const struct mesh *model) {
    char err[512] = "";
    struct mesh copy;
    cr_assert(mesh_load(path, &copy, err, sizeof err), "%s", err);
    cr_assert_eq(copy.vertex_count, model->vertex_count, "%s", path);
    cr_assert_eq(copy.face_count, model->face_count, "%s", path);
    cr_assert(memcmp(copy.vertices, model->vertices, model->vertex_count * sizeof(vec3)) == 0,
              "%s: the vertices differ from the model's", path);
    cr_assert(memcmp(copy.faces, model->faces, model->face_count * sizeof(struct mesh_face)) == 0,
              "%s: the faces differ from the model's", path);
    mesh_free(&copy);
}

Test(mesh_ply_paths, a_model_written_as_ascii_little_and_big_endian_reads_back_the_same) {
    struct mesh model;
    load_model_for_copies("scenes/models/teapot-5k.ply", &model);
    static const char *const formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    for (size_t k = 0; k < 3; k++) {
        char path[256];
        snprintf(path, sizeof path, SCRATCH "teapot-5k-%s.ply", formats[k]);
        write_ply(path, &model, formats[k], 0);
        assert_loads_as(path, &model);
        size_t size;
        char *data = read_whole(path, &size);
        cr_assert(both_paths_agree(path, data, size), "%s should load", path);
        free(data);
    }
    mesh_free(&model);
}

/* mesh_load maps a big file into memory, but reads it when it ends exactly at the end of a page (the
 * byte after it would not be there to read as the NUL the readers need): both give the model. */
Test(mesh_ply_paths, a_big_file_loads_alike_whether_it_ends_at_a_page_boundary_or_not) {
    struct mesh model;
    load_model_for_copies("scenes/models/teapot-346k.ply", &model);
    long page = sysconf(_SC_PAGESIZE);
    cr_assert_gt(page, 0);
    const char *path = SCRATCH "teapot-346k-paged.ply";
    write_ply(path, &model, "binary_little_endian", 0);
    struct stat info;
    cr_assert_eq(stat(path, &info), 0);
    long unpadded = (long)(info.st_size % page);
    for (long wanted_remainder = 0; wanted_remainder < 2; wanted_remainder++) {
        size_t padding = (size_t)((wanted_remainder - unpadded + page) % page);
        write_ply(path, &model, "binary_little_endian", padding);
        cr_assert_eq(stat(path, &info), 0);
        cr_assert_eq(info.st_size % page, wanted_remainder, "%s is %lld bytes", path, (long long)info.st_size);
        assert_loads_as(path, &model);
    }
    mesh_free(&model);
}

/* ---- damaged files ------------------------------------------------------------------------------- */

/* A small binary file with every kind of value the fast path reads: vertices of double x, float y,
 * short z, uchar red (read past), float nx ny nz and float u v; faces with a uchar flag before the
 * corner list, a triangle, a quad and a pentagon. */
static size_t small_binary_file(unsigned char *out, size_t room, bool big) {
    const char *header = big ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n";
    int used = snprintf((char *)out, room,
                        "%selement vertex 6\nproperty double x\nproperty float y\nproperty short z\n"
                        "property uchar red\nproperty float nx\nproperty float ny\nproperty float nz\n"
                        "property float u\nproperty float v\nelement face 3\nproperty uchar flag\n"
                        "property list uchar ushort vertex_indices\nend_header\n",
                        header);
    cr_assert(used > 0 && (size_t)used < room);
    size_t n = (size_t)used;
    /* Each value's bytes in the file's order: put(bits, size). */
#define PUT(bits, size)                                                                                                \
    do {                                                                                                               \
        uint64_t b_ = (bits);                                                                                          \
        for (size_t k_ = 0; k_ < (size); k_++)                                                                         \
            out[n++] = (unsigned char)(b_ >> (8 * (big ? (size) - 1 - k_ : k_)));                                      \
    } while (0)
    for (int v = 0; v < 6; v++) {
        double x = 0.5 * v - 1.25;
        float y = (float)v * 0.75f, nx = 0.0f, ny = 1.0f, nz = 0.0f, tu = 0.1f * (float)v, tv = 1.0f - tu;
        uint64_t xb;
        memcpy(&xb, &x, 8);
        PUT(xb, 8);
        uint32_t fb;
        memcpy(&fb, &y, 4);
        PUT(fb, 4);
        PUT((uint64_t)(uint16_t)(int16_t)(v - 3), 2);
        PUT(200u, 1);
        const float rest[5] = {nx, ny, nz, tu, tv};
        for (int k = 0; k < 5; k++) {
            memcpy(&fb, &rest[k], 4);
            PUT(fb, 4);
        }
    }
    static const int corners[3][6] = {{3, 0, 1, 2}, {4, 1, 2, 3, 4}, {5, 0, 2, 3, 4, 5}};
    for (int f = 0; f < 3; f++) {
        PUT(7u, 1);
        PUT((uint64_t)corners[f][0], 1);
        for (int c = 1; c <= corners[f][0]; c++)
            PUT((uint64_t)corners[f][c], 2);
    }
#undef PUT
    cr_assert_leq(n, room);
    return n;
}

/* The commonest layout, which the fast path reads on a path of its own (read_plain_triangles): x, y and
 * z as float, and triangles as a uchar count and int corners, in the machine's byte order (here little
 * endian, as on every machine the course runs on). Five triangles over six vertices. */
static size_t small_plain_file(unsigned char *out, size_t room) {
    int used = snprintf((char *)out, room,
                        "ply\nformat binary_little_endian 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n");
    cr_assert(used > 0 && (size_t)used < room);
    size_t n = (size_t)used;
    for (int v = 0; v < 6; v++) {
        const float xyz[3] = {0.5f * (float)v - 1.25f, (float)(v % 3), (float)(v % 2) * 0.25f};
        memcpy(out + n, xyz, sizeof xyz);
        n += sizeof xyz;
    }
    static const int32_t corners[5][3] = {{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 5}, {5, 0, 1}};
    for (int f = 0; f < 5; f++) {
        out[n++] = 3;
        memcpy(out + n, corners[f], sizeof corners[f]);
        n += sizeof corners[f];
    }
    cr_assert_leq(n, room);
    return n;
}

Test(mesh_ply_paths, both_paths_read_every_binary_layout_alike_and_refuse_damaged_copies_alike) {
    unsigned char file[2048], copy[2049];
    uint32_t state = DAMAGE_SEED;
    for (int big = 0; big < 3; big++) { /* little endian, big endian, and the plain layout */
        size_t size = big < 2 ? small_binary_file(file, sizeof file, big) : small_plain_file(file, sizeof file);
        cr_assert(both_paths_agree(big ? "big.ply" : "little.ply", (const char *)file, size), "the file should load");
        size_t body = (size_t)(strstr((const char *)file, "end_header\n") - (const char *)file) + 11;
        int refused = 0;
        for (int k = 0; k < DAMAGED_COPIES; k++) {
            memcpy(copy, file, size);
            size_t damaged_size = size;
            /* xorshift32: a byte or two of the body changed, or the file cut short */
            for (int change = 0; change < 2; change++) {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                if (state % 7 == 0)
                    damaged_size = body + state / 7 % (size - body);
                else
                    copy[body + state / 7 % (size - body)] = (unsigned char)(state >> 24);
            }
            copy[damaged_size] = '\0';
            refused += !both_paths_agree("damaged.ply", (const char *)copy, damaged_size);
        }
        cr_assert_gt(refused, DAMAGED_COPIES / 10, "the damage should make many copies bad (%d refused)", refused);
        cr_assert_lt(refused, DAMAGED_COPIES, "and leave some good");
    }
}

/* ---- numbers in text files --------------------------------------------------------------------- */

/* Decimal numbers tried against strtod in reads_every_decimal_as_strtod_does, and the seed of their digits. */
#define DECIMALS_TRIED 200000
#define DECIMALS_SEED 12345u

/* mesh_parse_double reads the commonest numbers without strtod (mesh_read.c); it must give strtod's
 * double to the bit, and refuse what strtod would not read whole. */
Test(mesh_numbers, reads_every_decimal_as_strtod_does) {
    uint32_t state = DECIMALS_SEED;
    char text[64];
    for (int k = 0; k < DECIMALS_TRIED; k++) {
        uint32_t r[4];
        for (int j = 0; j < 4; j++) {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            r[j] = state;
        }
        /* 1 to 21 digits, a point somewhere or nowhere, an exponent or none, a sign or none */
        int digits = 1 + (int)(r[0] % 21), point = (int)(r[1] % (unsigned)(digits + 2)) - 1, n = 0;
        if (r[2] % 3 == 0)
            text[n++] = r[2] % 2 ? '-' : '+';
        for (int d = 0; d < digits; d++) {
            if (d == point)
                text[n++] = '.';
            uint32_t digit = (r[3] >> (d % 8 * 4)) % 10 ^ (uint32_t)(d * 7 % 10);
            text[n++] = (char)('0' + digit % 10);
        }
        if (r[1] % 4 == 0)
            n += snprintf(text + n, sizeof text - (size_t)n, "%c%d", r[0] % 2 ? 'e' : 'E', (int)(r[2] % 61) - 30);
        text[n] = '\0';
        struct mesh_token token = {text, n};
        char *end;
        double expected = strtod(text, &end), got;
        bool whole = end == text + n;
        cr_assert_eq(mesh_parse_double(token, &got), whole, "'%s': read whole by one and not the other", text);
        if (whole)
            cr_assert(memcmp(&got, &expected, sizeof got) == 0, "'%s' read as %.17g, strtod gives %.17g", text, got,
                      expected);
    }
}

Test(mesh_numbers, reads_the_odd_forms_as_strtod_does_and_refuses_the_rest) {
    static const char *const read[] = {"-0", "-0.0", "+.5", "5.", "1e22", "1e23", "9007199254740993", "1e-400", "123456789012345678901234567890", "1e99999", "nan", "-inf"};
    for (size_t k = 0; k < sizeof read / sizeof read[0]; k++) {
        struct mesh_token token = {read[k], (int)strlen(read[k])};
        double got, expected = strtod(read[k], NULL);
        cr_assert(mesh_parse_double(token, &got), "'%s' should be read", read[k]);
        cr_assert(memcmp(&got, &expected, sizeof got) == 0 || (got != got && expected != expected),
                  "'%s' read as %.17g, strtod gives %.17g", read[k], got, expected);
    }
    /* C's hexadecimal too, which strtod reads and neither mesh format has */
    static const char *const refused[] = {".", "-", "1e", "1e+", "1.5.3", "1,5", "--1", "e5", "1f", "0x1p3", "0X10"};
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        struct mesh_token token = {refused[k], (int)strlen(refused[k])};
        double ignored;
        cr_assert_not(mesh_parse_double(token, &ignored), "'%s' should be refused", refused[k]);
    }
    static const char *const integers[] = {"0", "-7", "+12", "007", "999999999999999999", "9223372036854775807",
                                           "-9223372036854775808"};
    for (size_t k = 0; k < sizeof integers / sizeof integers[0]; k++) {
        struct mesh_token token = {integers[k], (int)strlen(integers[k])};
        long long got;
        cr_assert(mesh_parse_integer(token, &got), "'%s' should be read", integers[k]);
        cr_assert_eq(got, strtoll(integers[k], NULL, 10), "'%s' read as %lld", integers[k], got);
    }
    static const char *const not_integers[] = {"-", "+", "1.0", "9223372036854775808", "12a", "+-5", "0x10"};
    for (size_t k = 0; k < sizeof not_integers / sizeof not_integers[0]; k++) {
        struct mesh_token token = {not_integers[k], (int)strlen(not_integers[k])};
        long long ignored;
        cr_assert_not(mesh_parse_integer(token, &ignored), "'%s' should be refused", not_integers[k]);
    }
}

/* fuzz_mesh.c: one fuzz input through a mesh reader and the checks on what it gives (make fuzz). */
#include "fuzz_mesh.h"

#include <stdlib.h>
#include <string.h>

#include "fuzz_support.h"
#include "mesh_obj.h"
#include "mesh_ply.h"

bool fuzz_mesh_is_ply(const uint8_t *data, size_t size) {
    return (size >= 4 && memcmp(data, "ply\n", 4) == 0) || (size >= 5 && memcmp(data, "ply\r\n", 5) == 0);
}

/* Aborts unless every index of `faces` (count of them; NULL: none) is below `limit`. */
static void check_corner_faces(const struct mesh_face *faces, size_t count, size_t limit, const char *what) {
    for (size_t f = 0; faces != NULL && f < count; f++)
        for (int c = 0; c < 3; c++)
            if (faces[f].v[c] >= limit)
                fuzz_abort("face %zu corner %d is %s %u of %zu", f, c, what, faces[f].v[c], limit);
}

/* Aborts unless `count` items of `size` bytes at a and b are the same bits (both NULL: the same). */
static void check_same_bits(const void *a, const void *b, size_t count, size_t size, const char *what) {
    if ((a == NULL) != (b == NULL) || (a != NULL && memcmp(a, b, count * size) != 0))
        fuzz_abort("the PLY reader's fast path and its general reader give different %s", what);
}

/* Aborts unless the PLY reader's general path (mesh_read_ply_general) gives what its fast path gave:
 * loaded or refused alike, with the same message, the same mesh and the same corners. */
static void check_general_path(const struct mesh_input *fast_in, bool fast_ok, const struct mesh *fast,
                               const struct mesh_corners *fast_corners) {
    char err[512] = "";
    struct mesh m = {0};
    struct mesh_corners c = {0};
    struct mesh_input in = *fast_in;
    in.err = err;
    in.err_size = sizeof err;
    in.corners = fast_in->corners != NULL ? &c : NULL;
    bool ok = mesh_read_ply_general(&in, &m);
    if (ok != fast_ok || strcmp(err, fast_in->err) != 0)
        fuzz_abort("fast path: %s '%s'; general reader: %s '%s'", fast_ok ? "loaded" : "refused", fast_in->err,
                   ok ? "loaded" : "refused", err);
    if (ok) {
        if (m.vertex_count != fast->vertex_count || m.face_count != fast->face_count ||
            c.normal_count != fast_corners->normal_count || c.uv_count != fast_corners->uv_count)
            fuzz_abort("the PLY reader's fast path and its general reader give different counts");
        check_same_bits(m.vertices, fast->vertices, m.vertex_count, sizeof *m.vertices, "vertices");
        check_same_bits(m.faces, fast->faces, m.face_count, sizeof *m.faces, "faces");
        check_same_bits(c.normals, fast_corners->normals, c.normal_count, sizeof *c.normals, "normals");
        check_same_bits(c.uvs, fast_corners->uvs, c.uv_count, sizeof *c.uvs, "texture coordinates");
        check_same_bits(c.normal_faces, fast_corners->normal_faces, m.face_count, sizeof *m.faces, "normal indices");
        check_same_bits(c.uv_faces, fast_corners->uv_faces, m.face_count, sizeof *m.faces, "(u, v) indices");
    }
    mesh_free(&m);
    mesh_corners_free(&c);
}

/* One read, with the corners kept (chapter 14) or not (chapters 3 to 13). */
static void read_once(const char *text, size_t size, bool ply, const char *name, bool corners) {
    char err[512] = "";
    struct mesh m = {0};
    struct mesh_corners c = {0};
    struct mesh_input in = {.path = name, .data = text, .size = size, .err = err, .err_size = sizeof err,
                            .corners = corners ? &c : NULL};
    bool ok = ply ? mesh_read_ply(&in, &m) : mesh_read_obj(&in, &m);
    if (ply)
        check_general_path(&in, ok, &m, &c);
    if (ok) {
        for (size_t k = 0; k < m.vertex_count; k++)
            if (!vec3_is_finite(m.vertices[k]))
                fuzz_abort("vertex %zu of %zu is not finite", k, m.vertex_count);
        for (size_t f = 0; f < m.face_count; f++)
            for (int k = 0; k < 3; k++)
                if (m.faces[f].v[k] >= m.vertex_count)
                    fuzz_abort("face %zu corner %d is vertex %u of %zu", f, k, m.faces[f].v[k], m.vertex_count);
        check_corner_faces(c.normal_faces, m.face_count, c.normal_count, "normal");
        check_corner_faces(c.uv_faces, m.face_count, c.uv_count, "texture coordinate");
    } else if (!fuzz_message_names(err, name)) {
        fuzz_abort("refused with a message that does not start with '%s:': '%s'", name, err);
    }
    mesh_free(&m); /* on failure a reader may leave a half-built mesh, which mesh_load frees */
    mesh_corners_free(&c);
}

void fuzz_mesh_read(const uint8_t *data, size_t size, bool ply, const char *name) {
    char *text = fuzz_copy_with_nul(data, size);
    read_once(text, size, ply, name, false);
    read_once(text, size, ply, name, true);
    free(text);
}

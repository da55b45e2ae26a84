/* closed_mesh.c: closed test meshes with shared vertices, a tessellated cube and an icosphere, for the
 * tests that no ray slips between two triangles (chapter 3's watertight test). */
#include "closed_mesh.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The icosphere's limit: 20 * 4^8 = 1,310,720 triangles. */
#define CLOSED_MESH_MAX_SUBDIVISIONS 8

/* Allocates m for the given counts. Returns false (m empty) when memory runs out. */
static bool mesh_allocate(struct mesh *m, size_t vertices, size_t faces) {
    m->vertices = malloc(vertices * sizeof *m->vertices);
    m->faces = malloc(faces * sizeof *m->faces);
    m->vertex_count = 0;
    m->face_count = 0;
    if (m->vertices == NULL || m->faces == NULL) {
        mesh_free(m);
        return false;
    }
    return true;
}

static void add_face(struct mesh *m, uint32_t a, uint32_t b, uint32_t c) {
    m->faces[m->face_count++] = (struct mesh_face){{a, b, c}};
}

/* ---- the cube ----------------------------------------------------------------------------------- */

/* The vertex at grid point (i, j, k), 0 <= i, j, k <= n, made on first use. The coordinate of grid
 * index i is -1 + 2 i / n, computed from i alone, so every face touching the point agrees on it. */
static uint32_t cube_vertex(struct mesh *m, uint32_t *index, int n, const int g[3]) {
    uint32_t *slot = &index[((size_t)g[0] * (size_t)(n + 1) + (size_t)g[1]) * (size_t)(n + 1) + (size_t)g[2]];
    if (*slot == UINT32_MAX) {
        vec3 p = {-1.0 + 2.0 * g[0] / n, -1.0 + 2.0 * g[1] / n, -1.0 + 2.0 * g[2] / n};
        *slot = (uint32_t)m->vertex_count;
        m->vertices[m->vertex_count++] = p;
    }
    return *slot;
}

bool closed_mesh_cube(int n, struct mesh *m) {
    *m = (struct mesh){0};
    if (n < 1 || n > 4096)
        return false;
    size_t lattice = (size_t)(n + 1) * (size_t)(n + 1) * (size_t)(n + 1);
    uint32_t *index = malloc(lattice * sizeof *index);
    if (index == NULL || !mesh_allocate(m, 6 * (size_t)n * (size_t)n + 2, 12 * (size_t)n * (size_t)n)) {
        free(index);
        return false;
    }
    memset(index, 0xff, lattice * sizeof *index);
    for (int axis = 0; axis < 3; axis++) {
        int u = (axis + 1) % 3, v = (axis + 2) % 3; /* (u, v, axis) is right-handed */
        for (int side = 0; side <= n; side += n) {
            for (int i = 0; i < n; i++) {
                for (int j = 0; j < n; j++) {
                    int g00[3], g10[3], g11[3], g01[3];
                    g00[axis] = g10[axis] = g11[axis] = g01[axis] = side;
                    g00[u] = g01[u] = i;
                    g10[u] = g11[u] = i + 1;
                    g00[v] = g10[v] = j;
                    g01[v] = g11[v] = j + 1;
                    uint32_t p00 = cube_vertex(m, index, n, g00), p10 = cube_vertex(m, index, n, g10);
                    uint32_t p11 = cube_vertex(m, index, n, g11), p01 = cube_vertex(m, index, n, g01);
                    if (side == n) { /* outward normal +axis: counter-clockwise in (u, v) */
                        add_face(m, p00, p10, p11);
                        add_face(m, p00, p11, p01);
                    } else {
                        add_face(m, p00, p11, p10);
                        add_face(m, p00, p01, p11);
                    }
                }
            }
        }
    }
    free(index);
    return true;
}

/* ---- the icosphere ------------------------------------------------------------------------------ */

/* Edge midpoints made so far, in an open-addressing table keyed by the edge's two vertices. */
struct midpoints {
    uint64_t *keys; /* (low << 32 | high) + 1; 0 = empty */
    uint32_t *vertex;
    size_t capacity; /* a power of two */
};

static uint32_t midpoint(struct midpoints *t, struct mesh *m, uint32_t a, uint32_t b) {
    uint32_t low = a < b ? a : b, high = a < b ? b : a;
    uint64_t key = ((uint64_t)low << 32 | high) + 1;
    size_t slot = (size_t)(key * 0x9e3779b97f4a7c15ull >> 20) & (t->capacity - 1);
    while (t->keys[slot] != 0 && t->keys[slot] != key)
        slot = (slot + 1) & (t->capacity - 1);
    if (t->keys[slot] == 0) {
        vec3 p = vec3_scale(vec3_add(m->vertices[low], m->vertices[high]), 0.5);
        t->keys[slot] = key;
        t->vertex[slot] = (uint32_t)m->vertex_count;
        m->vertices[m->vertex_count++] = vec3_normalize(p);
    }
    return t->vertex[slot];
}

bool closed_mesh_icosphere(int subdivisions, struct mesh *m) {
    *m = (struct mesh){0};
    if (subdivisions < 0 || subdivisions > CLOSED_MESH_MAX_SUBDIVISIONS)
        return false;
    size_t faces = (size_t)20 << (2 * subdivisions);
    if (!mesh_allocate(m, faces / 2 + 2, faces)) /* Euler: V = F / 2 + 2 for a closed triangle mesh */
        return false;
    /* The icosahedron: the corners of three golden rectangles, pushed onto the unit sphere. */
    const double g = (1.0 + sqrt(5.0)) / 2.0;
    const double corners[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                   {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    static const uint32_t triangles[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int k = 0; k < 12; k++)
        m->vertices[m->vertex_count++] = vec3_normalize(vec3_make(corners[k][0], corners[k][1], corners[k][2]));
    for (int k = 0; k < 20; k++)
        add_face(m, triangles[k][0], triangles[k][1], triangles[k][2]);

    struct mesh_face *next = malloc(faces * sizeof *next);
    struct midpoints table = {NULL, NULL, 1};
    while (table.capacity < 2 * faces)
        table.capacity *= 2;
    table.keys = calloc(table.capacity, sizeof *table.keys);
    table.vertex = malloc(table.capacity * sizeof *table.vertex);
    bool ok = next != NULL && table.keys != NULL && table.vertex != NULL;
    for (int level = 0; ok && level < subdivisions; level++) {
        size_t count = 0;
        for (size_t f = 0; f < m->face_count; f++) {
            uint32_t a = m->faces[f].v[0], b = m->faces[f].v[1], c = m->faces[f].v[2];
            uint32_t ab = midpoint(&table, m, a, b), bc = midpoint(&table, m, b, c), ca = midpoint(&table, m, c, a);
            next[count++] = (struct mesh_face){{a, ab, ca}};
            next[count++] = (struct mesh_face){{b, bc, ab}};
            next[count++] = (struct mesh_face){{c, ca, bc}};
            next[count++] = (struct mesh_face){{ab, bc, ca}};
        }
        memcpy(m->faces, next, count * sizeof *next);
        m->face_count = count;
    }
    free(next);
    free(table.keys);
    free(table.vertex);
    if (!ok)
        mesh_free(m);
    return ok;
}

/* ---- writing ------------------------------------------------------------------------------------ */

bool closed_mesh_write_ply(const struct mesh *m, const char *path, char *err, size_t err_size) {
    FILE *out = fopen(path, "w");
    if (out == NULL) {
        snprintf(err, err_size, "%s: cannot write: %s", path, strerror(errno));
        return false;
    }
    fprintf(out, "ply\nformat ascii 1.0\ncomment closed test mesh with shared vertices (tests/support/closed_mesh.c)\n");
    fprintf(out, "element vertex %zu\nproperty double x\nproperty double y\nproperty double z\n", m->vertex_count);
    fprintf(out, "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n", m->face_count);
    for (size_t k = 0; k < m->vertex_count; k++)
        fprintf(out, "%.17g %.17g %.17g\n", m->vertices[k].x, m->vertices[k].y, m->vertices[k].z);
    for (size_t k = 0; k < m->face_count; k++)
        fprintf(out, "3 %u %u %u\n", m->faces[k].v[0], m->faces[k].v[1], m->faces[k].v[2]);
    bool ok = !ferror(out);
    ok &= fclose(out) == 0;
    if (!ok)
        snprintf(err, err_size, "%s: cannot write: %s", path, strerror(errno));
    return ok;
}

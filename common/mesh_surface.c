/* mesh_surface.c: normals and texture coordinates blended across a mesh's triangles (chapter 14;
 * mesh_surface.h). */
#include "mesh_surface.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "world.h"

bool mesh_surface_average_normals(const struct mesh *m, struct mesh_corners *c) {
    size_t room = m->vertex_count > 0 ? m->vertex_count : 1;
    vec3 *normals = calloc(room, sizeof *normals);
    struct mesh_face *corners = malloc((m->face_count > 0 ? m->face_count : 1) * sizeof *corners);
    if (normals == NULL || corners == NULL) {
        free(normals);
        free(corners);
        return false;
    }
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
        vec3 area = vec3_cross(vec3_sub(b, a), vec3_sub(c, a)); /* twice the area, along the normal */
        for (int k = 0; k < 3; k++)
            normals[v[k]] = vec3_add(normals[v[k]], area);
    }
    for (size_t k = 0; k < m->vertex_count; k++) {
        double length = vec3_length(normals[k]);
        normals[k] = length > MESH_SURFACE_MIN_NORMAL ? vec3_scale(normals[k], 1.0 / length) : vec3_make(0, 0, 0);
    }
    memcpy(corners, m->faces, m->face_count * sizeof *corners);
    free(c->normals);
    free(c->normal_faces);
    c->normals = normals;
    c->normal_count = m->vertex_count;
    c->normal_faces = corners;
    return true;
}

bool mesh_surface_prepare(struct scene *s, char *err, size_t err_size) {
    for (size_t k = 0; k < s->mesh_count; k++) {
        struct scene_mesh *m = &s->meshes[k];
        struct mesh_corners *c = &m->corners;
        if (m->smooth == SCENE_SMOOTH_OFF) {
            free(c->normals);
            free(c->normal_faces);
            c->normals = NULL;
            c->normal_faces = NULL;
            c->normal_count = 0;
        } else if (m->smooth == SCENE_SMOOTH_ON && c->normal_faces == NULL &&
                   !mesh_surface_average_normals(&m->mesh, c)) {
            snprintf(err, err_size, "%s:%d: mesh %s: out of memory for its normals", s->path, m->line, m->path);
            return false;
        }
        for (size_t n = 0; n < c->normal_count; n++) { /* a file's normals made unit, as POV-Ray does */
            double length = vec3_length(c->normals[n]);
            if (isinf(length)) /* its squares overflow (vn 1e200 0 0): measured without them */
                length = vec3_length_scaled(c->normals[n]);
            if (length > MESH_SURFACE_MIN_NORMAL)
                c->normals[n] = vec3_scale(c->normals[n], 1.0 / length);
        }
    }
    return true;
}

void mesh_surface_weights(vec3 a, vec3 b, vec3 c, vec3 p, double w[3]) {
    vec3 e0 = vec3_sub(b, a), e1 = vec3_sub(c, a), ep = vec3_sub(p, a);
    double d00 = vec3_dot(e0, e0), d01 = vec3_dot(e0, e1), d11 = vec3_dot(e1, e1);
    double dp0 = vec3_dot(ep, e0), dp1 = vec3_dot(ep, e1);
    double denominator = d00 * d11 - d01 * d01;
    w[1] = (d11 * dp0 - d01 * dp1) / denominator;
    w[2] = (d00 * dp1 - d01 * dp0) / denominator;
    w[0] = 1.0 - w[1] - w[2];
}

const struct scene_mesh *mesh_surface_find(const struct scene *s, const struct hit *h) {
    if (h->face < 0)
        return NULL;
    for (size_t k = 0; k < s->mesh_count; k++)
        if (world_mesh_object_number(s, k) == h->object)
            return &s->meshes[k];
    return NULL; /* a triangle line */
}

/* The barycentric weights of p in face f of m. */
static void face_weights(const struct mesh *m, size_t f, vec3 p, double w[3]) {
    const uint32_t *v = m->faces[f].v;
    mesh_surface_weights(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]], p, w);
}

/* TASK 14.2: the interpolated normal */
bool mesh_surface_normal(const struct scene_mesh *m, size_t f, vec3 p, vec3 *normal) {
    const struct mesh_corners *c = &m->corners;
    if (c->normal_faces == NULL)
        return false;
    double w[3];
    face_weights(&m->mesh, f, p, w);
    const uint32_t *n = c->normal_faces[f].v;
    vec3 blend = vec3_add(vec3_add(vec3_scale(c->normals[n[0]], w[0]), vec3_scale(c->normals[n[1]], w[1])),
                          vec3_scale(c->normals[n[2]], w[2]));
    double length = vec3_length(blend);
    if (!(length > MESH_SURFACE_MIN_NORMAL))
        return false;
    *normal = vec3_scale(blend, 1.0 / length);
    return true;
}

/* TASK 14.2 ALSO: the blended texture coordinates of a point of a face */
bool mesh_surface_uv(const struct scene_mesh *m, size_t f, vec3 p, struct mesh_uv *uv) {
    const struct mesh_corners *c = &m->corners;
    if (c->uv_faces == NULL)
        return false;
    double w[3];
    face_weights(&m->mesh, f, p, w);
    const uint32_t *t = c->uv_faces[f].v;
    uv->u = w[0] * c->uvs[t[0]].u + w[1] * c->uvs[t[1]].u + w[2] * c->uvs[t[2]].u;
    uv->v = w[0] * c->uvs[t[0]].v + w[1] * c->uvs[t[1]].v + w[2] * c->uvs[t[2]].v;
    return true;
}

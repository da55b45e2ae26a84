/* mesh.c: what a triangle mesh is made of, freeing it, and placing it in the scene (chapter 3).
 *
 * Reading meshes from files is in mesh_load.c, which chooses a reader (mesh_ply.c or mesh_obj.c); the
 * readers build the arrays defined here, so the calls go one way: mesh_load.c to the readers, the
 * readers to mesh_read.c, and all of them to this file. */
#include "mesh.h"

#include <math.h>
#include <stdlib.h>

void mesh_free(struct mesh *m) {
    free(m->vertices);
    free(m->faces);
    *m = (struct mesh){0};
}

void mesh_corners_free(struct mesh_corners *c) {
    free(c->normals);
    free(c->uvs);
    free(c->normal_faces);
    free(c->uv_faces);
    *c = (struct mesh_corners){0};
}

/* ---- placing ---------------------------------------------------------------------------------- */

size_t mesh_bytes(const struct mesh *m) {
    return m->vertex_count * sizeof *m->vertices + m->face_count * sizeof *m->faces;
}

size_t mesh_corners_bytes(const struct mesh_corners *c, size_t face_count) {
    size_t faces = face_count * sizeof(struct mesh_face);
    return c->normal_count * sizeof *c->normals + c->uv_count * sizeof *c->uvs +
           (c->normal_faces != NULL ? faces : 0) + (c->uv_faces != NULL ? faces : 0);
}

/* Sine and cosine of an angle in degrees, exact for multiples of 90 so that axis-aligned meshes stay
 * exactly axis-aligned (cos(pi / 2) is 6e-17 in floating point, not 0). */
static void sin_cos_degrees(double degrees, double *s, double *c) {
    double turn = fmod(degrees, 360.0);
    if (turn < 0)
        turn += 360.0;
    if (turn == 0.0 || turn == 90.0 || turn == 180.0 || turn == 270.0) {
        static const double quarter_sin[4] = {0, 1, 0, -1}, quarter_cos[4] = {1, 0, -1, 0};
        int quarter = (int)(turn / 90.0);
        *s = quarter_sin[quarter];
        *c = quarter_cos[quarter];
        return;
    }
    double radians = turn * (M_PI / 180.0);
    *s = sin(radians);
    *c = cos(radians);
}

struct mesh_turn mesh_turn_from_degrees(vec3 rotate_degrees) {
    struct mesh_turn t;
    sin_cos_degrees(rotate_degrees.x, &t.sx, &t.cx);
    sin_cos_degrees(rotate_degrees.y, &t.sy, &t.cy);
    sin_cos_degrees(rotate_degrees.z, &t.sz, &t.cz);
    return t;
}

vec3 mesh_turn_point(const struct mesh_turn *t, vec3 p) {
    p = (vec3){p.x, p.y * t->cx - p.z * t->sx, p.y * t->sx + p.z * t->cx}; /* about x: (y, z) turn */
    p = (vec3){p.z * t->sy + p.x * t->cy, p.y, p.z * t->cy - p.x * t->sy}; /* about y: (z, x) turn */
    return (vec3){p.x * t->cz - p.y * t->sz, p.x * t->sz + p.y * t->cz, p.z}; /* about z: (x, y) turn */
}

void mesh_transform(struct mesh *m, double scale, vec3 rotate_degrees, vec3 translate) {
    struct mesh_turn turn = mesh_turn_from_degrees(rotate_degrees);
    for (size_t k = 0; k < m->vertex_count; k++)
        m->vertices[k] = vec3_add(mesh_turn_point(&turn, vec3_scale(m->vertices[k], scale)), translate);
}

void mesh_corners_turn(struct mesh_corners *c, vec3 rotate_degrees) {
    struct mesh_turn turn = mesh_turn_from_degrees(rotate_degrees);
    for (size_t k = 0; k < c->normal_count; k++)
        c->normals[k] = mesh_turn_point(&turn, c->normals[k]);
}

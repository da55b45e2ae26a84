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

/* Turns p about x, then y, then z, by the angles whose sines and cosines are given. */
static vec3 turn_point(vec3 p, double sx, double cx, double sy, double cy, double sz, double cz) {
    p = (vec3){p.x, p.y * cx - p.z * sx, p.y * sx + p.z * cx}; /* about x: (y, z) turn */
    p = (vec3){p.z * sy + p.x * cy, p.y, p.z * cy - p.x * sy}; /* about y: (z, x) turn */
    return (vec3){p.x * cz - p.y * sz, p.x * sz + p.y * cz, p.z}; /* about z: (x, y) turn */
}

void mesh_transform(struct mesh *m, double scale, vec3 rotate_degrees, vec3 translate) {
    double sx, cx, sy, cy, sz, cz;
    sin_cos_degrees(rotate_degrees.x, &sx, &cx);
    sin_cos_degrees(rotate_degrees.y, &sy, &cy);
    sin_cos_degrees(rotate_degrees.z, &sz, &cz);
    for (size_t k = 0; k < m->vertex_count; k++)
        m->vertices[k] = vec3_add(turn_point(vec3_scale(m->vertices[k], scale), sx, cx, sy, cy, sz, cz), translate);
}

void mesh_corners_turn(struct mesh_corners *c, vec3 rotate_degrees) {
    double sx, cx, sy, cy, sz, cz;
    sin_cos_degrees(rotate_degrees.x, &sx, &cx);
    sin_cos_degrees(rotate_degrees.y, &sy, &cy);
    sin_cos_degrees(rotate_degrees.z, &sz, &cz);
    for (size_t k = 0; k < c->normal_count; k++)
        c->normals[k] = turn_point(c->normals[k], sx, cx, sy, cy, sz, cz);
}

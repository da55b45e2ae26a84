/* mesh.h: triangle meshes: their arrays, freeing and placing (chapter 3).
 *
 * A mesh is a shared vertex array and a face array of vertex indices. Loading (mesh_load.h) checks
 * everything a file could get wrong and reports it as "file:line: what is wrong"; binary PLY data is located by
 * byte offset instead, "file: byte N: face 3: what is wrong" (entries of a PLY element are numbered from
 * 0, like PLY's own indices), and problems of the file as a whole read "file: what is wrong" ("no faces",
 * "empty file", "cannot open: ..."). A count in a header is never trusted further than the file's size
 * allows. The readers live in mesh_ply.c and mesh_obj.c, chosen by mesh_load.c. */
#ifndef WHITTED_MESH_H
#define WHITTED_MESH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vec3.h"

struct mesh_face {
    uint32_t v[3]; /* indices into mesh.vertices, each < vertex_count */
};

/* A texture coordinate: where a point of the surface is in a picture (chapter 14). */
struct mesh_uv {
    double u, v;
};

struct mesh {
    vec3 *vertices;          /* owned, vertex_count entries */
    size_t vertex_count;
    struct mesh_face *faces; /* owned, face_count entries; polygons arrive fan-triangulated */
    size_t face_count;
};

/* What a file says about the surface at the corners of its faces besides their places, for chapter 14
 * (NULL and 0 where it says nothing): normals (OBJ vn, PLY nx ny nz) and texture coordinates (OBJ vt,
 * PLY u v, s t or texture_u texture_v), and for each face of the mesh the indices of its corners'
 * normals and coordinates (in PLY the face's own vertex indices; OBJ numbers them apart). */
struct mesh_corners {
    vec3 *normals;
    size_t normal_count;
    struct mesh_uv *uvs;
    size_t uv_count;
    struct mesh_face *normal_faces; /* one per face of the mesh, each index < normal_count; or NULL */
    struct mesh_face *uv_faces;     /* one per face of the mesh, each index < uv_count; or NULL */
};

/* Frees the arrays of m and leaves it empty. Safe on an empty mesh. */
void mesh_free(struct mesh *m);

/* The bytes the arrays of m take. */
size_t mesh_bytes(const struct mesh *m);

/* The bytes the arrays of c take, for a mesh of face_count faces. */
size_t mesh_corners_bytes(const struct mesh_corners *c, size_t face_count);

/* Frees the arrays of c and leaves it empty. */
void mesh_corners_free(struct mesh_corners *c);

/* Turns the normals of c as mesh_transform turns the vertices (the scale and the translation leave a
 * normal's direction alone). */
void mesh_corners_turn(struct mesh_corners *c, vec3 rotate_degrees);

/* The sines and cosines of a `rotate <x, y, z>` in degrees (exact at multiples of 90 degrees, so that
 * quarter turns move coordinates without rounding). Chapter 16's transforms (transform.c) use the same
 * numbers in the same order, so that an instance's vertices round as a written-out mesh's do. */
struct mesh_turn {
    double sx, cx, sy, cy, sz, cz;
};

/* Returns the sines and cosines of the rotation by rotate_degrees about x, then y, then z. */
struct mesh_turn mesh_turn_from_degrees(vec3 rotate_degrees);

/* Returns p turned about x, then y, then z (POV-Ray's order and sense) by the angles of t. */
vec3 mesh_turn_point(const struct mesh_turn *t, vec3 p);

/* Applies, in this order, a uniform scale, rotations about x, y then z by `rotate_degrees` (POV-Ray's
 * `rotate <x, y, z>` order and sense), and a translation to every vertex. */
void mesh_transform(struct mesh *m, double scale, vec3 rotate_degrees, vec3 translate);

#endif

/* mesh.h: triangle meshes and their loading from PLY and OBJ files (chapter 3).
 *
 * A mesh is a shared vertex array and a face array of vertex indices. Loading checks everything a
 * file could get wrong and reports it as "file:line: what is wrong"; binary PLY data is located by
 * byte offset instead, "file: byte N: face 3: what is wrong" (entries of a PLY element are numbered from
 * 0, like PLY's own indices), and problems of the file as a whole read "file: what is wrong" ("no faces",
 * "empty file", "cannot open: ..."). A count in a header is never trusted further than the file's size
 * allows. The readers live in mesh_ply.c and mesh_obj.c. */
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

/* Loads a mesh from `path`, choosing the reader by content: a file whose first line is exactly "ply"
 * is PLY (ascii, binary_little_endian or binary_big_endian 1.0), anything else is read as Wavefront OBJ.
 * Only vertex positions and faces are kept (mesh_load_with_corners keeps normals and texture
 * coordinates too); other vertex properties (colours, Stanford's intensity) are read past. Faces with more than three corners are split into a
 * fan (0,1,2), (0,2,3), ... On success returns true and fills *m (free it with mesh_free); every face
 * index is below vertex_count and every vertex is finite. On failure returns false, leaves *m empty
 * (whatever it held before is overwritten, not freed) and writes the message into err (cut to
 * err_size bytes; err may be NULL when err_size is 0). */
bool mesh_load(const char *path, struct mesh *m, char *err, size_t err_size);

/* mesh_load that also keeps what the file says at the corners in *corners (chapter 14; it is left
 * empty when the file gives neither normals nor texture coordinates). Then an OBJ file's vt and vn
 * indices are checked too: in range, and given by every corner or by none. On failure *corners is
 * empty too. */
bool mesh_load_with_corners(const char *path, struct mesh *m, struct mesh_corners *corners, char *err,
                            size_t err_size);

/* Frees the arrays of m and leaves it empty. Safe on an empty mesh. */
void mesh_free(struct mesh *m);

/* Frees the arrays of c and leaves it empty. */
void mesh_corners_free(struct mesh_corners *c);

/* Turns the normals of c as mesh_transform turns the vertices (the scale and the translation leave a
 * normal's direction alone). */
void mesh_corners_turn(struct mesh_corners *c, vec3 rotate_degrees);

/* Applies, in this order, a uniform scale, rotations about x, y then z by `rotate_degrees` (POV-Ray's
 * `rotate <x, y, z>` order and sense), and a translation to every vertex. */
void mesh_transform(struct mesh *m, double scale, vec3 rotate_degrees, vec3 translate);

#endif

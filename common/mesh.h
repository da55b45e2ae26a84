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

struct mesh {
    vec3 *vertices;          /* owned, vertex_count entries */
    size_t vertex_count;
    struct mesh_face *faces; /* owned, face_count entries; polygons arrive fan-triangulated */
    size_t face_count;
};

/* Loads a mesh from `path`, choosing the reader by content: a file whose first line is exactly "ply"
 * is PLY (ascii, binary_little_endian or binary_big_endian 1.0), anything else is read as Wavefront OBJ.
 * Only vertex positions and faces are kept; other vertex properties (normals, colours, Stanford's
 * intensity, texture coordinates) are read past. Faces with more than three corners are split into a
 * fan (0,1,2), (0,2,3), ... On success returns true and fills *m (free it with mesh_free); every face
 * index is below vertex_count and every vertex is finite. On failure returns false, leaves *m empty
 * (whatever it held before is overwritten, not freed) and writes the message into err (cut to
 * err_size bytes; err may be NULL when err_size is 0). */
bool mesh_load(const char *path, struct mesh *m, char *err, size_t err_size);

/* Frees the arrays of m and leaves it empty. Safe on an empty mesh. */
void mesh_free(struct mesh *m);

/* Applies, in this order, a uniform scale, rotations about x, y then z by `rotate_degrees` (POV-Ray's
 * `rotate <x, y, z>` order and sense), and a translation to every vertex. */
void mesh_transform(struct mesh *m, double scale, vec3 rotate_degrees, vec3 translate);

#endif

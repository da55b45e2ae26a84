/* mesh_load.h: loading a triangle mesh from a PLY or OBJ file, with every fault of the file reported as
 * "file:line: what is wrong" (chapter 3; the message forms are described in mesh.h). */
#ifndef WHITTED_MESH_LOAD_H
#define WHITTED_MESH_LOAD_H

#include <stdbool.h>
#include <stddef.h>

#include "mesh.h"

/* Loads a mesh from `path`, choosing the reader by content: a file whose first line is exactly "ply"
 * is PLY (ascii, binary_little_endian or binary_big_endian 1.0), anything else is read as Wavefront OBJ.
 * Only vertex positions and faces are kept (mesh_load_with_corners keeps normals and texture
 * coordinates too); other vertex properties (colours, Stanford's intensity) are read past. Faces with
 * more than three corners are split into a fan (0,1,2), (0,2,3), ... On success returns true and fills *m (free it with mesh_free); every face
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

#endif

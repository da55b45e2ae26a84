/* mesh_ply.h: the PLY reader (chapter 3), which mesh_load (mesh_load.c) calls for a file whose first line is
 * "ply". Not for other modules: load meshes with mesh_load (mesh_load.h). */
#ifndef WHITTED_MESH_PLY_H
#define WHITTED_MESH_PLY_H

#include <stdbool.h>

#include "mesh.h"
#include "mesh_read.h"

/* Fills the empty mesh m from in, which holds a PLY file (ascii, binary_little_endian or
 * binary_big_endian 1.0). Returns false with the message in in->err when the file is bad; m may then
 * hold a half-built mesh, which the caller frees. */
bool mesh_read_ply(const struct mesh_input *in, struct mesh *m);

/* mesh_read_ply without its fast path for binary files (mesh_ply.c): every value through the general
 * reader. The same answer, the same message, only slower; the tests and the PLY fuzzer compare the two. */
bool mesh_read_ply_general(const struct mesh_input *in, struct mesh *m);

#endif

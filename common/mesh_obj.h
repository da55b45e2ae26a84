/* mesh_obj.h: the Wavefront OBJ reader (chapter 3), which mesh_load (mesh_load.c) calls for a file that is
 * not PLY. Not for other modules: load meshes with mesh_load (mesh_load.h). */
#ifndef WHITTED_MESH_OBJ_H
#define WHITTED_MESH_OBJ_H

#include <stdbool.h>

#include "mesh.h"
#include "mesh_read.h"

/* Fills the empty mesh m from in, which holds an OBJ file. Returns false with the message in in->err
 * when the file is bad; m may then hold a half-built mesh, which the caller frees. */
bool mesh_read_obj(const struct mesh_input *in, struct mesh *m);

#endif

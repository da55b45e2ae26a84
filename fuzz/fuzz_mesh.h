/* fuzz_mesh.h: what the PLY and OBJ harnesses share: one input through a mesh reader, the way
 * mesh_load takes a file through it, and the checks on the result (make fuzz; not part of any chapter). */
#ifndef WHITTED_FUZZ_MESH_H
#define WHITTED_FUZZ_MESH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Which reader mesh_load would choose for data[0..size): true for PLY (the first line is exactly
 * "ply"), false for OBJ. */
bool fuzz_mesh_is_ply(const uint8_t *data, size_t size);

/* Reads data[0..size) with the PLY reader (ply true) or the OBJ reader, from a copy followed by a NUL
 * byte, as mesh_load does after reading a file called `name`, and again keeping the corners' normals
 * and texture coordinates as mesh_load_with_corners does (chapter 14). Then checks their promises and
 * aborts when one is broken: on success every face index is below the vertex count, every corner's
 * normal and texture index below theirs, and every vertex is finite; on failure the message starts
 * with "name:". */
void fuzz_mesh_read(const uint8_t *data, size_t size, bool ply, const char *name);

#endif

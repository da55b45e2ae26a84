/* closed_mesh.h: closed test meshes with shared vertices, a tessellated cube and an icosphere, for the
 * tests that no ray slips between two triangles (chapter 3's watertight test). */
#ifndef WHITTED_CLOSED_MESH_H
#define WHITTED_CLOSED_MESH_H

#include <stdbool.h>
#include <stddef.h>

#include "mesh.h"

/* Fills *m with the surface of the cube [-1, 1]^3, each face an n x n grid of squares, each square
 * split along its diagonal from its (low u, low v) corner to its (high u, high v) corner. (u, v) are
 * the face's other two axes: (y, z) on the faces x = +-1, (z, x) on y = +-1, (x, y) on z = +-1, so
 * on z = +-1 the diagonals run along the lines x - y = constant. Every grid point is one vertex,
 * shared by all faces that touch it: 6 n^2 + 2 vertices, 12 n^2 triangles, wound counter-clockwise
 * seen from outside.
 * Returns false (and leaves *m empty) when n < 1 or memory runs out; free it with mesh_free. */
bool closed_mesh_cube(int n, struct mesh *m);

/* Fills *m with the unit sphere approximated by an icosahedron whose triangles are split into four
 * `subdivisions` times, the new vertices (edge midpoints, one per edge, shared) pushed out onto the
 * sphere: 20 * 4^subdivisions triangles, wound counter-clockwise seen from outside. Returns false
 * (and leaves *m empty) when subdivisions is outside 0..8 or memory runs out. */
bool closed_mesh_icosphere(int subdivisions, struct mesh *m);

/* Writes m to `path` as an ASCII PLY file, coordinates with 17 significant digits (read back, they
 * are the same doubles). Returns false, with the reason in err, when the file cannot be written. */
bool closed_mesh_write_ply(const struct mesh *m, const char *path, char *err, size_t err_size);

#endif

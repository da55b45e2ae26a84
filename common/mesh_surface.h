/* mesh_surface.h: a mesh's surface between its corners (chapter 14; docs/14-textures.md): normals and
 * texture coordinates given at the corners and blended across each triangle with the hit's barycentric
 * weights, as POV-Ray's smooth triangles and mesh2 blend them. A blended normal is made unit length
 * again: three unit vectors averaged are shorter than one, and the shading needs a unit normal. */
#ifndef WHITTED_MESH_SURFACE_H
#define WHITTED_MESH_SURFACE_H

#include <stdbool.h>
#include <stddef.h>

#include "hit.h"
#include "scene.h"

/* Below this length a blended or averaged normal has no direction worth using (opposite corner normals
 * cancel, or a vertex's faces have no area): the face's own normal is used instead. */
#define MESH_SURFACE_MIN_NORMAL 1e-12

/* Gets the scene's meshes ready for chapter 14 (after scene_load_meshes): a mesh with `smooth off`
 * forgets its normals, one with `smooth on` and no normals in its file gets the average of its faces'
 * normals at each vertex (each weighted by its area), and a file's normals are made unit length (as
 * POV-Ray's mesh2 makes them). Returns false with "scene:line: ..." in err when memory runs out. */
bool mesh_surface_prepare(struct scene *s, char *err, size_t err_size);

/* Makes c's normals the area-weighted average of the normals of the faces of m around each vertex,
 * unit length (zero where they cancel), one per vertex (c->normal_faces = m->faces). Returns false when
 * memory runs out (c unchanged). */
bool mesh_surface_average_normals(const struct mesh *m, struct mesh_corners *c);

/* Returns the barycentric weights (w[0] for corner a, w[1] for b, w[2] for c) of the point p, which lies
 * in the plane of the triangle a, b, c: p = w0 a + w1 b + w2 c with w0 + w1 + w2 = 1. */
void mesh_surface_weights(vec3 a, vec3 b, vec3 c, vec3 p, double w[3]);

/* Returns the mesh the hit *h is on (its face is h->face), or NULL for a triangle line or another shape. */
const struct scene_mesh *mesh_surface_find(const struct scene *s, const struct hit *h);

/* Stores in *normal the corner normals of m blended at point p of face f and made unit length. Returns
 * false (and leaves *normal) when m has no normals or the blend has no direction. */
bool mesh_surface_normal(const struct scene_mesh *m, size_t f, vec3 p, vec3 *normal);

/* Stores in *uv the corners' texture coordinates of m blended at point p of face f. Returns false when
 * m has none. */
bool mesh_surface_uv(const struct scene_mesh *m, size_t f, vec3 p, struct mesh_uv *uv);

#endif

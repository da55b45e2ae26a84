/* scene_meshes.c: loads the mesh files a scene names and places them in the world (chapter 3). */
#include "scene.h"

#include <math.h>
#include <stdio.h>

#include "memory_budget.h"
#include "mesh_load.h"
#include "triangle.h"

/* The accelerating structures of chapters 5, 9 and 10 keep boxes in float and the SAH multiplies two
 * sides of a box in float to get its area. A side s has an area that is a normal float (about 1.2e-38
 * to 3.4e38) only for s between about 1e-19 and 1e19; beyond that the areas overflow or vanish and the
 * builds fail (a mesh at 1e39 does not even fit a float box). A placed mesh must stay inside these
 * limits, a factor of ten within that range: */
#define SCENE_MESH_MAX_COORD TRIANGLE_MAX_COORD /* no coordinate beyond 1e18, so no side beyond 2e18 */
#define SCENE_MESH_MIN_SIZE 1e-18 /* the mesh's largest side at least this */
#define SCENE_MESH_ERROR_SIZE 4096 /* room for a mesh reader's message, which names its file */

/* Checks that the placed mesh m lies within the limits above, and its texture coordinates too (so that
 * a point of a picture blended from three stays finite); otherwise writes "scene:line: mesh FILE placed
 * out of range: ..." (or "mesh FILE: texture coordinate ...") into err and returns false. */
static bool placed_in_range(const struct scene *s, const struct scene_mesh *m, char *err, size_t err_size) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < m->mesh.vertex_count; k++) {
        vec3 v = m->mesh.vertices[k];
        double c[3] = {v.x, v.y, v.z};
        for (int axis = 0; axis < 3; axis++) {
            if (!(fabs(c[axis]) <= SCENE_MESH_MAX_COORD)) { /* also catches infinity and NaN */
                snprintf(err, err_size, "%s:%d: mesh %s placed out of range: vertex %zu lands at (%g, %g, %g); "
                         "coordinates must stay within -%g .. %g", s->path, m->line, m->path, k, v.x, v.y, v.z,
                         SCENE_MESH_MAX_COORD, SCENE_MESH_MAX_COORD);
                return false;
            }
            lo[axis] = fmin(lo[axis], c[axis]);
            hi[axis] = fmax(hi[axis], c[axis]);
        }
    }
    for (size_t k = 0; k < m->corners.uv_count; k++) { /* a picture's place, blended across a face */
        struct mesh_uv uv = m->corners.uvs[k];
        if (!(fabs(uv.u) <= SCENE_MESH_MAX_COORD && fabs(uv.v) <= SCENE_MESH_MAX_COORD)) {
            snprintf(err, err_size, "%s:%d: mesh %s: texture coordinate %zu is (%g, %g); texture coordinates must "
                     "stay within -%g .. %g", s->path, m->line, m->path, k + 1, uv.u, uv.v, SCENE_MESH_MAX_COORD,
                     SCENE_MESH_MAX_COORD);
            return false;
        }
    }
    double size = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    if (!(size >= SCENE_MESH_MIN_SIZE)) {
        snprintf(err, err_size, "%s:%d: mesh %s placed out of range: it is %g across; it must be at least %g "
                 "across", s->path, m->line, m->path, size, SCENE_MESH_MIN_SIZE);
        return false;
    }
    return true;
}

bool scene_load_meshes(struct scene *s, char *err, size_t err_size) {
    size_t budget = memory_budget_share(MEMORY_BUDGET_MESH_SHARE), taken = 0;
    for (size_t k = 0; k < s->mesh_count; k++) {
        struct scene_mesh *m = &s->meshes[k];
        if (m->mesh.vertices != NULL) { /* already loaded */
            taken += mesh_bytes(&m->mesh) + mesh_corners_bytes(&m->corners, m->mesh.face_count);
            continue;
        }
        /* Chapter 14 (which sets s->paint) keeps the corners' normals and (u, v); before, meshes are flat. */
        char why[SCENE_MESH_ERROR_SIZE]; /* the reader's own "FILE:LINE: what is wrong", after the scene's line */
        if (!mesh_load_with_corners(m->path, &m->mesh, s->paint != NULL ? &m->corners : NULL, why, sizeof why)) {
            snprintf(err, err_size, "%s:%d: mesh: %s", s->path, m->line, why);
            return false;
        }
        taken += mesh_bytes(&m->mesh) + mesh_corners_bytes(&m->corners, m->mesh.face_count);
        if (taken > budget) {
            memory_budget_explain(why, sizeof why, "meshes", taken, MEMORY_BUDGET_MESH_SHARE);
            snprintf(err, err_size, "%s:%d: mesh %s: %s", s->path, m->line, m->path, why);
            return false;
        }
        mesh_transform(&m->mesh, m->scale, m->rotate, m->translate);
        mesh_corners_turn(&m->corners, m->rotate);
        if (!placed_in_range(s, m, err, err_size))
            return false;
    }
    return true;
}

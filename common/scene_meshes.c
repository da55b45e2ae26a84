/* scene_meshes.c: loads the mesh files a scene names and places them in the world (chapter 3). */
#include "scene.h"

bool scene_load_meshes(struct scene *s, char *err, size_t err_size) {
    for (size_t k = 0; k < s->mesh_count; k++) {
        struct scene_mesh *m = &s->meshes[k];
        if (m->mesh.vertices != NULL)
            continue; /* already loaded */
        if (!mesh_load(m->path, &m->mesh, err, err_size))
            return false;
        mesh_transform(&m->mesh, m->scale, m->rotate, m->translate);
    }
    return true;
}

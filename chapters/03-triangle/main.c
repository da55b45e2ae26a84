/* Chapter 3, the triangle: single triangles and whole meshes join the spheres.
 *
 * Moller-Trumbore is in common/triangle.c, the mesh loader in common/mesh.c (PLY in mesh_ply.c, OBJ
 * in mesh_obj.c). Every mesh face is
 * tested against every ray, one by one: the brute-force loop whose cost chapters 5, 9 and 10 attack. */
#include "cli.h"
#include "headlight.h"

/* Returns the colour of the nearest sphere, triangle or mesh face along r, or the background. */
static vec3 trace_triangles(const void *world, const ray *r) {
    const struct scene *s = world;
    struct hit h = hit_nothing(INFINITY);
    sphere_closest(s->spheres, s->sphere_count, r, RAY_T_MIN, &h);
    triangle_closest(s->triangles, s->triangle_count, r, RAY_T_MIN, &h);
    for (size_t k = 0; k < s->mesh_count; k++)
        triangle_mesh_closest(&s->meshes[k].mesh, s->meshes[k].material, r, RAY_T_MIN, &h);
    if (!hit_found(&h))
        return s->background;
    return headlight_shade(s, &h, r->direction);
}

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 3,
        .title = "triangle",
        .default_scene = "scenes/03-triangle.scene",
        .features = SCENE_SPHERES | SCENE_TRIANGLES,
        .lighting = POV_HEADLIGHT,
        .load_meshes = scene_load_meshes,
        .trace = trace_triangles,
    };
    return cli_run(&chapter, argc, argv);
}

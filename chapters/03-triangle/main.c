/* Chapter 3, the triangle: single triangles and whole meshes join the spheres.
 *
 * Moller-Trumbore is in common/triangle.c, the mesh loader in common/mesh.c (PLY in mesh_ply.c, OBJ
 * in mesh_obj.c). Every mesh face is
 * tested against every ray, one by one: the brute-force loop whose cost chapters 5, 9 and 10 attack. */
#include "cli.h"
#include "headlight.h"
#include "sphere.h"
#include "triangle.h"

/* Returns the colour of the nearest sphere, triangle or mesh face along r, or the background. */
static vec3 trace_triangles(const void *world, const ray *r) {
    const struct scene *s = world;
    const struct shape_list *spheres = scene_shapes(s, &sphere_syntax);
    const struct shape_list *triangles = scene_shapes(s, &triangle_syntax);
    struct hit h = hit_nothing(INFINITY);
    sphere_closest(spheres->items, spheres->count, r, RAY_T_MIN, &h);
    triangle_closest(triangles->items, triangles->count, r, RAY_T_MIN, &h);
    for (size_t k = 0; k < s->mesh_count; k++)
        triangle_mesh_closest(&s->meshes[k].mesh, s->meshes[k].material, r, RAY_T_MIN, &h);
    if (!hit_found(&h))
        return s->background;
    return headlight_shade(s, &h, r->direction);
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 3 draws: chapter 2's spheres, and triangles (`triangle` lines; the
     * faces of meshes are triangles too). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, NULL};
    static const struct chapter chapter = {
        .number = 3,
        .title = "triangle",
        .default_scene = "scenes/03-triangle.scene",
        .kinds = kinds,
        .lighting = POV_HEADLIGHT,
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err)) /* the mesh files, PLY or OBJ */
        return cli_fail(&run);
    cli_render(&run, trace_triangles, &run.scene);
    return cli_finish(&run);
}

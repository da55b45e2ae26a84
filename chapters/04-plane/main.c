/* Chapter 4, the plane: an infinite floor (or wall) under the spheres and triangles.
 *
 * The ray-plane formula is in common/plane.c. A plane is the one shape without a bounding box, which
 * is why chapters 5, 9 and 10 keep planes out of their acceleration structures. */
#include "cli.h"
#include "headlight.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"

/* Returns the colour of the nearest sphere, triangle, mesh face or plane along r, or the background. */
static vec3 trace_with_planes(const void *world, const ray *r) {
    const struct scene *s = world;
    const struct shape_list *spheres = scene_shapes(s, &sphere_syntax);
    const struct shape_list *triangles = scene_shapes(s, &triangle_syntax);
    const struct shape_list *planes = scene_shapes(s, &plane_syntax);
    struct hit h = hit_nothing(INFINITY);
    sphere_closest(spheres->items, spheres->count, r, RAY_T_MIN, &h);
    triangle_closest(triangles->items, triangles->count, r, RAY_T_MIN, &h);
    for (size_t k = 0; k < s->mesh_count; k++)
        triangle_mesh_closest(&s->meshes[k].mesh, s->meshes[k].material, r, RAY_T_MIN, &h);
    plane_closest(planes->items, planes->count, r, RAY_T_MIN, &h);
    if (!hit_found(&h))
        return s->background;
    return headlight_shade(s, &h, r->direction);
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 4 draws: chapter 3's, and the infinite plane. */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, NULL};
    static const struct chapter chapter = {
        .number = 4,
        .title = "plane",
        .default_scene = "scenes/04-plane.scene",
        .kinds = kinds,
        .lighting = POV_HEADLIGHT,
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    cli_render(&run, trace_with_planes, &run.scene);
    return cli_finish(&run);
}

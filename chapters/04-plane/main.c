/* Chapter 4, the plane: an infinite floor (or wall) under the spheres and triangles.
 *
 * The ray-plane formula is in common/plane.c. A plane is the one shape without a bounding box, which
 * is why chapters 5, 9 and 10 keep planes out of their acceleration structures. */
#include "cli.h"
#include "headlight.h"

/* Returns the colour of the nearest sphere, triangle, mesh face or plane along r, or the background. */
static vec3 trace_with_planes(const void *world, const ray *r) {
    const struct scene *s = world;
    struct hit h = hit_nothing(INFINITY);
    sphere_closest(s->spheres, s->sphere_count, r, RAY_T_MIN, &h);
    triangle_closest(s->triangles, s->triangle_count, r, RAY_T_MIN, &h);
    for (size_t k = 0; k < s->mesh_count; k++)
        triangle_mesh_closest(&s->meshes[k].mesh, s->meshes[k].material, r, RAY_T_MIN, &h);
    plane_closest(s->planes, s->plane_count, r, RAY_T_MIN, &h);
    if (!hit_found(&h))
        return s->background;
    return headlight_shade(s, &h, r->direction);
}

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 4,
        .title = "plane",
        .default_scene = "scenes/04-plane.scene",
        .features = SCENE_SPHERES | SCENE_TRIANGLES | SCENE_PLANES,
        .lighting = POV_HEADLIGHT,
        .load_meshes = scene_load_meshes,
        .trace = trace_with_planes,
    };
    return cli_run(&chapter, argc, argv);
}

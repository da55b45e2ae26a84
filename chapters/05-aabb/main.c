/* Chapter 5, axis-aligned boxes: a new shape, and the first speed-up.
 *
 * The slab test (common/aabb.c) answers whether a ray meets a box. Boxes become shapes of their own
 * (common/box.c), and every mesh gets a bounding box (common/world.c): a ray that misses it skips all
 * of the mesh's triangles. The counter "triangles culled" says how many triangle tests that saved. */
#include "box.h"
#include "cli.h"
#include "headlight.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"
#include "world.h"

/* Returns the colour of the nearest shape along r (meshes behind their bounding boxes), or the
 * background. */
static vec3 trace_culled(const void *world, const ray *r) {
    const struct world *w = world;
    struct hit h = hit_nothing(INFINITY);
    if (!world_closest(w, r, RAY_T_MIN, &h))
        return w->scene->background;
    return headlight_shade(w->scene, &h, r->direction);
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 5 draws: chapter 4's, and the box. */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 5,
        .title = "aabb",
        .default_scene = "scenes/05-aabb.scene",
        .kinds = kinds,
        .lighting = POV_HEADLIGHT,
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct world w; /* new: the shapes kind by kind, each mesh behind its bounding box */
    if (!world_init(&w, &run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    cli_render(&run, trace_culled, &w);
    world_free(&w);
    return cli_finish(&run);
}

/* Chapter 5, axis-aligned boxes: a new shape, and the first speed-up.
 *
 * The slab test (common/aabb.c) answers whether a ray meets a box. Boxes become shapes of their own
 * (common/box.c), and every mesh gets a bounding box (common/world.c): a ray that misses it skips all
 * of the mesh's triangles. The counter "triangles culled" says how many triangle tests that saved. */
#include "cli.h"
#include "headlight.h"
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
    static const struct chapter chapter = {
        .number = 5,
        .title = "aabb",
        .default_scene = "scenes/05-aabb.scene",
        .features = SCENE_EVERY_SHAPE,
        .lighting = POV_HEADLIGHT,
        .load_meshes = scene_load_meshes,
        .prepare = world_create,
        .release = world_destroy,
        .trace = trace_culled,
    };
    return cli_run(&chapter, argc, argv);
}

/* Chapter 7, shadows: before a light counts, a shadow ray checks that nothing stands in its way.
 *
 * The shadow ray is in common/shadow.c, its offset constant SHADOW_T_MIN in common/ray.h. The shading
 * is chapter 6's with one change: phong_trace_nearest is given shadow_opaque, so a light blocked by any
 * shape adds nothing. Run the scene scenes/07-shadow-acne.scene to see what happens without the offset. */
#include "cli.h"
#include "phong.h"
#include "shadow.h"
#include "world.h"

/* Returns the Phong-shaded colour of the nearest shape along r, lights blocked by shapes left out. */
static vec3 trace_shadowed(const void *world, const ray *r) { return phong_trace_nearest(world, r, shadow_opaque); }

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 7,
        .title = "shadows",
        .default_scene = "scenes/07-shadows.scene",
        .features = SCENE_EVERY_SHAPE,
        .lighting = POV_PHONG_SHADOWS,
        .load_meshes = scene_load_meshes,
        .prepare = world_create,
        .release = world_destroy,
        .trace = trace_shadowed,
    };
    return cli_run(&chapter, argc, argv);
}

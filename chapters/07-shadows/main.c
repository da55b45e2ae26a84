/* Chapter 7, shadows: before a light counts, a shadow ray checks that nothing stands in its way.
 *
 * The shadow ray is in common/shadow.c, its offset constant SHADOW_T_MIN in common/ray.h. The shading
 * is chapter 6's with one change: phong_trace_nearest is given shadow_opaque, so a light blocked by any
 * shape adds nothing. Run the scene scenes/07-shadow-acne.scene to see what happens without the offset. */
#include "box.h"
#include "cli.h"
#include "phong.h"
#include "plane.h"
#include "shadow.h"
#include "sphere.h"
#include "triangle.h"
#include "world.h"

/* Returns the Phong-shaded colour of the nearest shape along r, lights blocked by shapes left out. */
static vec3 trace_shadowed(const void *world, const ray *r) { return phong_trace_nearest(world, r, shadow_opaque); }

int main(int argc, char **argv) {
    /* The kinds of shape chapter 7 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 7,
        .title = "shadows",
        .default_scene = "scenes/07-shadows.scene",
        .kinds = kinds,
        .lighting = POV_PHONG_SHADOWS,
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct world w;
    if (!world_init(&w, &run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    cli_render(&run, trace_shadowed, &w);
    world_free(&w);
    return cli_finish(&run);
}

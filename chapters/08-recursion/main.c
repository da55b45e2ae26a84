/* Chapter 8, recursion: mirrors and glass. A hit spawns a reflected ray, a refracted ray, or both, and
 * traces them exactly as it traced the camera ray, down to a maximum depth.
 *
 * The recursion is in common/whitted.c (chapters 9 and 10 reuse it), Snell's law in whitted_refract,
 * and light filtered through glass in common/shadow.c (shadow_filtered). */
#include "box.h"
#include "cli.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"
#include "whitted.h"
#include "world.h"

int main(int argc, char **argv) {
    /* The kinds of shape chapter 8 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 8,
        .title = "recursion",
        .default_scene = "scenes/08-recursion.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct world w;
    if (!world_init(&w, &run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    cli_render(&run, whitted_trace, &w);
    world_free(&w);
    return cli_finish(&run);
}

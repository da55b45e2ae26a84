/* Chapter 8, recursion: mirrors and glass. A hit spawns a reflected ray, a refracted ray, or both, and
 * traces them exactly as it traced the camera ray, down to a maximum depth.
 *
 * The recursion is in common/whitted.c (chapters 9 and 10 reuse it), Snell's law in whitted_refract,
 * and light filtered through glass in common/shadow.c (shadow_filtered). */
#include "cli.h"
#include "whitted.h"

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 8,
        .title = "recursion",
        .default_scene = "scenes/08-recursion.scene",
        .features = SCENE_EVERY_SHAPE,
        .lighting = POV_WHITTED,
        .load_meshes = scene_load_meshes,
        .prepare = world_create,
        .release = world_destroy,
        .trace = whitted_trace,
    };
    return cli_run(&chapter, argc, argv);
}

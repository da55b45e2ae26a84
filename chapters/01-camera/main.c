/* Chapter 1, the camera: one ray through the centre of every pixel, coloured by where it points.
 *
 * There are no shapes yet. Each ray's colour is its direction mapped from [-1, 1] to [0, 1] per
 * channel: red grows with x, green with y and blue with z (for this scene's camera, which looks down
 * -z: red to the right, green upwards, blue dark in the centre and rising towards the corners). A camera that is wrong in any
 * way (mirrored, upside down, wrong field of view, rays through pixel corners) gives a visibly
 * different picture. The camera itself is in common/camera.c; the pixel loop in common/render.c. */
#include "cli.h"

/* Returns 0.5 + 0.5 * direction: a unit direction becomes a colour with every channel in [0, 1]. */
static vec3 colour_by_direction(const void *world, const ray *r) {
    (void)world; /* nothing to hit yet */
    return vec3_add_scaled(vec3_make(0.5, 0.5, 0.5), r->direction, 0.5);
}

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 1,
        .title = "camera",
        .default_scene = "scenes/01-camera.scene",
        .kinds = NULL, /* no shapes yet: the scene's are read and ignored */
        .lighting = POV_RAY_DIRECTION,
    };
    struct cli_run run;
    if (cli_start(&run, &chapter, argc, argv))
        cli_render(&run, colour_by_direction, NULL);
    return cli_finish(&run);
}

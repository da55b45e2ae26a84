/* Chapter 2, the sphere: each primary ray looks for the nearest sphere it meets.
 *
 * The intersection itself (the quadratic formula) is in common/sphere.c; the stand-in lighting, a white
 * light at the eye, in common/headlight.c. This file is the search for the nearest hit. */
#include "cli.h"
#include "headlight.h"
#include "sphere.h"

/* Returns the colour of the nearest sphere along r, or the background when r meets none. */
static vec3 trace_spheres(const void *world, const ray *r) {
    const struct scene *s = world;
    const struct shape_list *spheres = scene_shapes(s, &sphere_syntax);
    struct hit h = hit_nothing(INFINITY);
    sphere_closest(spheres->items, spheres->count, r, RAY_T_MIN, &h);
    if (!hit_found(&h))
        return s->background;
    return headlight_shade(s, &h, r->direction);
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 2 draws: the sphere, the first of all. */
    static const struct shape_kind *const kinds[] = {&sphere_kind, NULL};
    static const struct chapter chapter = {
        .number = 2,
        .title = "sphere",
        .default_scene = "scenes/02-sphere.scene",
        .kinds = kinds,
        .lighting = POV_HEADLIGHT,
    };
    struct cli_run run;
    if (cli_start(&run, &chapter, argc, argv))
        cli_render(&run, trace_spheres, &run.scene);
    return cli_finish(&run);
}

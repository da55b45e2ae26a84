/* Chapter 2, the sphere: each primary ray looks for the nearest sphere it meets.
 *
 * The intersection itself (the quadratic formula) is in common/sphere.c; the stand-in lighting, a white
 * light at the eye, in common/headlight.c. This file is the search for the nearest hit. */
#include "cli.h"
#include "headlight.h"

/* Returns the colour of the nearest sphere along r, or the background when r meets none. */
static vec3 trace_spheres(const void *world, const ray *r) {
    const struct scene *s = world;
    struct hit h = hit_nothing(INFINITY);
    sphere_closest(s->spheres, s->sphere_count, r, RAY_T_MIN, &h);
    if (!hit_found(&h))
        return s->background;
    return headlight_shade(s, &h, r->direction);
}

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 2,
        .title = "sphere",
        .default_scene = "scenes/02-sphere.scene",
        .features = SCENE_SPHERES,
        .lighting = POV_HEADLIGHT,
        .trace = trace_spheres,
    };
    return cli_run(&chapter, argc, argv);
}

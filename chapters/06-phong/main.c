/* Chapter 6, Phong shading: materials and coloured point lights replace the light at the eye.
 *
 * Each hit is shaded by ambient light, the diffuse (Lambert) term and the Phong highlight of every light
 * that faces the surface (common/phong.c, POV-Ray's formula exactly: phong_shade for one point,
 * phong_trace_nearest for a ray). Nothing casts shadows yet: a light reaches every surface that faces
 * it. */
#include "cli.h"
#include "phong.h"
#include "world.h"

/* Returns the Phong-shaded colour of the nearest shape along r, or the background; no shadows. */
static vec3 trace_phong(const void *world, const ray *r) { return phong_trace_nearest(world, r, NULL); }

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 6,
        .title = "phong",
        .default_scene = "scenes/06-phong.scene",
        .features = SCENE_EVERY_SHAPE,
        .lighting = POV_PHONG,
        .load_meshes = scene_load_meshes,
        .prepare = world_create,
        .release = world_destroy,
        .trace = trace_phong,
    };
    return cli_run(&chapter, argc, argv);
}

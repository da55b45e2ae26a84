/* Chapter 6, Phong shading: materials and coloured point lights replace the light at the eye.
 *
 * Each hit is shaded by ambient light, the diffuse (Lambert) term and the Phong highlight of every light
 * that faces the surface (common/phong.c, POV-Ray's formula exactly: phong_shade for one point,
 * phong_trace_nearest for a ray). Nothing casts shadows yet: a light reaches every surface that faces
 * it. */
#include "box.h"
#include "cli.h"
#include "phong.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"
#include "world.h"

/* Returns the Phong-shaded colour of the nearest shape along r, or the background; no shadows. */
static vec3 trace_phong(const void *world, const ray *r) { return phong_trace_nearest(world, r, NULL); }

int main(int argc, char **argv) {
    /* The kinds of shape chapter 6 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 6,
        .title = "phong",
        .default_scene = "scenes/06-phong.scene",
        .kinds = kinds,
        .lighting = POV_PHONG,
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct world w;
    if (!world_init(&w, &run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    cli_render(&run, trace_phong, &w);
    world_free(&w);
    return cli_finish(&run);
}

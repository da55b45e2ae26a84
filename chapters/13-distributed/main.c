/* Chapter 13, distributed ray tracing: soft shadows from area lights, and depth of field.
 *
 * A light with axis1, axis2 and samples on its line (common/area_light.h) is a rectangle of point
 * lights, and a point that sees part of it lies in the penumbra: its shadow ray becomes several, one
 * per point of the grid, fewer where POV-Ray's adaptive rule finds the corners agree
 * (common/soft_shadow.c). A camera with an aperture (common/lens.h) is a lens instead of a pinhole:
 * each camera sample becomes several rays from points over the lens, sharp only on the focal plane
 * (common/thin_lens.c). Everything else is chapter 12's: the pixels sampled by the scene's antialias
 * line, chapter 11's fast BVH, the same threads. */
#include "accel_fast_bvh.h"
#include "box.h"
#include "cli.h"
#include "fast_bvh.h"
#include "plane.h"
#include "soft_shadow.h"
#include "sphere.h"
#include "thin_lens.h"
#include "triangle.h"
#include "whitted.h"

static struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

/* What chapter 13 adds to the tracer: every light's shadow by soft_shadow_filtered, which is chapter 8's
 * filtered shadow ray for a point light and a grid of them for an area light. */
static vec3 trace_soft(const void *world, const ray *r) {
    return whitted_trace_shadowed(world, r, soft_shadow_filtered);
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 13 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 13,
        .title = "distributed",
        .default_scene = "scenes/13-distributed.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule (BVH: median split;\n"
                        "                   kd-tree: the axis holding most objects)\n"
                        "  (a light's samples and adaptive keys say how many shadow rays it takes, e.g.\n"
                        "   --set light.1.samples=\"9 9\" --set light.1.adaptive=1; the camera's aperture\n"
                        "   and focal_point give it a lens, e.g. --set camera.aperture=0)\n",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct accel_world *w =
        accel_world_create_at_rung(&run.scene, &choice, FAST_BVH_RUNG_DEFAULT, run.err, sizeof run.err);
    if (w == NULL)
        return cli_fail(&run);
    /* What chapter 13 adds: soft shadows in the tracer, and the camera samples traced through the lens. */
    if (cli_render_sampled(&run, trace_soft, &w->world, &thin_lens_sampler))
        accel_report(w, &run.total, run.options.stats);
    accel_world_destroy(w);
    return cli_finish(&run);
}

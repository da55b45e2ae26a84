/* Chapter 12, anti-aliasing: several camera rays per pixel, averaged, so that edges are no longer
 * staircases and fine patterns no longer turn into false ones.
 *
 * The scene's antialias line says how (common/antialias.h): a regular n x n grid, jittered samples,
 * or POV-Ray's two adaptive rules, which spend more rays only where neighbouring colours differ. The
 * sampling is in common/supersample.c, its random numbers in common/sample_hash.c. Everything else
 * is chapter 11's: the fast BVH at its default rung, the same shading, the same threads. --heatmap shows
 * how many camera rays each pixel took. */
#include "accel_fast_bvh.h"
#include "box.h"
#include "cli.h"
#include "fast_bvh.h"
#include "plane.h"
#include "sphere.h"
#include "supersample.h"
#include "triangle.h"
#include "whitted.h"

static struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 12 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 12,
        .title = "antialias",
        .default_scene = "scenes/12-antialias.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule (BVH: median split;\n"
                        "                   kd-tree: the axis holding most objects)\n"
                        "  (the scene's antialias line says how many rays a pixel gets, e.g.\n"
                        "   --set antialias.method=grid --set antialias.samples=4)\n",
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
    /* What chapter 12 adds: the pixels sampled by the scene's antialias line. */
    if (cli_render_sampled(&run, whitted_trace, &w->world, &supersample_sampler))
        accel_report(w, &run.total, run.options.stats);
    accel_world_destroy(w);
    return cli_finish(&run);
}

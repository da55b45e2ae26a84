/* Chapter 12, anti-aliasing: several camera rays per pixel, averaged, so that edges are no longer
 * staircases and fine patterns no longer turn into false ones.
 *
 * The scene's antialias line says how (common/antialias.h): a regular n x n grid, jittered samples,
 * or POV-Ray's two adaptive rules, which spend more rays only where neighbouring colours differ. The
 * sampling is in common/supersample.c, its random numbers in common/sample_hash.c. Everything else
 * is chapter 11's: the fast BVH at its top rung, the same shading, the same threads. --heatmap shows
 * how many camera rays each pixel took. */
#include "accel_fast_bvh.h"
#include "cli.h"
#include "fast_bvh.h"
#include "supersample.h"
#include "whitted.h"

static struct accel_choice choice = {ACCEL_BVH, true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

/* accel_world_use_fast_bvh at chapter 11's top rung. */
static bool use_fast_bvh(struct accel_world *w, int split, char *err, size_t err_size) {
    return accel_world_use_fast_bvh(w, split, FAST_BVH_RUNG_TOP, err, err_size);
}

/* Builds the world with the chosen structure over every triangle of the scene. */
static void *prepare(struct scene *s, char *err, size_t err_size) {
    return accel_world_create(s, &choice, use_fast_bvh, err, err_size);
}

int main(int argc, char **argv) {
    static const struct chapter chapter = {
        .number = 12,
        .title = "antialias",
        .default_scene = "scenes/12-antialias.scene",
        .features = SCENE_EVERY_SHAPE,
        .lighting = POV_WHITTED,
        .load_meshes = scene_load_meshes,
        .prepare = prepare,
        .release = accel_world_destroy,
        .trace = whitted_trace,
        .sampler = &supersample_sampler,
        .parse_option = parse_option,
        .options_help = "  --accel KIND     none, kdtree or bvh (default bvh: chapter 11's fast BVH)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule (BVH: median split;\n"
                        "                   kd-tree: the axis holding most objects)\n"
                        "  (the scene's antialias line says how many rays a pixel gets, e.g.\n"
                        "   --set antialias.method=grid --set antialias.samples=4)\n",
        .report = accel_chapter_report,
    };
    return cli_run(&chapter, argc, argv);
}

/* Chapter 10, the bounding volume hierarchy: instead of cutting space, group the triangles, box each
 * group, and split the groups again, so a ray skips every group whose box it misses.
 *
 * The hierarchy (median and SAH builds, ordered traversal) is in common/bvh.c and is plugged into the
 * world by common/accel_bvh.c. Shading is chapter 8's: the picture equals chapters 8 and 9's, only
 * faster. --accel none|kdtree|bvh compares all three on the same scene. */
#include "accel.h"
#include "box.h"
#include "bvh.h"
#include "cli.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"
#include "whitted.h"

static struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

/* Builds the world with the chosen structure over every triangle of the scene: chapter 9's, or the BVH. */
static struct accel_world *prepare(struct scene *s, char *err, size_t err_size) {
    struct accel_world *w = accel_world_create(s, &choice, err, err_size);
    if (w != NULL && choice.kind == ACCEL_BVH &&
        !accel_world_use_bvh(w, choice.sah ? BVH_SPLIT_SAH : BVH_SPLIT_MEDIAN, err, err_size)) {
        accel_world_destroy(w);
        return NULL;
    }
    return w;
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 10 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 10,
        .title = "bvh",
        .default_scene = "scenes/10-bvh.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --accel KIND     none, kdtree or bvh (default bvh)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule (BVH: median split;\n"
                        "                   kd-tree: the axis holding most objects)\n",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct accel_world *w = prepare(&run.scene, run.err, sizeof run.err);
    if (w == NULL)
        return cli_fail(&run);
    if (cli_render(&run, whitted_trace, &w->world))
        accel_report(w, &run.total, run.options.stats);
    accel_world_destroy(w);
    return cli_finish(&run);
}

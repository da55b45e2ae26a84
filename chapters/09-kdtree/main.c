/* Chapter 9, the kd-tree: space is cut in two, again and again, so a ray only visits the cells it
 * passes through, front to back, and stops at the first cell where it hits something.
 *
 * The tree (build rules, traversal) is in common/kdtree.c; common/accel.c gathers the scene's
 * triangles and routes the world's queries through the tree. The shading is chapter 8's, unchanged:
 * the picture must not change, only the work. Try --accel none to compare. */
#include "accel.h"
#include "box.h"
#include "cli.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"
#include "whitted.h"

static struct accel_choice choice = {.kind = ACCEL_KDTREE, .sah = true};

static int parse_option(const char *option, const char *value) {
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE, option, value);
}

/* Builds the world with the chosen structure over every triangle of the scene. */
static struct accel_world *prepare(struct scene *s, char *err, size_t err_size) {
    return accel_world_create(s, &choice, err, err_size);
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 9 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 9,
        .title = "kdtree",
        .default_scene = "scenes/09-kdtree.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --accel KIND     none or kdtree (default kdtree)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule, the axis holding most objects\n",
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

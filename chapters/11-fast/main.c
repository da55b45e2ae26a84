/* Chapter 11, going fast: chapter 10's hierarchy, the same tree and the same answers, laid out and
 * walked for speed, one optimisation (a rung) at a time.
 *
 * The fast hierarchy is in common/fast_bvh.c and is plugged into the world by common/accel_fast_bvh.c.
 * --rung N (1 to 9) or its name picks how far up the ladder to go: 1 is chapter 10's plain BVH, 6 the
 * default, 7 the smallest, 8 eight boxes at a time where the processor has AVX2, 9 the same tree walked
 * with less work per ray. The picture is
 * chapter 10's on every rung; only the time and the memory change. */
#include <stdio.h>
#include <string.h>

#include "accel_fast_bvh.h"
#include "box.h"
#include "cli.h"
#include "fast_bvh.h"
#include "plane.h"
#include "sphere.h"
#include "triangle.h"
#include "whitted.h"

static struct accel_choice choice = {ACCEL_BVH, true};
static int rung = FAST_BVH_RUNG_DEFAULT;

static int parse_option(const char *option, const char *value) {
    if (strcmp(option, "--rung") == 0) {
        rung = value != NULL ? fast_bvh_rung_from_name(value) : 0;
        if (rung != 0)
            return 2;
        fprintf(stderr, "--rung needs 1 to 9 or one of: plain wide simd prefetch build float compact eight lean; got '%s'\n",
                value != NULL ? value : "");
        return -1;
    }
    return accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
}

/* Rung 7: frees the scene's meshes once w has gathered their triangles, so that the program does not
 * hold them twice. Afterwards the world reads only the gathered copy, except where a transparent
 * mesh's inside is asked for (interior.c) and where the POV-Ray twin writes the meshes out (--pov):
 * those meshes, or then all of them, are kept. */
static void free_gathered_meshes(struct scene *s, bool writing_twin) {
    for (size_t k = 0; k < s->mesh_count && !writing_twin; k++) {
        const struct material *m = &s->materials[s->meshes[k].material];
        if (!(m->filter > 0.0 || m->transmit > 0.0)) /* opaque, as interior.c tells */
            mesh_free(&s->meshes[k].mesh);
    }
}

/* Builds the world with the chosen structure over every triangle of the scene: chapter 9's, or the BVH
 * at the chosen rung. */
static struct accel_world *prepare(struct scene *s, bool writing_twin, char *err, size_t err_size) {
    struct accel_world *w = accel_world_create(s, &choice, err, err_size);
    if (w != NULL && choice.kind == ACCEL_BVH && rung == FAST_BVH_RUNG_COMPACT)
        free_gathered_meshes(s, writing_twin);
    if (w != NULL && choice.kind == ACCEL_BVH &&
        !accel_world_use_fast_bvh(w, choice.sah ? BVH_SPLIT_SAH : BVH_SPLIT_MEDIAN, rung, err, err_size)) {
        accel_world_destroy(w);
        return NULL;
    }
    return w;
}

int main(int argc, char **argv) {
    /* The kinds of shape chapter 11 draws: every kind so far (chapter 5's). */
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    static const struct chapter chapter = {
        .number = 11,
        .title = "fast",
        .default_scene = "scenes/11-fast.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
        .parse_option = parse_option,
        .options_help = "  --rung R         how much of the speed-up to use: 1 plain (chapter 10's BVH),\n"
                        "                   2 wide, 3 simd, 4 prefetch, 5 build, 6 float (the default),\n"
                        "                   7 compact (the least memory), 8 eight (eight boxes at a\n"
                        "                   time with AVX2; rung 6 without it), 9 lean (rung 8's tree,\n"
                        "                   less work per ray); a number or a name\n"
                        "  --accel KIND     none, kdtree or bvh (default bvh: the fast BVH at the chosen rung)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule (BVH: median split;\n"
                        "                   kd-tree: the axis holding most objects)\n",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    render_use_threads(run.options.threads); /* the build's too; the tree is the same for any number */
    struct accel_world *w = prepare(&run.scene, run.options.pov != NULL, run.err, sizeof run.err);
    if (w == NULL)
        return cli_fail(&run);
    if (cli_render(&run, whitted_trace, &w->world))
        accel_report(w, &run.total, run.options.stats);
    accel_world_destroy(w);
    return cli_finish(&run);
}

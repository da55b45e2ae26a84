/* Chapter 11, going fast: chapter 10's hierarchy, the same tree and the same answers, laid out and
 * walked for speed, one optimisation (a rung) at a time.
 *
 * The fast hierarchy is in common/fast_bvh.c and is plugged into the world by common/accel_fast_bvh.c.
 * --rung N (1 to 11) or its name picks how far up the ladder to go: 1 is chapter 10's plain BVH, 6
 * float boxes, 7 the smallest and the default, 8 eight boxes at a time where the processor has AVX2, 9
 * the same tree walked with less work per ray, 10 rung 9 with the camera rays traced in packets of eight (render_in_packets,
 * below), 11 rung 9 with its triangles tested in float first, and in double only where the float test
 * cannot rule a hit out. The picture is chapter 10's on every rung; only the time and the memory change. */
#include <stdio.h>
#include <string.h>

#include "accel_fast_bvh.h"
#include "box.h"
#include "cli.h"
#include "fast_bvh.h"
#include "fast_bvh_packet.h"
#include "plane.h"
#include "render.h"
#include "sphere.h"
#include "triangle.h"
#include "whitted.h"

static struct accel_choice choice = {.kind = ACCEL_BVH, .sah = true};
static int rung = FAST_BVH_RUNG_DEFAULT;

static bool rung_given; /* --rung was on the command line: only the BVH has rungs */

/* The message for --rung given with an --accel other than bvh; returns parse_option's -1. */
static int rung_without_bvh(void) {
    fprintf(stderr, "--rung picks a step of the BVH's ladder, and --accel %s builds no BVH: give one or the other\n",
            choice.kind == ACCEL_NONE ? "none" : "kdtree");
    return -1;
}

static int parse_option(const char *option, const char *value) {
    if (strcmp(option, "--rung") == 0) {
        rung = value != NULL ? fast_bvh_rung_from_name(value) : 0;
        rung_given = true;
        if (rung != 0)
            return choice.kind == ACCEL_BVH ? 2 : rung_without_bvh();
        fprintf(stderr, "--rung needs 1 to 11 or one of: plain wide simd prefetch build float compact eight lean "
                        "packet exact-float; got '%s'\n",
                value != NULL ? value : "");
        return -1;
    }
    int used = accel_parse_option(&choice, 1u << ACCEL_NONE | 1u << ACCEL_KDTREE | 1u << ACCEL_BVH, option, value);
    return used == 2 && rung_given && choice.kind != ACCEL_BVH ? rung_without_bvh() : used;
}

/* Rung 7: frees the scene's meshes once w has gathered their triangles, so that the program does not
 * hold them twice. Afterwards the world reads only the gathered copy, except where a transparent
 * mesh's inside is asked for (interior.c) and where the POV-Ray twin writes the meshes out (--pov):
 * those meshes, or then all of them, are kept. A scene's only mesh is not copied (w borrows it): it is
 * held once already. */
static void free_gathered_meshes(struct scene *s, const struct accel_world *w, bool writing_twin) {
    for (size_t k = 0; k < s->mesh_count && !writing_twin && !w->triangles_borrowed; k++) {
        if (!material_passes_light(&s->materials[s->meshes[k].material])) /* opaque: interior.c never asks */
            mesh_free(&s->meshes[k].mesh);
    }
}

/* Builds the world with the chosen structure over every triangle of the scene: chapter 9's, or the BVH
 * at the chosen rung. */
static struct accel_world *prepare(struct scene *s, bool writing_twin, char *err, size_t err_size) {
    struct accel_world *w = accel_world_create(s, &choice, err, err_size);
    if (w != NULL && choice.kind == ACCEL_BVH && rung == FAST_BVH_RUNG_COMPACT)
        free_gathered_meshes(s, w, writing_twin);
    if (w != NULL && choice.kind == ACCEL_BVH &&
        !accel_world_use_fast_bvh(w, choice.sah ? BVH_SPLIT_SAH : BVH_SPLIT_MEDIAN, rung, err, err_size)) {
        accel_world_destroy(w);
        return NULL;
    }
    return w;
}

/* ---- rung 10: camera rays in packets ---------------------------------------------------------- */

/* The answer of a packet's walk for one of its camera rays, and the hierarchy's own queries. */
struct packet_answer {
    const struct world_accel *tree;
    ray camera_ray;
    double t_min;
    bool found;
    double t;
    uint32_t face;
};

/* The world's nearest-triangle query (struct world_accel's closest) over a packet_answer: for its camera
 * ray, from the very origin, direction and t_min the packet was walked with, the packet's answer cut at
 * t_max (the nearest face over (t_min, infinity) is the nearest over (t_min, t_max) when it is before
 * t_max, and else there is none); for every other ray, the hierarchy's own query. */
static bool packet_closest(const void *answer, const ray *r, double t_min, double t_max, double *t, uint32_t *face) {
    const struct packet_answer *a = answer;
    if (memcmp(r, &a->camera_ray, sizeof *r) != 0 || t_min != a->t_min)
        return a->tree->closest(a->tree->structure, r, t_min, t_max, t, face);
    if (!a->found || !(a->t < t_max))
        return false;
    *t = a->t;
    *face = a->face;
    return true;
}

/* The other two queries, the hierarchy's own. */
static bool packet_occluded(const void *answer, const ray *r, double t_min, double t_max) {
    const struct world_accel *tree = ((const struct packet_answer *)answer)->tree;
    return tree->occluded(tree->structure, r, t_min, t_max);
}

static void packet_for_each_hit(const void *answer, const ray *r, double t_min, double t_max,
                                world_hit_visitor visit, void *context) {
    const struct world_accel *tree = ((const struct packet_answer *)answer)->tree;
    tree->for_each_hit(tree->structure, r, t_min, t_max, visit, context);
}

/* Renders pixels [left, right) x [top, bottom) (a render_block_fn) with their camera rays walked through
 * the hierarchy in packets: one walk finds each ray's nearest triangle, and then each pixel is traced as
 * on every other rung, by job->trace, whose first query for the camera ray finds that answer waiting.
 * The spheres, boxes and planes are still tested ray by ray, and the nearest of all wins as before. */
static void render_in_packets(const struct render_job *job, struct image *img, int left, int top, int right,
                              int bottom) {
    const struct world *seen = job->world;
    struct packet_answer answer = {.tree = seen->accel};
    struct world_accel packets = {&answer, seen->accel->triangles, seen->accel->materials, packet_closest,
                                  packet_occluded, packet_for_each_hit};
    struct world world = *seen;
    world.accel = &packets;
    for (int y = top; y < bottom; y += FAST_BVH_PACKET_ROWS) {
        for (int x = left; x < right; x += FAST_BVH_PACKET_COLUMNS) {
            ray rays[FAST_BVH_PACKET_SIZE];
            double t_min[FAST_BVH_PACKET_SIZE], t_max[FAST_BVH_PACKET_SIZE], t[FAST_BVH_PACKET_SIZE];
            uint32_t face[FAST_BVH_PACKET_SIZE];
            unsigned active = fast_bvh_camera_packet(job->camera, x, y, right, bottom, rays, t_min, t_max);
            uint64_t cost_before = render_thread_cost();
            unsigned found = fast_bvh_closest_packet(seen->accel->structure, rays, active, t_min, t_max, t, face);
            uint64_t packet_cost = (render_thread_cost() - cost_before) / (uint64_t)__builtin_popcount(active);
            for (unsigned rest = active; rest != 0; rest &= rest - 1) {
                int k = __builtin_ctz(rest);
                int i = x + k % FAST_BVH_PACKET_COLUMNS, j = y + k / FAST_BVH_PACKET_COLUMNS;
                answer = (struct packet_answer){seen->accel, rays[k], t_min[k], found >> k & 1, t[k], face[k]};
                cost_before = render_thread_cost();
                stats_thread.primary_rays++;
                vec3 colour = job->trace(&world, &rays[k]);
                stats_thread.non_finite_pixels += !vec3_is_finite(colour); /* cli.c writes no such picture */
                image_set(img, i, j, colour);
                if (job->heatmap != NULL) { /* the packet's walk shared out among its rays */
                    uint64_t cost = render_thread_cost() - cost_before + packet_cost;
                    image_set(job->heatmap, i, j, heatmap_colour(cost > UINT32_MAX ? UINT32_MAX : (uint32_t)cost));
                }
            }
        }
    }
    stats_thread.pixels += (uint64_t)(right - left) * (uint64_t)(bottom - top);
    stats_thread.camera_rays_max = 1;
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
                        "                   2 wide, 3 simd, 4 prefetch, 5 build, 6 float, 7 compact\n"
                        "                   (the default: the least memory), 8 eight (eight boxes at a\n"
                        "                   time with AVX2; rung 6 without it), 9 lean (rung 8 with\n"
                        "                   fuller leaves, less work per ray), 10 packet (rung 9 with\n"
                        "                   the camera rays traced eight at a time), 11 exact-float\n"
                        "                   (rung 9, its triangles tested in float first, in double\n"
                        "                   only where the float test cannot tell); a number or a name\n"
                        "  --accel KIND     none, kdtree or bvh (default bvh: the fast BVH at the chosen rung)\n"
                        "  --split RULE     sah (default) or seed: the seed's rule (BVH: median split;\n"
                        "                   kd-tree: the axis holding most objects)\n",
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    cli_check_scale(&run); /* before rung 7 lets go of the meshes it has gathered */
    struct accel_world *w = prepare(&run.scene, run.options.pov != NULL, run.err, sizeof run.err);
    if (w == NULL)
        return cli_fail(&run);
    static const struct render_sampler in_packets = {render_in_packets, &heatmap_cost_scale, NULL};
    bool packets = choice.kind == ACCEL_BVH && rung == FAST_BVH_RUNG_PACKET;
    if (cli_render_sampled(&run, whitted_trace, &w->world, packets ? &in_packets : NULL))
        accel_report(w, &run.total, run.options.stats);
    accel_world_destroy(w);
    return cli_finish(&run);
}

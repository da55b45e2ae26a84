/* check_main.c: the coursework's grader (make check-N, make check): the task table, the list of
 * checks, and the scoreboard (the coursework kit; docs/coursework.md explains it). Every check runs in a
 * process of its own with a time limit (check_process.c), once per run however many tasks need it, so
 * a crash or an endless loop in one fails that check and the scoreboard still prints.
 *
 *   check N          chapter N's tasks and its picture, then a scoreboard; exit 0 when all pass
 *   check all        every chapter
 *   check --task ID  one task's checks only (for the tests that prove the kit)
 *   check --needs ID the tasks ID needs, directly or through others (for the same tests)
 *   check --list     every task, pictures included, one a line (for the same tests)
 *
 * A task's checks run only when the tasks it needs pass theirs; otherwise each of its checks reports
 * "needs task X" and counts as not passed, so a later chapter never fails for an earlier mistake. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scene.h"
#include "world.h"

/* Which tasks exist: what the student writes, where, and what it needs. A picture check N.P needs
 * exactly the tasks chapter N's program runs on its own scene (tests/test_coursework.c proves it, by
 * recording which marked functions each program calls). */
const struct task check_tasks[] = {
    {"1.1", "the primary ray through a pixel centre", "camera_ray in common/camera.c", ""},
    {"1.P", "chapter 1's picture", "chapters/01-camera", "1.1"},
    {"2.1", "ray-sphere intersection, the nearest root", "sphere_intersect in common/sphere.c", ""},
    {"2.2", "the sphere's outward normal", "sphere_normal in common/sphere.c", ""},
    {"2.P", "chapter 2's picture", "chapters/02-sphere", "1.1 2.1 2.2"},
    {"3.1", "Moller-Trumbore ray-triangle intersection", "triangle_crossing_mt in common/triangle.c", ""},
    {"3.P", "chapter 3's picture", "chapters/03-triangle", "1.1 2.1 2.2"},
    {"4.1", "ray-plane intersection", "plane_intersect in common/plane.c", ""},
    {"4.P", "chapter 4's picture", "chapters/04-plane", "1.1 2.1 2.2 4.1"},
    {"5.1", "the slab test, one axis", "clip_to_slab in common/aabb.h", ""},
    {"5.2", "the box as a shape: entry or exit", "box_intersect in common/box.c", "5.1"},
    {"5.P", "chapter 5's picture", "chapters/05-aabb", "1.1 4.1 5.1 5.2"},
    {"6.1", "the mirror direction", "phong_reflect in common/phong.c", ""},
    {"6.2", "ambient, diffuse and Phong highlight", "phong_shade in common/phong.c", "6.1"},
    {"6.P", "chapter 6's picture", "chapters/06-phong", "1.1 2.1 2.2 4.1 5.1 5.2 6.1 6.2"},
    {"7.1", "the shadow ray: is the light blocked?", "shadow_opaque in common/shadow.c", "2.1"},
    {"7.P", "chapter 7's picture", "chapters/07-shadows", "1.1 2.1 2.2 4.1 5.1 5.2 6.1 6.2 7.1"},
    {"8.1", "Snell's refraction and total internal reflection", "whitted_refract in common/whitted.c", ""},
    {"8.2", "the recursion: reflected and refracted rays, bounded depth", "trace in common/whitted.c",
     "4.1 6.1 6.2"},
    {"8.P", "chapter 8's picture", "chapters/08-recursion", "1.1 2.1 2.2 4.1 5.1 6.1 6.2 7.1 8.1 8.2"},
    {"9.1", "the dissertation's split rule", "seed_plane in common/kdtree.c", ""},
    {"9.2", "the surface area heuristic", "sah_plane in common/kdtree.c", ""},
    {"9.3", "front-to-back traversal", "traverse in common/kdtree.c", ""},
    {"9.P", "chapter 9's picture", "chapters/09-kdtree", "1.1 2.1 2.2 4.1 5.1 6.1 6.2 7.1 8.1 8.2 9.2 9.3"},
    {"10.1", "BVH build: the median split", "split_median in common/bvh.c", ""},
    {"10.2", "BVH build: the binned SAH", "split_sah in common/bvh.c", ""},
    {"10.3", "ordered BVH traversal", "traverse in common/bvh.c", "5.1 10.2"},
    {"10.P", "chapter 10's picture", "chapters/10-bvh", "1.1 2.1 2.2 4.1 5.1 6.1 6.2 7.1 8.1 8.2 10.2 10.3"},
    {"11.1", "two children's slab tests at once", "child_pair_hit in common/fast_bvh.c", "5.1"},
    {"11.2", "the children hit, nearest first", "nearest_first in common/fast_bvh.c", "5.1 10.2 11.1"},
    {"11.P", "chapter 11's picture", "chapters/11-fast", "1.1 2.1 2.2 4.1 5.1 6.1 6.2 7.1 8.1 8.2 10.2 11.1 11.2"},
    {"12.1", "the box filter over a regular grid", "supersample_grid in common/supersample.c", ""},
    {"12.2", "POV-Ray's colour difference test", "supersample_differ in common/supersample.c", ""},
    {"12.P", "chapter 12's picture", "chapters/12-antialias",
     "1.1 2.1 2.2 4.1 5.1 5.2 6.1 6.2 7.1 8.2 10.2 11.1 11.2 12.1 12.2"},
    {"13.1", "POV-Ray's area light: corners, quarters and the adaptive rule", "rectangle in common/soft_shadow.c",
     "5.1 5.2 7.1"},
    {"13.2", "the thin lens: a ray from a point of the lens through the focal plane", "thin_lens_ray in common/thin_lens.c",
     ""},
    {"13.P", "chapter 13's picture", "chapters/13-distributed",
     "1.1 2.1 2.2 4.1 5.1 5.2 6.1 6.2 7.1 8.1 8.2 12.1 12.2 13.1"},
    {"14.1", "the checker pattern", "checker in common/texture.c", ""},
    {"14.2", "the interpolated normal", "mesh_surface_normal in common/mesh_surface.c", ""},
    {"14.P", "chapter 14's picture", "chapters/14-textures",
     "1.1 2.1 2.2 4.1 5.1 5.2 6.1 6.2 7.1 8.2 10.2 11.1 11.2 14.1 14.2"},
    {"15.1", "next-event estimation, and its weight against scattering", "path_direct_light in common/path_trace.c", "2.1"},
    {"15.2", "the path: emission, scattering, Russian roulette", "radiance in common/path_trace.c", "1.1 2.2 15.1"},
    {"15.P", "chapter 15's picture", "chapters/15-paths", "1.1 2.1 2.2 5.1 6.1 8.1 10.2 11.1 11.2 15.1 15.2"},
    {"16.1", "the ray carried into an instance, its hit carried back", "closest_in_instance in common/instances.c",
     "5.1 10.2 10.3 11.1 11.2"},
    {"16.2", "refitting the top level: the same tree, its boxes from the leaves up", "instance_bvh_refit in "
     "common/instance_bvh.c", "5.1 10.2 10.3"},
    {"16.3", "the box of a moving object over a stretch of the shutter", "stretch_box in common/keyframes.c", ""},
    {"16.P", "chapter 16's picture", "chapters/16-instances",
     "1.1 2.2 4.1 5.1 6.1 6.2 7.1 8.2 10.2 10.3 11.1 11.2 12.1 16.1 16.3"},
    {"17.1", "the GGX distribution of microfacet normals", "microfacet_ggx_d in common/microfacet.c", ""},
    {"17.2", "the rough metal's BRDF: Fresnel, distribution and masking", "conductor_eval in common/microfacet.c",
     "17.1"},
    {"17.3", "the density of a reflected direction", "conductor_pdf in common/microfacet.c", "17.1"},
    {"17.P", "chapter 17's picture", "chapters/17-rough",
     "1.1 2.1 2.2 5.1 10.2 11.1 11.2 15.1 15.2 17.1 17.2 17.3"},
};
const size_t check_task_count = sizeof check_tasks / sizeof check_tasks[0];

CHECK(check_camera_top_left);
CHECK(check_camera_bottom_right);
CHECK(check_sphere_in_front);
CHECK(check_sphere_from_inside);
CHECK(check_sphere_misses);
CHECK(check_sphere_open_window);
CHECK(check_sphere_counted);
CHECK(check_sphere_normal);
CHECK(check_triangle_hit);
CHECK(check_triangle_misses);
CHECK(check_plane_hit);
CHECK(check_plane_misses);
CHECK(check_plane_counted);
CHECK(check_slab_hits);
CHECK(check_slab_misses);
CHECK(check_slab_face_planes);
CHECK(check_box_outside);
CHECK(check_box_inside);
CHECK(check_box_counted);
CHECK(check_reflect);
CHECK(check_phong_overhead);
CHECK(check_phong_slanted);
CHECK(check_phong_behind);
CHECK(check_shadow_blocked);
CHECK(check_shadow_clear);
CHECK(check_shadow_no_acne);
CHECK(check_shadow_end_margin);
CHECK(check_shadow_counted);
CHECK(check_refract_snell);
CHECK(check_refract_total_internal_reflection);
CHECK(check_recursion_mirror);
CHECK(check_recursion_depth);
CHECK(check_seed_row_x);
CHECK(check_seed_row_z);
CHECK(check_sah_gap);
CHECK(check_kd_traversal);
CHECK(check_kd_occluded);
CHECK(check_kd_crossing);
CHECK(check_bvh_median);
CHECK(check_bvh_sah);
CHECK(check_bvh_sah_unequal);
CHECK(check_bvh_traversal);
CHECK(check_bvh_crossing);
CHECK(check_bvh_near_first);
CHECK(check_bvh_slivers);
CHECK(check_bvh_counted);
CHECK(check_fast_layers);
CHECK(check_fast_crossing);
CHECK(check_fast_near_first);
CHECK(check_picture_1);
CHECK(check_picture_2);
CHECK(check_picture_3);
CHECK(check_picture_4);
CHECK(check_picture_5);
CHECK(check_picture_6);
CHECK(check_picture_7);
CHECK(check_picture_8);
CHECK(check_picture_9);
CHECK(check_picture_10);
CHECK(check_picture_11);
CHECK(check_grid_centres);
CHECK(check_grid_edge);
CHECK(check_differ_plain);
CHECK(check_differ_gamma);
CHECK(check_differ_channels);
CHECK(check_picture_12);
CHECK(check_area_open_sky);
CHECK(check_area_weights);
CHECK(check_area_adaptive);
CHECK(check_lens_focus);
CHECK(check_lens_spread);
CHECK(check_picture_13);
CHECK(check_checker_cubes);
CHECK(check_checker_boundary);
CHECK(check_normal_corners);
CHECK(check_normal_unit);
CHECK(check_picture_14);
CHECK(check_direct_overhead);
CHECK(check_direct_tilted);
CHECK(check_direct_blocked_or_behind);
CHECK(check_pixels_uncorrelated);
CHECK(check_furnace_scatter);
CHECK(check_furnace_light);
CHECK(check_furnace_mis);
CHECK(check_strategies_agree);
CHECK(check_picture_15);
CHECK(check_instance_distance);
CHECK(check_instance_normal);
CHECK(check_refit_holds_the_moved_boxes);
CHECK(check_refit_finds_every_instance);
CHECK(check_refit_keeps_the_tree);
CHECK(check_motion_box_translation);
CHECK(check_motion_box_turn);
CHECK(check_motion_box_keys_and_shutter);
CHECK(check_picture_16);
CHECK(check_ggx_d_values);
CHECK(check_ggx_d_projected_area);
CHECK(check_metal_mirror_pair);
CHECK(check_metal_fresnel_and_half_vector);
CHECK(check_metal_pdf_values);
CHECK(check_metal_pdf_integrates_to_one);
CHECK(check_picture_17);

const struct check check_list[] = {
    {"1.1", "the top-left pixel's ray", check_camera_top_left},
    {"1.1", "the bottom-right pixel's ray", check_camera_bottom_right},
    {"1.P", "the picture matches the reference", check_picture_1},
    {"2.1", "a sphere in front: the near root", check_sphere_in_front},
    {"2.1", "from inside: the far root", check_sphere_from_inside},
    {"2.1", "misses: beside, behind, beyond t_max", check_sphere_misses},
    {"2.1", "a root exactly at t_min or t_max is not a hit", check_sphere_open_window},
    {"2.1", "counts one sphere test per call", check_sphere_counted},
    {"2.2", "the unit outward normal", check_sphere_normal},
    {"2.P", "the picture matches the reference", check_picture_2},
    {"3.1", "a hit with its u and v", check_triangle_hit},
    {"3.1", "misses: outside an edge, parallel; behind: a negative t", check_triangle_misses},
    {"3.P", "the picture matches the reference", check_picture_3},
    {"4.1", "hits, straight and slanted", check_plane_hit},
    {"4.1", "misses: parallel, pointing away", check_plane_misses},
    {"4.1", "counts one plane test per call", check_plane_counted},
    {"4.P", "the picture matches the reference", check_picture_4},
    {"5.1", "entry points from every side", check_slab_hits},
    {"5.1", "misses", check_slab_misses},
    {"5.1", "rays in a face's plane (0 * infinity = NaN): inside the slab", check_slab_face_planes},
    {"5.2", "from outside: the entry", check_box_outside},
    {"5.2", "from inside: the exit", check_box_inside},
    {"5.2", "counts one box test per call", check_box_counted},
    {"5.P", "the picture matches the reference", check_picture_5},
    {"6.1", "45 degrees in, 45 degrees out", check_reflect},
    {"6.2", "a light straight above", check_phong_overhead},
    {"6.2", "a light at 45 degrees", check_phong_slanted},
    {"6.2", "a light behind the surface", check_phong_behind},
    {"6.P", "the picture matches the reference", check_picture_6},
    {"7.1", "a blocker in between", check_shadow_blocked},
    {"7.1", "no blocker: beside, beyond the light", check_shadow_clear},
    {"7.1", "no shadow acne", check_shadow_no_acne},
    {"7.1", "a blocker touching the light: the margin at the end", check_shadow_end_margin},
    {"7.1", "counts one shadow ray per call", check_shadow_counted},
    {"7.P", "the picture matches the reference", check_picture_7},
    {"8.1", "Snell's law into glass", check_refract_snell},
    {"8.1", "total internal reflection", check_refract_total_internal_reflection},
    {"8.2", "a mirror shows the sky", check_recursion_mirror},
    {"8.2", "two mirrors, max_depth", check_recursion_depth},
    {"8.P", "the picture matches the reference", check_picture_8},
    {"9.1", "a row along x", check_seed_row_x},
    {"9.1", "a row along z: the axis is chosen", check_seed_row_z},
    {"9.2", "two clusters: the gap is cut", check_sah_gap},
    {"9.3", "nearest hits in three layers", check_kd_traversal},
    {"9.3", "shadow queries", check_kd_occluded},
    {"9.3", "triangles in many cells: the nearest hit", check_kd_crossing},
    {"9.P", "the picture matches the reference", check_picture_9},
    {"10.1", "a row: leaves of at most two", check_bvh_median},
    {"10.2", "two clusters", check_bvh_sah},
    {"10.2", "unequal clusters: the gap first", check_bvh_sah_unequal},
    {"10.3", "nearest hits in three layers", check_bvh_traversal},
    {"10.3", "overlapping boxes: the nearest hit", check_bvh_crossing},
    {"10.3", "the nearer child first: few triangle tests", check_bvh_near_first},
    {"10.3", "needle-thin triangles (slivers), kept out of the tree", check_bvh_slivers},
    {"10.3", "counts node visits, box tests and triangle tests", check_bvh_counted},
    {"10.P", "the picture matches the reference", check_picture_10},
    {"11.1", "nearest hits in three layers, rays up and down", check_fast_layers},
    {"11.1", "overlapping boxes: the nearest hit, rays along x and z", check_fast_crossing},
    {"11.2", "the nearer children first: few triangle tests", check_fast_near_first},
    {"11.P", "the picture matches the reference", check_picture_11},
    {"12.1", "the mean of the cells' centres is the pixel's centre", check_grid_centres},
    {"12.1", "an edge 0.3 across the pixel: 0.3 grey", check_grid_edge},
    {"12.2", "far colours differ, equal ones do not", check_differ_plain},
    {"12.2", "POV-Ray's gamma: a dark step counts more", check_differ_gamma},
    {"12.2", "the channels add up, negative ones count as 0", check_differ_channels},
    {"12.P", "the picture matches the reference", check_picture_12},
    {"13.1", "open sky: every point traced, all the light", check_area_open_sky},
    {"13.1", "one column of 3 hidden: POV-Ray's weights give 3/4", check_area_weights},
    {"13.1", "adaptive 0: corners that agree, of light not of shares", check_area_adaptive},
    {"13.2", "lens rays start on the lens and meet on the focal plane", check_lens_focus},
    {"13.2", "the lens points spread around the eye; aperture 0 is a pinhole", check_lens_spread},
    {"13.P", "the picture matches the reference", check_picture_13},
    {"14.1", "unit cubes alternate, negative coordinates too", check_checker_cubes},
    {"14.1", "a point a hair below a boundary: the cube above", check_checker_boundary},
    {"14.2", "at the corners and along an edge", check_normal_corners},
    {"14.2", "in the middle: unit length again", check_normal_unit},
    {"14.P", "the picture matches the reference", check_picture_14},
    {"15.1", "a glowing ball straight above: 1/16 of its radiance", check_direct_overhead},
    {"15.1", "the surface tilted by 60 degrees: half of that", check_direct_tilted},
    {"15.1", "hidden by a triangle, or behind the surface: nothing", check_direct_blocked_or_behind},
    {"15.2", "neighbouring pixels' noise is uncorrelated", check_pixels_uncorrelated},
    {"15.2", "the white furnace by scattering alone: Le / (1 - rho)", check_furnace_scatter},
    {"15.2", "the white furnace by light sampling alone", check_furnace_light},
    {"15.2", "the white furnace by MIS: no light counted twice", check_furnace_mis},
    {"15.2", "light, scattering and MIS converge to one picture", check_strategies_agree},
    {"15.P", "the picture matches the reference", check_picture_15},
    {"16.1", "a ray along the stretch: t is the same in both spaces", check_instance_distance},
    {"16.1", "the normal of a stretched slope: the inverse transpose", check_instance_normal},
    {"16.2", "boxes moved, one far away: the refitted tree holds them all", check_refit_holds_the_moved_boxes},
    {"16.2", "a ray through each moved box reaches its instance", check_refit_finds_every_instance},
    {"16.2", "all moved together: the same tree, each box moved with them", check_refit_keeps_the_tree},
    {"16.3", "a box sliding and growing: every position held, none far beyond", check_motion_box_translation},
    {"16.3", "an arm turning 90 degrees: its middle position held too", check_motion_box_turn},
    {"16.3", "three keys, a shutter across the middle one, a shutter of no length", check_motion_box_keys_and_shutter},
    {"16.P", "the picture matches the reference", check_picture_16},
    {"17.1", "D at the peak, at 30, 45 and 80 degrees; nothing below", check_ggx_d_values},
    {"17.1", "the microfacets' projected area is the surface's: D cos integrates to 1", check_ggx_d_projected_area},
    {"17.2", "eye and light along the normal, and mirrored at 60 degrees: masked", check_metal_mirror_pair},
    {"17.2", "the eye at 60 degrees, the light overhead: Fresnel at the half vector", check_metal_fresnel_and_half_vector},
    {"17.3", "the density at the mirror direction and off it, worked by hand", check_metal_pdf_values},
    {"17.3", "the density integrates to just under 1 over the hemisphere", check_metal_pdf_integrates_to_one},
    {"17.P", "the picture matches the reference", check_picture_17},
};
const size_t check_count = sizeof check_list / sizeof check_list[0];

bool check_near(double a, double b, double tolerance) { return fabs(a - b) <= tolerance; }

bool check_vec_near(vec3 a, vec3 b, double tolerance) {
    return check_near(a.x, b.x, tolerance) && check_near(a.y, b.y, tolerance) && check_near(a.z, b.z, tolerance);
}

const char *check_vec_text(vec3 v, char buffer[static 64]) {
    snprintf(buffer, 64, "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
    return buffer;
}

bool check_counted_once(uint64_t added, const char *function, const char *what, const char *shown, char *why,
                        size_t why_size) {
    if (added == 1)
        return true;
    snprintf(why, why_size, "%s: its contract says it counts %s per call (in stats_thread; the chapter's program "
             "prints the total as `%s`); one call of yours added %llu%s", function, what, shown,
             (unsigned long long)added, added == 0 ? ": the line that counts it is missing"
             : ": counted more than once? A function it calls may count one already (aabb_hit counts a box test, "
               "aabb_clip does not)");
    return false;
}

const char *check_ray_text(const ray *r, char buffer[static 160]) {
    char o[64], d[64];
    snprintf(buffer, 160, "a ray from %s along %s", check_vec_text(r->origin, o), check_vec_text(r->direction, d));
    return buffer;
}

bool check_scene_world(const char *text, const struct shape_kind *const *kinds, struct scene *s, struct world *w,
                       char *why, size_t why_size) {
    char err[512];
    if (!scene_parse("check.scene", text, kinds, s, err, sizeof err)) {
        snprintf(why, why_size, "the check's own scene did not parse (a framework problem, not your task): %s", err);
        return false;
    }
    if (!world_init(w, s, err, sizeof err)) {
        snprintf(why, why_size, "world_init failed: %s", err);
        scene_free(s);
        return false;
    }
    return true;
}

static int chapter_of(const char *id) { return atoi(id); }

static const struct task *find_task(const char *id) {
    for (size_t k = 0; k < check_task_count; k++)
        if (strcmp(check_tasks[k].id, id) == 0)
            return &check_tasks[k];
    return NULL;
}

/* Each check runs once per run of the grader, however many tasks need it: its verdict is kept here. */
#define CHECK_MAX 128
static struct check_verdict verdicts[CHECK_MAX];
static bool verdict_known[CHECK_MAX];

/* The time limit of a unit check: CHECK_SECONDS, or WHITTED_CHECK_SECONDS from the environment. */
static int unit_check_seconds(void) {
    const char *set = getenv("WHITTED_CHECK_SECONDS");
    return set != NULL && atoi(set) > 0 ? atoi(set) : CHECK_SECONDS;
}

/* The verdict of check_list[k], run now if it has not run yet (in its own process, with its limit). */
static const struct check_verdict *verdict_of(size_t k) {
    if (!verdict_known[k]) {
        bool picture = strstr(check_list[k].task, ".P") != NULL;
        check_run_isolated(&check_list[k], picture ? CHECK_PICTURE_SECONDS : unit_check_seconds(), &verdicts[k]);
        verdict_known[k] = true;
    }
    return &verdicts[k];
}

/* Runs every check of task t; prints each outcome unless quiet. Returns how many passed (of *total).
 * When a task it needs fails, runs none and names that task in missing ("" otherwise). */
static int run_task(const struct task *t, bool quiet, int *total, char missing[static 16]) {
    missing[0] = '\0';
    char id[16];
    int used;
    for (const char *p = t->needs; sscanf(p, "%15s%n", id, &used) == 1; p += used) {
        const struct task *need = find_task(id);
        int need_total;
        char need_missing[16];
        if (need != NULL && run_task(need, true, &need_total, need_missing) < need_total) {
            snprintf(missing, 16, "%s", need->id);
            break;
        }
    }
    int passed = 0;
    *total = 0;
    for (size_t k = 0; k < check_count; k++) {
        if (strcmp(check_list[k].task, t->id) != 0)
            continue;
        (*total)++;
        const struct check_verdict *v = missing[0] == '\0' ? verdict_of(k) : NULL;
        bool ok = v != NULL && v->passed;
        passed += ok;
        if (quiet)
            continue;
        if (ok)
            printf("  ok    %s: %s\n", t->id, check_list[k].name);
        else if (v == NULL)
            printf("  --    %s: %s: needs task %s (%s) first: make check-%d\n", t->id, check_list[k].name, missing,
                   find_task(missing)->title, chapter_of(missing));
        else
            printf("  FAIL  %s: %s\n        %s\n", t->id, check_list[k].name, v->why);
    }
    return passed;
}

/* Prints the tasks t needs, directly or not, each once (printed[] remembers them). */
static void print_needs(const struct task *t, bool printed[]) {
    char id[16];
    int used;
    for (const char *p = t->needs; sscanf(p, "%15s%n", id, &used) == 1; p += used) {
        const struct task *need = find_task(id);
        if (need == NULL || printed[need - check_tasks])
            continue;
        printed[need - check_tasks] = true;
        printf("%s\n", need->id);
        print_needs(need, printed);
    }
}

/* Whether chapter n has tasks in the table (chapters without coursework have none). */
static bool has_tasks(int n) {
    for (size_t k = 0; k < check_task_count; k++)
        if (n >= 1 && atoi(check_tasks[k].id) == n)
            return true;
    return false;
}

int main(int argc, char **argv) {
    if (argc == 3 && strcmp(argv[1], "--needs") == 0 && find_task(argv[2]) != NULL) {
        bool printed[64] = {false};
        print_needs(find_task(argv[2]), printed);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "--list") == 0) {
        for (size_t k = 0; k < check_task_count; k++)
            printf("%s\n", check_tasks[k].id);
        return 0;
    }
    const char *only = NULL;
    int chapter = 0;
    if (argc == 3 && strcmp(argv[1], "--task") == 0 && find_task(argv[2]) != NULL)
        only = argv[2];
    else if (argc == 2 && strcmp(argv[1], "all") == 0)
        chapter = -1;
    else if (argc == 2 && has_tasks(atoi(argv[1])))
        chapter = atoi(argv[1]);
    else {
        fprintf(stderr, "usage: %s N | all | --task N.K | --needs N.K | --list   (N = 1..16; make check-N runs it)\n", argv[0]);
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (check_count > CHECK_MAX) {
        fprintf(stderr, "%s: %zu checks, room for %d (CHECK_MAX in check_main.c)\n", argv[0], check_count, CHECK_MAX);
        return 2;
    }
    struct row {
        const char *id, *title, *function;
        char missing[16];
        int passed, total;
    } rows[64];
    size_t count = 0;
    for (size_t k = 0; k < check_task_count; k++) {
        const struct task *t = &check_tasks[k];
        if (only ? strcmp(t->id, only) != 0 : chapter > 0 && chapter_of(t->id) != chapter)
            continue;
        struct row *r = &rows[count++];
        r->id = t->id;
        r->title = t->title;
        r->function = t->function;
        r->passed = run_task(t, false, &r->total, r->missing);
    }
    int done = 0;
    printf("\nscoreboard\n");
    for (size_t k = 0; k < count; k++) {
        bool passed = rows[k].passed == rows[k].total;
        done += passed;
        printf("  %-5s %-4s %d/%d checks  %s (%s)%s%s\n", rows[k].id, passed ? "done" : "todo", rows[k].passed,
               rows[k].total, rows[k].title, rows[k].function, rows[k].missing[0] ? ": needs task " : "",
               rows[k].missing);
    }
    printf("%d of %zu tasks done\n", done, count);
    return done == (int)count ? 0 : 1;
}

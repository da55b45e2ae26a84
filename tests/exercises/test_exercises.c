/* test_exercises.c: the checks of the walkthroughs' build exercises, run on the student's own code.
 *
 * Each test is skipped, with a note saying where to start, until the function its exercise asks for
 * exists (see exercises.h: the functions are weak, so a missing one is NULL). Then it grades it. */
#include <criterion/criterion.h>

#include "exercises.h"

#define EXERCISE(chapter, name, function, check, where)                                                    \
    Test(exercise_##chapter, name) {                                                                      \
        if (function == NULL)                                                                             \
            cr_skip_test("exercise " #chapter ".4 not started: write " #function " in " where               \
                         " (docs, chapter " #chapter ", Exercises)");                                     \
        char why[1024];                                                                                   \
        cr_assert(check(function, why, sizeof why), "exercise " #chapter ".4, " #function ": %s", why);    \
    }

/* Exercise 2.4 is a kind of shape, so its test looks for the kind's table, not for a function. */
Test(exercise_2, the_disc_is_a_kind_of_shape) {
    if (&disc_kind == NULL)
        cr_skip_test("exercise 2.4 not started: write common/disc.h and common/disc.c with the table disc_kind, "
                     "and add disc to MODULES_02 in the Makefile (docs, chapter 2, Exercises)");
    char why[1024];
    cr_assert(check_disc(&disc_kind, why, sizeof why), "exercise 2.4, the disc: %s", why);
}

EXERCISE(3, smooth_normals_average_the_faces_by_area, mesh_vertex_normals, check_vertex_normals,
         "common/mesh_normals.c")
EXERCISE(4, a_ray_meets_an_open_cylinder, cylinder_intersect, check_cylinder, "common/cylinder.c")
EXERCISE(5, the_bounding_sphere_holds_every_vertex, mesh_bounding_sphere, check_bounding_sphere,
         "common/bounding_sphere.c")
EXERCISE(6, blinns_highlight_uses_the_half_vector, phong_blinn_highlight, check_blinn, "common/phong.c")
EXERCISE(7, an_area_light_casts_a_penumbra, shadow_area_fraction, check_area_fraction, "common/shadow.c")
EXERCISE(8, schlick_reflects_more_at_grazing_angles, whitted_schlick, check_schlick, "common/whitted.c")
EXERCISE(9, the_grid_walk_lists_the_cells_in_order, grid_walk, check_grid_walk, "common/grid.c")
EXERCISE(10, the_split_cost_follows_the_sah, bvh_split_cost, check_split_cost, "common/bvh.c")
EXERCISE(11, four_children_per_node_widest_opened_first, bvh4_collapse, check_collapse, "common/fast_bvh.c")
EXERCISE(12, n_rooks_one_sample_in_each_row_and_column, supersample_rooks, check_rooks, "common/supersample.c")
EXERCISE(13, the_concentric_map_keeps_areas, thin_lens_concentric, check_concentric, "common/thin_lens.c")

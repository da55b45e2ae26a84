/* test_exercise_proof.c: every build exercise's check passes the model answer and fails a plausible
 * wrong one (solutions.c), so a student's green check means something. */
#include <criterion/criterion.h>

#include "solutions.h"

#define PROOF(name, check, right, wrong)                                                                  \
    Test(exercise_checks, name) {                                                                         \
        char why[1024] = "";                                                                              \
        cr_assert(check(right, why, sizeof why), "the model answer fails: %s", why);                      \
        cr_assert(!check(wrong, why, sizeof why), "the wrong answer passes");                             \
        cr_log_info("the wrong answer is told: %s", why);                                                  \
    }

PROOF(disc, check_disc, &solution_disc_kind, &wrong_disc_kind)
PROOF(vertex_normals, check_vertex_normals, solution_mesh_vertex_normals, wrong_mesh_vertex_normals)
PROOF(cylinder, check_cylinder, solution_cylinder_intersect, wrong_cylinder_intersect)
PROOF(bounding_sphere, check_bounding_sphere, solution_mesh_bounding_sphere, wrong_mesh_bounding_sphere)
PROOF(blinn, check_blinn, solution_phong_blinn_highlight, wrong_phong_blinn_highlight)
PROOF(area_fraction, check_area_fraction, solution_shadow_area_fraction, wrong_shadow_area_fraction)
PROOF(schlick, check_schlick, solution_whitted_schlick, wrong_whitted_schlick)
PROOF(grid_walk, check_grid_walk, solution_grid_walk, wrong_grid_walk)
PROOF(split_cost, check_split_cost, solution_bvh_split_cost, wrong_bvh_split_cost)
PROOF(collapse, check_collapse, solution_bvh4_collapse, wrong_bvh4_collapse)
PROOF(rooks, check_rooks, solution_supersample_rooks, wrong_supersample_rooks)

/* test_exercise_proof.c: every build exercise's check passes the model answer and fails a plausible
 * wrong one (solutions.c), so a student's green check means something; and the model disc, added to
 * chapter 8's list of kinds and nowhere else, is read, drawn and written for POV-Ray, as chapter 2's
 * walkthrough promises. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image_test_support.h"
#include "test_support.h"
#include "box.h"
#include "cli.h"
#include "image.h"
#include "plane.h"
#include "solutions.h"
#include "sphere.h"
#include "triangle.h"
#include "whitted.h"
#include "world.h"

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

/* ---- a new kind of shape is one more line in a chapter's list (docs/02-sphere.md) ---------------- */

/* A floor, a red disc tilted towards the camera, a mirror disc beside it, and a light that makes the
 * discs cast shadows on the floor. */
static const char disc_scene[] = "camera eye 0 3 6 target 0 0.6 0 fov 40\n"
                                 "image 80 60\n"
                                 "light position 2 6 4\n"
                                 "material floor colour 0.8 0.8 0.8\n"
                                 "material red colour 0.9 0.1 0.1 phong 0.5\n"
                                 "material mirror colour 0.2 0.2 0.2 reflection 0.8\n"
                                 "plane normal 0 1 0 distance 0 material floor\n"
                                 "disc centre 0 1 0 normal 0 1 0.6 radius 1 material red\n"
                                 "disc centre 1.6 0.8 -1 normal -1 0.5 1 radius 0.7 material mirror\n";

/* Chapter 8's main.c, with the model disc added to its list of kinds: the one line a new kind takes. */
static int chapter_8_with_discs(int argc, char **argv) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind,
                                                     &solution_disc_kind, NULL};
    static const struct chapter chapter = {
        .number = 8,
        .title = "recursion",
        .default_scene = "scenes/08-recursion.scene",
        .kinds = kinds,
        .lighting = POV_WHITTED,
    };
    struct cli_run run;
    if (!cli_start(&run, &chapter, argc, argv))
        return cli_finish(&run);
    if (!scene_load_meshes(&run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    struct world w;
    if (!world_init(&w, &run.scene, run.err, sizeof run.err))
        return cli_fail(&run);
    cli_render(&run, whitted_trace, &w);
    world_free(&w);
    return cli_finish(&run);
}

Test(exercise_checks, a_new_kind_is_one_more_line_in_a_chapters_list_of_kinds, .timeout = 120) {
    mkdir("out", 0755);
    mkdir(TEST_OUT, 0755);
    const char *scene = TEST_OUT "/discs.scene", *png = TEST_OUT "/discs.png", *pov = TEST_OUT "/discs.pov",
               *povray_png = TEST_OUT "/discs-povray.png";
    FILE *f = fopen(scene, "w");
    cr_assert_not_null(f);
    fputs(disc_scene, f);
    fclose(f);
    char *render[] = {"chapter-08", (char *)scene, "-o", (char *)png, "--threads", "1", "--quiet", NULL};
    cr_assert_eq(chapter_8_with_discs(7, render), 0);
    char *twin[] = {"chapter-08", (char *)scene, "--pov", (char *)pov, "--quiet", NULL};
    cr_assert_eq(chapter_8_with_discs(5, twin), 0);

    /* The twin holds both discs, and POV-Ray's picture of it agrees with ours. */
    char *text = read_text_file(pov);
    cr_assert_not_null(strstr(text, "disc { <0, 1, 0>, <0, 0.85749292571254432, 0.51449575542752657>, 1 texture"), "%s",
                       text);
    cr_assert_not_null(strstr(text, "disc { <1.6000000000000001, 0.80000000000000004, -1>"), "%s", text);
    free(text);
    char command[1024];
    snprintf(command, sizeof command, "povray +I%s +O%s +W80 +H60 +WT1 %s", pov, povray_png, POVRAY_OPTIONS);
    cr_assert_eq(run_logged(command, TEST_OUT "/discs-povray.log"), 0, "POV-Ray failed: see %s",
                 TEST_OUT "/discs-povray.log");
    struct image_difference d = compare_png(png, povray_png);
    report_difference("model discs against POV-Ray", &d);
    cr_assert(image_difference_agrees(&d), "mean %.4f, max %d", d.mean, d.max);

    /* Not vacuous: the red disc fills the middle of the picture. */
    int width, height;
    char err[256];
    uint8_t *rgb = image_read_rgb(png, &width, &height, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    const uint8_t *middle = rgb + 3 * ((size_t)(height / 2) * (size_t)width + (size_t)(width / 2));
    cr_assert(middle[0] > 100 && middle[1] < 60 && middle[2] < 60, "the middle pixel is (%d, %d, %d), not red",
              middle[0], middle[1], middle[2]);
    free(rgb);
}
PROOF(rooks, check_rooks, solution_supersample_rooks, wrong_supersample_rooks)
PROOF(concentric, check_concentric, solution_thin_lens_concentric, wrong_thin_lens_concentric)
PROOF(cylindrical, check_cylindrical, solution_image_map_cylindrical, wrong_image_map_cylindrical)
PROOF(cone, check_cone, solution_sampling_sphere_cone, wrong_sampling_sphere_cone)
PROOF(slerp, check_slerp, solution_keyframes_slerp, wrong_keyframes_slerp)
PROOF(ggx_normals, check_ggx_normals, solution_microfacet_ggx_sample_normal, wrong_microfacet_ggx_sample_normal)

/* test_images.c: every chapter's picture against its reference image and against POV-Ray, and proof
 * that both checks catch real mistakes. */
#include <criterion/criterion.h>
#include <stdio.h>

#include "image_test_support.h"

/* Renders chapter n's own scene and compares it with reference_images/chapter-NN.png. */
static void check_reference(int n) {
    char png[256], reference[256], what[64];
    snprintf(reference, sizeof reference, "reference_images/chapter-%02d.png", n);
    snprintf(what, sizeof what, "chapter %d vs reference", n);
    cr_assert_eq(render_own_scene(n, png, sizeof png), 0, "chapter %d failed to render", n);
    struct image_difference d = compare_png(png, reference);
    report_difference(what, &d);
    cr_assert(regression_passes(&d), "chapter %d differs from its reference: max %d, mean %.4f, within 1: %.3f%%",
              n, d.max, d.mean, 100.0 * d.within_1);
}

/* Renders chapter n's scene with the chapter and with POV-Ray, and checks that they agree. */
static void check_povray(int n) {
    char ours[256], theirs[256], what[64];
    snprintf(theirs, sizeof theirs, TEST_OUT "/chapter-%02d-povray.png", n);
    snprintf(what, sizeof what, "chapter %d vs POV-Ray", n);
    cr_assert_eq(render_own_scene(n, ours, sizeof ours), 0, "chapter %d failed to render", n);
    cr_assert(render_povray(n, chapter_scene(n), theirs), "POV-Ray failed on chapter %d's twin", n);
    struct image_difference d = compare_png(ours, theirs);
    report_difference(what, &d);
    cr_assert(image_difference_agrees(&d),
              "chapter %d disagrees with POV-Ray: within 2: %.3f%% (need 99.9), mean %.4f (need <= 0.05)", n,
              100.0 * d.within_2, d.mean);
}

#define CHAPTER_IMAGE_TESTS(n, name)                                                                      \
    Test(reference_image, name##_matches_its_reference, .timeout = 120) { check_reference(n); }          \
    Test(povray_agreement, name##_agrees_with_povray, .timeout = 120) { check_povray(n); }

CHAPTER_IMAGE_TESTS(1, chapter_01_camera)
CHAPTER_IMAGE_TESTS(2, chapter_02_sphere)
CHAPTER_IMAGE_TESTS(3, chapter_03_triangle)
CHAPTER_IMAGE_TESTS(4, chapter_04_plane)
CHAPTER_IMAGE_TESTS(5, chapter_05_aabb)
CHAPTER_IMAGE_TESTS(6, chapter_06_phong)
CHAPTER_IMAGE_TESTS(7, chapter_07_shadows)
CHAPTER_IMAGE_TESTS(8, chapter_08_recursion)
CHAPTER_IMAGE_TESTS(9, chapter_09_kdtree)
CHAPTER_IMAGE_TESTS(10, chapter_10_bvh)
CHAPTER_IMAGE_TESTS(11, chapter_11_fast)
CHAPTER_IMAGE_TESTS(12, chapter_12_antialias)
CHAPTER_IMAGE_TESTS(13, chapter_13_distributed)
CHAPTER_IMAGE_TESTS(14, chapter_14_textures)

/* Chapter 15 solves the rendering equation, which POV-Ray does not: its independent renderer is Blender's
 * Cycles (make compare-cycles, tools/cycles/). Its picture is the same on any machine and thread count
 * (its random numbers are keyed by pixel, sample and seed), so it is held to its reference like the others;
 * at 256 paths a pixel it takes some seconds, so this test is one of make test-long's. */
Test(reference_image, chapter_15_paths_matches_its_reference, .timeout = 300) { check_reference(15); }

/* Chapter 16 draws motion blur, which POV-Ray 3.7 does not: its twin is compared on a frame without it
 * (tests/test_instances.c); its own picture, blur and all, is held to its reference. */
Test(reference_image, chapter_16_instances_matches_its_reference, .timeout = 120) { check_reference(16); }

/* ---- acceleration changes the work, never the picture ------------------------------------------ */

/* Renders `scene` with chapter n and the extra options, and asserts the picture equals `expected`. */
static void check_identical(int n, const char *scene, const char *extra, const char *expected, const char *tag) {
    char png[256];
    snprintf(png, sizeof png, TEST_OUT "/identical-%s.png", tag);
    cr_assert_eq(render_chapter(n, scene, png, extra), 0, "chapter %d %s failed", n, extra);
    struct image_difference d = compare_png(png, expected);
    cr_assert_eq(d.max, 0, "chapter %d %s differs from %s by up to %d levels", n, extra, expected, d.max);
}

Test(acceleration, every_structure_draws_the_brute_force_picture, .timeout = 300) {
    const char *scene = chapter_scene(9);
    const char *brute = TEST_OUT "/brute-force-09.png";
    cr_assert_eq(render_chapter(10, scene, brute, "--accel none"), 0);
    check_identical(10, scene, "--accel bvh --split sah", brute, "bvh-sah");
    check_identical(10, scene, "--accel bvh --split seed", brute, "bvh-median");
    check_identical(10, scene, "--accel kdtree --split sah", brute, "kd-sah");
    check_identical(10, scene, "--accel kdtree --split seed", brute, "kd-seed");
    check_identical(9, scene, "", brute, "chapter-9");
    check_identical(8, scene, "", brute, "chapter-8");
}

/* Chapter 11 changes only the speed: its reference is chapter 10's picture, and every rung of its
 * ladder, by either split rule, draws the brute-force picture. */
Test(acceleration, every_rung_of_chapter_11_draws_the_brute_force_picture, .timeout = 300) {
    struct image_difference same = compare_png("reference_images/chapter-11.png", "reference_images/chapter-10.png");
    cr_assert_eq(same.max, 0, "chapter 11's reference differs from chapter 10's by up to %d levels", same.max);
    const char *scene = chapter_scene(9);
    const char *brute = TEST_OUT "/brute-force-09-for-11.png";
    cr_assert_eq(render_chapter(11, scene, brute, "--accel none"), 0);
    static const char *const rungs[] = {"1", "2", "3", "4", "5", "6", "7", "8", "9", "10", "11"};
    for (size_t k = 0; k < sizeof rungs / sizeof rungs[0]; k++) {
        char extra[64], tag[32];
        snprintf(extra, sizeof extra, "--rung %s", rungs[k]);
        snprintf(tag, sizeof tag, "rung-%s", rungs[k]);
        check_identical(11, scene, extra, brute, tag);
    }
    check_identical(11, scene, "--rung float --split seed", brute, "rung-6-median");
    check_identical(11, scene, "--rung compact --split seed", brute, "rung-7-median");
    check_identical(11, scene, "--rung plain --split seed", brute, "rung-1-median");
    check_identical(11, scene, "--rung eight --split seed", brute, "rung-8-median");
    check_identical(11, scene, "--rung lean --split seed", brute, "rung-9-median");
    check_identical(11, scene, "--rung packet --split seed", brute, "rung-10-median");
    check_identical(11, scene, "--rung exact-float --split seed", brute, "rung-11-median");
    check_identical(11, scene, "--rung packet --threads 2", brute, "rung-10-two-threads");
    cr_assert_eq(setenv("WHITTED_NO_AVX2", "1", 1), 0); /* rungs 8's to 11's fallback, as without AVX2 */
    check_identical(11, scene, "--rung eight", brute, "rung-8-without-avx2");
    check_identical(11, scene, "--rung lean", brute, "rung-9-without-avx2");
    check_identical(11, scene, "--rung packet", brute, "rung-10-without-avx2");
    check_identical(11, scene, "--rung exact-float", brute, "rung-11-without-avx2");
    cr_assert_eq(unsetenv("WHITTED_NO_AVX2"), 0);
}

/* Transparent meshes: shadow rays pass through glass and take its colour, so every rung's shadow query
 * must find each triangle the brute-force loop finds, not only the first. Chapter 9's scene with the
 * teapot made filtering glass and the bunny clear glass, at half size, by rungs 1, 6, 7, 8, 9, 10 and 11. */
Test(acceleration, rungs_draw_transparent_meshes_as_the_brute_force_loop, .timeout = 120) {
    const char *olds[] = {
        "material china  colour 0.9 0.88 0.82 ambient 0.1 diffuse 0.7 phong 0.8 phong_size 120 reflection 0.1",
        "material clay   colour 0.85 0.55 0.35 ambient 0.1 diffuse 0.8 phong 0.3 phong_size 20"};
    const char *news[] = {
        "material china  colour 0.5 0.9 0.6 ambient 0 diffuse 0.05 phong 0.8 phong_size 120 reflection 0.05 "
        "filter 0.8 ior 1.4",
        "material clay   colour 1 1 1 ambient 0 diffuse 0.05 phong 0.3 phong_size 20 transmit 0.85 ior 1.3"};
    const char *scene = "scenes/09-kdtree.scene.glass-meshes.variant";
    const char *brute = TEST_OUT "/brute-force-glass-meshes.png";
    write_scene_variant(chapter_scene(9), scene, olds, news, 2, NULL);
    int status = render_chapter(11, scene, brute, "--accel none --width 120 --height 90");
    static const char *const rungs[] = {"1", "6", "7", "8", "9", "10", "11"};
    for (size_t k = 0; status == 0 && k < sizeof rungs / sizeof rungs[0]; k++) {
        char extra[64], tag[32];
        snprintf(extra, sizeof extra, "--rung %s --width 120 --height 90", rungs[k]);
        snprintf(tag, sizeof tag, "glass-meshes-rung-%s", rungs[k]);
        check_identical(11, scene, extra, brute, tag);
    }
    remove(scene);
    cr_assert_eq(status, 0, "chapter 11 --accel none failed on the glass meshes");
}

Test(acceleration, chapters_9_to_11_draw_chapter_8s_picture) {
    char expected[256];
    cr_assert_eq(render_own_scene(8, expected, sizeof expected), 0);
    check_identical(9, chapter_scene(8), "", expected, "ch9-on-8");
    check_identical(10, chapter_scene(8), "", expected, "ch10-on-8");
    check_identical(11, chapter_scene(8), "", expected, "ch11-on-8");
}

Test(acceleration, the_picture_is_the_same_for_1_2_and_4_threads, .timeout = 300) {
    const char *one = TEST_OUT "/threads-1.png";
    cr_assert_eq(render_chapter(10, chapter_scene(10), one, "--threads 1"), 0);
    check_identical(10, chapter_scene(10), "--threads 2", one, "threads-2");
    check_identical(10, chapter_scene(10), "--threads 4", one, "threads-4");
    check_identical(11, chapter_scene(10), "--threads 2", one, "ch11-threads-2");
}

/* ---- the checks catch real changes ------------------------------------------------------------ */

/* Renders chapter n on a variant of its scene and returns the difference from the reference. */
static struct image_difference variant_vs_reference(int n, const char *tag, const char *const *olds,
                                                    const char *const *news, int count, const char *camera) {
    char variant[256], png[256], reference[256];
    snprintf(variant, sizeof variant, "%s.%s.variant", chapter_scene(n), tag);
    snprintf(png, sizeof png, TEST_OUT "/chapter-%02d-%s.png", n, tag);
    snprintf(reference, sizeof reference, "reference_images/chapter-%02d.png", n);
    write_scene_variant(chapter_scene(n), variant, olds, news, count, camera);
    int status = render_chapter(n, variant, png, "");
    remove(variant);
    cr_assert_eq(status, 0, "chapter %d failed on the %s variant", n, tag);
    struct image_difference d = compare_png(png, reference);
    report_difference(tag, &d);
    return d;
}

Test(reference_image, catches_a_camera_shifted_by_one_pixel) {
    struct image_difference d = variant_vs_reference(2, "shifted", NULL, NULL, 0,
                                                     shifted_camera_line(chapter_scene(2), 1.0));
    cr_assert(!regression_passes(&d), "a one-pixel camera shift went unnoticed");
}

Test(reference_image, catches_a_changed_material_colour) {
    const char *olds[] = {"material red    colour 0.9 0.2 0.15"};
    const char *news[] = {"material red    colour 0.9 0.22 0.15"};
    struct image_difference d = variant_vs_reference(2, "recoloured", olds, news, 1, NULL);
    cr_assert(!regression_passes(&d), "a changed colour went unnoticed");
}

Test(reference_image, catches_a_changed_phong_size) {
    const char *olds[] = {"phong 0.9 phong_size 80"};
    const char *news[] = {"phong 0.9 phong_size 70"};
    struct image_difference d = variant_vs_reference(6, "phong-size", olds, news, 1, NULL);
    cr_assert(!regression_passes(&d), "a changed phong_size went unnoticed");
}

Test(reference_image, catches_a_removed_light) {
    const char *olds[] = {"light position  4 5 3    colour 0.3 0.35 0.55"};
    const char *news[] = {"# light removed"};
    struct image_difference d = variant_vs_reference(7, "one-light", olds, news, 1, NULL);
    cr_assert(!regression_passes(&d), "a removed light went unnoticed");
}

Test(reference_image, catches_a_wrong_ior) {
    const char *olds[] = {"transmit 0.9 ior 1.5"};
    const char *news[] = {"transmit 0.9 ior 1.45"};
    struct image_difference d = variant_vs_reference(8, "ior", olds, news, 1, NULL);
    cr_assert(!regression_passes(&d), "a wrong ior went unnoticed");
}

Test(povray_agreement, catches_one_extra_trace_level) {
    /* Our tracer goes one level deeper than the twin POV-Ray renders: the oracle's "max_trace_level + 1"
     * mistake. The agreement rule must reject it. */
    const char *olds[] = {"max_depth 5"};
    const char *news[] = {"max_depth 6"};
    const char *scene = chapter_scene(8);
    char variant[256];
    snprintf(variant, sizeof variant, "%s.deeper.variant", scene);
    write_scene_variant(scene, variant, olds, news, 1, NULL);
    int status = render_chapter(8, variant, TEST_OUT "/deeper-ours.png", "");
    remove(variant);
    cr_assert_eq(status, 0);
    cr_assert(render_povray(8, scene, TEST_OUT "/deeper-povray.png"));
    struct image_difference d = compare_png(TEST_OUT "/deeper-ours.png", TEST_OUT "/deeper-povray.png");
    report_difference("one extra level vs POV-Ray", &d);
    cr_assert(!image_difference_agrees(&d), "one extra trace level went unnoticed");
}

Test(povray_agreement, catches_a_highlight_multiplied_by_the_pigment) {
    /* Chapter 6 built with the oracle's first negative control: the highlight multiplied by the pigment
     * colour (tests/mutants/highlight-times-pigment.patch, applied to a copy of the sources). The
     * agreement rule must reject it against the twin of the same scene. */
    const char *scene = chapter_scene(6);
    cr_assert_eq(render_with(mutant_program("highlight-times-pigment"), scene, TEST_OUT "/tinted-ours.png", ""), 0);
    cr_assert(render_povray(6, scene, TEST_OUT "/tinted-povray.png"));
    struct image_difference d = compare_png(TEST_OUT "/tinted-ours.png", TEST_OUT "/tinted-povray.png");
    report_difference("highlight x pigment vs POV-Ray", &d);
    cr_assert(!image_difference_agrees(&d), "a highlight multiplied by the pigment went unnoticed");
}

/* ---- shadow acne ------------------------------------------------------------------------------- */

Test(shadows, without_the_offset_lit_surfaces_break_out_in_acne) {
    cr_assert_eq(render_chapter(7, chapter_scene(7), TEST_OUT "/acne-off.png", ""), 0);
    cr_assert_eq(render_chapter(7, "scenes/07-shadow-acne.scene", TEST_OUT "/acne-on.png", ""), 0);
    struct image_difference d = compare_png(TEST_OUT "/acne-off.png", TEST_OUT "/acne-on.png");
    report_difference("acne vs no acne", &d);
    /* Measured: about 8 % of the pixels turn dark. Acne hits lit surfaces at random, so demand a lot
     * of changed pixels, not a particular pattern. */
    cr_assert_gt(d.pixels_over_2, 2000, "only %ld pixels changed: no acne?", d.pixels_over_2);
}

Test(shadows, the_acne_scene_has_no_povray_twin) {
    remove(TEST_OUT "/acne.pov");
    expect_chapter_run(7, "scenes/07-shadow-acne.scene --pov " TEST_OUT "/acne.pov", 1,
                       "scenes/07-shadow-acne.scene: shadow_offset off has no POV-Ray equivalent");
    FILE *twin = fopen(TEST_OUT "/acne.pov", "r");
    cr_assert_null(twin, "a twin was written although POV-Ray cannot draw acne");
}

/* The grader's picture check of chapter 15 (tests/checks/check_picture.c) renders a smaller picture with
 * fewer paths, to take a second instead of half a minute; its reference is the reference program's. */
static void check_small_picture(int n, const char *options) {
    char png[256], reference[256], what[64];
    snprintf(png, sizeof png, TEST_OUT "/chapter-%02d-check.png", n);
    snprintf(reference, sizeof reference, "reference_images/chapter-%02d-check.png", n);
    snprintf(what, sizeof what, "chapter %d's picture check vs reference", n);
    cr_assert_eq(render_chapter(n, chapter_scene(n), png, options), 0);
    struct image_difference d = compare_png(png, reference);
    report_difference(what, &d);
    cr_assert(regression_passes(&d), "%s is stale: max %d, mean %.4f, within 1: %.3f%% (make it again: "
              "build/chapter-%02d %s)", reference, d.max, d.mean, 100.0 * d.within_1, n, options);
}

Test(reference_image, chapter_15_check_picture_matches_its_reference, .timeout = 120) {
    check_small_picture(15, "--width 128 --height 128 --set paths.samples=16");
}

/* Chapter 17's picture, held to its reference as chapter 15's (make test-long: some seconds), and its
 * smaller picture of 16 paths a pixel (make test). Its independent renderer is Cycles (tools/cycles/). */
Test(reference_image, chapter_17_rough_matches_its_reference, .timeout = 300) { check_reference(17); }

Test(reference_image, chapter_17_check_picture_matches_its_reference, .timeout = 120) {
    check_small_picture(17, "--width 128 --height 85 --set paths.samples=16");
}

/* test_fuzz_regressions.c: every input the fuzzers (make fuzz, docs/fuzzing.md) found a fault with,
 * replayed through the normal build: each now gives a clean answer, not a crash.
 *
 * The inputs live in tests/data/fuzz/HARNESS/, one file each, with a comment saying what they broke when
 * the format allows one. A scene or mesh input must load, or be refused with a message that starts
 * with its file name ("file:line: what is wrong"); a renderer input must pass the renderer fuzzer's
 * whole check (fuzz/render_check.h): every structure agrees with brute force and every hit is finite.
 * An input that triggers a defect still being fixed is skipped with the defect's name (the list is in
 * fuzz/render_check.c); deleting the entry there makes it run. Each file is its
 * own test, so a crash names the file. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../fuzz/render_check.h"
#include "../fuzz/tiny_images.h"
#include "image_map.h"
#include "mesh.h"
#include "mesh_load.h"
#include "scene.h"
#include "test_support.h"

#define FUZZ_INPUTS_MAX 256

struct input {
    char path[256];
};

/* Fills inputs[] with the files matching `pattern`, sorted; returns how many. */
static size_t find_inputs(const char *pattern, struct input *inputs) {
    glob_t found;
    size_t count = 0;
    if (glob(pattern, 0, NULL, &found) != 0)
        return 0;
    for (size_t k = 0; k < found.gl_pathc && count < FUZZ_INPUTS_MAX; k++)
        snprintf(inputs[count++].path, sizeof inputs[0].path, "%s", found.gl_pathv[k]);
    globfree(&found);
    return count;
}

/* Asserts that err is a message about the file `path`: "path:" and then something. */
static void expect_names_file(const char *err, const char *path) {
    size_t n = strlen(path);
    cr_expect(strncmp(err, path, n) == 0 && err[n] == ':' && err[n + 1] != '\0',
              "the message does not start with '%s:': '%s'", path, err);
}

/* ---- the scene parser ------------------------------------------------------------------------- */

static struct input scene_inputs[FUZZ_INPUTS_MAX];

ParameterizedTestParameters(fuzz_regressions, scene_input_loads_or_is_refused_cleanly) {
    return cr_make_param_array(struct input, scene_inputs, find_inputs("tests/data/fuzz/scene/*", scene_inputs));
}

ParameterizedTest(struct input *in, fuzz_regressions, scene_input_loads_or_is_refused_cleanly) {
    struct scene s;
    char err[512] = "";
    if (scene_load(in->path, test_every_kind, &s, err, sizeof err))
        scene_free(&s);
    else
        expect_names_file(err, in->path);
}

/* ---- the mesh readers ------------------------------------------------------------------------- */

static struct input mesh_inputs[FUZZ_INPUTS_MAX];

ParameterizedTestParameters(fuzz_regressions, mesh_input_loads_or_is_refused_cleanly) {
    size_t count = find_inputs("tests/data/fuzz/ply/*", mesh_inputs);
    count += find_inputs("tests/data/fuzz/obj/*", mesh_inputs + count);
    return cr_make_param_array(struct input, mesh_inputs, count);
}

ParameterizedTest(struct input *in, fuzz_regressions, mesh_input_loads_or_is_refused_cleanly) {
    struct mesh m;
    char err[512] = "";
    if (mesh_load(in->path, &m, err, sizeof err)) {
        for (size_t f = 0; f < m.face_count; f++)
            for (int c = 0; c < 3; c++)
                cr_assert_lt(m.faces[f].v[c], m.vertex_count);
        mesh_free(&m);
    } else {
        expect_names_file(err, in->path);
    }
}

/* ---- the image-map reader ---------------------------------------------------------------------- */

/* Reads the image file at path as chapter 14 does: it must be read, with every texel in [0, 1], or
 * refused with a message naming the file. */
static void expect_image_read_or_refused(const char *path, bool must_read) {
    struct pigment_image image;
    char why[1024] = "";
    if (!image_map_read(path, &image, why, sizeof why)) {
        cr_expect(!must_read, "%s", why);
        expect_names_file(why, path);
        return;
    }
    cr_expect(image.width >= 1 && image.height >= 1, "%s: %d x %d", path, image.width, image.height);
    for (size_t k = 0; k < (size_t)image.width * (size_t)image.height * 4; k++)
        cr_expect(image.texels[k] >= 0.0f && image.texels[k] <= 1.0f, "%s: texel %zu is %g", path, k, image.texels[k]);
    free(image.texels);
}

static struct input image_inputs[FUZZ_INPUTS_MAX];

ParameterizedTestParameters(fuzz_regressions, image_input_is_read_or_refused_cleanly) {
    return cr_make_param_array(struct input, image_inputs, find_inputs("tests/data/fuzz/image/*", image_inputs));
}

ParameterizedTest(struct input *in, fuzz_regressions, image_input_is_read_or_refused_cleanly) {
    expect_image_read_or_refused(in->path, false);
}

/* The image harness's seeds and the renderer check's pictures (fuzz/tiny_images.h) are pictures the
 * reader takes, of every kind: 8 and 16 bits, 1 to 4 channels, sRGB and gAMA chunks, JPEG. */
Test(fuzz_regressions, every_tiny_image_is_read) {
    char folder[] = "/tmp/whitted-tiny-images-XXXXXX", err[512], path[256];
    cr_assert_not_null(mkdtemp(folder));
    cr_assert(tiny_images_write(folder, err, sizeof err), "%s", err);
    for (size_t k = 0; k < TINY_IMAGE_COUNT; k++) {
        snprintf(path, sizeof path, "%s/%s", folder, tiny_image_name(k));
        expect_image_read_or_refused(path, true);
        remove(path);
    }
    rmdir(folder);
}

/* ---- the renderer ----------------------------------------------------------------------------- */

/* Runs the renderer fuzzer's check on the scene file at path. */
static void expect_render_check_passes(const char *path) {
    char *text = read_text_file(path);
    char why[1024];
    enum render_check_result result = render_check_scene(path, text, why, sizeof why);
    free(text);
    if (result == RENDER_CHECK_KNOWN_DEFECT)
        cr_skip_test("%s: %s", path, why);
    cr_expect_eq(result, RENDER_CHECK_PASSED, "%s: %s", path, why);
}

static struct input render_inputs[FUZZ_INPUTS_MAX];

ParameterizedTestParameters(fuzz_regressions, render_input_passes_the_renderer_check) {
    return cr_make_param_array(struct input, render_inputs, find_inputs("tests/data/fuzz/render/*", render_inputs));
}

ParameterizedTest(struct input *in, fuzz_regressions, render_input_passes_the_renderer_check) {
    expect_render_check_passes(in->path);
}

/* The check itself on the chapters' scenes (their meshes replaced by the tiny ones): every structure
 * agrees with brute force on real scenes with glass, mirrors, boxes and meshes. */
static struct input chapter_scenes[FUZZ_INPUTS_MAX];

ParameterizedTestParameters(fuzz_regressions, chapter_scene_passes_the_renderer_check) {
    return cr_make_param_array(struct input, chapter_scenes, find_inputs("scenes/*.scene", chapter_scenes));
}

ParameterizedTest(struct input *in, fuzz_regressions, chapter_scene_passes_the_renderer_check) {
    expect_render_check_passes(in->path);
}

/* A mesh placed out of the float range the structures hold (the renderer fuzzer's first finding, a
 * crash in the BVH build) is refused with the scene's file and line, and one placed within it is drawn. */
Test(fuzz_regressions, a_mesh_placed_out_of_float_range_is_refused_with_file_and_line) {
    char why[1024];
    const char *text = "camera eye 0 0 5  target 0 0 0  fov 40\nimage 4 3\nmesh a.ply translate 1e39 0 0\n";
    cr_expect_eq(render_check_scene("far.scene", text, why, sizeof why), RENDER_CHECK_PASSED, "%s", why);
    cr_expect(strstr(why, "refused: far.scene:3: mesh ") != NULL && strstr(why, "out of range") != NULL, "%s", why);
    const char *inside = "camera eye 0 0 5  target 0 0 0  fov 40\nimage 4 3\nmesh a.ply translate 1e3 0 0\n";
    cr_expect_eq(render_check_scene("near.scene", inside, why, sizeof why), RENDER_CHECK_PASSED, "%s", why);
    cr_expect_str_eq(why, "all checks hold");
}

/* A `triangle` directive with a corner out of that range (the renderer fuzzer's second finding, the
 * same crash through a directive instead of a mesh) is refused by the parser with file and line. */
Test(fuzz_regressions, a_triangle_directive_out_of_float_range_is_refused_with_file_and_line) {
    char why[1024];
    const char *text = "camera eye 0 1 5  target 1 0 0  fov 92\nimage 4 3\ntriangle a -1 -4 2  b .6 4 -2  c 0 8 1e39\n";
    cr_expect_eq(render_check_scene("far.scene", text, why, sizeof why), RENDER_CHECK_PASSED, "%s", why);
    cr_expect(strstr(why, "refused: far.scene:3: ") != NULL &&
              strstr(why, "corner c is at (0, 8, 1e+39); coordinates must stay within -1e+18 .. 1e+18") != NULL,
              "%s", why);
}

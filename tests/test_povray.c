/* test_povray.c: the POV-Ray exporter (common/povray.c) writes the twin that docs/povray.md
 * prescribes for each lighting: the header settings, the explicit camera basis, the lights and finishes
 * of each chapter, transparency only where the chapter draws it, and meshes as mesh2. Numbers are
 * printed with 17 significant digits, so they are read back here with strtod and compared exactly. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image_test_support.h"
#include "povray.h"
#include "test_support.h"

#define NAME "twin.scene"
#define CAMERA "camera eye 0 0 0 target 0 0 -1 fov 90\nimage 2 1\n"

/* ---- helpers ----------------------------------------------------------------------------------- */

static struct scene parse(const char *text) {
    struct scene s;
    char err[512] = "";
    cr_assert(scene_parse(NAME, text, NULL, &s, err, sizeof err), "refused: %s", err);
    return s;
}

/* Writes the twin of s under `lighting` into a temporary folder and returns its text (malloc'd). */
static char *write_twin(const struct scene *s, enum pov_lighting lighting) {
    char dir[64] = "/tmp/whitted-povray-XXXXXX", path[96], err[512] = "";
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/twin.pov", dir);
    cr_assert(povray_write_scene(s, lighting, path, err, sizeof err), "%s", err);
    FILE *file = fopen(path, "rb");
    cr_assert_not_null(file);
    char *text = NULL;
    size_t size = 0;
    FILE *copy = open_memstream(&text, &size);
    for (int c; (c = fgetc(file)) != EOF;)
        fputc(c, copy);
    fclose(copy);
    fclose(file);
    remove(path);
    rmdir(dir);
    return text;
}

/* Parses `text` as a scene and returns the text of its twin under `lighting` (malloc'd). */
static char *twin_of(const char *text, enum pov_lighting lighting) {
    struct scene s = parse(text);
    char *pov = write_twin(&s, lighting);
    scene_free(&s);
    return pov;
}

static bool contains(const char *text, const char *part) { return strstr(text, part) != NULL; }

/* Reads "<x, y, z>" right after the first occurrence of `label` in text. */
static vec3 vector_after(const char *text, const char *label) {
    const char *at = strstr(text, label);
    cr_assert_not_null(at, "no '%s' in the twin", label);
    at += strlen(label);
    cr_assert_eq(*at, '<', "no vector after '%s'", label);
    double v[3];
    char *end = (char *)at + 1;
    for (int k = 0; k < 3; k++) {
        v[k] = strtod(end, &end);
        cr_assert_eq(*end, k < 2 ? ',' : '>', "bad vector after '%s'", label);
        end++;
    }
    return vec3_make(v[0], v[1], v[2]);
}

/* Reads the whole number right after the first occurrence of `label` in text. */
static long number_after(const char *text, const char *label) {
    const char *at = strstr(text, label);
    cr_assert_not_null(at, "no '%s' in the twin", label);
    return strtol(at + strlen(label), NULL, 10);
}

static void assert_vec3_exact(vec3 got, vec3 want, const char *what) {
    cr_assert(got.x == want.x && got.y == want.y && got.z == want.z,
              "%s: got <%.17g, %.17g, %.17g>, want <%.17g, %.17g, %.17g>", what, got.x, got.y, got.z, want.x,
              want.y, want.z);
}

/* ---- header and camera ------------------------------------------------------------------------- */

Test(povray_export, header_has_version_gamma_and_bailout) {
    char *pov = twin_of(CAMERA, POV_HEADLIGHT);
    cr_assert(contains(pov, "#version 3.7;"));
    cr_assert(contains(pov, "assumed_gamma 1.0"));
    cr_assert(contains(pov, "adc_bailout 0"));
    cr_assert(contains(pov, "+W2 +H1 " POVRAY_OPTIONS), "the render command names the size and options");
    free(pov);
}

Test(povray_export, camera_is_an_explicit_basis_with_the_right_vectors) {
    char *pov = twin_of(CAMERA, POV_HEADLIGHT);
    /* t = tan(45 degrees), a = 2: right = 2 t a (1, 0, 0) ~ <4, 0, 0>, up = 2 t (0, 1, 0) ~ <0, 2, 0>. */
    double t = tan(90 * M_PI / 360.0);
    vec3 right = vector_after(pov, "\n  right "), up = vector_after(pov, "\n  up ");
    assert_vec3_exact(vector_after(pov, "\n  location "), vec3_make(0, 0, 0), "location");
    assert_vec3_exact(vector_after(pov, "\n  direction "), vec3_make(0, 0, -1), "direction");
    assert_vec3_exact(right, vec3_make(2.0 * (t * 2.0), 0, 0), "right");
    assert_vec3_exact(up, vec3_make(0, 2.0 * t, 0), "up");
    cr_assert_float_eq(right.x, 4.0, 1e-15);
    cr_assert_float_eq(up.y, 2.0, 1e-15);
    cr_assert(contains(pov, "perspective"));
    free(pov);
}

Test(povray_export, camera_basis_matches_a_tilted_camera_with_a_non_unit_up) {
    char *pov = twin_of("camera eye 1 2 3 target 1 1 2 up 0 5 0 fov 90\nimage 3 3\n", POV_HEADLIGHT);
    /* f = (0,-1,-1)/sqrt2, r = (1,0,0), u = (0,1,-1)/sqrt2; t = tan(45 degrees), a = 1. */
    double s = sqrt(0.5);
    vec3 direction = vector_after(pov, "\n  direction "), right = vector_after(pov, "\n  right ");
    vec3 up = vector_after(pov, "\n  up ");
    cr_assert(fabs(direction.x) + fabs(direction.y + s) + fabs(direction.z + s) < 1e-15, "direction");
    cr_assert(fabs(right.x - 2) + fabs(right.y) + fabs(right.z) < 1e-15, "right");
    cr_assert(fabs(up.x) + fabs(up.y - 2 * s) + fabs(up.z + 2 * s) < 1e-15, "up");
    assert_vec3_exact(vector_after(pov, "\n  location "), vec3_make(1, 2, 3), "location");
    free(pov);
}

Test(povray_export, numbers_read_back_bit_exact) {
    char *pov = twin_of(CAMERA "sphere centre 0.1 -0.7 1e-7 radius 0.3333333333333333\n", POV_HEADLIGHT);
    vec3 centre = vector_after(pov, "sphere { ");
    assert_vec3_exact(centre, vec3_make(0.1, -0.7, 1e-7), "centre");
    const char *radius = strstr(pov, "sphere { ");
    radius = strchr(radius, '>') + 2; /* "<...>, r" */
    cr_assert_eq(strtod(radius, NULL), 0.3333333333333333);
    free(pov);
}

/* ---- lighting per chapter ---------------------------------------------------------------------- */

#define LIT_SCENE                                                                                       \
    "camera eye 1 2 3 target 0 0 0 fov 40\nimage 8 6\nambient_light 0.5 0.25 1\nmax_depth 7\n"          \
    "light position 9 8 7 colour 0.5 0.5 0.5\n"                                                         \
    "material glass colour 1 0.5 0.25 filter 0.25 transmit 0.5 ior 1.5 reflection 0.125 phong 0.75\n"  \
    "material matte colour 0.5 0.5 0.5 reflection 0.5\n"                                                \
    "sphere centre 0 0 0 radius 1 material glass\n"                                                    \
    "plane normal 0 2 0 distance -1 material matte\n"

Test(povray_export, headlight_puts_a_white_light_at_the_eye_and_diffuse_only_finishes) {
    char *pov = twin_of(LIT_SCENE, POV_HEADLIGHT);
    cr_assert(contains(pov, "light_source { <1, 2, 3> color rgb <1, 1, 1> }"));
    cr_assert(!contains(pov, "<9, 8, 7>"), "the scene's own lights are not used");
    cr_assert(contains(pov, "finish { ambient 0 diffuse 1 phong 0 phong_size"));
    cr_assert(!contains(pov, "finish { ambient 0.1"));
    assert_vec3_exact(vector_after(pov, "ambient_light rgb "), vec3_make(0, 0, 0), "ambient_light");
    cr_assert(contains(pov, "reflection { rgb 0 }"));
    free(pov);
}

Test(povray_export, phong_uses_the_scene_lights_and_no_shadows) {
    char *pov = twin_of(LIT_SCENE, POV_PHONG);
    cr_assert(contains(pov, "light_source { <9, 8, 7> color rgb <0.5, 0.5, 0.5> }"));
    cr_assert(contains(pov, "finish { ambient 0.10000000000000001 diffuse 0.59999999999999998 phong 0.75 "));
    assert_vec3_exact(vector_after(pov, "ambient_light rgb "), vec3_make(0.5, 0.25, 1), "ambient_light");
    cr_assert(contains(pov, "no_shadow"), "chapter 6 casts no shadows");
    /* `shadowless` lights would drop the highlights too (povray.c), so no light is shadowless. */
    cr_assert(!contains(pov, "shadowless"));
    free(pov);
}

Test(povray_export, only_phong_has_no_shadow_and_no_lighting_has_shadowless_lights) {
    enum pov_lighting others[] = {POV_HEADLIGHT, POV_PHONG_SHADOWS, POV_WHITTED};
    for (int k = 0; k < 3; k++) {
        char *pov = twin_of(LIT_SCENE, others[k]);
        bool wrong = contains(pov, "no_shadow") || contains(pov, "shadowless");
        free(pov);
        cr_assert(!wrong, "lighting %d", (int)others[k]);
    }
}

Test(povray_export, whitted_writes_filter_transmit_ior_reflection_and_the_depth) {
    char *pov = twin_of(LIT_SCENE, POV_WHITTED);
    cr_assert(contains(pov, "rgbft <1, 0.5, 0.25, 0.25, 0.5>"), "glass keeps filter and transmit");
    cr_assert(contains(pov, "rgbft <0.5, 0.5, 0.5, 0, 0>"), "matte is opaque");
    cr_assert(contains(pov, "reflection { rgb 0.125 }"));
    cr_assert(contains(pov, "texture { M1 } interior { ior 1.5 } }"), "the glass sphere has an interior");
    cr_assert(contains(pov, "texture { M2 } }"), "the opaque plane has none");
    cr_assert_eq(number_after(pov, "max_trace_level "), 7);
    free(pov);
}

Test(povray_export, chapters_before_8_drop_transparency_reflection_and_depth) {
    enum pov_lighting before[] = {POV_HEADLIGHT, POV_PHONG, POV_PHONG_SHADOWS};
    for (int k = 0; k < 3; k++) {
        char *pov = twin_of(LIT_SCENE, before[k]);
        bool opaque = contains(pov, "rgbft <1, 0.5, 0.25, 0, 0>") && !contains(pov, "interior");
        bool no_reflection = !contains(pov, "reflection { rgb 0.125 }") && !contains(pov, "reflection { rgb 0.5 }");
        long depth = number_after(pov, "max_trace_level ");
        free(pov);
        cr_assert(opaque, "lighting %d writes transparency", (int)before[k]);
        cr_assert(no_reflection, "lighting %d writes reflection", (int)before[k]);
        cr_assert_eq(depth, 1, "lighting %d", (int)before[k]);
    }
}

Test(povray_export, planes_are_written_with_a_unit_normal_and_the_distance_kept) {
    char *pov = twin_of(LIT_SCENE, POV_PHONG);
    cr_assert(contains(pov, "plane { <0, 1, 0>, -1 texture"));
    free(pov);
}

Test(povray_export, ray_direction_chapter_writes_the_sky_and_no_shapes) {
    char *pov = twin_of(LIT_SCENE, POV_RAY_DIRECTION);
    cr_assert(contains(pov, "sky_sphere"));
    cr_assert(!contains(pov, "light_source"));
    cr_assert(!contains(pov, "\nsphere {"), "no sphere (sky_sphere aside)");
    cr_assert(!contains(pov, "\nplane {"));
    free(pov);
}

/* ---- meshes ------------------------------------------------------------------------------------ */

Test(povray_export, mesh_is_one_mesh2_with_the_right_counts) {
    struct scene s = parse(CAMERA "material red\nmesh quad.ply material red\n");
    struct mesh *m = &s.meshes[0].mesh; /* loaded by hand: the parser does not read mesh files */
    m->vertices = malloc(4 * sizeof *m->vertices);
    m->faces = malloc(2 * sizeof *m->faces);
    cr_assert(m->vertices != NULL && m->faces != NULL);
    m->vertices[0] = vec3_make(0, 0, 0);
    m->vertices[1] = vec3_make(1, 0, 0);
    m->vertices[2] = vec3_make(1, 1, 0);
    m->vertices[3] = vec3_make(0, 1, 0.5);
    m->faces[0] = (struct mesh_face){{0, 1, 2}};
    m->faces[1] = (struct mesh_face){{0, 2, 3}};
    m->vertex_count = 4;
    m->face_count = 2;
    char *pov = write_twin(&s, POV_HEADLIGHT);
    scene_free(&s);
    cr_assert(contains(pov, "mesh2 { // quad.ply\n"));
    cr_assert_eq(number_after(pov, "vertex_vectors { "), 4);
    cr_assert_eq(number_after(pov, "face_indices { "), 2);
    cr_assert(contains(pov, "<0, 1, 0.5> }"), "the last vertex closes the list");
    cr_assert(contains(pov, "<0, 1, 2>,\n    <0, 2, 3> }"));
    cr_assert(contains(pov, "<0, 2, 3> }\n  inside_vector <0, 0, 1>\n "),
              "inside_vector, before the texture, so POV-Ray searches the whole mesh");
    cr_assert(contains(pov, "texture { M1 }"));
    free(pov);
}

/* ---- refusals and failures --------------------------------------------------------------------- */

/* Tries to write the twin of `text` under `lighting` into a fresh folder; returns whether it worked,
 * with the message in err and whether a file (or temporary file) was left in the folder. */
static bool try_twin(const char *text, enum pov_lighting lighting, char *err, size_t err_size, bool *file_left) {
    struct scene s = parse(text);
    char dir[64] = "/tmp/whitted-povray-XXXXXX", path[96];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/twin.pov", dir);
    bool ok = povray_write_scene(&s, lighting, path, err, err_size);
    scene_free(&s);
    remove(path);
    *file_left = rmdir(dir) != 0; /* fails only if something else is in the folder */
    return ok;
}

Test(povray_export, shadow_offset_off_is_refused_from_chapter_7_on) {
    enum pov_lighting refused[] = {POV_PHONG_SHADOWS, POV_WHITTED};
    for (int k = 0; k < 2; k++) {
        char err[256] = "";
        bool file_left = false;
        cr_assert(!try_twin(CAMERA "shadow_offset off\n", refused[k], err, sizeof err, &file_left));
        cr_assert_str_eq(err, NAME ": shadow_offset off has no POV-Ray equivalent");
        cr_assert(!file_left);
        cr_assert(!povray_can_express(&(struct scene){.path = NAME, .shadow_offset = false}, refused[k], err,
                                      sizeof err));
    }
}

Test(povray_export, shadow_offset_off_is_fine_before_chapter_7) {
    enum pov_lighting allowed[] = {POV_RAY_DIRECTION, POV_HEADLIGHT, POV_PHONG};
    for (int k = 0; k < 3; k++) {
        char err[256] = "";
        bool file_left = false;
        cr_assert(try_twin(CAMERA "shadow_offset off\n", allowed[k], err, sizeof err, &file_left), "%s", err);
    }
}

/* The twin names an image map's file by its whole path, inside a POV-Ray string: a folder whose name holds
 * a quote or a backslash (the scene's own word for the file may not) would end the string early, so the
 * twin is refused and none is written. */
Test(povray_export, an_image_map_whose_whole_path_holds_a_quote_is_refused) {
    mkdir("out", 0755);
    mkdir(TEST_OUT, 0755);
    const char *folder = TEST_OUT "/pov-q\"d\\x";
    mkdir(folder, 0755);
    char path[256];
    size_t size = 0;
    char *png = read_file("scenes/textures/grid.png", &size);
    snprintf(path, sizeof path, "%s/grid.png", folder);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    fwrite(png, 1, size, f);
    fclose(f);
    free(png);
    snprintf(path, sizeof path, "%s/s.scene", folder);
    f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs(CAMERA "pigment p image_map file grid.png\nmaterial m pigment p\nsphere centre 0 0 -3 radius 1 material m\n",
          f);
    fclose(f);
    remove(TEST_OUT "/pov-quote.pov");
    char *whole = realpath(folder, NULL), arguments[512], expected[1024];
    cr_assert_not_null(whole);
    snprintf(arguments, sizeof arguments, "'%s' --pov " TEST_OUT "/pov-quote.pov", path);
    snprintf(expected, sizeof expected, "%s: pigment 'p': its file's whole path, %s/grid.png, holds a quote, a "
             "backslash or a control character, which the twin's POV-Ray string cannot hold as written", path, whole);
    free(whole);
    expect_chapter_run(14, arguments, 1, expected);
    cr_assert_neq(access(TEST_OUT "/pov-quote.pov", F_OK), 0, "a twin was written");
}

/* The twin's first line is a comment naming the scene's path, which comes from the command line: a line
 * break in it is written as \x0a, so that what follows stays in the comment instead of becoming POV-Ray's
 * code. */
Test(povray_export, a_line_break_in_the_scene_path_stays_in_the_twins_comment) {
    mkdir("out", 0755);
    mkdir(TEST_OUT, 0755);
    const char *folder = TEST_OUT "/pov-nl\n#error \"injected\"\n";
    mkdir(folder, 0755);
    char path[256], arguments[512];
    snprintf(path, sizeof path, "%s/s.scene", folder);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs(CAMERA "sphere centre 0 0 -3 radius 1\n", f);
    fclose(f);
    snprintf(arguments, sizeof arguments, "'%s' --pov " TEST_OUT "/pov-nl.pov", path);
    expect_chapter_run(2, arguments, 0, "wrote POV-Ray twin");
    char *twin = read_text_file(TEST_OUT "/pov-nl.pov");
    cr_expect(strstr(twin, "\n#error") == NULL, "a line of the twin begins with #error:\n%s", twin);
    cr_expect(strncmp(twin, "// POV-Ray 3.7 twin of " TEST_OUT "/pov-nl\\x0a#error \"injected\"\\x0a/s.scene, ",
                      strlen("// POV-Ray 3.7 twin of " TEST_OUT "/pov-nl\\x0a#error \"injected\"\\x0a/s.scene, ")) == 0,
              "%s", twin);
    free(twin);
}

Test(povray_export, writing_into_a_missing_folder_fails_with_the_path) {
    struct scene s = parse(CAMERA);
    char err[256] = "";
    bool ok = povray_write_scene(&s, POV_HEADLIGHT, "/nonexistent/folder/twin.pov", err, sizeof err);
    scene_free(&s);
    cr_assert(!ok);
    cr_assert_str_eq(err, "/nonexistent/folder/twin.pov: cannot create: No such file or directory");
}

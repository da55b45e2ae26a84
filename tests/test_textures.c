/* test_textures.c: chapter 14's pigments and image maps: the pigment line and its errors, each pattern's
 * value against POV-Ray's rules (boundaries, the 1.00001 fold, the brick's offsets), the texture
 * transform, the sRGB decoding and the PNG chunks that choose it, nearest and bilinear lookups on a
 * picture small enough to work out by hand, the errors of a missing or broken image, and agreement with
 * POV-Ray on procedural and image-mapped scenes. */
#include <criterion/criterion.h>
#include <math.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_map.h"
#include "mesh_load.h"
#include "mesh_surface.h"
#include "image_test_support.h"
#include "scene.h"
#include "test_support.h"
#include "texture.h"

#define SCENE_HEAD "camera eye 0 0 5 target 0 0 0 fov 40\nimage 64 48\n"
#define PIGMENTS_SCENE "tests/data/textures/pigments.scene"
#define IMAGES_SCENE "tests/data/textures/images.scene"

/* ---- the pigment line ------------------------------------------------------------------------------ */

/* Parses SCENE_HEAD followed by `lines`; returns whether it parsed, the scene in *s and the message. */
static bool parse_lines(const char *lines, struct scene *s, char *err, size_t err_size) {
    char text[1024];
    snprintf(text, sizeof text, SCENE_HEAD "%s\n", lines);
    return scene_parse("tex.scene", text, NULL, s, err, err_size);
}

static void expect_refused(const char *lines, const char *message) {
    struct scene s;
    char err[512] = "";
    cr_expect(!parse_lines(lines, &s, err, sizeof err), "'%s' was accepted", lines);
    cr_expect_str_eq(err, message, "for '%s'", lines);
}

Test(pigment_line, keys_transform_and_povrays_brick_defaults_are_read) {
    struct scene s;
    char err[512] = "";
    cr_assert(parse_lines("pigment b brick colour 1 1 1 colour2 0.5 0 0 rotate 0 90 0\n"
                          "pigment g gradient axis 0 2 0 colour 0 0 0 colour2 1 1 1 scale 2 2 2 translate 1 0 0\n"
                          "material m pigment g diffuse 0.5",
                          &s, err, sizeof err),
              "%s", err);
    cr_assert_eq(s.pigment_count, 2);
    const struct pigment *b = &s.pigments[0], *g = &s.pigments[1];
    cr_expect_eq(b->pattern, PIGMENT_BRICK);
    cr_expect(b->brick_size.x == 8 && b->brick_size.y == 3 && b->brick_size.z == 4.5, "POV-Ray's brick_size");
    cr_expect_eq(b->mortar, 0.5);
    cr_expect(b->scale.x == 1 && b->scale.y == 1 && b->scale.z == 1 && b->rotate.y == 90 && b->translate.x == 0);
    cr_expect_eq(b->line, 3);
    cr_expect(g->axis.x == 0 && g->axis.y == 1 && g->axis.z == 0, "the axis is normalised, as POV-Ray does");
    cr_expect(g->scale.x == 2 && g->translate.x == 1);
    cr_expect_eq(s.materials[1].pigment, 1);
    cr_expect_eq(s.materials[0].pigment, -1, "the default material is plain");
    scene_free(&s);
    /* an axis whose length would overflow or vanish when squared keeps its direction */
    cr_assert(parse_lines("pigment h gradient axis 1e200 1e200 0 colour 0 0 0 colour2 1 1 1\n"
                          "pigment t gradient axis 0 0 -1e-200 colour 0 0 0 colour2 1 1 1\n"
                          "pigment u gradient axis 1e-310 0 0 colour 0 0 0 colour2 1 1 1",
                          &s, err, sizeof err),
              "%s", err);
    cr_expect(fabs(s.pigments[0].axis.x - sqrt(0.5)) < 1e-15 && fabs(s.pigments[0].axis.y - sqrt(0.5)) < 1e-15 &&
                  s.pigments[0].axis.z == 0,
              "axis 1e200 1e200 0 became %g %g %g", s.pigments[0].axis.x, s.pigments[0].axis.y, s.pigments[0].axis.z);
    cr_expect(s.pigments[1].axis.x == 0 && s.pigments[1].axis.y == 0 && s.pigments[1].axis.z == -1,
              "axis 0 0 -1e-200 became %g %g %g", s.pigments[1].axis.x, s.pigments[1].axis.y, s.pigments[1].axis.z);
    /* subnormal: 1 / 1e-310 is infinite, and scaling by it once gave a NaN axis (another picture) */
    cr_expect(s.pigments[2].axis.x == 1 && s.pigments[2].axis.y == 0 && s.pigments[2].axis.z == 0,
              "axis 1e-310 0 0 became %g %g %g", s.pigments[2].axis.x, s.pigments[2].axis.y, s.pigments[2].axis.z);
    scene_free(&s);
}

Test(pigment_line, bad_values_are_refused_with_file_and_line) {
    expect_refused("pigment p", "tex.scene:3: pigment needs a name and a pattern");
    expect_refused("pigment p marble colour 1 1 1",
                   "tex.scene:3: unknown pattern 'marble' (checker, gradient, brick, radial or image_map)");
    expect_refused("pigment p checker colour 1 1 1", "tex.scene:3: pigment needs 'colour2'");
    expect_refused("pigment p checker colour 1 1 1 colour2 0 0 0 axis 0 1 0", "tex.scene:3: unknown key 'axis' for pigment");
    expect_refused("pigment p checker colour -1 1 1 colour2 0 0 0", "tex.scene:3: pigment 'p': colour must not be negative");
    expect_refused("pigment p gradient axis 0 0 0 colour 1 1 1 colour2 0 0 0", "tex.scene:3: pigment 'p': axis must not be 0 0 0");
    expect_refused("pigment p radial colour 1 1 1 colour2 0 0 0 scale 1 0 1",
                   "tex.scene:3: pigment 'p': scale must not be 0 along any axis");
    expect_refused("pigment p brick colour 1 1 1 colour2 0 0 0 mortar -0.1", "tex.scene:3: pigment 'p': mortar must not be negative");
    /* a brick or mortar beyond a scale's range made every point brick: a black picture with exit 0 */
    expect_refused("pigment p brick colour 1 1 1 colour2 0 0 0 mortar 1e39",
                   "tex.scene:3: pigment 'p': mortar 1e+39 is out of range (at most 1e+09)");
    expect_refused("pigment p brick colour 1 1 1 colour2 0 0 0 brick_size 1 1e-10 1",
                   "tex.scene:3: pigment 'p': brick_size 1e-10 is out of range (each side from 1e-09 to 1e+09)");
    expect_refused("pigment p brick colour 1 1 1 colour2 0 0 0 brick_size 1 1 2e9",
                   "tex.scene:3: pigment 'p': brick_size 2000000000 is out of range (each side from 1e-09 to 1e+09)");
    expect_refused("pigment p image_map file a.png interpolate 1",
                   "tex.scene:3: pigment 'p': interpolate must be 0 (nearest) or 2 (bilinear), got 1");
    expect_refused("pigment p image_map file a.png map cylindrical",
                   "tex.scene:3: pigment 'p': map must be planar, spherical or uv, got 'cylindrical'");
    expect_refused("pigment p image_map file a.png wrap mirror", "tex.scene:3: pigment 'p': wrap must be repeat or once, got 'mirror'");
    expect_refused("pigment p image_map map planar", "tex.scene:3: pigment needs 'file'");
    expect_refused("pigment p image_map file a\"b.png",
                   "tex.scene:3: pigment 'p': the file name must not hold a quote or a backslash");
    expect_refused("pigment p radial colour 1 1 1 colour2 0 0 0\npigment p radial colour 1 1 1 colour2 0 0 0",
                   "tex.scene:4: pigment 'p' is already defined");
    expect_refused("material m pigment q", "tex.scene:3: unknown pigment 'q' (define it with a pigment line first)");
}

Test(pigment_line, chapters_before_14_ignore_pigments_and_draw_the_plain_colour, .timeout = 60) {
    expect_chapter_run(12, PIGMENTS_SCENE " --quiet --pov " TEST_OUT "/tex-12.pov", 0, "");
    char *twin = read_text_file(TEST_OUT "/tex-12.pov");
    cr_expect_null(strstr(twin, "checker"), "chapter 12's twin carries a pigment");
    free(twin);
    expect_chapter_run(12, PIGMENTS_SCENE " -o " TEST_OUT "/tex-12.png", 0,
                       PIGMENTS_SCENE ": chapter 12 ignores 4 pigments (not introduced yet)");
}

/* ---- the patterns ---------------------------------------------------------------------------------- */

/* A pigment of the pattern with the identity transform. */
static struct pigment plain(enum pigment_pattern pattern) {
    return (struct pigment){.pattern = pattern, .colour = {{0, 0, 0}, {1, 1, 1}}, .axis = {0, 1, 0},
                            .brick_size = {8, 3, 4.5}, .mortar = 0.5, .scale = {1, 1, 1}};
}

Test(texture, checker_alternates_and_counts_a_point_just_below_a_boundary_on_the_upper_side) {
    struct pigment p = plain(PIGMENT_CHECKER);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(0.5, 0.5, 0.5)), 0.0);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(1.5, 0.5, 0.5)), 1.0);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(1.5, -0.5, 0.5)), 0.0);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(-0.5, 0.5, 0.5)), 1.0);
    /* A floor at y = 0 hit at y = -1e-12 (rounding) is still the cube above: POV-Ray adds 1e-10. */
    cr_expect_eq(texture_pattern_value(&p, vec3_make(0.5, -1e-12, 0.5)), 0.0);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(0.5, -1e-9, 0.5)), 1.0);
}

Test(texture, gradient_folds_its_value_as_povray_does) {
    struct pigment p = plain(PIGMENT_GRADIENT);
    cr_expect_float_eq(texture_pattern_value(&p, vec3_make(0, 0.25, 0)), 0.25, 1e-12);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(0, 1.0, 0)), 1.0, "1 stays 1 (colour2), not 0");
    cr_expect_float_eq(texture_pattern_value(&p, vec3_make(0, 1.5, 0)), 0.5, 1e-12);
    cr_expect_float_eq(texture_pattern_value(&p, vec3_make(0, -0.25, 0)), 0.75, 1e-12);
    /* Below -1 the fold is by 1.00001, POV-Ray's own figure: -2.3 + 2 * 1.00001 + 1. */
    cr_expect_float_eq(texture_pattern_value(&p, vec3_make(0, -2.3, 0)), 0.70002, 1e-12);
    struct texture_colour c = texture_pigment_at(&p, vec3_make(0, 0.25, 0));
    cr_expect_float_eq(c.colour.x, 0.25, 1e-12, "the colour map blends linearly");
}

Test(texture, radial_turns_once_round_y_from_plus_x) {
    struct pigment p = plain(PIGMENT_RADIAL);
    cr_expect_float_eq(texture_pattern_value(&p, vec3_make(0, 0, 1)), 0.75, 1e-12);
    cr_expect_float_eq(texture_pattern_value(&p, vec3_make(-1, 0, 0)), 0.5, 1e-12);
    /* Straight behind, 1.25 folds by 1.00001 to 0.24999, a hair short of the 0.25 on the other side. */
    cr_expect_float_eq(texture_pattern_value(&p, vec3_make(0, 0, -1)), 0.24999, 1e-12);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(1, 0, 0)), 1.0);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(0.0005, 7, 0.0005)), 0.25, "on the axis: POV-Ray's 0.25");
}

Test(texture, brick_has_mortar_between_rows_and_staggered_ends) {
    struct pigment p = plain(PIGMENT_BRICK);
    cr_expect_eq(texture_pattern_value(&p, vec3_make(1, 1.5, 1)), 1.0, "inside a brick");
    cr_expect_eq(texture_pattern_value(&p, vec3_make(1, 2.9, 1)), 0.0, "the mortar under the next row");
    cr_expect_eq(texture_pattern_value(&p, vec3_make(7.8, 1.5, 1)), 0.0, "the end of a brick of the first row");
    cr_expect_eq(texture_pattern_value(&p, vec3_make(7.8, 4.5, 1)), 1.0, "the next row is shifted by half a brick");
    cr_expect_eq(texture_pattern_value(&p, vec3_make(3.8, 4.5, 1)), 0.0, "its ends are half way along");
}

Test(texture, texture_space_undoes_scale_then_rotate_then_translate) {
    struct pigment p = plain(PIGMENT_CHECKER);
    p.scale = vec3_make(2, 3, 4);
    p.rotate = vec3_make(30, 45, 60);
    p.translate = vec3_make(1, -2, 3);
    vec3 world = vec3_make(0.3 * 2, -0.7 * 3, 1.1 * 4); /* scaled, then turned and moved as a mesh is */
    struct mesh m = {.vertices = &world, .vertex_count = 1};
    mesh_transform(&m, 1.0, p.rotate, p.translate);
    vec3 back = texture_space(&p, world);
    cr_expect_float_eq(back.x, 0.3, 1e-12);
    cr_expect_float_eq(back.y, -0.7, 1e-12);
    cr_expect_float_eq(back.z, 1.1, 1e-12);
}

/* ---- image maps ------------------------------------------------------------------------------------ */

Test(image_map, srgb_decoding_is_povrays_curve) {
    cr_expect_eq(image_map_decode_srgb(0.0f), 0.0f);
    cr_expect_float_eq(image_map_decode_srgb(1.0f), 1.0f, 1e-6);
    cr_expect_float_eq(image_map_decode_srgb(0.5f), 0.21404f, 1e-5, "mid grey in the file is 21 %% light");
    cr_expect_float_eq(image_map_decode_srgb(0.04f), 0.04f / 12.92f, 1e-9, "the linear toe");
}

/* Appends a PNG chunk (with a dummy CRC, which image_map_png_gamma does not check) to bytes at *at. */
static void chunk(uint8_t *bytes, size_t *at, const char *type, const uint8_t *data, uint32_t length) {
    uint8_t *b = bytes + *at;
    b[0] = 0, b[1] = 0, b[2] = (uint8_t)(length >> 8), b[3] = (uint8_t)length;
    memcpy(b + 4, type, 4);
    memcpy(b + 8, data, length);
    memset(b + 8 + length, 0, 4);
    *at += 12 + length;
}

Test(image_map, png_chunks_choose_the_curve_as_povray_does) {
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const uint8_t header[13] = {0}, gamma[4] = {0, 0, 0xb1, 0x8f} /* 45455 */, srgb[1] = {0};
    uint8_t bytes[256];
    size_t at = 8;
    memcpy(bytes, signature, 8);
    chunk(bytes, &at, "IHDR", header, 13);
    cr_expect_eq(image_map_png_gamma(bytes, at), 0.0, "no chunk: sRGB, as the PNG recommendation says");
    chunk(bytes, &at, "gAMA", gamma, 4);
    cr_expect_float_eq(image_map_png_gamma(bytes, at), 0.45455, 1e-12, "gAMA alone: its power law");
    size_t with_gamma = at;
    chunk(bytes, &at, "sRGB", srgb, 1);
    cr_expect_eq(image_map_png_gamma(bytes, at), 0.0, "an sRGB chunk wins");
    at = with_gamma;
    chunk(bytes, &at, "IDAT", srgb, 1);
    chunk(bytes, &at, "sRGB", srgb, 1);
    cr_expect_float_eq(image_map_png_gamma(bytes, at), 0.45455, 1e-12, "chunks after the image data do not count");
    cr_expect_eq(image_map_png_gamma((const uint8_t *)"GIF89a", 6), 0.0);
}

/* A 2 x 2 picture: top row red, green; bottom row blue, white (alpha 1, then 0.5 for white). */
static struct pigment two_by_two(int interpolate, bool once) {
    static float texels[16] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 0.5f};
    struct pigment p = plain(PIGMENT_IMAGE_MAP);
    p.mapping = PIGMENT_MAP_PLANAR;
    p.interpolate = interpolate;
    p.once = once;
    p.image = (struct pigment_image){.width = 2, .height = 2, .texels = texels};
    return p;
}

Test(image_map, nearest_takes_the_pixel_the_point_falls_in_with_v_up) {
    struct pigment p = two_by_two(0, false);
    double rgba[4];
    cr_assert(image_map_lookup(&p, vec3_make(0.25, 0.75, 0), rgba));
    cr_expect(rgba[0] == 1 && rgba[1] == 0 && rgba[2] == 0, "top left is red");
    image_map_lookup(&p, vec3_make(0.25, 0.25, 0), rgba);
    cr_expect(rgba[2] == 1 && rgba[0] == 0, "bottom left is blue: v runs up, rows down");
    image_map_lookup(&p, vec3_make(1.75, 0.25, 0), rgba);
    cr_expect(rgba[0] == 1 && rgba[1] == 1 && rgba[3] == 0.5, "repeated: bottom right is white, half transparent");
    struct texture_colour c = texture_pigment_at(&p, vec3_make(0.75, 0.25, 5));
    cr_expect_float_eq(c.transmit, 0.5, 1e-12, "alpha 0.5 lets half the light through");
}

Test(image_map, bilinear_blends_the_four_pixel_centres_around_the_point) {
    struct pigment p = two_by_two(2, false);
    double rgba[4];
    image_map_lookup(&p, vec3_make(0.5, 0.5, 0), rgba); /* the middle: a quarter of each */
    cr_expect_float_eq(rgba[0], 0.5, 1e-9);
    cr_expect_float_eq(rgba[1], 0.5, 1e-9);
    cr_expect_float_eq(rgba[2], 0.5, 1e-9);
    image_map_lookup(&p, vec3_make(0.25, 0.75, 0), rgba); /* the centre of the red pixel */
    cr_expect_float_eq(rgba[0], 1.0, 1e-8);
    cr_expect_float_eq(rgba[1], 0.0, 1e-8);
}

Test(image_map, once_shows_one_copy_and_nothing_around_it) {
    struct pigment p = two_by_two(0, true);
    double rgba[4];
    cr_expect(image_map_lookup(&p, vec3_make(0.5, 0.5, 0), rgba));
    cr_expect(!image_map_lookup(&p, vec3_make(1.5, 0.5, 0), rgba));
    cr_expect(rgba[3] == 0.0, "outside: fully transparent");
    cr_expect(!image_map_lookup(&p, vec3_make(0.5, -0.1, 0), rgba));
}

Test(image_map, spherical_map_puts_longitude_0_at_x_and_the_north_at_the_top) {
    struct pigment p = two_by_two(0, false);
    p.mapping = PIGMENT_MAP_SPHERICAL;
    double rgba[4];
    image_map_lookup(&p, vec3_make(1, 0.5, 0.01), rgba); /* u just above 0, v above the equator */
    cr_expect(rgba[0] == 1 && rgba[1] == 0, "north of longitude 0: the top left pixel, red");
    image_map_lookup(&p, vec3_make(-1, -0.5, -0.01), rgba); /* u just under 1/2... past it */
    cr_expect(rgba[0] == 1 && rgba[1] == 1, "south, longitude just past 180: bottom right, white");
}

/* Reads a 2 x 1 PNG written with `channels` channels from `pixels`; returns image.opaque. */
static bool read_opaque(const char *name, int channels, const uint8_t *pixels) {
    char path[256], why[512] = "";
    snprintf(path, sizeof path, TEST_OUT "/%s", name);
    cr_assert(stbi_write_png(path, 2, 1, channels, pixels, 2 * channels), "cannot write %s", path);
    struct pigment_image image;
    cr_assert(image_map_read(path, &image, why, sizeof why), "%s", why);
    free(image.texels);
    return image.opaque;
}

Test(image_map, a_picture_is_opaque_when_every_alpha_is_the_largest) {
    static const uint8_t rgb[6] = {10, 20, 30, 40, 50, 60}, full[8] = {10, 20, 30, 255, 40, 50, 60, 255},
                         one_less[8] = {10, 20, 30, 255, 40, 50, 60, 254};
    cr_expect(read_opaque("opaque-rgb.png", 3, rgb), "no alpha channel");
    cr_expect(read_opaque("opaque-rgba.png", 4, full), "alpha everywhere 255");
    cr_expect(!read_opaque("see-through.png", 4, one_less), "one alpha of 254");
}

Test(image_map, missing_and_broken_images_name_the_pigment_line, .timeout = 60) {
    FILE *f = fopen(TEST_OUT "/tex-broken.scene", "w");
    cr_assert_not_null(f);
    fprintf(f, SCENE_HEAD "pigment p image_map file no-such.png\nmaterial m pigment p\n");
    fclose(f);
    expect_chapter_run(14, TEST_OUT "/tex-broken.scene -o " TEST_OUT "/tex-broken.png", 1,
                       TEST_OUT "/tex-broken.scene:3: pigment 'p': " TEST_OUT "/no-such.png: cannot open: No such file or directory");
    f = fopen(TEST_OUT "/tex-broken.scene", "w");
    cr_assert_not_null(f);
    fprintf(f, SCENE_HEAD "pigment p image_map file tex-broken.scene\n");
    fclose(f);
    expect_chapter_run(14, TEST_OUT "/tex-broken.scene -o " TEST_OUT "/tex-broken.png", 1,
                       TEST_OUT "/tex-broken.scene:3: pigment 'p': " TEST_OUT "/tex-broken.scene: not a PNG or JPEG image (");
}

/* Reads the PNG written with `channels` channels of `count` pixels into TEST_OUT/name; returns its texels
 * (free them). */
static float *read_written(const char *name, int channels, int count, const uint8_t *pixels) {
    char path[256], why[512] = "";
    snprintf(path, sizeof path, TEST_OUT "/%s", name);
    cr_assert(stbi_write_png(path, count, 1, channels, pixels, count * channels), "cannot write %s", path);
    struct pigment_image image;
    cr_assert(image_map_read(path, &image, why, sizeof why), "%s", why);
    return image.texels;
}

/* POV-Ray 3.7 stores an 8-bit grey PNG as whole 255ths of linear light, the fraction cut off; an RGB
 * file of the same levels keeps the decoded value (docs/povray.md, "Image maps"). */
Test(image_map, a_grey_png_keeps_whole_255ths_of_linear_light_as_povray_does) {
    static const uint8_t grey[3] = {10, 128, 255}, rgb[9] = {10, 10, 10, 128, 128, 128, 255, 255, 255};
    float *g = read_written("grey-levels.png", 1, 3, grey), *c = read_written("rgb-levels.png", 3, 3, rgb);
    for (int k = 0; k < 3; k++) {
        float decoded = image_map_decode_srgb(grey[k] / 255.0f);
        cr_expect_float_eq(c[4 * k], decoded, 1e-7, "RGB level %d: decoded, kept whole", grey[k]);
        cr_expect_eq(g[4 * k], floorf(decoded * 255.0f) / 255.0f, "grey level %d: %.7f, cut to %.7f", grey[k],
                     decoded, g[4 * k]);
        cr_expect_eq(g[4 * k], g[4 * k + 1], "grey: red and green alike");
        cr_expect_eq(g[4 * k + 3], 1.0f, "grey: opaque");
    }
    cr_expect_eq(g[0], 0.0f, "level 10 is 0.0030 of linear light: under one 255th, cut to black");
    cr_expect_gt(c[0], 0.003f);
    free(g);
    free(c);
}

/* ---- agreement with POV-Ray ----------------------------------------------------------------------- */

/* Renders `scene` with chapter 14 and with POV-Ray; expects 99.99 % of pixels within one level. */
static void expect_agreement(const char *tag, const char *scene) {
    char ours[256], theirs[256], what[128];
    snprintf(ours, sizeof ours, TEST_OUT "/tex-%s-ours.png", tag);
    snprintf(theirs, sizeof theirs, TEST_OUT "/tex-%s-povray.png", tag);
    cr_assert_eq(render_chapter(14, scene, ours, ""), 0, "chapter 14 failed on %s", scene);
    cr_assert(render_povray(14, scene, theirs), "POV-Ray failed on the twin of %s", scene);
    struct image_difference d = compare_png(ours, theirs);
    snprintf(what, sizeof what, "chapter 14 %s vs POV-Ray", tag);
    report_difference(what, &d);
    cr_expect_geq(d.within_1, 0.9999, "%s: %.4f %% of pixels within 1 level of POV-Ray, max %d", tag,
                  100 * d.within_1, d.max);
}

Test(povray_agreement, chapter_14_checker_gradient_brick_and_radial, .timeout = 120) {
    expect_agreement("pigments", PIGMENTS_SCENE);
}

Test(povray_agreement, chapter_14_image_maps_nearest_bilinear_once_and_jpeg, .timeout = 120) {
    expect_agreement("images", IMAGES_SCENE);
}

/* A palette PNG whose tRNS chunk makes colours clear, on materials that let no light through themselves:
 * the twin wrote `filter all 0 transmit all 0`, which in POV-Ray replaces each palette colour's own
 * transparency, so its cards were opaque (80.6 % of the pixels within 2 levels). */
Test(povray_agreement, chapter_14_a_palette_pictures_clear_colours, .timeout = 120) {
    expect_agreement("palette-alpha", "tests/data/textures/palette-alpha.scene");
}

/* Opaque materials with an ior under pictures with clear parts (alpha, a `wrap once` decal): light passes
 * there and bends, so the twin needs the interior it gave only to materials with filter or transmit
 * (a decal on a thick block: 65 % of the pixels within 2 levels). */
Test(povray_agreement, chapter_14_clear_parts_of_pictures_bend_light_by_the_ior, .timeout = 120) {
    expect_agreement("clear-parts-ior", "tests/data/textures/clear-parts-ior.scene");
}

/* A floor on a gradient's boundary (tests/data/textures/gradient-on-its-boundary.scene): every pixel of
 * it turns on the last bits of its camera ray. With the window's vectors scaled after x and y (chapter 1's
 * order before 2 December 2026), 2.4 % of the pixels took the other colour from POV-Ray's. */
Test(povray_agreement, chapter_14_a_floor_on_a_gradients_boundary_takes_povrays_rays_to_the_bit, .timeout = 120) {
    expect_agreement("gradient-boundary", "tests/data/textures/gradient-on-its-boundary.scene");
}

/* Pictures POV-Ray 3.7 draws otherwise: the twin is refused with the reason (exit 1), and the picture is
 * still drawn. */
Test(povray_export, twins_of_pictures_povray_draws_otherwise_are_refused) {
    const struct {
        const char *scene, *message;
    } rows[] = {
        {"twin-colour-key", "twin-colour-key.scene:6: pigment 'key': its picture is a grey or RGB PNG with a "
                            "transparent colour (a tRNS chunk), which POV-Ray 3.7 draws opaque (and, in a grey file, "
                            "crashes on), so the twin would differ"},
        {"twin-uv-sphere", "twin-uv-sphere.scene:7: material 'm' (pigment 'p', map uv) is on a sphere, which has no "
                           "surface coordinates here (it is painted at (0, 0)) and has others in POV-Ray, so the twin "
                           "would differ"},
        {"twin-alpha-transmit", "twin-alpha-transmit.scene:8: material 'card': its picture (pigment 'p') has alpha "
                                "below 1 and the material lets light through as well (filter or transmit); POV-Ray "
                                "adds the two without a limit, we keep their sum at most 1, so the twin would differ"},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        char arguments[512], png[256];
        snprintf(arguments, sizeof arguments, "tests/data/textures/%s.scene --pov " TEST_OUT "/%s.pov", rows[k].scene,
                 rows[k].scene);
        expect_chapter_run(14, arguments, 1, rows[k].message);
        char scene[256];
        snprintf(scene, sizeof scene, "tests/data/textures/%s.scene", rows[k].scene);
        snprintf(png, sizeof png, TEST_OUT "/%s.png", rows[k].scene);
        cr_expect_eq(render_chapter(14, scene, png, ""), 0, "%s is drawn", scene);
    }
}

/* ---- smooth meshes and texture coordinates -------------------------------------------------------- */

#define QUAD_OBJ "tests/data/textures/quad.obj"
#define SMOOTH_SCENE "tests/data/textures/smooth.scene"

/* Writes `text` to TEST_OUT/NAME and returns the path. */
static const char *write_file(const char *name, const char *text) {
    static char path[256];
    snprintf(path, sizeof path, TEST_OUT "/%s", name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f, "cannot write %s", path);
    fputs(text, f);
    fclose(f);
    return path;
}

/* A grey ramp of every level 0 to 255, one column each, as an 8-bit grey PNG on a card facing the camera
 * (ambient 1: the picture shows the map's light itself). A PNG's grey levels are kept as POV-Ray keeps
 * them (truncated to 255ths of linear light), so the two pictures agree to the level; before that rule
 * 27 of the ramp's 256 columns came out one level brighter than POV-Ray's. */
Test(povray_agreement, chapter_14_grey_png_image_map_to_the_level, .timeout = 120) {
    uint8_t ramp[256 * 4];
    for (int k = 0; k < 256 * 4; k++)
        ramp[k] = (uint8_t)(k % 256);
    cr_assert(stbi_write_png(TEST_OUT "/grey-ramp.png", 256, 4, 1, ramp, 256), "cannot write the ramp");
    write_file("grey-ramp.scene",
               "camera eye 0 0 10  target 0 0 0  fov 30\nimage 256 64\n"
               "pigment ramp image_map file grey-ramp.png interpolate 0 scale 4 1 1 translate -2 -0.5 0\n"
               "material card pigment ramp ambient 1 diffuse 0\n"
               "box min -2 -0.5 -0.01 max 2 0.5 0 material card\n");
    char ours[256], theirs[256];
    snprintf(ours, sizeof ours, TEST_OUT "/tex-grey-ours.png");
    snprintf(theirs, sizeof theirs, TEST_OUT "/tex-grey-povray.png");
    cr_assert_eq(render_chapter(14, TEST_OUT "/grey-ramp.scene", ours, ""), 0, "chapter 14 failed on the ramp");
    cr_assert(render_povray(14, TEST_OUT "/grey-ramp.scene", theirs), "POV-Ray failed on the ramp's twin");
    struct image_difference d = compare_png(ours, theirs);
    report_difference("chapter 14 grey ramp vs POV-Ray", &d);
    cr_expect_eq(d.max, 0, "the grey ramp differs from POV-Ray's by up to %d levels (%.4f %% of pixels within 1)",
                 d.max, 100 * d.within_1);
}

/* Busy JPEGs (a pattern that changes every texel) on a card, as POV-Ray draws them: to the level. POV-Ray
 * decodes a JPEG with libjpeg, and we in its arithmetic (common/jpeg_decode.c); decoded by stb_image, such
 * a picture differed in 1 to 3 levels from libjpeg's in 5 to 7 % of its values, colour kept at half
 * resolution (4:2:0, stb's writer below quality 90) or not (4:4:4), and grey ones too. */
Test(povray_agreement, chapter_14_busy_jpeg_image_maps_to_the_level, .timeout = 120) {
    enum { W = 48, H = 32 };
    static uint8_t texels[W * H * 3];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint8_t *t = texels + 3 * (y * W + x);
            t[0] = (uint8_t)(127 + 127 * sin(x * 0.7 + y * 0.3));
            t[1] = (uint8_t)(127 + 127 * cos(x * 0.2 - y * 0.9));
            t[2] = (uint8_t)((x * 37 + y * 91) % 256);
        }
    static const struct {
        const char *name;
        int channels, quality;
    } kinds[] = {{"busy-420", 3, 80}, {"busy-444", 3, 95}, {"busy-grey", 1, 85}};
    for (int k = 0; k < 3; k++) {
        char jpeg[256], scene[256], text[512], ours[256], theirs[256];
        snprintf(jpeg, sizeof jpeg, TEST_OUT "/%s.jpg", kinds[k].name);
        uint8_t grey[W * H];
        for (int i = 0; i < W * H; i++)
            grey[i] = texels[3 * i];
        cr_assert(stbi_write_jpg(jpeg, W, H, kinds[k].channels, kinds[k].channels == 1 ? grey : texels,
                                 kinds[k].quality), "cannot write %s", jpeg);
        snprintf(text, sizeof text, "camera eye 0 0 10  target 0 0 0  fov 15\nimage 192 128\n"
                 "pigment busy image_map file %s.jpg interpolate 0 scale 3 2 1 translate -1.5 -1 0\n"
                 "material card pigment busy ambient 1 diffuse 0\nbox min -1.5 -1 -0.01 max 1.5 1 0 material card\n",
                 kinds[k].name);
        snprintf(scene, sizeof scene, "%s.scene", kinds[k].name);
        write_file(scene, text);
        snprintf(scene, sizeof scene, TEST_OUT "/%s.scene", kinds[k].name);
        snprintf(ours, sizeof ours, TEST_OUT "/tex-%s-ours.png", kinds[k].name);
        snprintf(theirs, sizeof theirs, TEST_OUT "/tex-%s-povray.png", kinds[k].name);
        cr_assert_eq(render_chapter(14, scene, ours, ""), 0, "chapter 14 failed on %s", scene);
        cr_assert(render_povray(14, scene, theirs), "POV-Ray failed on %s's twin", scene);
        struct image_difference d = compare_png(ours, theirs);
        cr_expect_eq(d.max, 0, "%s: the card differs from POV-Ray's by up to %d levels (%.4f %% of pixels within 1)",
                     kinds[k].name, d.max, 100 * d.within_1);
    }
}

/* Loads the mesh text `text` (written to TEST_OUT/NAME) with its corners; expects failure with
 * `message` after the path, or success when message is NULL. */
static void expect_mesh(const char *name, const char *text, const char *message) {
    const char *path = write_file(name, text);
    struct mesh m;
    struct mesh_corners c;
    char err[512] = "", expected[512];
    bool ok = mesh_load_with_corners(path, &m, &c, err, sizeof err);
    if (message == NULL) {
        cr_expect(ok, "%s", err);
    } else {
        snprintf(expected, sizeof expected, "%s%s", path, message);
        cr_expect(!ok, "%s loaded", name);
        cr_expect_str_eq(err, expected);
        cr_expect_null(c.normals, "a failed load leaves no normals");
    }
    mesh_free(&m);
    mesh_corners_free(&c);
}

Test(mesh_surface, obj_corners_number_texture_coordinates_and_normals_apart) {
    struct mesh m;
    struct mesh_corners c;
    char err[512] = "";
    cr_assert(mesh_load_with_corners(QUAD_OBJ, &m, &c, err, sizeof err), "%s", err);
    cr_assert_eq(m.face_count, 2, "the quad is a fan of two triangles");
    cr_expect_eq(c.uv_count, 4);
    cr_expect_eq(c.normal_count, 4);
    cr_assert_not_null(c.uv_faces);
    cr_assert_not_null(c.normal_faces);
    cr_expect(c.uv_faces[1].v[0] == 0 && c.uv_faces[1].v[1] == 2 && c.uv_faces[1].v[2] == 3);
    cr_expect(c.normal_faces[1].v[2] == 3 && c.uvs[2].u == 1 && c.uvs[2].v == 1 && c.normals[0].x == -0.4);
    mesh_free(&m);
    mesh_corners_free(&c);
    /* Without the corners (chapters 3 to 12), vt and vn are read past as before. */
    cr_assert(mesh_load(QUAD_OBJ, &m, err, sizeof err), "%s", err);
    mesh_free(&m);
}

Test(mesh_surface, bad_corners_are_refused_with_file_and_line) {
    static const char *const base = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    char text[512];
    snprintf(text, sizeof text, "%sf 1/1/1 2/1/1 3/5/1\n", base);
    expect_mesh("bad-vt.obj", text, ":6: vt index 5 out of range (1 texture coordinates)");
    snprintf(text, sizeof text, "%sf 1//1 2//1 3//9\n", base);
    expect_mesh("bad-vn.obj", text, ":6: vn index 9 out of range (1 normals)");
    snprintf(text, sizeof text, "%sf 1//-2 2//1 3//1\n", base);
    expect_mesh("bad-vn-back.obj", text, ":6: vn index -2 reaches before the first normal (1 normals so far)");
    snprintf(text, sizeof text, "%sf 1//1 2//1 3\n", base);
    expect_mesh("mixed.obj", text, ":6: corner '3' has no normal index and earlier corners do");
    snprintf(text, sizeof text, "%sf 1 2 3\nf 1/1 2/1 3/1\n", base);
    expect_mesh("mixed-vt.obj", text, ":7: corner '1/1' gives a texture coordinate index and earlier corners do not");
    expect_mesh("half-normal.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                "property float nx\nproperty float ny\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n",
                ":3: element vertex has nx but no nz");
    expect_mesh("half-uv.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                "property float s\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0 0\n1 0 0 0\n0 1 0 0\n3 0 1 2\n",
                ":3: element vertex has u but no v");
    expect_mesh("uv.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                "property float texture_u\nproperty float texture_v\nelement face 1\n"
                "property list uchar int vertex_indices\nend_header\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n",
                NULL);
}

Test(mesh_surface, weights_blend_and_the_blended_normal_is_unit_length) {
    double w[3];
    mesh_surface_weights(vec3_make(0, 0, 0), vec3_make(2, 0, 0), vec3_make(0, 2, 0), vec3_make(0.5, 1, 0), w);
    cr_expect_float_eq(w[0], 0.25, 1e-12);
    cr_expect_float_eq(w[1], 0.25, 1e-12);
    cr_expect_float_eq(w[2], 0.5, 1e-12);
    vec3 vertices[3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, normals[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    struct mesh_face face = {{0, 1, 2}};
    struct scene_mesh sm = {.mesh = {.vertices = vertices, .vertex_count = 3, .faces = &face, .face_count = 1},
                            .corners = {.normals = normals, .normal_count = 3, .normal_faces = &face}};
    vec3 n;
    cr_assert(mesh_surface_normal(&sm, 0, vec3_make(2.0 / 3, 2.0 / 3, 0), &n));
    cr_expect_float_eq(vec3_length(n), 1.0, 1e-12, "renormalised: the plain blend is 1/sqrt(3) long");
    cr_expect_float_eq(n.x, 1 / sqrt(3.0), 1e-12);
    cr_expect(mesh_surface_normal(&sm, 0, vec3_make(0, 0, 0), &n) && n.x == 1.0, "at a corner, its own normal");
}

Test(mesh_surface, averaged_normals_weigh_each_face_by_its_area) {
    /* Two faces meet at vertices 0 and 1: a large one in the x-y plane and a small one in x-z. */
    vec3 vertices[4] = {{0, 0, 0}, {1, 0, 0}, {0, 3, 0}, {0, 0, -1}};
    struct mesh_face faces[2] = {{{0, 1, 2}}, {{0, 1, 3}}};
    struct mesh m = {.vertices = vertices, .vertex_count = 4, .faces = faces, .face_count = 2};
    struct mesh_corners c = {0};
    cr_assert(mesh_surface_average_normals(&m, &c));
    cr_expect_float_eq(c.normals[2].z, 1.0, 1e-12, "a vertex of one face takes its normal");
    cr_expect_float_eq(c.normals[3].y, 1.0, 1e-12);
    cr_expect_float_eq(c.normals[0].z / c.normals[0].y, 3.0, 1e-12, "the larger face weighs three times more");
    mesh_corners_free(&c);
}

Test(mesh_surface, chapters_before_14_draw_meshes_flat_and_the_twin_says_so, .timeout = 60) {
    expect_chapter_run(12, SMOOTH_SCENE " --quiet --pov " TEST_OUT "/smooth-12.pov", 0, "");
    char *twin = read_text_file(TEST_OUT "/smooth-12.pov");
    cr_expect_null(strstr(twin, "normal_vectors"), "chapter 12's twin has smooth meshes");
    free(twin);
    expect_chapter_run(14, SMOOTH_SCENE " --quiet --pov " TEST_OUT "/smooth-14.pov", 0, "");
    twin = read_text_file(TEST_OUT "/smooth-14.pov");
    cr_expect_not_null(strstr(twin, "normal_vectors"), "chapter 14's twin has no smooth meshes");
    cr_expect_not_null(strstr(twin, "uv_indices"));
    free(twin);
    write_file("bad-smooth.scene", SCENE_HEAD "mesh quad.obj smooth yes\n");
    expect_chapter_run(14, TEST_OUT "/bad-smooth.scene -o " TEST_OUT "/bad.png", 1,
                       TEST_OUT "/bad-smooth.scene:3: mesh smooth must be on or off, got 'yes'");
}

Test(povray_agreement, chapter_14_smooth_teapot_and_uv_mapped_card, .timeout = 120) {
    expect_agreement("smooth", SMOOTH_SCENE);
}

/* ---- the teapot's own (u, v): tools/models/teapot.c --uv ------------------------------------------- */

#define TEAPOT_WELDED "scenes/models/teapot-5k.ply"
#define TEAPOT_UV "scenes/models/teapot-5k-uv.ply"
#define TEAPOT_UV_SCENE "tests/data/textures/teapot-uv.scene"
#define TEAPOT_N 9 /* teapot-5k's subdivisions per patch side */

Test(teapot_uv, has_the_welded_teapots_triangles_with_a_uv_and_a_normal_at_every_corner, .timeout = 60) {
    struct mesh welded, m;
    struct mesh_corners none, c;
    char err[512] = "";
    cr_assert(mesh_load_with_corners(TEAPOT_WELDED, &welded, &none, err, sizeof err), "%s", err);
    cr_assert(mesh_load_with_corners(TEAPOT_UV, &m, &c, err, sizeof err), "%s", err);
    cr_assert_eq(m.face_count, welded.face_count, "the same triangles");
    cr_expect_gt(m.vertex_count, welded.vertex_count, "seam vertices are one per patch");
    cr_assert_not_null(c.uv_faces, "no texture coordinates");
    cr_assert_not_null(c.normal_faces, "no normals");
    /* The welded teapot's normals, averaged as `smooth on` averages them: the file's must be the same at
     * every corner, so the seams, where each patch has its own vertex, do not crease. */
    struct mesh_corners averaged = {0};
    cr_assert(mesh_surface_average_normals(&welded, &averaged));
    size_t moved = 0, creased = 0, mirrored = 0, outside = 0;
    for (size_t f = 0; f < m.face_count; f++) {
        const uint32_t *v = m.faces[f].v, *w = welded.faces[f].v;
        const struct mesh_uv *uv[3];
        for (int k = 0; k < 3; k++) {
            vec3 a = m.vertices[v[k]], b = welded.vertices[w[k]];
            moved += a.x != b.x || a.y != b.y || a.z != b.z;
            vec3 n = c.normals[c.normal_faces[f].v[k]], expected = averaged.normals[w[k]];
            creased += vec3_length(vec3_sub(n, expected)) > 1e-6;
            uv[k] = &c.uvs[c.uv_faces[f].v[k]];
            outside += uv[k]->u < 0 || uv[k]->u > 1 || uv[k]->v < 0 || uv[k]->v > 1;
        }
        /* Counter-clockwise in (u, v) as in space seen from outside: a picture is not mirrored. A triangle
         * spans one grid cell: two sides of 1/N. */
        double du1 = uv[1]->u - uv[0]->u, dv1 = uv[1]->v - uv[0]->v, du2 = uv[2]->u - uv[0]->u,
               dv2 = uv[2]->v - uv[0]->v;
        double area = du1 * dv2 - dv1 * du2;
        mirrored += !(fabs(area - 1.0 / (TEAPOT_N * TEAPOT_N)) < 1e-6);
    }
    cr_expect_eq(moved, 0, "%zu corners moved", moved);
    cr_expect_eq(creased, 0, "%zu corners' normals differ from the welded average", creased);
    cr_expect_eq(mirrored, 0, "%zu triangles are not one counter-clockwise half grid cell in (u, v)", mirrored);
    cr_expect_eq(outside, 0);
    mesh_corners_free(&averaged);
    mesh_free(&welded);
    mesh_free(&m);
    mesh_corners_free(&c);
}

Test(povray_agreement, chapter_14_teapot_wearing_its_patches_uv, .timeout = 120) {
    expect_agreement("teapot-uv", TEAPOT_UV_SCENE);
}

/* ---- uv mapping on a box: POV-Ray's cross ------------------------------------------------------------ */

#define BOX_UV_SCENE "tests/data/textures/box-uv.scene"

/* Expects texture_box_uv of the box (0, 0, 0)-(2, 3, 4) at `point` on the face with normal n. */
static void expect_box_uv(vec3 point, vec3 n, double u, double v, const char *face) {
    struct box b = {{0, 0, 0}, {2, 3, 4}, 0};
    struct mesh_uv uv = texture_box_uv(&b, point, n);
    cr_expect_float_eq(uv.u, u, 1e-12, "%s: u %g, expected %g", face, uv.u, u);
    cr_expect_float_eq(uv.v, v, 1e-12, "%s: v %g, expected %g", face, uv.v, v);
}

Test(texture, box_uv_unfolds_the_six_faces_into_povrays_cross) {
    /* The point (x, y, z) = (0.5, 1.5, 1) of the box scaled to [0, 1]: (0.25, 0.5, 0.25). */
    expect_box_uv(vec3_make(0, 1.5, 1), vec3_make(-1, 0, 0), 0.25 / 4, 1.0 / 3 + 0.5 / 3, "-x");
    expect_box_uv(vec3_make(2, 1.5, 1), vec3_make(1, 0, 0), 0.75 - 0.25 / 4, 1.0 / 3 + 0.5 / 3, "+x");
    expect_box_uv(vec3_make(0.5, 1.5, 4), vec3_make(0, 0, 1), 0.25 + 0.25 / 4, 1.0 / 3 + 0.5 / 3, "+z");
    expect_box_uv(vec3_make(0.5, 1.5, 0), vec3_make(0, 0, -1), 1 - 0.25 / 4, 1.0 / 3 + 0.5 / 3, "-z");
    expect_box_uv(vec3_make(0.5, 3, 1), vec3_make(0, 1, 0), 0.25 + 0.25 / 4, 1 - 0.25 / 3, "+y");
    expect_box_uv(vec3_make(0.5, 0, 1), vec3_make(0, -1, 0), 0.25 + 0.25 / 4, 0.25 / 3, "-y");
    /* The cross folds up: the +z face's top edge is the +y face's bottom edge, and its sides run on
     * into the side faces' edges at the same height. */
    expect_box_uv(vec3_make(2, 3, 4), vec3_make(0, 0, 1), 0.5, 2.0 / 3, "+z, top right corner");
    expect_box_uv(vec3_make(2, 3, 4), vec3_make(0, 1, 0), 0.5, 2.0 / 3, "+y, the same corner");
    expect_box_uv(vec3_make(2, 3, 4), vec3_make(1, 0, 0), 0.5, 2.0 / 3, "+x, the same corner");
}

Test(povray_agreement, chapter_14_uv_mapping_on_boxes_seen_from_outside_and_inside, .timeout = 120) {
    expect_agreement("box-uv", BOX_UV_SCENE);
}

/* ---- shadows through patterned glass --------------------------------------------------------------- */

#define SHADOWS_SCENE "tests/data/textures/shadows.scene"

Test(texture, a_shadow_ray_through_glass_takes_the_pigment_but_povrays_opaque_uv_pictures_block_it) {
    struct scene s;
    char err[512] = "";
    cr_assert(parse_lines("pigment c checker colour 1 0 0 colour2 0 0 1\n"
                          "pigment u image_map file a.png map uv\n"
                          "material glass pigment c filter 0.8 transmit 0.1\n"
                          "material tiles pigment u filter 0.6 transmit 0.3",
                          &s, err, sizeof err),
              "%s", err);
    static float white[4] = {1, 1, 1, 1};
    s.pigments[1].image = (struct pigment_image){.width = 1, .height = 1, .texels = white, .opaque = true};
    struct material painted;
    struct hit h = {1, {0, 1, 0}, 1, -1, -1};
    const struct material *m = texture_paint_shadow(&s, &h, vec3_make(1.5, 0.5, 0.5), &painted);
    cr_expect(m->colour.x == 0 && m->colour.z == 1, "the checker's colour2 where the ray crosses");
    cr_expect(m->filter == 0.8 && m->transmit == 0.1, "the material's filter and transmit");
    h.material = 2;
    m = texture_paint_shadow(&s, &h, vec3_make(0.5, 0.5, 0), &painted);
    cr_expect(m->filter == 0 && m->transmit == 0, "map uv, repeated, no alpha: opaque, as POV-Ray takes it");
    s.pigments[1].once = true;
    m = texture_paint_shadow(&s, &h, vec3_make(0.5, 0.5, 0), &painted);
    cr_expect(m->filter == 0.6 && m->transmit == 0.3, "wrap once: the light goes through");
    s.pigments[1].once = false;
    s.pigments[1].uv_mapping = false;
    m = texture_paint_shadow(&s, &h, vec3_make(0.5, 0.5, 0), &painted);
    cr_expect(m->filter == 0.6 && m->transmit == 0.3, "a planar map: the light goes through");
    s.pigments[1].image = (struct pigment_image){0};
    scene_free(&s);
}

Test(povray_agreement, chapter_14_shadows_through_patterned_glass, .timeout = 120) {
    expect_agreement("shadows", SHADOWS_SCENE);
}

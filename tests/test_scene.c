/* test_scene.c: the scene file parser (common/scene.c): every directive and key, the defaults, and every
 * error with its exact "file:line: message" text. On error the scene must be left empty; the sanitizer
 * run of this suite checks that nothing leaks on either path. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "box.h"
#include "camera.h"
#include "plane.h"
#include "scene.h"
#include "sphere.h"
#include "triangle.h"

#define NAME "test.scene"
/* The two lines every scene needs; a line appended after them is line 3. */
#define HEAD "camera eye 0 0 0 target 0 0 -1 fov 60\nimage 4 3\n"

/* ---- helpers ----------------------------------------------------------------------------------- */

static void assert_vec3_eq(vec3 got, vec3 want, const char *what) {
    cr_assert(got.x == want.x && got.y == want.y && got.z == want.z,
              "%s: got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g)", what, got.x, got.y, got.z, want.x,
              want.y, want.z);
}

/* Parses `text` (named NAME), drawing no kind of shape, and fails the test with the parser's message if
 * it is refused. */
static void parse_ok(const char *text, struct scene *s) {
    char err[512] = "";
    cr_assert(scene_parse(NAME, text, NULL, s, err, sizeof err), "refused: %s", err);
}

/* The number of shapes of the kind whose line is `syntax` in s. */
static size_t count_of(const struct scene *s, const struct shape_syntax *syntax) {
    return scene_shapes(s, syntax)->count;
}

/* Those shapes, as an array of the kind's struct. */
static const void *shapes_of(const struct scene *s, const struct shape_syntax *syntax) {
    return scene_shapes(s, syntax)->items;
}

/* The number of shapes of every kind in s, and of meshes. */
static size_t count_all(const struct scene *s) {
    size_t count = s->mesh_count;
    for (size_t k = 0; k < s->kind_count; k++)
        count += s->shapes[k].count;
    return count;
}

/* Parses HEAD followed by `lines` and returns the scene (free it with scene_free). */
static struct scene parse_with_head(const char *lines) {
    char text[4096];
    cr_assert_lt(strlen(HEAD) + strlen(lines), sizeof text);
    snprintf(text, sizeof text, "%s%s", HEAD, lines);
    struct scene s;
    parse_ok(text, &s);
    return s;
}

/* An empty scene is all zero bytes: every count 0, every pointer NULL (scene_free memsets it). */
static void assert_scene_empty(const struct scene *s) {
    static const struct scene empty;
    cr_assert_eq(memcmp(s, &empty, sizeof empty), 0, "the scene was not left empty (%zu kinds of shape, path %p)",
                 s->kind_count, (void *)s->path);
}

/* Parses `text`, expects it to be refused with exactly `message`, and the scene to be left empty. */
static void expect_error(const char *text, const char *message) {
    char err[512] = "";
    struct scene s;
    memset(&s, 0xA5, sizeof s); /* garbage, as an uninitialised variable would hold */
    bool accepted = scene_parse(NAME, text, NULL, &s, err, sizeof err);
    if (accepted)
        scene_free(&s);
    cr_assert(!accepted, "accepted:\n%s", text);
    cr_assert_str_eq(err, message);
    assert_scene_empty(&s);
}

/* Expects HEAD followed by `line` to be refused with "test.scene:3: " + message. */
static void expect_line3_error(const char *line, const char *message) {
    char text[1024], full[512];
    snprintf(text, sizeof text, "%s%s\n", HEAD, line);
    snprintf(full, sizeof full, NAME ":3: %s", message);
    expect_error(text, full);
}

/* ---- directives -------------------------------------------------------------------------------- */

Test(scene, camera_keys_in_any_order) {
    struct scene s;
    parse_ok("image 4 3\ncamera fov 45 up 0 0 1 target 1 2 3 eye 4 5 6\n", &s);
    assert_vec3_eq(s.eye, vec3_make(4, 5, 6), "eye");
    assert_vec3_eq(s.target, vec3_make(1, 2, 3), "target");
    assert_vec3_eq(s.up, vec3_make(0, 0, 1), "up");
    cr_assert_eq(s.fov, 45.0);
    cr_assert_str_eq(s.path, NAME);
    scene_free(&s);
}

Test(scene, minimal_scene_has_the_documented_defaults) {
    struct scene s = parse_with_head("");
    assert_vec3_eq(s.up, vec3_make(0, 1, 0), "up");
    cr_assert_eq(s.width, 4);
    cr_assert_eq(s.height, 3);
    assert_vec3_eq(s.background, vec3_make(0, 0, 0), "background");
    assert_vec3_eq(s.ambient_light, vec3_make(1, 1, 1), "ambient_light");
    cr_assert_eq(s.max_depth, 5);
    cr_assert(s.shadow_offset);
    cr_assert_eq(s.material_count, 1);
    cr_assert_eq(s.light_count + count_all(&s), 0);
    scene_free(&s);
}

Test(scene, material_0_is_the_default_material) {
    struct scene s = parse_with_head("");
    const struct material *m = &s.materials[0];
    cr_assert_str_eq(m->name, "default");
    assert_vec3_eq(m->colour, vec3_make(1, 1, 1), "colour");
    cr_assert_eq(m->ambient, 0.1);
    cr_assert_eq(m->diffuse, 0.6);
    cr_assert_eq(m->phong, 0.0);
    cr_assert_eq(m->phong_size, 40.0);
    cr_assert_eq(m->reflection, 0.0);
    cr_assert_eq(m->filter + m->transmit, 0.0);
    cr_assert_eq(m->ior, 1.0);
    scene_free(&s);
}

Test(scene, global_settings_are_read) {
    struct scene s = parse_with_head("background 0.1 0.2 0.3\nambient_light 0.5 0.6 0.7\nmax_depth 12\n"
                                     "shadow_offset off\n");
    assert_vec3_eq(s.background, vec3_make(0.1, 0.2, 0.3), "background");
    assert_vec3_eq(s.ambient_light, vec3_make(0.5, 0.6, 0.7), "ambient_light");
    cr_assert_eq(s.max_depth, 12);
    cr_assert(!s.shadow_offset);
    scene_free(&s);
    s = parse_with_head("shadow_offset on\nmax_depth 1\n");
    cr_assert(s.shadow_offset);
    cr_assert_eq(s.max_depth, 1);
    scene_free(&s);
}

Test(scene, light_keys_in_any_order_and_default_colour) {
    struct scene s = parse_with_head("light colour 0.5 0.25 2 position 1 2 3\nlight position -1 -2 -3\n");
    cr_assert_eq(s.light_count, 2);
    assert_vec3_eq(s.lights[0].position, vec3_make(1, 2, 3), "position");
    assert_vec3_eq(s.lights[0].colour, vec3_make(0.5, 0.25, 2), "colour");
    assert_vec3_eq(s.lights[1].position, vec3_make(-1, -2, -3), "position");
    assert_vec3_eq(s.lights[1].colour, vec3_make(1, 1, 1), "default colour");
    scene_free(&s);
}

Test(scene, material_with_every_key_in_any_order) {
    struct scene s = parse_with_head("material glass ior 1.5 transmit 0.6 filter 0.3 reflection 0.2 phong_size 80 "
                                     "phong 0.9 diffuse 0.4 ambient 0.05 colour 0.8 0.9 1\n");
    cr_assert_eq(s.material_count, 2);
    const struct material *m = &s.materials[1];
    cr_assert_str_eq(m->name, "glass");
    assert_vec3_eq(m->colour, vec3_make(0.8, 0.9, 1), "colour");
    double got[8] = {m->ambient, m->diffuse, m->phong, m->phong_size, m->reflection, m->filter, m->transmit, m->ior};
    double want[8] = {0.05, 0.4, 0.9, 80, 0.2, 0.3, 0.6, 1.5};
    for (int k = 0; k < 8; k++)
        cr_assert_eq(got[k], want[k], "value %d: got %g, want %g", k, got[k], want[k]);
    scene_free(&s);
}

Test(scene, material_keys_left_out_keep_the_defaults) {
    struct scene s = parse_with_head("material red colour 1 0 0 phong 0.5\n");
    struct material want = s.materials[0];
    snprintf(want.name, sizeof want.name, "red");
    want.colour = vec3_make(1, 0, 0);
    want.phong = 0.5;
    want.line = 3; /* where it was read, for messages */
    cr_assert_eq(memcmp(&s.materials[1], &want, sizeof want), 0);
    scene_free(&s);
}

Test(scene, sphere_triangle_and_box_with_and_without_material) {
    struct scene s = parse_with_head("material red\n"
                                     "sphere radius 2 material red centre 1 2 3\n"
                                     "sphere centre 0 0 0 radius 0.5\n"
                                     "triangle material red c 7 8 9 b 4 5 6 a 1 2 3\n"
                                     "box max 1 2 3 min -1 -2 -3 material red\n");
    const struct sphere *spheres = shapes_of(&s, &sphere_syntax);
    const struct triangle *triangles = shapes_of(&s, &triangle_syntax);
    const struct box *boxes = shapes_of(&s, &box_syntax);
    cr_assert_eq(count_of(&s, &sphere_syntax), 2);
    assert_vec3_eq(spheres[0].centre, vec3_make(1, 2, 3), "centre");
    cr_assert_eq(spheres[0].radius, 2.0);
    cr_assert_eq(spheres[0].material, 1);
    cr_assert_eq(spheres[1].material, 0);
    cr_assert_eq(count_of(&s, &triangle_syntax), 1);
    assert_vec3_eq(triangles[0].a, vec3_make(1, 2, 3), "a");
    assert_vec3_eq(triangles[0].b, vec3_make(4, 5, 6), "b");
    assert_vec3_eq(triangles[0].c, vec3_make(7, 8, 9), "c");
    cr_assert_eq(triangles[0].material, 1);
    cr_assert_eq(count_of(&s, &box_syntax), 1);
    assert_vec3_eq(boxes[0].min, vec3_make(-1, -2, -3), "min");
    assert_vec3_eq(boxes[0].max, vec3_make(1, 2, 3), "max");
    cr_assert_eq(boxes[0].material, 1);
    scene_free(&s);
}

/* Parses one plane line and checks the stored unit normal and distance. */
static void check_plane(const char *line, vec3 normal, double distance) {
    struct scene s = parse_with_head(line);
    cr_assert_eq(count_of(&s, &plane_syntax), 1, "%s", line);
    struct plane got = *(const struct plane *)shapes_of(&s, &plane_syntax);
    scene_free(&s);
    assert_vec3_eq(got.normal, normal, line);
    cr_assert_eq(got.distance, distance, "%s: distance %.17g", line, got.distance);
}

Test(scene, plane_in_all_three_forms_stores_unit_normal_and_distance) {
    check_plane("plane normal 0 2 0 distance 1", vec3_make(0, 1, 0), 1);
    check_plane("plane distance 1 normal 0 0 -5", vec3_make(0, 0, -1), 1);
    check_plane("plane normal 0 1 0 point 0 -1 0", vec3_make(0, 1, 0), -1);
    check_plane("plane point 1 1 1 normal 4 0 0", vec3_make(1, 0, 0), 1);
    check_plane("plane a 0 0 0 b 1 0 0 c 0 0 -1", vec3_make(0, 1, 0), 0);   /* (1,0,0) x (0,0,-1) = (0,1,0) */
    check_plane("plane c 1 2 0 b 0 2 -1 a 0 2 0", vec3_make(0, -1, 0), -2); /* (0,0,-1) x (1,0,0) = (0,-1,0) */
}

/* A normal (or edges) below about 5.6e-309, subnormal: 1 / its largest component is infinite, and
 * scaling by it once gave a NaN normal, a plane never drawn, with exit 0. */
Test(scene, plane_of_a_subnormal_normal_or_points_a_subnormal_distance_apart_keeps_its_direction) {
    check_plane("plane normal 0 0 1e-310 distance 2", vec3_make(0, 0, 1), 2);
    check_plane("plane normal 0 -4.9e-324 0 point 0 3 0", vec3_make(0, -1, 0), -3);
    check_plane("plane a 0 0 0 b 1e-310 0 0 c 0 1e-310 0", vec3_make(0, 0, 1), 0);
    check_plane("plane a 1 0 0 b 1 1e-320 0 c 1 0 1e-315", vec3_make(1, 0, 0), 1);
}

Test(scene, plane_material_is_kept) {
    struct scene s = parse_with_head("material floor\nplane material floor normal 0 1 0 distance 0\n");
    const struct plane *planes = shapes_of(&s, &plane_syntax);
    cr_assert_eq(planes[0].material, 1);
    scene_free(&s);
}

Test(scene, mesh_with_every_key_and_its_path_relative_to_the_scene_folder) {
    struct scene s;
    parse_ok(HEAD "material red\nmesh models/bunny.ply translate 1 2 3 material red rotate 10 20 30 scale 2\n"
                  "mesh /abs/teapot.obj\n",
             &s);
    cr_assert_eq(s.mesh_count, 2);
    cr_assert_str_eq(s.meshes[0].path, "models/bunny.ply", "a scene name without a folder");
    cr_assert_eq(s.meshes[0].scale, 2.0);
    assert_vec3_eq(s.meshes[0].rotate, vec3_make(10, 20, 30), "rotate");
    assert_vec3_eq(s.meshes[0].translate, vec3_make(1, 2, 3), "translate");
    cr_assert_eq(s.meshes[0].material, 1);
    cr_assert_eq(s.meshes[0].line, 4);
    cr_assert_null(s.meshes[0].mesh.vertices, "meshes are not loaded by the parser");
    cr_assert_str_eq(s.meshes[1].path, "/abs/teapot.obj");
    cr_assert_eq(s.meshes[1].scale, 1.0);
    assert_vec3_eq(s.meshes[1].rotate, vec3_make(0, 0, 0), "default rotate");
    assert_vec3_eq(s.meshes[1].translate, vec3_make(0, 0, 0), "default translate");
    cr_assert_eq(s.meshes[1].material, 0);
    scene_free(&s);
}

Test(scene, mesh_path_is_joined_to_the_folder_of_the_scene_name) {
    struct scene s;
    char err[256] = "";
    cr_assert(scene_parse("scenes/sub/x.scene", HEAD "mesh ../models/m.ply\n", NULL, &s, err, sizeof err), "%s", err);
    cr_assert_str_eq(s.meshes[0].path, "scenes/sub/../models/m.ply");
    scene_free(&s);
}

Test(scene, comments_blank_lines_and_crlf_are_ignored) {
    struct scene s;
    parse_ok("# a comment line\r\n\r\n   \t \r\n"
             "camera eye 0 0 0 target 0 0 -1 fov 60 # trailing comment\r\n"
             "image 4 3\r\n"
             "sphere centre 0 0 -5 radius 1#comment glued to a number\r\n"
             "\tsphere centre 1 2 3 radius 2\r\n"
             "# the last line has no newline",
             &s);
    const struct sphere *spheres = shapes_of(&s, &sphere_syntax);
    cr_assert_eq(count_of(&s, &sphere_syntax), 2);
    cr_assert_eq(spheres[0].radius, 1.0);
    assert_vec3_eq(spheres[1].centre, vec3_make(1, 2, 3), "centre");
    cr_assert_eq(s.height, 3);
    scene_free(&s);
}

/* A file whose lines end in carriage returns alone (old Mac OS) is one line to a reader that splits at
 * line feeds: "unknown key 'image' for camera" said nothing of why. The message now says, on the line
 * where it happens; a carriage return after the last word or in a comment is still nothing. */
Test(scene, lines_ended_by_carriage_returns_alone_are_refused_saying_so) {
    const char *message = NAME ":%d: a carriage return inside the line: its lines end in carriage returns alone "
                          "(old Mac OS), and they are read as one; save it with line feeds";
    char expected[512];
    snprintf(expected, sizeof expected, message, 1);
    expect_error("camera eye 0 0 0 target 0 0 -1 fov 60\rimage 4 3\rsphere centre 0 0 -5 radius 1\r", expected);
    snprintf(expected, sizeof expected, message, 3);
    expect_error("camera eye 0 0 0 target 0 0 -1 fov 60\nimage 4 3\nsphere centre 0 0 -5\r radius 1\n", expected);
    struct scene s;
    parse_ok("camera eye 0 0 0 target 0 0 -1 fov 60 \r \r\nimage 4 3 # a note\rwith a return\n", &s);
    scene_free(&s);
}

Test(scene, many_shapes_are_all_kept_in_order) {
    char text[8192];
    int used = snprintf(text, sizeof text, HEAD);
    for (int k = 0; k < 100; k++)
        used += snprintf(text + used, sizeof text - (size_t)used, "sphere centre %d 0 0 radius 1\n", k);
    struct scene s;
    parse_ok(text, &s);
    const struct sphere *spheres = shapes_of(&s, &sphere_syntax);
    cr_assert_eq(count_of(&s, &sphere_syntax), 100);
    for (int k = 0; k < 100; k++)
        cr_assert_eq(spheres[k].centre.x, (double)k);
    scene_free(&s);
}

Test(scene, numbers_in_exponent_notation_are_read) {
    struct scene s = parse_with_head("sphere centre -1e-3 2.5E2 +3 radius .5\n");
    const struct sphere *spheres = shapes_of(&s, &sphere_syntax);
    assert_vec3_eq(spheres[0].centre, vec3_make(-1e-3, 250, 3), "centre");
    cr_assert_eq(spheres[0].radius, 0.5);
    scene_free(&s);
}

/* ---- errors ------------------------------------------------------------------------------------ */

Test(scene_errors, unknown_directive) { expect_line3_error("spheer centre 0 0 0", "unknown directive 'spheer'"); }

Test(scene_errors, unknown_key) {
    expect_line3_error("sphere centre 0 0 0 radus 1", "unknown key 'radus' for sphere");
    expect_line3_error("box min 0 0 0 max 1 1 1 centre 0 0 0", "unknown key 'centre' for box");
}

Test(scene_errors, american_color_gets_a_hint) {
    expect_line3_error("light position 0 0 0 color 1 1 1",
                       "unknown key 'color' for light (the format spells it 'colour')");
    expect_line3_error("material red color 1 0 0", "unknown key 'color' for material (the format spells it 'colour')");
}

Test(scene_errors, key_given_twice) {
    expect_line3_error("sphere centre 0 0 0 radius 1 radius 2", "'radius' given twice");
    expect_line3_error("material m ior 1.5 ior 1.3", "'ior' given twice");
}

Test(scene_errors, missing_required_keys) {
    expect_line3_error("sphere centre 0 0 0", "sphere needs 'radius'");
    expect_line3_error("sphere radius 1", "sphere needs 'centre'");
    expect_line3_error("light colour 1 1 1", "light needs 'position'");
    expect_line3_error("triangle a 0 0 0 b 1 0 0", "triangle needs 'c'");
    expect_line3_error("box min 0 0 0", "box needs 'max'");
    expect_error("image 4 3\ncamera eye 0 0 0 target 0 0 -1\n", NAME ":2: camera needs 'fov'");
    expect_error("camera target 0 0 -1 fov 60\nimage 4 3\n", NAME ":1: camera needs 'eye'");
}

Test(scene_errors, too_few_numbers) {
    expect_line3_error("sphere radius 1 centre 0 0", "'centre' needs 3 numbers");
    expect_line3_error("sphere centre 0 0 0 radius", "'radius' needs a value");
    expect_line3_error("sphere centre 0 0 0 radius 1 material", "'material' needs a value");
    expect_line3_error("sphere centre 0 0 radius 1", "expected a number for 'centre', got 'radius'");
    expect_line3_error("background 0.5 0.5", "background needs 3 numbers, got 2");
    expect_line3_error("ambient_light 1 1 1 1", "ambient_light needs 3 numbers, got 4");
    expect_line3_error("max_depth", "max_depth needs one whole number");
}

Test(scene_errors, words_that_are_not_numbers) {
    expect_line3_error("sphere centre 0 0 0 radius one", "expected a number for 'radius', got 'one'");
    expect_line3_error("sphere centre 1,2 0 0 radius 1", "expected a number for 'centre', got '1,2'");
    expect_line3_error("sphere centre 0 0 0 radius 0x1p5", "expected a number for 'radius', got '0x1p5'");
    expect_line3_error("sphere centre 0x28 0 0 radius 1", "expected a number for 'centre', got '0x28'");
    expect_line3_error("background 0 0 black", "expected a number for 'background', got 'black'");
    expect_line3_error("max_depth 2.5", "expected a whole number for 'max_depth', got '2.5'");
    expect_line3_error("shadow_offset yes", "shadow_offset needs 'on' or 'off'");
}

Test(scene_errors, nan_and_infinity_are_refused) {
    expect_line3_error("sphere centre 0 0 0 radius nan", "'nan' is not a finite number (for 'radius')");
    expect_line3_error("sphere centre inf 0 0 radius 1", "'inf' is not a finite number (for 'centre')");
    expect_line3_error("light position 0 -INF 0", "'-INF' is not a finite number (for 'position')");
    expect_line3_error("background 1e999 0 0", "'1e999' is not a finite number (for 'background')");
}

Test(scene_errors, values_out_of_range) {
    expect_line3_error("sphere centre 0 0 0 radius -1", "sphere radius must be positive, got -1");
    expect_line3_error("sphere centre 0 0 0 radius 0", "sphere radius must be positive, got 0");
    /* Finite, but past what the program can compute with: each would overflow a square or a product. */
    expect_line3_error("sphere centre 0 0 0 radius 1e200", "sphere radius must be between 1e-18 and 1e+18, got 1e+200");
    expect_line3_error("sphere centre 0 0 0 radius 1e-19", "sphere radius must be between 1e-18 and 1e+18, got 1e-19");
    expect_line3_error("sphere centre 0 -2e18 0 radius 1",
                       "sphere centre is (0, -2e+18, 0); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("box min -1e300 0 0 max 1 1 1", "box min is (-1e+300, 0, 0); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("box min 0 0 0 max 1 1 1e19", "box max is (1, 1, 1e+19); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("plane normal 0 1 0 distance -1e300",
                       "plane distance must stay within -1e+18 .. 1e+18, got -1e+300");
    expect_line3_error("plane normal 0 1 0 point 0 1e19 0", "plane point is (0, 1e+19, 0); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("plane a 0 0 0 b 1 0 0 c 0 0 1e19", "plane c is (0, 0, 1e+19); it must stay within -1e+18 .. 1e+18");
    expect_error("camera eye 0 0 1e200 target 0 0 0 fov 40\n",
                 NAME ":1: camera eye is (0, 0, 1e+200); it must stay within -1e+18 .. 1e+18");
    expect_error("camera eye 0 0 5 target 0 0 -1e19 fov 40\n",
                 NAME ":1: camera target is (0, 0, -1e+19); it must stay within -1e+18 .. 1e+18");
    expect_error("camera eye 0 0 5 target 0 0 0 up 0 1e300 0 fov 40\n",
                 NAME ":1: camera up is (0, 1e+300, 0); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("light position 0 5e18 5", "light position is (0, 5e+18, 5); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("ambient_light 1e19 1 1", "ambient_light is (1e+19, 1, 1); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("background 0 -1e300 0", "background is (0, -1e+300, 0); it must stay within -1e+18 .. 1e+18");
    expect_line3_error("material m ambient 100.5", "material 'm': ambient must be at most 100, got 100.5");
    expect_line3_error("material m diffuse 1e300", "material 'm': diffuse must be at most 100, got 1e+300");
    expect_line3_error("material m phong 101", "material 'm': phong must be at most 100, got 101");
    expect_line3_error("material m colour 0 0 101", "material 'm': colour must be at most 100 in each channel, got 0 0 101");
    /* The limits themselves are in range. */
    struct scene s;
    parse_ok(HEAD "sphere centre 1e18 -1e18 0 radius 1e18\nsphere centre 0 0 0 radius 1e-18\n"
                  "plane normal 0 1 0 distance -1e18\nlight position -1e18 1e18 1e18\nbackground -1e18 0 1e18\n"
                  "material m colour 100 100 100 ambient 100 diffuse 100 phong 100 reflection 100 phong_size 1e300\n",
             &s);
    cr_assert_eq(scene_shapes(&s, &sphere_syntax)->count, 2);
    scene_free(&s);
    expect_line3_error("max_depth 0", "'max_depth' must be between 1 and 64, got 0");
    expect_line3_error("max_depth 65", "'max_depth' must be between 1 and 64, got 65");
    expect_line3_error("mesh a.ply scale 0", "mesh scale must be positive, got 0");
    expect_line3_error("mesh", "mesh needs a file name");
}

Test(scene_errors, bad_planes) {
    expect_line3_error("plane normal 0 0 0 distance 1", "plane normal must not be zero");
    expect_line3_error("plane a 0 0 0 b 1 1 1 c 2 2 2", "plane points a, b, c lie on one line");
    expect_line3_error("plane a 0 0 0 b 1 1 1 c 1 1 1", "plane points a, b, c lie on one line");
    const char *forms = "plane needs 'normal' with 'distance' or 'point', or three points 'a', 'b', 'c'";
    expect_line3_error("plane normal 0 1 0 distance 1 point 0 0 0", forms);
    expect_line3_error("plane normal 0 1 0", forms);
    expect_line3_error("plane a 0 0 0 b 1 0 0", forms);
    expect_line3_error("plane a 0 0 0 b 1 0 0 c 0 0 -1 normal 0 1 0", forms);
}

Test(scene_errors, unknown_material) {
    expect_line3_error("sphere centre 0 0 0 radius 1 material glas",
                       "unknown material 'glas' (define it with a material line first)");
    expect_error(HEAD "sphere centre 0 0 0 radius 1 material red\nmaterial red\n",
                 NAME ":3: unknown material 'red' (define it with a material line first)");
}

Test(scene_errors, material_defined_twice) {
    expect_error(HEAD "material red\nmaterial red colour 1 0 0\n", NAME ":4: material 'red' is already defined");
    expect_line3_error("material default", "material 'default' is already defined");
}

Test(scene_errors, material_name_longer_than_63_characters) {
    char name[SCENE_NAME_MAX + 1];
    memset(name, 'm', SCENE_NAME_MAX);
    name[SCENE_NAME_MAX] = '\0'; /* 64 characters */
    char line[128];
    snprintf(line, sizeof line, "material %s", name);
    expect_line3_error(line, "material name longer than 63 characters");
    name[SCENE_NAME_MAX - 1] = '\0'; /* 63 characters are fine */
    snprintf(line, sizeof line, "material %s\n", name);
    struct scene s = parse_with_head(line);
    cr_assert_eq(scene_find_material(&s, name), 1);
    scene_free(&s);
}

Test(scene_errors, bad_material_values) {
    expect_line3_error("material glass filter 0.6 transmit 0.5", "material 'glass': filter + transmit must not exceed 1");
    expect_line3_error("material m ambient -0.1", "material 'm': ambient must not be negative");
    expect_line3_error("material m transmit -1", "material 'm': transmit must not be negative");
    expect_line3_error("material m colour 1 -0.5 0", "material 'm': colour must not be negative");
    expect_line3_error("material m phong_size 0", "material 'm': phong_size must be positive");
    expect_line3_error("material m ior 0", "material 'm': ior must be positive");
    expect_line3_error("material m ior 1e-51", "material 'm': ior 1e-51 is out of range (from 1e-50 to 1e+50)");
    expect_line3_error("material m ior 2e50", "material 'm': ior 2e+50 is out of range (from 1e-50 to 1e+50)");
    expect_line3_error("material", "material needs a name");
}

Test(scene_errors, box_with_min_not_below_max) {
    expect_line3_error("box min 0 0 0 max 1 0 1", "box min must be below max on every axis");
    expect_line3_error("box min 0 0 2 max 1 1 1", "box min must be below max on every axis");
}

Test(scene_errors, image_size_out_of_range) {
    const char *camera = "camera eye 0 0 0 target 0 0 -1 fov 60\n";
    char text[256];
    snprintf(text, sizeof text, "%simage 0 3\n", camera);
    expect_error(text, NAME ":2: 'image width' must be between 1 and 16384, got 0");
    snprintf(text, sizeof text, "%simage 4 16385\n", camera);
    expect_error(text, NAME ":2: 'image height' must be between 1 and 16384, got 16385");
    snprintf(text, sizeof text, "%simage 4\n", camera);
    expect_error(text, NAME ":2: image needs a width and a height");
    snprintf(text, sizeof text, "%simage 4 3 1\n", camera);
    expect_error(text, NAME ":2: image needs a width and a height");
    expect_line3_error("image 4 3", "a second image line");
}

Test(scene_errors, bad_cameras) {
    expect_error("camera eye 0 0 0 target 0 0 -1 fov 180\nimage 4 3\n",
                 NAME ":1: camera fov must be between 0 and 180 degrees, got 180");
    expect_error("camera eye 0 0 0 target 0 0 -1 fov 0\nimage 4 3\n",
                 NAME ":1: camera fov must be between 0 and 180 degrees, got 0");
    expect_error("camera eye 1 2 3 target 1 2 3 fov 60\nimage 4 3\n", NAME ":1: camera eye and target are the same point");
    expect_error("camera eye 0 0 0 target 0 5 0 fov 60\nimage 4 3\n",
                 NAME ":1: camera up vector is zero or parallel to the viewing direction");
    expect_error("camera eye 0 0 0 target 0 0 -1 up 0 0 0 fov 60\nimage 4 3\n",
                 NAME ":1: camera up vector is zero or parallel to the viewing direction");
    /* Lengths whose squares vanish were read as zero, and an up of 1e-310 was called parallel. */
    expect_error("camera eye 0 0 1e-200 target 0 0 0 fov 60\nimage 4 3\n",
                 NAME ":1: camera eye and target are 1e-200 apart; they must be at least 1e-18 apart");
    expect_error("camera eye 0 0 5 target 0 0 0 up 0 1e-200 0 fov 60\nimage 4 3\n",
                 NAME ":1: camera up vector is 1e-200 long; it must be at least 1e-18 long");
    expect_error("camera eye 0 0 5 target 0 0 0 up 0 1e-19 0 fov 60\nimage 4 3\n",
                 NAME ":1: camera up vector is 1e-19 long; it must be at least 1e-18 long");
    /* a number just past a limit is shown with the digits that tell it from the limit */
    expect_error("camera eye 0 0 0 target 0 0 -1 fov 180.00000000000003\nimage 4 3\n",
                 NAME ":1: camera fov must be between 0 and 180 degrees, got 180.00000000000003");
}

Test(scene, a_camera_of_tiny_but_allowed_lengths_keeps_its_basis) {
    struct camera cam;
    char err[256];
    cr_assert(camera_init(&cam, vec3_make(0, 0, 1e-18), vec3_make(0, 0, 0), vec3_make(0, 1e-18, 0), 60, 4, 3, err,
                          sizeof err),
              "%s", err);
    cr_expect(cam.forward.x == 0 && cam.forward.y == 0 && fabs(cam.forward.z + 1) < 1e-15, "forward %g %g %.17g",
              cam.forward.x, cam.forward.y, cam.forward.z);
    cr_expect(fabs(cam.up.x) < 1e-15 && fabs(cam.up.y - 1) < 1e-15 && fabs(cam.up.z) < 1e-15, "up %g %.17g %g",
              cam.up.x, cam.up.y, cam.up.z);
}

Test(scene_errors, second_camera_missing_camera_and_missing_image) {
    expect_line3_error("camera eye 0 0 0 target 0 0 -1 fov 60", "a second camera (a scene has one)");
    expect_error("image 4 3\nsphere centre 0 0 0 radius 1\n", NAME ": no camera line (a scene needs one)");
    expect_error("camera eye 0 0 0 target 0 0 -1 fov 60\n",
                 NAME ": no image line (a scene needs its size, e.g. 'image 320 240')");
    expect_error("", NAME ": no camera line (a scene needs one)");
}

Test(scene_errors, too_many_words_on_a_line) {
    char line[512] = "background";
    for (int k = 0; k < 48; k++) /* 49 words in all */
        strcat(line, " 1");
    expect_line3_error(line, "too many words on one line (at most 48)");
    line[strlen(line) - 2] = '\0'; /* 48 words: read, and refused for what they say */
    expect_line3_error(line, "background needs 3 numbers, got 47");
}

Test(scene_errors, error_after_many_good_lines_frees_everything) {
    expect_error(HEAD "material red\nmesh a.ply material red\nlight position 1 1 1\nsphere centre 0 0 0 radius 1\n"
                      "plane normal 0 1 0 distance 0\ntriangle a 0 0 0 b 1 0 0 c 0 1 0\nbox min 0 0 0 max 1 1 1\n"
                      "bogus\n",
                 NAME ":10: unknown directive 'bogus'");
}

/* ---- numeric edge cases (regressions of bugs found by these tests) ----------------------------- */

Test(scene, plane_normal_of_any_finite_size_is_stored_as_a_unit_vector) {
    /* |(0, 1e200, 0)| overflows to infinity, and dividing by it gave the zero vector; |(0, 1e-200, 0)|
     * underflows to 0, and the normal was refused as zero. */
    check_plane("plane normal 0 1e200 0 distance 1", vec3_make(0, 1, 0), 1);
    check_plane("plane normal 0 0 -1e-200 distance 1", vec3_make(0, 0, -1), 1);
}

Test(scene, plane_from_three_far_apart_points_has_a_unit_normal) {
    /* (b - a) x (c - a) = (0, 4e36, 0) is finite now that points stay within KEY_MAX_COORD, but the
     * edges are scaled to at most 1 first all the same: at 1e200 the product overflowed to infinity, and
     * normalising that gave NaNs. */
    check_plane("plane a 0 0 0 b 1e18 0 0 c 0 0 -1e18", vec3_make(0, 1, 0), 0);
}

Test(scene_errors, plane_with_keys_of_two_forms) {
    /* Like 'distance' with 'point', three points next to 'normal distance' must not be silently ignored. */
    expect_line3_error("plane normal 0 1 0 distance 1 a 0 0 0 b 1 0 0 c 0 0 -1",
                       "plane needs 'normal' with 'distance' or 'point', or three points 'a', 'b', 'c'");
    expect_line3_error("plane normal 0 1 0 point 0 0 0 c 0 0 -1",
                       "plane needs 'normal' with 'distance' or 'point', or three points 'a', 'b', 'c'");
}

Test(scene, tiny_but_finite_numbers_are_accepted) {
    /* 1e-310 is a finite (subnormal) double; strtod reports ERANGE for it, which must not be taken for
     * "not a finite number". */
    struct scene s = parse_with_head("sphere centre 1e-310 0 0 radius 1\n");
    double x = ((const struct sphere *)shapes_of(&s, &sphere_syntax))[0].centre.x;
    scene_free(&s);
    cr_assert_eq(x, 1e-310);
}

/* ---- files ------------------------------------------------------------------------------------- */

/* A scene file in a fresh temporary folder; remove it with remove_scene_file. */
struct scene_file {
    char dir[64];
    char path[96];
};

static struct scene_file write_scene_file(const char *bytes, size_t length) {
    struct scene_file f;
    snprintf(f.dir, sizeof f.dir, "/tmp/whitted-scene-XXXXXX");
    cr_assert_not_null(mkdtemp(f.dir));
    snprintf(f.path, sizeof f.path, "%s/test.scene", f.dir);
    FILE *file = fopen(f.path, "wb");
    cr_assert_not_null(file);
    cr_assert_eq(fwrite(bytes, 1, length, file), length);
    cr_assert_eq(fclose(file), 0);
    return f;
}

static void remove_scene_file(const struct scene_file *f) {
    remove(f->path);
    rmdir(f->dir);
}

Test(scene_files, load_reads_a_file_and_resolves_mesh_paths_beside_it) {
    const char text[] = HEAD "mesh models/m.ply\nsphere centre 0 0 0 radius 1\n";
    struct scene_file f = write_scene_file(text, sizeof text - 1);
    struct scene s;
    char err[256] = "", mesh_path[128];
    cr_assert(scene_load(f.path, NULL, &s, err, sizeof err), "%s", err);
    snprintf(mesh_path, sizeof mesh_path, "%s/models/m.ply", f.dir);
    cr_assert_str_eq(s.meshes[0].path, mesh_path);
    cr_assert_str_eq(s.path, f.path);
    cr_assert_eq(count_of(&s, &sphere_syntax), 1);
    scene_free(&s);
    remove_scene_file(&f);
}

/* Writes `length` bytes as a scene file, expects scene_load to refuse it with "PATH" + `message` and to
 * leave the scene empty. */
static void expect_file_error(const char *bytes, size_t length, const char *message) {
    struct scene_file f = write_scene_file(bytes, length);
    struct scene s;
    char err[256] = "", want[192];
    bool loaded = scene_load(f.path, NULL, &s, err, sizeof err);
    remove_scene_file(&f);
    cr_assert(!loaded);
    snprintf(want, sizeof want, "%s%s", f.path, message);
    cr_assert_str_eq(err, want);
    assert_scene_empty(&s);
}

Test(scene_files, errors_in_a_file_name_the_file_and_line) {
    const char text[] = HEAD "\nsphere centre 0 0 0 radius -2\n";
    expect_file_error(text, sizeof text - 1, ":4: sphere radius must be positive, got -2");
}

Test(scene_files, a_zero_byte_is_refused_with_its_line) {
    const char text[] = HEAD "sph\0ere centre 0 0 0 radius 1\n";
    expect_file_error(text, sizeof text - 1, ":3: contains a zero byte; not a text file");
}

Test(scene_files, a_missing_file_cannot_be_opened) {
    struct scene s;
    char err[256] = "";
    cr_assert(!scene_load("/nonexistent/folder/x.scene", NULL, &s, err, sizeof err));
    cr_assert_str_eq(err, "/nonexistent/folder/x.scene: cannot open: No such file or directory");
    assert_scene_empty(&s);
}

/* ---- dropping unsupported shapes, finding materials -------------------------------------------- */

#define ALL_SHAPES                                                                                            \
    HEAD "sphere centre 0 0 0 radius 1\nsphere centre 1 0 0 radius 1\ntriangle a 0 0 0 b 1 0 0 c 0 1 0\n"   \
         "mesh m.ply\nplane normal 0 1 0 distance 0\nplane normal 0 1 0 distance 1\n"                        \
         "plane normal 0 1 0 distance 2\nbox min 0 0 0 max 1 1 1\n"

/* Reads a scene with every kind of shape, drawing `kinds` (ending with NULL), and drops the others as
 * chapter `chapter` does; returns the note printed (malloc'd) and the scene. */
static char *drop_unsupported(const struct shape_kind *const *kinds, int chapter, struct scene *s) {
    char *note = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&note, &size);
    cr_assert_not_null(out);
    char err[512] = "";
    cr_assert(scene_parse(NAME, ALL_SHAPES, kinds, s, err, sizeof err), "refused: %s", err);
    scene_drop_unsupported(s, chapter, out);
    cr_assert_eq(fclose(out), 0);
    return note;
}

Test(scene_drop, unsupported_shapes_are_counted_in_one_note_and_removed) {
    static const struct shape_kind *const spheres[] = {&sphere_kind, NULL};
    struct scene s;
    char *note = drop_unsupported(spheres, 2, &s);
    cr_assert_str_eq(note, NAME ": chapter 2 ignores 1 triangle, 1 mesh, 3 planes, 1 box (not introduced yet)\n");
    cr_assert_eq(count_of(&s, &sphere_syntax), 2);
    cr_assert_eq(count_all(&s), 2);
    free(note);
    scene_free(&s);
}

Test(scene_drop, nothing_dropped_prints_nothing) {
    static const struct shape_kind *const every[] = {&box_kind, &plane_kind, &triangle_kind, &sphere_kind, NULL};
    struct scene s;
    char *note = drop_unsupported(every, 5, &s);
    cr_assert_str_eq(note, "");
    cr_assert_eq(count_all(&s), 8);
    free(note);
    scene_free(&s);
}

Test(scene_drop, chapter_1_drops_every_shape_and_a_null_note_is_allowed) {
    struct scene s;
    char *note = drop_unsupported(NULL, 1, &s);
    cr_assert_str_eq(note,
                     NAME ": chapter 1 ignores 2 spheres, 1 triangle, 1 mesh, 3 planes, 1 box (not introduced yet)\n");
    cr_assert_eq(count_all(&s), 0);
    free(note);
    scene_free(&s);
    static const struct shape_kind *const spheres_and_planes[] = {&sphere_kind, &plane_kind, NULL};
    char err[512] = "";
    cr_assert(scene_parse(NAME, ALL_SHAPES, spheres_and_planes, &s, err, sizeof err), "refused: %s", err);
    scene_drop_unsupported(&s, 4, NULL);
    cr_assert_eq(count_of(&s, &plane_syntax), 3);
    cr_assert_eq(count_all(&s), 5);
    scene_free(&s);
}

Test(scene, find_material_returns_the_index_or_minus_one) {
    struct scene s = parse_with_head("material red\nmaterial glass\n");
    cr_assert_eq(scene_find_material(&s, "default"), 0);
    cr_assert_eq(scene_find_material(&s, "red"), 1);
    cr_assert_eq(scene_find_material(&s, "glass"), 2);
    cr_assert_eq(scene_find_material(&s, "Glass"), -1);
    cr_assert_eq(scene_find_material(&s, ""), -1);
    scene_free(&s);
}

Test(scene, free_is_safe_twice) {
    struct scene s = parse_with_head("sphere centre 0 0 0 radius 1\n");
    scene_free(&s);
    assert_scene_empty(&s);
    scene_free(&s);
}

/* test_scene_set.c: --set PATH=VALUE changes one value of a scene's text before it is parsed
 * (common/scene_set.c), and the chapter programs take it on the command line. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "scene.h"
#include "scene_set.h"

static const char *const base =
    "camera eye 0 1 5 target 0 0 0 fov 40  # the view\n"
    "image 64 48\n"
    "material glass colour 1 1 1 transmit 0.9 ior 1.5\n"
    "material clay colour 0.8 0.5 0.3\n"
    "sphere centre 0 0 0 radius 1 material glass\n"
    "sphere centre 2 0 0 radius 0.5 material clay\n";

/* Applies spec to a copy of base; returns the new text (caller frees) or NULL with err filled. */
static char *changed(const char *spec, char *err, size_t err_size) {
    char *text = strdup(base);
    if (!scene_set_apply(&text, spec, err, err_size)) {
        free(text);
        return NULL;
    }
    return text;
}

Test(scene_set, a_key_of_the_camera_is_replaced_in_its_line_and_the_comment_kept) {
    char err[256];
    char *text = changed("camera.fov=30", err, sizeof err);
    cr_assert_not_null(text, "%s", err);
    cr_assert(strstr(text, "camera eye 0 1 5 target 0 0 0 fov 30  # the view\nimage 64 48\n") == text, "%s", text);
    free(text);
}

Test(scene_set, a_missing_key_is_added_and_a_vector_replaces_three_words) {
    char err[256];
    char *text = changed("camera.up=1 0 0", err, sizeof err);
    cr_assert_not_null(text, "%s", err);
    cr_assert_not_null(strstr(text, "camera eye 0 1 5 target 0 0 0 fov 40 up 1 0 0  # the view\n"), "%s", text);
    free(text);
    text = changed("camera.eye=9 8 7", err, sizeof err);
    cr_assert_not_null(strstr(text, "camera eye 9 8 7 target 0 0 0 fov 40"), "%s", text);
    free(text);
}

Test(scene_set, too_few_values_replace_all_of_the_old_value_and_the_parser_says_so) {
    /* "eye=3" must not quietly become eye 3 1 5 (the old y and z kept): the key's whole old value goes, and
     * the parser names what is missing. */
    char err[256];
    char *text = changed("camera.eye=3", err, sizeof err);
    cr_assert_not_null(strstr(text, "camera eye 3 target 0 0 0 fov 40  # the view\n"), "%s", text);
    struct scene s;
    cr_assert(!scene_parse("test.scene", text, NULL, &s, err, sizeof err));
    cr_assert_str_eq(err, "test.scene:1: expected a number for 'eye', got 'target'");
    free(text);
    text = changed("camera.eye=3 4", err, sizeof err);
    cr_assert_not_null(strstr(text, "camera eye 3 4 target 0 0 0 fov 40"), "%s", text);
    free(text);
    /* A word value (a material's name) is one word, whatever follows it. */
    text = changed("sphere.2.material=glass", err, sizeof err);
    cr_assert_not_null(strstr(text, "sphere centre 2 0 0 radius 0.5 material glass\n"), "%s", text);
    free(text);
    /* Negative numbers and exponents are numbers too. */
    text = changed("camera.target=-1e-3 .5 -2", err, sizeof err);
    cr_assert(scene_set_apply(&text, "camera.target=7", err, sizeof err), "%s", err);
    cr_assert_not_null(strstr(text, "camera eye 0 1 5 target 7 fov 40"), "%s", text);
    free(text);
}

Test(scene_set, a_material_is_found_by_name_and_a_shape_by_its_place) {
    char err[256];
    char *text = changed("material.glass.ior=1.33", err, sizeof err);
    cr_assert_not_null(strstr(text, "material glass colour 1 1 1 transmit 0.9 ior 1.33\nmaterial clay"), "%s", text);
    free(text);
    text = changed("sphere.2.radius=0.25", err, sizeof err);
    cr_assert_not_null(strstr(text, "sphere centre 0 0 0 radius 1 material glass\n"
                                    "sphere centre 2 0 0 radius 0.25 material clay\n"), "%s", text);
    free(text);
}

Test(scene_set, a_positional_directive_is_replaced_or_added) {
    char err[256];
    char *text = changed("image=32 24", err, sizeof err);
    cr_assert_not_null(strstr(text, "\nimage 32 24\n"), "%s", text);
    free(text);
    text = changed("max_depth=2", err, sizeof err);
    cr_assert(strlen(text) > 12 && strcmp(text + strlen(text) - 12, "max_depth 2\n") == 0, "%s", text);
    free(text);
}

Test(scene_set, changed_scenes_parse_to_the_new_values) {
    char err[256];
    char *text = changed("material.glass.ior=1.33", err, sizeof err);
    cr_assert(scene_set_apply(&text, "max_depth=3", err, sizeof err), "%s", err);
    struct scene s;
    cr_assert(scene_parse("test.scene", text, NULL, &s, err, sizeof err), "%s", err);
    cr_assert_float_eq(s.materials[scene_find_material(&s, "glass")].ior, 1.33, 1e-15);
    cr_assert_eq(s.max_depth, 3);
    scene_free(&s);
    free(text);
}

Test(scene_set, mistakes_are_named_exactly) {
    static const struct {
        const char *spec, *message;
    } cases[] = {
        {"max_depth", "--set max_depth: expected PATH=VALUE, e.g. max_depth=1 or camera.fov=30"},
        {"camera.fov=", "--set camera.fov=: no value after '='"},
        {"camera=1", "--set camera=1: say which key of the camera line, e.g. camera.KEY=VALUE"},
        {"image.width=3", "--set image.width=3: image takes its values directly: write image=VALUE"},
        {"material.steel.ior=2", "--set material.steel.ior=2: the scene has no material called 'steel'"},
        {"sphere.3.radius=1", "--set sphere.3.radius=1: the scene has fewer than 3 sphere lines"},
        {"sphere.0.radius=1", "--set sphere.0.radius=1: line numbers count from 1 (sphere.1 is the first sphere line)"},
        {"light.position=1 2 3", "--set light.position=1 2 3: the scene has no light line"},
        {"sphere.big.radius=1", "--set sphere.big.radius=1: only materials have names; use sphere.N for the Nth sphere line"},
        {"a.b.c.d=1", "--set a.b.c.d=1: PATH has more than three parts"},
        {"sphere.2x.radius=1", "--set sphere.2x.radius=1: '2x' is not a line number (digits only, at most 2147483647)"},
        {"sphere.4294967297.radius=1",
         "--set sphere.4294967297.radius=1: '4294967297' is not a line number (digits only, at most 2147483647)"},
        {"sphere.2147483648.radius=1",
         "--set sphere.2147483648.radius=1: '2147483648' is not a line number (digits only, at most 2147483647)"},
        {"sphere.2147483647.radius=1", "--set sphere.2147483647.radius=1: the scene has fewer than 2147483647 sphere lines"},
        /* a KEY that is a value of the line: "0" once matched the centre's x and moved the sphere */
        {"sphere.1.0=5 6", "--set sphere.1.0=5 6: '0' is not a key's name (a letter, then letters, digits or '_')"},
        /* a line break in PATH once added a line of its own to the scene */
        {"camera.up 0 1 0\nsphere centre 2 1 0 radius=1",
         "--set camera.up 0 1 0\nsphere centre 2 1 0 radius=1: PATH may not contain blanks, '#' or a line break"},
        {"camera#.fov=1", "--set camera#.fov=1: PATH may not contain blanks, '#' or a line break"},
        /* empty parts, which splitting at the dots once skipped: camera..fov changed the camera's fov */
        {"camera..fov=3", "--set camera..fov=3: PATH has an empty part (a dot at an end, or two together)"},
        {".camera.fov=20", "--set .camera.fov=20: PATH has an empty part (a dot at an end, or two together)"},
        {"sphere.1..radius=0.2", "--set sphere.1..radius=0.2: PATH has an empty part (a dot at an end, or two together)"},
        {"max_depth.=3", "--set max_depth.=3: PATH has an empty part (a dot at an end, or two together)"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char err[256];
        cr_assert_null(changed(cases[k].spec, err, sizeof err), "%s was accepted", cases[k].spec);
        cr_assert_str_eq(err, cases[k].message);
    }
}

/* The key is looked for only where keys stand, after the line's positional words, each key followed
 * by its old value: a material's name, or a word of a value, is never taken for a key. */
Test(scene_set, a_key_is_found_only_where_keys_stand) {
    char err[2048]; /* the message repeats the spec */
    /* "clay" is the 2nd sphere's material (a value) and the 4th line's name: material.clay.colour below
     * changes the material, and sphere.2.clay is no key of the sphere line, so it is added as one (the
     * parser then refuses it) rather than changing the material the sphere names */
    char *text = changed("sphere.2.clay=3", err, sizeof err);
    cr_assert_not_null(text, "%s", err);
    cr_expect(strstr(text, "sphere centre 2 0 0 radius 0.5 material clay clay 3\n") != NULL, "%s", text);
    free(text);
    text = changed("material.1.ior=1.33", err, sizeof err);
    cr_assert_not_null(text, "%s", err);
    cr_expect(strstr(text, "material glass colour 1 1 1 transmit 0.9 ior 1.33\n") != NULL, "%s", text);
    free(text);
    /* an object's name and file and a key's label are not keys either */
    char *scene = strdup("object bunny bunny.ply smooth off\ninstance bunny id bunny scale 1 1 1\n"
                         "key bunny time 0 scale 2 2 2\n");
    cr_assert(scene_set_apply(&scene, "object.1.smooth=on", err, sizeof err), "%s", err);
    cr_assert(scene_set_apply(&scene, "instance.1.id=hare", err, sizeof err), "%s", err);
    cr_assert(scene_set_apply(&scene, "key.1.bunny=hare", err, sizeof err), "%s", err);
    cr_expect_str_eq(scene, "object bunny bunny.ply smooth on\ninstance bunny id hare scale 1 1 1\n"
                            "key bunny time 0 scale 2 2 2 bunny hare\n");
    free(scene);
    /* limits, each with its own reason */
    char spec[1024];
    snprintf(spec, sizeof spec, "camera.fov=%0600d", 1);
    cr_assert_null(changed(spec, err, sizeof err));
    cr_expect(strstr(err, ": VALUE is longer than 511 bytes") != NULL, "%s", err);
    snprintf(spec, sizeof spec, "camera.%0300d=1", 1);
    cr_assert_null(changed(spec, err, sizeof err));
    cr_expect(strstr(err, ": PATH is longer than 255 bytes") != NULL, "%s", err);
    int at = snprintf(spec, sizeof spec, "camera.fov=");
    for (int k = 0; k < 65; k++)
        at += snprintf(spec + at, sizeof spec - (size_t)at, "1 ");
    cr_assert_null(changed(spec, err, sizeof err));
    cr_expect(strstr(err, ": VALUE has more than 64 words") != NULL, "%s", err);
}

/* The parser parts words at vertical tabs and form feeds too: --set once took "sphere\vcentre ..." for
 * no sphere line, and changed the next sphere instead (exit 0). */
Test(scene_set, lines_are_found_with_the_parsers_blanks) {
    char err[512];
    char *scene = strdup("image\f16 12\nsphere\vcentre -1 0 0 radius 0.5\nsphere centre 1 0 0 radius 0.5\n"
                         "material\vglass\fcolour 1 0 0\n");
    cr_assert(scene_set_apply(&scene, "sphere.1.radius=0.1", err, sizeof err), "%s", err);
    cr_assert(scene_set_apply(&scene, "sphere.2.radius=0.2", err, sizeof err), "%s", err);
    cr_assert(scene_set_apply(&scene, "material.glass.ior=1.5", err, sizeof err), "%s", err);
    cr_assert(scene_set_apply(&scene, "image=8 8", err, sizeof err), "%s", err);
    cr_expect_str_eq(scene, "image 8 8\nsphere centre -1 0 0 radius 0.1\nsphere centre 1 0 0 radius 0.2\n"
                            "material glass colour 1 0 0 ior 1.5\n");
    free(scene);
}

/* A scene may start with a byte-order mark, which the reader skips; so does --set: its first line was
 * not found behind the mark, so sphere.1 changed the second sphere, and camera.fov and image, not found
 * at all, added a second line of their kind. The mark is kept. */
Test(scene_set, a_byte_order_mark_before_the_first_line_is_skipped_and_kept) {
    char err[512];
    char *scene = strdup(SCENE_UTF8_BOM "sphere centre -1.5 0 0 radius 0.5\nsphere centre 1.5 0 0 radius 0.5\n");
    cr_assert(scene_set_apply(&scene, "sphere.1.radius=1.2", err, sizeof err), "%s", err);
    cr_expect_str_eq(scene, SCENE_UTF8_BOM "sphere centre -1.5 0 0 radius 1.2\nsphere centre 1.5 0 0 radius 0.5\n");
    free(scene);
    scene = strdup(SCENE_UTF8_BOM "camera eye 0 0 5 target 0 0 0 fov 40\nimage 4 3\n");
    cr_assert(scene_set_apply(&scene, "camera.fov=30", err, sizeof err), "%s", err);
    cr_expect_str_eq(scene, SCENE_UTF8_BOM "camera eye 0 0 5 target 0 0 0 fov 30\nimage 4 3\n");
    free(scene);
    scene = strdup(SCENE_UTF8_BOM "image 4 3\ncamera eye 0 0 5 target 0 0 0 fov 40\n");
    cr_assert(scene_set_apply(&scene, "image=8 6", err, sizeof err), "%s", err);
    cr_expect_str_eq(scene, SCENE_UTF8_BOM "image 8 6\ncamera eye 0 0 5 target 0 0 0 fov 40\n");
    free(scene);
}

Test(scene_set, a_bad_value_is_the_parsers_error_at_the_scene_line) {
    struct scene s;
    bool bad_spec = true;
    char err[512];
    const char *specs[] = {"camera.fov=wide"};
    cr_assert(!scene_load_changed("scenes/02-sphere.scene", specs, 1, NULL, &s, &bad_spec, err, sizeof err));
    cr_assert(!bad_spec);
    cr_assert_not_null(strstr(err, "scenes/02-sphere.scene:"), "%s", err);
    cr_assert_not_null(strstr(err, "'wide' (the line as changed by --set)"), "%s", err);
}

/* The note is for an error at a line the changes made (rewritten, or added after the last), whose text
 * in the file may not show the bad value; an error at a line they left alone carries none. */
Test(scene_set, only_an_error_at_a_line_the_changes_made_carries_the_note) {
    cr_assert_eq(system("mkdir -p out/test"), 0);
    const char *path = "out/test/set-note.scene";
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs(base, f);
    fputs("sphere centre 0 2 0 radius -1 material clay\n", f); /* line 7: wrong in the file itself */
    cr_assert_eq(fclose(f), 0);
    struct scene s;
    bool bad_spec;
    char err[512];
    const char *elsewhere[] = {"camera.fov=30"};
    cr_assert(!scene_load_changed(path, elsewhere, 1, NULL, &s, &bad_spec, err, sizeof err));
    cr_expect(!bad_spec);
    cr_expect_str_eq(err, "out/test/set-note.scene:7: sphere radius must be positive, got -1");
    const char *there[] = {"camera.fov=30", "sphere.3.radius=-2"};
    cr_assert(!scene_load_changed(path, there, 2, NULL, &s, &bad_spec, err, sizeof err));
    cr_expect_str_eq(err, "out/test/set-note.scene:7: sphere radius must be positive, got -2 "
                          "(the line as changed by --set)");
    const char *added[] = {"max_depth=0"};
    cr_assert(!scene_load_changed("scenes/02-sphere.scene", added, 1, NULL, &s, &bad_spec, err, sizeof err));
    cr_expect_str_eq(err, "scenes/02-sphere.scene:17: 'max_depth' must be between 1 and 64, got 0 "
                          "(the line as changed by --set)");
}

Test(scene_set, the_chapter_programs_take_set_and_say_what_is_wrong) {
    const char *build = getenv("WHITTED_BUILD");
    char command[512];
    snprintf(command, sizeof command,
             "%s/chapter-08 --set material.glass.ior=1.45 --set max_depth=2 --set image='40 30' "
             "-o out/test/set-ok.png --quiet", build != NULL ? build : "build");
    cr_assert_eq(system(command), 0);
    snprintf(command, sizeof command, "%s/chapter-08 --set material.nope.ior=1 -o out/test/set-bad.png 2>/dev/null",
             build != NULL ? build : "build");
    int status = system(command);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 2, "a wrong --set is a command-line error (2)");
}

/* test_shapes.c: the table of kinds of shape (shape.h, shape_kinds.h): what it holds, that the scene's
 * two views of its shapes are one memory, that every kind's queries agree with each other (the nearest
 * hit is the nearest crossing, every crossing lies in the kind's bounding box), and that chapters draw
 * exactly the kinds introduced up to them. Every kind in the table is tested, so a new one is too. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "world.h"

#define NAME "test.scene"

/* One shape of every kind, several of some, in a scene. A new kind adds its line here. */
static const char scene_text[] =
    "camera eye 0 0 5 target 0 0 0 fov 60\n"
    "image 4 3\n"
    "material red colour 1 0 0\n"
    "sphere centre 0.5 -0.2 0.1 radius 0.9 material red\n"
    "sphere centre -1 0.4 -0.6 radius 0.4\n"
    "triangle a -1 -1 0 b 1.2 -0.8 0.3 c 0.1 1.1 -0.4\n"
    "plane normal 0.2 1 0.1 distance -0.7\n"
    "box min -0.4 -0.3 -0.9 max 0.6 0.8 0.2 material red\n"
    "box min 0.8 -1 -1 max 1.3 -0.2 0.4\n";

Test(shapes, the_table_lists_every_kind_with_its_chapter_and_bit) {
    static const struct {
        const char *keyword, *plural;
        int chapter;
        unsigned feature;
    } expected[] = {{"sphere", "spheres", 2, SCENE_SPHERES},
                    {"triangle", "triangles", 3, SCENE_TRIANGLES},
                    {"plane", "planes", 4, SCENE_PLANES},
                    {"box", "boxes", 5, SCENE_BOXES}};
    cr_assert_geq(SHAPE_KIND_COUNT, 4);
    for (size_t k = 0; k < 4; k++) {
        cr_assert_str_eq(shape_kinds[k].keyword, expected[k].keyword);
        cr_assert_str_eq(shape_kinds[k].plural, expected[k].plural);
        cr_assert_eq(shape_kinds[k].chapter, expected[k].chapter, "%s", expected[k].keyword);
        cr_assert_eq(shape_kinds[k].feature, expected[k].feature, "%s", expected[k].keyword);
    }
    unsigned seen = 0;
    for (size_t k = 0; k < SHAPE_KIND_COUNT; k++) {
        const struct shape_kind *kind = &shape_kinds[k];
        cr_assert_eq(kind->feature & seen, 0, "%s shares a feature bit", kind->keyword);
        seen |= kind->feature;
        cr_assert(kind->material_offset + sizeof(int) <= kind->size, "%s: material outside the struct",
                  kind->keyword);
        cr_assert_not_null(kind->syntax, "%s", kind->keyword);
        cr_assert_lt(kind->syntax->key_count, KEY_MAX, "%s: the parser adds `material` to at most KEY_MAX - 1 keys",
                     kind->keyword);
        cr_assert_not_null(kind->behaviour, "%s: the tests link every module, so every kind has behaviour",
                           kind->keyword);
    }
}

Test(shapes, the_named_arrays_and_the_arrays_by_kind_are_the_same) {
    struct scene s;
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, &s, err, sizeof err), "%s", err);
    cr_assert_eq((void *)s.spheres, s.shapes[SHAPE_SPHERES].items);
    cr_assert_eq(s.sphere_count, 2);
    cr_assert_eq(s.shapes[SHAPE_SPHERES].count, 2);
    cr_assert_eq((void *)s.boxes, s.shapes[SHAPE_BOXES].items);
    cr_assert_eq(s.shapes[SHAPE_BOXES].count, 2);
    cr_assert_eq(s.boxes[0].material, 1);
    cr_assert_eq(s.boxes[1].material, 0);
    cr_assert_eq(s.shapes[SHAPE_TRIANGLES].count, 1);
    cr_assert_eq(s.shapes[SHAPE_PLANES].count, 1);
    scene_free(&s);
}

/* Records every crossing: the nearest, and whether all lay in a box. */
struct crossings {
    const ray *r;
    vec3 min, max;
    bool bounded;
    int count;
    double nearest;
    bool outside; /* a crossing point outside the box */
};

static bool record(void *context, double t, int material) {
    (void)material;
    struct crossings *c = context;
    c->count++;
    c->nearest = fmin(c->nearest, t);
    vec3 p = ray_at(*c->r, t);
    double slack = 1e-9 * (1.0 + fabs(t)); /* the point is computed, so it may stray by rounding */
    if (c->bounded)
        for (int a = 0; a < 3; a++)
            c->outside |= vec3_axis(p, a) < vec3_axis(c->min, a) - slack || vec3_axis(p, a) > vec3_axis(c->max, a) + slack;
    return true;
}

/* A repeatable stream of numbers in [-1, 1). */
static double next_number(unsigned long long *state) {
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*state >> 11) / (double)(1ULL << 52) - 1.0;
}

Test(shapes, every_kinds_nearest_hit_is_its_nearest_crossing_and_lies_in_its_bounds) {
    struct scene s;
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, &s, err, sizeof err), "%s", err);
    unsigned long long state = 12345;
    for (size_t k = 0; k < SHAPE_KIND_COUNT; k++) {
        const struct shape_kind *kind = &shape_kinds[k];
        const struct scene_shapes *shapes = &s.shapes[k];
        cr_assert_gt(shapes->count, 0, "add a %s to scene_text", kind->keyword);
        int hits = 0;
        for (int n = 0; n < 2000; n++) {
            vec3 origin = vec3_scale(vec3_make(next_number(&state), next_number(&state), next_number(&state)), 3.0);
            vec3 towards = vec3_scale(vec3_make(next_number(&state), next_number(&state), next_number(&state)), 0.5);
            ray r = {origin, vec3_normalize(vec3_sub(towards, origin))};
            struct hit h = hit_nothing(INFINITY);
            bool hit = kind->behaviour->closest(shapes->items, shapes->count, &r, RAY_T_MIN, &h);
            struct crossings all = {&r, {0, 0, 0}, {0, 0, 0}, false, 0, INFINITY, false};
            for (size_t item = 0; item < shapes->count; item++) {
                const char *one = (const char *)shapes->items + item * kind->size;
                all.bounded = kind->behaviour->bounds(one, &all.min, &all.max);
                kind->behaviour->crossings(one, 1, &r, RAY_T_MIN, INFINITY, record, &all);
                cr_assert(!all.outside, "%s %zu: a crossing outside its bounds", kind->keyword, item + 1);
            }
            cr_assert_eq(hit, all.count > 0, "%s, ray %d: nearest hit %d but %d crossings", kind->keyword, n, hit,
                         all.count);
            if (hit) {
                hits++;
                cr_assert_eq(h.t, all.nearest, "%s, ray %d: nearest hit at %.17g, nearest crossing at %.17g",
                             kind->keyword, n, h.t, all.nearest);
                cr_assert_float_eq(vec3_length(h.normal), 1.0, 1e-12, "%s: the normal is not unit length",
                                   kind->keyword);
            }
        }
        cr_assert_gt(hits, 100, "%s: only %d of 2000 rays hit; the test says little", kind->keyword, hits);
    }
    scene_free(&s);
}

Test(shapes, a_chapter_draws_only_kinds_introduced_up_to_it) {
    struct scene s;
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, &s, err, sizeof err), "%s", err);
    char *note = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&note, &size);
    cr_assert_not_null(out);
    scene_drop_unsupported(&s, SCENE_EVERY_SHAPE, 4, out); /* boxes arrive in chapter 5 */
    cr_assert_eq(fclose(out), 0);
    cr_assert_str_eq(note, NAME ": chapter 4 ignores 2 boxes (not introduced yet)\n");
    cr_assert_eq(s.sphere_count + s.triangle_count + s.plane_count, 4);
    cr_assert_eq(s.box_count, 0);
    free(note);
    scene_free(&s);
}

Test(shapes, the_world_searches_bounded_kinds_then_triangles_then_unbounded_kinds) {
    struct scene s;
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, &s, err, sizeof err), "%s", err);
    struct world w;
    cr_assert(world_init(&w, &s, err, sizeof err), "%s", err);
    size_t expected[] = {SHAPE_SPHERES, SHAPE_BOXES, SHAPE_TRIANGLES, SHAPE_PLANES};
    cr_assert_eq(w.kind_count, 4);
    for (size_t k = 0; k < 4; k++)
        cr_assert_eq(w.kinds[k].kind, expected[k], "place %zu: kind %zu, expected %zu", k, w.kinds[k].kind,
                     expected[k]);
    world_free(&w);
    /* Kinds without shapes are not visited, except the triangles, which also stand for the meshes. */
    s.sphere_count = 0;
    s.plane_count = 0;
    cr_assert(world_init(&w, &s, err, sizeof err), "%s", err);
    cr_assert_eq(w.kind_count, 2);
    cr_assert_eq(w.kinds[0].kind, SHAPE_BOXES);
    cr_assert_eq(w.kinds[1].kind, SHAPE_TRIANGLES);
    world_free(&w);
    scene_free(&s);
}

/* test_shapes.c: the kinds of shape (shape.h): what their tables hold, that the scene keeps one list per
 * kind with the kinds the program draws, that every kind's queries agree with each other (the nearest
 * hit is the nearest crossing, every crossing lies in the kind's bounding box, a closed shape contains
 * exactly the points from which a ray crosses it an odd number of times), and that chapters draw exactly
 * the kinds they list. Every kind of test_every_kind is tested, so a new one is too. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "box.h"
#include "plane.h"
#include "scene.h"
#include "sphere.h"
#include "test_support.h"
#include "triangle.h"
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

/* Reads scene_text, drawing every kind. */
static void parse_every_kind(struct scene *s) {
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, test_every_kind, s, err, sizeof err), "%s", err);
}

Test(shapes, the_scene_format_reads_every_kind_and_each_kind_points_at_its_line) {
    static const struct {
        const char *keyword, *plural;
    } expected[] = {{"sphere", "spheres"}, {"triangle", "triangles"}, {"plane", "planes"}, {"box", "boxes"}};
    size_t count = 0;
    while (scene_syntaxes[count] != NULL)
        count++;
    cr_assert_eq(count, 4);
    for (size_t k = 0; k < count; k++) {
        const struct shape_syntax *syntax = scene_syntaxes[k];
        cr_assert_str_eq(syntax->keyword, expected[k].keyword);
        cr_assert_str_eq(syntax->plural, expected[k].plural);
        cr_assert(syntax->material_offset + sizeof(int) <= syntax->size, "%s: material outside the struct",
                  syntax->keyword);
        cr_assert_lt(syntax->key_count, KEY_MAX, "%s: the parser adds `material` to at most KEY_MAX - 1 keys",
                     syntax->keyword);
        cr_assert_eq(test_every_kind[k]->syntax, syntax, "the tests' kind %zu is not the %s", k, syntax->keyword);
    }
    cr_assert_null(test_every_kind[count], "a kind the scene format does not read");
}

Test(shapes, the_scene_keeps_one_list_per_kind_in_the_formats_order) {
    struct scene s;
    parse_every_kind(&s);
    cr_assert_eq(s.kind_count, 4);
    static const size_t counts[] = {2, 1, 1, 2};
    for (size_t k = 0; k < s.kind_count; k++) {
        cr_assert_eq(s.shapes[k].syntax, scene_syntaxes[k]);
        cr_assert_eq(s.shapes[k].kind, test_every_kind[k], "the %s have not their kind", s.shapes[k].syntax->plural);
        cr_assert_eq(s.shapes[k].count, counts[k], "%s", s.shapes[k].syntax->plural);
    }
    const struct box *boxes = scene_shapes(&s, &box_syntax)->items;
    cr_assert_eq(boxes[0].material, 1);
    cr_assert_eq(boxes[1].material, 0);
    scene_free(&s);
    /* Without kinds, the shapes are read all the same: chapter 1 reads every scene. */
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, NULL, &s, err, sizeof err), "%s", err);
    for (size_t k = 0; k < s.kind_count; k++)
        cr_assert(s.shapes[k].kind == NULL && s.shapes[k].count == counts[k], "%s", s.shapes[k].syntax->plural);
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
    parse_every_kind(&s);
    unsigned long long state = 12345;
    for (size_t k = 0; k < s.kind_count; k++) {
        const struct shape_list *shapes = &s.shapes[k];
        const struct shape_kind *kind = shapes->kind;
        const char *keyword = shapes->syntax->keyword;
        cr_assert_gt(shapes->count, 0, "add a %s to scene_text", keyword);
        int hits = 0;
        for (int n = 0; n < 2000; n++) {
            vec3 origin = vec3_scale(vec3_make(next_number(&state), next_number(&state), next_number(&state)), 3.0);
            vec3 towards = vec3_scale(vec3_make(next_number(&state), next_number(&state), next_number(&state)), 0.5);
            ray r = {origin, vec3_normalize(vec3_sub(towards, origin))};
            struct hit h = hit_nothing(INFINITY);
            bool hit = kind->closest(shapes->items, shapes->count, &r, RAY_T_MIN, &h);
            struct crossings all = {&r, {0, 0, 0}, {0, 0, 0}, false, 0, INFINITY, false};
            for (size_t item = 0; item < shapes->count; item++) {
                const void *one = shape_item(shapes->syntax, shapes->items, item);
                all.bounded = kind->bounds(one, &all.min, &all.max);
                kind->crossings(one, 1, &r, RAY_T_MIN, INFINITY, record, &all);
                cr_assert(!all.outside, "%s %zu: a crossing outside its bounds", keyword, item + 1);
            }
            cr_assert_eq(hit, all.count > 0, "%s, ray %d: nearest hit %d but %d crossings", keyword, n, hit,
                         all.count);
            if (hit) {
                hits++;
                cr_assert_eq(h.t, all.nearest, "%s, ray %d: nearest hit at %.17g, nearest crossing at %.17g",
                             keyword, n, h.t, all.nearest);
                cr_assert_float_eq(vec3_length(h.normal), 1.0, 1e-12, "%s: the normal is not unit length", keyword);
                cr_assert(h.object >= 0 && (size_t)h.object < shapes->count, "%s: object %d is no index", keyword,
                          h.object);
                const void *nearest = shape_item(shapes->syntax, shapes->items, (size_t)h.object);
                cr_assert_eq(h.material, shape_material(shapes->syntax, nearest), "%s: not the material of the "
                             "shape h.object names", keyword);
            }
        }
        cr_assert_gt(hits, 100, "%s: only %d of 2000 rays hit; the test says little", keyword, hits);
    }
    scene_free(&s);
}

/* A closed shape contains a point exactly when a ray from the point crosses its surface an odd number of
 * times. Tested for every bounded kind with an inside, from points around and inside the shapes. */
Test(shapes, a_closed_shape_contains_the_points_a_ray_leaves_it_from) {
    struct scene s;
    parse_every_kind(&s);
    unsigned long long state = 777;
    size_t kinds_tested = 0;
    for (size_t k = 0; k < s.kind_count; k++) {
        const struct shape_list *shapes = &s.shapes[k];
        const struct shape_kind *kind = shapes->kind;
        vec3 min, max;
        if (kind->contains == NULL || !kind->bounds(shapes->items, &min, &max))
            continue; /* no inside (a triangle), or not closed (a plane) */
        kinds_tested++;
        int inside = 0;
        for (size_t item = 0; item < shapes->count; item++) {
            const void *one = shape_item(shapes->syntax, shapes->items, item);
            for (int n = 0; n < 500; n++) {
                vec3 point = vec3_make(next_number(&state), next_number(&state), next_number(&state));
                vec3 direction =
                    vec3_normalize(vec3_make(next_number(&state), next_number(&state), next_number(&state)));
                ray r = {point, direction};
                struct crossings all = {&r, {0, 0, 0}, {0, 0, 0}, false, 0, INFINITY, false};
                kind->crossings(one, 1, &r, 0.0, INFINITY, record, &all);
                bool contains = kind->contains(one, point);
                cr_assert_eq(contains, all.count % 2 == 1, "%s %zu, point (%g, %g, %g): contains says %d, %d crossings",
                             shapes->syntax->keyword, item + 1, point.x, point.y, point.z, contains, all.count);
                inside += contains;
            }
        }
        cr_assert_gt(inside, 50, "%s: only %d points inside; the test says little", shapes->syntax->keyword, inside);
    }
    cr_assert_eq(kinds_tested, 2, "the sphere and the box");
    scene_free(&s);
}

Test(shapes, a_chapter_draws_only_the_kinds_it_lists) {
    static const struct shape_kind *const chapter_4[] = {&sphere_kind, &triangle_kind, &plane_kind, NULL};
    struct scene s;
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, chapter_4, &s, err, sizeof err), "%s", err);
    char *note = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&note, &size);
    cr_assert_not_null(out);
    scene_drop_unsupported(&s, 4, out); /* boxes arrive in chapter 5 */
    cr_assert_eq(fclose(out), 0);
    cr_assert_str_eq(note, NAME ": chapter 4 ignores 2 boxes (not introduced yet)\n");
    cr_assert_eq(scene_shapes(&s, &sphere_syntax)->count + scene_shapes(&s, &triangle_syntax)->count +
                     scene_shapes(&s, &plane_syntax)->count, 4);
    cr_assert_eq(scene_shapes(&s, &box_syntax)->count, 0);
    free(note);
    scene_free(&s);
}

Test(shapes, the_world_searches_bounded_kinds_then_triangles_then_unbounded_kinds) {
    struct scene s;
    parse_every_kind(&s);
    struct world w;
    char err[256];
    cr_assert(world_init(&w, &s, err, sizeof err), "%s", err);
    cr_assert_eq(w.bounded_count, 2);
    cr_assert_eq(w.bounded[0].kind, &sphere_kind);
    cr_assert_eq(w.bounded[1].kind, &box_kind);
    cr_assert_eq(w.triangles.kind, &triangle_kind);
    cr_assert_eq(w.triangles.count, 1);
    cr_assert_eq(w.unbounded_count, 1);
    cr_assert_eq(w.unbounded[0].kind, &plane_kind);
    /* The objects are numbered list by list in the scene's order: spheres 0-1, triangle 2, plane 3, boxes 4-5. */
    cr_assert_eq(w.bounded[0].first_object, 0);
    cr_assert_eq(w.triangles.first_object, 2);
    cr_assert_eq(w.unbounded[0].first_object, 3);
    cr_assert_eq(w.bounded[1].first_object, 4);
    world_free(&w);
    /* Kinds without shapes are not visited. */
    s.shapes[0].count = 0; /* the spheres */
    s.shapes[2].count = 0; /* the plane */
    cr_assert(world_init(&w, &s, err, sizeof err), "%s", err);
    cr_assert_eq(w.bounded_count, 1);
    cr_assert_eq(w.bounded[0].kind, &box_kind);
    cr_assert_eq(w.unbounded_count, 0);
    world_free(&w);
    scene_free(&s);
}

Test(shapes, the_world_refuses_shapes_of_a_kind_the_program_does_not_draw) {
    struct scene s;
    char err[256];
    cr_assert(scene_parse(NAME, scene_text, NULL, &s, err, sizeof err), "%s", err);
    struct world w;
    cr_assert_not(world_init(&w, &s, err, sizeof err));
    cr_assert_str_eq(err, NAME ": 2 spheres of no kind (give the scene reader the kinds the program draws)");
    scene_free(&s);
}

/* A kind the scene format does not know is read when the program lists it, after the format's kinds;
 * one list per kind, up to SCENE_KIND_MAX in all. */
Test(shapes, a_kind_the_program_lists_is_read_up_to_the_most_kinds_a_scene_holds) {
    enum { EXTRA = SCENE_KIND_MAX - 4 + 1 }; /* one more than fits beside the format's four kinds */
    static struct shape_syntax syntaxes[EXTRA];
    static struct shape_kind kinds[EXTRA];
    static char keywords[EXTRA][16];
    const struct shape_kind *list[EXTRA + 1];
    for (int k = 0; k < EXTRA; k++) {
        snprintf(keywords[k], sizeof keywords[k], "ball%d", k);
        syntaxes[k] = sphere_syntax; /* a sphere's line and queries under another keyword */
        syntaxes[k].keyword = keywords[k];
        kinds[k] = sphere_kind;
        kinds[k].syntax = &syntaxes[k];
        list[k] = &kinds[k];
    }
    char text[256], err[256];
    snprintf(text, sizeof text, "camera eye 0 0 5 target 0 0 0 fov 60\nimage 4 3\nball%d centre 1 2 3 radius 0.5\n",
             EXTRA - 2);
    list[EXTRA] = NULL;
    struct scene s;
    char expected[128];
    cr_assert_not(scene_parse(NAME, text, list, &s, err, sizeof err));
    snprintf(expected, sizeof expected, NAME ": more than %d kinds of shape", SCENE_KIND_MAX);
    cr_assert_str_eq(err, expected);
    list[EXTRA - 1] = NULL; /* now exactly SCENE_KIND_MAX */
    cr_assert(scene_parse(NAME, text, list, &s, err, sizeof err), "%s", err);
    cr_assert_eq(s.kind_count, SCENE_KIND_MAX);
    const struct shape_list *balls = scene_shapes(&s, &syntaxes[EXTRA - 2]);
    cr_assert_not_null(balls);
    cr_assert_eq(balls->kind, &kinds[EXTRA - 2]);
    cr_assert_eq(balls->count, 1);
    cr_assert_eq(((const struct sphere *)balls->items)->radius, 0.5);
    scene_free(&s);
    /* Without the kind in the list, its line is no directive at all. */
    cr_assert_not(scene_parse(NAME, text, test_every_kind, &s, err, sizeof err));
    snprintf(expected, sizeof expected, NAME ":3: unknown directive 'ball%d'", EXTRA - 2);
    cr_assert_str_eq(err, expected);
}

/* test_instances.c: chapter 16's instances: the scene lines and their errors, the two-level queries
 * against brute force over every instance and triangle, the instanced picture against the same scene
 * written out in world space and drawn by chapter 11, refit against rebuild, the time of a sample,
 * thread counts, the twin against POV-Ray, and the hostile cases. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "image.h"
#include "image_test_support.h"
#include "instances.h"
#include "mesh_load.h"
#include "povray.h"
#include "scene.h"
#include "shutter.h"
#include "stats.h"
#include "test_support.h"
#include "triangle.h"

#define BUNNY "scenes/models/bunny.ply"
#define HEAD "camera eye 0 1 6 target 0 0.5 0 fov 40\nimage 64 48\nmaterial red colour 1 0 0\n"

/* ---- the lines ------------------------------------------------------------------------------------ */

Test(instance_lines, are_read_with_their_keys_poses_and_shutter) {
    struct scene s;
    char err[512];
    cr_assert(parse_scene_lines("scenes/inline.scene", "camera eye 0 1 6 target 0 0 0 fov 40 shutter 0.25\nimage 8 8\n"
                                "material red colour 1 0 0\n",
                                "object bunny models/bunny.ply smooth on\n"
                                "instance bunny material red scale 1 2 3 rotate 10 20 30 translate 4 5 6 id b\n"
                                "instance bunny\n"
                                "key b time 0.5 translate 1 0 0\n"
                                "key b time 1 scale 2 2 2",
                                test_every_kind, &s, err, sizeof err), "%s", err);
    cr_assert_eq(s.shutter, 0.25);
    cr_assert_eq(s.object_count, 1);
    cr_assert_str_eq(s.objects[0].path, "scenes/models/bunny.ply");
    cr_assert_eq(s.objects[0].smooth, SCENE_SMOOTH_ON);
    cr_assert_eq(s.instance_count, 2);
    const struct scene_instance *a = &s.instances[0], *b = &s.instances[1];
    cr_assert_eq(a->material, 1);
    cr_assert_str_eq(a->id, "b");
    cr_assert(a->pose.scale.y == 2 && a->pose.rotate.z == 30 && a->pose.translate.x == 4);
    cr_assert_eq(a->key_count, 2);
    /* what a key leaves out is the instance line's */
    cr_assert(a->keys[0].time == 0.5 && a->keys[0].pose.translate.x == 1 && a->keys[0].pose.scale.z == 3);
    cr_assert(a->keys[1].pose.scale.x == 2 && a->keys[1].pose.translate.y == 5 && a->keys[1].pose.rotate.x == 10);
    cr_assert_eq(a->keys[1].line, 8);
    cr_assert(b->material == 0 && b->key_count == 0 && b->pose.scale.x == 1 && b->id[0] == '\0');
    scene_free(&s);
}

Test(instance_lines, errors_name_the_file_line_and_what_is_wrong) {
    struct {
        const char *lines, *message;
    } cases[] = {
        {"instance bunyn", "x.scene:4: unknown object 'bunyn' (define it with an object line first)"},
        {"object bunny models/bunny.ply\nobject bunny models/bunny.ply", "x.scene:5: object 'bunny' is already defined"},
        {"object", "x.scene:4: object needs a name and a file name"},
        {"object b f smooth maybe", "x.scene:4: object smooth must be on or off, got 'maybe'"},
        {"object bunny models/bunny.ply\ninstance bunny id a\ninstance bunny id a",
         "x.scene:6: instance id 'a' is already defined"},
        {"object bunny models/bunny.ply\ninstance bunny scale 0 1 1",
         "x.scene:5: instance of 'bunny': scale is 0 1 1; each factor's size must be between 1e-09 and 1e+09 (a zero "
         "scale flattens the object)"},
        {"object bunny models/bunny.ply\ninstance bunny scale 1 1e10 1",
         "x.scene:5: instance of 'bunny': scale is 1 10000000000 1; each factor's size must be between 1e-09 and 1e+09 "
         "(a zero scale flattens the object)"},
        {"object bunny models/bunny.ply\ninstance bunny rotate 0 1e7 0",
         "x.scene:5: instance of 'bunny': rotate is (0, 10000000, 0); it must stay within -1e+06 .. 1e+06"},
        {"object bunny models/bunny.ply\ninstance bunny translate 0 0 1e19",
         "x.scene:5: instance of 'bunny': translate is (0, 0, 1e+19); it must stay within -1e+18 .. 1e+18"},
        {"object bunny models/bunny.ply\ninstance bunny material glass",
         "x.scene:5: unknown material 'glass' (define it with a material line first)"},
        {"object bunny models/bunny.ply\ninstance bunny id b\nkey c time 0",
         "x.scene:6: unknown instance id 'c' (give an instance line 'id c' first)"},
        {"object bunny models/bunny.ply\ninstance bunny id b\nkey b translate 1 0 0", "x.scene:6: key needs 'time'"},
        {"object bunny models/bunny.ply\ninstance bunny id b\nkey b time 1.5",
         "x.scene:6: key of 'b': key time must be between 0 and 1, got 1.5"},
        {"object bunny models/bunny.ply\ninstance bunny id b\nkey b time 0.5\nkey b time 0.2",
         "x.scene:7: key of 'b': key time 0.2 is not after the instance's previous key's (0.5): keys go in increasing "
         "time"},
        {"object bunny models/bunny.ply\ninstance bunny id b\nkey b time 0.5\nkey b time 0.5",
         "x.scene:7: key of 'b': key time 0.5 is not after the instance's previous key's (0.5): keys go in increasing "
         "time"},
        {"object bunny models/bunny.ply\ninstance bunny id b\nkey b time 1 scale 1 0 1",
         "x.scene:6: key of 'b': scale is 1 0 1; each factor's size must be between 1e-09 and 1e+09 (a zero scale "
         "flattens the object)"},
        {"instance", "x.scene:4: instance needs the name of an object"},
        {"object bunny models/bunny.ply\ninstance bunny id b\ninstance b", "x.scene:6: unknown object 'b' (define it "
         "with an object line first)"},
        {"key", "x.scene:4: key needs the id of an instance"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        expect_scene_refused("x.scene", HEAD, cases[k].lines, test_every_kind, cases[k].message);
    expect_scene_refused("x.scene", "camera eye 0 1 6 target 0 0 0 fov 40 shutter 2\n", "image 8 8",
                         test_every_kind, "x.scene:1: camera shutter must be between 0 and 1 (clock units), got 2");
}

/* parse_scene_lines for texts longer than it takes: HEAD, then `lines`, as the scene file `name`. */
static bool parse_long(const char *name, const char *lines, struct scene *s, char *err, size_t err_size) {
    char *text = malloc(strlen(HEAD) + strlen(lines) + 2);
    cr_assert_not_null(text);
    sprintf(text, "%s%s\n", HEAD, lines);
    bool parsed = scene_parse(name, text, test_every_kind, s, err, err_size);
    free(text);
    return parsed;
}

/* Expects parse_long to refuse `lines` with exactly `message`. */
static void expect_long_refused(const char *lines, const char *message) {
    struct scene s;
    char err[512] = "";
    bool parsed = parse_long("x.scene", lines, &s, err, sizeof err);
    if (parsed)
        scene_free(&s);
    cr_assert(!parsed);
    cr_assert_str_eq(err, message);
}

/* Returns "FIRST\n" followed by `count` lines made by line(k, buffer, size), without the last newline. */
static char *many_lines(const char *first, size_t count, size_t line_size, void (*line)(size_t k, char *out, size_t size)) {
    char *text = malloc(strlen(first) + 1 + count * line_size + 1), *at = text;
    cr_assert_not_null(text);
    at += sprintf(at, "%s\n", first);
    for (size_t k = 0; k < count; k++) {
        line(k, at, line_size);
        at += strlen(at);
    }
    at[-1] = '\0';
    return text;
}

static void key_line(size_t k, char *out, size_t size) {
    snprintf(out, size, "key b time %.17g translate %zu 0 0\n", (double)k / 2048.0, k);
}

Test(instance_lines, take_a_thousand_keys_and_refuse_one_more_than_the_limit) {
    const char *first = "object bunny models/bunny.ply\ninstance bunny id b";
    char *most = many_lines(first, SCENE_KEY_MAX, 64, key_line), *over = many_lines(first, SCENE_KEY_MAX + 1, 64, key_line);
    struct scene s;
    char err[512];
    cr_assert(parse_long("x.scene", most, &s, err, sizeof err), "%s", err);
    cr_assert_eq(s.instances[0].key_count, SCENE_KEY_MAX);
    cr_assert_eq(s.instances[0].keys[999].pose.translate.x, 999);
    scene_free(&s);
    /* HEAD's 3 lines, the object and the instance: key k is on line 6 + k */
    expect_long_refused(over, "x.scene:1030: more than 1024 keys for instance 'b'");
    free(most);
    free(over);
}

static void instance_line(size_t k, char *out, size_t size) {
    snprintf(out, size, "instance t translate %zu 0 0\n", k % 1000);
}

Test(instance_lines, a_million_instances_are_read_and_one_more_than_the_limit_refused, .timeout = 120) {
    char *most = many_lines("object t models/bunny.ply", SCENE_INSTANCE_MAX, 40, instance_line);
    struct scene s;
    char err[512];
    cr_assert(parse_long("x.scene", most, &s, err, sizeof err), "%s", err);
    cr_assert_eq(s.instance_count, SCENE_INSTANCE_MAX);
    scene_free(&s);
    free(most);
    char *over = many_lines("object t models/bunny.ply", SCENE_INSTANCE_MAX + 1, 40, instance_line);
    /* HEAD's 3 lines and the object: instance k is on line 5 + k */
    expect_long_refused(over, "x.scene:1048581: more than 1048576 instance lines");
    free(over);
}

/* Parses `head` and `lines` as x.scene, lets chapter `chapter` drop what it does not draw, and expects
 * its note to be `expected`; returns the scene (free it with scene_free). */
static struct scene dropped_by(int chapter, const char *head, const char *lines, const char *expected) {
    struct scene s;
    char err[512], note[512] = "";
    cr_assert(parse_scene_lines("x.scene", head, lines, test_every_kind, &s, err, sizeof err), "%s", err);
    FILE *out = fmemopen(note, sizeof note, "w");
    scene_drop_unsupported(&s, chapter, out);
    fclose(out);
    cr_assert_str_eq(note, expected);
    return s;
}

Test(instance_lines, are_dropped_with_a_note_before_chapter_16) {
    struct scene s = dropped_by(15, "camera eye 0 1 6 target 0 0 0 fov 40 shutter 0.5\nimage 8 8\n",
                                "object a models/bunny.ply\nobject b models/bunny.ply\ninstance a id i\ninstance b\n"
                                "key i time 0",
                                "x.scene: chapter 15 ignores 2 objects, 2 instances, the camera's shutter (not introduced "
                                "yet)\n");
    cr_assert(s.object_count == 0 && s.instance_count == 0 && s.shutter == 0.0);
    scene_free(&s);
}

Test(instance_lines, chapter_16_ignores_pigments_paths_and_emission_as_chapter_13_does) {
    struct scene s = dropped_by(16, "camera eye 0 1 6 target 0 0 0 fov 40\nimage 8 8\n",
                                "pigment p checker colour 1 0 0 colour2 0 1 0\nmaterial m pigment p emission 1 1 1\n"
                                "paths samples 4\nobject a models/bunny.ply\ninstance a material m",
                                "x.scene: chapter 16 ignores 1 pigment, the emission of 1 material, the paths line "
                                "(chapter 16 is built on chapter 13's tracer)\n");
    cr_assert(s.instance_count == 1 && s.pigment_count == 0 && s.materials[1].pigment == -1);
    scene_free(&s);
}

/* ---- the two-level queries against brute force -------------------------------------------------- */

/* splitmix64: reproducible random numbers. */
static uint64_t next_random(uint64_t *state) {
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double uniform(uint64_t *state, double lo, double hi) {
    return lo + (hi - lo) * (double)(next_random(state) >> 11) * 0x1p-53;
}

/* A scene of 24 instances of the bunny and of a small tetrahedron soup, stretched, turned, mirrored and
 * overlapping, three of them moving. */
static const char *const FOREST =
    "object bunny models/bunny.ply\n"
    "object teapot models/teapot-5k.ply\n"
    "instance bunny scale 0.1 0.1 0.1 translate 0 0 0\n"
    "instance bunny scale 0.1 0.3 0.1 rotate 10 20 30 translate 0.4 0 0.2\n"
    "instance bunny scale -0.1 0.1 0.1 rotate 0 90 0 translate -0.5 0.1 0\n"
    "instance teapot scale 0.2 0.2 0.2 rotate 0 45 0 translate 1 0 -1\n"
    "instance teapot scale 0.3 0.1 0.2 rotate 90 0 0 translate -1 0.5 -1 material red\n"
    "instance teapot scale 0.2 0.2 0.2 translate 0 0 0 material red\n" /* overlaps the first bunny */
    "instance bunny scale 0.1 0.1 0.1 translate 0 0 0\n"              /* the first again: equal t, lower wins */
    "instance teapot scale 0.15 0.15 0.15 translate -1 0 1 id m1\n"
    "key m1 time 0 translate -1 0 1\nkey m1 time 1 translate 1 0 1 rotate 0 180 0\n"
    "instance bunny scale 0.08 0.08 0.08 id m2\n"
    "key m2 time 0.2 rotate 0 0 0 translate 0 1 0\nkey m2 time 0.6 rotate 90 0 45 translate 0 1 0.5\n"
    "key m2 time 0.9 scale 0.2 0.05 0.1 translate 0.5 0.5 0\n"
    "instance bunny scale 0.05 0.05 0.05 id m3\nkey m3 time 0.5 translate 0 0.2 1.5\n";

/* Parses FOREST (with more instances, `extra`) and builds its instances over [t0, t1]. */
static struct instances *forest(struct scene *s, const char *extra, double t0, double t1) {
    char err[4096];
    char *lines = malloc(strlen(FOREST) + strlen(extra) + 1);
    sprintf(lines, "%s%s", FOREST, extra);
    cr_assert(parse_scene_lines("scenes/forest.scene", HEAD, lines, test_every_kind, s, err, sizeof err), "%s", err);
    free(lines);
    struct instances *in = instances_create(s, 100, t0, t1, err, sizeof err);
    cr_assert_not_null(in, "%s", err);
    return in;
}

/* The brute-force nearest hit: every instance in order, every face in order, the ray carried into each
 * instance's space as instances.c carries it; the first of equal t wins. */
static bool brute_closest(const struct instances *in, const ray *r, double t_min, double time, struct hit *h) {
    bool found = false;
    for (size_t k = 0; k < in->count; k++) {
        struct transform to_world, to_object;
        if (!instances_transform_at(in, k, time, &to_world, &to_object))
            continue;
        ray local = {transform_point(&to_object, r->origin), transform_vector(&to_object, r->direction)};
        const struct mesh *m = &in->scene->objects[in->items[k].object].mesh;
        for (size_t f = 0; f < m->face_count; f++) {
            const uint32_t *c = m->faces[f].v;
            double t, u, v;
            if (triangle_intersect(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]], &local, t_min, h->t, &t, &u,
                                   &v)) {
                h->t = t;
                h->object = in->first_object + (int)k;
                h->face = (int)f;
                h->normal = vec3_normalize(transform_normal(&to_object, triangle_normal(m->vertices[c[0]],
                                                                                        m->vertices[c[1]],
                                                                                        m->vertices[c[2]])));
                found = true;
            }
        }
    }
    return found;
}

/* Collects crossings' t for comparison. */
struct crossing_list {
    double t[4096];
    int material[4096];
    size_t count;
};

static bool collect(void *context, double t, int material) {
    struct crossing_list *l = context;
    if (l->count < 4096) {
        l->t[l->count] = t;
        l->material[l->count] = material;
    }
    l->count++;
    return true;
}

static int by_t(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void brute_crossings(const struct instances *in, const ray *r, double t_min, double t_max, double time,
                            struct crossing_list *l) {
    for (size_t k = 0; k < in->count; k++) {
        struct transform to_world, to_object;
        if (!instances_transform_at(in, k, time, &to_world, &to_object))
            continue;
        ray local = {transform_point(&to_object, r->origin), transform_vector(&to_object, r->direction)};
        const struct mesh *m = &in->scene->objects[in->items[k].object].mesh;
        for (size_t f = 0; f < m->face_count; f++) {
            const uint32_t *c = m->faces[f].v;
            double t, u, v;
            if (triangle_intersect(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]], &local, t_min, t_max, &t, &u,
                                   &v))
                collect(l, t, in->items[k].material);
        }
    }
}

/* A random ray: from a point around the forest towards a point of an instance's box (so most hit), at a
 * random time in [t0, t1]. */
static ray random_ray(uint64_t *g, const struct instances *in, double *time, double t0, double t1) {
    size_t k = next_random(g) % in->count;
    struct aabb b = in->items[k].in_tree ? in->boxes[k] : (struct aabb){{-1, -1, -1}, {1, 1, 1}};
    vec3 to = vec3_make(uniform(g, b.min.x, b.max.x), uniform(g, b.min.y, b.max.y), uniform(g, b.min.z, b.max.z));
    vec3 from = vec3_make(uniform(g, -4, 4), uniform(g, -1, 4), uniform(g, -4, 4));
    double length = uniform(g, 0.01, 100.0); /* directions of any length: t is the same in both spaces */
    *time = uniform(g, t0, t1);
    return (ray){from, vec3_scale(vec3_normalize(vec3_sub(to, from)), length)};
}

Test(two_level, nearest_hits_and_crossings_equal_brute_force_exactly, .timeout = 120) {
    struct scene s;
    double t0 = 0.1, t1 = 0.7;
    struct instances *in = forest(&s, "", t0, t1);
    uint64_t g = 16;
    int hits = 0;
    for (int n = 0; n < 3000; n++) {
        double time;
        ray r = random_ray(&g, in, &time, t0, t1);
        struct hit fast = hit_nothing(INFINITY), slow = hit_nothing(INFINITY);
        bool a = in->hook.closest(in->hook.structure, &r, 1e-9, time, &fast);
        bool b = brute_closest(in, &r, 1e-9, time, &slow);
        cr_assert_eq(a, b, "ray %d: two levels %s, brute force %s", n, a ? "hit" : "missed", b ? "hit" : "missed");
        hits += a;
        if (!a)
            continue;
        cr_assert(fast.t == slow.t, "ray %d: t %.17g against %.17g", n, fast.t, slow.t);
        cr_assert_eq(fast.object, slow.object, "ray %d", n);
        cr_assert_eq(fast.face, slow.face, "ray %d", n);
        cr_assert(fast.normal.x == slow.normal.x && fast.normal.y == slow.normal.y && fast.normal.z == slow.normal.z);
        if (n % 10 == 0) {
            static struct crossing_list x, y;
            x.count = y.count = 0;
            double t_max = fast.t * uniform(&g, 0.5, 3.0);
            in->hook.for_each_crossing(in->hook.structure, &r, 1e-9, t_max, time, collect, &x);
            brute_crossings(in, &r, 1e-9, t_max, time, &y);
            cr_assert_eq(x.count, y.count, "ray %d: %zu crossings against %zu", n, x.count, y.count);
            qsort(x.t, x.count, sizeof x.t[0], by_t);
            qsort(y.t, y.count, sizeof y.t[0], by_t);
            for (size_t k = 0; k < x.count && k < 4096; k++)
                cr_assert(x.t[k] == y.t[k], "ray %d crossing %zu", n, k);
        }
    }
    cr_assert_gt(hits, 1500, "only %d of 3000 rays hit", hits);
    instances_free(in);
    scene_free(&s);
}

Test(two_level, a_refitted_top_level_stays_valid_and_answers_as_a_rebuilt_one, .timeout = 60) {
    struct scene s, s2;
    struct instances *refitted = forest(&s, "", 0.0, 0.1);
    struct instances *rebuilt = forest(&s2, "", 0.0, 0.1);
    char err[256], why[256];
    uint64_t g = 35;
    for (int frame = 1; frame <= 5; frame++) {
        double t0 = frame / 5.0 * 0.9, t1 = t0 + 0.1;
        cr_assert(instances_set_interval(refitted, t0, t1, INSTANCES_REFIT, err, sizeof err), "%s", err);
        cr_assert(instances_set_interval(rebuilt, t0, t1, INSTANCES_REBUILD, err, sizeof err), "%s", err);
        cr_assert(instance_bvh_is_valid(refitted->top, refitted->boxes, refitted->count, why, sizeof why),
                  "frame %d: %s", frame, why);
        for (int n = 0; n < 300; n++) {
            double time;
            ray r = random_ray(&g, refitted, &time, t0, t1);
            struct hit a = hit_nothing(INFINITY), b = hit_nothing(INFINITY);
            cr_assert_eq(refitted->hook.closest(refitted, &r, 1e-9, time, &a),
                         rebuilt->hook.closest(rebuilt, &r, 1e-9, time, &b));
            cr_assert(a.t == b.t || (isinf(a.t) && isinf(b.t)));
            cr_assert_eq(a.object, b.object);
        }
    }
    cr_assert_eq(refitted->info.refits, 5);
    instances_free(refitted);
    instances_free(rebuilt);
    scene_free(&s);
    scene_free(&s2);
}

Test(two_level, refuses_transforms_it_cannot_carry_rays_through) {
    struct scene s;
    char err[4096];
    struct {
        const char *lines, *message;
    } cases[] = {
        {"object bunny models/bunny.ply\ninstance bunny scale 1e-9 1 1e9",
         "scenes/x.scene:5: instance of 'bunny': its transform cannot be inverted accurately (its scale factors differ "
         "by more than the tracer can carry rays through)"},
        {"object bunny models/bunny.ply\ninstance bunny id a\nkey a time 0\nkey a time 1 scale -1 1 1",
         "scenes/x.scene:7: instance of 'bunny': a scale factor changes sign since the previous key, so it passes "
         "through zero (a flat object) in between"},
        {"object bunny models/bunny.ply\ninstance bunny scale 1e9 1e9 1e9 translate 1e18 0 0",
         "scenes/x.scene:5: instance of 'bunny': placed out of range (coordinates must stay within -1e18 .. 1e18 and "
         "the object at least 1e-18 across)"},
        {"object self x.scene\ninstance self", "scenes/x.scene:4: object 'self': scenes/x.scene: no faces"},
        {"object none models/no-such-mesh.ply\ninstance none",
         "scenes/x.scene:4: object 'none': scenes/models/no-such-mesh.ply: "},
        /* each key invertible (its turn keeps the thin axis on an axis), the pose half-way not */
        {"object bunny models/bunny.ply\ninstance bunny scale 8 8 1e-9 id a\nkey a time 0\nkey a time 1 rotate 0 0 90",
         "scenes/x.scene:7: instance of 'bunny': between the previous key and this one, a turn can make its "
         "transform impossible to invert accurately (a key's scale factors differ by more than a third of what the "
         "tracer can carry rays through)"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        cr_assert(parse_scene_lines("scenes/x.scene", HEAD, cases[k].lines, test_every_kind, &s, err, sizeof err), "%s",
                  err);
        /* the scene's own file as a mesh: it does not exist as scenes/x.scene, so write it for this case */
        FILE *self = k == 3 ? fopen("scenes/x.scene", "w") : NULL;
        if (self != NULL) {
            fputs(HEAD, self);
            fclose(self);
        }
        struct instances *in = instances_create(&s, 0, 0.0, 0.0, err, sizeof err);
        if (k == 3)
            remove("scenes/x.scene");
        cr_expect_null(in, "case %zu was accepted", k);
        instances_free(in);
        cr_expect(strncmp(err, cases[k].message, strlen(cases[k].message)) == 0, "case %zu: '%s'", k, err);
        scene_free(&s);
    }
}

/* Between two keys the bound is on each key's spread of scale factors, not on all six together: an
 * instance that grows evenly from 1e-9 to 1e9 is uniform at every moment, and was refused ("its scale
 * factors differ by more than a third of what the tracer can carry rays through"). And the spread of the
 * poses in between is at most the larger key's, the fact the check rests on, over random keys. */
Test(two_level, keys_each_within_the_bound_are_taken_however_far_apart_their_sizes) {
    struct scene s;
    char err[4096];
    cr_assert(parse_scene_lines("scenes/x.scene", HEAD,
                                "object bunny models/bunny.ply\ninstance bunny id a\nkey a time 0 scale 1e-9 1e-9 1e-9\n"
                                "key a time 1 scale 1e9 1e9 1e9",
                                test_every_kind, &s, err, sizeof err), "%s", err);
    struct instances *in = instances_create(&s, 0, 0.0, 0.0, err, sizeof err);
    cr_expect_not_null(in, "%s", err);
    instances_free(in);
    scene_free(&s);
    uint32_t state = 12345;
    for (int k = 0; k < 10000; k++) {
        double f[6];
        for (int i = 0; i < 6; i++) {
            state = state * 1664525u + 1013904223u;
            f[i] = pow(10.0, (state >> 8) / 16777216.0 * 18.0 - 9.0); /* 1e-9 to 1e9 */
        }
        vec3 a = vec3_make(f[0], f[1], f[2]), b = vec3_make(f[3], f[4], f[5]);
        double spread_a = fmax(fmax(a.x, a.y), a.z) / fmin(fmin(a.x, a.y), a.z);
        double spread_b = fmax(fmax(b.x, b.y), b.z) / fmin(fmin(b.x, b.y), b.z);
        for (int step = 1; step < 16; step++) {
            vec3 m = vec3_add_scaled(a, vec3_sub(b, a), step / 16.0);
            double spread = fmax(fmax(m.x, m.y), m.z) / fmin(fmin(m.x, m.y), m.z);
            cr_assert_leq(spread, fmax(spread_a, spread_b) * (1 + 1e-12), "keys %d: the spread %g half-way exceeds "
                          "the keys' %g and %g", k, spread, spread_a, spread_b);
        }
    }
}

/* The bound behind INSTANCES_TURN_SPREAD: scale factors as far apart as it lets through between two keys
 * invert at every turn (a grid of angles on all three axes), where three times as far apart the same
 * scale, which inverts unturned, fails at some turn. */
Test(two_level, scale_factors_within_the_turn_bound_invert_at_every_turn) {
    double ratio = TRANSFORM_CONDITION_MAX / INSTANCES_TURN_SPREAD;
    vec3 within = vec3_make(7.0, -7.0 * ratio, 7.0 * sqrt(ratio)), beyond = vec3_make(7.0, -7.0 * 3.0 * ratio, 7.0);
    struct transform t, inverse;
    t = transform_from_pose(beyond, vec3_make(0, 0, 0), vec3_make(0, 0, 0));
    cr_assert(transform_invert(&t, &inverse), "three times as far apart, unturned, should still invert");
    int beyond_fails = 0;
    for (int x = 0; x < 360; x += 15)
        for (int y = 0; y < 360; y += 15)
            for (int z = 0; z < 360; z += 15) {
                vec3 turn = vec3_make(x + 0.5, y + 0.25, z + 0.125);
                t = transform_from_pose(within, turn, vec3_make(1e3, -2e3, 3e3));
                cr_assert(transform_invert(&t, &inverse), "within the bound, turned %g %g %g: not invertible",
                          turn.x, turn.y, turn.z);
                t = transform_from_pose(beyond, turn, vec3_make(0, 0, 0));
                beyond_fails += !transform_invert(&t, &inverse);
            }
    cr_assert_gt(beyond_fails, 0, "three times as far apart, no turn failed: the bound would not be needed");
}

/* ---- the time of a sample ----------------------------------------------------------------------- */

Test(shutter, a_samples_time_depends_only_on_its_point_and_seed_and_stays_in_the_shutter) {
    cr_assert_eq(shutter_time(0.25, 0.0, 3.5, 7.25, 9), 0.25);
    double sum = 0.0;
    for (int k = 0; k < 10000; k++) {
        double x = k % 100 + 0.5, y = k / 100 + 0.5;
        double t = shutter_time(0.5, 0.25, x, y, 7);
        cr_assert(t >= 0.5 && t < 0.75, "%.17g", t);
        cr_assert_eq(t, shutter_time(0.5, 0.25, x, y, 7));
        sum += t;
    }
    cr_assert_float_eq(sum / 10000, 0.625, 0.005); /* uniform over the shutter */
    cr_assert_neq(shutter_time(0.5, 0.25, 1.5, 1.5, 7), shutter_time(0.5, 0.25, 1.5, 1.5, 8));
}

/* ---- pictures ----------------------------------------------------------------------------------- */

/* Writes a scene of instances of the bunny and the teapot (no motion) to `path`, with every instance
 * either as an instance line, or with its triangles written out in world space (by the transform's
 * transform_point) into one OBJ file drawn as a mesh line. */
static void write_forest_scene(const char *path, bool written_out) {
    static const struct {
        const char *object;
        struct scene_pose pose;
    } placed[] = {
        {BUNNY, {{0.12, 0.12, 0.12}, {0, 30, 0}, {-1.2, 0, 0}}},
        {BUNNY, {{0.1, 0.2, 0.1}, {0, -60, 10}, {1.0, 0, -0.5}}},
        {"scenes/models/teapot-5k.ply", {{0.25, 0.25, 0.25}, {0, 200, 0}, {0.1, 0, 0.6}}},
        {"scenes/models/teapot-5k.ply", {{0.2, 0.3, -0.2}, {15, 45, 0}, {-0.3, 0.3, -1.5}}},
    };
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    FILE *out = fopen(path, "w");
    cr_assert_not_null(out);
    fprintf(out, "camera eye 0 1.6 4.5 target 0 0.4 0 fov 40\nimage 160 120\nbackground 0.3 0.4 0.6\n"
                 "light position -4 6 5\nmaterial clay colour 0.8 0.5 0.3 phong 0.3\n"
                 "plane normal 0 1 0 distance 0\n");
    size_t count = sizeof placed / sizeof placed[0];
    if (!written_out) {
        fprintf(out, "object bunny %s/%s\nobject teapot %s/scenes/models/teapot-5k.ply\n", cwd, BUNNY, cwd);
        for (size_t k = 0; k < count; k++) {
            const struct scene_pose *p = &placed[k].pose;
            fprintf(out, "instance %s material clay scale %.17g %.17g %.17g rotate %.17g %.17g %.17g translate %.17g %.17g %.17g\n",
                    strcmp(placed[k].object, BUNNY) == 0 ? "bunny" : "teapot", p->scale.x, p->scale.y, p->scale.z, p->rotate.x,
                    p->rotate.y, p->rotate.z, p->translate.x, p->translate.y, p->translate.z);
        }
        fclose(out);
        return;
    }
    char obj[1100];
    snprintf(obj, sizeof obj, "%s.obj", path);
    FILE *mesh = fopen(obj, "w");
    cr_assert_not_null(mesh);
    size_t first = 1;
    for (size_t k = 0; k < count; k++) {
        struct mesh m;
        char err[512];
        cr_assert(mesh_load(placed[k].object, &m, err, sizeof err), "%s", err);
        const struct scene_pose *p = &placed[k].pose;
        struct transform t = transform_from_pose(p->scale, p->rotate, p->translate);
        for (size_t v = 0; v < m.vertex_count; v++) {
            vec3 w = transform_point(&t, m.vertices[v]);
            fprintf(mesh, "v %.17g %.17g %.17g\n", w.x, w.y, w.z);
        }
        for (size_t f = 0; f < m.face_count; f++)
            fprintf(mesh, "f %zu %zu %zu\n", first + m.faces[f].v[0], first + m.faces[f].v[1], first + m.faces[f].v[2]);
        first += m.vertex_count;
        mesh_free(&m);
    }
    fclose(mesh);
    fprintf(out, "mesh %s/%s material clay\n", cwd, obj);
    fclose(out);
}

/* The tolerance of the instanced picture against the written-out one: the two intersect the same
 * triangles, one in object space (the ray carried by the inverse transform), one in world space (the
 * vertices carried by the transform), so each t and normal differ by a few units in the last place.
 * That moves a shade by far less than a level, except where a ray grazes an edge or a shadow ray a
 * silhouette and the two roundings fall on either side: such pixels are allowed, at most 0.1 % of them. */
#define WRITTEN_OUT_MIN_WITHIN_1 0.999

Test(pictures, the_instanced_forest_draws_the_written_out_forest_of_chapter_11, .timeout = 120) {
    write_forest_scene(TEST_OUT "/forest-instanced.scene", false);
    write_forest_scene(TEST_OUT "/forest-written.scene", true);
    cr_assert_eq(render_chapter(16, TEST_OUT "/forest-instanced.scene", TEST_OUT "/forest-instanced.png", ""), 0);
    cr_assert_eq(render_chapter(11, TEST_OUT "/forest-written.scene", TEST_OUT "/forest-written.png", ""), 0);
    struct image_difference d = compare_png(TEST_OUT "/forest-instanced.png", TEST_OUT "/forest-written.png");
    report_difference("instanced vs written out", &d);
    cr_assert_geq(d.within_1, WRITTEN_OUT_MIN_WITHIN_1, "within 1: %.4f%%, max %d", 100 * d.within_1, d.max);
}

Test(pictures, refit_and_rebuild_draw_the_same_frames, .timeout = 120) {
    const char *scene = chapter_scene(16);
    cr_assert_eq(render_chapter(16, scene, TEST_OUT "/refit.png", "--frames 3 --width 96 --height 60 --refit"), 0);
    cr_assert_eq(render_chapter(16, scene, TEST_OUT "/rebuild.png", "--frames 3 --width 96 --height 60 --rebuild"), 0);
    for (int k = 1; k <= 3; k++) {
        char a[256], b[256];
        snprintf(a, sizeof a, TEST_OUT "/refit-%04d.png", k);
        snprintf(b, sizeof b, TEST_OUT "/rebuild-%04d.png", k);
        struct image_difference d = compare_png(a, b);
        cr_assert_eq(d.max, 0, "frame %d differs by %d levels", k, d.max);
    }
    /* and the frames differ: the teapot moves */
    struct image_difference d = compare_png(TEST_OUT "/refit-0001.png", TEST_OUT "/refit-0003.png");
    cr_assert_gt(d.max, 50);
}

Test(pictures, one_frame_of_the_farm_is_the_same_frame_of_the_whole_run, .timeout = 120) {
    const char *scene = chapter_scene(16);
    cr_assert_eq(render_chapter(16, scene, TEST_OUT "/one.png", "--frames 3 --frame 2 --width 96 --height 60"), 0);
    cr_assert_eq(render_chapter(16, scene, TEST_OUT "/all.png", "--frames 3 --width 96 --height 60"), 0);
    struct image_difference d = compare_png(TEST_OUT "/one-0002.png", TEST_OUT "/all-0002.png");
    cr_assert_eq(d.max, 0);
}

Test(pictures, are_the_same_for_any_thread_count, .timeout = 120) {
    const char *scene = chapter_scene(16);
    cr_assert_eq(render_chapter(16, scene, TEST_OUT "/threads-1.png", "--threads 1 --width 120 --height 75"), 0);
    cr_assert_eq(render_chapter(16, scene, TEST_OUT "/threads-3.png", "--threads 3 --width 120 --height 75"), 0);
    struct image_difference d = compare_png(TEST_OUT "/threads-1.png", TEST_OUT "/threads-3.png");
    cr_assert_eq(d.max, 0);
}

Test(pictures, the_twin_of_a_frame_without_blur_agrees_with_povray, .timeout = 300) {
    struct image_difference d =
        variant_against_povray(16, "camera eye 0 3.2 8.5  target 0 0.4 -2.5  fov 42  shutter 0.12",
                               "camera eye 0 3.2 8.5  target 0 0.4 -2.5  fov 42", "chapter-16-no-blur", 1);
    report_difference("chapter 16 (no blur) vs POV-Ray", &d);
    cr_assert(image_difference_agrees(&d), "within 2: %.3f%%, mean %.4f", 100 * d.within_2, d.mean);
    cr_assert_geq(d.within_1, 0.9999, "within 1: %.4f%%", 100 * d.within_1);
}

Test(command_line, animation_options_are_checked) {
    expect_chapter_run(16, "--frame 2", 2, "--frame K needs --frames N");
    expect_chapter_run(16, "--frames 2 --frame 3", 2, "--frame K must be at most --frames N");
    expect_chapter_run(16, "--frames 0", 2, "--frames needs a whole number from 1 to 100000, got '0'");
    expect_chapter_run(16, "--video", 2, "--video needs --frames N (at least 2) and all of them (no --frame)");
    expect_chapter_run(16, "--frames 2 -o -", 2, "--frames writes one file a frame");
    expect_chapter_run(16, "--frames 3 --refit --rebuild", 2,
                       "--refit and --rebuild say opposite things: give one of them (or neither, for the default rule)");
    expect_chapter_run(16, "--refit", 2,
                       "--refit and --rebuild choose what happens between frames: they need --frames N (at least 2)");
    expect_chapter_run(16, "--frames 2 --video -o " TEST_OUT "/film", 2,
                       "--video makes its film from the frames' PNG files: -o must name a .png file");
}

Test(command_line, video_without_ffmpeg_is_refused_before_any_frame) {
    /* ffmpeg missing from the PATH is found before the frames are drawn, not after: none is written */
    remove(TEST_OUT "/no-ffmpeg-0001.png");
    char command[1024], output[4096];
    snprintf(command, sizeof command, "env PATH=/nonexistent %s --frames 2 --video --width 16 --height 10 -o "
             TEST_OUT "/no-ffmpeg.png", chapter_program(16));
    cr_assert_eq(run_capturing(command, output, sizeof output), 3, "%s", output);
    cr_expect_not_null(strstr(output, "--video: cannot find ffmpeg, which makes the film (install it with "
                                      "tools/build/install-deps.sh video)"), "%s", output);
    cr_expect_eq(access(TEST_OUT "/no-ffmpeg-0001.png", F_OK), -1, "a frame was drawn before ffmpeg was looked for");
}

Test(command_line, the_ray_budget_counts_every_frame) {
    /* About 1.5e7 rays a frame (1089 a pixel, 37 through the lens, a shadow ray and a reflection each): ten
     * frames are well within the limit, a hundred thousand over it. */
    FILE *out = fopen(TEST_OUT "/frames.scene", "w");
    cr_assert_not_null(out);
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    fprintf(out, "camera eye 0 1 6 target 0 0.5 0 fov 40 aperture 0.2 focal_point 0 0.5 0 blur_samples 37\n"
                 "image 16 12\nantialias method recursive samples 6\nlight position -4 6 5\n"
                 "object bunny %s/" BUNNY "\ninstance bunny scale 0.2 0.2 0.2 id a\n"
                 "key a time 0 translate -1 0 0\nkey a time 1 translate 1 0 0\n", cwd);
    fclose(out);
    expect_chapter_run(16, TEST_OUT "/frames.scene --frames 100000 -o " TEST_OUT "/frames.png", 1,
                       TEST_OUT "/frames.scene:3: the scene asks for up to about 1.5e+12 rays (16 x 12 pixels, "
                       "antialias recursive depth 6: up to 1089 rays a pixel, blur_samples 37, 1 light: 1 shadow ray "
                       "a hit, max_depth 5: up to 2 rays a camera ray, 100000 pictures), over the limit of 1e+12; "
                       "pass --no-limit to render it anyway");
    /* One frame of the hundred thousand is one picture's rays. */
    expect_chapter_run(16, TEST_OUT "/frames.scene --frames 100000 --frame 7 --quiet -o " TEST_OUT "/frames.png", 0,
                       "");
}

Test(command_line, each_frame_has_its_own_heat_map_and_keeps_the_outputs_capitals, .timeout = 60) {
    const char *names[] = {TEST_OUT "/caps-0001.PNG", TEST_OUT "/caps-0002.PNG", TEST_OUT "/caps-heat-0001.png",
                           TEST_OUT "/caps-heat-0002.png"};
    for (int k = 0; k < 4; k++)
        remove(names[k]);
    cr_assert_eq(render_chapter(16, chapter_scene(16), TEST_OUT "/caps.PNG",
                                "--frames 2 --width 32 --height 20 --heatmap " TEST_OUT "/caps-heat.png"),
                 0);
    for (int k = 0; k < 4; k++) {
        char err[256];
        int width = 0, height = 0;
        uint8_t *rgb = image_read_rgb(names[k], &width, &height, err, sizeof err);
        cr_assert_not_null(rgb, "%s", err);
        cr_assert_eq(width, 32);
        free(rgb);
    }
}

Test(command_line, video_makes_a_film_of_the_frames, .timeout = 120) {
    /* a % in the name, which ffmpeg's pattern of the frames' names must take as itself */
    remove(TEST_OUT "/film%d.mp4");
    cr_assert_eq(render_chapter(16, chapter_scene(16), TEST_OUT "/film%d.png", "--frames 4 --video --width 64 --height 40"),
                 0);
    size_t size = 0;
    free(read_file(TEST_OUT "/film%d.mp4", &size));
    cr_assert_gt(size, 1000, "the film has %zu bytes", size);
}

Test(command_line, video_takes_names_that_ffmpeg_would_read_as_an_option_or_a_protocol, .timeout = 120) {
    /* Run in the test folder, so that the names are as given: ffmpeg read "-v.mp4" as an option and
     * "x:y-%04d.png" as a file of the protocol x, and failed after every frame was drawn; both names now
     * reach it after "file:". */
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    static const char *const names[] = {"-v", "x:y"};
    for (int k = 0; k < 2; k++) {
        char film[256], command[4096], output[4096];
        snprintf(film, sizeof film, TEST_OUT "/%s.mp4", names[k]);
        remove(film);
        snprintf(command, sizeof command, "cd " TEST_OUT " && %s/%s %s/%s --quiet --frames 2 --video --width 16 "
                 "--height 10 -o %s.png", cwd, chapter_program(16), cwd, chapter_scene(16), names[k]);
        cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s\n%s", command, output);
        cr_expect_str_eq(output, "", "--quiet printed more than errors:\n%s", output);
        size_t size = 0;
        free(read_file(film, &size));
        cr_expect_gt(size, 500, "%s has %zu bytes", film, size);
    }
}

/* The film is made of this run's frames only: ffmpeg read the numbered names on until one was missing, and
 * a film of 2 frames took in the 4 a run before had left (exit 0). Counted by ffprobe, which comes with
 * ffmpeg. */
Test(command_line, video_takes_only_this_runs_frames, .timeout = 120) {
    cr_assert_eq(render_chapter(16, chapter_scene(16), TEST_OUT "/stale.png", "--frames 4 --width 16 --height 10"), 0);
    cr_assert_eq(render_chapter(16, chapter_scene(16), TEST_OUT "/stale.png", "--frames 2 --video --width 16 --height 10"),
                 0);
    char output[256];
    cr_assert_eq(run_capturing("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                               "-of csv=p=0 " TEST_OUT "/stale.mp4", output, sizeof output), 0, "%s", output);
    cr_expect_eq(atoi(output), 2, "the film of 2 frames has %s", output);
}

/* A frame's file or the film that cannot be made is found before any frame is drawn: a folder named as the
 * second frame let the first be drawn and written, and a folder named as the film let every frame be
 * drawn, then ffmpeg failed (docs/16-instances.md says every frame's file is checked first). And a device
 * as -o is not a name to number (-o /dev/null --frames 2 wrote /dev/null-0001 and /dev/null-0002). */
Test(command_line, a_frame_or_film_that_cannot_be_made_is_found_before_any_frame_is_drawn, .timeout = 60) {
    const char *folder = TEST_OUT "/unmade";
    char command[256];
    snprintf(command, sizeof command, "rm -rf %s && mkdir -p %s/x-0002.png %s/y.mp4", folder, folder, folder);
    cr_assert_eq(system(command), 0);
    expect_chapter_run(16, "--frames 3 --width 16 --height 10 -o " TEST_OUT "/unmade/x.png", 3,
                       TEST_OUT "/unmade/x-0002.png: cannot create: Is a directory");
    cr_expect_neq(access(TEST_OUT "/unmade/x-0001.png", F_OK), 0, "the first frame was drawn");
    expect_chapter_run(16, "--frames 2 --video --width 16 --height 10 -o " TEST_OUT "/unmade/y.png", 3,
                       "--video: " TEST_OUT "/unmade/y.mp4: cannot create: Is a directory");
    cr_expect_neq(access(TEST_OUT "/unmade/y-0001.png", F_OK), 0, "a frame was drawn");
    expect_chapter_run(16, "--frames 2 --width 16 --height 10 -o /dev/null", 2,
                       "--frames writes one file a frame, named after -o (and --heatmap): a device or a FIFO (such as "
                       "/dev/null) is not a file whose name can be numbered, and its frames would be new files beside it");
    cr_expect_neq(access("/dev/null-0001", F_OK), 0, "/dev/null-0001 was written");
}

/* The files the frames go to are checked before the first frame is drawn, as -o's own file is. */
Test(command_line, the_frames_files_are_checked_before_any_frame_is_drawn) {
    expect_chapter_run(16, "--frames 2 -o " TEST_OUT "/hm.png --heatmap -", 2,
                       "--frames writes one heat-map a frame: --heatmap - (standard output) cannot take them");
    /* a scene whose name is that of a frame: it was written over with the frame's picture, exit 0 */
    const char *text = "camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 6\nlight position 5 8 4\n"
                       "sphere centre 0 0 0 radius 1\n";
    FILE *f = fopen(TEST_OUT "/clip-0001", "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
    expect_chapter_run(16, TEST_OUT "/clip-0001 --frames 1 -o " TEST_OUT "/clip", 2,
                       "-o (its frame 1) names '" TEST_OUT "/clip-0001', which the run reads (the scene file): "
                       "writing it would destroy it; give another file");
    expect_chapter_run(16, TEST_OUT "/clip-0001 --frames 1 -o " TEST_OUT "/clip.png --heatmap " TEST_OUT "/clip", 2,
                       "--heatmap (its frame 1) names '" TEST_OUT "/clip-0001', which the run reads (the scene file)");
    char *now = read_text_file(TEST_OUT "/clip-0001");
    cr_assert_not_null(now);
    cr_expect_str_eq(now, text, "the scene was overwritten");
    free(now);
    /* a frame's picture that is its heat-map under another name (a link): the heat-map took its place */
    remove(TEST_OUT "/fr-0001.png");
    remove(TEST_OUT "/fh-0001.png");
    cr_assert_eq(symlink("fh-0001.png", TEST_OUT "/fr-0001.png"), 0);
    expect_chapter_run(16, TEST_OUT "/clip-0001 --frames 1 -o " TEST_OUT "/fr.png --heatmap " TEST_OUT "/fh.png", 2,
                       "-o and --heatmap name the same file for frame 1 ('" TEST_OUT "/fr-0001.png' and '" TEST_OUT
                       "/fh-0001.png'); give two");
    cr_expect_neq(access(TEST_OUT "/fh-0001.png", F_OK), 0, "a frame was written");
    remove(TEST_OUT "/fr-0001.png");
    /* --video's film too */
    f = fopen(TEST_OUT "/clip.mp4", "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
    expect_chapter_run(16, TEST_OUT "/clip.mp4 --frames 2 --video -o " TEST_OUT "/clip.png", 2,
                       "--video (its film) names '" TEST_OUT "/clip.mp4', which the run reads (the scene file)");
}

/* The frames' names are checked against the files the run reads with each input looked at once: they
 * were compared one by one, two stats a pair, and a scene of 4,096 object lines run with --frames
 * 10000 drew its first frame after 271 s, printing nothing. Here 5,000 frames of a picture and a
 * heat-map against 4,096 objects, the last frame's heat-map a link to the last object's file: about
 * 80 million stats before (two minutes and more), a moment now; and the link is still refused. */
#define MANY_OBJECTS_FRAMES 5000
#define MANY_OBJECTS_OUT TEST_OUT "/many-objects"
Test(command_line, thousands_of_frames_are_checked_against_thousands_of_objects_at_once, .timeout = 20) {
    char command[1024], output[4096], link_name[256];
    snprintf(command, sizeof command, "rm -rf " MANY_OBJECTS_OUT " && mkdir -p " MANY_OBJECTS_OUT);
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    static const char *const meshes[] = {MANY_OBJECTS_OUT "/tri.obj", MANY_OBJECTS_OUT "/last.obj"};
    for (int k = 0; k < 2; k++) {
        FILE *mesh = fopen(meshes[k], "w");
        cr_assert_not_null(mesh);
        fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", mesh);
        fclose(mesh);
    }
    FILE *out = fopen(MANY_OBJECTS_OUT "/many.scene", "w");
    cr_assert_not_null(out);
    fputs("camera eye 0 0 5 target 0 0 0 fov 40\nimage 8 6\nlight position 5 8 4\n", out);
    for (int k = 1; k <= SCENE_OBJECT_MAX; k++)
        fprintf(out, "object o%d %s\n", k, k < SCENE_OBJECT_MAX ? "tri.obj" : "last.obj");
    fputs("instance o1\n", out);
    fclose(out);
    snprintf(link_name, sizeof link_name, MANY_OBJECTS_OUT "/h-%04d.png", MANY_OBJECTS_FRAMES);
    cr_assert_eq(symlink("last.obj", link_name), 0);
    /* the run's own bound ends the old code's search soon after this test's time is up */
    snprintf(command, sizeof command, "timeout 30 %s " MANY_OBJECTS_OUT "/many.scene --frames %d -o " MANY_OBJECTS_OUT
             "/f.png --heatmap " MANY_OBJECTS_OUT "/h.png --quiet", chapter_program(16), MANY_OBJECTS_FRAMES);
    int status = run_capturing(command, output, sizeof output);
    char expected[512];
    snprintf(expected, sizeof expected, "--heatmap (its frame %d) names '%s', which the run reads (the mesh of object "
             "'o%d'): writing it would destroy it; give another file", MANY_OBJECTS_FRAMES, link_name, SCENE_OBJECT_MAX);
    cr_expect_eq(status, 2, "'%s' exited with %d, not 2:\n%s", command, status, output);
    cr_expect(strstr(output, expected) != NULL, "'%s' did not say '%s':\n%s", command, expected, output);
    cr_expect_neq(access(MANY_OBJECTS_OUT "/f-0001.png", F_OK), 0, "a frame was written");
    size_t size = 0;
    char *mesh = read_file(MANY_OBJECTS_OUT "/last.obj", &size);
    cr_expect(mesh != NULL && strncmp(mesh, "v 0 0 0\n", 8) == 0, "the last object's file was written over");
    free(mesh);
}

Test(command_line, instances_on_top_of_each_other_count_in_the_ray_budget) {
    /* 20,000 bunnies in one place: every ray is carried into each of them, 2.6e12 times in a picture of
     * 1000 x 1000 pixels, 64 camera rays each and their shadow rays, more than a day; refused at once, naming the crowded place's
     * line. The same instances spread apart are met a few at a time. */
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    for (int spread = 0; spread < 2; spread++) {
        FILE *out = fopen(TEST_OUT "/crowd.scene", "w");
        cr_assert_not_null(out);
        fprintf(out, "camera eye 0 1 6 target 0 0.5 0 fov 40\nimage 1000 1000\nantialias method grid samples 8\n"
                     "light position -4 6 5\nobject bunny %s/" BUNNY "\n", cwd);
        for (int k = 0; k < 20000; k++)
            fprintf(out, "instance bunny translate %g 0 %g\n", spread ? (k % 200) * 2.0 : 0.0,
                    spread ? (k / 200) * -2.0 : 0.0);
        fclose(out);
        if (spread == 0) {
            expect_chapter_run(16, TEST_OUT "/crowd.scene -o " TEST_OUT "/crowd.png", 1,
                               TEST_OUT "/crowd.scene:6: a ray is carried into about 20000 instances, their boxes lying "
                               "over each other here: about 2.6e+12 for the scene's 1.3e+08 rays, over the limit of "
                               "1e+12; pass --no-limit to render it anyway");
        } else {
            /* spread: no note, and a picture (small, to be quick) */
            expect_chapter_run(16, TEST_OUT "/crowd.scene --width 8 --height 8 -o " TEST_OUT "/crowd.png", 0,
                               "chapter 16 (instances): wrote");
        }
    }
}

Test(command_line, instances_every_ray_meets_count_in_the_ray_budget_with_the_reason) {
    /* An object with a sliver face (its second face 1e-8 from a line) keeps its instances out of the top
     * level, since no box can be trusted to hold a sliver's hits: every ray meets each of them. 40,000 of
     * them in a picture of 4000 x 4000 pixels and its shadow rays are 1.3e12, refused at once with the
     * reason, not the crowding the message gives for instances on top of one another. */
    FILE *mesh = fopen(TEST_OUT "/sliver.obj", "w");
    cr_assert_not_null(mesh);
    fputs("v -1 0 0\nv 1 0 0\nv 0 1 0\nv 0 1e-8 0\nf 1 2 3\nf 1 2 4\n", mesh);
    fclose(mesh);
    FILE *out = fopen(TEST_OUT "/slivers.scene", "w");
    cr_assert_not_null(out);
    fputs("camera eye 0 1 6 target 0 0.5 0 fov 40\nimage 4000 4000\nlight position 5 5 5\nobject t sliver.obj\n", out);
    for (int k = 0; k < 40000; k++)
        fprintf(out, "instance t translate %d 0 %d\n", k % 200, -(k / 200) - 10);
    fclose(out);
    expect_chapter_run(16, TEST_OUT "/slivers.scene -o " TEST_OUT "/slivers.png", 1,
                       TEST_OUT "/slivers.scene:5: a ray is carried into about 40000 instances, 40000 of them met by "
                       "every ray (their objects have sliver faces, which no box can be trusted to hold): about "
                       "1.3e+12 for the scene's 3.2e+07 rays, over the limit of 1e+12; pass --no-limit to render it "
                       "anyway");
}

Test(command_line, a_bad_instance_is_a_bad_scene_with_its_line) {
    FILE *out = fopen(TEST_OUT "/flat.scene", "w");
    cr_assert_not_null(out);
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    fprintf(out, "camera eye 0 1 6 target 0 0 0 fov 40\nimage 8 8\nobject b %s/" BUNNY "\n"
                 "instance b scale 1e-9 1 1e9\n", cwd);
    fclose(out);
    expect_chapter_run(16, TEST_OUT "/flat.scene", 1, TEST_OUT "/flat.scene:4: instance of 'b': its transform cannot be "
                                                      "inverted accurately");
}

/* An object line whose file does not open is an error at its line, whether an instance places the object
 * (its mesh is then read) or not (it is never read, but its name is a mistake all the same), and no
 * picture is written. */
Test(command_line, an_object_whose_file_does_not_open_names_its_line) {
    const struct {
        const char *lines, *message;
    } cases[] = {
        {"object b no-such.ply\ninstance b\n", "/unopened.scene:3: object 'b': " TEST_OUT "/no-such.ply: cannot open: "
                                                "No such file or directory"},
        {"object b no-such.ply\n", "/unopened.scene:3: object 'b': " TEST_OUT "/no-such.ply: cannot open: No such "
                                   "file or directory"},
        {"object a no-such.ply\nobject b .\n", "/unopened.scene:3: object 'a': " TEST_OUT "/no-such.ply: cannot open: "
                                                "No such file or directory"},
        {"object b .\n", "/unopened.scene:3: object 'b': " TEST_OUT "/.: not a regular file (a directory)"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        remove(TEST_OUT "/unopened.png");
        FILE *out = fopen(TEST_OUT "/unopened.scene", "w");
        cr_assert_not_null(out);
        fprintf(out, "camera eye 0 1 6 target 0 0 0 fov 40\nimage 8 8\n%s", cases[k].lines);
        fclose(out);
        char message[256];
        snprintf(message, sizeof message, "%s%s", TEST_OUT, cases[k].message);
        expect_chapter_run(16, TEST_OUT "/unopened.scene -o " TEST_OUT "/unopened.png", 1, message);
        cr_assert_neq(access(TEST_OUT "/unopened.png", F_OK), 0, "case %zu wrote a picture", k);
    }
}

/* Objects that do not fit in memory: the error names the object's line, whether the memory runs out while
 * its mesh is read or while its tree is built (limits on the address space that, on the machine this was
 * written on, stop the first, second and fourth teapot, in its tree, its tree and its mesh; one thread, so
 * that thread stacks do not count; not under the sanitizers, whose shadow memory the limit would refuse). */
static const int instances_memory_limits_kb[] = {60000, 150000, 250000};

Test(command_line, running_out_of_memory_for_an_object_names_its_line, .timeout = 60) {
    const char *build = getenv("WHITTED_BUILD");
    if (build != NULL && strstr(build, "san") != NULL)
        cr_skip_test("the sanitizers reserve more address space than the limit");
    remove(TEST_OUT "/heavy.png");
    FILE *out = fopen(TEST_OUT "/heavy.scene", "w");
    cr_assert_not_null(out);
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    fprintf(out, "camera eye 0 1 6 target 0 0 0 fov 40\nimage 8 8\n");
    for (int k = 0; k < 40; k++)
        fprintf(out, "object o%d %s/scenes/models/teapot-346k.ply\ninstance o%d\n", k, cwd, k);
    fclose(out);
    for (size_t k = 0; k < sizeof instances_memory_limits_kb / sizeof instances_memory_limits_kb[0]; k++) {
        static char command[2048], output[16384];
        snprintf(command, sizeof command, "ulimit -v %d; OMP_NUM_THREADS=1 exec %s %s --quiet -o %s",
                 instances_memory_limits_kb[k], chapter_program(16), TEST_OUT "/heavy.scene", TEST_OUT "/heavy.png");
        int status = run_capturing(command, output, sizeof output);
        cr_log_info("%d KB: %s", instances_memory_limits_kb[k], output);
        cr_assert_eq(status, 1, "'%s' exited with %d:\n%s", command, status, output);
        cr_assert(strncmp(output, TEST_OUT "/heavy.scene:", strlen(TEST_OUT "/heavy.scene:")) == 0 &&
                      strstr(output, ": object 'o") != NULL && strstr(output, "out of memory") != NULL,
                  "'%s' said:\n%s", command, output);
        cr_assert_eq(access(TEST_OUT "/heavy.png", F_OK), -1, "a picture was written");
    }
}

static void spinning_key(size_t k, char *out, size_t size) {
    double t = (double)k / 999.0;
    snprintf(out, size, "key x time %.17g translate %.6f 0 0 rotate 0 %.3f 0\n", t, sin(20.0 * t), 3600.0 * t);
}

Test(two_level, a_thousand_keys_spinning_ten_times_answer_as_brute_force, .timeout = 60) {
    char *lines = many_lines("object bunny models/bunny.ply\ninstance bunny scale 0.1 0.1 0.1 id x", 1000, 80,
                             spinning_key);
    struct scene s;
    char err[4096];
    cr_assert(parse_long("scenes/keys.scene", lines, &s, err, sizeof err), "%s", err);
    free(lines);
    struct instances *in = instances_create(&s, 0, 0.0, 1.0, err, sizeof err);
    cr_assert_not_null(in, "%s", err);
    uint64_t g = 1000;
    int hits = 0;
    for (int n = 0; n < 500; n++) {
        double time = uniform(&g, 0.0, 1.0);
        ray r = {vec3_make(uniform(&g, -2, 2), uniform(&g, 0, 1), 5), vec3_make(uniform(&g, -0.3, 0.3), 0, -1)};
        struct hit fast = hit_nothing(INFINITY), slow = hit_nothing(INFINITY);
        cr_assert_eq(in->hook.closest(in, &r, 1e-9, time, &fast), brute_closest(in, &r, 1e-9, time, &slow));
        cr_assert(fast.t == slow.t || (isinf(fast.t) && isinf(slow.t)), "ray %d", n);
        hits += isfinite(fast.t);
    }
    cr_assert_gt(hits, 25, "only %d of 500 rays hit the spinning bunny", hits);
    instances_free(in);
    scene_free(&s);
}

/* ---- motion blur, analytically ------------------------------------------------------------------ */

/* A white square (ambient light only, so exactly 1 wherever it is seen) 2 units wide and taller than the
 * picture slides along x at BLUR_SPEED units per unit of clock over a black background, 10 units in front
 * of the camera, during a shutter of BLUR_SHUTTER. A camera ray through the point x of the plane sees it
 * for the times t in [0, BLUR_SHUTTER] with |x - (BLUR_START + BLUR_SPEED t)| < 1: the pixel's expected
 * value is that time's share of the shutter, averaged over the pixel's 16 sample columns. Each pixel
 * averages 256 samples whose times are random: its value is within 0.5 / 16 (one standard deviation)
 * of the expectation, and a column's mean over the 32 rows within 0.0055; the test allows 0.03. */
#define BLUR_SPEED 6.0
#define BLUR_START (-3.0)
#define BLUR_SHUTTER 0.5
#define BLUR_TOLERANCE 0.03

/* The share of the shutter the square covers the plane's point x. */
static double covered_share(double x) {
    double enter = (x - 1.0 - BLUR_START) / BLUR_SPEED, leave = (x + 1.0 - BLUR_START) / BLUR_SPEED;
    double from = fmax(enter, 0.0), to = fmin(leave, BLUR_SHUTTER);
    return to > from ? (to - from) / BLUR_SHUTTER : 0.0;
}

Test(motion_blur, a_sliding_square_blurs_by_the_share_of_the_shutter_it_covers, .timeout = 60) {
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    FILE *square = fopen(TEST_OUT "/square.obj", "w"), *out = fopen(TEST_OUT "/blur.scene", "w");
    cr_assert(square != NULL && out != NULL);
    fprintf(square, "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\nf 1 2 3\nf 1 3 4\n");
    fclose(square);
    fprintf(out, "camera eye 0 0 10 target 0 0 0 fov 20 shutter %g\nimage 64 32\nbackground 0 0 0\n"
                 "antialias method grid samples 16\nmaterial white colour 1 1 1 ambient 1 diffuse 0\n"
                 "object square %s/" TEST_OUT "/square.obj\ninstance square material white scale 2 20 1 id s\n"
                 "key s time 0 translate %g 0 0\nkey s time 1 translate %g 0 0\n",
            BLUR_SHUTTER, cwd, BLUR_START, BLUR_START + BLUR_SPEED);
    fclose(out);
    cr_assert_eq(render_chapter(16, TEST_OUT "/blur.scene", TEST_OUT "/blur.png", ""), 0);
    int w, h, channels;
    uint8_t *pixels = stbi_load(TEST_OUT "/blur.png", &w, &h, &channels, 3);
    cr_assert(pixels != NULL && w == 64 && h == 32);
    double half_width = tan(10.0 * M_PI / 180.0) * 64.0 / 32.0, worst = 0.0;
    int blurred = 0;
    for (int i = 0; i < w; i++) {
        double expected = 0.0, seen = 0.0;
        for (int a = 0; a < 16; a++) { /* the grid's sample columns; a ray meets the plane at 10 px half_width */
            double px = 2.0 * (i + (a + 0.5) / 16.0) / w - 1.0;
            expected += covered_share(10.0 * px * half_width) / 16.0;
        }
        for (int j = 0; j < h; j++)
            seen += pixels[3 * (j * w + i)] / 255.0 / h;
        worst = fmax(worst, fabs(seen - expected));
        cr_assert(fabs(seen - expected) <= BLUR_TOLERANCE, "column %d: %.4f, expected %.4f", i, seen, expected);
        blurred += expected > 0.1 && expected < 0.9;
    }
    cr_assert_gt(blurred, 8, "the profile is not a ramp: %d columns between 0.1 and 0.9", blurred);
    printf("motion blur: largest column error %.4f over %d blurred columns\n", worst, blurred);
    free(pixels);
}

Test(command_line, stats_count_both_levels_and_the_memory_of_an_instance) {
    expect_chapter_run(16, "--stats --width 40 --height 25 -o " TEST_OUT "/stats.png", 0, "  instance nodes ");
    expect_chapter_run(16, "--stats --width 40 --height 25 -o " TEST_OUT "/stats.png", 0, "  node visits ");
    expect_chapter_run(16, "--stats --width 40 --height 25 -o " TEST_OUT "/stats.png", 0,
                       "instances: 41 of 2 objects (1 moving), 1.808e+05 triangles instanced from 8786");
    expect_chapter_run(16, "--stats --width 40 --height 25 -o " TEST_OUT "/stats.png", 0, " bytes (with its keys and "
                                                                                          "its share of the top level)");
}

Test(pictures, the_last_frame_of_an_animation_agrees_with_povray_at_its_clock, .timeout = 120) {
    char cwd[1024], command[4096], output[4096];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    FILE *out = fopen(TEST_OUT "/moving.scene", "w");
    cr_assert_not_null(out);
    fprintf(out, "camera eye 0 1.6 4.5 target 0 0.4 0 fov 40\nimage 160 120\nbackground 0.3 0.4 0.6\n"
                 "light position -4 6 5\nmaterial clay colour 0.8 0.5 0.3 phong 0.3\nplane normal 0 1 0 distance 0\n"
                 "object bunny %s/" BUNNY "\ninstance bunny material clay scale 0.1 0.1 0.1 id b\n"
                 "key b time 0 translate -1 0 0\nkey b time 0.5 translate 0 0.5 0 rotate 0 90 0 scale 0.1 0.15 0.1\n"
                 "key b time 1 translate 1 0 -1 rotate 0 200 30\n", cwd);
    fclose(out);
    cr_assert_eq(render_chapter(16, TEST_OUT "/moving.scene", TEST_OUT "/moving.png", "--frames 5 --frame 4"), 0);
    snprintf(command, sizeof command, "%s " TEST_OUT "/moving.scene --quiet --pov " TEST_OUT "/moving.pov",
             chapter_program(16));
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    /* frame 4 of 5 is clock 0.75: POV-Ray's frames 1 .. 5 over clock 0 .. 1, only the fourth rendered */
    snprintf(command, sizeof command, "povray +I" TEST_OUT "/moving.pov +O" TEST_OUT "/moving-povray.png +W160 +H120 "
             POVRAY_OPTIONS " +KFI1 +KFF5 +KI0 +KF1 +SF4 +EF4 +FN8");
    cr_assert_eq(run_capturing(command, output, sizeof output), 0, "%s", output);
    struct image_difference d = compare_png(TEST_OUT "/moving-0004.png", TEST_OUT "/moving-povray4.png");
    report_difference("frame 4 of 5 vs POV-Ray", &d);
    cr_assert(image_difference_agrees(&d), "within 2: %.3f%%, mean %.4f", 100 * d.within_2, d.mean);
    cr_assert_geq(d.within_1, 0.9999, "within 1: %.4f%%", 100 * d.within_1);
    /* and the frame is not the first: the bunny moved */
    cr_assert_eq(render_chapter(16, TEST_OUT "/moving.scene", TEST_OUT "/still.png", "--frames 5 --frame 1"), 0);
    cr_assert_gt(compare_png(TEST_OUT "/still-0001.png", TEST_OUT "/moving-0004.png").max, 50);
}

/* ---- a camera inside a glass instance ----------------------------------------------------------- */

/* A closed unit cube (corners at -1 and 1), its faces turned outwards. Written beside `path` and renamed
 * over it, so that a test reading the cube while another writes it (the tests run at once, and three
 * share it) never finds it cut short: POV-Ray's twin of it once failed so. */
static void write_cube(const char *path) {
    char temporary[512];
    snprintf(temporary, sizeof temporary, "%s.%ld", path, (long)getpid());
    FILE *out = fopen(temporary, "w");
    cr_assert_not_null(out);
    fprintf(out, "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                 "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
    cr_assert_eq(fclose(out), 0);
    cr_assert_eq(rename(temporary, path), 0);
}

/* Writes a scene whose eye is inside a glass cube turned and scaled 1.2 (a yellow ball and floor seen
 * through it), the cube given by `cube`: an object and an instance, or a mesh line. */
static void write_inside_glass_scene(const char *path, const char *cube) {
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    write_cube(TEST_OUT "/glass-cube.obj");
    FILE *out = fopen(path, "w");
    cr_assert_not_null(out);
    fprintf(out, "image 80 60\ncamera eye 0.2 0.1 0.3 target 0 0 -3 fov 60\nlight position 5 8 4\n"
                 "background 0.2 0.3 0.5\n"
                 "material g colour 0.9 1 0.9 ambient 0 diffuse 0 transmit 0.9 ior 1.5 reflection 0.05\n"
                 "material f colour 1 1 0 ambient 0.2\nplane normal 0 1 0 distance -1.5 material f\n"
                 "sphere centre 0 0 -3 radius 1 material f\n");
    fprintf(out, cube, cwd);
    fclose(out);
}

#define GLASS_CUBE_OBJECT "object c %s/" TEST_OUT "/glass-cube.obj\n"
#define GLASS_CUBE_MESH "mesh %s/" TEST_OUT "/glass-cube.obj material g scale 1.2 rotate 10 20 0\n"

Test(instance_interior, an_eye_inside_a_glass_instance_sees_what_it_sees_inside_the_same_mesh, .timeout = 60) {
    write_inside_glass_scene(TEST_OUT "/inside-instance.scene",
                             GLASS_CUBE_OBJECT "instance c material g scale 1.2 1.2 1.2 rotate 10 20 0\n");
    write_inside_glass_scene(TEST_OUT "/inside-mesh.scene", GLASS_CUBE_MESH);
    cr_assert_eq(render_chapter(16, TEST_OUT "/inside-instance.scene", TEST_OUT "/inside-instance.png", ""), 0);
    cr_assert_eq(render_chapter(16, TEST_OUT "/inside-mesh.scene", TEST_OUT "/inside-mesh.png", ""), 0);
    struct image_difference d = compare_png(TEST_OUT "/inside-instance.png", TEST_OUT "/inside-mesh.png");
    report_difference("eye inside a glass instance vs the same mesh", &d);
    cr_assert_eq(d.max, 0, "differs by up to %d levels (mean %.3f)", d.max, d.mean);
}

Test(instance_interior, an_eye_inside_a_glass_instance_agrees_with_povray, .timeout = 120) {
    write_inside_glass_scene(TEST_OUT "/inside-pov.scene",
                             GLASS_CUBE_OBJECT "instance c material g scale 1.2 1.2 1.2 rotate 10 20 0\n");
    cr_assert_eq(render_chapter(16, TEST_OUT "/inside-pov.scene", TEST_OUT "/inside-pov.png", ""), 0);
    cr_assert(render_povray(16, TEST_OUT "/inside-pov.scene", TEST_OUT "/inside-pov-povray.png"));
    struct image_difference d = compare_png(TEST_OUT "/inside-pov.png", TEST_OUT "/inside-pov-povray.png");
    report_difference("eye inside a glass instance vs POV-Ray", &d);
    cr_assert(image_difference_agrees(&d), "within 2: %.3f%%, mean %.4f, max %d", 100 * d.within_2, d.mean, d.max);
}

/* The cube slides from x = 3 to x = -3 over the clock: at clock 0.5 (frame 2 of 3) it is where the
 * fixed mesh is, around the eye, and only then. */
Test(instance_interior, an_eye_inside_a_moving_glass_instance_at_the_frames_time, .timeout = 60) {
    write_inside_glass_scene(TEST_OUT "/inside-moving.scene",
                             GLASS_CUBE_OBJECT "instance c material g scale 1.2 1.2 1.2 rotate 10 20 0 id m\n"
                                               "key m time 0 translate 3 0 0\nkey m time 1 translate -3 0 0\n");
    write_inside_glass_scene(TEST_OUT "/inside-still.scene", GLASS_CUBE_MESH);
    cr_assert_eq(render_chapter(16, TEST_OUT "/inside-moving.scene", TEST_OUT "/inside-moving.png",
                                "--frames 3 --frame 2"), 0);
    cr_assert_eq(render_chapter(16, TEST_OUT "/inside-still.scene", TEST_OUT "/inside-still.png", ""), 0);
    struct image_difference d = compare_png(TEST_OUT "/inside-moving-0002.png", TEST_OUT "/inside-still.png");
    report_difference("eye inside a moving glass instance at clock 0.5 vs the mesh", &d);
    cr_assert_eq(d.max, 0, "differs by up to %d levels (mean %.3f)", d.max, d.mean);
}

/* ---- the scale warning measures the instances ---------------------------------------------------- */

/* Writes a scene of one instance of the unit cube placed by `pose`, seen from `eye`. */
static void write_lone_cube_scene(const char *path, const char *eye, const char *pose) {
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    write_cube(TEST_OUT "/lone-cube.obj");
    FILE *out = fopen(path, "w");
    cr_assert_not_null(out);
    fprintf(out, "image 8 6\ncamera eye %s fov 50\nlight position 5 8 4\nbackground 0.2 0.3 0.5\n"
                 "material f colour 1 1 0 ambient 0.2\nobject c %s/" TEST_OUT "/lone-cube.obj\n"
                 "instance c material f %s\n", eye, cwd, pose);
    fclose(out);
}

/* Two millionths of a unit across, 10,000 times smaller than the margins: as the same cube on a mesh
 * line (the extent is the same to the last digit printed), not a blank picture without a word. */
Test(instance_scale, a_scene_of_tiny_instances_is_warned_about) {
    write_lone_cube_scene(TEST_OUT "/tiny-instance.scene", "0 0.000002 0.000006 target 0 0 0",
                          "scale 0.000001 0.000001 0.000001 rotate 10 20 0");
    expect_chapter_run(16, TEST_OUT "/tiny-instance.scene -o " TEST_OUT "/tiny-instance.png", 0,
                       TEST_OUT "/tiny-instance.scene: warning: the scene is 7.43061e-06 units across, only "
                       "0.00743061 times the shadow-ray margin 0.001 (and 0.0743061 times the ray margin 0.0001); "
                       "surfaces that close are missed and the picture will differ from POV-Ray's: scale the scene "
                       "up 1e+06 times or more\n");
}

Test(instance_scale, a_scene_of_instances_far_from_the_origin_is_warned_about) {
    write_lone_cube_scene(TEST_OUT "/far-instance.scene", "1e12 1 6 target 1e12 0 0", "translate 1e12 0 0");
    expect_chapter_run(16, TEST_OUT "/far-instance.scene -o " TEST_OUT "/far-instance.png", 0,
                       "far-instance.scene: warning: the scene is 7 units across and reaches 1e+12 from the origin, "
                       "where a ray leaving a surface accepts hits only beyond 1000 (1e-09 of that distance");
}

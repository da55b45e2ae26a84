/* test_shading.c: unit tests of chapters 5 to 8 against closed-form answers: the box shape and the
 * world's mesh culling (chapter 5), POV-Ray's Phong formula (chapter 6), opaque and filtered shadow rays
 * (chapters 7 and 8) and the recursive Whitted tracer (chapter 8). Scenes are parsed from text held in
 * memory. Every expected value is worked out by hand in the comment next to it. One test reads the real
 * chapter 5 scene and its meshes instead, to check the culling counter against chapter 4's brute force. */
#include <criterion/criterion.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel.h"
#include "box.h"
#include "camera.h"
#include "phong.h"
#include "plane.h"
#include "scene.h"
#include "shadow.h"
#include "stats.h"
#include "test_support.h"
#include "triangle.h"
#include "whitted.h"
#include "world.h"

#define EXACT 0.0  /* every step exact in binary floating point */
#define SAME 1e-12 /* the same arithmetic up to rounding (a square root, a normalisation, another order) */

/* ---- helpers ----------------------------------------------------------------------------------- */

/* True when got equals want or is within tolerance of it, relative to |want| but never tighter than
 * absolute tolerance: an expected 0 is compared absolutely. */
static bool close_to(double got, double want, double tolerance) {
    return got == want || fabs(got - want) <= tolerance * fmax(1.0, fabs(want)); /* == for infinities */
}

static void assert_colour(vec3 got, vec3 want, double tolerance, const char *what) {
    cr_assert(close_to(got.x, want.x, tolerance) && close_to(got.y, want.y, tolerance) &&
                  close_to(got.z, want.z, tolerance),
              "%s: got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g)", what, got.x, got.y, got.z, want.x,
              want.y, want.z);
}

static void assert_number(double got, double want, double tolerance, const char *what) {
    cr_assert(close_to(got, want, tolerance), "%s: got %.17g, want %.17g", what, got, want);
}

static vec3 grey(double v) { return vec3_make(v, v, v); }

/* The unit vector at `degrees` from +z towards +x: (sin, 0, cos). */
static vec3 tilted_from_z(double degrees) {
    double a = degrees * M_PI / 180.0;
    return vec3_make(sin(a), 0, cos(a));
}

/* A parsed scene and the world made from it. Mesh directives get the octahedron below instead of a
 * file, so no test depends on mesh files or on scene_meshes.c. */
struct fixture {
    struct scene scene;
    struct world world;
};

/* The regular octahedron |x| + |y| + |z| = 1: 6 vertices, 8 faces wound outwards. */
static const vec3 octahedron_vertices[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const struct mesh_face octahedron_faces[8] = {{{0, 2, 4}}, {{1, 4, 2}}, {{0, 4, 3}}, {{0, 5, 2}},
                                                     {{1, 3, 4}}, {{1, 2, 5}}, {{0, 3, 5}}, {{1, 5, 3}}};

/* Gives mesh directive m the octahedron, placed by the directive's own scale, rotate and translate.
 * The arrays are heap copies, owned by the scene as loaded meshes are. */
static void give_octahedron(struct scene_mesh *m) {
    m->mesh.vertices = malloc(sizeof octahedron_vertices);
    m->mesh.faces = malloc(sizeof octahedron_faces);
    cr_assert(m->mesh.vertices != NULL && m->mesh.faces != NULL, "out of memory");
    memcpy(m->mesh.vertices, octahedron_vertices, sizeof octahedron_vertices);
    memcpy(m->mesh.faces, octahedron_faces, sizeof octahedron_faces);
    m->mesh.vertex_count = 6;
    m->mesh.face_count = 8;
    mesh_transform(&m->mesh, m->scale, m->rotate, m->translate);
}

/* Parses the camera and image lines followed by `lines` formatted with `args`, and makes the world. */
__attribute__((format(printf, 2, 0))) static void build_from(struct fixture *f, const char *lines, va_list args) {
    char text[4096];
    int head = snprintf(text, sizeof text, "camera eye 0 0 0 target 0 0 -1 fov 60\nimage 4 3\n");
    int body = vsnprintf(text + head, sizeof text - (size_t)head, lines, args);
    cr_assert_lt((size_t)(head + body), sizeof text, "scene text too long");
    char err[512] = "";
    cr_assert(scene_parse("memory.scene", text, test_every_kind, &f->scene, err, sizeof err), "refused: %s\n%s", err,
              text);
    for (size_t k = 0; k < f->scene.mesh_count; k++)
        give_octahedron(&f->scene.meshes[k]);
    cr_assert(world_init(&f->world, &f->scene, err, sizeof err), "%s", err);
}

/* build_from with printf-style arguments. */
__attribute__((format(printf, 2, 3))) static void build(struct fixture *f, const char *lines, ...) {
    va_list args;
    va_start(args, lines);
    build_from(f, lines, args);
    va_end(args);
}

static void release(struct fixture *f) {
    world_free(&f->world);
    scene_free(&f->scene);
}

static ray ray_along(vec3 origin, vec3 direction) { return (ray){origin, vec3_normalize(direction)}; }

/* ---- box (chapter 5) --------------------------------------------------------------------------- */

/* The 2-unit cube centred on (0, 0, -5): x and y in [-1, 1], z in [-6, -4]. */
static const struct box cube = {{-1, -1, -6}, {1, 1, -4}, 7};

/* The t box_intersect reports for the ray from origin along direction, in (RAY_T_MIN, INFINITY); NAN
 * for a miss. */
static double cube_t(vec3 origin, vec3 direction) {
    ray r = ray_along(origin, direction);
    double t = NAN;
    return box_intersect(&cube, &r, RAY_T_MIN, INFINITY, &t) ? t : NAN;
}

Test(box, ray_from_outside_reports_the_entry_distance) {
    /* From the origin along -z the ray enters at z = -4 (t = 4) and leaves at z = -6. */
    cr_assert_eq(cube_t(vec3_make(0, 0, 0), vec3_make(0, 0, -1)), 4.0);
    /* Along (1, 0, -2)/sqrt(5) from (-1.5, 0, 0): the x slab is entered at t = 0.5 sqrt(5), the z slab at
     * 4 sqrt(5)/2 = 2 sqrt(5); the later one, 2 sqrt(5), is the entry (point (0.5, 0, -4)). */
    assert_number(cube_t(vec3_make(-1.5, 0, 0), vec3_make(1, 0, -2)), 2.0 * sqrt(5.0), SAME, "oblique entry");
}

Test(box, ray_from_inside_reports_the_exit_distance) {
    /* From the centre (0, 0, -5) every face is 1 away; along (1, 1, 0)/sqrt 2 the x and y faces are both
     * reached at t = sqrt 2. */
    cr_assert_eq(cube_t(vec3_make(0, 0, -5), vec3_make(0, 0, -1)), 1.0);
    cr_assert_eq(cube_t(vec3_make(0.5, 0, -5), vec3_make(1, 0, 0)), 0.5);
    assert_number(cube_t(vec3_make(0, 0, -5), vec3_make(1, 1, 0)), sqrt(2.0), SAME, "diagonal exit");
}

Test(box, ray_starting_on_a_face_finds_the_far_face_inwards_and_nothing_outwards) {
    /* On the face z = -4: inwards the interval is [0, 2], 0 is not above t_min, so the far face at t = 2;
     * outwards the interval is [-2, 0] and nothing lies ahead. */
    cr_assert_eq(cube_t(vec3_make(0.25, 0.5, -4), vec3_make(0, 0, -1)), 2.0);
    cr_assert(isnan(cube_t(vec3_make(0.25, 0.5, -4), vec3_make(0, 0, 1))));
}

Test(box, ray_parallel_to_faces_hits_inside_the_slab_and_misses_outside) {
    /* Along -z the x and y slabs never change: x = 0.5 is inside [-1, 1] (entry at z = -4, t = 4), x = 1.5
     * is outside, and x = 1 exactly runs in the face plane, which belongs to the box. */
    cr_assert_eq(cube_t(vec3_make(0.5, -0.75, 0), vec3_make(0, 0, -1)), 4.0);
    cr_assert(isnan(cube_t(vec3_make(1.5, 0, 0), vec3_make(0, 0, -1))));
    cr_assert(isnan(cube_t(vec3_make(0, -1.5, 0), vec3_make(0, 0, -1))));
    cr_assert_eq(cube_t(vec3_make(1, 0, 0), vec3_make(0, 0, -1)), 4.0);
}

Test(box, box_behind_the_ray_misses) {
    /* Along +z the interval is [-6, -4]: all behind the origin. */
    cr_assert(isnan(cube_t(vec3_make(0, 0, 0), vec3_make(0, 0, 1))));
}

Test(box, t_max_before_the_entry_cuts_the_hit_off_and_counts_one_test) {
    ray r = ray_along(vec3_make(0, 0, 0), vec3_make(0, 0, -1));
    double t = -1;
    uint64_t before = stats_thread.box_tests;
    cr_assert(!box_intersect(&cube, &r, RAY_T_MIN, 3.9, &t)); /* entry 4 > 3.9 */
    cr_assert_eq(t, -1.0, "t must be left alone on a miss");
    cr_assert(box_intersect(&cube, &r, RAY_T_MIN, 4.5, &t));
    cr_assert_eq(t, 4.0);
    cr_assert(box_intersect(&cube, &r, 4.0, INFINITY, &t)); /* t_min at the entry: the exit, z = -6 */
    cr_assert_eq(t, 6.0);
    cr_assert_eq(stats_thread.box_tests - before, 3);
}

Test(box, closest_gives_the_outward_normal_of_each_of_the_six_faces) {
    /* From 3 units out along each axis towards the centre (0, 0, -5): the face is hit at t = 2 and its
     * outward normal is that axis. */
    static const vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    vec3 centre = vec3_make(0, 0, -5);
    for (int k = 0; k < 6; k++) {
        ray r = ray_along(vec3_add_scaled(centre, axes[k], 3), vec3_neg(axes[k]));
        struct hit h = hit_nothing(INFINITY);
        cr_assert(box_closest(&cube, 1, &r, RAY_T_MIN, &h), "face %d missed", k);
        cr_assert_eq(h.t, 2.0, "face %d", k);
        assert_colour(h.normal, axes[k], EXACT, "normal");
        cr_assert_eq(h.material, 7);
    }
}

Test(box, closest_from_inside_gives_the_outward_normal_of_the_exit_face) {
    /* From the centre along +y: the face y = 1 at t = 1, normal +y (not turned towards the ray). */
    ray r = ray_along(vec3_make(0, 0, -5), vec3_make(0, 1, 0));
    struct hit h = hit_nothing(INFINITY);
    cr_assert(box_closest(&cube, 1, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 1.0);
    assert_colour(h.normal, vec3_make(0, 1, 0), EXACT, "normal");
}

Test(box, closest_keeps_the_nearer_box_and_leaves_a_nearer_hit_alone) {
    /* Two cubes along -z: the second one, x and y in [-1, 1], z in [-3, -2], is entered at t = 2. */
    struct box boxes[2] = {cube, {{-1, -1, -3}, {1, 1, -2}, 3}};
    ray r = ray_along(vec3_make(0, 0, 0), vec3_make(0, 0, -1));
    struct hit h = hit_nothing(INFINITY);
    cr_assert(box_closest(boxes, 2, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 2.0);
    cr_assert_eq(h.material, 3);
    struct hit nearer = hit_nothing(1.5);
    cr_assert(!box_closest(boxes, 2, &r, RAY_T_MIN, &nearer));
    cr_assert_eq(nearer.t, 1.5);
}

Test(box, a_face_lying_in_a_plane_gives_the_planes_t_to_the_last_bit) {
    /* A box standing on the floor y = 0, and rays from a point inside it to a 41 x 41 grid of points on
     * its bottom face: the face's t must equal the floor's exactly, or rounding, not plane_closest's rule
     * for a tie, decides which one a ray meets. (Found by the slab test's multiplication by 1 / d, the
     * two differed by one unit in the last place on 449 of these 1,681 rays.) */
    const struct box standing = {{-0.8, 0, -0.6}, {0.8, 1.2, 0.6}, 1};
    const struct plane floor = {{0, 1, 0}, 0, 2};
    int unequal = 0;
    for (int i = 0; i <= 40; i++)
        for (int j = 0; j <= 40; j++) {
            vec3 target = vec3_make(-0.79 + 1.58 * i / 40, 0, -0.59 + 1.18 * j / 40);
            vec3 from = vec3_make(0.13, 0.71, 0.29);
            ray r = ray_along(from, vec3_sub(target, from));
            struct hit h = hit_nothing(INFINITY);
            double t_floor;
            cr_assert(box_closest(&standing, 1, &r, RAY_T_MIN, &h));
            assert_colour(h.normal, vec3_make(0, -1, 0), EXACT, "the bottom face");
            cr_assert(plane_intersect(&floor, &r, RAY_T_MIN, INFINITY, &t_floor));
            unequal += h.t != t_floor;
        }
    cr_assert_eq(unequal, 0, "%d of 1681 rays found the face and the floor at different t", unequal);
}

/* ---- world: mesh bounding boxes (chapter 5) ---------------------------------------------------- */

Test(world, mesh_bounds_hold_the_transformed_vertices) {
    /* The octahedron scaled by 0.5 and moved to (2, 0, -5): x in [1.5, 2.5], y in [-0.5, 0.5], z in
     * [-5.5, -4.5], all exact in binary. */
    struct fixture f;
    build(&f, "mesh octahedron.obj scale 0.5 translate 2 0 -5\n");
    struct aabb b = world_mesh_bounds(&f.scene.meshes[0].mesh);
    assert_colour(b.min, vec3_make(1.5, -0.5, -5.5), EXACT, "min");
    assert_colour(b.max, vec3_make(2.5, 0.5, -4.5), EXACT, "max");
    /* world_init culls with that box grown by triangle_box_pad: 2^-20 of the longest side, 1. */
    double pad = 1.0 / 1048576.0;
    assert_colour(f.world.mesh_bounds[0].min, vec3_sub(b.min, grey(pad)), EXACT, "world_init's min");
    assert_colour(f.world.mesh_bounds[0].max, vec3_add(b.max, grey(pad)), EXACT, "world_init's max");
    release(&f);
}

Test(world, a_structures_faces_keep_their_objects_after_a_gathered_mesh_is_freed) {
    /* A triangle line and three octahedra along x; chapter 11 frees a mesh once the structure has
     * gathered its triangles. A ray at the middle octahedron must still find that mesh's object and its
     * own face numbers, which are counted from the first mesh's faces, now gone from the scene. */
    struct fixture f;
    build(&f, "triangle a 10 10 -9 b 11 10 -9 c 10 11 -9\n"
              "mesh octahedron.obj translate -3 0 -5\nmesh octahedron.obj translate 0 0 -5\n"
              "mesh octahedron.obj translate 3 0 -5\n");
    char err[512] = "";
    struct accel_world *w = accel_world_create(&f.scene, &(struct accel_choice){.kind = ACCEL_KDTREE, .sah = true}, err, sizeof err);
    cr_assert_not_null(w, "%s", err);
    mesh_free(&f.scene.meshes[0].mesh);
    for (int k = 1; k <= 2; k++) {
        ray r = ray_along(vec3_make(3.0 * (k - 1), 0.1, 0), vec3_make(0, 0, -1));
        struct hit h = hit_nothing(INFINITY);
        cr_assert(world_closest(&w->world, &r, RAY_T_MIN, &h));
        cr_assert_eq(h.object, world_mesh_object_number(&f.scene, (size_t)k), "mesh %d: object %d", k, h.object);
        cr_assert(h.face >= 0 && h.face < 8, "mesh %d: face %d", k, h.face);
    }
    accel_world_destroy(w);
    release(&f);
}

Test(world, under_a_structure_only_meshes_light_passes_through_get_a_box) {
    /* world_init_for_structure: a structure answers for the triangles, so an opaque mesh's cull box is
     * never read and is left as all of space; a glass mesh's is made, for interior.c's inside test. */
    struct fixture f;
    build(&f, "material glass colour 1 1 1 filter 0.9 ior 1.5\n"
              "mesh octahedron.obj translate 0 0 -5\nmesh octahedron.obj translate 3 0 -5 material glass\n");
    struct world w;
    char err[512] = "";
    cr_assert(world_init_for_structure(&w, &f.scene, err, sizeof err), "%s", err);
    cr_assert(isinf(w.mesh_bounds[0].min.x) && w.mesh_bounds[0].min.x < 0 && isinf(w.mesh_bounds[0].max.z),
              "the opaque mesh's box: all of space");
    for (int a = 0; a < 2; a++) { /* the glass mesh's box is world_init's, to the bit */
        const struct aabb *got = a == 0 ? &w.mesh_bounds[1] : &f.world.mesh_bounds[1];
        cr_assert(memcmp(got, &f.world.mesh_bounds[1], sizeof *got) == 0 && got->min.x > 1.9 && got->max.x < 4.1);
    }
    cr_assert(w.mesh_first_face[2] == 16 && f.world.mesh_first_face[2] == 16);
    world_free(&w);
    release(&f);
}

Test(world, a_lone_mesh_is_borrowed_by_the_structure_and_more_are_copied) {
    /* A scene whose only triangles are one mesh's: the structure is built over that mesh itself (the
     * same arrays, not a copy), and destroying the world leaves it to the scene. With a triangle line
     * or a second mesh beside it, the triangles are gathered into a copy. Each finds the same face. */
    const char *scenes[] = {"mesh octahedron.obj translate 0 0 -5\n",
                            "triangle a 10 10 -9 b 11 10 -9 c 10 11 -9\nmesh octahedron.obj translate 0 0 -5\n",
                            "mesh octahedron.obj translate 0 0 -5\nmesh octahedron.obj translate 3 0 -5\n"};
    for (int k = 0; k < 3; k++) {
        struct fixture f;
        build(&f, "%s", scenes[k]);
        char err[512] = "";
        struct accel_world *w = accel_world_create(&f.scene, &(struct accel_choice){.kind = ACCEL_KDTREE, .sah = true}, err, sizeof err);
        cr_assert_not_null(w, "%s", err);
        const struct mesh *m = &f.scene.meshes[0].mesh;
        bool shared = w->triangles.vertices == m->vertices && w->triangles.faces == m->faces;
        cr_assert_eq(w->triangles_borrowed, k == 0, "scene %d: borrowed %d", k, w->triangles_borrowed);
        cr_assert_eq(shared, k == 0, "scene %d: the structure's arrays are the mesh's: %d", k, shared);
        ray r = ray_along(vec3_make(0, 0.1, 0), vec3_make(0, 0, -1));
        struct hit h = hit_nothing(INFINITY);
        cr_assert(world_closest(&w->world, &r, RAY_T_MIN, &h));
        cr_assert(h.object == world_mesh_object_number(&f.scene, 0) && fabs(h.t - 4.1) < 1e-9, "scene %d: object %d at %g", k,
                  h.object, h.t);
        accel_world_destroy(w);
        cr_assert(m->face_count == 8 && m->vertices[0].x == m->vertices[0].x, "the scene's mesh is still there");
        release(&f); /* frees the mesh once: AddressSanitizer would see a second free */
    }
}

Test(world, bounds_of_a_mesh_without_vertices_are_the_empty_box) {
    struct mesh empty = {NULL, 0, NULL, 0};
    struct aabb b = world_mesh_bounds(&empty);
    assert_colour(b.min, grey(INFINITY), EXACT, "min");
    assert_colour(b.max, grey(-INFINITY), EXACT, "max");
}

/* Runs world_closest for the ray from origin along -z against the octahedron at (0, 0, -5) (bounding box
 * x, y in [-1, 1], z in [-6, -4]); returns the triangle tests it cost and the hit in *h. */
static uint64_t octahedron_triangle_tests(vec3 origin, struct hit *h, bool *found) {
    struct fixture f;
    build(&f, "mesh octahedron.obj translate 0 0 -5\n");
    ray r = ray_along(origin, vec3_make(0, 0, -1));
    *h = hit_nothing(INFINITY);
    uint64_t before = stats_thread.triangle_tests, boxes_before = stats_thread.box_tests;
    *found = world_closest(&f.world, &r, RAY_T_MIN, h);
    cr_assert_eq(stats_thread.box_tests - boxes_before, 1, "one bounding-box test per mesh");
    release(&f);
    return stats_thread.triangle_tests - before;
}

Test(world, ray_missing_a_mesh_bounding_box_costs_no_triangle_test) {
    /* y = 1.5 is outside the box's y slab [-1, 1]. */
    struct hit h;
    bool found;
    cr_assert_eq(octahedron_triangle_tests(vec3_make(0, 1.5, 0), &h, &found), 0);
    cr_assert(!found);
}

Test(world, ray_entering_a_mesh_bounding_box_tests_every_face) {
    /* (0.9, 0.9) is inside the box but |x| + |y| = 1.8 > 1: all 8 faces are tested and none is hit. */
    struct hit h;
    bool found;
    cr_assert_eq(octahedron_triangle_tests(vec3_make(0.9, 0.9, 0), &h, &found), 8);
    cr_assert(!found);
    /* (0.25, 0.25) meets the face x + y + (z + 5) = 1 at z + 5 = 0.5, z = -4.5: t = 4.5, outward normal
     * (1, 1, 1)/sqrt 3, after all 8 faces were tested. */
    cr_assert_eq(octahedron_triangle_tests(vec3_make(0.25, 0.25, 0), &h, &found), 8);
    cr_assert(found);
    assert_number(h.t, 4.5, SAME, "t");
    assert_colour(h.normal, grey(1.0 / sqrt(3.0)), SAME, "normal");
}

/* ---- world: the triangle tests the bounding boxes saved (chapter 5) ---------------------------- */

/* The triangle tests one query ran and the ones its bounding boxes saved, since `before`. */
struct triangle_work {
    uint64_t tested;
    uint64_t culled;
};

static struct triangle_work triangle_work_since(const struct stats *before) {
    return (struct triangle_work){stats_thread.triangle_tests - before->triangle_tests,
                                  stats_thread.triangle_tests_culled - before->triangle_tests_culled};
}

/* A world_crossing_visitor that counts the crossings in *(int *)context and never stops. */
static bool count_every_crossing(void *context, double t, int material) {
    (void)t;
    (void)material;
    ++*(int *)context;
    return true;
}

Test(world, a_mesh_whose_bounding_box_is_missed_adds_its_faces_to_the_culled_count) {
    /* Two octahedra of 8 faces on the -z axis: boxes z in [-6, -4] and z in [-11, -9], x and y in
     * [-1, 1]. */
    struct fixture f;
    build(&f, "mesh octahedron.obj translate 0 0 -5\nmesh octahedron.obj translate 0 0 -10\n");
    struct stats before = stats_thread;

    /* From (0.25, 0.25) the nearest search hits the first octahedron at t = 4.5, before the second box
     * begins (t = 9): 8 faces tested, 8 culled by the shorter ray. */
    ray through = ray_along(vec3_make(0.25, 0.25, 0), vec3_make(0, 0, -1));
    struct hit h = hit_nothing(INFINITY);
    cr_assert(world_closest(&f.world, &through, RAY_T_MIN, &h));
    assert_number(h.t, 4.5, SAME, "t");
    struct triangle_work work = triangle_work_since(&before);
    cr_assert_eq(work.tested, 8);
    cr_assert_eq(work.culled, 8);

    /* The crossings along the whole ray enter both boxes: all 16 faces tested, none culled. With
     * |x| + |y| = 0.5 the ray crosses each octahedron where |z + 5|, or |z + 10|, is 0.5: 4 crossings. */
    before = stats_thread;
    int crossings = 0;
    world_for_each_crossing(&f.world, &through, RAY_T_MIN, INFINITY, count_every_crossing, &crossings);
    work = triangle_work_since(&before);
    cr_assert_eq(crossings, 4);
    cr_assert_eq(work.tested, 16);
    cr_assert_eq(work.culled, 0);

    /* y = 1.5 is outside both boxes' y slab: both queries test nothing and cull all 16 faces. */
    ray above = ray_along(vec3_make(0, 1.5, 0), vec3_make(0, 0, -1));
    before = stats_thread;
    h = hit_nothing(INFINITY);
    cr_assert(!world_closest(&f.world, &above, RAY_T_MIN, &h));
    work = triangle_work_since(&before);
    cr_assert_eq(work.tested, 0);
    cr_assert_eq(work.culled, 16);
    before = stats_thread;
    crossings = 0;
    world_for_each_crossing(&f.world, &above, RAY_T_MIN, INFINITY, count_every_crossing, &crossings);
    work = triangle_work_since(&before);
    cr_assert_eq(crossings, 0);
    cr_assert_eq(work.tested, 0);
    cr_assert_eq(work.culled, 16);
    release(&f);
}

/* The test below traces the centre pixel of each CHAPTER_5_PIXEL_STEP x CHAPTER_5_PIXEL_STEP block:
 * 40 x 30 of the 320 x 240 camera rays, enough to cross each bounding box and to miss both, for about
 * 10 million brute-force triangle tests (a fraction of a second). */
#define CHAPTER_5_PIXEL_STEP 8

/* Loads scenes/05-aabb.scene with its meshes, as chapter 5 does, into *s and *w, and its camera into
 * *cam; skips the test when a mesh file is missing (the teapots are generated: make models). */
static void load_chapter_5_scene(struct scene *s, struct world *w, struct camera *cam) {
    static const char path[] = "scenes/05-aabb.scene";
    char err[512] = "";
    cr_assert(scene_load(path, test_every_kind, s, err, sizeof err), "%s (run the tests from the repository root)",
              err);
    for (size_t k = 0; k < s->mesh_count; k++) {
        FILE *mesh_file = fopen(s->meshes[k].path, "rb");
        if (mesh_file == NULL) {
            char missing[512];
            snprintf(missing, sizeof missing, "%s", s->meshes[k].path);
            scene_free(s);
            cr_skip_test("%s not found (make models)", missing);
        }
        fclose(mesh_file);
    }
    cr_assert(scene_load_meshes(s, err, sizeof err), "%s", err);
    cr_assert(world_init(w, s, err, sizeof err), "%s", err);
    cr_assert(camera_init(cam, s->eye, s->target, s->up, s->fov, s->width, s->height, err, sizeof err), "%s",
              err);
}

Test(world, on_the_chapter_5_scene_triangle_tests_plus_culled_equal_chapter_4s_brute_force) {
    struct scene s;
    struct world w;
    struct camera cam;
    load_chapter_5_scene(&s, &w, &cam);
    const struct shape_list *triangles = scene_shapes(&s, &triangle_syntax);
    uint64_t rays = 0, tested = 0, culled = 0, brute_force = 0;
    for (int j = CHAPTER_5_PIXEL_STEP / 2; j < cam.height; j += CHAPTER_5_PIXEL_STEP) {
        for (int i = CHAPTER_5_PIXEL_STEP / 2; i < cam.width; i += CHAPTER_5_PIXEL_STEP) {
            ray r = camera_ray(&cam, i, j);
            struct stats before = stats_thread;
            struct hit h = hit_nothing(INFINITY);
            world_closest(&w, &r, RAY_T_MIN, &h);
            struct triangle_work work = triangle_work_since(&before);

            /* Chapter 4's trace_with_planes: every triangle, then every face of every mesh. */
            before = stats_thread;
            struct hit every = hit_nothing(INFINITY);
            triangle_closest(triangles->items, triangles->count, &r, RAY_T_MIN, &every);
            for (size_t k = 0; k < s.mesh_count; k++)
                triangle_mesh_closest(&s.meshes[k].mesh, s.meshes[k].material, &r, RAY_T_MIN, &every);
            uint64_t all = stats_thread.triangle_tests - before.triangle_tests;

            cr_assert_eq(work.tested + work.culled, all, "pixel (%d, %d): %" PRIu64 " tested + %" PRIu64
                         " culled, brute force %" PRIu64, i, j, work.tested, work.culled, all);
            rays++;
            tested += work.tested;
            culled += work.culled;
            brute_force += all;
        }
    }
    /* Not vacuous: both kinds of ray occur, and brute force tested every face (the bunny's 3,674 and
     * the teapot's 5,112) for each of the 40 x 30 rays. */
    uint64_t faces = triangles->count;
    for (size_t k = 0; k < s.mesh_count; k++)
        faces += s.meshes[k].mesh.face_count;
    cr_assert_gt(tested, 0);
    cr_assert_gt(culled, tested, "the boxes should save most of the work on this scene");
    cr_assert_eq(rays, 40 * 30);
    cr_assert_eq(brute_force, faces * rays);
    world_free(&w);
    scene_free(&s);
}

/* ---- Phong (chapter 6) ------------------------------------------------------------------------- */

/* The surface of every Phong test: the origin, normal +z. */
static const vec3 up_normal = {0, 0, 1};
static const vec3 earthy = {0.8, 0.4, 0.2}; /* a colour with three different channels */

static struct material finish(vec3 colour, double ambient, double diffuse, double phong, double phong_size) {
    struct material m = {.colour = colour,
                         .ambient = ambient,
                         .diffuse = diffuse,
                         .phong = phong,
                         .phong_size = phong_size,
                         .ior = 1.0};
    return m;
}

/* A light of `colour` 10 units from the origin in direction `towards`. */
static struct light light_towards(vec3 towards, vec3 colour) {
    return (struct light){.position = vec3_scale(vec3_normalize(towards), 10.0), .colour = colour};
}

/* phong_shade at the origin (normal +z), seen along `direction`, with the given lights and ambient
 * light, no shadows. */
static vec3 shade(const struct material *m, vec3 direction, struct light *lights, size_t light_count,
                  vec3 ambient_light, double opacity) {
    struct scene s;
    memset(&s, 0, sizeof s);
    s.ambient_light = ambient_light;
    s.lights = lights;
    s.light_count = light_count;
    struct phong_surface at = {{0, 0, 0}, up_normal, vec3_normalize(direction), m, opacity};
    return phong_shade(&s, &at, NULL, NULL);
}

/* shade with one white light towards `towards`, ambient light 1 and opacity 1. */
static vec3 shade_one_light(const struct material *m, vec3 direction, vec3 towards) {
    struct light light = light_towards(towards, grey(1));
    return shade(m, direction, &light, 1, grey(1), 1.0);
}

Test(phong, light_behind_the_surface_leaves_only_the_ambient_term) {
    /* The ray comes in along (1, 0, -1): its mirror direction is (1, 0, 1)/sqrt 2. The light at
     * (1, 0, -0.05) is below the surface (N.L < 0) yet R.L = (1 - 0.05)/(sqrt 2 |(1, 0, -0.05)|) > 0:
     * still no diffuse and no highlight. Left: ambient 0.1 * 1 * C. */
    struct material m = finish(earthy, 0.1, 0.6, 1.0, 1.0);
    assert_colour(shade_one_light(&m, vec3_make(1, 0, -1), vec3_make(1, 0, -0.05)), vec3_scale(earthy, 0.1), SAME,
                  "colour");
}

Test(phong, a_highlight_rounded_past_full_alignment_stays_finite) {
    /* A light straight along the mirror direction: R.L is 1 exactly in real numbers, but rounded it can be
     * 1 + 2e-16, and that to the power 1e300 is infinite. Some such direction is found among a few
     * hundred; the highlight there must be phong times the light, 1, not infinity. */
    struct material m = finish(earthy, 0.0, 0.0, 1.0, 1e300);
    int found = 0;
    for (int k = 1; k < 100000 && !found; k++) {
        vec3 direction = vec3_normalize(vec3_make(sin(k), cos(0.7 * k), -1.0 - 0.001 * k));
        vec3 mirror = phong_reflect(direction, up_normal);
        struct light light = light_towards(mirror, grey(1));
        if (vec3_dot(mirror, vec3_normalize(light.position)) <= 1.0)
            continue;
        found = k;
        vec3 colour = shade(&m, direction, &light, 1, grey(0), 1.0);
        cr_assert(isfinite(colour.x) && fabs(colour.x - 1.0) < 1e-9, "direction %d: highlight %g", k, colour.x);
    }
    cr_assert(found > 0, "no direction rounds past full alignment");
}

Test(phong, diffuse_at_60_degrees_is_half_of_kd_times_the_colour) {
    /* N.L = cos 60 = 0.5: 0.5 * 0.6 * C = (0.24, 0.12, 0.06). */
    struct material m = finish(earthy, 0.0, 0.6, 0.0, 40.0);
    assert_colour(shade_one_light(&m, vec3_make(0, 0, -1), tilted_from_z(60)), vec3_scale(earthy, 0.5 * 0.6), SAME,
                  "colour");
}

Test(phong, highlight_along_the_mirror_direction_is_phong_in_the_light_colour) {
    /* The ray along (1, 0, -1) mirrors to (1, 0, 1)/sqrt 2, exactly towards the light: R.L = 1, so the
     * highlight is phong * 1^40 = 0.7 in every channel, not 0.7 * C. */
    struct material m = finish(earthy, 0.0, 0.0, 0.7, 40.0);
    assert_colour(shade_one_light(&m, vec3_make(1, 0, -1), vec3_make(1, 0, 1)), grey(0.7), SAME, "colour");
}

Test(phong, highlight_at_60_degrees_from_the_mirror_direction_is_phong_times_cos_to_the_n) {
    /* Straight down, the mirror direction is +z; the light at 60 degrees from it: R.L = 0.5, and with
     * phong_size 3 the highlight is 0.8 * 0.5^3 = 0.1. */
    struct material m = finish(earthy, 0.0, 0.0, 0.8, 3.0);
    assert_colour(shade_one_light(&m, vec3_make(0, 0, -1), tilted_from_z(60)), grey(0.1), SAME, "colour");
}

Test(phong, larger_phong_size_narrows_the_highlight_but_keeps_its_peak) {
    /* Off the mirror direction by 60 degrees (R.L = 0.5): phong_size 1 gives 0.5, 10 gives 0.5^10 =
     * 1/1024. Along the mirror direction both give phong = 1. */
    struct material wide = finish(earthy, 0.0, 0.0, 1.0, 1.0), narrow = finish(earthy, 0.0, 0.0, 1.0, 10.0);
    vec3 down = vec3_make(0, 0, -1), off = tilted_from_z(60);
    assert_colour(shade_one_light(&wide, down, off), grey(0.5), SAME, "phong_size 1");
    assert_colour(shade_one_light(&narrow, down, off), grey(1.0 / 1024.0), SAME, "phong_size 10");
    assert_colour(shade_one_light(&wide, down, up_normal), grey(1.0), SAME, "peak, phong_size 1");
    assert_colour(shade_one_light(&narrow, down, up_normal), grey(1.0), SAME, "peak, phong_size 10");
}

Test(phong, two_coloured_lights_add_channel_by_channel) {
    /* Seen straight down (R = +z). A red light straight above: N.L = R.L = 1, adds (kd C.r + kp, 0, 0).
     * A green light at 60 degrees: N.L = R.L = 0.5, adds (0, 0.5 kd C.g + kp 0.5^2, 0). With kd = 0.5,
     * kp = 0.25, phong_size 2, C = (0.8, 0.4, 0.2), ambient 0: (0.4 + 0.25, 0.1 + 0.0625, 0). */
    struct material m = finish(earthy, 0.0, 0.5, 0.25, 2.0);
    struct light lights[2] = {light_towards(up_normal, vec3_make(1, 0, 0)),
                              light_towards(tilted_from_z(60), vec3_make(0, 1, 0))};
    assert_colour(shade(&m, vec3_make(0, 0, -1), lights, 2, grey(1), 1.0), vec3_make(0.65, 0.1625, 0.0), SAME,
                  "colour");
}

Test(phong, ambient_light_and_ambient_scale_the_ambient_term) {
    /* No lights: ka * Ia * C = 0.5 * (0.5, 0.25, 2) * (0.8, 0.4, 0.2) = (0.2, 0.05, 0.2). */
    struct material m = finish(earthy, 0.5, 0.6, 0.7, 40.0);
    assert_colour(shade(&m, vec3_make(0, 0, -1), NULL, 0, vec3_make(0.5, 0.25, 2.0), 1.0),
                  vec3_make(0.2, 0.05, 0.2), SAME, "colour");
}

Test(phong, opacity_scales_ambient_and_diffuse_but_not_the_highlight) {
    /* filter 0.25 + transmit 0.5: opacity 0.25. Light straight above, ray straight down: N.L = R.L = 1.
     * ka C opacity + kd C opacity + kp = (0.2 + 0.6) * 0.25 * C + 0.7 = 0.2 C + 0.7
     * = (0.86, 0.78, 0.74). */
    struct material m = finish(earthy, 0.2, 0.6, 0.7, 40.0);
    m.filter = 0.25;
    m.transmit = 0.5;
    struct light light = light_towards(up_normal, grey(1));
    assert_colour(shade(&m, vec3_make(0, 0, -1), &light, 1, grey(1), 1.0 - m.filter - m.transmit),
                  vec3_make(0.86, 0.78, 0.74), SAME, "colour");
}

Test(phong, light_in_the_tangent_plane_or_below_the_cut_off_adds_nothing) {
    /* The ray along (1, 0, -1) mirrors to (1, 0, 1)/sqrt 2. A light along +x lies in the tangent plane:
     * N.L = 0, yet R.L = 1/sqrt 2 > 0. Nothing is added: ambient 0.1 C only. The same for N.L = 1e-11,
     * below PHONG_MIN_COSINE = 1e-10. */
    struct material m = finish(earthy, 0.1, 0.6, 1.0, 1.0);
    vec3 ambient_only = vec3_scale(earthy, 0.1);
    assert_colour(shade_one_light(&m, vec3_make(1, 0, -1), vec3_make(1, 0, 0)), ambient_only, EXACT, "N.L = 0");
    assert_colour(shade_one_light(&m, vec3_make(1, 0, -1), vec3_make(1, 0, 1e-11)), ambient_only, EXACT,
                  "N.L = 1e-11");
}

Test(phong, light_just_above_the_cut_off_adds_diffuse_and_highlight) {
    /* Light along (1, 0, 1e-9): N.L = 1e-9 >= 1e-10, and R.L = (1 + 1e-9)/sqrt 2 (|L| = 1 to within
     * 1e-18). With ka 0.1, kd 0.6, kp 1, phong_size 1: 0.1 C + 0.6e-9 C + (1 + 1e-9)/sqrt 2. */
    struct material m = finish(earthy, 0.1, 0.6, 1.0, 1.0);
    vec3 want = vec3_add(vec3_scale(earthy, 0.1 + 0.6e-9), grey((1 + 1e-9) / sqrt(2.0)));
    assert_colour(shade_one_light(&m, vec3_make(1, 0, -1), vec3_make(1, 0, 1e-9)), want, SAME, "colour");
}

/* A shadow factor that lets half the red, all the green and none of the blue through, and counts calls. */
static int shadow_calls;
static vec3 half_red_no_blue(const void *world, vec3 point, const struct light *light) {
    (void)world;
    (void)point;
    (void)light;
    shadow_calls++;
    return vec3_make(0.5, 1, 0);
}

Test(phong, shadow_factor_scales_diffuse_and_highlight_and_is_asked_only_for_lights_in_front) {
    /* Light straight above, ray straight down: N.L = R.L = 1; diffuse 0.5 C + highlight 0.25 = (0.65,
     * 0.45, 0.35), times S = (0.5, 1, 0): (0.325, 0.45, 0). The light below is skipped before its shadow
     * ray. Ambient 0.1 C = (0.08, 0.04, 0.02) is not shadowed. */
    struct material m = finish(earthy, 0.1, 0.5, 0.25, 40.0);
    struct light lights[2] = {light_towards(up_normal, grey(1)), light_towards(vec3_make(0, 0, -1), grey(1))};
    struct scene s;
    memset(&s, 0, sizeof s);
    s.ambient_light = grey(1);
    s.lights = lights;
    s.light_count = 2;
    struct phong_surface at = {{0, 0, 0}, up_normal, {0, 0, -1}, &m, 1.0};
    shadow_calls = 0;
    assert_colour(phong_shade(&s, &at, half_red_no_blue, NULL), vec3_make(0.405, 0.49, 0.02), SAME, "colour");
    cr_assert_eq(shadow_calls, 1);
}

Test(phong, reflect_mirrors_about_the_normal) {
    /* D - 2 (D.N) N: (1, -1, 0) about +y is (1, 1, 0); straight down about +z is straight up; (0, 0, -1)
     * about (0, 0.6, 0.8): D.N = -0.8, D + 1.6 N = (0, 0.96, 0.28); a direction in the tangent plane
     * stays as it is. */
    assert_colour(phong_reflect(vec3_make(1, -1, 0), vec3_make(0, 1, 0)), vec3_make(1, 1, 0), EXACT, "45 degrees");
    assert_colour(phong_reflect(vec3_make(0, 0, -1), up_normal), vec3_make(0, 0, 1), EXACT, "normal incidence");
    assert_colour(phong_reflect(vec3_make(0, 0, -1), vec3_make(0, 0.6, 0.8)), vec3_make(0, 0.96, 0.28), SAME,
                  "oblique normal");
    assert_colour(phong_reflect(vec3_make(0.6, 0.8, 0), up_normal), vec3_make(0.6, 0.8, 0), EXACT, "grazing");
}

/* A sphere of radius 1 at (0, 0, -5) lit from the eye, background (0.1, 0.2, 0.3). */
#define LIT_SPHERE_SCENE                                                                                          \
    "background 0.1 0.2 0.3\nlight position 0 0 0\n"                                                              \
    "material m colour 0.8 0.4 0.2 ambient 0.2 diffuse 0.6 phong 0.5\nsphere centre 0 0 -5 radius 1 material m\n"

Test(phong, trace_nearest_returns_the_background_on_a_miss) {
    struct fixture f;
    build(&f, LIT_SPHERE_SCENE);
    ray r = ray_along(vec3_make(0, 0, 0), vec3_make(0, 1, 0));
    assert_colour(phong_trace_nearest(&f.world, &r, NULL), vec3_make(0.1, 0.2, 0.3), EXACT, "miss");
    assert_colour(phong_trace_nearest(&f.world, &r, shadow_opaque), vec3_make(0.1, 0.2, 0.3), EXACT,
                  "miss, with shadows");
    release(&f);
}

Test(phong, trace_nearest_shades_the_nearest_hit) {
    /* Straight down -z: the sphere at (0, 0, -4), N = +z, the light straight back along N: N.L = R.L = 1,
     * 0.2 C + 0.6 C + 0.5 = 0.8 (0.8, 0.4, 0.2) + 0.5 = (1.14, 0.82, 0.66). The sphere does not shadow
     * its own lit side. */
    struct fixture f;
    build(&f, LIT_SPHERE_SCENE);
    ray r = ray_along(vec3_make(0, 0, 0), vec3_make(0, 0, -1));
    assert_colour(phong_trace_nearest(&f.world, &r, NULL), vec3_make(1.14, 0.82, 0.66), SAME, "no shadows");
    assert_colour(phong_trace_nearest(&f.world, &r, shadow_opaque), vec3_make(1.14, 0.82, 0.66), SAME,
                  "opaque shadows");
    release(&f);
}

/* ---- shadows (chapters 7 and 8) ---------------------------------------------------------------- */

/* Every shadow test: the point at the origin, the light 10 units straight up. */
static const struct light overhead = {.position = {0, 10, 0}, .colour = {1, 1, 1}};

/* The shadow factor `fn` gives at the origin in the scene `lines` (printf-formatted). */
__attribute__((format(printf, 2, 3))) static vec3 shadow_at_origin(phong_shadow_fn fn, const char *lines, ...) {
    struct fixture f;
    va_list args;
    va_start(args, lines);
    build_from(&f, lines, args);
    va_end(args);
    vec3 factor = fn(&f.world, vec3_make(0, 0, 0), &overhead);
    release(&f);
    return factor;
}

Test(shadow, sphere_between_the_point_and_the_light_blocks_it) {
    assert_colour(shadow_at_origin(shadow_opaque, "sphere centre 0 5 0 radius 1\n"), grey(0), EXACT, "blocked");
}

Test(shadow, sphere_beyond_the_light_or_behind_the_point_does_not_block) {
    /* y in [12, 14] is past the light at 10; y in [-4, -2] is behind the point. */
    assert_colour(shadow_at_origin(shadow_opaque, "sphere centre 0 13 0 radius 1\n"), grey(1), EXACT, "beyond");
    assert_colour(shadow_at_origin(shadow_opaque, "sphere centre 0 -3 0 radius 1\n"), grey(1), EXACT, "behind");
    assert_colour(shadow_at_origin(shadow_opaque, "sphere centre 3 5 0 radius 1\n"), grey(1), EXACT, "beside");
}

/* The opaque shadow of the plane y = height, shadow_offset `offset`. */
static vec3 shadow_of_plane_at(double height, const char *offset) {
    return shadow_at_origin(shadow_opaque, "shadow_offset %s\nplane normal 0 1 0 distance %.17g\n", offset,
                            height);
}

Test(shadow, blocker_within_the_margin_of_the_point_does_not_count) {
    /* Blockers count for 1e-3 < t < 10 - 1e-3: a plane at t = 0.5e-3 is ignored, one at 2e-3 blocks; so
     * is a thin box lying wholly at 0.4e-3 < y < 0.6e-3, and a box reaching from there to y = 2e-3
     * blocks with its far face. */
    assert_colour(shadow_of_plane_at(0.5e-3, "on"), grey(1), EXACT, "plane at 0.5e-3");
    assert_colour(shadow_of_plane_at(2e-3, "on"), grey(0), EXACT, "plane at 2e-3");
    assert_colour(shadow_at_origin(shadow_opaque, "box min -1 0.0004 -1 max 1 0.0006 1\n"), grey(1), EXACT,
                  "thin box");
    assert_colour(shadow_at_origin(shadow_opaque, "box min -1 0.0004 -1 max 1 0.002 1\n"), grey(0), EXACT,
                  "box reaching past the margin");
}

Test(shadow, blocker_within_the_margin_of_the_light_does_not_count) {
    /* The light is at t = 10: a plane at 10 - 0.5e-3 is inside the end margin, one at 10 - 2e-3 is not. */
    assert_colour(shadow_of_plane_at(10 - 0.5e-3, "on"), grey(1), EXACT, "plane 0.5e-3 below the light");
    assert_colour(shadow_of_plane_at(10 - 2e-3, "on"), grey(0), EXACT, "plane 2e-3 below the light");
}

Test(shadow, shadow_offset_off_drops_both_margins) {
    /* With the window 0 < t < 10, the planes the margins ignored now block. */
    assert_colour(shadow_of_plane_at(0.5e-3, "off"), grey(0), EXACT, "plane at 0.5e-3");
    assert_colour(shadow_of_plane_at(10 - 0.5e-3, "off"), grey(0), EXACT, "plane 0.5e-3 below the light");
    assert_colour(shadow_of_plane_at(-0.5e-3, "off"), grey(1), EXACT, "plane behind the point");
}

/* How many lit surface points of a sphere shadow themselves, over a 40 x 40 fan of rays from the origin:
 * each hit point ray_at(r, t) is rounded, about half of them slightly inside the sphere, where the
 * shadow ray meets the sphere again at t of about 1e-16. Only points facing the light (N.L > 0.1) are
 * asked, so every shadow found is acne. */
static int self_shadowed_points(const char *offset) {
    struct fixture f;
    build(&f, "shadow_offset %s\nlight position 2 3 1\nsphere centre 0.1 0.2 -3 radius 0.7\n", offset);
    const struct light *light = &f.scene.lights[0];
    int acne = 0, asked = 0;
    for (int i = 0; i < 40; i++)
        for (int j = 0; j < 40; j++) {
            ray r = ray_along(vec3_make(0, 0, 0), vec3_make(-0.3 + 0.015 * i, -0.2 + 0.015 * j, -1));
            struct hit h = hit_nothing(INFINITY);
            if (!world_closest(&f.world, &r, RAY_T_MIN, &h))
                continue;
            vec3 p = ray_at(r, h.t);
            if (vec3_dot(h.normal, vec3_normalize(vec3_sub(light->position, p))) < 0.1)
                continue;
            asked++;
            acne += shadow_opaque(&f.world, p, light).x == 0.0;
        }
    cr_assert_gt(asked, 100, "the fan should see the lit side of the sphere");
    release(&f);
    return acne;
}

Test(shadow, shadow_offset_off_lets_a_sphere_shadow_its_own_lit_side) {
    cr_assert_eq(self_shadowed_points("on"), 0);
    cr_assert_gt(self_shadowed_points("off"), 0);
}

Test(shadow, filtered_light_through_a_clear_sphere_is_transmit_squared) {
    /* Crossed twice: 0.9 * 0.9 = 0.81 in every channel. */
    vec3 factor = shadow_at_origin(shadow_filtered, "material glass transmit 0.9\n"
                                                    "sphere centre 0 5 0 radius 1 material glass\n");
    assert_colour(factor, grey(0.9 * 0.9), SAME, "two crossings");
}

Test(shadow, filtered_light_through_tinted_glass_is_colour_times_filter_per_crossing) {
    /* C F = (1, 0.5, 0.25) * 0.8 = (0.8, 0.4, 0.2): once through a plane, squared through a sphere,
     * (0.64, 0.16, 0.04). */
    const char *tint = "material tint colour 1 0.5 0.25 filter 0.8\n";
    assert_colour(shadow_at_origin(shadow_filtered, "%splane normal 0 1 0 distance 5 material tint\n", tint),
                  vec3_make(0.8, 0.4, 0.2), SAME, "plane");
    assert_colour(shadow_at_origin(shadow_filtered, "%ssphere centre 0 5 0 radius 1 material tint\n", tint),
                  vec3_make(0.64, 0.16, 0.04), SAME, "sphere");
}

Test(shadow, filtered_light_multiplies_every_surface_and_stops_at_opaque_ones) {
    /* Glass sphere (0.81) then a plane with filter 0.5 and transmit 0.25 of colour (1, 0, 0.5):
     * (0.75, 0.25, 0.5) * 0.81 = (0.6075, 0.2025, 0.405). An opaque box in the way gives 0. */
    const char *materials =
        "material glass transmit 0.9\nmaterial pane colour 1 0 0.5 filter 0.5 transmit 0.25\n"
        "sphere centre 0 5 0 radius 1 material glass\nplane normal 0 1 0 distance 8 material pane\n";
    assert_colour(shadow_at_origin(shadow_filtered, "%s", materials), vec3_make(0.6075, 0.2025, 0.405), SAME,
                  "glass and pane");
    assert_colour(shadow_at_origin(shadow_filtered, "%sbox min -1 2 -1 max 1 3 1\n", materials), grey(0), EXACT,
                  "with an opaque box");
    assert_colour(shadow_at_origin(shadow_filtered, "sphere centre 0 5 0 radius 1\n"), grey(0), EXACT,
                  "opaque sphere");
}

Test(shadow, filtered_shadows_keep_the_same_margins) {
    assert_colour(shadow_at_origin(shadow_filtered, "plane normal 0 1 0 distance 0.0005\n"), grey(1), EXACT,
                  "plane at 0.5e-3");
    assert_colour(shadow_at_origin(shadow_filtered, "plane normal 0 1 0 distance 9.9995\n"), grey(1), EXACT,
                  "plane 0.5e-3 below the light");
}

Test(shadow, each_call_is_one_shadow_ray_however_many_surfaces_it_crosses) {
    /* Two glass spheres (four crossings) and an opaque box: still one shadow ray per call. */
    struct fixture f;
    build(&f, "material glass transmit 0.5\nsphere centre 0 3 0 radius 1 material glass\n"
              "sphere centre 0 6 0 radius 1 material glass\nbox min -1 8 -1 max 1 9 1\n");
    uint64_t before = stats_thread.shadow_rays;
    vec3 o = vec3_make(0, 0, 0);
    assert_colour(shadow_filtered(&f.world, o, &overhead), grey(0), EXACT, "filtered");
    cr_assert_eq(stats_thread.shadow_rays - before, 1);
    assert_colour(shadow_opaque(&f.world, o, &overhead), grey(0), EXACT, "opaque");
    cr_assert_eq(stats_thread.shadow_rays - before, 2);
    struct light low = {.position = {0, 4.5, 0}, .colour = {1, 1, 1}}; /* between the spheres: 0.5^2 = 0.25 */
    assert_colour(shadow_filtered(&f.world, o, &low), grey(0.25), SAME, "first sphere only");
    cr_assert_eq(stats_thread.shadow_rays - before, 3);
    release(&f);
}

/* ---- refraction (chapter 8) -------------------------------------------------------------------- */

/* The unit direction arriving at `degrees` from the normal +z, going down: (sin, 0, -cos). */
static vec3 incident(double degrees) {
    vec3 v = tilted_from_z(degrees);
    return vec3_make(v.x, 0, -v.z);
}

Test(refract, normal_incidence_goes_straight_through) {
    /* c = 1, k = 1: eta D + (eta - 1) N = (0, 0, -eta + eta - 1) = (0, 0, -1). */
    vec3 out;
    cr_assert(whitted_refract(vec3_make(0, 0, -1), up_normal, 1.0 / 1.5, &out));
    assert_colour(out, vec3_make(0, 0, -1), SAME, "into glass");
    cr_assert(whitted_refract(vec3_make(0, 0, -1), up_normal, 1.5, &out));
    assert_colour(out, vec3_make(0, 0, -1), SAME, "out of glass");
}

Test(refract, thirty_degrees_into_glass_obeys_snell) {
    /* eta = 1/1.5, sin i = 0.5: sin t = 1/3; k = 1 - (4/9)(1/4) = 8/9, so the direction is
     * (1/3, 0, -sqrt(8)/3), unit length, bent towards the normal. */
    vec3 out;
    cr_assert(whitted_refract(incident(30), up_normal, 1.0 / 1.5, &out));
    assert_colour(out, vec3_make(1.0 / 3.0, 0, -sqrt(8.0) / 3.0), SAME, "direction");
    assert_number(vec3_length(out), 1.0, SAME, "length");
    assert_number(out.x / vec3_length(out), (1.0 / 1.5) * 0.5, SAME, "sin t = eta sin i");
}

Test(refract, total_internal_reflection_starts_exactly_at_the_critical_angle) {
    /* Glass to air, eta = 1.5: critical angle asin(1/1.5) = 41.81 degrees. 1e-9 radians above it k < 0
     * (false, out untouched); 1e-9 below it k is about 2e-9 > 0 and the ray leaves almost grazing
     * (sin t = 1.5 sin i, just under 1). */
    double critical = asin(1.0 / 1.5) * 180.0 / M_PI, nudge = 1e-9 * 180.0 / M_PI;
    vec3 out = vec3_make(7, 7, 7);
    cr_assert(!whitted_refract(incident(critical + nudge), up_normal, 1.5, &out));
    assert_colour(out, grey(7), EXACT, "left alone");
    cr_assert(whitted_refract(incident(critical - nudge), up_normal, 1.5, &out));
    assert_number(out.x, 1.5 * sin(asin(1.0 / 1.5) - 1e-9), SAME, "sin t");
    cr_assert(out.z < 0.0 && out.z > -1e-4, "nearly grazing, got z = %g", out.z);
    assert_number(vec3_length(out), 1.0, SAME, "length");
}

/* ---- the Whitted tracer (chapter 8) ------------------------------------------------------------ */

/* Traces the ray from origin along direction in the scene `lines` and returns the colour; *counted
 * gets the counters it added. */
__attribute__((format(printf, 4, 5))) static vec3 trace_in(vec3 origin, vec3 direction, struct stats *counted,
                                                           const char *lines, ...) {
    struct fixture f;
    va_list args;
    va_start(args, lines);
    build_from(&f, lines, args);
    va_end(args);
    ray r = ray_along(origin, direction);
    struct stats before = stats_thread;
    vec3 colour = whitted_trace(&f.world, &r);
    counted->reflected_rays = stats_thread.reflected_rays - before.reflected_rays;
    counted->refracted_rays = stats_thread.refracted_rays - before.refracted_rays;
    counted->shadow_rays = stats_thread.shadow_rays - before.shadow_rays;
    counted->plane_tests = stats_thread.plane_tests - before.plane_tests;
    counted->sphere_tests = stats_thread.sphere_tests - before.sphere_tests;
    release(&f);
    return colour;
}

static const vec3 eye = {0, 0, 0}, down_z = {0, 0, -1};

/* Two facing mirrors, z = -5 (red, ambient 0.5) and z = 5 (green, ambient 0.25), both reflection 0.5,
 * no light, white background, seen from the origin along -z. */
static vec3 between_mirrors(int max_depth, struct stats *counted) {
    return trace_in(
        eye, down_z, counted,
        "max_depth %d\nbackground 1 1 1\n"
        "material red colour 1 0 0 ambient 0.5 diffuse 0 reflection 0.5\n"
        "material green colour 0 1 0 ambient 0.25 diffuse 0 reflection 0.5\n"
        "plane normal 0 0 1 distance -5 material red\nplane normal 0 0 -1 distance -5 material green\n",
        max_depth);
}

Test(whitted, max_depth_limits_the_bounces_between_two_mirrors) {
    /* Local colours: red 0.5 (1, 0, 0) = (0.5, 0, 0), green 0.25 (0, 1, 0) = (0, 0.25, 0).
     * max_depth 1: red only, the reflected ray is black: (0.5, 0, 0).
     * max_depth 2: + 0.5 green = (0.5, 0.125, 0).
     * max_depth 3: + 0.5 * 0.5 red = (0.625, 0.125, 0). All exact in binary. Each traced ray tests both
     * planes (2 plane tests per level); the ray past the limit is neither intersected nor counted, so
     * max_depth - 1 reflected rays. */
    struct stats counted;
    assert_colour(between_mirrors(1, &counted), vec3_make(0.5, 0, 0), EXACT, "max_depth 1");
    cr_assert_eq(counted.plane_tests, 2);
    cr_assert_eq(counted.reflected_rays, 0);
    assert_colour(between_mirrors(2, &counted), vec3_make(0.5, 0.125, 0), EXACT, "max_depth 2");
    cr_assert_eq(counted.plane_tests, 4);
    cr_assert_eq(counted.reflected_rays, 1);
    assert_colour(between_mirrors(3, &counted), vec3_make(0.625, 0.125, 0), EXACT, "max_depth 3");
    cr_assert_eq(counted.plane_tests, 6);
    cr_assert_eq(counted.reflected_rays, 2);
    cr_assert_eq(counted.refracted_rays, 0);
}

/* A perfect mirror z = -5 with no local colour under a white background, seen along -z. */
static vec3 off_a_perfect_mirror(int max_depth) {
    struct stats counted;
    return trace_in(eye, down_z, &counted,
                    "max_depth %d\nbackground 1 1 1\nmaterial mirror ambient 0 diffuse 0 reflection 1\n"
                    "plane normal 0 0 1 distance -5 material mirror\n",
                    max_depth);
}

Test(whitted, ray_past_max_depth_is_black_not_the_background) {
    /* The reflected ray (level 2) sees only the background, 1 * (1, 1, 1), when max_depth is 2, and is
     * black when max_depth is 1. */
    assert_colour(off_a_perfect_mirror(1), grey(0), EXACT, "max_depth 1");
    assert_colour(off_a_perfect_mirror(2), grey(1), EXACT, "max_depth 2");
}

/* Glass (transmit 1, ior 1.5, reflection 0.5, no local colour) filling y <= 0 around the ray, with an
 * opaque plane y = -2 inside it that shows only its ambient colour K = (0.2, 0.4, 0.6), under a
 * background B = (1, 1, 1); the ray starts inside the glass at (0, -1, 0), `degrees` from the face
 * y = 0's normal. */
static vec3 from_inside_glass(double degrees, struct stats *counted) {
    double a = degrees * M_PI / 180.0;
    return trace_in(
        vec3_make(0, -1, 0), vec3_make(sin(a), cos(a), 0), counted, "%s",
        "background 1 1 1\nmaterial glass ambient 0 diffuse 0 transmit 1 ior 1.5 reflection 0.5\n"
        "material floor colour 0.2 0.4 0.6 ambient 1 diffuse 0\n"
        "box min -10 -10 -10 max 10 0 10 material glass\nplane normal 0 1 0 distance -2 material floor\n");
}

Test(whitted, total_internal_reflection_takes_the_mirror_ray_at_weight_one_instead_of_reflection) {
    /* 60 degrees from the normal is past the critical angle 41.8: no refracted ray; the mirror ray
     * (sin 60, -cos 60, 0) from (sqrt 3, 0, 0) hits the floor at y = -2 and brings back K at weight 1.
     * The reflection 0.5 term is skipped: K, not 1.5 K. One reflected ray, no refracted ray. */
    struct stats counted;
    assert_colour(from_inside_glass(60, &counted), vec3_make(0.2, 0.4, 0.6), SAME, "colour");
    cr_assert_eq(counted.reflected_rays, 1);
    cr_assert_eq(counted.refracted_rays, 0);
}

Test(whitted, below_the_critical_angle_light_refracts_out_and_reflection_adds_on_top) {
    /* At 30 degrees the ray leaves the glass upwards into the background: 1 * B; the reflection term
     * adds 0.5 * K from the floor: (1.1, 1.2, 1.3). One refracted and one reflected ray. */
    struct stats counted;
    assert_colour(from_inside_glass(30, &counted), vec3_make(1.1, 1.2, 1.3), SAME, "colour");
    cr_assert_eq(counted.reflected_rays, 1);
    cr_assert_eq(counted.refracted_rays, 1);
}

/* A transparent sphere (transmit 1, no local colour) of ior `ior` at (0, 0, -5), background
 * (0.25, 0.5, 0.75), max_depth `depth`, seen through its centre. */
static vec3 through_clear_sphere(int depth, const char *ior, struct stats *counted) {
    return trace_in(eye, down_z, counted,
                    "max_depth %d\nbackground 0.25 0.5 0.75\nmaterial clear ambient 0 diffuse 0 transmit 1 ior %s\n"
                    "sphere centre 0 0 -5 radius 1 material clear\n",
                    depth, ior);
}

Test(whitted, ior_exactly_one_passes_straight_through_without_using_a_level) {
    /* max_depth 2. With ior 1 both crossings stay at level 1 and reach the background: 1 * 1 * B. Two
     * refracted rays and three sphere tests (camera ray, inside, out); had each crossing used a level,
     * the second would be level 3 > max_depth, black. With ior 1.5 the first refracted ray is level 2
     * and the one leaving the sphere level 3: black, neither intersected nor counted. */
    struct stats counted;
    assert_colour(through_clear_sphere(2, "1", &counted), vec3_make(0.25, 0.5, 0.75), EXACT, "ior 1");
    cr_assert_eq(counted.refracted_rays, 2);
    cr_assert_eq(counted.sphere_tests, 3);
    assert_colour(through_clear_sphere(2, "1.5", &counted), grey(0), EXACT, "ior 1.5");
    cr_assert_eq(counted.sphere_tests, 2);
    cr_assert_eq(counted.refracted_rays, 1);
}

Test(whitted, at_the_last_level_a_crossing_is_not_made) {
    /* max_depth 1: the camera ray is at the last level, so its crossing into the ior 1 sphere is not
     * made (POV-Ray tests the level before every ray, a crossing's too): black, one sphere test, no
     * refracted ray. ior 1.5 likewise, its refracted ray being level 2. */
    struct stats counted;
    assert_colour(through_clear_sphere(1, "1", &counted), grey(0), EXACT, "ior 1");
    cr_assert_eq(counted.sphere_tests, 1);
    cr_assert_eq(counted.refracted_rays, 0);
    assert_colour(through_clear_sphere(1, "1.5", &counted), grey(0), EXACT, "ior 1.5");
    cr_assert_eq(counted.sphere_tests, 1);
    cr_assert_eq(counted.refracted_rays, 0);
}

Test(whitted, refracted_light_is_weighted_by_colour_filter_plus_transmit_and_local_by_opacity) {
    /* Sphere of colour C = (1, 0.5, 0), filter 0.5, transmit 0.25, ambient 0.4, ior 1, white background.
     * Opacity 0.25: local = 0.4 * 0.25 * C = (0.1, 0.05, 0) at both surfaces. Weight w = C F + T =
     * (0.75, 0.5, 0.25). Seen: local + w (local + w B):
     * x 0.1 + 0.75 (0.1 + 0.75) = 0.7375, y 0.05 + 0.5 (0.05 + 0.5) = 0.325, z 0.25 * 0.25 = 0.0625. */
    struct stats counted;
    vec3 colour = trace_in(eye, down_z, &counted,
                           "background 1 1 1\nmaterial tint colour 1 0.5 0 ambient 0.4 diffuse 0 filter 0.5 "
                           "transmit 0.25 ior 1\nsphere centre 0 0 -5 radius 1 material tint\n");
    assert_colour(colour, vec3_make(0.7375, 0.325, 0.0625), SAME, "colour");
    cr_assert_eq(counted.refracted_rays, 2);
    cr_assert_eq(counted.reflected_rays, 0);
}

Test(whitted, local_light_is_shadowed_by_filtered_shadow_rays) {
    /* From (0, 2, 0) straight down onto a white floor y = 0 (diffuse 1, ambient 0); the light at
     * (0, 10, 0) shines through a clear sphere (transmit 0.9) at (0, 5, 0): N.L = 1, S = 0.81, so 0.81.
     * One shadow ray, no secondary ray. */
    struct stats counted;
    vec3 colour =
        trace_in(vec3_make(0, 2, 0), vec3_make(0, -1, 0), &counted,
                 "light position 0 10 0\nmaterial floor ambient 0 diffuse 1\n"
                 "material glass ambient 0 diffuse 0 transmit 0.9\n"
                 "plane normal 0 1 0 distance 0 material floor\nsphere centre 0 5 0 radius 1 material glass\n");
    assert_colour(colour, grey(0.81), SAME, "colour");
    cr_assert_eq(counted.shadow_rays, 1);
    cr_assert_eq(counted.reflected_rays + counted.refracted_rays, 0);
}

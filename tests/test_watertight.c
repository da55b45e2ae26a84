/* test_watertight.c: no ray slips between the triangles of a closed mesh (chapter 3's watertight
 * triangle test), while Moller-Trumbore, on the very same rays, lets some through.
 *
 * The meshes (tests/support/closed_mesh.c) share their vertices: a cube whose faces are 64 x 64 grids of
 * squares split along a diagonal (49,152 triangles), and an icosphere subdivided five times (20,480).
 * The views look from inside, so every ray must hit the mesh: the cube from its centre straight at a
 * face (a sixteenth of the pixels aim exactly at the face's diagonal edges) and straight at one of its
 * edges, the icosphere from a point off its centre, plus rays aimed at every edge of the icosphere. The light is outside, so every shadow
 * ray from a point inside must be blocked.
 *
 * Three levels: chapter 3's brute-force loop on rays aimed exactly at diagonal edges; whole 1024 x 1024
 * pictures traced with the kd-tree in this process, camera rays and shadow rays; and the programs of
 * chapters 9 and 10 rendering the scene with a red background, beside chapter 10 built with
 * Moller-Trumbore (tests/mutants/moller-trumbore.patch), which must show red pixels, so the check is
 * seen to catch a leak, and beside POV-Ray, which shows none either. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "closed_mesh.h"
#include "hit.h"
#include "image.h"
#include "image_test_support.h"
#include "kdtree.h"
#include "mesh.h"
#include "speck_triangle.h"
#include "ray.h"
#include "triangle.h"

#define CUBE_GRID 64
#define ICOSPHERE_SUBDIVISIONS 5
#define VIEW_SIZE 1024
/* The edge view has an odd size, so that its middle column and row aim exactly at the cube's edge and
 * at the vertex in the middle of it. */
#define EDGE_VIEW_SIZE 1023
/* In the face view, pixel (i, j) aims at the line x - y = (j - i) / 512 of the face z = 1, and the
 * diagonal edges lie on the lines x - y = k / 32: every pixel with i - j a multiple of EDGE_PERIOD aims
 * exactly at a shared edge. Chapter 3's loop is tried on those of the first EDGE_ROWS rows (4,096 rays;
 * Moller-Trumbore lets 5 of them through). */
#define EDGE_PERIOD 16
#define EDGE_ROWS 64
#define AIMS_PER_EDGE 8 /* rays through points of each icosphere edge, its first corner included */
/* The close-up of the face view in docs/03-triangle.md: 4 camera rays and 7 shadow rays leak there
 * with Moller-Trumbore. */
#define CROP_LEFT 96
#define CROP_TOP 160
#define CROP_SIZE 128
#define CROP_ZOOM 4
#define WATERTIGHT_OUT TEST_OUT "/watertight"

/* Shadow rays are checked only where the light is at least this cosine inside the face they start on
 * (about 6 degrees, twice the angle between neighbouring faces of the icosphere): there the ray crosses
 * the inside for a chord of 0.2 or more, far beyond SHADOW_T_MIN, before it reaches the far side. */
#define SHADOW_MIN_COSINE 0.1

/* Outside the cube, behind the camera of the face view: the shadow rays cross the face z = -1, and
 * some meet its diagonal edges exactly (Moller-Trumbore lets 30 of them through). */
static const vec3 cube_light = {0, 0, -3};
static const vec3 icosphere_light = {1.7, 2.3, -1.9};

struct view {
    const char *name;
    vec3 eye, target;
    double fov;
    int size;
};

static const struct view cube_face = {"cube-face", {0, 0, 0}, {0, 0, 1}, 90, VIEW_SIZE};
static const struct view cube_edge = {"cube-edge", {0, 0, 0}, {1, 0, 1}, 90, EDGE_VIEW_SIZE};
static const struct view icosphere_inside = {"icosphere", {0.31, -0.22, 0.17}, {-0.4, 0.35, 0.9}, 100, VIEW_SIZE};

static struct camera view_camera(const struct view *v) {
    struct camera cam;
    char err[128];
    cr_assert(camera_init(&cam, v->eye, v->target, vec3_make(0, 1, 0), v->fov, v->size, v->size, err, sizeof err),
              "%s", err);
    return cam;
}

static struct mesh cube_mesh(void) {
    struct mesh m;
    cr_assert(closed_mesh_cube(CUBE_GRID, &m));
    return m;
}

static struct mesh icosphere_mesh(void) {
    struct mesh m;
    cr_assert(closed_mesh_icosphere(ICOSPHERE_SUBDIVISIONS, &m));
    return m;
}

/* ---- the meshes themselves ---------------------------------------------------------------------- */

static int compare(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Every edge of a closed mesh with consistent winding is used exactly twice, once in each direction. */
static void assert_closed_and_consistently_wound(const struct mesh *m) {
    size_t edges = 3 * m->face_count;
    uint64_t *directed = malloc(edges * sizeof *directed);
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++)
            directed[3 * f + k] = (uint64_t)m->faces[f].v[k] << 32 | m->faces[f].v[(k + 1) % 3];
    qsort(directed, edges, sizeof *directed, compare);
    for (size_t e = 0; e < edges; e++) {
        cr_assert(e == 0 || directed[e] != directed[e - 1], "a directed edge is used twice");
        uint64_t reverse = directed[e] << 32 | directed[e] >> 32;
        cr_assert_not_null(bsearch(&reverse, directed, edges, sizeof *directed, compare),
                           "edge %u-%u has no twin: the mesh is open", (unsigned)(directed[e] >> 32),
                           (unsigned)directed[e]);
    }
    free(directed);
}

Test(closed_mesh, cube_and_icosphere_are_closed_and_have_the_expected_counts) {
    struct mesh cube = cube_mesh(), sphere = icosphere_mesh();
    cr_assert_eq(cube.face_count, 12u * CUBE_GRID * CUBE_GRID);
    cr_assert_eq(cube.vertex_count, 6u * CUBE_GRID * CUBE_GRID + 2);
    cr_assert_eq(sphere.face_count, 20u << (2 * ICOSPHERE_SUBDIVISIONS));
    cr_assert_eq(sphere.vertex_count, sphere.face_count / 2 + 2);
    assert_closed_and_consistently_wound(&cube);
    assert_closed_and_consistently_wound(&sphere);
    for (size_t k = 0; k < sphere.vertex_count; k++)
        cr_assert_float_eq(vec3_length(sphere.vertices[k]), 1.0, 1e-15);
    /* Wound counter-clockwise seen from outside: every normal points away from the centre. */
    const struct mesh *both[2] = {&cube, &sphere};
    for (int which = 0; which < 2; which++)
        for (size_t f = 0; f < both[which]->face_count; f++) {
            const uint32_t *c = both[which]->faces[f].v;
            const vec3 *v = both[which]->vertices;
            cr_assert_gt(vec3_dot(triangle_normal(v[c[0]], v[c[1]], v[c[2]]), v[c[0]]), 0.0, "face %zu", f);
        }
    mesh_free(&cube);
    mesh_free(&sphere);
}

/* ---- chapter 3's loop on the rays of the picture's diagonal -------------------------------------- */

/* The brute-force loop of triangle_mesh_closest with Moller-Trumbore: whether r hits any face. */
static bool mt_hits_mesh(const struct mesh *m, const ray *r, double t_min, double t_max) {
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *c = m->faces[f].v;
        double t, u, v;
        if (triangle_crossing_mt(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]], r, &t, &u, &v) &&
            t > t_min && t < t_max)
            return true;
    }
    return false;
}

Test(watertight, chapter_3s_loop_has_no_leak_where_moller_trumbore_has_some, .timeout = 240) {
    struct mesh m = cube_mesh();
    struct camera cam = view_camera(&cube_face);
    int leaks = 0, mt_leaks = 0, rays = 0;
    for (int j = 0; j < EDGE_ROWS; j++) {
        for (int i = j % EDGE_PERIOD; i < VIEW_SIZE; i += EDGE_PERIOD) {
            ray r = camera_ray(&cam, i, j);
            struct hit h = hit_nothing(INFINITY);
            leaks += !triangle_mesh_closest(&m, 0, &r, RAY_T_MIN, &h);
            mt_leaks += !mt_hits_mesh(&m, &r, RAY_T_MIN, INFINITY);
            rays++;
        }
    }
    cr_log_info("%d rays at diagonal edges: Moller-Trumbore lets %d through", rays, mt_leaks);
    cr_assert_eq(leaks, 0, "%d of %d rays slipped through the cube", leaks, rays);
    cr_assert_gt(mt_leaks, 0, "Moller-Trumbore should leak here, or this test proves nothing");
    mesh_free(&m);
}

/* ---- whole pictures, with the kd-tree ------------------------------------------------------------ */

/* For each vertex, the faces that use it (compressed rows). */
struct vertex_faces {
    size_t *first; /* vertex_count + 1 entries */
    uint32_t *faces;
};

static struct vertex_faces vertex_faces_make(const struct mesh *m) {
    struct vertex_faces a = {calloc(m->vertex_count + 1, sizeof(size_t)), malloc(3 * m->face_count * sizeof(uint32_t))};
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++)
            a.first[m->faces[f].v[k] + 1]++;
    for (size_t v = 0; v < m->vertex_count; v++)
        a.first[v + 1] += a.first[v];
    size_t *fill = malloc(m->vertex_count * sizeof *fill);
    memcpy(fill, a.first, m->vertex_count * sizeof *fill);
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++)
            a.faces[fill[m->faces[f].v[k]]++] = (uint32_t)f;
    free(fill);
    return a;
}

/* Whether Moller-Trumbore finds r crossing the mesh in (t_min, t_max), given the face the watertight
 * test found nearest. Only the faces around that face's corners are tested: its rounding errors are
 * about 1e-16 of the distance, and every other face is at least a grid cell (or a subdivided
 * triangle) away from where the ray crosses. */
static bool mt_hits_near(const struct mesh *m, const struct vertex_faces *around, uint32_t face, const ray *r,
                         double t_min, double t_max) {
    for (int k = 0; k < 3; k++) {
        uint32_t v = m->faces[face].v[k];
        for (size_t n = around->first[v]; n < around->first[v + 1]; n++) {
            const uint32_t *c = m->faces[around->faces[n]].v;
            double t, u, w;
            if (triangle_crossing_mt(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]], r, &t, &u, &w) &&
                t > t_min && t < t_max)
                return true;
        }
    }
    return false;
}

/* The shadow ray from p towards `light`, and the window in which a blocker counts (chapter 7). */
static ray shadow_ray(vec3 p, vec3 light, double *t_max) {
    vec3 to_light = vec3_sub(light, p);
    double distance = vec3_length(to_light);
    *t_max = distance - SHADOW_T_MIN;
    return (ray){p, vec3_scale(to_light, 1.0 / distance)};
}

struct leaks {
    long camera, shadow;       /* the watertight test, through the kd-tree */
    long mt_camera, mt_shadow; /* Moller-Trumbore on the same rays */
};

static struct leaks trace_view(const struct mesh *m, const struct view *v, vec3 light) {
    struct kdtree *tree = kdtree_build(m, KD_SPLIT_SAH);
    cr_assert_not_null(tree);
    struct vertex_faces around = vertex_faces_make(m);
    struct camera cam = view_camera(v);
    struct leaks l = {0, 0, 0, 0};
    for (int j = 0; j < v->size; j++) {
        for (int i = 0; i < v->size; i++) {
            ray r = camera_ray(&cam, i, j);
            double t, t_max;
            uint32_t face;
            if (!kdtree_closest(tree, &r, RAY_T_MIN, INFINITY, &t, &face)) {
                l.camera++;
                l.mt_camera++;
                continue;
            }
            l.mt_camera += !mt_hits_near(m, &around, face, &r, RAY_T_MIN, INFINITY);
            /* Only points whose face turns its inner side to the light, by more than a grazing angle:
             * from the others the shadow ray leaves through the face it starts on, or a neighbour within
             * SHADOW_T_MIN, and rightly finds no blocker (the shading sees the light behind the surface). */
            ray s = shadow_ray(ray_at(r, t), light, &t_max);
            const uint32_t *c = m->faces[face].v;
            vec3 outward = triangle_normal(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]]);
            if (vec3_dot(outward, s.direction) > -SHADOW_MIN_COSINE)
                continue;
            if (!kdtree_closest(tree, &s, SHADOW_T_MIN, t_max, &t, &face)) {
                l.shadow++;
                l.mt_shadow++;
                continue;
            }
            l.mt_shadow += !mt_hits_near(m, &around, face, &s, SHADOW_T_MIN, t_max);
        }
    }
    free(around.first);
    free(around.faces);
    kdtree_free(tree);
    cr_log_info("%s: watertight %ld camera and %ld shadow leaks; Moller-Trumbore %ld and %ld", v->name, l.camera,
                l.shadow, l.mt_camera, l.mt_shadow);
    return l;
}

/* Traces view v of mesh m (then freed) and asserts that no ray leaks; when `mt_leaks_too`, also that
 * Moller-Trumbore does leak there, camera and shadow rays both, so the view is seen to catch a leak. */
static void check_view(struct mesh m, const struct view *v, vec3 light, bool mt_leaks_too) {
    struct leaks l = trace_view(&m, v, light);
    cr_assert_eq(l.camera, 0, "%s: %ld camera rays slipped through", v->name, l.camera);
    cr_assert_eq(l.shadow, 0, "%s: %ld shadow rays slipped through", v->name, l.shadow);
    if (mt_leaks_too) {
        cr_assert_gt(l.mt_camera, 0, "%s: Moller-Trumbore should leak camera rays here", v->name);
        cr_assert_gt(l.mt_shadow, 0, "%s: Moller-Trumbore should leak shadow rays here", v->name);
    }
    mesh_free(&m);
}

/* Moller-Trumbore lets 63 camera rays and 30 shadow rays through here. */
Test(watertight, cube_seen_from_its_centre_straight_at_a_face_has_no_leak, .timeout = 240) {
    check_view(cube_mesh(), &cube_face, cube_light, true);
}

/* Moller-Trumbore lets 200 camera rays and 48 shadow rays through here. */
Test(watertight, cube_seen_from_its_centre_straight_at_an_edge_has_no_leak, .timeout = 240) {
    check_view(cube_mesh(), &cube_edge, cube_light, true);
}

/* Moller-Trumbore happens to let no pixel's ray through here: the next test aims at the edges. */
Test(watertight, icosphere_seen_from_off_its_centre_has_no_leak, .timeout = 240) {
    check_view(icosphere_mesh(), &icosphere_inside, icosphere_light, false);
}

/* Whether the ray from `from` through p, looking for hits in (t_min, t_max), misses the mesh (1) or
 * not (0), with the watertight test through the kd-tree; adds 1 to *mt_leaks when Moller-Trumbore
 * misses it. */
static int ray_leaks(const struct mesh *m, const struct kdtree *tree, const struct vertex_faces *around, vec3 from,
                     vec3 p, double t_min, double t_max, long *mt_leaks) {
    ray r = {from, vec3_normalize(vec3_sub(p, from))};
    double t;
    uint32_t face;
    if (!kdtree_closest(tree, &r, t_min, t_max, &t, &face)) {
        (*mt_leaks)++;
        return 1;
    }
    *mt_leaks += !mt_hits_near(m, around, face, &r, t_min, t_max);
    return 0;
}

/* Random pixels seldom meet an icosphere's edge exactly; these rays do: from the eye of the icosphere
 * view through AIMS_PER_EDGE evenly spaced points of every edge, the first of them its corner. */
Test(watertight, icosphere_rays_aimed_at_every_edge_and_vertex_do_not_leak, .timeout = 240) {
    struct mesh m = icosphere_mesh();
    struct kdtree *tree = kdtree_build(&m, KD_SPLIT_SAH);
    struct vertex_faces around = vertex_faces_make(&m);
    vec3 eye = icosphere_inside.eye;
    long camera_leaks = 0, shadow_leaks = 0, mt_camera_leaks = 0, mt_shadow_leaks = 0, rays = 0;
    for (size_t f = 0; f < m.face_count; f++) {
        for (int k = 0; k < 3; k++) {
            vec3 a = m.vertices[m.faces[f].v[k]], b = m.vertices[m.faces[f].v[(k + 1) % 3]];
            for (int step = 0; step < AIMS_PER_EDGE; step++, rays++) {
                /* A camera ray, and a shadow ray towards a light as far outside the mesh as p is from
                 * the eye: both from the eye, through p. */
                vec3 p = vec3_add_scaled(a, vec3_sub(b, a), (double)step / AIMS_PER_EDGE);
                double reach = 2.0 * vec3_length(vec3_sub(p, eye));
                camera_leaks += ray_leaks(&m, tree, &around, eye, p, RAY_T_MIN, INFINITY, &mt_camera_leaks);
                shadow_leaks += ray_leaks(&m, tree, &around, eye, p, SHADOW_T_MIN, reach - SHADOW_T_MIN, &mt_shadow_leaks);
            }
        }
    }
    cr_log_info("%ld camera and shadow rays at edges and corners: Moller-Trumbore lets %ld and %ld through", rays,
                mt_camera_leaks, mt_shadow_leaks);
    cr_assert_eq(camera_leaks, 0, "%ld of %ld camera rays slipped through", camera_leaks, rays);
    cr_assert_eq(shadow_leaks, 0, "%ld of %ld shadow rays slipped through", shadow_leaks, rays);
    cr_assert_gt(mt_camera_leaks, 0, "Moller-Trumbore should leak camera rays here");
    cr_assert_gt(mt_shadow_leaks, 0, "Moller-Trumbore should leak shadow rays here");
    free(around.first);
    free(around.faces);
    kdtree_free(tree);
    mesh_free(&m);
}

/* ---- the chapter programs, end to end ------------------------------------------------------------ */

/* Writes the cube into WATERTIGHT_OUT and a scene seeing it from view v, with a red background and a
 * white light at `light`; both file names start with `who` (tests running at once write their own).
 * The scene's path goes into `scene`. */
static void write_cube_scene(const char *who, const struct view *v, vec3 light, char *scene, size_t size) {
    cr_assert_eq(system("mkdir -p " WATERTIGHT_OUT), 0);
    struct mesh m = cube_mesh();
    char err[256];
    char ply[256];
    snprintf(ply, sizeof ply, WATERTIGHT_OUT "/%s-cube-64.ply", who);
    cr_assert(closed_mesh_write_ply(&m, ply, err, sizeof err), "%s", err);
    mesh_free(&m);
    snprintf(scene, size, WATERTIGHT_OUT "/%s-%s.scene", who, v->name);
    FILE *f = fopen(scene, "w");
    cr_assert_not_null(f);
    fprintf(f, "# The tessellated cube seen from inside (tests/test_watertight.c). A red pixel is a camera ray\n"
               "# that slipped through, a lit one a shadow ray that did.\n"
               "camera eye %g %g %g  target %g %g %g  fov %g\nimage %d %d\nbackground 1 0 0\n"
               "light position %g %g %g  colour 1 1 1\n"
               "material wall  colour 0.3 0.6 0.9  ambient 0.3 diffuse 0.7\n"
               "mesh %s-cube-64.ply  material wall\n",
            v->eye.x, v->eye.y, v->eye.z, v->target.x, v->target.y, v->target.z, v->fov, v->size, v->size, light.x,
            light.y, light.z, who);
    cr_assert_eq(fclose(f), 0);
}

struct picture_leaks {
    long red; /* the background: camera rays that missed the cube */
    long lit; /* brighter than the shadowed wall: shadow rays that missed it */
};

/* Counts the red pixels of the picture at `png`, and the others that differ from the shadowed wall.
 * Every point of the inside of the cube is in shadow: the light is outside, and each face turns its
 * inner side to it, so the wall is one flat colour. */
static struct picture_leaks count_picture_leaks(const char *png) {
    int width, height;
    char err[256];
    uint8_t *rgb = image_read_rgb(png, &width, &height, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    const uint8_t wall[3] = {image_quantize(0.3 * 0.3), image_quantize(0.3 * 0.6), image_quantize(0.3 * 0.9)};
    struct picture_leaks l = {0, 0};
    for (long p = 0; p < (long)width * height; p++) {
        const uint8_t *c = &rgb[3 * p];
        if (c[0] == 255 && c[1] == 0 && c[2] == 0)
            l.red++;
        else if (c[0] != wall[0] || c[1] != wall[1] || c[2] != wall[2])
            l.lit++;
    }
    free(rgb);
    return l;
}

/* Writes the square of CROP_SIZE pixels at (CROP_LEFT, CROP_TOP) of the picture at `png`, each pixel
 * drawn as a CROP_ZOOM x CROP_ZOOM block, to `out`: the close-up that docs/03-triangle.md shows. */
static void write_close_up(const char *png, const char *out) {
    int width, height;
    char err[256];
    uint8_t *rgb = image_read_rgb(png, &width, &height, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    cr_assert(CROP_LEFT + CROP_SIZE <= width && CROP_TOP + CROP_SIZE <= height);
    int side = CROP_SIZE * CROP_ZOOM;
    uint8_t *close_up = malloc(3 * (size_t)side * side);
    for (int y = 0; y < side; y++)
        for (int x = 0; x < side; x++)
            memcpy(&close_up[3 * ((size_t)y * side + x)],
                   &rgb[3 * ((size_t)(CROP_TOP + y / CROP_ZOOM) * width + CROP_LEFT + x / CROP_ZOOM)], 3);
    cr_assert(image_write_png_bytes(close_up, side, side, out, err, sizeof err), "%s", err);
    free(close_up);
    free(rgb);
}

static struct picture_leaks render_leaks(const char *program, const char *scene, const char *tag,
                                         const char *extra) {
    char png[256];
    snprintf(png, sizeof png, WATERTIGHT_OUT "/%s.png", tag);
    cr_assert_eq(render_with(program, scene, png, extra), 0, "%s %s failed on %s", program, extra, scene);
    struct picture_leaks l = count_picture_leaks(png);
    cr_log_info("%s %s: %ld red and %ld lit pixels", program, extra, l.red, l.lit);
    return l;
}

Test(watertight, chapters_9_and_10_draw_the_cube_from_inside_without_a_leak, .timeout = 300) {
    const struct view *views[2] = {&cube_face, &cube_edge};
    for (int k = 0; k < 2; k++) {
        char scene[256], tag[64];
        write_cube_scene("chapters", views[k], cube_light, scene, sizeof scene);
        for (int n = 9; n <= 10; n++) {
            snprintf(tag, sizeof tag, "%s-chapter-%d", views[k]->name, n);
            struct picture_leaks l = render_leaks(chapter_program(n), scene, tag, "");
            cr_assert_eq(l.red, 0, "chapter %d, %s: %ld camera rays slipped through", n, views[k]->name, l.red);
            cr_assert_eq(l.lit, 0, "chapter %d, %s: %ld shadow rays slipped through", n, views[k]->name, l.lit);
        }
        if (views[k] == &cube_face)
            write_close_up(WATERTIGHT_OUT "/cube-face-chapter-10.png", WATERTIGHT_OUT "/close-up-watertight.png");
    }
}

Test(watertight, chapter_10_with_moller_trumbore_draws_the_leak, .timeout = 300) {
    char scene[256];
    write_cube_scene("mutant", &cube_face, cube_light, scene, sizeof scene);
    const char *structures[2] = {"--accel bvh", "--accel kdtree"};
    for (int k = 0; k < 2; k++) {
        char tag[64];
        snprintf(tag, sizeof tag, "cube-face-moller-trumbore-%s", structures[k] + 8);
        struct picture_leaks l = render_leaks(mutant_program("moller-trumbore"), scene, tag, structures[k]);
        if (k == 0)
            write_close_up(WATERTIGHT_OUT "/cube-face-moller-trumbore-bvh.png",
                           WATERTIGHT_OUT "/close-up-moller-trumbore.png");
        cr_assert_gt(l.red, 0, "%s: Moller-Trumbore let no camera ray through: the check above proves nothing",
                     structures[k]);
        cr_assert_gt(l.lit, 0, "%s: Moller-Trumbore let no shadow ray through: the check above proves nothing",
                     structures[k]);
    }
}

Test(watertight, povray_draws_the_cube_from_inside_without_a_leak_as_chapter_10_does, .timeout = 300) {
    char scene[256];
    const char *ours = WATERTIGHT_OUT "/povray-cube-face-chapter-10.png", *theirs = WATERTIGHT_OUT "/povray-cube-face.png";
    write_cube_scene("povray", &cube_face, cube_light, scene, sizeof scene);
    cr_assert_eq(render_chapter(10, scene, ours, ""), 0);
    cr_assert(render_povray(10, scene, theirs), "POV-Ray failed on the cube's twin");
    struct picture_leaks l = count_picture_leaks(theirs);
    cr_assert_eq(l.red, 0, "POV-Ray: %ld red pixels", l.red);
    cr_assert_eq(l.lit, 0, "POV-Ray: %ld lit pixels", l.lit);
    struct image_difference d = compare_png(ours, theirs);
    cr_assert_eq(d.max, 0, "chapter 10 and POV-Ray differ by up to %d levels", d.max);
}

/* The triangle of triangle/a_triangle_a_few_units_in_the_last_place_across_is_missed_by_a_ray_passing_far_from_it
 * (test_geometry.c), white on black, seen by chapter 3's brute-force loop from the origin of that test's
 * ray, 90 degrees wide: it is some 1e-17 across, no camera ray passes through it, and the picture is
 * black. With an edge function of 0 where its two products rounded alike, 153 of the pixels were lit. */
Test(watertight, a_triangle_a_unit_in_the_last_place_across_lights_no_pixel_of_chapter_3s_picture, .timeout = 60) {
    cr_assert_eq(system("mkdir -p " WATERTIGHT_OUT), 0);
    const char *scene = WATERTIGHT_OUT "/speck.scene", *png = WATERTIGHT_OUT "/speck.png";
    FILE *f = fopen(scene, "w");
    cr_assert_not_null(f);
    fprintf(f, "camera eye 0 0 0  target " SPECK_TEXT(SPECK_DIRECTION) "  fov 90\n"
               "image 200 200\nbackground 0 0 0\nlight position 0 0 0  colour 1 1 1\nmaterial white  colour 1 1 1\n"
               "triangle a " SPECK_TEXT(SPECK_A) "  b " SPECK_TEXT(SPECK_B) "  c " SPECK_TEXT(SPECK_C)
               "  material white\n");
    cr_assert_eq(fclose(f), 0);
    cr_assert_eq(render_chapter(3, scene, png, ""), 0);
    int width, height;
    char err[256];
    uint8_t *rgb = image_read_rgb(png, &width, &height, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    long lit = 0;
    for (long p = 0; p < 3L * width * height; p++)
        lit += rgb[p] != 0;
    free(rgb);
    cr_assert_eq(lit, 0, "%ld channels of the picture are not black", lit);
}

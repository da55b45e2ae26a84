/* render_check.c: a scene text through the whole renderer of chapter 10, every structure against the
 * brute-force loop (the renderer fuzzer's check; not part of any chapter).
 *
 * The fuzzer writes scene text, so what it can reach is whatever a scene file can ask for: any camera,
 * materials, lights, shapes, and meshes placed with any scale, rotation and translation. Mesh files
 * are not read (their readers have fuzzers of their own, and a fuzzer must not wander the file
 * system): each `mesh` directive gets one of the tiny meshes below, chosen by its file name, so the
 * fuzzer can still pick among them by changing the name. */
#include "render_check.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel.h"
#include "bvh.h"
#include "camera.h"
#include "kdtree.h"
#include "triangle.h"
#include "whitted.h"

/* Lights beyond this many are dropped: each light sends a shadow ray from every hit, and a shadow ray
 * crosses every shape, so a text of many lights and many shapes would cost lights x shapes per hit. */
#define RENDER_CHECK_MAX_LIGHTS 4

/* The colours of two worlds are compared to this relative tolerance, not exactly: a shadow ray through
 * glass multiplies the filters of the surfaces it crosses in the order the world reports them, and
 * the structures report them in their own order (world.h: "every crossing"), which can change the last
 * bits of a product. The nearest hits themselves must agree exactly. */
#define RENDER_CHECK_COLOUR_TOLERANCE 1e-9

/* ---- the tiny meshes -------------------------------------------------------------------------- */

struct tiny_mesh {
    const vec3 *vertices;
    size_t vertex_count;
    const struct mesh_face *faces;
    size_t face_count;
};

static const vec3 triangle_vertices[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
static const struct mesh_face triangle_faces[] = {{{0, 1, 2}}};

/* A unit square in z = 0, as two triangles sharing the diagonal. */
static const vec3 square_vertices[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
static const struct mesh_face square_faces[] = {{{0, 1, 2}}, {{0, 2, 3}}};

static const vec3 tetrahedron_vertices[] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
static const struct mesh_face tetrahedron_faces[] = {{{0, 1, 2}}, {{0, 3, 1}}, {{0, 2, 3}}, {{1, 3, 2}}};

static const vec3 octahedron_vertices[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const struct mesh_face octahedron_faces[] = {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}},
                                                    {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}};

/* What well-made meshes lack: a face with two equal corners, one with all three on a line, a needle
 * a million times longer than wide, the same face twice (ties exactly), and a face in an axis plane. */
static const vec3 awkward_vertices[] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1e-6, 0}, {0, 0, 1}, {1, 1, 1}};
static const struct mesh_face awkward_faces[] = {{{0, 0, 4}}, {{0, 1, 2}}, {{0, 2, 3}},
                                                 {{1, 4, 5}}, {{1, 4, 5}}, {{0, 1, 4}}};

#define TINY(name) {name##_vertices, sizeof name##_vertices / sizeof *name##_vertices, name##_faces, \
                    sizeof name##_faces / sizeof *name##_faces}
static const struct tiny_mesh tiny_meshes[] = {TINY(triangle), TINY(square), TINY(tetrahedron), TINY(octahedron),
                                               TINY(awkward)};
#define TINY_MESH_COUNT (sizeof tiny_meshes / sizeof *tiny_meshes)

/* Which tiny mesh a file name stands for: a hash of the name (FNV-1a), so that every name is one of
 * them and a mutation of the name can pick another. */
static const struct tiny_mesh *tiny_mesh_for(const char *path) {
    uint32_t hash = 2166136261u;
    for (const unsigned char *c = (const unsigned char *)path; *c != '\0'; c++)
        hash = (hash ^ *c) * 16777619u;
    return &tiny_meshes[hash % TINY_MESH_COUNT];
}

/* Gives every mesh directive of s its tiny mesh, placed by the directive's transform, as
 * scene_load_meshes does with the file. Returns false when memory runs out. */
static bool place_tiny_meshes(struct scene *s) {
    for (size_t k = 0; k < s->mesh_count; k++) {
        struct scene_mesh *sm = &s->meshes[k];
        const struct tiny_mesh *tiny = tiny_mesh_for(sm->path);
        sm->mesh.vertices = malloc(tiny->vertex_count * sizeof *sm->mesh.vertices);
        sm->mesh.faces = malloc(tiny->face_count * sizeof *sm->mesh.faces);
        if (sm->mesh.vertices == NULL || sm->mesh.faces == NULL)
            return false;
        memcpy(sm->mesh.vertices, tiny->vertices, tiny->vertex_count * sizeof *tiny->vertices);
        memcpy(sm->mesh.faces, tiny->faces, tiny->face_count * sizeof *tiny->faces);
        sm->mesh.vertex_count = tiny->vertex_count;
        sm->mesh.face_count = tiny->face_count;
        mesh_transform(&sm->mesh, sm->scale, sm->rotate, sm->translate);
    }
    return true;
}

/* ---- known defects ------------------------------------------------------------------------------
 *
 * Scenes that trigger a defect someone is fixing are recognised here and not rendered, so that the
 * fuzzer looks past them for new ones, and their saved inputs are skipped by the tests with the
 * defect's name. When a defect is fixed, delete its entry: its saved inputs then run in the tests. */

/* Coordinates beyond this are outside float range, or so close that a box's extent overflows it. */
#define KNOWN_FLOAT_RANGE (FLT_MAX / 4)

static bool beyond_float_range(vec3 p) {
    return !(fabs(p.x) <= KNOWN_FLOAT_RANGE && fabs(p.y) <= KNOWN_FLOAT_RANGE && fabs(p.z) <= KNOWN_FLOAT_RANGE);
}

/* The BVH bins triangles in float and crashes (bin index out of bounds) and the kd-tree can hang when
 * a triangle lies outside float range (`mesh ... scale 1e308`, `translate 1e39 0 0`). */
static bool has_triangles_beyond_float_range(const struct scene *s) {
    for (size_t k = 0; k < s->triangle_count; k++)
        if (beyond_float_range(s->triangles[k].a) || beyond_float_range(s->triangles[k].b) ||
            beyond_float_range(s->triangles[k].c))
            return true;
    for (size_t k = 0; k < s->mesh_count; k++)
        for (size_t v = 0; v < s->meshes[k].mesh.vertex_count; v++)
            if (beyond_float_range(s->meshes[k].mesh.vertices[v]))
                return true;
    return false;
}

static const struct known_defect {
    const char *name;
    bool (*triggered)(const struct scene *s);
} known_defects[] = {
    {"triangles outside float range crash the BVH build and hang the kd-tree (bvh.c, kdtree.c)",
     has_triangles_beyond_float_range},
};

/* Returns the known defect s would trigger, or NULL. */
static const struct known_defect *known_defect_of(const struct scene *s) {
    for (size_t k = 0; k < sizeof known_defects / sizeof *known_defects; k++)
        if (known_defects[k].triggered(s))
            return &known_defects[k];
    return NULL;
}

/* ---- checking --------------------------------------------------------------------------------- */

enum { WORLD_BRUTE, WORLD_KD_SEED, WORLD_KD_SAH, WORLD_BVH_MEDIAN, WORLD_BVH_SAH, WORLD_COUNT };
static const char *world_names[WORLD_COUNT] = {"brute force", "kd-tree (seed's rule)", "kd-tree (SAH)",
                                               "BVH (median)", "BVH (SAH)"};

struct checker {
    struct accel_world worlds[WORLD_COUNT];
    double *face_t; /* per face of the merged mesh: the brute-force t of the ray being checked, or NAN */
    unsigned char *reported; /* per face: times for_each_hit reported it */
    char *why;
    size_t why_size;
};

static bool broken(struct checker *c, const char *format, ...) __attribute__((format(printf, 2, 3)));
static bool broken(struct checker *c, const char *format, ...) {
    va_list args;
    va_start(args, format);
    vsnprintf(c->why, c->why_size, format, args);
    va_end(args);
    return false;
}

static bool count_hit(void *context, double t, uint32_t face) {
    struct checker *c = context;
    (void)t;
    if (c->reported[face] < UCHAR_MAX)
        c->reported[face]++;
    return true;
}

/* Checks the three queries of world `k`'s structure on ray r against the brute-force loop. */
static bool check_structure(struct checker *c, int k, const ray *r, int pixel) {
    const struct accel_world *w = &c->worlds[k];
    const struct mesh *m = &w->triangles;
    const double t_min = RAY_T_MIN, t_max = INFINITY;
    double best_t = INFINITY;
    uint32_t best_face = 0;
    bool any = false;
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *v = m->faces[f].v;
        double t, u, vv;
        c->face_t[f] = NAN;
        if (triangle_intersect(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]], r, t_min, t_max, &t, &u, &vv)) {
            c->face_t[f] = t;
            if (!any || t < best_t) {
                best_t = t;
                best_face = (uint32_t)f;
            }
            any = true;
        }
    }
    double t = NAN;
    uint32_t face = UINT32_MAX;
    bool found = w->accel.closest(w->structure, r, t_min, t_max, &t, &face);
    if (found != any || (any && (t != best_t || face != best_face)))
        return broken(c, "pixel %d: %s closest gives %s t=%.17g face %u, brute force %s t=%.17g face %u", pixel,
                      world_names[k], found ? "a hit" : "no hit", t, face, any ? "a hit" : "no hit", best_t, best_face);
    if (w->accel.occluded(w->structure, r, t_min, t_max) != any)
        return broken(c, "pixel %d: %s occluded says %s, brute force %s", pixel, world_names[k],
                      any ? "no" : "yes", any ? "yes" : "no");
    memset(c->reported, 0, m->face_count);
    w->accel.for_each_hit(w->structure, r, t_min, t_max, count_hit, c);
    for (size_t f = 0; f < m->face_count; f++)
        if (c->reported[f] != (isnan(c->face_t[f]) ? 0 : 1))
            return broken(c, "pixel %d: %s for_each_hit reports face %zu %u times, brute force %s", pixel,
                          world_names[k], f, c->reported[f], isnan(c->face_t[f]) ? "misses it" : "hits it once");
    return true;
}

static bool same_colour_channel(double a, double b) {
    if (isnan(a) || isnan(b))
        return isnan(a) && isnan(b);
    if (isinf(a) || isinf(b))
        return a == b;
    double scale = fmax(1.0, fmax(fabs(a), fabs(b)));
    return fabs(a - b) <= RENDER_CHECK_COLOUR_TOLERANCE * scale;
}

/* Checks one camera ray in every world. */
static bool check_ray(struct checker *c, const ray *r, int pixel) {
    struct hit brute = hit_nothing(INFINITY);
    bool brute_found = world_closest(&c->worlds[WORLD_BRUTE].world, r, RAY_T_MIN, &brute);
    if (brute_found && (!isfinite(brute.t) || !vec3_is_finite(brute.normal)))
        return broken(c, "pixel %d: brute force hit at t=%g with normal (%g %g %g)", pixel, brute.t, brute.normal.x,
                      brute.normal.y, brute.normal.z);
    vec3 brute_colour = whitted_trace(&c->worlds[WORLD_BRUTE].world, r);
    for (int k = WORLD_BRUTE + 1; k < WORLD_COUNT; k++) {
        if (!check_structure(c, k, r, pixel))
            return false;
        struct hit h = hit_nothing(INFINITY);
        bool found = world_closest(&c->worlds[k].world, r, RAY_T_MIN, &h);
        bool same = h.t == brute.t && h.material == brute.material && h.normal.x == brute.normal.x &&
                    h.normal.y == brute.normal.y && h.normal.z == brute.normal.z;
        if (found != brute_found || (found && !same))
            return broken(c, "pixel %d: %s nearest hit t=%.17g material %d, brute force t=%.17g material %d", pixel,
                          world_names[k], h.t, h.material, brute.t, brute.material);
        vec3 colour = whitted_trace(&c->worlds[k].world, r);
        if (!same_colour_channel(colour.x, brute_colour.x) || !same_colour_channel(colour.y, brute_colour.y) ||
            !same_colour_channel(colour.z, brute_colour.z))
            return broken(c, "pixel %d: %s sees colour (%.17g %.17g %.17g), brute force (%.17g %.17g %.17g)", pixel,
                          world_names[k], colour.x, colour.y, colour.z, brute_colour.x, brute_colour.y, brute_colour.z);
    }
    return true;
}

/* Builds the five worlds of s. Returns false with why filled when memory runs out. */
static bool build_worlds(struct checker *c, const struct scene *s) {
    char err[256];
    for (int k = 0; k < WORLD_COUNT; k++)
        if (!accel_world_init(&c->worlds[k], s, err, sizeof err))
            return broken(c, "%s: %s", world_names[k], err);
    bool built = accel_world_use_kdtree(&c->worlds[WORLD_KD_SEED], KD_SPLIT_SEED, err, sizeof err) &&
                 accel_world_use_kdtree(&c->worlds[WORLD_KD_SAH], KD_SPLIT_SAH, err, sizeof err) &&
                 accel_world_use_bvh(&c->worlds[WORLD_BVH_MEDIAN], BVH_SPLIT_MEDIAN, err, sizeof err) &&
                 accel_world_use_bvh(&c->worlds[WORLD_BVH_SAH], BVH_SPLIT_SAH, err, sizeof err);
    if (!built)
        return broken(c, "%s", err);
    size_t faces = c->worlds[WORLD_BRUTE].triangles.face_count;
    c->face_t = malloc((faces + 1) * sizeof *c->face_t);
    c->reported = malloc(faces + 1);
    if (c->face_t == NULL || c->reported == NULL)
        return broken(c, "out of memory");
    return true;
}

enum render_check_result render_check_scene(const char *name, const char *text, char *why, size_t why_size) {
    struct checker c = {.why = why, .why_size = why_size};
    snprintf(why, why_size, "all checks hold");
    struct scene s;
    char err[512];
    if (!scene_parse(name, text, &s, err, sizeof err)) {
        size_t n = strlen(name);
        if (strncmp(err, name, n) != 0 || err[n] != ':') {
            broken(&c, "the scene is refused with a message that does not start with '%s:': %s", name, err);
            return RENDER_CHECK_FAILED;
        }
        return RENDER_CHECK_PASSED;
    }
    bool ok = place_tiny_meshes(&s) || broken(&c, "out of memory");
    const struct known_defect *known = ok ? known_defect_of(&s) : NULL;
    if (known != NULL) {
        snprintf(why, why_size, "known defect: %s", known->name);
        scene_free(&s);
        return RENDER_CHECK_KNOWN_DEFECT;
    }
    s.width = s.width < RENDER_CHECK_MAX_WIDTH ? s.width : RENDER_CHECK_MAX_WIDTH;
    s.height = s.height < RENDER_CHECK_MAX_HEIGHT ? s.height : RENDER_CHECK_MAX_HEIGHT;
    s.max_depth = s.max_depth < RENDER_CHECK_MAX_DEPTH ? s.max_depth : RENDER_CHECK_MAX_DEPTH;
    s.light_count = s.light_count < RENDER_CHECK_MAX_LIGHTS ? s.light_count : RENDER_CHECK_MAX_LIGHTS;
    struct camera cam;
    /* A camera with no picture is refused by the chapter programs before anything is built. */
    bool has_picture = camera_init(&cam, s.eye, s.target, s.up, s.fov, s.width, s.height, err, sizeof err);
    if (ok && has_picture && build_worlds(&c, &s)) {
        for (int j = 0; ok && j < cam.height; j++)
            for (int i = 0; ok && i < cam.width; i++) {
                ray r = camera_ray(&cam, i, j);
                ok = check_ray(&c, &r, j * cam.width + i);
            }
    } else if (has_picture) {
        ok = false;
    }
    for (int k = 0; k < WORLD_COUNT; k++)
        accel_world_free(&c.worlds[k]);
    free(c.face_t);
    free(c.reported);
    scene_free(&s);
    return ok ? RENDER_CHECK_PASSED : RENDER_CHECK_FAILED;
}

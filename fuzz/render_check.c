/* render_check.c: a scene text through the whole renderer of chapter 10, every structure against the
 * brute-force loop (the renderer fuzzer's check; not part of any chapter).
 *
 * The fuzzer writes scene text, so what it can reach is whatever a scene file can ask for: any camera,
 * materials, lights, shapes, and meshes placed with any scale, rotation and translation. The mesh
 * files it names are not read (their readers have fuzzers of their own, and a fuzzer must not wander
 * the file system): each `mesh` directive is pointed at one of the tiny meshes below, chosen by its
 * file name so the fuzzer can still pick among them, written once as OBJ files to a folder of our own
 * and loaded by scene_load_meshes as the programs load theirs. */
#include "render_check.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "accel.h"
#include "box.h"
#include "bvh.h"
#include "camera.h"
#include "kdtree.h"
#include "plane.h"
#include "sphere.h"
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

/* Exact agreement is promised for rays starting near the triangles: bvh.c and kdtree.c pad their boxes
 * by 2^-20 of the mesh's size, which covers Moller-Trumbore's rounding (about 1e-16 of the distance
 * from the ray's origin) for rays starting within about a thousand mesh sizes, and chapter 5's
 * per-mesh boxes (world.c) are not padded at all. From farther away, whether a ray passing a hair
 * from a triangle "hits" it is rounding noise that a box test and the triangle test may call
 * differently. So the exact checks take only rays starting within this many sizes of the triangles'
 * bounding box (size: its largest extent), and the colours are compared only when every light, the
 * eye and every other shape lie that near (render_check_scene). 2^10: bvh.c's "a thousand". */
#define RENDER_CHECK_NEAR_SIZES 1024.0

/* The structures' own invariant checks (kdtree_is_valid, bvh_is_valid) walk the whole tree once per
 * face, so they cost faces x nodes: they run only on scenes of at most this many triangles (the tiny
 * meshes have 1 to 8 faces, so a handful of meshes), to keep the fuzzer's pace. */
#define RENDER_CHECK_VALIDATE_FACES 64

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

/* The folder holding the tiny meshes as OBJ files, written on the first call (a new folder under /tmp
 * for each process, removed at exit); NULL when it cannot be made. */
static char tiny_folder[64];

static void remove_tiny_files(void) {
    char path[96];
    for (size_t k = 0; k < TINY_MESH_COUNT; k++) {
        snprintf(path, sizeof path, "%s/tiny-%zu.obj", tiny_folder, k);
        remove(path);
    }
    rmdir(tiny_folder);
}

static const char *tiny_mesh_folder(void) {
    if (tiny_folder[0] != '\0')
        return tiny_folder;
    snprintf(tiny_folder, sizeof tiny_folder, "/tmp/whitted-tiny-meshes-XXXXXX");
    if (mkdtemp(tiny_folder) == NULL)
        return NULL;
    atexit(remove_tiny_files);
    for (size_t k = 0; k < TINY_MESH_COUNT; k++) {
        char path[96];
        snprintf(path, sizeof path, "%s/tiny-%zu.obj", tiny_folder, k);
        FILE *f = fopen(path, "w");
        if (f == NULL)
            return NULL;
        const struct tiny_mesh *t = &tiny_meshes[k];
        for (size_t v = 0; v < t->vertex_count; v++)
            fprintf(f, "v %.17g %.17g %.17g\n", t->vertices[v].x, t->vertices[v].y, t->vertices[v].z);
        for (size_t face = 0; face < t->face_count; face++)
            fprintf(f, "f %u %u %u\n", t->faces[face].v[0] + 1, t->faces[face].v[1] + 1, t->faces[face].v[2] + 1);
        if (fclose(f) != 0)
            return NULL;
    }
    return tiny_folder;
}

/* Points every mesh directive of s at the file of its tiny mesh and loads them all with
 * scene_load_meshes, which places each by its transform and refuses one placed out of range, as for
 * the chapters' programs. Returns its answer, with its message in err; false with a message also when
 * the tiny files cannot be written or memory runs out. */
static bool load_tiny_meshes(struct scene *s, char *err, size_t err_size) {
    const char *folder = tiny_mesh_folder();
    if (folder == NULL) {
        snprintf(err, err_size, "cannot write the tiny meshes under /tmp");
        return false;
    }
    for (size_t k = 0; k < s->mesh_count; k++) {
        struct scene_mesh *sm = &s->meshes[k];
        size_t which = (size_t)(tiny_mesh_for(sm->path) - tiny_meshes);
        char *path = malloc(strlen(folder) + 32);
        if (path == NULL) {
            snprintf(err, err_size, "out of memory");
            return false;
        }
        sprintf(path, "%s/tiny-%zu.obj", folder, which);
        free(sm->path);
        sm->path = path;
    }
    return scene_load_meshes(s, err, err_size);
}

/* ---- known defects ------------------------------------------------------------------------------
 *
 * Scenes that trigger a defect someone is fixing are recognised here and not rendered, so that the
 * fuzzer looks past them for new ones, and their saved inputs are skipped by the tests with the
 * defect's name. When a defect is fixed, delete its entry: its saved inputs then run in the tests. */

/* The first two entries, "meshes outside float range crash the BVH build and hang the kd-tree" and "a
 * triangle directive outside float range crashes the BVH build", were deleted when scene_load_meshes
 * began to refuse meshes placed out of range and the parser triangle directives with a corner out of
 * range; their inputs in tests/data/fuzz/render/ now check those refusals. An entry reads
 *     {"what goes wrong, in which files", predicate},
 * with a predicate taking the loaded scene and saying whether it triggers the defect. */

static const struct known_defect {
    const char *name;
    bool (*triggered)(const struct scene *s);
} known_defects[] = {
    {NULL, NULL}, /* the end of the list */
};

/* Returns the known defect s would trigger, or NULL. */
static const struct known_defect *known_defect_of(const struct scene *s) {
    for (size_t k = 0; known_defects[k].name != NULL; k++)
        if (known_defects[k].triggered(s))
            return &known_defects[k];
    return NULL;
}

/* ---- checking --------------------------------------------------------------------------------- */

enum { WORLD_BRUTE, WORLD_KD_SEED, WORLD_KD_SAH, WORLD_BVH_MEDIAN, WORLD_BVH_SAH, WORLD_COUNT };
static const char *world_names[WORLD_COUNT] = {"brute force", "kd-tree (seed's rule)", "kd-tree (SAH)",
                                               "BVH (median)", "BVH (SAH)"};

/* The crossings world_for_each_crossing reports, as a list of t. */
struct crossings {
    double *t;
    size_t count, capacity;
};

struct checker {
    struct accel_world worlds[WORLD_COUNT];
    double *face_t; /* per face of the merged mesh: the brute-force t of the ray being checked, or NAN */
    unsigned char *reported; /* per face: times for_each_hit reported it */
    struct crossings expected, got; /* a shadow ray's crossings in the brute-force world and another */
    struct aabb bounds;  /* of all triangles */
    double near;         /* RENDER_CHECK_NEAR_SIZES times the largest extent of bounds */
    bool compare_colours; /* the whole scene lies near the triangles */
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

/* True when p lies within c->near of the triangles' bounding box (a scene without triangles has
 * nothing to disagree about: every point is near). */
static bool is_near(const struct checker *c, vec3 p) {
    if (c->worlds[WORLD_BRUTE].triangles.face_count == 0)
        return true;
    vec3 below = vec3_sub(c->bounds.min, p), above = vec3_sub(p, c->bounds.max);
    vec3 outside = vec3_max(vec3_max(below, above), vec3_make(0, 0, 0));
    return vec3_is_finite(p) && outside.x <= c->near && outside.y <= c->near && outside.z <= c->near;
}

/* True when the eye, every light, the bounding box of every shape and the point of every plane nearest
 * the origin lie near the triangles, so that no ray of the picture should start far from them (a
 * grazing ray can still hit a plane far away: the colours are compared to a tolerance, and no such
 * case has turned up). */
static bool scene_is_near(const struct checker *c, const struct scene *s) {
    bool near = is_near(c, s->eye);
    for (size_t k = 0; k < s->light_count; k++)
        near = near && is_near(c, s->lights[k].position);
    for (size_t k = 0; k < s->kind_count; k++) {
        const struct shape_list *list = &s->shapes[k];
        for (size_t n = 0; n < list->count; n++) {
            vec3 min, max;
            if (list->kind->bounds(shape_item(list->syntax, list->items, n), &min, &max))
                near = near && is_near(c, min) && is_near(c, max);
        }
    }
    const struct shape_list *planes = scene_shapes(s, &plane_syntax);
    const struct plane *plane = planes->items;
    for (size_t k = 0; k < planes->count; k++)
        near = near && is_near(c, vec3_scale(plane[k].normal, plane[k].distance));
    return near;
}

static bool count_hit(void *context, double t, uint32_t face) {
    struct checker *c = context;
    (void)t;
    if (c->reported[face] < UCHAR_MAX)
        c->reported[face]++;
    return true;
}

/* Checks the three queries of world `k`'s structure on ray r in the window (t_min, t_max) against the
 * brute-force loop over the same triangles. `what` names the ray in messages. */
static bool check_structure(struct checker *c, int k, const ray *r, double t_min, double t_max, const char *what) {
    const struct accel_world *w = &c->worlds[k];
    const struct mesh *m = &w->triangles;
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
        return broken(c, "%s: %s closest gives %s t=%.17g face %u, brute force %s t=%.17g face %u", what,
                      world_names[k], found ? "a hit" : "no hit", t, face, any ? "a hit" : "no hit", best_t, best_face);
    if (w->accel.occluded(w->structure, r, t_min, t_max) != any)
        return broken(c, "%s: %s occluded says %s, brute force %s", what, world_names[k],
                      any ? "no" : "yes", any ? "yes" : "no");
    memset(c->reported, 0, m->face_count);
    w->accel.for_each_hit(w->structure, r, t_min, t_max, count_hit, c);
    for (size_t f = 0; f < m->face_count; f++)
        if (c->reported[f] != (isnan(c->face_t[f]) ? 0 : 1))
            return broken(c, "%s: %s for_each_hit reports face %zu %u times, brute force %s", what,
                          world_names[k], f, c->reported[f], isnan(c->face_t[f]) ? "misses it" : "hits it once");
    return true;
}

static bool collect_crossing(void *context, double t, int material) {
    struct crossings *list = context;
    (void)material;
    if (list->count < list->capacity)
        list->t[list->count] = t;
    list->count++;
    return true;
}

static int compare_doubles(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Fills `list` with the sorted crossings of r in world `k` within (t_min, t_max). */
static void crossings_of(struct checker *c, int k, const ray *r, double t_min, double t_max, struct crossings *list) {
    list->count = 0;
    world_for_each_crossing(&c->worlds[k].world, r, t_min, t_max, collect_crossing, list);
    qsort(list->t, list->count < list->capacity ? list->count : list->capacity, sizeof *list->t, compare_doubles);
}

/* Checks the shadow rays from the brute-force hit of pixel's ray to every light, as shadow.c makes them:
 * each structure's queries against the brute-force loop, and every world's crossings (all shapes)
 * against the brute-force world's. */
static bool check_shadow_rays(struct checker *c, const ray *r, const struct hit *h, int pixel) {
    const struct scene *s = c->worlds[WORLD_BRUTE].world.scene;
    vec3 point = ray_at(*r, h->t);
    if (!is_near(c, point))
        return true;
    for (size_t l = 0; l < s->light_count; l++) {
        vec3 to_light = vec3_sub(s->lights[l].position, point);
        double distance = vec3_length(to_light);
        double margin = s->shadow_offset ? SHADOW_T_MIN : 0.0;
        ray shadow = {point, vec3_scale(to_light, 1.0 / distance)};
        char what[64];
        snprintf(what, sizeof what, "pixel %d, shadow ray to light %zu", pixel, l);
        crossings_of(c, WORLD_BRUTE, &shadow, margin, distance - margin, &c->expected);
        for (int k = WORLD_BRUTE + 1; k < WORLD_COUNT; k++) {
            if (!check_structure(c, k, &shadow, margin, distance - margin, what))
                return false;
            crossings_of(c, k, &shadow, margin, distance - margin, &c->got);
            bool same = c->got.count == c->expected.count;
            for (size_t j = 0; same && j < c->got.count && j < c->got.capacity; j++)
                same = c->got.t[j] == c->expected.t[j];
            if (!same)
                return broken(c, "%s: %s world reports %zu crossings, the brute-force world %zu (first t %.17g, %.17g)",
                              what, world_names[k], c->got.count, c->expected.count,
                              c->got.count > 0 ? c->got.t[0] : NAN, c->expected.count > 0 ? c->expected.t[0] : NAN);
        }
    }
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
    if (!is_near(c, r->origin))
        return true;
    char what[32];
    snprintf(what, sizeof what, "pixel %d", pixel);
    for (int k = WORLD_BRUTE + 1; k < WORLD_COUNT; k++)
        if (!check_structure(c, k, r, RAY_T_MIN, INFINITY, what))
            return false;
    if (brute_found && !check_shadow_rays(c, r, &brute, pixel))
        return false;
    vec3 brute_colour = whitted_trace(&c->worlds[WORLD_BRUTE].world, r);
    for (int k = WORLD_BRUTE + 1; k < WORLD_COUNT; k++) {
        struct hit h = hit_nothing(INFINITY);
        bool found = world_closest(&c->worlds[k].world, r, RAY_T_MIN, &h);
        bool same = h.t == brute.t && h.material == brute.material && h.normal.x == brute.normal.x &&
                    h.normal.y == brute.normal.y && h.normal.z == brute.normal.z;
        if (found != brute_found || (found && !same))
            return broken(c, "pixel %d: %s nearest hit t=%.17g material %d, brute force t=%.17g material %d", pixel,
                          world_names[k], h.t, h.material, brute.t, brute.material);
        vec3 colour = whitted_trace(&c->worlds[k].world, r);
        bool same_colour = same_colour_channel(colour.x, brute_colour.x) &&
                           same_colour_channel(colour.y, brute_colour.y) && same_colour_channel(colour.z, brute_colour.z);
        if (c->compare_colours && !same_colour)
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
    if (faces <= RENDER_CHECK_VALIDATE_FACES) {
        for (int k = WORLD_KD_SEED; k <= WORLD_KD_SAH; k++)
            if (!kdtree_is_valid(c->worlds[k].structure, &c->worlds[k].triangles, err, sizeof err))
                return broken(c, "%s: %s", world_names[k], err);
        for (int k = WORLD_BVH_MEDIAN; k <= WORLD_BVH_SAH; k++)
            if (!bvh_is_valid(c->worlds[k].structure, &c->worlds[k].triangles, err, sizeof err))
                return broken(c, "%s: %s", world_names[k], err);
    }
    c->face_t = malloc((faces + 1) * sizeof *c->face_t);
    c->reported = malloc(faces + 1);
    c->bounds = world_mesh_bounds(&c->worlds[WORLD_BRUTE].triangles);
    vec3 extent = vec3_sub(c->bounds.max, c->bounds.min);
    c->near = faces > 0 ? RENDER_CHECK_NEAR_SIZES * fmax(extent.x, fmax(extent.y, extent.z)) : 0.0;
    c->compare_colours = scene_is_near(c, s);
    size_t crossings = faces + 1; /* each face once, each other shape at most twice */
    for (size_t k = 0; k < s->kind_count; k++)
        crossings += 2 * s->shapes[k].count;
    c->expected = (struct crossings){malloc(crossings * sizeof(double)), 0, crossings};
    c->got = (struct crossings){malloc(crossings * sizeof(double)), 0, crossings};
    if (c->face_t == NULL || c->reported == NULL || c->expected.t == NULL || c->got.t == NULL)
        return broken(c, "out of memory");
    return true;
}

enum render_check_result render_check_scene(const char *name, const char *text, char *why, size_t why_size) {
    struct checker c = {.why = why, .why_size = why_size};
    snprintf(why, why_size, "all checks hold");
    struct scene s;
    char err[512];
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    if (!scene_parse(name, text, kinds, &s, err, sizeof err)) {
        size_t n = strlen(name);
        if (strncmp(err, name, n) != 0 || err[n] != ':') {
            broken(&c, "the scene is refused with a message that does not start with '%s:': %s", name, err);
            return RENDER_CHECK_FAILED;
        }
        snprintf(why, why_size, "refused: %s", err);
        return RENDER_CHECK_PASSED;
    }
    if (!load_tiny_meshes(&s, err, sizeof err)) {
        /* Refused like a scene file: the message must name the scene and its line. */
        size_t n = strlen(name);
        bool named = strncmp(err, name, n) == 0 && err[n] == ':';
        scene_free(&s);
        if (!named) {
            broken(&c, "the meshes are refused with a message that does not start with '%s:': %s", name, err);
            return RENDER_CHECK_FAILED;
        }
        snprintf(why, why_size, "refused: %s", err);
        return RENDER_CHECK_PASSED;
    }
    bool ok = true;
    const struct known_defect *known = known_defect_of(&s);
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
    free(c.expected.t);
    free(c.got.t);
    scene_free(&s);
    return ok ? RENDER_CHECK_PASSED : RENDER_CHECK_FAILED;
}

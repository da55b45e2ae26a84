/* render_check.c: a scene text through the whole renderer of chapter 10, then chapters 12 to 15's
 * sampling, lens, area lights, textures and paths, chapter 16's instances and chapter 17's rough
 * surfaces, every structure against the brute-force loop or a plainer route to the same answer (the
 * renderer fuzzer's check; not part of any chapter).
 *
 * The fuzzer writes scene text, so what it can reach is whatever a scene file can ask for: any camera,
 * materials, lights, shapes, and meshes placed with any scale, rotation and translation. The mesh
 * files it names are not read (their readers have fuzzers of their own, and a fuzzer must not wander
 * the file system): each `mesh` directive is pointed at one of the tiny meshes below, chosen by its
 * file name so the fuzzer can still pick among them, written once as OBJ files to a folder of our own
 * and loaded by scene_load_meshes as the programs load theirs. The image maps' files likewise: each
 * pigment's file is one of the tiny images of tiny_images.h, written once to the same folder and read
 * by texture_load_images as chapter 14 reads them. */
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
#include "emitter.h"
#include "instances.h"
#include "kdtree.h"
#include "mesh_surface.h"
#include "path_trace.h"
#include "plane.h"
#include "rough_surface.h"
#include "soft_shadow.h"
#include "sphere.h"
#include "supersample.h"
#include "texture.h"
#include "thin_lens.h"
#include "tiny_images.h"
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

/* FNV-1a of a text: what chooses a tiny mesh, a tiny image or a structure, so that every text stands
 * for one of them and a mutation of the text can pick another. */
static uint32_t text_hash(const char *text) {
    uint32_t hash = 2166136261u;
    for (const unsigned char *c = (const unsigned char *)text; *c != '\0'; c++)
        hash = (hash ^ *c) * 16777619u;
    return hash;
}

/* Which tiny mesh a file name stands for. */
static const struct tiny_mesh *tiny_mesh_for(const char *path) {
    return &tiny_meshes[text_hash(path) % TINY_MESH_COUNT];
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
    for (size_t k = 0; k < TINY_IMAGE_COUNT; k++) {
        snprintf(path, sizeof path, "%s/%s", tiny_folder, tiny_image_name(k));
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
        /* Chapter 14 keeps a mesh's texture coordinates and normals: every corner gets a (u, v) from its
         * x and y, and every corner but those of the first two meshes its direction from the origin as
         * its normal (the awkward mesh's first corner, at the origin, a zero one). */
        bool normals = k >= 2;
        for (size_t v = 0; v < t->vertex_count; v++) {
            vec3 p = t->vertices[v];
            fprintf(f, "v %.17g %.17g %.17g\nvt %.17g %.17g\n", p.x, p.y, p.z, p.x * 0.5 + 0.5, p.y * 0.5 + 0.5);
            if (normals)
                fprintf(f, "vn %.17g %.17g %.17g\n", p.x, p.y, p.z);
        }
        for (size_t face = 0; face < t->face_count; face++) {
            fprintf(f, "f");
            for (int c = 0; c < 3; c++)
                fprintf(f, normals ? " %u/%u/%u" : " %u/%u", t->faces[face].v[c] + 1, t->faces[face].v[c] + 1,
                        t->faces[face].v[c] + 1);
            fprintf(f, "\n");
        }
        if (fclose(f) != 0)
            return NULL;
    }
    char err[256];
    if (!tiny_images_write(tiny_folder, err, sizeof err))
        return NULL;
    return tiny_folder;
}

/* Which tiny image a pigment's file name stands for. */
static size_t tiny_image_for(const char *path) { return text_hash(path) % TINY_IMAGE_COUNT; }

/* Replaces the malloc'd path *path by folder/name; false with "out of memory" in err. */
static bool replace_path(char **path, const char *folder, const char *name, char *err, size_t err_size) {
    char *joined = malloc(strlen(folder) + strlen(name) + 2);
    if (joined == NULL) {
        snprintf(err, err_size, "out of memory");
        return false;
    }
    sprintf(joined, "%s/%s", folder, name);
    free(*path);
    *path = joined;
    return true;
}

/* Points every mesh directive of s at the file of its tiny mesh and every image map at its tiny image,
 * and loads them as chapter 14 does: the images with texture_load_images, the meshes with
 * scene_load_meshes (which places each by its transform and refuses one placed out of range) keeping
 * their texture coordinates and normals, then mesh_surface_prepare. s's paint hooks are chapter 14's,
 * so every trace of s is painted. Returns false with the first refusal in err; false with a message
 * also when the tiny files cannot be written or memory runs out. */
static bool load_tiny_meshes(struct scene *s, char *err, size_t err_size) {
    const char *folder = tiny_mesh_folder();
    if (folder == NULL) {
        snprintf(err, err_size, "cannot write the tiny meshes under /tmp");
        return false;
    }
    char name[32];
    for (size_t k = 0; k < s->mesh_count; k++) {
        snprintf(name, sizeof name, "tiny-%zu.obj", (size_t)(tiny_mesh_for(s->meshes[k].path) - tiny_meshes));
        if (!replace_path(&s->meshes[k].path, folder, name, err, err_size))
            return false;
    }
    for (size_t k = 0; k < s->pigment_count; k++) {
        struct pigment *p = &s->pigments[k];
        if (p->pattern == PIGMENT_IMAGE_MAP &&
            !replace_path(&p->file, folder, tiny_image_name(tiny_image_for(p->file)), err, err_size))
            return false;
    }
    s->paint = texture_paint;
    s->shadow_paint = texture_paint_shadow;
    return texture_load_images(s, err, err_size) && scene_load_meshes(s, err, err_size) &&
           mesh_surface_prepare(s, err, err_size);
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

static bool same_colour(vec3 a, vec3 b) {
    return same_colour_channel(a.x, b.x) && same_colour_channel(a.y, b.y) && same_colour_channel(a.z, b.z);
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
        if (c->compare_colours && !same_colour(colour, brute_colour))
            return broken(c, "pixel %d: %s sees colour (%.17g %.17g %.17g), brute force (%.17g %.17g %.17g)", pixel,
                          world_names[k], colour.x, colour.y, colour.z, brute_colour.x, brute_colour.y, brute_colour.z);
    }
    return true;
}

/* Builds the five worlds of s. Returns false with why filled when memory runs out. */
static bool build_worlds(struct checker *c, const struct scene *s) {
    char err[256];
    for (int k = 0; k < WORLD_COUNT; k++)
        if (!accel_world_init(&c->worlds[k], s, k != WORLD_BRUTE, err, sizeof err)) /* a structure follows */
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

/* ---- chapters 12 to 15: sampling, lens, area lights, textures, paths ------------------------------
 *
 * After chapter 10's checks, the same scene (painted by chapter 14's textures all along) is drawn by
 * chapters 12 to 14's sampled tracer and by chapter 15's path tracer, in the brute-force world and in
 * one structure's world chosen by a hash of the text (so that every structure takes its turn over the
 * inputs), on a picture cut to RENDER_CHECK_SAMPLED_SIDE pixels a side, and the two must agree. Every
 * count the scene gives that multiplies the work is cut first, so that an input costs milliseconds
 * whatever it asks for (the limits below: at most about 60,000 rays an input in the sampled tracer). */
#define RENDER_CHECK_SAMPLED_SIDE 2       /* pixels a side of the sampled and path-traced pictures */
#define RENDER_CHECK_SAMPLED_DEPTH 2      /* max_depth of the sampled tracer: 3 rays a tree */
#define RENDER_CHECK_MAX_AA_SAMPLES 2     /* antialias samples: a 2 x 2 grid, recursive depth 2 */
#define RENDER_CHECK_MAX_BLUR_SAMPLES 7   /* a lens's rays a camera sample: one ring */
#define RENDER_CHECK_MAX_AREA_SIDE 3      /* an area light's points a side: the middle lines are cut */
#define RENDER_CHECK_MAX_AREA_ADAPTIVE 1  /* an area light's adaptive level */
#define RENDER_CHECK_MAX_PATHS 2          /* paths a pixel */
#define RENDER_CHECK_MAX_BOUNCES 3        /* bounces a path */
#define RENDER_CHECK_UNIT_TOLERANCE 1e-9  /* a normalised direction's length differs from 1 by rounding only */

/* Cuts what multiplies the work of chapters 12 to 15 (the antialias samples, the lens's rays, the area
 * lights' grids, the paths and their bounces) to the limits above, keeping every setting valid. */
static void cut_sampling(struct scene *s) {
    if (s->antialias.samples > RENDER_CHECK_MAX_AA_SAMPLES)
        s->antialias.samples = RENDER_CHECK_MAX_AA_SAMPLES;
    if (s->lens.blur_samples > RENDER_CHECK_MAX_BLUR_SAMPLES)
        s->lens.blur_samples = RENDER_CHECK_MAX_BLUR_SAMPLES;
    for (size_t k = 0; k < s->light_count; k++) {
        struct area_light *a = &s->lights[k].area;
        a->size1 = a->size1 < RENDER_CHECK_MAX_AREA_SIDE ? a->size1 : RENDER_CHECK_MAX_AREA_SIDE;
        a->size2 = a->size2 < RENDER_CHECK_MAX_AREA_SIDE ? a->size2 : RENDER_CHECK_MAX_AREA_SIDE;
        if (a->adaptive != AREA_LIGHT_NOT_ADAPTIVE && a->adaptive > RENDER_CHECK_MAX_AREA_ADAPTIVE)
            a->adaptive = RENDER_CHECK_MAX_AREA_ADAPTIVE;
    }
    s->paths.samples = s->paths.samples < RENDER_CHECK_MAX_PATHS ? s->paths.samples : RENDER_CHECK_MAX_PATHS;
    s->paths.bounces = s->paths.bounces < RENDER_CHECK_MAX_BOUNCES ? s->paths.bounces : RENDER_CHECK_MAX_BOUNCES;
    s->paths.roulette = s->paths.roulette < s->paths.bounces ? s->paths.roulette : s->paths.bounces;
}

/* The structure whose world the sampled tracer and the paths are checked in: a hash of the text. */
static int structure_for(const char *text) { return WORLD_BRUTE + 1 + (int)(text_hash(text) % (WORLD_COUNT - 1)); }

/* What a sample of the sampled tracer looks through: chapter 13's tracer in one world, through the
 * lens when the camera has one (as thin_lens_sampler does), else through the pinhole (supersample's). */
struct sampled_view {
    const struct world *world;
    const struct camera *camera;
    const struct thin_lens *lens; /* NULL for a pinhole */
};

static vec3 trace_soft(const struct sampled_view *v, const ray *r) {
    return whitted_trace_shadowed(v->world, r, soft_shadow_filtered);
}

static vec3 sampled_colour_at(const void *context, double x, double y) {
    const struct sampled_view *v = context;
    if (v->lens == NULL) {
        ray r = camera_ray_through(v->camera, x, y);
        return trace_soft(v, &r);
    }
    vec3 sum = vec3_make(0, 0, 0);
    for (int k = 0; k < v->lens->samples; k++) {
        ray r = thin_lens_ray(v->lens, x, y, k);
        sum = vec3_add(sum, trace_soft(v, &r));
    }
    return vec3_scale(sum, 1.0 / v->lens->samples);
}

/* Draws the small picture of `cam` by the scene's antialias line, lens and area lights (chapters 12 to
 * 14) in the brute-force world and in world k, and checks that they see the same colours and the same
 * number of rays per pixel, and that the lens's rays are rays: a finite origin, a unit direction. */
static bool check_sampled(struct checker *c, const struct scene *s, const struct camera *cam, int k) {
    struct thin_lens lens;
    if (lens_is_open(&s->lens)) {
        thin_lens_init(&lens, cam, &s->lens, s->antialias.seed);
        /* Every lens ray through a pixel's centre starts at a finite point and has a unit direction. */
        for (int p = 0; p < cam->width * cam->height; p++)
            for (int n = 0; n < lens.samples; n++) {
                ray r = thin_lens_ray(&lens, p % cam->width + 0.5, p / cam->width + 0.5, n);
                if (!vec3_is_finite(r.origin) || !(fabs(vec3_length(r.direction) - 1.0) < RENDER_CHECK_UNIT_TOLERANCE))
                    return broken(c, "lens ray %d of pixel %d starts at (%g %g %g) with direction (%g %g %g)", n, p,
                                  r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z);
            }
    }
    vec3 colours[2][RENDER_CHECK_SAMPLED_SIDE * RENDER_CHECK_SAMPLED_SIDE];
    int rays[2][RENDER_CHECK_SAMPLED_SIDE * RENDER_CHECK_SAMPLED_SIDE];
    const int worlds[2] = {WORLD_BRUTE, k};
    for (int w = 0; w < 2; w++) {
        struct sampled_view view = {&c->worlds[worlds[w]].world, cam, lens_is_open(&s->lens) ? &lens : NULL};
        struct sample_view sample_view = {sampled_colour_at, &view};
        supersample_block(&s->antialias, &sample_view, 0, 0, cam->width, cam->height, colours[w], rays[w]);
    }
    for (int p = 0; p < cam->width * cam->height; p++) {
        if (rays[0][p] != rays[1][p])
            return broken(c, "sampled pixel %d: %s takes %d camera rays, brute force %d", p, world_names[k], rays[1][p],
                          rays[0][p]);
        if (c->compare_colours && !same_colour(colours[0][p], colours[1][p]))
            return broken(c, "sampled pixel %d: %s sees colour (%.17g %.17g %.17g), brute force (%.17g %.17g %.17g)", p,
                          world_names[k], colours[1][p].x, colours[1][p].y, colours[1][p].z, colours[0][p].x,
                          colours[0][p].y, colours[0][p].z);
    }
    return true;
}

/* Chapter 15: parses the text again (the area lights become emitting triangles of the scene), loads it
 * as chapter 15 does, builds the brute-force world and world k, and traces the paths of the small
 * picture in both with the emitters gathered from the brute-force world. Every pixel must be finite
 * (not always positive: a scene may ask for a negative background), and the same in both. A scene
 * refused on the way (an emissive plane) must be refused with a message naming it. */
static bool check_paths(struct checker *c, const char *name, const char *text, int k) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    struct scene s;
    char err[512];
    if (!scene_parse(name, text, kinds, &s, err, sizeof err))
        return broken(c, "the scene is refused the second time: %s", err);
    struct accel_world worlds[2];
    memset(worlds, 0, sizeof worlds);
    struct emitter_list emitters = {0};
    struct camera cam;
    bool ok = true, built = load_tiny_meshes(&s, err, sizeof err) && emitter_add_area_lights(&s, err, sizeof err) >= 0;
    if (built) {
        s.shadow_paint = NULL; /* chapter 15 sets only the paint hook: its shadow rays stop at any surface */
        cut_sampling(&s);
        int side_w = s.width < RENDER_CHECK_SAMPLED_SIDE ? s.width : RENDER_CHECK_SAMPLED_SIDE;
        int side_h = s.height < RENDER_CHECK_SAMPLED_SIDE ? s.height : RENDER_CHECK_SAMPLED_SIDE;
        built = camera_init(&cam, s.eye, s.target, s.up, s.fov, side_w, side_h, err, sizeof err) &&
                accel_world_init(&worlds[0], &s, false, err, sizeof err) &&
                accel_world_init(&worlds[1], &s, true, err, sizeof err);
        built = built && (k == WORLD_KD_SEED || k == WORLD_KD_SAH
                              ? accel_world_use_kdtree(&worlds[1], k == WORLD_KD_SEED ? KD_SPLIT_SEED : KD_SPLIT_SAH,
                                                       err, sizeof err)
                              : accel_world_use_bvh(&worlds[1], k == WORLD_BVH_MEDIAN ? BVH_SPLIT_MEDIAN : BVH_SPLIT_SAH,
                                                    err, sizeof err));
        if (built && !emitter_list_build(&emitters, &worlds[0], err, sizeof err)) {
            built = false;
            size_t n = strlen(name);
            if (strncmp(err, name, n) != 0 || err[n] != ':')
                ok = broken(c, "the paths' emitters are refused with a message that does not start with '%s:': %s",
                            name, err);
        } else if (!built) {
            ok = broken(c, "chapter 15's scene cannot be built: %s", err);
        }
    } else {
        ok = broken(c, "chapter 15's scene cannot be loaded: %s", err);
    }
    /* Chapter 15's surfaces, then, when a material is rough, chapter 17's rough mirrors and glass, in the
     * chapter's form and in the form its --form cycles-3.4 draws for the comparison with Cycles. */
    bool rough = false;
    for (size_t m = 0; m < s.material_count; m++)
        rough = rough || s.materials[m].roughness > 0.0;
    const struct path_surface *surfaces[] = {NULL, &rough_surface_hook, &rough_surface_hook_cycles_3_4};
    for (int form = 0; form < (rough ? 3 : 1); form++)
        for (int j = 0; built && ok && j < cam.height; j++)
            for (int i = 0; ok && i < cam.width; i++) {
                vec3 colour[2];
                for (int w = 0; w < 2; w++) {
                    struct path_world paths;
                    path_world_init(&paths, &worlds[w].world, &emitters, &cam, &s.paths);
                    paths.surface = surfaces[form];
                    colour[w] = path_pixel(&paths, i, j, NULL);
                }
                const char *chapter = form == 0 ? "" : form == 1 ? " (chapter 17)" : " (chapter 17, cycles-3.4)";
                if (!vec3_is_finite(colour[0]))
                    ok = broken(c, "path pixel (%d, %d)%s: radiance (%g %g %g)", i, j, chapter, colour[0].x,
                                colour[0].y, colour[0].z);
                else if (c->compare_colours && !same_colour(colour[0], colour[1]))
                    ok = broken(c, "path pixel (%d, %d)%s: %s sees (%.17g %.17g %.17g), brute force "
                                "(%.17g %.17g %.17g)", i, j, chapter, world_names[k], colour[1].x, colour[1].y,
                                colour[1].z, colour[0].x, colour[0].y, colour[0].z);
            }
    emitter_list_free(&emitters);
    accel_world_free(&worlds[0]);
    accel_world_free(&worlds[1]);
    scene_free(&s);
    return ok;
}

/* ---- chapter 16: instances on the two-level structure --------------------------------------------
 *
 * The instance lines are drawn by chapter 16 only, on its two-level structure: a top-level BVH over the
 * instances' world boxes (a moving instance's box holding it over the shutter), each ray carried into
 * an instance's object space and walked through its object's chapter-11 BVH (instances.h). The check
 * places them as chapter 16 places them for a single picture (over its shutter [0, shutter]) and asks
 * of rays at the shutter's start, middle and end what the same instances give with no top level, every
 * instance tested by every ray (as chapter 16 tests the instances of objects with slivers): the same
 * nearest hit and the same crossings. So a box of the top level that leaves out what its instance
 * holds at some time of the shutter, or a walk that skips a box, shows as a difference. (The
 * brute-force loop that carries each ray into each instance itself is tests/test_instances.c's, kept
 * out of the students' hand-out because it is a second route to task 16.1's answer; this file is in the
 * hand-out.) Then the top level is refitted to the last frame's interval, [1, 1 + shutter / 2] (chapter
 * 16's frames run from clock 0 to 1, each exposed for the shutter; the poses hold after the last key),
 * and asked again there. */

/* The clock times each ray of the check is traced at, as shares of the interval the instances are placed
 * over. */
static const double instance_check_times[] = {0.0, 0.5, 1.0};

/* Besides the camera rays, rays from the eye towards points of the first RENDER_CHECK_INSTANCE_TARGETS
 * instances, so that the tiny objects are hit: the points at these shares of the diagonal of the
 * object's box (its centre lies near the tiny triangle's long edge and on the square's diagonal:
 * grazing hits), carried to where the instance has them at the ray's time. */
#define RENDER_CHECK_INSTANCE_TARGETS 16
#define INSTANCE_CHECK_POINTS 3
static const double instance_check_points[INSTANCE_CHECK_POINTS] = {0.5, 0.3, 0.7};

/* True when p lies within RENDER_CHECK_NEAR_SIZES sizes of box b (size: its largest extent), where the
 * instances' exactness is promised as the structures' is (RENDER_CHECK_NEAR_SIZES says why). */
static bool near_box(struct aabb b, vec3 p) {
    vec3 extent = vec3_sub(b.max, b.min);
    double near = RENDER_CHECK_NEAR_SIZES * fmax(extent.x, fmax(extent.y, extent.z));
    vec3 outside = vec3_max(vec3_max(vec3_sub(b.min, p), vec3_sub(p, b.max)), vec3_make(0, 0, 0));
    return vec3_is_finite(p) && outside.x <= near && outside.y <= near && outside.z <= near;
}

/* Compares the two-level structure `in` with `every` (the same instances, no top level) on ray r at
 * clock time `time`: the nearest hit (t to the last bit, instance, face, material and normal, and a
 * finite t and normal) and, cut at twice its t (or unbounded), the crossings, into expected and got. */
static bool check_instance_ray(struct checker *c, const struct instances *in, const struct instances *every,
                               const ray *r, int n, double time, struct crossings *expected, struct crossings *got) {
    struct hit fast = hit_nothing(INFINITY), slow = hit_nothing(INFINITY);
    bool a = in->hook.closest(in, r, RAY_T_MIN, time, &fast);
    bool b = in->hook.closest(every, r, RAY_T_MIN, time, &slow);
    if (a != b || (a && (fast.t != slow.t || fast.object != slow.object || fast.face != slow.face ||
                         fast.material != slow.material || fast.normal.x != slow.normal.x ||
                         fast.normal.y != slow.normal.y || fast.normal.z != slow.normal.z)))
        return broken(c, "instances, ray %d at time %.17g: two levels %s t %.17g instance %d face %d, every instance "
                      "tested %s t %.17g instance %d face %d", n, time, a ? "hit" : "missed", fast.t, fast.object,
                      fast.face, b ? "hit" : "missed", slow.t, slow.object, slow.face);
    if (a && !(isfinite(fast.t) && vec3_is_finite(fast.normal)))
        return broken(c, "instances, ray %d: a hit at t %g with normal (%g %g %g)", n, fast.t, fast.normal.x,
                      fast.normal.y, fast.normal.z);
    double t_max = a ? 2.0 * fast.t : INFINITY;
    struct crossings *lists[] = {expected, got};
    const struct instances *structures[] = {every, in};
    for (int k = 0; k < 2; k++) {
        lists[k]->count = 0;
        in->hook.for_each_crossing(structures[k], r, RAY_T_MIN, t_max, time, collect_crossing, lists[k]);
        size_t kept = lists[k]->count < lists[k]->capacity ? lists[k]->count : lists[k]->capacity;
        qsort(lists[k]->t, kept, sizeof *lists[k]->t, compare_doubles);
    }
    bool same = got->count == expected->count;
    for (size_t j = 0; same && j < got->count && j < got->capacity; j++)
        same = got->t[j] == expected->t[j];
    return same || broken(c, "instances, ray %d at time %.17g: %zu crossings, every instance tested %zu", n, time,
                          got->count, expected->count);
}

/* Checks the rays of the check (the camera rays of cam, then rays from the eye towards points of the
 * first instances) at instance_check_times over in's interval [in->t0, in->t1], when the eye lies near
 * the instances' boxes over that interval. */
static bool check_instance_rays(struct checker *c, const struct instances *in, const struct camera *cam, vec3 eye,
                                struct crossings *expected, struct crossings *got) {
    struct aabb all = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (size_t k = 0; k < in->count; k++)
        all = (struct aabb){vec3_min(all.min, in->boxes[k].min), vec3_max(all.max, in->boxes[k].max)};
    if (in->count == 0 || !near_box(all, eye))
        return true;
    /* The same instances with no top level: every one in the list a ray tests one by one (the queries
     * read the top level and that list from the struct they are given). */
    struct instances every = *in;
    every.top = NULL;
    every.outside = malloc((in->count + 1) * sizeof *every.outside);
    if (every.outside == NULL)
        return broken(c, "out of memory");
    for (size_t k = 0; k < in->count; k++)
        every.outside[k] = k;
    every.outside_count = in->count;
    size_t targets = in->count < RENDER_CHECK_INSTANCE_TARGETS ? in->count : RENDER_CHECK_INSTANCE_TARGETS;
    int camera_rays = cam->width * cam->height, rays = camera_rays + (int)(targets * INSTANCE_CHECK_POINTS);
    bool ok = true;
    for (size_t k = 0; ok && k < sizeof instance_check_times / sizeof *instance_check_times; k++) {
        double time = in->t0 + instance_check_times[k] * (in->t1 - in->t0);
        for (int n = 0; ok && n < rays; n++) {
            ray r;
            if (n < camera_rays) {
                r = camera_ray(cam, n % cam->width, n / cam->width);
            } else { /* towards a point of the object's box, where the instance has it at `time` */
                int m = n - camera_rays;
                size_t target = (size_t)m / INSTANCE_CHECK_POINTS;
                struct aabb b = in->object_boxes[in->items[target].object];
                struct transform placed, unplaced; /* object to world at `time`, and back (not needed) */
                if (!instances_transform_at(in, target, time, &placed, &unplaced))
                    continue;
                double share = instance_check_points[m % INSTANCE_CHECK_POINTS];
                vec3 to = transform_point(&placed, vec3_add(b.min, vec3_scale(vec3_sub(b.max, b.min), share)));
                r = (ray){eye, vec3_normalize(vec3_sub(to, eye))};
                if (!vec3_is_finite(r.direction))
                    continue; /* the eye is that point, or the object is empty */
            }
            ok = check_instance_ray(c, in, &every, &r, n, time, expected, got);
        }
    }
    free(every.outside);
    return ok;
}

/* Chapter 16: parses the text again, points every object line at its tiny mesh, places the instances
 * over [0, shutter] with instances_create (a refusal must name the scene) and checks the rays of
 * check_instance_rays there; then refits the top level to [1, 1 + shutter / 2] and checks them there. */
static bool check_instances(struct checker *c, const char *name, const char *text, const struct camera *cam) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, &plane_kind, &box_kind, NULL};
    struct scene s;
    char err[512];
    if (!scene_parse(name, text, kinds, &s, err, sizeof err))
        return broken(c, "the scene is refused the second time: %s", err);
    const char *folder = tiny_mesh_folder();
    bool ok = folder != NULL || broken(c, "cannot write the tiny meshes under /tmp");
    char file[32];
    for (size_t k = 0; ok && k < s.object_count; k++) {
        snprintf(file, sizeof file, "tiny-%zu.obj", (size_t)(tiny_mesh_for(s.objects[k].path) - tiny_meshes));
        ok = replace_path(&s.objects[k].path, folder, file, err, sizeof err) || broken(c, "%s", err);
    }
    struct instances *in = NULL;
    if (ok) {
        in = instances_create(&s, 0, 0.0, s.shutter, err, sizeof err);
        size_t n = strlen(name);
        if (in == NULL && (strncmp(err, name, n) != 0 || err[n] != ':'))
            ok = broken(c, "the instances are refused with a message that does not start with '%s:': %s", name, err);
    }
    size_t faces = 0;
    for (size_t k = 0; in != NULL && k < in->count; k++)
        faces += s.objects[in->items[k].object].mesh.face_count;
    struct crossings expected = {malloc((faces + 1) * sizeof(double)), 0, faces + 1};
    struct crossings got = {malloc((faces + 1) * sizeof(double)), 0, faces + 1};
    if (ok && (expected.t == NULL || got.t == NULL))
        ok = broken(c, "out of memory");
    if (ok && in != NULL) {
        ok = check_instance_rays(c, in, cam, s.eye, &expected, &got);
        if (ok && !instances_set_interval(in, 1.0, 1.0 + 0.5 * s.shutter, INSTANCES_REFIT, err, sizeof err))
            ok = broken(c, "the instances cannot be refitted: %s", err);
        if (ok)
            ok = check_instance_rays(c, in, cam, s.eye, &expected, &got);
    }
    free(expected.t);
    free(got.t);
    instances_free(in);
    scene_free(&s);
    return ok;
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
        /* Chapters 12 to 15 on a smaller picture, with every count that multiplies the work cut. */
        struct camera small;
        int k = structure_for(text);
        s.max_depth = s.max_depth < RENDER_CHECK_SAMPLED_DEPTH ? s.max_depth : RENDER_CHECK_SAMPLED_DEPTH;
        cut_sampling(&s);
        int small_w = cam.width < RENDER_CHECK_SAMPLED_SIDE ? cam.width : RENDER_CHECK_SAMPLED_SIDE;
        int small_h = cam.height < RENDER_CHECK_SAMPLED_SIDE ? cam.height : RENDER_CHECK_SAMPLED_SIDE;
        if (ok && camera_init(&small, s.eye, s.target, s.up, s.fov, small_w, small_h, err, sizeof err))
            ok = check_sampled(&c, &s, &small, k) && check_paths(&c, name, text, k) &&
                 (s.instance_count == 0 || check_instances(&c, name, text, &small));
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

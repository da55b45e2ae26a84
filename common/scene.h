/* scene.h: the scene description and its text file format, docs/scene-format.md (chapter 1).
 *
 * A scene file is parsed into plain data: camera, image size, colours, materials, lights and shapes.
 * Parsing needs no intersection code, so chapter 1 can read the same files as chapter 10: each kind of
 * shape brings the syntax of its line in its header (shape.h), and the kinds are listed in
 * shape_kinds.h. Meshes are only named here (file and transform); chapters that draw them load them
 * with scene_load_meshes. */
#ifndef WHITTED_SCENE_H
#define WHITTED_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "mesh.h"
#include "shape.h"
#include "shape_kinds.h"

#define SCENE_NAME_MAX 64 /* longest material name, including the terminating zero */

struct material {
    char name[SCENE_NAME_MAX];
    vec3 colour;        /* pigment, each channel 0..1 */
    double ambient;     /* share of the ambient light reflected (POV-Ray finish ambient) */
    double diffuse;     /* Lambertian share (finish diffuse) */
    double phong;       /* highlight strength (finish phong) */
    double phong_size;  /* highlight exponent, larger is smaller and sharper (finish phong_size) */
    double reflection;  /* mirror share added on top (finish reflection) */
    double filter;      /* share of light passing through, tinted by colour (pigment filter) */
    double transmit;    /* share of light passing through untinted (pigment transmit) */
    double ior;         /* index of refraction of the inside (interior ior) */
};

struct light {
    vec3 position;
    vec3 colour; /* intensity per channel; no fall-off with distance */
};

/* A `mesh` directive: which file, how to place it, and (once loaded) its triangles in world space. */
struct scene_mesh {
    char *path;          /* resolved relative to the scene file's folder; owned */
    double scale;        /* uniform scale, applied first */
    vec3 rotate;         /* degrees about x, then y, then z, applied second */
    vec3 translate;      /* applied last */
    int material;
    int line;            /* line of the directive, for messages */
    struct mesh mesh;    /* empty until scene_load_meshes */
};

/* The kinds of shape, by their position in shape_kinds.h: SHAPE_SPHERES, SHAPE_TRIANGLES, ... */
#define SHAPE_KIND(type, array, FEATURE, chapter) SHAPE_##FEATURE,
enum shape_kind_index {
#include "shape_kinds.h"
    SHAPE_KIND_COUNT
};
#undef SHAPE_KIND

/* Which kinds of shape a chapter draws, one bit per kind: SCENE_SPHERES, SCENE_TRIANGLES (`triangle`
 * and `mesh`), SCENE_PLANES, SCENE_BOXES, ...; see scene_drop_unsupported. */
#define SHAPE_KIND(type, array, FEATURE, chapter) SCENE_##FEATURE = 1u << SHAPE_##FEATURE,
enum scene_feature {
#include "shape_kinds.h"
};
#undef SHAPE_KIND

/* Every kind of shape introduced up to the chapter: what chapters that search through the world
 * (chapter 5 on) draw, so that a new kind needs no change to them. */
#define SCENE_EVERY_SHAPE (~0u)

/* Every kind of shape, in the order of shape_kinds.h. Defined in scene.c. */
extern const struct shape_kind shape_kinds[SHAPE_KIND_COUNT];

/* The shapes of one kind: an array of count structs of that kind (struct sphere, ...). */
struct scene_shapes {
    void *items;
    size_t count;
};

struct scene {
    char *path; /* the file it was read from; owned */
    vec3 eye, target, up;
    double fov;           /* vertical field of view, degrees */
    int width, height;    /* image size in pixels */
    vec3 background;      /* colour of rays that hit nothing */
    vec3 ambient_light;   /* global ambient light (POV-Ray ambient_light), default 1 1 1 */
    int max_depth;        /* the deepest ray level traced, POV-Ray's max_trace_level: the camera ray is
                           * level 1, and a ray of level max_depth + 1 is black */
    bool shadow_offset;   /* false: shadow rays accept hits from t > 0 (chapter 7's acne demo) */
    double adc_bailout;   /* secondary rays weighing less are not traced (POV-Ray's adc_bailout), 0..1 */

    struct material *materials; size_t material_count; /* materials[0] is "default" */
    struct light *lights;       size_t light_count;
    struct scene_mesh *meshes;  size_t mesh_count;
    /* The shapes, one array per kind, seen two ways: by kind, shapes[SHAPE_SPHERES], for code that
     * treats every kind alike; and by name, spheres and sphere_count, for code about one kind. */
    union {
        struct scene_shapes shapes[SHAPE_KIND_COUNT];
        struct {
#define SHAPE_KIND(type, array, FEATURE, chapter) struct type *array; size_t type##_count;
#include "shape_kinds.h"
#undef SHAPE_KIND
        };
    };
};

/* Reads the scene file at `path` into *s. On success returns true; free *s with scene_free. On
 * failure returns false, leaves *s empty and writes "file:line: what is wrong" into err. Mesh files
 * are not opened here (see scene_load_meshes). */
bool scene_load(const char *path, struct scene *s, char *err, size_t err_size);

/* Reads the scene file at `path` whole, as scene_load does before parsing it. Returns a malloc'd,
 * zero-terminated string (the caller frees it), or NULL with "file: what is wrong" in err when the file
 * cannot be read, is not a regular file, is too large or holds a zero byte. */
char *scene_read_text(const char *path, char *err, size_t err_size);

/* Parses scene text held in memory, as scene_load does for a file; `name` is used in messages and to
 * resolve mesh paths (relative to its folder). Same results and ownership as scene_load. */
bool scene_parse(const char *name, const char *text, struct scene *s, char *err, size_t err_size);

/* Frees everything *s owns (meshes included) and leaves it empty. Safe on an empty scene. */
void scene_free(struct scene *s);

/* Loads the file of every mesh directive and moves its vertices into world space (scale, rotate,
 * translate). Returns false at the first file that fails, with the mesh reader's "file:line: what is
 * wrong" in err; meshes loaded so far stay owned by *s. Defined in scene_meshes.c (chapter 3 on). */
bool scene_load_meshes(struct scene *s, char *err, size_t err_size);

/* Removes the shapes of every kind not in `supported` (a mask of enum scene_feature) or introduced
 * after `chapter` (meshes go with SCENE_TRIANGLES), so that a chapter can read any scene file and draw
 * what it knows. If something was removed, prints one line to `note` (when not NULL) saying what was
 * ignored, e.g. "scene.txt: chapter 2 ignores 3 triangles, 1 plane (not introduced yet)". */
void scene_drop_unsupported(struct scene *s, unsigned supported, int chapter, FILE *note);

/* Returns the index of the material called `name`, or -1 if there is none. */
int scene_find_material(const struct scene *s, const char *name);

#endif

/* scene.h: the scene description and its text file format, docs/scene-format.md (chapter 1).
 *
 * A scene file is parsed into plain data: camera, image size, colours, materials, lights and shapes.
 * Parsing needs no intersection code, so chapter 1 can read the same files as chapter 10: each kind of
 * shape brings the syntax of its line (struct shape_syntax, shape.h), and the reader knows the kinds
 * listed in scene_syntaxes[] and those the program draws. Meshes are only named here (file and
 * transform); chapters that draw them load them with scene_load_meshes. */
#ifndef WHITTED_SCENE_H
#define WHITTED_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "antialias.h"
#include "area_light.h"
#include "instance_syntax.h"
#include "lens.h"
#include "mesh.h"
#include "path_settings.h"
#include "pigment.h"
#include "shape.h"

/* The brightest light colour or emission, in each channel: a sum of powers (emission times area, over
 * every emitter) stays finite. */
#define SCENE_MAX_LIGHT 1e18
/* A material's ior lies within these, so that the ratio of two, squared (Snell's law and Fresnel's
 * equations square it), stays far within double's range: at 1e-155 the square of 1e155 overflowed,
 * and a refraction head-on (sine 0 times infinity) gave chapter 17 NaN pixels. */
#define SCENE_MIN_IOR 1e-50
#define SCENE_MAX_IOR 1e50
/* The bytes of U+FEFF, the byte-order mark, as UTF-8: some editors start a file with it, and the reader
 * skips it at the start of the text (it is no part of the first line's first word). */
#define SCENE_UTF8_BOM "\xef\xbb\xbf"
#define SCENE_NAME_MAX 64 /* longest material name, including the terminating zero */
#define ROUGH_CHAPTER 17  /* the chapter that draws a material's roughness, metal and lobe */

/* How a rough mirror's reflectance varies with the angle (chapter 17, the material's `metal` key). */
enum scene_metal {
    SCENE_METAL_NONE,   /* `reflection` at every angle, untinted: chapter 15's mirror */
    SCENE_METAL_COLOUR, /* Schlick's Fresnel from reflection * colour at normal incidence */
    SCENE_METAL_GOLD,   /* Fresnel's equations from the metal's complex index, per channel */
    SCENE_METAL_SILVER,
    SCENE_METAL_COPPER,
    SCENE_METAL_ALUMINIUM,
    SCENE_METAL_COUNT
};
/* The words of the `metal` key, in the order of enum scene_metal ("none" first). */
extern const char *const scene_metal_names[SCENE_METAL_COUNT];

/* The shape of a rough surface's highlight (chapter 17, the material's `lobe` key). */
enum scene_lobe { SCENE_LOBE_GGX, SCENE_LOBE_PHONG };

struct material {
    char name[SCENE_NAME_MAX];
    vec3 colour;        /* each channel 0..KEY_MAX_SURFACE (0..1 for chapters 15 and 17, bsdf.h) */
    double ambient;     /* share of the ambient light reflected (POV-Ray finish ambient) */
    double diffuse;     /* Lambertian share (finish diffuse) */
    double phong;       /* highlight strength (finish phong) */
    double phong_size;  /* highlight exponent, larger is smaller and sharper (finish phong_size) */
    double reflection;  /* mirror share added on top (finish reflection) */
    double filter;      /* share of light passing through, tinted by colour (pigment filter) */
    double transmit;    /* share of light passing through untinted (pigment transmit) */
    double ior;         /* index of refraction of the inside (interior ior) */
    int pigment;        /* index into scene.pigments, or -1: the plain colour (chapter 14; pigment.h) */
    vec3 emission;      /* radiance the surface gives off, from both faces (chapter 15; 0 0 0: none) */
    double roughness;   /* 0..1: 0 the smooth mirror and glass of chapter 15, 1 the roughest (chapter 17) */
    enum scene_metal metal; /* the rough mirror's Fresnel (chapter 17; SCENE_METAL_NONE: constant) */
    enum scene_lobe lobe;   /* the rough surface's distribution (chapter 17; default SCENE_LOBE_GGX) */
    int line;               /* the scene file's line, for messages (0: the default material) */
};

/* True when light passes through material m (a filter or a transmit above 0): a shape of it is glass,
 * with an inside a ray can be in (interior.c), and its shadows are filtered. */
static inline bool material_passes_light(const struct material *m) { return m->filter > 0.0 || m->transmit > 0.0; }

struct light {
    vec3 position; /* of the point light, or of an area light's centre */
    vec3 colour;   /* intensity per channel; no fall-off with distance */
    struct area_light area; /* a point light unless area_light_is_area (chapter 13) */
    int line;               /* the line of the scene file it was read from */
};

/* A `mesh` directive: which file, how to place it, and (once loaded) its triangles in world space. */
struct scene_mesh {
    char *path;          /* resolved relative to the scene file's folder; owned */
    double scale;        /* uniform scale, applied first */
    vec3 rotate;         /* degrees about x, then y, then z, applied second */
    vec3 translate;      /* applied last */
    int material;
    int smooth;          /* chapter 14: SCENE_SMOOTH_FILE, _OFF or _ON (mesh_surface.h) */
    int line;            /* line of the directive, for messages */
    struct mesh mesh;    /* empty until scene_load_meshes */
    struct mesh_corners corners; /* the file's normals and (u, v), world space; chapter 14 only (mesh.h) */
};

/* An `object` line (chapter 16): a mesh defined once in its own space, drawn only where an `instance`
 * line places it. */
struct scene_object {
    char name[SCENE_NAME_MAX];
    char *path;          /* resolved relative to the scene file's folder; owned */
    int smooth;          /* SCENE_SMOOTH_FILE, _OFF or _ON, as the mesh line's */
    int line;
    struct mesh mesh;    /* object space; empty until loaded (instances.h) */
};

/* An `instance` line (chapter 16) with the `key` lines that move it. */
struct scene_instance {
    int object;          /* index into scene.objects */
    int material;
    char id[SCENE_NAME_MAX]; /* its label for key lines; "" without one */
    struct scene_pose pose;  /* the instance line's own pose, used when it has no keys */
    struct scene_key *keys;  /* in increasing time; owned; NULL when key_count is 0 */
    size_t key_count;
    int line;
};

/* How chapter 14 draws a mesh (the mesh line's `smooth` key): with the file's normals when it has them
 * (no key), flat whatever the file says (off), or smooth, averaging the faces' normals at each vertex
 * when the file has none (on). */
enum { SCENE_SMOOTH_FILE, SCENE_SMOOTH_OFF, SCENE_SMOOTH_ON };

/* The kinds of shape every chapter reads, whether it draws them or not: the lines of spheres,
 * triangles, planes and boxes, in this order, ending with NULL. Defined in scene.c. */
extern const struct shape_syntax *const scene_syntaxes[];

#define SCENE_KIND_MAX 16 /* the most kinds of shape one scene holds */

/* The shapes of one kind in a scene. */
struct shape_list {
    const struct shape_syntax *syntax; /* the kind's line: its keyword, the size of one shape, ... */
    const struct shape_kind *kind;     /* the kind's ray queries if the program draws it, else NULL */
    void *items;                       /* `count` structs of the kind (struct sphere, ...); owned */
    size_t count;
};

struct scene;

/* Chapter 14's hook (texture.h): returns the material of the hit *h at `point` as the surface is there,
 * either the scene's own material or `painted`, filled from it with its pigment's colour (and an image's
 * alpha as transmit); and replaces h->normal by the interpolated normal where a mesh is smooth. NULL
 * before chapter 14: materials are plain and triangles flat. */
typedef const struct material *(*scene_paint_fn)(const struct scene *s, struct hit *h, vec3 point,
                                                 struct material *painted);

/* Chapter 16's measure of its instances (instances_bounds): grows the box [*min, *max] by the world box
 * of every instance `placed` holds, as placed for the picture (a moving one over the shutter), and
 * returns true when there is one. */
typedef bool (*scene_bounds_fn)(const void *placed, vec3 *min, vec3 *max);

struct scene {
    char *path; /* the file it was read from; owned */
    vec3 eye, target, up;
    double fov;           /* vertical field of view, degrees */
    struct lens lens;     /* the camera's lens (chapter 13); a pinhole without its keys */
    int width, height;    /* image size in pixels */
    vec3 background;      /* colour of rays that hit nothing */
    int background_line;  /* the background line's line in the file, 0 without one */
    vec3 ambient_light;   /* global ambient light (POV-Ray ambient_light), default 1 1 1 */
    int max_depth;        /* the deepest ray level traced, POV-Ray's max_trace_level: the camera ray is
                           * level 1, and a ray of level max_depth + 1 is black */
    bool shadow_offset;   /* false: shadow rays accept hits from t > 0 (chapter 7's acne demo) */
    double adc_bailout;   /* secondary rays weighing less are not traced (POV-Ray's adc_bailout), 0..1 */
    struct antialias antialias; /* camera rays per pixel (chapter 12); method NONE without the line */
    struct path_settings paths; /* how chapter 15 traces paths; the defaults without the line */
    double shutter;       /* the camera's exposure in clock units, 0..1 (chapter 16); 0: no motion blur */

    struct material *materials; size_t material_count; /* materials[0] is "default" */
    struct light *lights;       size_t light_count;
    struct scene_mesh *meshes;  size_t mesh_count;
    struct pigment *pigments;   size_t pigment_count; /* the pigment lines (chapter 14 draws them) */
    struct scene_object *objects;     size_t object_count;   /* the object lines (chapter 16) */
    struct scene_instance *instances; size_t instance_count; /* the instance lines with their keys */
    scene_paint_fn paint;       /* set by chapter 14 (texture.h); NULL: plain materials, flat triangles */
    scene_paint_fn shadow_paint; /* chapter 14: the same for a surface a shadow ray crosses (shadow.c);
                                  * NULL: a shadow is filtered by the material's plain colour */
    scene_bounds_fn instance_bounds; /* chapter 16, once its instances are placed (instances.h); NULL: the
                                      * scene's extent has no instances in it (scene_scale.h) */
    const void *placed_instances;    /* what instance_bounds measures */
    /* The shapes, one list per kind: the kinds of scene_syntaxes[] in that order, then the other kinds
     * the program draws, in the order it lists them. A list may be empty. */
    struct shape_list shapes[SCENE_KIND_MAX];
    size_t kind_count;
};

/* Reads the scene file at `path` into *s. `kinds` lists the kinds of shape the program draws, ending
 * with NULL (NULL for none): their lists get their `kind`, and a kind not in scene_syntaxes[] (a new
 * one, like the disc of chapter 2's exercises) is read too. On success returns true; free *s with
 * scene_free. On failure returns false, leaves *s empty and writes "file:line: what is wrong" into
 * err. Mesh files are not opened here (see scene_load_meshes). */
bool scene_load(const char *path, const struct shape_kind *const *kinds, struct scene *s, char *err,
                size_t err_size);

/* Reads the scene file at `path` whole, as scene_load does before parsing it. Returns a malloc'd,
 * zero-terminated string (the caller frees it), or NULL with "file: what is wrong" in err when the file
 * cannot be read, is not a regular file, is too large or holds a zero byte. */
char *scene_read_text(const char *path, char *err, size_t err_size);

/* Parses scene text held in memory, as scene_load does for a file; `name` is used in messages and to
 * resolve mesh paths (relative to its folder). Same results and ownership as scene_load. */
bool scene_parse(const char *name, const char *text, const struct shape_kind *const *kinds, struct scene *s,
                 char *err, size_t err_size);

/* Frees everything *s owns (meshes included) and leaves it empty. Safe on an empty scene. */
void scene_free(struct scene *s);

/* Loads the file of every mesh directive and moves its vertices into world space (scale, rotate,
 * translate). The normals and texture coordinates of the files are kept only when s->paint is set
 * (chapter 14, which draws them); before, they are dropped and every mesh is flat, in the twin too. Returns false at the first file that fails, with the mesh reader's "file:line: what is
 * wrong" in err; meshes loaded so far stay owned by *s. Defined in scene_meshes.c (chapter 3 on). */
bool scene_load_meshes(struct scene *s, char *err, size_t err_size);

/* Removes the shapes of every kind the program does not draw (a list without its kind; the meshes go
 * with the triangles), before chapter 12 the antialias line, before chapter 13 the area of area lights
 * (each becomes a point light at its centre) and the camera's lens (a pinhole again), and before chapter
 * 14 the pigments (every material is then its plain colour), before chapter 15 the paths line and the
 * materials' emission, before chapter 17 the materials' roughness, metal and lobe (every mirror and
 * glass smooth again), in every chapter but 16 the objects, instances (with their keys) and the camera's
 * shutter, so that chapter `chapter` can read any
 * scene file and draw what it knows. If something was removed, prints one line to `note` (when not
 * NULL) saying what was ignored, e.g.
 * "scene.txt: chapter 2 ignores 3 triangles, 1 plane (not introduced yet)". */
void scene_drop_unsupported(struct scene *s, int chapter, FILE *note);

/* Returns the list of the shapes whose line is `syntax` (one of scene_syntaxes[], or a drawn kind's),
 * or NULL when s has none. The kinds of scene_syntaxes[] always have a list, perhaps empty. */
const struct shape_list *scene_shapes(const struct scene *s, const struct shape_syntax *syntax);

/* Returns the index of the material called `name`, or -1 if there is none. */
int scene_find_material(const struct scene *s, const char *name);

#endif

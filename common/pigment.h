/* pigment.h: the scene's `pigment` lines, colours that vary over a surface (read from chapter 1 on,
 * drawn by chapter 14; docs/14-textures.md).
 *
 *   pigment floor checker colour 1 1 1 colour2 0.1 0.1 0.1 scale 0.5 0.5 0.5
 *   pigment bands gradient axis 0 1 0 colour 1 0 0 colour2 0 0 1
 *   pigment wall brick colour 0.8 0.8 0.8 colour2 0.6 0.2 0.1 brick_size 1 0.5 0.5 mortar 0.05
 *   pigment fan radial colour 1 1 0 colour2 0 0 1 rotate 0 0 90
 *   pigment earth image_map file earth.png map spherical interpolate 2 wrap repeat
 *   pigment skin image_map file grid.png map uv      (a mesh's corners' (u, v), a box's cross: uv_mapping)
 *   material floor pigment floor diffuse 0.8
 *
 * Like the antialias line (antialias.h), a pigment is plain data read with every scene, so that any
 * chapter reads any scene; the chapters before 14 ignore it (scene_drop_unsupported) and draw the
 * material's own colour. Every pattern takes the texture transform `scale X Y Z`, `rotate X Y Z`
 * (degrees about x, then y, then z) and `translate X Y Z`, applied in that order as POV-Ray applies
 * them to a texture: the pattern is evaluated at the surface point carried back through the inverse.
 * The evaluation is chapter 14's, in texture.c; the image file is read there too (image_map.c). */
#ifndef WHITTED_PIGMENT_H
#define WHITTED_PIGMENT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "shape.h"

#define TEXTURE_CHAPTER 14 /* the chapter that draws pigments */
#define PIGMENT_NAME_MAX 64 /* longest pigment name, including the terminating zero */

enum pigment_pattern {
    PIGMENT_CHECKER,   /* unit cubes alternating colour and colour2 */
    PIGMENT_GRADIENT,  /* colour to colour2 along an axis, repeating every unit */
    PIGMENT_BRICK,     /* bricks of colour2 laid in mortar of colour */
    PIGMENT_RADIAL,    /* colour to colour2 once round the y axis */
    PIGMENT_IMAGE_MAP, /* a picture, wrapped over the surface by a mapping */
};

/* How an image map's (u, v) are found from a point (POV-Ray's map_type). */
enum pigment_mapping {
    PIGMENT_MAP_PLANAR = 0,    /* u = x, v = y: the image lies on the unit square of the x-y plane */
    PIGMENT_MAP_SPHERICAL = 1, /* u = longitude round y, v = latitude: the image wraps a sphere at 0 */
};

/* The pixels of an image map once chapter 14 has read the file (image_map.c): linear light. */
struct pigment_image {
    int width, height;
    float *texels; /* width * height * 4 floats (red, green, blue, alpha), top row first; owned unless borrowed */
    bool opaque;   /* every alpha is 1: the file has no alpha channel, or every pixel's is at its largest */
    bool borrowed; /* texels are an earlier pigment's, read from the same file (texture_load_images) */
    bool colour_key; /* a grey or RGB PNG whose tRNS chunk names a colour drawn transparent (POV-Ray 3.7
                        ignores it, and crashes on a grey file's: the twin is refused, povray.c) */
};

struct pigment {
    char name[PIGMENT_NAME_MAX];
    enum pigment_pattern pattern;
    vec3 colour[2];   /* checker: the two cubes; gradient, radial: values 0 and 1; brick: mortar, brick */
    vec3 axis;        /* gradient: the unit direction it grows along */
    vec3 brick_size;  /* brick: one brick and its share of mortar, POV-Ray's default 8 3 4.5 */
    double mortar;    /* brick: the mortar's width, POV-Ray's default 0.5 */
    vec3 scale, rotate, translate; /* the texture transform: scale, then rotate (degrees), then translate */
    /* image_map only: */
    char *file;                 /* the image's path, resolved relative to the scene file; owned */
    enum pigment_mapping mapping;
    bool uv_mapping;            /* `map uv`: at the surface's (u, v, 0) (mesh corners, box cross), then planar */
    int interpolate;            /* 0: the nearest pixel; 2: bilinear (POV-Ray's interpolate 0 and 2) */
    bool once;                  /* true: one copy, transparent outside it; false: repeated */
    struct pigment_image image; /* empty until chapter 14 reads it (texture_load_images) */
    int line;                   /* the scene file's line, for messages */
};

/* One pattern's line: its word and the keys it takes besides the texture transform. */
struct pigment_syntax {
    const char *pattern; /* the word after the name, e.g. "checker" */
    const struct key_spec *keys;
    int key_count;
    const int *required; /* indices into keys that must be given, ending with -1 */
    /* Fills the pattern's fields of *p from the values read for `keys` (the transform is filled by the
     * parser). Returns false with the reason in why (without file and line) when they make no pigment. */
    bool (*make)(const struct key_values *kv, struct pigment *p, char *why, size_t why_size);
};

/* The patterns a scene may name, ending with NULL. */
extern const struct pigment_syntax *const pigment_syntaxes[];

/* The texture transform's keys, which every pattern takes after its own. */
#define PIGMENT_TRANSFORM_KEY_COUNT 3
extern const struct key_spec pigment_transform_keys[PIGMENT_TRANSFORM_KEY_COUNT];

/* The texture transform's limits, so that the point it makes of any point of the scene stays finite
 * (and a turn's sine keeps some precision). */
#define PIGMENT_MIN_SCALE 1e-9  /* each scale's size at least this, at most PIGMENT_MAX_SCALE */
#define PIGMENT_MAX_SCALE 1e9
#define PIGMENT_MAX_TURN 1e6    /* degrees each way about each axis */

/* Fills the transform of *p from the values of pigment_transform_keys, which the parser read at
 * positions first .. first + 2 of kv; keys not given leave the identity. Returns false with the reason
 * in why for a scale with a zero component or out of range, a turn beyond PIGMENT_MAX_TURN or a move
 * beyond KEY_MAX_COORD. */
bool pigment_make_transform(const struct key_values *kv, int first, struct pigment *p, char *why, size_t why_size);

/* Returns true when the image file's name ends in .jpg or .jpeg (either case): POV-Ray's twin names it
 * `jpeg`, every other `png`, so chapter 14 refuses a file whose bytes say otherwise. */
bool pigment_file_is_jpeg(const char *file);

/* The path by which the twin names p's image file: its whole path, written into `whole` (PATH_MAX bytes),
 * so that POV-Ray finds the file from whichever folder it runs in; p->file when it does not resolve. */
const char *pigment_twin_file(const struct pigment *p, char *whole);

/* Returns true when `path` can stand in a POV-Ray string as it is: it holds no quote and no backslash,
 * which POV-Ray reads as the string's own syntax, and no control character (a line break would end the
 * twin's line). A scene's file name is checked when it is read; the folders of a whole path are not. */
bool pigment_twin_file_writable(const char *path);

/* Writes p as POV-Ray's `pigment { ... }`, every colour as rgbft with the given filter and transmit
 * (the material's), the transform last. An image map names its file by pigment_twin_file. */
void pigment_write_pov(FILE *out, const struct pigment *p, double filter, double transmit);

#endif

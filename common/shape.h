/* shape.h: what every kind of shape tells the rest of the tracer about itself (chapter 1).
 *
 * A kind of shape (sphere, triangle, plane, box, ...) is one module, e.g. sphere.h and sphere.c, and
 * one line in shape_kinds.h that includes its header. The module has two halves, because a chapter
 * links only the modules of chapters up to its own while every chapter reads every scene:
 *
 *  - its syntax, in the header: the keys of its scene-file line, how they become the shape's struct,
 *    and how the shape is written for POV-Ray (struct shape_syntax). It is plain arithmetic, compiled
 *    into the scene reader of chapter 1, so chapter 1 reads spheres without any intersection code;
 *  - its behaviour, in the .c file: the nearest hit, every crossing and the bounding box over an
 *    array of its shapes (struct shape_behaviour), linked from the chapter that introduces it.
 *
 * The header ends with its registration, outside the include guard:
 *     SHAPE_KIND(sphere, spheres, SPHERES, 2)
 * the struct's name (also the directive's keyword), the name of its array in struct scene (also the
 * plural in messages), its feature bit (SCENE_SPHERES) and the chapter that introduces it. scene.h
 * and scene.c expand these lines into the scene's arrays and the table shape_kinds[]. */
#ifndef WHITTED_SHAPE_H
#define WHITTED_SHAPE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "hit.h"
#include "ray.h"

/* ---- syntax: the scene-file line (chapter 1) --------------------------------------------------- */

/* One key a directive accepts: its name and how many numbers follow it (0 = one word, not a number). */
struct key_spec {
    const char *name;
    int count;
};

#define KEY_MAX 10          /* no directive has more keys */
#define KEY_MAX_NUMBERS 3   /* no key takes more numbers */

/* The values found for each key of a table, by position in the table. */
struct key_values {
    bool present[KEY_MAX];
    double number[KEY_MAX][KEY_MAX_NUMBERS];
    const char *word[KEY_MAX];
};

/* Returns the three numbers of key `key` as a vector. */
static inline vec3 key_vec3(const struct key_values *kv, int key) {
    return vec3_make(kv->number[key][0], kv->number[key][1], kv->number[key][2]);
}

/* Writes a vector as POV-Ray's <x, y, z>, with 17 significant digits so that POV-Ray reads back the
 * very doubles we use. */
static inline void shape_write_vector(FILE *out, vec3 v) { fprintf(out, "<%.17g, %.17g, %.17g>", v.x, v.y, v.z); }

struct shape_syntax {
    /* The keys of the directive besides `material`, which every shape takes (the parser adds it and
     * stores the material's index in the shape's `material` field). */
    const struct key_spec *keys;
    int key_count;
    const int *required; /* indices into keys that must be given, ending with -1 */
    /* Fills the shape *item (zeroed, of the kind's size) from the values read for `keys`. Returns
     * false with the reason in why (without file and line: the parser adds them) when the values make
     * no shape, e.g. "sphere radius must be positive, got 0". */
    bool (*make)(const struct key_values *kv, void *item, char *why, size_t why_size);
    /* Writes the shape as POV-Ray's object up to its texture, e.g. "sphere { <0, 1, 0>, 0.5"; the
     * caller writes the texture and the closing brace. */
    void (*write_pov)(FILE *out, const void *item);
};

/* ---- behaviour: ray queries over an array of shapes (the chapter that introduces the kind) ----- */

/* Called for one crossing of a surface at distance t; returns false to stop the enumeration. */
typedef bool (*shape_crossing_visitor)(void *context, double t, int material);

struct shape_behaviour {
    /* Tests r against items[0..count) for hits with t_min < t < h->t and keeps the nearest in *h (t,
     * the shape's own normal, material). Returns true when *h was replaced. */
    bool (*closest)(const void *items, size_t count, const ray *r, double t_min, struct hit *h);
    /* Calls visit(context, t, material) for every crossing of a surface of items[0..count) by r with
     * t_min < t < t_max (both crossings of a closed shape). Returns false as soon as visit does. */
    bool (*crossings)(const void *items, size_t count, const ray *r, double t_min, double t_max,
                      shape_crossing_visitor visit, void *context);
    /* Stores the smallest axis-aligned box holding *item in *min and *max and returns true; returns
     * false for a shape without one (an infinite plane). */
    bool (*bounds)(const void *item, vec3 *min, vec3 *max);
};

/* ---- the registry entry ------------------------------------------------------------------------ */

/* One kind of shape as the table shape_kinds[] (scene.h) holds it. */
struct shape_kind {
    const char *keyword;    /* the directive, e.g. "sphere"; also one shape in messages */
    const char *plural;     /* e.g. "spheres": several shapes in messages, and the array's name */
    int chapter;            /* the chapter that introduces it */
    unsigned feature;       /* its bit of enum scene_feature */
    size_t size;            /* sizeof one shape */
    size_t material_offset; /* offsetof its `int material` field */
    const struct shape_syntax *syntax;
    /* NULL in a program that does not link the kind's module (chapter 1 links none). */
    const struct shape_behaviour *behaviour;
};

#endif

/* shape.h: what a kind of shape (sphere, triangle, plane, box, ...) tells the rest of the tracer about
 * itself, in two tables (chapter 1).
 *
 * A kind of shape is one module: sphere.h declares struct sphere and the two tables, sphere_syntax.c
 * fills the first and sphere.c the second.
 *
 *  - struct shape_syntax, the kind's scene-file line: its keyword, its keys, how they make the shape's
 *    struct, and how the shape is written for POV-Ray. It is plain arithmetic, linked from chapter 1 on,
 *    because every chapter reads every scene: chapter 1 reads spheres, and ignores them, without any
 *    intersection code. The scene reader knows the lines of the kinds in its list (scene.c).
 *  - struct shape_kind, the kind's ray queries over an array of its shapes: the nearest hit, every
 *    crossing, the bounding box, whether a point is inside. It is linked from the chapter that
 *    introduces the kind, and it points at the kind's syntax.
 *
 * A chapter's main.c lists the kinds it draws, e.g. chapter 3's
 *     static const struct shape_kind *const kinds[] = {&sphere_kind, &triangle_kind, NULL};
 * and hands the list to the scene reader (cli_start). The scene keeps one struct shape_list per kind,
 * and every place that treats the kinds alike (the world's searches, the interior list, the scale
 * warning, the POV-Ray twin) goes through these tables. So a new kind is a new module and one line in
 * the list of each chapter that draws it (docs/02-sphere.md, "One module per kind of shape"). */
#ifndef WHITTED_SHAPE_H
#define WHITTED_SHAPE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ray.h"

struct hit; /* hit.h (chapter 2): what the nearest-hit search of a kind fills in */

/* ---- the scene-file line (chapter 1) ----------------------------------------------------------- */

/* One key a directive accepts: its name and how many numbers follow it (0 = one word, not a number). */
struct key_spec {
    const char *name;
    int count;
};

#define KEY_MAX 14          /* no directive has more keys (a material has 14) */
#define KEY_MAX_NUMBERS 3   /* no key takes more numbers */

/* The values found for each key of a table, by position in the table. */
struct key_values {
    bool present[KEY_MAX];
    double number[KEY_MAX][KEY_MAX_NUMBERS];
    const char *word[KEY_MAX];
};

/* How a message shows a number read from the scene ("got 1048577"): KEY_NUMBER_SHOWN in the format,
 * KEY_NUMBER(x) in the arguments. 15 significant digits, so that a whole number up to 10^15 and any
 * decimal written with 15 digits or fewer print as they were written (%g's six would print 1048577 as
 * 1.04858e+06, which looks in range); 16 or 17 where 15 would round x to another number, so that a
 * value just past a limit never prints as the limit (1.0000000000000002 is not "1"). */
#define KEY_NUMBER_SHOWN "%.*g"
#define KEY_NUMBER(x) key_number_digits(x), (x)

/* The fewest significant digits, from 15 to 17, that print x as a number that reads back as x (17
 * always do; a NaN or an infinity takes 17, and prints as nan or inf). */
static inline int key_number_digits(double x) {
    for (int digits = 15; digits < 17; digits++) {
        char text[32];
        snprintf(text, sizeof text, "%.*g", digits, x);
        if (strtod(text, NULL) == x)
            return digits;
    }
    return 17;
}

/* The largest coordinate a point of the scene may have: a corner, a placed mesh's vertex, a focal
 * point, a texture's move. Within it, what the program derives (sums and differences of points,
 * lengths, boxes in float: triangle.h says why 1e18) stays finite. */
#define KEY_MAX_COORD 1e18

/* The largest share a surface may give: each channel of a colour (a material's, a pigment's), and a
 * material's ambient, diffuse, phong and reflection. A real surface gives back at most the light that
 * reaches it (1), and POV-Ray scenes go a little above 1 for a glow; at most 100, the weight of a ray
 * 64 reflections or refractions deep (max_depth's most) stays below 100^64 = 1e128, far inside
 * double's range, where a colour of 1e300 seen through glass twice was infinite. */
#define KEY_MAX_SURFACE 100.0

/* Returns true when every component of v is within -limit .. limit; otherwise false (NaN included), with
 * "WHAT is (x, y, z); it must stay within -limit .. limit" in why. For every vector a key gives, or that
 * is derived from keys, that must stay finite through what is computed from it. */
static inline bool key_vec3_within(vec3 v, double limit, const char *what, char *why, size_t why_size) {
    if (fabs(v.x) <= limit && fabs(v.y) <= limit && fabs(v.z) <= limit)
        return true;
    snprintf(why, why_size, "%s is (" KEY_NUMBER_SHOWN ", " KEY_NUMBER_SHOWN ", " KEY_NUMBER_SHOWN
             "); it must stay within -%g .. %g", what, KEY_NUMBER(v.x), KEY_NUMBER(v.y), KEY_NUMBER(v.z), limit, limit);
    return false;
}

/* Returns the three numbers of key `key` as a vector. */
static inline vec3 key_vec3(const struct key_values *kv, int key) {
    return vec3_make(kv->number[key][0], kv->number[key][1], kv->number[key][2]);
}

/* Writes a vector as POV-Ray's <x, y, z>, with 17 significant digits so that POV-Ray reads back the
 * very doubles we use. */
static inline void shape_write_vector(FILE *out, vec3 v) { fprintf(out, "<%.17g, %.17g, %.17g>", v.x, v.y, v.z); }

struct shape_syntax {
    const char *keyword;    /* the directive, e.g. "sphere"; also one shape in messages */
    const char *plural;     /* e.g. "spheres": several shapes in messages */
    size_t size;            /* sizeof one shape, e.g. sizeof(struct sphere) */
    size_t material_offset; /* offsetof its `int material` field */
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
    /* The shape has surface coordinates (u, v) for an image map's `map uv` (chapter 14: a box's); the
     * others are painted at (0, 0) there, and POV-Ray's rules for them differ (povray_can_express). */
    bool surface_uv;
};

/* Returns the index-th shape of an array of shapes of one kind (a struct sphere *, ...). */
static inline const void *shape_item(const struct shape_syntax *syntax, const void *items, size_t index) {
    return (const char *)items + index * syntax->size;
}

/* Returns the material of the shape `item` of a kind with this syntax. */
static inline int shape_material(const struct shape_syntax *syntax, const void *item) {
    int material;
    memcpy(&material, (const char *)item + syntax->material_offset, sizeof material);
    return material;
}

/* ---- the ray queries (the chapter that introduces the kind) ----------------------------------- */

/* Called for one crossing of a surface at distance t; returns false to stop the enumeration. */
typedef bool (*shape_crossing_visitor)(void *context, double t, int material);

struct shape_kind {
    const struct shape_syntax *syntax; /* its scene-file line */
    /* Tests r against items[0..count) for hits with t_min < t < h->t and keeps the nearest in *h (t,
     * the shape's own normal, material, and in h->object its index in items). Returns true when *h
     * was replaced. */
    bool (*closest)(const void *items, size_t count, const ray *r, double t_min, struct hit *h);
    /* Calls visit(context, t, material) for every crossing of a surface of items[0..count) by r with
     * t_min < t < t_max (both crossings of a closed shape). Returns false as soon as visit does. */
    bool (*crossings)(const void *items, size_t count, const ray *r, double t_min, double t_max,
                      shape_crossing_visitor visit, void *context);
    /* Stores the smallest axis-aligned box holding *item in *min and *max and returns true; returns
     * false for a shape without one (an infinite plane). */
    bool (*bounds)(const void *item, vec3 *min, vec3 *max);
    /* Returns true when `point` is inside *item (a plane: on the side its normal points away from), as
     * POV-Ray decides for a camera inside glass (chapter 8); NULL for a kind without an inside (a
     * single triangle). */
    bool (*contains)(const void *item, vec3 point);
};

#endif

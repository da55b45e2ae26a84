/* area_light.h: the keys of a light line that make it an area light, a rectangle of point lights
 * (read from chapter 1 on, drawn by chapter 13; docs/13-distributed.md).
 *
 *   light position 0 6 2  colour 1 1 1  axis1 2 0 0  axis2 0 0 2  samples 5 5  adaptive 1
 *
 * The light is then POV-Ray 3.7's `area_light <axis1>, <axis2>, n1, n2`: n1 x n2 point lights on a
 * grid over the parallelogram centred at `position` with sides axis1 and axis2, the first and last
 * on its edges (jitter off). Like the antialias line (antialias.h) the settings are plain data read
 * with every scene, so that any chapter reads any scene; before chapter 13 the light is a point light
 * at its centre (scene_drop_unsupported). The sampling itself is chapter 13's, in soft_shadow.c. */
#ifndef WHITTED_AREA_LIGHT_H
#define WHITTED_AREA_LIGHT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "shape.h"

#define AREA_LIGHT_CHAPTER 13    /* the chapter that draws it */
#define AREA_LIGHT_MAX_SIZE 33   /* point lights a side: 33 x 33 = 1089 shadow rays a point at most */
#define AREA_LIGHT_MAX_ADAPTIVE 16 /* deeper levels than 2^16 points a side change nothing */
#define AREA_LIGHT_NOT_ADAPTIVE (-1) /* no adaptive key: every point of the grid is traced */
/* Axes closer to parallel than this (|a1 x a2| below it times |a1| |a2|) span no rectangle. */
#define AREA_LIGHT_MIN_SINE 1e-9
/* The shortest axis (and the longest: each coordinate within KEY_MAX_COORD), so that the light's
 * rectangle, its area and the lengths derived from it stay finite and not zero. */
#define AREA_LIGHT_MIN_AXIS 1e-18

struct area_light {
    vec3 axis1, axis2; /* the sides of the parallelogram */
    int size1, size2;  /* point lights along axis1 and axis2; 0 for a point light */
    int adaptive;      /* POV-Ray's adaptive level, or AREA_LIGHT_NOT_ADAPTIVE */
    bool circular;     /* the grid squeezed into an ellipse (POV-Ray's circular) */
    bool orient;       /* the ellipse turned to face each lit point (POV-Ray's orient; needs circular) */
};

/* The keys a light line may add: axis1, axis2, samples (two whole numbers), adaptive, circular and
 * orient (on or off). */
#define AREA_LIGHT_KEY_COUNT 6
extern const struct key_spec area_light_keys[AREA_LIGHT_KEY_COUNT];

/* Fills *a from the values read for area_light_keys (the parser's struct key_values): a point light
 * ({0}, adaptive AREA_LIGHT_NOT_ADAPTIVE) when none is given. Returns false with the reason in why
 * (without file and line: the parser adds them) when axis1, axis2 and samples are not all given or
 * the others come without them, samples are not whole numbers from 1 to AREA_LIGHT_MAX_SIZE, an axis
 * is zero, shorter than AREA_LIGHT_MIN_AXIS or beyond KEY_MAX_COORD, the two are parallel (whatever
 * their lengths), adaptive is not a whole number from 0 to AREA_LIGHT_MAX_ADAPTIVE,
 * circular or orient is not on or off, circular has a side of one point, or orient comes without
 * circular. */
bool area_light_make(const struct key_values *kv, struct area_light *a, char *why, size_t why_size);

/* Returns whether the light is an area light (samples given), not a point light. */
static inline bool area_light_is_area(const struct area_light *a) { return a->size1 > 0; }

/* Writes POV-Ray's area_light keywords for *a (nothing for a point light), starting with a space:
 * " area_light <a1>, <a2>, n1, n2 adaptive N circular orient". Jitter stays off, POV-Ray's default. */
void area_light_write_pov(FILE *out, const struct area_light *a);

#endif

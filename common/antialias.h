/* antialias.h: the scene's `antialias` line, how many camera rays each pixel gets and where (read
 * from chapter 1 on, drawn by chapter 12; docs/12-antialias.md).
 *
 *   antialias method adaptive samples 3 threshold 0.3
 *
 * Like a shape's syntax (shape.h), the settings are plain data read with every scene, so that any
 * chapter reads any scene; the chapters before 12 ignore them (scene_drop_unsupported). The sampling
 * itself is chapter 12's, in supersample.c. The POV-Ray twin carries the settings as a comment line
 * naming the options POV-Ray is to be run with (antialias_write_pov). */
#ifndef WHITTED_ANTIALIAS_H
#define WHITTED_ANTIALIAS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "shape.h"

#define ANTIALIAS_CHAPTER 12           /* the chapter that draws it */
#define ANTIALIAS_DEFAULT_SAMPLES 3    /* POV-Ray's default Antialias_Depth (+R) */
#define ANTIALIAS_DEFAULT_THRESHOLD 0.3 /* POV-Ray's default Antialias_Threshold (+A) */
#define ANTIALIAS_MAX_SAMPLES 16       /* grid and jitter: 16 x 16 = 256 rays a pixel */
#define ANTIALIAS_MAX_ADAPTIVE 9       /* adaptive: POV-Ray's largest Antialias_Depth */
#define ANTIALIAS_MAX_DEPTH 6          /* recursive: at most 33 x 33 points a pixel (POV-Ray allows 9,
                                          257 x 257, which no picture needs) */
#define ANTIALIAS_MAX_THRESHOLD 1.0    /* POV-Ray clips its threshold to [0, 1] */
/* POV-Ray compares colours after raising each channel to the power 1 / ANTIALIAS_GAMMA (its default
 * Antialias_Gamma), so that a step between dark colours counts as much as the eye sees it. */
#define ANTIALIAS_GAMMA 2.5
/* POV-Ray renders in blocks of this many pixels a side (its default Render_Block_Size); the
 * adaptive method's rule depends on where the blocks begin (supersample.c). */
#define ANTIALIAS_BLOCK 32

enum antialias_method {
    ANTIALIAS_NONE,      /* one ray through each pixel's centre, as chapters 1 to 11 */
    ANTIALIAS_GRID,      /* n x n rays on a regular grid across the pixel, averaged */
    ANTIALIAS_JITTER,    /* n x n rays, each at a random place in its own cell of that grid */
    ANTIALIAS_ADAPTIVE,  /* the centre; n x n more where a neighbour differs (POV-Ray's method 1) */
    ANTIALIAS_RECURSIVE, /* the corners, quartered where they differ (POV-Ray's method 2) */
};

struct antialias {
    enum antialias_method method;
    int samples;      /* n, the side of the grid; for RECURSIVE the depth (2^(n-1) + 1 rays a side at most) */
    double threshold; /* ADAPTIVE and RECURSIVE: the colour difference that asks for more rays */
    uint32_t seed;    /* JITTER: chooses the random numbers; the same seed gives the same picture */
    int line;         /* the scene file's line, 0 when the scene has none (method NONE) */
};

/* The keys of the line: method (a word), samples, threshold, seed. */
#define ANTIALIAS_KEY_COUNT 4
extern const struct key_spec antialias_keys[ANTIALIAS_KEY_COUNT];

/* Fills *a from the values read for antialias_keys (the parser's struct key_values); keys not given
 * keep POV-Ray's defaults (method grid when the line names none). Returns false with the reason in why
 * (without file and line: the parser adds them) for an unknown method, samples that are not a whole
 * number from 1 to the method's largest (ANTIALIAS_MAX_SAMPLES, _ADAPTIVE or _DEPTH), a threshold
 * outside [0, 1] or a seed that is not a whole number from 0 to 2^32 - 1. */
bool antialias_make(const struct key_values *kv, struct antialias *a, char *why, size_t why_size);

/* Returns the method's name as the scene file spells it: "none", "grid", ... */
const char *antialias_method_name(enum antialias_method method);

/* Returns how many camera rays a side the method's regular grid has in the POV-Ray twin: n for
 * GRID and JITTER (POV-Ray renders the twin n times as wide and high, one ray a pixel, and each n x n
 * block is averaged: the same rays as the grid), 1 otherwise. */
int antialias_box(const struct antialias *a);

/* Writes the POV-Ray options of ADAPTIVE and RECURSIVE (e.g. "Antialias=on Sampling_Method=1
 * Antialias_Threshold=0.3 Antialias_Depth=3 Jitter=off ...") into out; "" for the other methods.
 * Cannot fail (the text is cut short if out_size is too small). */
void antialias_povray_options(const struct antialias *a, char *out, size_t out_size);

/* Writes the twin's comment lines that say how POV-Ray renders it: "// Antialias options: ..." for
 * ADAPTIVE and RECURSIVE, "// Antialias box: n" for GRID and JITTER, nothing for NONE. The scripts and
 * tests that render twins read these lines (tools/compare-povray.sh, tests/support/image_test_support.c). */
void antialias_write_pov(FILE *out, const struct antialias *a);

#endif

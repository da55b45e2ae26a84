/* lens.h: the keys of the camera line that give it a lens instead of a pinhole, for depth of field
 * (read from chapter 1 on, drawn by chapter 13; docs/13-distributed.md).
 *
 *   camera eye 0 2 8  target 0 1 0  fov 36  aperture 0.4  focal_point 0 1 0  blur_samples 19
 *
 * A pinhole sees everything sharp. A lens of diameter `aperture` sees sharp only what lies on the
 * focal plane: square to the view, as far from the eye as `focal_point` is (POV-Ray's rule). Each
 * camera sample becomes `blur_samples` rays from points spread over the lens (thin_lens.h). Like the
 * antialias line (antialias.h) the settings are plain data read with every scene; before chapter 13
 * the camera is a pinhole (scene_drop_unsupported). */
#ifndef WHITTED_LENS_H
#define WHITTED_LENS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "shape.h"

#define LENS_CHAPTER 13          /* the chapter that draws it */
#define LENS_DEFAULT_SAMPLES 19  /* two rings of POV-Ray's hexagonal grid */
/* The focal point must lie farther from the eye than this: nothing nearer can be in focus. */
#define LENS_MIN_FOCAL_DISTANCE 1e-9
/* The widest aperture: with it, the focal point and the eye within KEY_MAX_COORD, a lens ray's
 * direction is a difference of points whose length stays finite (and not zero). */
#define LENS_MAX_APERTURE KEY_MAX_COORD
/* The widest aperture for a focal point at distance d from the eye is this times d. A ray from the rim of
 * such a lens meets the view's axis at the focal point at atan(500) = 89.9 degrees: everything off the
 * focal plane is already blurred over the whole picture, and a wider lens changes nothing but the cost.
 * The cost grows with it: lens points far from a scene the size of d put the rays' origins so far away
 * that the structures' boxes can no longer tell their parts apart, and every ray tests every triangle. */
#define LENS_MAX_APERTURE_RATIO 1000.0

struct lens {
    double aperture;     /* the lens's diameter; 0 for a pinhole */
    vec3 focal_point;    /* the focal plane lies as far from the eye as this point */
    int blur_samples;    /* rays a camera sample: 7, 19 or 37 (1, 2 or 3 rings of a hexagonal grid) */
};

/* The keys the camera line may add: aperture, focal_point, blur_samples. */
#define LENS_KEY_COUNT 3
extern const struct key_spec lens_keys[LENS_KEY_COUNT];

/* Fills *l from the values read for lens_keys, `eye` being the camera's: a pinhole (aperture 0) when
 * none is given. Returns false with the reason in why (without file and line: the parser adds them)
 * for a negative aperture or one above LENS_MAX_APERTURE or above LENS_MAX_APERTURE_RATIO times the focal
 * point's distance from the eye, an aperture without focal_point or focal_point or
 * blur_samples without aperture, a focal point or (with a lens) an eye beyond KEY_MAX_COORD, a focal
 * point at the eye, or blur_samples other than 7, 19 or 37. */
bool lens_make(const struct key_values *kv, vec3 eye, struct lens *l, char *why, size_t why_size);

/* Returns whether the camera has a lens (aperture > 0), not a pinhole. */
static inline bool lens_is_open(const struct lens *l) { return l->aperture > 0.0; }

/* Writes POV-Ray's focal blur keywords for *l inside its camera block (nothing for a pinhole):
 * aperture (POV-Ray's is twice the diameter: its lens has radius aperture / 4), focal_point,
 * blur_samples, and variance 0, which makes POV-Ray trace every sample instead of stopping early. */
void lens_write_pov(FILE *out, const struct lens *l);

#endif

/* image_compare.h: pixel-by-pixel comparison of two 8-bit RGB pictures, as used by the image tests,
 * the coursework grader (make check-N) and `make compare` (test support, not a chapter). */
#ifndef WHITTED_IMAGE_COMPARE_H
#define WHITTED_IMAGE_COMPARE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct image_difference {
    int max;             /* largest |difference| of any channel of any pixel, in 8-bit levels */
    double mean;         /* mean |difference| over all channels of all pixels, in levels */
    double within_1;     /* share (0..1) of pixels whose largest channel difference is <= 1 */
    double within_2;     /* share (0..1) of pixels whose largest channel difference is <= 2 */
    double psnr;         /* peak signal-to-noise ratio in dB; INFINITY for identical pictures */
    long pixels_over_2;  /* number of pixels whose largest channel difference is > 2 */
};

/* Compares two width x height RGB pictures (3 bytes a pixel, same size). Cannot fail. */
struct image_difference image_compare(const uint8_t *a, const uint8_t *b, int width, int height);

/* The agreement rule between our renders and POV-Ray's (docs/povray.md, "The agreement rule"):
 * at least 99.9 % of pixels within 2 levels and a mean difference of at most 0.05 levels. */
#define AGREEMENT_MIN_WITHIN_2 0.999
#define AGREEMENT_MAX_MEAN 0.05

/* Returns true when d meets the agreement rule above. */
bool image_difference_agrees(const struct image_difference *d);

/* Writes into `out` (width * 2 by height RGB) the pictures a and b side by side, a on the left. */
void image_compare_side_by_side(const uint8_t *a, const uint8_t *b, int width, int height, uint8_t *out);

/* Writes into `out` (width by height RGB) the difference of a and b amplified `gain` times: each
 * channel |a - b| * gain, clamped to 255, so identical pixels are black. */
void image_compare_difference(const uint8_t *a, const uint8_t *b, int width, int height, int gain, uint8_t *out);

#endif

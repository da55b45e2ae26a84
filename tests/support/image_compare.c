/* image_compare.c: difference statistics of two pictures, and pictures of them side by side and of their
 * amplified difference (test support: the tests, the grader and build/compare use it). */
#include "image_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct image_difference image_compare(const uint8_t *a, const uint8_t *b, int width, int height) {
    struct image_difference d = {0};
    size_t pixels = (size_t)width * (size_t)height;
    double sum = 0.0, squares = 0.0;
    size_t within_1 = 0, within_2 = 0;
    for (size_t p = 0; p < pixels; p++) {
        int pixel_max = 0;
        for (int c = 0; c < 3; c++) {
            int delta = abs((int)a[3 * p + c] - (int)b[3 * p + c]);
            sum += delta;
            squares += (double)delta * delta;
            if (delta > pixel_max)
                pixel_max = delta;
        }
        within_1 += pixel_max <= 1;
        within_2 += pixel_max <= 2;
        if (pixel_max > d.max)
            d.max = pixel_max;
    }
    d.mean = sum / (3.0 * (double)pixels);
    d.within_1 = (double)within_1 / (double)pixels;
    d.within_2 = (double)within_2 / (double)pixels;
    d.pixels_over_2 = (long)(pixels - within_2);
    double mse = squares / (3.0 * (double)pixels);
    d.psnr = mse == 0.0 ? INFINITY : 10.0 * log10(255.0 * 255.0 / mse);
    return d;
}

bool image_difference_agrees(const struct image_difference *d) {
    return d->within_2 >= AGREEMENT_MIN_WITHIN_2 && d->mean <= AGREEMENT_MAX_MEAN;
}

void image_compare_side_by_side(const uint8_t *a, const uint8_t *b, int width, int height, uint8_t *out) {
    size_t row = (size_t)width * 3;
    for (int j = 0; j < height; j++) {
        uint8_t *line = out + (size_t)j * row * 2;
        memcpy(line, a + (size_t)j * row, row);
        memcpy(line + row, b + (size_t)j * row, row);
    }
}

void image_compare_difference(const uint8_t *a, const uint8_t *b, int width, int height, int gain, uint8_t *out) {
    size_t bytes = (size_t)width * (size_t)height * 3;
    for (size_t k = 0; k < bytes; k++) {
        int delta = abs((int)a[k] - (int)b[k]) * gain;
        out[k] = (uint8_t)(delta > 255 ? 255 : delta);
    }
}

/* box_filter.c: averages a picture down by n x n blocks, in its linear values (tools). */
#include "box_filter.h"

#include <stdio.h>
#include <stdlib.h>

#include <stb_image.h>

#include "image.h"

#define CHANNEL_MAX 65535.0 /* stbi_load_16 gives every file 16 bits a channel */

uint8_t *box_filter_png(const char *path, int n, int *width, int *height, char *err, size_t err_size) {
    int w = 0, h = 0, channels = 0;
    uint16_t *big = stbi_load_16(path, &w, &h, &channels, 3);
    if (big == NULL) {
        snprintf(err, err_size, "%s: cannot read image: %s", path, stbi_failure_reason());
        return NULL;
    }
    if (n < 1 || w % n != 0 || h % n != 0) {
        snprintf(err, err_size, "%s: %d x %d pixels cannot be cut into %d x %d blocks", path, w, h, n, n);
        stbi_image_free(big);
        return NULL;
    }
    *width = w / n;
    *height = h / n;
    uint8_t *small = malloc((size_t)*width * (size_t)*height * 3);
    if (small == NULL) {
        snprintf(err, err_size, "%s: out of memory", path);
        stbi_image_free(big);
        return NULL;
    }
    for (int j = 0; j < *height; j++)
        for (int i = 0; i < *width; i++)
            for (int c = 0; c < 3; c++) {
                double sum = 0.0;
                for (int b = 0; b < n; b++)
                    for (int a = 0; a < n; a++)
                        sum += big[3 * ((size_t)(n * j + b) * (size_t)w + (size_t)(n * i + a)) + (size_t)c];
                small[3 * ((size_t)j * (size_t)*width + (size_t)i) + (size_t)c] =
                    image_quantize(sum / (CHANNEL_MAX * n * n));
            }
    stbi_image_free(big);
    return small;
}

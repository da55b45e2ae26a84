/* heatmap.c: per-pixel cost drawn on a fixed logarithmic colour scale (chapter 1). */
#include "heatmap.h"

#include <math.h>
#include <stdio.h>

/* The colour ramp, evenly spaced on log(1 + cost): black, blue, red, yellow, white. */
static const vec3 ramp[] = {{0, 0, 0}, {0.1, 0.2, 0.9}, {0.9, 0.15, 0.1}, {1, 0.9, 0.1}, {1, 1, 1}};
#define RAMP_STEPS (sizeof ramp / sizeof ramp[0] - 1)

vec3 heatmap_colour(uint32_t cost) {
    double level = log1p((double)cost) / log1p((double)HEATMAP_MAX_COST);
    if (level >= 1.0)
        return ramp[RAMP_STEPS];
    double position = level * RAMP_STEPS;
    int step = (int)position;
    double blend = position - step;
    return vec3_add(vec3_scale(ramp[step], 1.0 - blend), vec3_scale(ramp[step + 1], blend));
}

bool heatmap_write(const uint32_t *cost, int width, int height, const char *path, char *err, size_t err_size) {
    struct image picture;
    if (!image_create(&picture, width, height)) {
        snprintf(err, err_size, "%s: out of memory", path);
        return false;
    }
    for (size_t k = 0; k < (size_t)width * (size_t)height; k++)
        picture.pixels[k] = heatmap_colour(cost[k]);
    bool ok = image_write_png(&picture, path, err, err_size);
    image_free(&picture);
    return ok;
}

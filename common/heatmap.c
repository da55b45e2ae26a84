/* heatmap.c: per-pixel cost drawn on a fixed logarithmic colour scale (chapter 1). */
#include "heatmap.h"

#include <math.h>

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

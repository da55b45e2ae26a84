/* heatmap.h: a picture of how much work each pixel cost (chapter 1; it tells its story in chapters 5,
 * 9 and 10).
 *
 * The cost of a pixel is the number of node visits plus box and shape tests its rays made. It is
 * drawn on one fixed logarithmic scale, black (no work) through blue, red and yellow to white
 * (HEATMAP_MAX_COST tests or more), so heat-maps of different chapters and structures can be set side
 * by side. Mind what a unit is: a BVH node visit also counts a box test for each of its (up to four)
 * children, a kd-tree step counts none, so equal colours are equal counts, not equal times. */
#ifndef WHITTED_HEATMAP_H
#define WHITTED_HEATMAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "image.h"

/* The cost drawn white: a little less than a brute-force ray through chapter 5's 8,786 triangles. */
#define HEATMAP_MAX_COST 8192

/* Returns the colour of one cost on the fixed scale. */
vec3 heatmap_colour(uint32_t cost);

#endif

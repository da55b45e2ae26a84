/* heatmap.h: a picture of how much work each pixel cost (chapter 1; it tells its story in chapters 5,
 * 9, 10 and 11).
 *
 * The cost of a pixel is the number of node visits plus box and shape tests its rays made. It is
 * drawn on one fixed logarithmic scale, black (no work) through blue, red and yellow to white
 * (HEATMAP_MAX_COST tests or more), so heat-maps of different chapters and structures can be set side
 * by side. Mind what a unit is: a BVH node visit also counts a box test for each of its children (two
 * in chapter 10, up to four in chapter 11), a kd-tree step counts none, so equal colours are equal
 * counts, not equal times.
 *
 * Under the picture, the heat-map gets a colour bar (heatmap_draw_bar): the scale from 0 to
 * HEATMAP_MAX_COST with a tick and its number at each cost in heatmap_ticks, the numbers drawn with a
 * built-in bitmap font of digits. */
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

/* The costs marked on the colour bar: 0, then the powers of ten, then HEATMAP_MAX_COST. */
#define HEATMAP_TICKS 6
extern const uint32_t heatmap_ticks[HEATMAP_TICKS];

/* A colour scale: the same logarithmic ramp from 0 (black) to `max` (white), and the values marked on
 * its bar. The cost scale above is heatmap_cost_scale; chapter 12 draws camera rays per pixel on a
 * scale of its own (supersample.h). */
struct heatmap_scale {
    uint32_t max;
    const uint32_t *ticks;
    int tick_count;
};
extern const struct heatmap_scale heatmap_cost_scale;

/* Returns the colour of `value` on `scale` (heatmap_colour is this on heatmap_cost_scale). */
vec3 heatmap_colour_on(const struct heatmap_scale *scale, uint32_t value);

/* heatmap_draw_bar for the bar of `scale`. */
void heatmap_draw_bar_on(struct image *img, int top, const struct heatmap_scale *scale);

/* Returns how many rows the colour bar adds under a width x height heat-map: 0 when the picture with
 * its bar would be taller than IMAGE_MAX_SIDE (then it has no bar). Cannot fail. */
int heatmap_bar_height(int width, int height);

/* Returns the size of the bar's digits for a picture `width` pixels wide: image pixels per pixel of
 * the 5 x 7 font. Cannot fail. */
int heatmap_bar_scale(int width);

/* Returns the column of the colour bar at which `cost` lies (costs above HEATMAP_MAX_COST at its end),
 * for a picture `width` pixels wide with room for the numbers (at least 56 times heatmap_bar_scale). */
int heatmap_bar_x(int width, uint32_t cost);

/* Draws the colour bar into rows top .. img->height - 1 of img, which the caller made
 * heatmap_bar_height(width, top) rows taller than the picture above them. A picture too narrow for the
 * numbers gets the ramp alone, across its whole width; with no rows to draw in, nothing is drawn. */
void heatmap_draw_bar(struct image *img, int top);

#endif

/* supersample.h: several camera rays per pixel, averaged: anti-aliasing (chapter 12;
 * docs/12-antialias.md).
 *
 * A pixel is a small square of the picture, not a point. One ray through its centre (chapters 1 to 11)
 * reports the colour at one point of the square: where an edge crosses the square, the pixel takes all
 * of one side's colour or all of the other's, and edges come out as staircases. Here a pixel gets
 * several rays and its colour is their plain mean, every point of the square weighted alike: a box
 * filter. The methods of the scene's antialias line (antialias.h) differ in where the rays go:
 *
 *   grid       n x n rays, one at the centre of each cell of an n x n grid over the pixel;
 *   jitter     one ray at a random point of each cell (random numbers from sample_hash.h);
 *   adaptive   POV-Ray's sampling method 1: one ray through the centre, and where the colour differs
 *              from the left or upper neighbour's by the threshold, n x n more for both;
 *   recursive  POV-Ray's sampling method 2: rays at the pixel's corners; where they differ, the
 *              square is cut into four and each quarter treated alike, down to the depth n.
 *
 * The last two are POV-Ray 3.7's rules, exactly (tracetask.cpp), so that the twin agrees pixel by
 * pixel; the walkthrough tells them in words. Every method gives the same picture for any thread count. */
#ifndef WHITTED_SUPERSAMPLE_H
#define WHITTED_SUPERSAMPLE_H

#include <stdbool.h>
#include <stdint.h>

#include "antialias.h"
#include "heatmap.h"
#include "render.h"
#include "vec3.h"

/* What the samples look at: the colour seen through point (x, y) of the picture, measured in pixels
 * from its top-left corner (pixel (i, j) covers [i, i + 1) x [j, j + 1)). In the renderer, the
 * camera's ray through that point, traced; in the tests, any function of (x, y). */
struct sample_view {
    vec3 (*colour_at)(const void *context, double x, double y);
    const void *context;
};

/* Pixel (i, j)'s colour through `view` as the mean of n x n samples, one at
 * the centre of each cell of an n x n grid over the pixel: (i + (a + 0.5) / n, j + (b + 0.5) / n) for
 * a, b = 0 .. n - 1. n = 1 is the centre, chapter 1's ray. Calls view->colour_at n * n times. */
vec3 supersample_grid(const struct sample_view *view, int i, int j, int n);

/* Whether two colours differ enough for the adaptive methods to take more
 * samples, by POV-Ray's rule: each channel raised to the power 1 / ANTIALIAS_GAMMA (negative channels
 * as 0), and the sum of the three channels' absolute differences at least `threshold`. */
bool supersample_differ(vec3 a, vec3 b, double threshold);

/* Samples the pixels [left, right) x [top, bottom) through `view` by the method of `a`, writing pixel
 * (i, j)'s colour to colours[(j - top) * (right - left) + (i - left)] and the number of rays it took to
 * rays[same index]. For ADAPTIVE the rectangle must be one of POV-Ray's render blocks (ANTIALIAS_BLOCK
 * pixels a side from the picture's top-left corner, smaller at the right and bottom edges): the rule
 * looks at the row above and the column to the left of it, traced again and never refined here, as
 * POV-Ray does. Returns the rays traced in all, those counted in no pixel included. The rectangle may be
 * at most ANTIALIAS_BLOCK pixels a side: a larger (or empty) one is refused, and 0 returned. */
uint64_t supersample_block(const struct antialias *a, const struct sample_view *view, int left, int top, int right,
                           int bottom, vec3 *colours, int *rays);

/* Renders pixels [left, right) x [top, bottom) of img (one block, as supersample_block takes) through
 * `view` by the job's antialias settings, with the heat-map and counters of supersample_sampler: its
 * block function with another view than the camera's (chapter 13's lens). view->colour_at counts its
 * own rays in stats_thread.primary_rays. */
void supersample_render_view(const struct render_job *job, const struct sample_view *view, struct image *img, int left,
                             int top, int right, int bottom);

/* Whether the edges of a render block change its pixels under the job's antialias line (render.h's
 * block_edges_matter): only with the adaptive method, whose rule looks at a pixel's neighbours in its
 * block and traces those outside it again instead. Every other method samples each pixel by itself. */
bool supersample_block_edges_matter(const struct render_job *job);

/* The renderer's way of sampling (render.h) with the scene's antialias line; its heat-map shows how
 * many camera rays each pixel took, on supersample_ray_scale. */
extern const struct render_sampler supersample_sampler;

/* Camera rays per pixel: 0 black, 100 (and more) white, marked at 0, 1, 10 and 100. */
extern const struct heatmap_scale supersample_ray_scale;

#endif

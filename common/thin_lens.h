/* thin_lens.h: depth of field: camera rays from points spread over a lens, all meeting again on the
 * focal plane (chapter 13; docs/13-distributed.md).
 *
 * A pinhole camera's rays all leave the eye. A thin lens of diameter D (the camera's aperture, lens.h)
 * sends the rays of one image point from every point of the lens towards one point: where the
 * pinhole's ray through that image point meets the focal plane. A surface on that plane is sharp; one
 * nearer or farther is seen through a small disc of the focal plane instead of a point, the circle of
 * confusion, and blurs.
 *
 * Each camera sample of the antialias line (chapter 12) becomes blur_samples rays, by POV-Ray's
 * focal blur pattern with our own random numbers (sample_hash.h): lens ray k starts at point k of a
 * hexagonal grid of 1, 2 or 3 rings over the lens (7, 19 or 37 points), moved at random within its
 * own cell, and passes through a random point of a pixel-sized square around the sample's image point.
 * The samples' colour is the mean of its rays'. POV-Ray draws its random numbers from a fixed table
 * in its source, which we do not copy; its picture and ours are two draws of the same distribution,
 * and the tests compare them as such (docs/13-distributed.md). */
#ifndef WHITTED_THIN_LENS_H
#define WHITTED_THIN_LENS_H

#include <stdint.h>

#include "camera.h"
#include "lens.h"
#include "render.h"
#include "vec3.h"

#define THIN_LENS_MAX_SAMPLES 37 /* three rings of the hexagonal grid */
/* Image points are told apart to this fraction of a pixel when their random numbers are drawn. */
#define THIN_LENS_POINT_STEPS 4096

/* The lens of one picture: the camera, the focal distance and the grid of lens points. */
struct thin_lens {
    const struct camera *camera;
    double aperture;       /* D, the lens's diameter */
    double focal_distance; /* from the eye along the view to the focal plane: |focal_point - eye| */
    int samples;           /* blur_samples: 7, 19 or 37 */
    double cell;           /* the grid's spacing, as a share of D: 1 / (sqrt(3) (rings + 1)) */
    double grid[THIN_LENS_MAX_SAMPLES][2]; /* the grid's points, as shares of D along right and up */
    uint32_t seed;         /* chooses the random numbers (the antialias line's seed) */
};

/* Sets up *t for `camera` (eye, basis, picture size) and the open lens *l, with `seed`. The grid: every
 * point a e1 + b e2 of the hexagonal lattice with e1 = (c, 0), e2 = (c / 2, c sqrt(3) / 2) and
 * max(|a|, |b|, |a + b|) <= rings, c = t->cell. Cannot fail. */
void thin_lens_init(struct thin_lens *t, const struct camera *camera, const struct lens *l, uint32_t seed);

/* Returns lens ray k (0 <= k < t->samples) of the camera sample at image point (x, y) (pixels from the
 * top-left corner): from eye + D (gx right + gy up), (gx, gy) being grid point k moved by
 * (u - 1/2, v - 1/2) cells, towards the point where the pinhole's ray through (x + s - 1/2, y + r - 1/2)
 * meets the focal plane, moved 1/32 of a pixel left and up as POV-Ray's are (thin_lens.c); u, v, s, r
 * are sample_hash_unit's numbers 4k .. 4k + 3 for the image point (to 1 / THIN_LENS_POINT_STEPS of a
 * pixel) and the seed. The direction has unit length. */
ray thin_lens_ray(const struct thin_lens *t, double x, double y, int k);

/* The renderer's way of sampling with a lens: supersample_sampler's (the antialias line) with each
 * camera sample traced through the lens as blur_samples rays; for a pinhole, supersample_sampler's. */
extern const struct render_sampler thin_lens_sampler;

#endif

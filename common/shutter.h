/* shutter.h: motion blur: each camera sample seen at its own time within the shutter's opening (chapter
 * 16; docs/16-instances.md).
 *
 * Cook's distributed ray tracing spreads the samples of a pixel over time as it spreads them over the
 * lens: a frame at clock c is exposed over [c, c + S] (S the camera's shutter), and each camera sample
 * traces the world as it is at a time of its own in that interval, drawn by the counter-based hashing of
 * sample_hash.h from the sample's image point and the antialias line's seed, so that a sample's time
 * depends only on its pixel, its place in the pixel and the seed, never on the thread that traced it.
 * A moving instance is then hit where it was at that time, and the pixel's mean over its samples is
 * the blur. */
#ifndef WHITTED_SHUTTER_H
#define WHITTED_SHUTTER_H

#include <stdint.h>

#include "render.h"

/* The sample_hash index shutter_time draws with: far above thin_lens_ray's 4k .. 4k + 3 (k < 37), so that a
 * sample's time and its lens point are independent numbers. */
#define SHUTTER_HASH_INDEX 0x10000u

/* Returns the time of the camera sample at image point (x, y) (pixels from the top-left corner, told
 * apart to 1 / THIN_LENS_POINT_STEPS of a pixel) of a frame at clock `clock` exposed for `shutter`:
 * clock + shutter u, u = sample_hash_unit of the point and SHUTTER_HASH_INDEX under `seed`; exactly
 * `clock` when shutter is 0. Cannot fail. */
double shutter_time(double clock, double shutter, double x, double y, uint32_t seed);

/* The renderer's way of sampling with a shutter: thin_lens_sampler's (the antialias line, the lens) with
 * each camera sample traced in a copy of the job's world (a struct world) whose time is the sample's
 * shutter_time, the frame's clock being the job's world's time and the shutter its scene's. */
extern const struct render_sampler shutter_sampler;

#endif

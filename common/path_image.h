/* path_image.h: chapter 15's picture: the paths of each pixel averaged into linear radiance, kept as a
 * frame of floats for the HDR file, and shown in the PNG through a stated tone map (docs/15-paths.md).
 *
 * Radiance has no upper bound: the lamp of the Cornell box is 17 times brighter than a white sheet of
 * paper under it. The PNG holds 8 bits of a display's range, so each channel is
 *   clipped to [0, 1]      (the tone map: the identity up to 1, as Blender's Standard view transform)
 *   encoded by the sRGB curve: 12.92 v below 0.0031308, else 1.055 v^(1 / 2.4) - 0.055
 * and quantised as every chapter's picture is (image.h). The linear radiance itself goes to a Radiance
 * .hdr file (stb's stbi_write_hdr), for comparing with another renderer without the tone map between, or
 * to a Portable Float Map (.pfm), which keeps every float whole: Radiance's format keeps 8 bits of each
 * channel under a shared exponent and stb cuts the rest off, which makes a picture's mean up to half a
 * percent low, too much for chapter 15's comparison with Cycles (docs/15-paths.md). */
#ifndef WHITTED_PATH_IMAGE_H
#define WHITTED_PATH_IMAGE_H

#include <stdbool.h>
#include <stddef.h>

#include "path_trace.h"
#include "render.h"

/* What the renderer hands the sampler as its world: the paths and the frame the linear pixels go to. */
struct path_picture {
    const struct path_world *paths;
    float *linear; /* width * height * 3 floats, rows top first; owned by whoever made the picture */
    float *error;  /* optional (NULL), the same size: each channel's standard error, sqrt(variance / samples) */
    int width;
    /* optional (NULL), width * height running sums (path_pixel_resume) kept between renders of more and
     * more samples, each pixel going on from its sum; NULL: every pixel from zero (path_pixel) */
    struct path_pixel_sum *sums;
};

/* The renderer's way of sampling (render.h) for a job whose world is a struct path_picture: each pixel
 * the mean of the scene's paths per pixel (path_pixel), stored linear in the frame and tone-mapped in the
 * PNG; its heat-map shows the work each pixel cost on chapter 1's scale. */
extern const struct render_sampler path_sampler;

/* Returns the noise of a picture rendered with errors: the mean standard error of its pixels' channels
 * over the mean of their values (0 for a black picture). */
double path_image_noise(const float *linear, const float *error, int width, int height);

/* Moves the linear pixels of `window` of a frame `width` pixels wide (3 floats a pixel) to the front of
 * `linear`, row after row: the frame of the window alone (a tile's, for its HDR file). */
void path_image_keep_window(float *linear, int width, struct render_window window);

/* Returns the display value of one linear channel: clipped to [0, 1], then the sRGB curve. NaN gives 0. */
double path_image_display(double linear);

/* Writes width x height x 3 linear floats as a Radiance .hdr file at `path` through outfile.h (temporary
 * file renamed into place; "-" is standard output). Returns false with "path: reason" in err on
 * failure. */
bool path_image_write_hdr(const float *linear, int width, int height, const char *path, char *err, size_t err_size);

/* path_image_write_hdr for a Portable Float Map: "PF", the size, -1 (little-endian), then the rows from
 * the bottom up, three 32-bit floats a pixel. */
bool path_image_write_pfm(const float *linear, int width, int height, const char *path, char *err, size_t err_size);

#endif

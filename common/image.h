/* image.h: a linear floating-point RGB framebuffer and its 8-bit PNG file (chapter 1).
 *
 * Colours stay unclamped doubles while the picture is made (a highlight may exceed 1); they are
 * clamped and rounded only when written, with the rule POV-Ray uses for File_Gamma=1.0:
 * level = floor(255 * clamp(v, 0, 1) + 0.5). No gamma curve is applied. */
#ifndef WHITTED_IMAGE_H
#define WHITTED_IMAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vec3.h"

/* The largest width or height accepted anywhere (scene files, command line, PNG files read). */
#define IMAGE_MAX_SIDE 16384

struct image {
    int width, height;
    vec3 *pixels; /* width * height colours, row 0 at the top, owned by the image */
};

/* Allocates a width x height image filled with black. Returns false (image left empty) if the size is
 * not in 1..IMAGE_MAX_SIDE or memory runs out. Free with image_free. */
bool image_create(struct image *img, int width, int height);

/* Frees the pixels and leaves an empty image. Safe on an empty or already freed image. */
void image_free(struct image *img);

/* Returns a pointer to pixel (i, j); i < width and j < height are the caller's precondition. */
static inline vec3 *image_pixel(const struct image *img, int i, int j) {
    return &img->pixels[(size_t)j * (size_t)img->width + (size_t)i];
}

/* Returns the 8-bit level of one linear channel value: floor(255 * clamp(v, 0, 1) + 0.5); NaN gives 0. */
uint8_t image_quantize(double v);

/* Writes the image as an 8-bit RGB PNG at `path`. The PNG is first written to a temporary file in the
 * same directory and renamed over `path` only when complete, so a failure never leaves a half-written
 * image. Returns false and writes "path: reason" into err on failure. */
bool image_write_png(const struct image *img, const char *path, char *err, size_t err_size);

/* Writes already-quantised RGB bytes (width * height * 3, rows top first) as a PNG at `path`, with the
 * same temporary-file rule and error report as image_write_png. */
bool image_write_png_bytes(const uint8_t *rgb, int width, int height, const char *path, char *err,
                           size_t err_size);

/* Reads an 8-bit PNG (or any format stb_image knows) as RGB bytes. On success returns a malloc'd
 * buffer of width * height * 3 bytes (the caller frees it) and sets *width and *height; on failure
 * returns NULL and writes "path: reason" into err. */
uint8_t *image_read_rgb(const char *path, int *width, int *height, char *err, size_t err_size);

#endif

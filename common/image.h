/* image.h: an 8-bit RGB framebuffer and its PNG file (chapter 1).
 *
 * Colours stay unclamped doubles while a pixel is computed (a highlight may exceed 1); they are
 * clamped and rounded when the pixel is stored, with the rule POV-Ray uses for File_Gamma=1.0:
 * level = floor(255 * clamp(v, 0, 1) + 0.5). No gamma curve is applied. The frame holds only what the
 * PNG holds, 3 bytes a pixel, so a 16384 x 16384 picture needs 768 MiB, not the 6 GiB of doubles. */
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
    uint8_t *rgb; /* width * height * 3 levels, red green blue, row 0 at the top, owned by the image */
};

/* Allocates a width x height image filled with black. Returns false (image left empty) if the size is
 * not in 1..IMAGE_MAX_SIDE or memory runs out. Free with image_free. */
bool image_create(struct image *img, int width, int height);

/* Frees the pixels and leaves an empty image. Safe on an empty or already freed image. */
void image_free(struct image *img);

/* Returns the 8-bit level of one linear channel value: floor(255 * clamp(v, 0, 1) + 0.5); NaN gives 0. */
uint8_t image_quantize(double v);

/* Stores `colour` as pixel (i, j), each channel quantised by image_quantize; i < width and j < height
 * are the caller's precondition. */
static inline void image_set(struct image *img, int i, int j, vec3 colour) {
    uint8_t *pixel = &img->rgb[3 * ((size_t)j * (size_t)img->width + (size_t)i)];
    pixel[0] = image_quantize(colour.x);
    pixel[1] = image_quantize(colour.y);
    pixel[2] = image_quantize(colour.z);
}

/* Copies the rectangle [left, left + width) x [top, top + height) of `from` into the top-left corner of
 * `to` (a tile of a picture into a picture of its own); the rectangle must fit in both (the caller's
 * precondition). */
void image_copy_rect(struct image *to, const struct image *from, int left, int top, int width, int height);

/* Writes the image as an 8-bit RGB PNG at `path` through outfile.h: to a temporary file renamed over
 * `path` only when complete, so a failure never leaves a half-written image ("-" is standard output; a
 * FIFO or device is written directly). Returns false and writes "path: reason" into err on failure. */
bool image_write_png(const struct image *img, const char *path, char *err, size_t err_size);

/* Writes already-quantised RGB bytes (width * height * 3, rows top first) as a PNG at `path`, with the
 * same temporary-file rule and error report as image_write_png. */
bool image_write_png_bytes(const uint8_t *rgb, int width, int height, const char *path, char *err,
                           size_t err_size);

/* Reads an 8-bit PNG (or any format stb_image knows) as RGB bytes. On success returns a malloc'd
 * buffer of width * height * 3 bytes (the caller frees it) and sets *width and *height; on failure
 * returns NULL and writes "path: reason" into err: infile_read_whole's reasons (a file that is not a
 * regular one, or larger than 1 GiB), "damaged: a pixel's palette index is past the end of its palette
 * (N colours)" (png_palette_check), "cannot read image: " and the decoder's reason, or "image larger
 * than 16384 pixels on a side". */
uint8_t *image_read_rgb(const char *path, int *width, int *height, char *err, size_t err_size);

#endif

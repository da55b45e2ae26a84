/* tiny_images.h: a few small PNG and JPEG files of every kind the image-map reader takes, drawn here
 * (make fuzz; not part of any chapter): the image harness's seed corpus (fuzz/image_seeds.c) and the
 * pictures the renderer harness wraps over surfaces (fuzz/render_check.c), so that nothing is
 * downloaded or committed.
 *
 * The kinds: 8-bit PNGs with 1, 2, 3 and 4 channels written by stb_image_write (compressed, filtered);
 * PNGs written here with stored (uncompressed) deflate blocks: 16 bits a channel, an sRGB chunk, a gAMA
 * chunk; and JPEGs (stb writes three channels even from a grey picture) with and without chroma
 * subsampling. Each is a few pixels a side,
 * drawn as a pattern of distinct colours with some alpha below 1 where it has alpha. */
#ifndef WHITTED_TINY_IMAGES_H
#define WHITTED_TINY_IMAGES_H

#include <stdbool.h>
#include <stddef.h>

/* The number of tiny images, and the file name of image k (0 <= k < TINY_IMAGE_COUNT), e.g. "rgb.png". */
#define TINY_IMAGE_COUNT 10
const char *tiny_image_name(size_t k);

/* Writes every tiny image into the existing folder `folder` under its name. Returns false with
 * "path: cannot write" in err when one cannot be written. The files are the same on every run. */
bool tiny_images_write(const char *folder, char *err, size_t err_size);

#endif

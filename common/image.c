/* image.c: framebuffer allocation, output quantisation, and PNG files through stb (chapter 1). */
#include "image.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "infile.h"
#include "outfile.h"
#include "png_palette.h"

#include <stb_image.h>
#include <stb_image_write.h>

bool image_create(struct image *img, int width, int height) {
    img->width = img->height = 0;
    img->rgb = NULL;
    if (width < 1 || height < 1 || width > IMAGE_MAX_SIDE || height > IMAGE_MAX_SIDE)
        return false;
    img->rgb = calloc((size_t)width * (size_t)height, 3);
    if (img->rgb == NULL)
        return false;
    img->width = width;
    img->height = height;
    return true;
}

void image_free(struct image *img) {
    free(img->rgb);
    img->rgb = NULL;
    img->width = img->height = 0;
}

void image_copy_rect(struct image *to, const struct image *from, int left, int top, int width, int height) {
    for (int y = 0; y < height; y++)
        memcpy(&to->rgb[3 * (size_t)y * (size_t)to->width],
               &from->rgb[3 * ((size_t)(top + y) * (size_t)from->width + (size_t)left)], 3 * (size_t)width);
}

uint8_t image_quantize(double v) {
    if (!(v > 0.0)) /* also catches NaN */
        return 0;
    if (v >= 1.0)
        return 255;
    return (uint8_t)floor(255.0 * v + 0.5);
}

/* No picture file read back is larger: a 16384 x 16384 PNG stored without compression takes about
 * 805 MB. */
#define IMAGE_FILE_MAX_BYTES (1024L * 1024 * 1024)

/* The PNG row filter stb is told to use for every row: 1, "Sub" (each byte minus the byte of the pixel
 * to its left). By default stb tries all five filters on each row and keeps the one that looks best,
 * which costs a third of the writing time; on our pictures, smooth gradients row after row, Sub alone
 * writes the same pixels, in a file a few per cent smaller or larger (docs/fast-notes.md measures both). */
#define IMAGE_PNG_FILTER_SUB 1

/* stb_image_write hands its output to this callback piece by piece; we append it to the file. */
static void write_to_file(void *context, void *data, int size) {
    outfile_write(context, data, (size_t)size);
}

bool image_write_png_bytes(const uint8_t *rgb, int width, int height, const char *path, char *err,
                           size_t err_size) {
    struct outfile out;
    if (!outfile_open(&out, path, err, err_size))
        return false;
    stbi_write_force_png_filter = IMAGE_PNG_FILTER_SUB;
    if (stbi_write_png_to_func(write_to_file, &out, width, height, 3, rgb, width * 3) == 0) {
        outfile_abandon(&out);
        snprintf(err, err_size, "%s: cannot write: PNG encoding failed", path);
        return false;
    }
    return outfile_commit(&out, err, err_size);
}

bool image_write_png(const struct image *img, const char *path, char *err, size_t err_size) {
    return image_write_png_bytes(img->rgb, img->width, img->height, path, err, err_size);
}

uint8_t *image_read_rgb(const char *path, int *width, int *height, char *err, size_t err_size) {
    size_t size = 0;
    uint8_t *bytes = infile_read_whole(path, IMAGE_FILE_MAX_BYTES, &size, err, err_size);
    if (bytes == NULL)
        return NULL;
    int channels = 0, palette_size = 0;
    enum png_palette_verdict palette = png_palette_check(bytes, size, &palette_size);
    /* stb_image keeps its last failure's reason until the next one, and some failures give none: the
     * reason is first set to a known one (by asking about an empty buffer) and shown only when the
     * decoder replaced it, as image_map.c does. */
    stbi_info_from_memory(bytes, 0, &channels, &channels, &channels);
    const char *stale = stbi_failure_reason();
    uint8_t *rgb = NULL;
    if (palette == PNG_PALETTE_INDEX_PAST_END)
        snprintf(err, err_size, "%s: damaged: a pixel's palette index is past the end of its palette (%d colours)",
                 path, palette_size);
    else if (palette == PNG_PALETTE_OUT_OF_MEMORY)
        snprintf(err, err_size, "%s: out of memory", path);
    else if ((rgb = stbi_load_from_memory(bytes, (int)size, width, height, &channels, 3)) == NULL) {
        const char *reason = stbi_failure_reason();
        snprintf(err, err_size, "%s: cannot read image: %s", path,
                 reason == stale || reason == NULL ? "the decoder gives no reason" : reason);
    }
    free(bytes);
    if (rgb != NULL && (*width > IMAGE_MAX_SIDE || *height > IMAGE_MAX_SIDE)) {
        snprintf(err, err_size, "%s: image larger than %d pixels on a side", path, IMAGE_MAX_SIDE);
        stbi_image_free(rgb);
        rgb = NULL;
    }
    return rgb;
}

/* box_filter.h: a picture averaged down by an n x n box, to set POV-Ray's one-ray-a-pixel render at n
 * times the size beside chapter 12's n x n grid (tools, not a chapter; docs/12-antialias.md).
 *
 * Rendered n times as wide and high with one ray through each pixel centre, POV-Ray shoots exactly the
 * rays of chapter 12's regular n x n grid; the mean of each n x n block of its pixels is then the
 * grid's box filter. POV-Ray writes the big picture linear (File_Gamma=1.0) and best in 16 bits a
 * channel, so that averaging adds less than a hundredth of an 8-bit level of rounding. */
#ifndef WHITTED_BOX_FILTER_H
#define WHITTED_BOX_FILTER_H

#include <stddef.h>
#include <stdint.h>

/* Reads the PNG at `path` (8 or 16 bits a channel; its width and height must be multiples of n) and
 * returns a malloc'd picture of width / n x height / n 8-bit RGB pixels (the caller frees it), each
 * the mean of an n x n block of the file's pixels, quantised as image_quantize does. Sets *width and
 * *height to the small picture's size. On failure returns NULL with "path: reason" in err. */
uint8_t *box_filter_png(const char *path, int n, int *width, int *height, char *err, size_t err_size);

#endif

/* png_palette.h: PNG files whose pixels name colours past the end of their palette, found before their
 * pixels are used (chapter 1, for every picture read back; chapter 14's image maps).
 *
 * A PNG of colour type 3 stores each pixel as an index into its palette (its PLTE chunk), and the
 * palette may list fewer colours than the bit depth can name: an 8-bit file of 16 colours is common.
 * An index past the palette's end is an error by the PNG specification. stb_image does not check for
 * it: it looks such an index up in a table the file never filled, so the pixel's colour is whatever
 * that memory held, and the picture changes from run to run. */
#ifndef WHITTED_PNG_PALETTE_H
#define WHITTED_PNG_PALETTE_H

#include <stddef.h>
#include <stdint.h>

/* What png_palette_check found. */
enum png_palette_verdict {
    PNG_PALETTE_FITS,           /* not a palette PNG, or every pixel names a colour of the palette */
    PNG_PALETTE_INDEX_PAST_END, /* some pixel names a colour past the palette's end */
    PNG_PALETTE_OUT_OF_MEMORY,
};

/* Checks the PNG (or other file) in bytes[0..size). A palette PNG whose palette holds fewer colours
 * than its bit depth can name is decoded twice, as a copy whose palette is filled up to that number
 * with black, and as one filled with white: the two pictures (in grey levels) differ exactly when a
 * pixel names one of the added colours. A file the decoder cannot read at all counts as fitting: the caller's own decode
 * says what is wrong with it. *palette_size is the number of colours the palette holds (0 when the file
 * is not a palette PNG). */
enum png_palette_verdict png_palette_check(const uint8_t *bytes, size_t size, int *palette_size);

#endif

/* image_map.h: image maps, pictures wrapped over surfaces (chapter 14; docs/14-textures.md).
 *
 * Reading: a PNG or JPEG file through stb_image, every pixel decoded to linear light as POV-Ray 3.7
 * decodes an image map under `assumed_gamma 1.0`. The file's numbers are encoded, not light: a PNG
 * with an sRGB chunk, or with neither an sRGB nor a gAMA chunk, and every JPEG, is decoded with the
 * sRGB curve (POV-Ray follows the PNG and W3C recommendations); a PNG with only a gAMA chunk g is
 * decoded as value^(1/g). Alpha is never decoded: it is a share, not light. A greyscale PNG of 8 bits
 * or fewer is then cut down to whole 255ths of linear light, as POV-Ray stores it (docs/povray.md).
 *
 * Looking up: the point (in texture space) gives (u, v) by the pigment's mapping, planar or spherical,
 * then a pixel by POV-Ray's rules: v runs up the picture while its rows run down, `interpolate 0` takes
 * the pixel the point falls in, `interpolate 2` blends the four around it, and `wrap once` leaves
 * everything outside the one copy transparent. */
#ifndef WHITTED_IMAGE_MAP_H
#define WHITTED_IMAGE_MAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pigment.h"

#define IMAGE_MAP_MAX_PIXELS (64L * 1024 * 1024) /* larger images are refused: 1 GiB of floats */
#define IMAGE_MAP_MAX_SIDE (16L * 1024 * 1024) /* longer sides are refused: stb_image's own limit */

/* Returns the linear light of an sRGB-encoded value in [0, 1] (POV-Ray's SRGBGammaCurve::Decode). */
float image_map_decode_srgb(float encoded);

/* Looks for the chunks that say how the PNG file bytes[0..size) is encoded, before its image data.
 * Returns 0 when the sRGB curve applies (an sRGB chunk, or no gAMA chunk), otherwise the gAMA chunk's
 * encoding gamma (e.g. 0.45455). Not a PNG: 0. */
double image_map_png_gamma(const uint8_t *bytes, size_t size);

/* Reads the image file at `path` into *image as linear red, green, blue and alpha, and notes whether
 * every alpha is 1 (image->opaque: POV-Ray's test for an image that lets no light through). Before the
 * decoder sees the bytes, their signature and header are checked. Returns false with the reason in words
 * in why ("path: cannot open: ...", "path: not a PNG or JPEG image (...)", "path: a JPEG named as a
 * PNG: ...", "path: truncated: ...", "path: its header declares 100000 x 100000 pixels, more than the
 * 67108864 an image map may have", "path: a kind of PNG that is not supported (...)") and *image empty. */
bool image_map_read(const char *path, struct pigment_image *image, char *why, size_t why_size);

/* The checks image_map_read makes on a file's bytes[0..size) before any decoder sees them: a PNG or
 * JPEG by its signature and its name (`path`, which messages start with), whole, with a header of a
 * kind the decoder takes (for a JPEG, Huffman tables of at most 256 symbols, which stb_image would
 * write past its arrays on) and a declared size within IMAGE_MAP_MAX_PIXELS. Returns true with the
 * declared size in *declared_width and *declared_height, or false with the reason in why. Needs no
 * decoder, so it is safe on any bytes. */
bool image_map_check_header(const char *path, const uint8_t *bytes, size_t size, long *declared_width,
                            long *declared_height, char *why, size_t why_size);

/* Looks the image of p up at the texture-space point q, writing red, green, blue and alpha into rgba.
 * Returns false (and rgba white, alpha 0) where p shows nothing: outside the one copy of `wrap once`,
 * or at the centre of a spherical map. */
bool image_map_lookup(const struct pigment *p, vec3 q, double rgba[4]);

#endif

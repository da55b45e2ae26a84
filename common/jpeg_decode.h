/* jpeg_decode.h: a JPEG's pixels as libjpeg, POV-Ray's decoder, gives them (chapter 14).
 *
 * POV-Ray 3.7 reads a JPEG image map with libjpeg's defaults: the "islow" inverse DCT and "fancy"
 * upsampling of colour kept at half resolution. stb_image, which reads our pictures, computes both
 * otherwise (a 12-bit inverse DCT, other rounding when filling in colour and converting it to RGB), and a
 * busy JPEG then differed by 1 to 3 levels in a few percent of its values, enough to fail the agreement
 * with POV-Ray. So the image maps' JPEGs are decoded here in libjpeg's arithmetic, with stb_image reading
 * the file itself. Covered: baseline and progressive files of one (grey) or three (YCbCr) components,
 * any of the usual samplings (4:4:4, 4:2:2, 4:2:0, 4:4:0). Others (CMYK, RGB by their components'
 * names or an Adobe marker) are left to stb_image. */
#ifndef WHITTED_JPEG_DECODE_H
#define WHITTED_JPEG_DECODE_H

#include <stdint.h>

enum jpeg_decoded {
    JPEG_DECODED,     /* *rgba holds width x height pixels, 4 bytes each (alpha 255); free() it */
    JPEG_NOT_HANDLED, /* a kind this does not decode: decode it with stb_image */
    JPEG_FAILED       /* damaged, or out of memory: stbi_failure_reason() says which */
};

/* Decodes the JPEG file bytes[0 .. size) into *rgba, *width and *height, as described above. */
enum jpeg_decoded jpeg_decode(const uint8_t *bytes, int size, uint8_t **rgba, int *width, int *height);

#endif

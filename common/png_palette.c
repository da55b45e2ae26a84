/* png_palette.c: palette PNGs checked for pixels that name colours past the end of their palette
 * (chapter 1; png_palette.h says why and how). */
#include "png_palette.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

/* A PNG's signature, where its header (IHDR, the first chunk) keeps the bit depth and the colour type,
 * the colour type of a palette file, and the bytes a chunk adds to its data: its length, its type and
 * its CRC, 4 each. */
#define PNG_SIGNATURE_BYTES 8
#define PNG_HEADER_END 33
#define PNG_BIT_DEPTH_AT 24
#define PNG_COLOUR_TYPE_AT 25
#define PNG_COLOUR_TYPE_PALETTE 3
#define PNG_CHUNK_FRAME 12
/* The largest bit depth of a palette PNG: 8, whose palette may hold 256 colours. */
#define PNG_PALETTE_DEPTH_MAX 8
/* The copies are decoded to grey levels, a byte a pixel: an added colour is black (0) in one and white
 * (255) in the other, and a colour of the palette gives both the same level. */
#define PNG_PALETTE_CHANNELS 1

static const uint8_t png_signature[PNG_SIGNATURE_BYTES] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

static uint32_t read_32(const uint8_t *b) {
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | (uint32_t)b[3];
}

static void write_32(uint8_t *b, uint32_t value) {
    for (int k = 0; k < 4; k++)
        b[k] = (uint8_t)(value >> (24 - 8 * k));
}

/* The CRC that ends a PNG chunk, of its type and data (the PNG specification's annex D), a bit at a
 * time: it is taken of one palette, at most 772 bytes. */
static uint32_t png_crc(const uint8_t *bytes, size_t size) {
    uint32_t crc = 0xffffffffu;
    for (size_t k = 0; k < size; k++) {
        crc ^= bytes[k];
        for (int bit = 0; bit < 8; bit++)
            crc = crc & 1u ? 0xedb88320u ^ (crc >> 1) : crc >> 1;
    }
    return crc ^ 0xffffffffu;
}

/* Where the palette chunk of the PNG bytes[0..size) starts, or 0 when none comes before the pixels
 * (the decoder refuses such a file) or the chunks run past the file's end. */
static size_t palette_chunk(const uint8_t *bytes, size_t size) {
    size_t at = PNG_SIGNATURE_BYTES;
    while (size - at >= PNG_CHUNK_FRAME) {
        uint32_t length = read_32(bytes + at);
        const uint8_t *type = bytes + at + 4;
        if (length > size - at - PNG_CHUNK_FRAME || memcmp(type, "IDAT", 4) == 0)
            return 0;
        if (memcmp(type, "PLTE", 4) == 0)
            return at;
        at += PNG_CHUNK_FRAME + (size_t)length;
    }
    return 0;
}

/* Decodes the PNG copy[0..size) to grey levels; NULL when the decoder cannot. */
static uint8_t *decode(const uint8_t *copy, size_t size, int *width, int *height) {
    int channels;
    return stbi_load_from_memory(copy, (int)size, width, height, &channels, PNG_PALETTE_CHANNELS);
}

enum png_palette_verdict png_palette_check(const uint8_t *bytes, size_t size, int *palette_size) {
    *palette_size = 0;
    if (size < PNG_HEADER_END || size > INT32_MAX || memcmp(bytes, png_signature, sizeof png_signature) != 0 ||
        bytes[PNG_COLOUR_TYPE_AT] != PNG_COLOUR_TYPE_PALETTE || bytes[PNG_BIT_DEPTH_AT] < 1 ||
        bytes[PNG_BIT_DEPTH_AT] > PNG_PALETTE_DEPTH_MAX)
        return PNG_PALETTE_FITS; /* not a palette PNG, or one the decoder refuses */
    size_t at = palette_chunk(bytes, size);
    if (at == 0)
        return PNG_PALETTE_FITS;
    size_t length = read_32(bytes + at), colours = (size_t)1 << bytes[PNG_BIT_DEPTH_AT];
    if (length % 3 != 0 || length / 3 > colours)
        return PNG_PALETTE_FITS; /* a palette the decoder refuses */
    *palette_size = (int)(length / 3);
    if (length / 3 == colours)
        return PNG_PALETTE_FITS; /* every index the bit depth can write names a colour */

    /* The copy: the file up to the palette's data, the palette filled up to `colours` entries, its CRC,
     * and the rest of the file. */
    size_t data = at + 8, grown = 3 * colours, after = data + length + 4;
    size_t copy_size = data + grown + 4 + (size - after);
    uint8_t *copy = malloc(copy_size);
    if (copy == NULL)
        return PNG_PALETTE_OUT_OF_MEMORY;
    memcpy(copy, bytes, data + length);
    write_32(copy + at, (uint32_t)grown);
    memcpy(copy + data + grown + 4, bytes + after, size - after);
    uint8_t *picture[2] = {NULL, NULL};
    int width[2] = {0, 0}, height[2] = {0, 0};
    for (int fill = 0; fill < 2; fill++) { /* black, then white */
        memset(copy + data + length, fill == 0 ? 0x00 : 0xff, grown - length);
        write_32(copy + data + grown, png_crc(copy + at + 4, 4 + grown));
        picture[fill] = decode(copy, copy_size, &width[fill], &height[fill]);
    }
    free(copy);
    enum png_palette_verdict verdict = PNG_PALETTE_FITS; /* also when the decoder refused the file */
    if (picture[0] != NULL && picture[1] != NULL && width[0] == width[1] && height[0] == height[1] &&
        memcmp(picture[0], picture[1], (size_t)width[0] * (size_t)height[0] * PNG_PALETTE_CHANNELS) != 0)
        verdict = PNG_PALETTE_INDEX_PAST_END;
    stbi_image_free(picture[0]);
    stbi_image_free(picture[1]);
    return verdict;
}

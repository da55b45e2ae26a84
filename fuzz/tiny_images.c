/* tiny_images.c: small PNG and JPEG files of every kind the image-map reader takes (tiny_images.h). */
#include "tiny_images.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#define TINY_IMAGE_MAX_SIDE 16
#define TINY_IMAGE_MAX_BYTES (TINY_IMAGE_MAX_SIDE * TINY_IMAGE_MAX_SIDE * 4 * 2)
#define TINY_ALPHA_PART 128 /* the alpha of every third pixel of an image with alpha (of 255) */
#define PNG_GAMMA_045455 45455 /* a gAMA chunk's number for gamma 1 / 2.2 */
#define ZLIB_STORED_MAX 65535 /* bytes one stored deflate block holds */
#define ADLER_MODULUS 65521u
#define CRC32_POLYNOMIAL 0xEDB88320u

enum writer { STB_PNG, STORED_PNG, STB_JPEG };

struct tiny_image {
    const char *name;
    enum writer writer;
    int width, height, channels, bits; /* bits: 8, or 16 for a stored PNG */
    const char *chunk;                 /* a stored PNG's extra chunk before its data: "sRGB", "gAMA" or NULL */
    int quality;                       /* a JPEG's (stb subsamples the colour below 90) */
};

static const struct tiny_image images[TINY_IMAGE_COUNT] = {
    {"rgb.png", STB_PNG, 5, 4, 3, 8, NULL, 0},
    {"rgba.png", STB_PNG, 4, 4, 4, 8, NULL, 0},
    {"grey.png", STB_PNG, 3, 2, 1, 8, NULL, 0},
    {"grey-alpha.png", STB_PNG, 2, 3, 2, 8, NULL, 0},
    {"rgba-16.png", STORED_PNG, 3, 3, 4, 16, NULL, 0},
    {"srgb.png", STORED_PNG, 4, 2, 3, 8, "sRGB", 0},
    {"gamma.png", STORED_PNG, 2, 2, 3, 8, "gAMA", 0},
    {"rgb.jpg", STB_JPEG, 8, 8, 3, 8, NULL, 95},
    {"rgb-subsampled.jpg", STB_JPEG, 16, 16, 3, 8, NULL, 50},
    {"grey.jpg", STB_JPEG, 8, 8, 1, 8, NULL, 90},
};

const char *tiny_image_name(size_t k) { return images[k].name; }

/* Sample c of pixel (x, y) in 8 bits: a colour for each pixel, the last of 2 or 4 channels alpha. */
static bool is_alpha(const struct tiny_image *t, int c) { return (t->channels == 2 || t->channels == 4) && c == t->channels - 1; }

static uint8_t sample(const struct tiny_image *t, int x, int y, int c) {
    if (is_alpha(t, c))
        return (x + y) % 3 == 0 ? TINY_ALPHA_PART : 255;
    return (uint8_t)((x * 7 + y * 13 + c * 5) * 37 % 256);
}

/* The image's samples, rows top first, as bytes: 8 bits each, or 16 big-endian (a colour's low byte
 * differs from its high byte, so that a reader keeping only 8 bits reads other numbers). */
static size_t draw(const struct tiny_image *t, uint8_t *out) {
    size_t n = 0;
    for (int y = 0; y < t->height; y++)
        for (int x = 0; x < t->width; x++)
            for (int c = 0; c < t->channels; c++) {
                uint8_t v = sample(t, x, y, c);
                out[n++] = v;
                if (t->bits == 16)
                    out[n++] = is_alpha(t, c) ? v : (uint8_t)(x * 17 + y * 5);
            }
    return n;
}

static uint32_t crc32_update(uint32_t crc, const uint8_t *bytes, size_t size) {
    crc = ~crc;
    for (size_t k = 0; k < size; k++) {
        crc ^= bytes[k];
        for (int bit = 0; bit < 8; bit++)
            crc = (crc >> 1) ^ (CRC32_POLYNOMIAL & (0u - (crc & 1u)));
    }
    return ~crc;
}

static void put_32(uint8_t *b, uint32_t v) {
    b[0] = (uint8_t)(v >> 24);
    b[1] = (uint8_t)(v >> 16);
    b[2] = (uint8_t)(v >> 8);
    b[3] = (uint8_t)v;
}

/* Writes one PNG chunk: length, type, data, CRC of type and data. */
static bool write_chunk(FILE *f, const char *type, const uint8_t *data, uint32_t length) {
    uint8_t head[8], tail[4];
    put_32(head, length);
    memcpy(head + 4, type, 4);
    put_32(tail, crc32_update(crc32_update(0, head + 4, 4), data, length));
    return fwrite(head, 1, 8, f) == 8 && (length == 0 || fwrite(data, 1, length, f) == length) &&
           fwrite(tail, 1, 4, f) == 4;
}

/* A PNG whose image data is one stored (uncompressed) deflate block, with t->chunk before it. */
static bool write_stored_png(FILE *f, const struct tiny_image *t) {
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const uint8_t colour_type[5] = {0, 0, 4, 2, 6}; /* by channels: grey, grey + alpha, RGB, RGBA */
    uint8_t samples[TINY_IMAGE_MAX_BYTES], raw[TINY_IMAGE_MAX_BYTES + TINY_IMAGE_MAX_SIDE];
    uint8_t zlib[sizeof raw + 11];
    draw(t, samples);
    size_t row = (size_t)t->width * (size_t)t->channels * (size_t)t->bits / 8, size = 0;
    for (int y = 0; y < t->height; y++) {
        raw[size++] = 0; /* filter: none */
        memcpy(raw + size, samples + (size_t)y * row, row);
        size += row;
    }
    uint32_t a = 1, b = 0;
    for (size_t k = 0; k < size; k++) {
        a = (a + raw[k]) % ADLER_MODULUS;
        b = (b + a) % ADLER_MODULUS;
    }
    size_t z = 0;
    zlib[z++] = 0x78; /* deflate, 32 KiB window */
    zlib[z++] = 0x01; /* no dictionary, fastest; (0x78 0x01) is a multiple of 31 */
    zlib[z++] = 0x01; /* the final block, stored */
    zlib[z++] = (uint8_t)(size & 0xff);
    zlib[z++] = (uint8_t)(size >> 8);
    zlib[z++] = (uint8_t)(~size & 0xff);
    zlib[z++] = (uint8_t)((~size >> 8) & 0xff);
    memcpy(zlib + z, raw, size);
    z += size;
    put_32(zlib + z, b << 16 | a);
    z += 4;
    uint8_t header[13];
    put_32(header, (uint32_t)t->width);
    put_32(header + 4, (uint32_t)t->height);
    header[8] = (uint8_t)t->bits;
    header[9] = colour_type[t->channels];
    header[10] = header[11] = header[12] = 0; /* deflate, adaptive filters, not interlaced */
    uint8_t gamma[4], srgb_intent[1] = {0};
    put_32(gamma, PNG_GAMMA_045455);
    bool ok = fwrite(signature, 1, sizeof signature, f) == sizeof signature && write_chunk(f, "IHDR", header, 13);
    if (ok && t->chunk != NULL)
        ok = strcmp(t->chunk, "gAMA") == 0 ? write_chunk(f, "gAMA", gamma, 4) : write_chunk(f, "sRGB", srgb_intent, 1);
    return ok && z <= ZLIB_STORED_MAX && write_chunk(f, "IDAT", zlib, (uint32_t)z) && write_chunk(f, "IEND", NULL, 0);
}

static bool write_image(const char *path, const struct tiny_image *t) {
    uint8_t samples[TINY_IMAGE_MAX_BYTES];
    if (t->writer != STORED_PNG) {
        draw(t, samples);
        return t->writer == STB_PNG ? stbi_write_png(path, t->width, t->height, t->channels, samples,
                                                     t->width * t->channels) != 0
                                    : stbi_write_jpg(path, t->width, t->height, t->channels, samples, t->quality) != 0;
    }
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        return false;
    bool ok = write_stored_png(f, t);
    return fclose(f) == 0 && ok;
}

bool tiny_images_write(const char *folder, char *err, size_t err_size) {
    for (size_t k = 0; k < TINY_IMAGE_COUNT; k++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", folder, images[k].name);
        if (!write_image(path, &images[k])) {
            snprintf(err, err_size, "%s: cannot write", path);
            return false;
        }
    }
    return true;
}

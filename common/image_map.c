/* image_map.c: reading image maps into linear light, and looking them up as POV-Ray 3.7 does
 * (chapter 14; image_map.h says what and why). */
#include "image_map.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "infile.h"
#include "jpeg_decode.h"
#include "png_palette.h"

#define IMAGE_MAP_FILE_MAX_BYTES (256L * 1024 * 1024) /* no PNG or JPEG we read is larger */
/* POV-Ray adds its EPSILON to the pixel coordinates before wrapping them (map_pos). */
#define IMAGE_MAP_EPSILON 1e-10
/* The sRGB curve's linear toe ends at this encoded value (POV-Ray's threshold; the older 0.03928 is from
 * a draft). */
#define SRGB_DECODE_THRESHOLD 0.04045f
#define PNG_GAMMA_UNIT 100000.0 /* a gAMA chunk holds the gamma times 100000 */
/* Where a PNG's header (IHDR) keeps its bit depth and colour type, and the types of a grey and an RGB file. */
#define PNG_BIT_DEPTH_AT 24
#define PNG_COLOUR_TYPE_AT 25
#define PNG_COLOUR_TYPE_GREY 0
#define PNG_COLOUR_TYPE_RGB 2
/* POV-Ray's weights for making a colour grey (Image::RGB2Gray), applied in single precision. */
#define POVRAY_GREY_RED 0.297f
#define POVRAY_GREY_GREEN 0.589f
#define POVRAY_GREY_BLUE 0.114f

float image_map_decode_srgb(float encoded) {
    if (encoded < SRGB_DECODE_THRESHOLD)
        return encoded / 12.92f;
    return powf((encoded + 0.055f) / 1.055f, 2.4f);
}

/* The first bytes of every PNG and every JPEG file. */
static const uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
static const uint8_t jpeg_signature[3] = {0xff, 0xd8, 0xff};

static uint32_t big_endian_32(const uint8_t *b) {
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | (uint32_t)b[3];
}

/* The first chunk named `name` among those before a PNG's pixel data (its first IDAT chunk), or NULL;
 * *length is its data's length. bytes[0..size) need not be a PNG (then NULL). */
static const uint8_t *png_chunk_before_pixels(const uint8_t *bytes, size_t size, const char name[4],
                                              uint32_t *length) {
    if (size < sizeof png_signature || memcmp(bytes, png_signature, sizeof png_signature) != 0)
        return NULL;
    size_t at = sizeof png_signature;
    while (size - at >= 12) { /* length, type, data, CRC */
        uint32_t data_length = big_endian_32(bytes + at);
        const uint8_t *type = bytes + at + 4;
        if (data_length > size - at - 12 || memcmp(type, "IDAT", 4) == 0)
            return NULL;
        if (memcmp(type, name, 4) == 0) {
            *length = data_length;
            return type + 4;
        }
        at += 12 + (size_t)data_length;
    }
    return NULL;
}

double image_map_png_gamma(const uint8_t *bytes, size_t size) {
    uint32_t length;
    if (png_chunk_before_pixels(bytes, size, "sRGB", &length) != NULL)
        return 0.0; /* the sRGB chunk wins over gAMA, as in POV-Ray */
    const uint8_t *gamma = png_chunk_before_pixels(bytes, size, "gAMA", &length);
    return gamma != NULL && length == 4 && big_endian_32(gamma) > 0 ? big_endian_32(gamma) / PNG_GAMMA_UNIT : 0.0;
}

/* Whether bytes[0..size) is a PNG of grey levels or of RGB colours (no alpha channel, no palette) with a
 * tRNS chunk: one colour that stands for "transparent", a colour key. The decoder makes such pixels
 * transparent, as the PNG specification says. */
static bool png_has_colour_key(const uint8_t *bytes, size_t size) {
    uint32_t length;
    return size > PNG_COLOUR_TYPE_AT &&
           (bytes[PNG_COLOUR_TYPE_AT] == PNG_COLOUR_TYPE_GREY || bytes[PNG_COLOUR_TYPE_AT] == PNG_COLOUR_TYPE_RGB) &&
           png_chunk_before_pixels(bytes, size, "tRNS", &length) != NULL;
}

/* Whether bytes[0..size) is a PNG of grey levels without an alpha channel, 8 bits or fewer a pixel:
 * the files POV-Ray 3.7 stores as whole 255ths of linear light (povray_grey_level). */
static bool png_is_grey_8bit(const uint8_t *bytes, size_t size) {
    return size > PNG_COLOUR_TYPE_AT && memcmp(bytes + 1, "PNG", 3) == 0 && memcmp(bytes + 12, "IHDR", 4) == 0 &&
           bytes[PNG_BIT_DEPTH_AT] <= 8 && bytes[PNG_COLOUR_TYPE_AT] == PNG_COLOUR_TYPE_GREY;
}

/* The linear light POV-Ray 3.7 keeps for a grey level of such a PNG: it decodes the level to linear
 * light, makes the colour grey (png.cpp passes it as a colour-map entry to an 8-bit grey image,
 * Gray_Int8), and stores that as an 8-bit integer, cutting off the fraction (GrayImage::SetGrayValue).
 * So a grey PNG is up to one 255th of linear light darker than its RGB twin, which keeps the decoded
 * value whole (RGB_Gamma8 decodes on lookup). */
static float povray_grey_level(float linear) {
    float grey = linear * POVRAY_GREY_RED + linear * POVRAY_GREY_GREEN + linear * POVRAY_GREY_BLUE;
    return (float)(uint8_t)(grey * 255.0f) / 255.0f;
}

/* ---- the file's header, read before the decoder sees it ------------------------------------------ */

#define PNG_HEADER_END 33 /* signature 8, IHDR's length and type 8, its data 13, its CRC 4 */

/* True when PNG allows bit depth `depth` with colour type `type` (the PNG specification, table 11.1);
 * these are all stb_image decodes. */
static bool png_kind_supported(int type, int depth) {
    switch (type) {
    case 0: /* grey */
        return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3: /* palette */
        return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2: /* RGB */
    case 4: /* grey and alpha */
    case 6: /* RGBA */
        return depth == 8 || depth == 16;
    default:
        return false;
    }
}

/* Reads a PNG's size from its IHDR chunk; false with why for a header that is cut short or not PNG's,
 * or a kind of PNG the reader does not take. */
static bool png_header(const uint8_t *b, size_t size, long *width, long *height, char *why, size_t why_size) {
    if (size < PNG_HEADER_END) {
        snprintf(why, why_size, "truncated: %zu bytes, too few for a PNG's header", size);
        return false;
    }
    if (big_endian_32(b + 8) != 13 || memcmp(b + 12, "IHDR", 4) != 0) {
        snprintf(why, why_size, "a damaged PNG: its first chunk is not the image header (IHDR)");
        return false;
    }
    *width = (long)big_endian_32(b + 16);
    *height = (long)big_endian_32(b + 20);
    int depth = b[24], type = b[25], compression = b[26], filter = b[27], interlace = b[28];
    if (!png_kind_supported(type, depth) || compression != 0 || filter != 0 || interlace > 1) {
        snprintf(why, why_size, "a kind of PNG that is not supported (colour type %d, bit depth %d, compression "
                 "%d, filter %d, interlace %d)", type, depth, compression, filter, interlace);
        return false;
    }
    return true;
}

/* True when the PNG b[0..size) holds every chunk it starts, up to its end chunk (IEND); otherwise false
 * with why saying where the file was cut short. Each chunk is its length (4 bytes), type (4), data and
 * CRC (4). */
static bool png_chunks_whole(const uint8_t *b, size_t size, char *why, size_t why_size) {
    size_t at = sizeof png_signature;
    while (at + 8 <= size) {
        size_t length = big_endian_32(b + at), end = at + 12 + length;
        bool named = isalpha(b[at + 4]) && isalpha(b[at + 5]) && isalpha(b[at + 6]) && isalpha(b[at + 7]);
        if (end > size || end < at) {
            snprintf(why, why_size, "truncated: the file ends inside its %s%.*s%s chunk, %zu bytes short",
                     named ? "'" : "", named ? 4 : 0, (const char *)b + at + 4, named ? "'" : "unnamed",
                     end < at ? (size_t)length : end - size);
            return false;
        }
        if (memcmp(b + at + 4, "IEND", 4) == 0)
            return true;
        at = end;
    }
    snprintf(why, why_size, "truncated: %zu bytes, and no end chunk (IEND) among them", size);
    return false;
}

/* Reads a JPEG's size from its frame header (SOF), walking the segments before it; false with why for a
 * file cut short before it, or a kind of JPEG the decoder does not take (only baseline and progressive
 * Huffman-coded JPEGs are: not lossless, hierarchical or arithmetic-coded ones). */
static bool jpeg_header(const uint8_t *b, size_t size, long *width, long *height, char *why, size_t why_size) {
    size_t at = 2; /* after the start-of-image marker */
    while (at + 4 <= size) {
        if (b[at] != 0xff) {
            snprintf(why, why_size, "a damaged JPEG: no marker at byte %zu", at);
            return false;
        }
        int marker = b[at + 1];
        if (marker == 0xff) { /* fill bytes before a marker */
            at++;
            continue;
        }
        size_t length = (size_t)b[at + 2] << 8 | b[at + 3];
        bool frame = marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
        if (frame) {
            if (marker > 0xc2) {
                snprintf(why, why_size, "a kind of JPEG that is not supported (frame type 0x%02x: only baseline "
                         "and progressive JPEGs are)", marker);
                return false;
            }
            if (at + 9 > size)
                break;
            *height = (long)b[at + 5] << 8 | b[at + 6];
            *width = (long)b[at + 7] << 8 | b[at + 8];
            return true;
        }
        if (marker == 0xd9 || marker == 0xda || length < 2)
            break; /* the end, or the image data, before any frame header */
        at += 2 + length;
    }
    snprintf(why, why_size, "truncated or damaged: %zu bytes, and no JPEG frame header among them", size);
    return false;
}

#define JPEG_HUFFMAN_MAX_SYMBOLS 256 /* a Huffman table codes at most 256 symbols (one per byte value) */

/* The byte at b[at], or 0 past the end, as the decoder reads a stream that has run out. */
static int byte_or_zero(const uint8_t *b, size_t size, size_t at) {
    return at < size ? b[at] : 0;
}

/* True when every Huffman table (DHT segment) of the JPEG b[0..size) codes at most 256 symbols. The
 * decoder (stb_image 2.27) adds a table's 16 code counts up without checking and writes past its arrays
 * when they come to more, so such a file must never reach it. The walk goes from segment to segment as
 * the decoder does, past each scan's coded data (where 0xff is followed by 0x00, a restart marker or
 * another 0xff) to the next marker, since a progressive JPEG puts tables between its scans; a table cut
 * short by the segment's length or the file's end is read on, as the decoder reads it. */
static bool jpeg_huffman_tables_fit(const uint8_t *b, size_t size) {
    size_t at = 2; /* after the start-of-image marker */
    while (at + 1 < size) {
        if (b[at] != 0xff || b[at + 1] == 0xff) { /* not a marker here: fill bytes, or damage */
            at++;
            continue;
        }
        int marker = b[at + 1];
        if (marker == 0xd8 || marker == 0xd9 || (marker >= 0xd0 && marker <= 0xd7) || marker == 0x01 ||
            marker == 0x00) { /* no length follows */
            at += 2;
            continue;
        }
        size_t length = (size_t)byte_or_zero(b, size, at + 2) << 8 | (size_t)byte_or_zero(b, size, at + 3);
        size_t end = at + 2 + length;
        if (marker == 0xc4) {
            for (size_t table = at + 4; table < end && table < size;) {
                size_t symbols = 0;
                for (size_t k = 1; k <= 16; k++)
                    symbols += (size_t)byte_or_zero(b, size, table + k);
                if (symbols > JPEG_HUFFMAN_MAX_SYMBOLS)
                    return false;
                table += 17 + symbols;
            }
        }
        at = end < at + 4 ? at + 4 : end;
        if (marker == 0xda) /* a scan: its coded data runs to the next real marker */
            while (at + 1 < size && !(b[at] == 0xff && b[at + 1] != 0x00 && b[at + 1] != 0xff &&
                                      !(b[at + 1] >= 0xd0 && b[at + 1] <= 0xd7)))
                at++;
    }
    return true;
}

bool image_map_check_header(const char *path, const uint8_t *bytes, size_t size, long *declared_width,
                            long *declared_height, char *why, size_t why_size) {
    char reason[256];
    long width = 0, height = 0;
    bool ok;
    if (size >= sizeof png_signature && memcmp(bytes, png_signature, sizeof png_signature) == 0)
        ok = png_header(bytes, size, &width, &height, reason, sizeof reason) &&
             png_chunks_whole(bytes, size, reason, sizeof reason);
    else if (size >= sizeof jpeg_signature && memcmp(bytes, jpeg_signature, sizeof jpeg_signature) == 0) {
        ok = jpeg_huffman_tables_fit(bytes, size);
        if (!ok)
            snprintf(reason, sizeof reason, "a damaged JPEG: a Huffman table codes more than %d symbols",
                     JPEG_HUFFMAN_MAX_SYMBOLS);
        else
            ok = jpeg_header(bytes, size, &width, &height, reason, sizeof reason);
    } else {
        ok = false;
        snprintf(reason, sizeof reason, "not a PNG or JPEG image (its first bytes are neither signature%s)",
                 size >= 2 && memcmp(bytes, "BM", 2) == 0   ? ": a BMP, it seems"
                 : size >= 4 && memcmp(bytes, "GIF8", 4) == 0 ? ": a GIF, it seems"
                                                               : "");
    }
    bool named_jpeg = pigment_file_is_jpeg(path);
    if (ok && named_jpeg != (bytes[0] == jpeg_signature[0])) {
        ok = false;
        snprintf(reason, sizeof reason, "a %s named as a %s: POV-Ray reads an image map by its name (.jpg or "
                 ".jpeg for a JPEG, anything else for a PNG), so rename it", named_jpeg ? "PNG" : "JPEG",
                 named_jpeg ? "JPEG" : "PNG");
    } else if (ok && (width == 0 || height == 0)) {
        ok = false;
        snprintf(reason, sizeof reason, "its header declares %ld x %ld pixels: an image has at least one", width,
                 height);
    } else if (ok && (unsigned long long)width * (unsigned long long)height > IMAGE_MAP_MAX_PIXELS) {
        ok = false;
        snprintf(reason, sizeof reason, "its header declares %ld x %ld pixels, more than the %ld an image map may "
                 "have", width, height, IMAGE_MAP_MAX_PIXELS);
    } else if (ok && (width > IMAGE_MAP_MAX_SIDE || height > IMAGE_MAP_MAX_SIDE)) {
        ok = false;
        snprintf(reason, sizeof reason, "its header declares %ld x %ld pixels: a side of more than %ld pixels, "
                 "which the decoder does not take", width, height, IMAGE_MAP_MAX_SIDE);
    }
    *declared_width = width;
    *declared_height = height;
    if (!ok)
        snprintf(why, why_size, "%s: %s", path, reason);
    return ok;
}

/* Decodes the file's pixels (8 or 16 bits a channel, any channels) into linear RGBA floats. */
static bool decode(const char *path, const uint8_t *bytes, size_t size, struct pigment_image *image, char *why,
                   size_t why_size) {
    int width, height, channels;
    long declared_width, declared_height;
    if (!image_map_check_header(path, bytes, size, &declared_width, &declared_height, why, why_size))
        return false;
    if (size > INT32_MAX || !stbi_info_from_memory(bytes, (int)size, &width, &height, &channels)) {
        snprintf(why, why_size, "%s: a damaged image: its header cannot be read (the decoder says: %s)", path,
                 stbi_failure_reason());
        return false;
    }
    int palette_size;
    enum png_palette_verdict palette = png_palette_check(bytes, size, &palette_size);
    if (palette != PNG_PALETTE_FITS) {
        if (palette == PNG_PALETTE_INDEX_PAST_END)
            snprintf(why, why_size, "%s: damaged: a pixel's palette index is past the end of its palette (%d "
                     "colours)", path, palette_size);
        else
            snprintf(why, why_size, "%s: out of memory", path);
        return false;
    }
    bool sixteen = stbi_is_16_bit_from_memory(bytes, (int)size);
    /* stb_image keeps its last failure's reason until the next one, and some of its failures give none:
     * a PNG whose compressed data is damaged showed the reason of the JPEG test stbi_info made before
     * ("no SOI"). So the reason is first set to a known one, by asking about an empty buffer, and shown
     * only when the decoder replaced it. */
    int unused;
    stbi_info_from_memory(bytes, 0, &unused, &unused, &unused);
    const char *stale = stbi_failure_reason();
    /* A JPEG is decoded as POV-Ray's libjpeg decodes it (jpeg_decode.h), the kinds it does not cover, and a
     * damaged one (for stb's reason), by stb_image. */
    uint8_t *as_libjpeg = NULL;
    bool jpeg = size >= sizeof jpeg_signature && memcmp(bytes, jpeg_signature, sizeof jpeg_signature) == 0;
    if (jpeg && jpeg_decode(bytes, (int)size, &as_libjpeg, &width, &height) != JPEG_DECODED)
        as_libjpeg = NULL;
    void *pixels = as_libjpeg != NULL ? (void *)as_libjpeg
                   : sixteen          ? (void *)stbi_load_16_from_memory(bytes, (int)size, &width, &height, &channels, 4)
                                      : (void *)stbi_load_from_memory(bytes, (int)size, &width, &height, &channels, 4);
    size_t count = (size_t)width * (size_t)height * 4;
    image->texels = pixels == NULL ? NULL : malloc(count * sizeof *image->texels);
    if (image->texels == NULL) {
        const char *reason = stbi_failure_reason();
        if (pixels == NULL)
            snprintf(why, why_size, "%s: truncated or damaged: its pixels cannot be decoded (%s%s)", path,
                     reason == stale ? "the decoder gives no reason" : "the decoder says: ",
                     reason == stale ? "" : reason);
        else
            snprintf(why, why_size, "%s: out of memory", path);
        if (as_libjpeg != NULL)
            free(as_libjpeg);
        else
            stbi_image_free(pixels);
        return false;
    }
    double gamma = image_map_png_gamma(bytes, size);
    bool grey_levels = !sixteen && png_is_grey_8bit(bytes, size);
    float largest = sixteen ? 65535.0f : 255.0f;
    image->opaque = true;
    for (size_t k = 0; k < count; k++) {
        float value = (sixteen ? ((const uint16_t *)pixels)[k] : ((const uint8_t *)pixels)[k]) / largest;
        if (k % 4 != 3) { /* red, green, blue are encoded light; alpha is a share */
            value = gamma > 0.0 ? powf(value, (float)(1.0 / gamma)) : image_map_decode_srgb(value);
            if (grey_levels)
                value = povray_grey_level(value);
        } else if (value < 1.0f) {
            image->opaque = false;
        }
        image->texels[k] = value;
    }
    if (as_libjpeg != NULL)
        free(as_libjpeg);
    else
        stbi_image_free(pixels);
    image->width = width;
    image->height = height;
    image->colour_key = png_has_colour_key(bytes, size);
    return true;
}

bool image_map_read(const char *path, struct pigment_image *image, char *why, size_t why_size) {
    *image = (struct pigment_image){0};
    size_t size = 0;
    uint8_t *bytes = infile_read_whole(path, IMAGE_MAP_FILE_MAX_BYTES, &size, why, why_size);
    if (bytes == NULL)
        return false;
    bool ok = decode(path, bytes, size, image, why, why_size);
    free(bytes);
    return ok;
}

/* ---- looking up ---------------------------------------------------------------------------------- */

/* x wrapped into [0, limit), as POV-Ray's wrap(); 0 for an x that is not finite, so that whatever
 * double arrives, the result is a safe index once cast. */
static double wrap(double x, double limit) {
    double r = fmod(x, limit);
    if (r < 0.0)
        r += limit;
    if (!(r >= 0.0 && r < limit)) /* not finite, or rounded up to limit */
        r = 0.0;
    return r;
}

/* The column or row of x in an image `size` pixels across, held at the edges: 0 for NaN. */
static int held(double x, int size) {
    return !(x >= 0.0) ? 0 : x >= size ? size - 1 : (int)x;
}

/* (u, v) in pixels, before wrapping, by the pigment's mapping; false where the mapping shows nothing. */
static bool map_point(const struct pigment *p, vec3 q, double *u, double *v) {
    double width = p->image.width, height = p->image.height;
    if (p->mapping == PIGMENT_MAP_PLANAR) { /* x across, y up: POV-Ray's gradient <1, -1, 0> */
        if (p->once && (q.x < 0.0 || q.x > 1.0 || q.y < 0.0 || q.y > 1.0))
            return false;
        *u = fmod(q.x * width, width);
        *v = fmod(q.y * height, height);
        return true;
    }
    double length = vec3_length(q);
    if (length == 0.0)
        return false;
    double x = q.x / length, y = q.y / length, z = q.z / length;
    double latitude = 0.5 + asin(y) / M_PI; /* 0 at the south pole, 1 at the north */
    double longitude = 0.0;                 /* 0 towards +x, growing towards +z, 1 all round */
    double round = sqrt(x * x + z * z);
    if (round != 0.0) {
        if (z == 0.0)
            longitude = x > 0.0 ? 0.0 : M_PI;
        else {
            longitude = acos(x / round);
            if (z < 0.0)
                longitude = 2.0 * M_PI - longitude;
        }
        longitude /= 2.0 * M_PI;
    }
    *u = longitude * width;
    *v = latitude * height;
    return true;
}

/* The pixel (x, y) (rows from the top), wrapped round or held at the edge as `once` says. */
static void pixel(const struct pigment *p, double x, double y, double rgba[4]) {
    int w = p->image.width, h = p->image.height, ix, iy;
    if (p->once) {
        ix = held(x, w);
        iy = held(y, h);
    } else {
        ix = (int)wrap(x, w);
        iy = (int)wrap(y, h);
    }
    const float *t = p->image.texels + 4 * ((size_t)iy * (size_t)w + (size_t)ix);
    for (int c = 0; c < 4; c++)
        rgba[c] = t[c];
}

bool image_map_lookup(const struct pigment *p, vec3 q, double rgba[4]) {
    double u = 0.0, v = 0.0;
    int w = p->image.width, h = p->image.height;
    bool shown = map_point(p, q, &u, &v);
    u += IMAGE_MAP_EPSILON;
    v += IMAGE_MAP_EPSILON;
    if (shown && p->once && (u >= w || v >= h || u < 0.0 || v < 0.0))
        shown = false;
    if (!shown) {
        rgba[0] = rgba[1] = rgba[2] = 1.0;
        rgba[3] = 0.0;
        return false;
    }
    double x = wrap(u, w), y = wrap(-v, h); /* rows run down the picture, v up */
    if (p->interpolate == 0) {
        pixel(p, x, y, rgba);
        return true;
    }
    /* Bilinear, POV-Ray's way: the four pixels whose centres surround the point. */
    x += 0.5;
    y += 0.5;
    int ix = (int)x, iy = (int)y;
    double fx = x - ix, fy = y - iy;
    double corner[4][4];
    pixel(p, ix, iy, corner[0]);
    pixel(p, ix - 1, iy, corner[1]);
    pixel(p, ix, iy - 1, corner[2]);
    pixel(p, ix - 1, iy - 1, corner[3]);
    double weight[4] = {fx * fy, (1 - fx) * fy, fx * (1 - fy), (1 - fx) * (1 - fy)};
    for (int c = 0; c < 4; c++)
        rgba[c] = weight[0] * corner[0][c] + weight[1] * corner[1][c] + weight[2] * corner[2][c] +
                  weight[3] * corner[3][c];
    return true;
}

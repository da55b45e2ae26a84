/* assemble.c: joins the tiles of one picture, rendered apart with a chapter's --tile option (on the
 * machines of a render farm: tools/farm/), into the picture itself (docs/farm.md).
 *
 *   assemble -o PICTURE.png [--size W H] TILE...
 *
 * A TILE is a PNG whose file name ends in tile-X-Y.png, X and Y the column and row of the picture its
 * top-left pixel is (as farm.sh names them), or `--at X Y FILE` for a file named otherwise. The picture
 * is W x H (without --size: as wide and high as the tiles reach from 0 0). Every pixel of it must be in
 * exactly one tile: an overlap, a gap or a tile reaching past the picture is refused with the pixel
 * that shows it, and nothing is written. The picture is written through outfile.h, complete or not at
 * all. Exit status: 0 written, 1 a tile is missing, unreadable or does not fit, 2 a bad command line,
 * 3 the picture cannot be written. */
#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "infile.h"
#include "outfile.h"

#define ASSEMBLE_ERROR_SIZE (PATH_MAX + 256) /* a message: a whole path and the reason */

/* One tile: its file, where its top-left pixel goes, and its size as its header declares it. */
struct tile {
    const char *path;
    int left, top, width, height;
};

/* A PNG's first 24 bytes: its signature, then its header chunk's length, type, width and height. */
#define PNG_SIZE_END 24

/* Reads tile t's size from its PNG header, without decoding a pixel, so that a tile too large for the
 * picture is refused before its pixels take memory. Opens it with infile_open, which never waits (a
 * FIFO is refused). Returns false with "path: reason" in err. */
static bool tile_size(struct tile *t, char *err, size_t err_size) {
    FILE *file = infile_open(t->path, err, err_size);
    if (file == NULL)
        return false;
    static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char b[PNG_SIZE_END];
    bool whole = fread(b, 1, sizeof b, file) == sizeof b;
    fclose(file);
    /* A tile is a PNG, as the chapters write them: stb would also decode a TGA, which has no signature,
     * so that any 18 bytes may pass for one. */
    if (!whole || memcmp(b, png_signature, sizeof png_signature) != 0 || memcmp(b + 12, "IHDR", 4) != 0) {
        snprintf(err, err_size, "%s: not a PNG (its first bytes are not PNG's signature and header)", t->path);
        return false;
    }
    unsigned long width = (unsigned long)b[16] << 24 | (unsigned long)b[17] << 16 | (unsigned long)b[18] << 8 | b[19];
    unsigned long height = (unsigned long)b[20] << 24 | (unsigned long)b[21] << 16 | (unsigned long)b[22] << 8 | b[23];
    if (width < 1 || height < 1 || width > IMAGE_MAX_SIDE || height > IMAGE_MAX_SIDE) {
        snprintf(err, err_size, "%s: its header declares %lu x %lu pixels; a tile has 1 to %d a side", t->path, width,
                 height, IMAGE_MAX_SIDE);
        return false;
    }
    t->width = (int)width;
    t->height = (int)height;
    return true;
}

static void usage(void) {
    fprintf(stderr, "usage: assemble -o PICTURE.png [--size W H] TILE...\n"
                    "  TILE: a PNG named ...tile-X-Y.png (X, Y: the picture's column and row of its\n"
                    "        top-left pixel), or --at X Y FILE for any name\n"
                    "  --size W H: the picture's size (default: as far as the tiles reach from 0 0)\n");
}

/* Reads a whole number in [lo, hi] from the whole of `text`. */
static bool whole_number(const char *text, long lo, long hi, int *out) {
    char *end = NULL;
    errno = 0;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || value < lo || value > hi)
        return false;
    *out = (int)value;
    return true;
}

/* Reads X and Y from a file name ending in tile-X-Y.png. */
static bool offset_from_name(const char *path, int *x, int *y) {
    const char *name = strrchr(path, '/') != NULL ? strrchr(path, '/') + 1 : path;
    const char *at = strstr(name, "tile-");
    if (at == NULL)
        return false;
    while (strstr(at + 1, "tile-") != NULL) /* the last "tile-" of the name */
        at = strstr(at + 1, "tile-");
    char xs[16], ys[16], rest[8];
    if (sscanf(at, "tile-%15[0-9]-%15[0-9]%7s", xs, ys, rest) != 3 || strcmp(rest, ".png") != 0)
        return false;
    return whole_number(xs, 0, IMAGE_MAX_SIDE - 1, x) && whole_number(ys, 0, IMAGE_MAX_SIDE - 1, y);
}

/* Whether tiles a and b share a pixel; if so, *x and *y are the top-left one they share. */
static bool overlap(const struct tile *a, const struct tile *b, int *x, int *y) {
    int left = a->left > b->left ? a->left : b->left, top = a->top > b->top ? a->top : b->top;
    int right = a->left + a->width < b->left + b->width ? a->left + a->width : b->left + b->width;
    int bottom = a->top + a->height < b->top + b->height ? a->top + a->height : b->top + b->height;
    *x = left;
    *y = top;
    return left < right && top < bottom;
}

/* Checks that the tiles cover the width x height picture, each pixel once. Returns false with the first
 * fault (a tile past the edge, two tiles on one pixel, a pixel in none) in err. */
static bool tiles_cover(const struct tile *tiles, int count, int width, int height, char *err, size_t err_size) {
    for (int k = 0; k < count; k++) {
        const struct tile *t = &tiles[k];
        if (t->left + t->width > width || t->top + t->height > height) {
            snprintf(err, err_size, "%s: the %d x %d tile at column %d, row %d reaches past the %d x %d picture",
                     t->path, t->width, t->height, t->left, t->top, width, height);
            return false;
        }
    }
    for (int a = 0; a < count; a++)
        for (int b = a + 1; b < count; b++) {
            int x, y;
            if (overlap(&tiles[a], &tiles[b], &x, &y)) {
                snprintf(err, err_size, "%s and %s overlap: both hold pixel (%d, %d)", tiles[a].path,
                         tiles[b].path, x, y);
                return false;
            }
        }
    /* No tile reaches past the picture and none overlaps another, so they cover it when their areas add
     * up to its area; otherwise find the first pixel none holds, to name it. */
    uint64_t area = 0;
    for (int k = 0; k < count; k++)
        area += (uint64_t)tiles[k].width * (uint64_t)tiles[k].height;
    if (area == (uint64_t)width * (uint64_t)height)
        return true;
    uint8_t *held = calloc((size_t)width * (size_t)height, 1);
    if (held == NULL) {
        snprintf(err, err_size, "a gap: the tiles hold %llu of the %d x %d picture's pixels",
                 (unsigned long long)area, width, height);
        return false;
    }
    for (int k = 0; k < count; k++)
        for (int y = tiles[k].top; y < tiles[k].top + tiles[k].height; y++)
            memset(&held[(size_t)y * (size_t)width + (size_t)tiles[k].left], 1, (size_t)tiles[k].width);
    size_t first = 0;
    while (first < (size_t)width * (size_t)height && held[first]) /* stops: some pixel is in no tile */
        first++;
    free(held);
    snprintf(err, err_size, "a gap: no tile holds pixel (%d, %d) of the %d x %d picture", (int)(first % (size_t)width),
             (int)(first / (size_t)width), width, height);
    return false;
}

/* Reads the command line into the tiles (their files not read yet), the output and the size (0: from
 * the tiles). Returns false after printing why. */
static bool parse(int argc, char **argv, struct tile *tiles, int *count, const char **output, int *width,
                  int *height) {
    *count = 0;
    *output = NULL;
    *width = *height = 0;
    for (int k = 1; k < argc; k++) {
        const char *arg = argv[k];
        if (strcmp(arg, "-o") == 0) {
            if (k + 1 >= argc) {
                fprintf(stderr, "assemble: -o needs a file name\n");
                return false;
            }
            *output = argv[++k];
        } else if (strcmp(arg, "--size") == 0) {
            if (k + 2 >= argc || !whole_number(argv[k + 1], 1, IMAGE_MAX_SIDE, width) ||
                !whole_number(argv[k + 2], 1, IMAGE_MAX_SIDE, height)) {
                fprintf(stderr, "assemble: --size needs two whole numbers W H from 1 to %d\n", IMAGE_MAX_SIDE);
                return false;
            }
            k += 2;
        } else if (strcmp(arg, "--at") == 0) {
            struct tile *t = &tiles[*count];
            if (k + 3 >= argc || !whole_number(argv[k + 1], 0, IMAGE_MAX_SIDE - 1, &t->left) ||
                !whole_number(argv[k + 2], 0, IMAGE_MAX_SIDE - 1, &t->top)) {
                fprintf(stderr, "assemble: --at needs X Y FILE, X and Y whole numbers from 0 to %d\n",
                        IMAGE_MAX_SIDE - 1);
                return false;
            }
            t->path = argv[k + 3];
            (*count)++;
            k += 3;
        } else if (arg[0] == '-') {
            fprintf(stderr, "assemble: unknown option '%s'\n", arg);
            return false;
        } else {
            struct tile *t = &tiles[*count];
            if (!offset_from_name(arg, &t->left, &t->top)) {
                fprintf(stderr, "assemble: %s: the name does not end in tile-X-Y.png; give it as --at X Y %s\n", arg,
                        arg);
                return false;
            }
            t->path = arg;
            (*count)++;
        }
    }
    if (*output == NULL || *count == 0) {
        fprintf(stderr, "assemble: %s\n", *output == NULL ? "-o PICTURE.png is missing" : "no tiles given");
        return false;
    }
    for (int k = 0; k < *count; k++)
        if (outfile_same_file(*output, tiles[k].path)) { /* the picture would be written over the tile */
            fprintf(stderr, "assemble: -o names '%s', one of the tiles it reads: writing it would destroy it; give "
                    "another file\n", *output);
            return false;
        }
    return true;
}

int main(int argc, char **argv) {
    struct tile *tiles = calloc((size_t)argc, sizeof *tiles); /* at most one tile a word */
    const char *output;
    int count, width, height, status = 0;
    if (tiles == NULL) {
        fprintf(stderr, "assemble: out of memory\n");
        return 3;
    }
    if (!parse(argc, argv, tiles, &count, &output, &width, &height)) {
        usage();
        free(tiles);
        return 2;
    }
    char err[ASSEMBLE_ERROR_SIZE];
    bool sized = width > 0;
    /* First every tile's size, from its header: the picture's size and the tiles' fit are settled
     * before a pixel is decoded. */
    for (int k = 0; k < count && status == 0; k++) {
        struct tile *t = &tiles[k];
        if (!tile_size(t, err, sizeof err)) {
            fprintf(stderr, "assemble: %s\n", err);
            status = 1;
        } else if (!sized) {
            width = t->left + t->width > width ? t->left + t->width : width;
            height = t->top + t->height > height ? t->top + t->height : height;
        }
    }
    if (status == 0 && (width > IMAGE_MAX_SIDE || height > IMAGE_MAX_SIDE)) {
        fprintf(stderr, "assemble: the tiles reach %d x %d, larger than the largest picture, %d a side\n", width,
                height, IMAGE_MAX_SIDE);
        status = 1;
    }
    if (status == 0 && !tiles_cover(tiles, count, width, height, err, sizeof err)) {
        fprintf(stderr, "assemble: %s\n", err);
        status = 1;
    }
    struct image picture = {0};
    if (status == 0 && !image_create(&picture, width, height)) {
        fprintf(stderr, "assemble: out of memory for a %d x %d picture\n", width, height);
        status = 3;
    }
    /* Then each tile's pixels, one tile at a time, into the picture. */
    for (int k = 0; k < count && status == 0; k++) {
        const struct tile *t = &tiles[k];
        int read_width = 0, read_height = 0;
        uint8_t *rgb = image_read_rgb(t->path, &read_width, &read_height, err, sizeof err);
        if (rgb == NULL) {
            fprintf(stderr, "assemble: %s\n", err);
            status = 1;
        } else if (read_width != t->width || read_height != t->height) {
            fprintf(stderr, "assemble: %s: decoded as %d x %d pixels, not the %d x %d its header declares\n", t->path,
                    read_width, read_height, t->width, t->height);
            status = 1;
        }
        for (int y = 0; status == 0 && y < t->height; y++) /* the tile's rows into the picture's */
            memcpy(&picture.rgb[3 * ((size_t)(t->top + y) * (size_t)width + (size_t)t->left)],
                   &rgb[3 * (size_t)y * (size_t)t->width], 3 * (size_t)t->width);
        free(rgb);
    }
    if (status == 0 && !image_write_png(&picture, output, err, sizeof err)) {
        fprintf(stderr, "assemble: %s\n", err);
        status = 3;
    }
    image_free(&picture);
    free(tiles);
    return status;
}

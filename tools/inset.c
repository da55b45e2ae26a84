/* inset.c: `inset OUT.png X Y W H ZOOM IN.png...` sets the same region of several pictures side by
 * side, enlarged, so that single pixels show (chapter 12's walkthrough; a tool, not a chapter).
 *
 * Each input (all of one size) gives a panel: its region of W x H pixels from (X, Y), every pixel drawn
 * as a ZOOM x ZOOM square; panels are GAP white pixels apart. With ZOOM 0 the panels are the whole
 * pictures instead, at their size, with the region outlined, to show where the enlargement comes from.
 * The numbers are whole decimal numbers, checked before they are used, and the picture made is at most
 * IMAGE_MAX_SIDE pixels on each side. Exit status 0, 2 for a bad command line or an unreadable picture,
 * or an OUT that names an input, 3 when OUT cannot be written. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "outfile.h"

#define GAP 6                /* white pixels between panels */
#define PANELS_MAX 8
#define OUTLINE_RGB 0xff, 0x30, 0x30 /* the region's outline on the whole pictures */

/* The whole of `text` as a decimal number from 0 to IMAGE_MAX_SIDE into *out; else says which argument
 * is wrong and returns false. */
static bool read_number(const char *what, const char *text, int *out) {
    char *end;
    errno = 0;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || value < 0 || value > IMAGE_MAX_SIDE) {
        fprintf(stderr, "inset: %s '%s' is not a whole number from 0 to %d\n", what, text, IMAGE_MAX_SIDE);
        return false;
    }
    *out = (int)value;
    return true;
}

/* Frees the pictures read, in[0 .. panels), and returns status: the end of main once they are read. */
static int finish(uint8_t *in[], int panels, int status) {
    for (int k = 0; k < panels; k++)
        free(in[k]);
    return status;
}

int main(int argc, char **argv) {
    if (argc < 8 || argc - 7 > PANELS_MAX) {
        fprintf(stderr, "usage: inset OUT.png X Y W H ZOOM IN.png... (at most %d pictures; ZOOM 0: whole pictures, "
                        "region outlined)\n", PANELS_MAX);
        return 2;
    }
    int x0, y0, w, h, zoom;
    if (!read_number("X", argv[2], &x0) || !read_number("Y", argv[3], &y0) || !read_number("W", argv[4], &w) ||
        !read_number("H", argv[5], &h) || !read_number("ZOOM", argv[6], &zoom))
        return 2;
    for (int k = 7; k < argc; k++)
        if (outfile_same_file(argv[1], argv[k])) {
            fprintf(stderr, "inset: OUT.png names '%s', a picture it reads: writing it would destroy it; give another "
                            "file\n", argv[k]);
            return 2;
        }
    int panels = argc - 7, width = 0, height = 0;
    uint8_t *in[PANELS_MAX] = {NULL};
    char err[512];
    for (int k = 0; k < panels; k++) {
        int wk, hk;
        in[k] = image_read_rgb(argv[7 + k], &wk, &hk, err, sizeof err);
        if (in[k] == NULL || (k > 0 && (wk != width || hk != height))) {
            fprintf(stderr, "%s\n", in[k] == NULL ? err : "inset: the pictures differ in size");
            return finish(in, k + 1, 2);
        }
        width = wk, height = hk;
    }
    if (w < 1 || h < 1 || zoom < 0 || x0 < 0 || y0 < 0 || x0 + w > width || y0 + h > height) {
        fprintf(stderr, "inset: the region %d x %d at (%d, %d) is not inside the %d x %d pictures\n", w, h, x0, y0, width,
                height);
        return finish(in, panels, 2);
    }
    /* At most IMAGE_MAX_SIDE each, so the products below stay far inside an int. */
    long long panel_w = zoom > 0 ? (long long)w * zoom : width, panel_h = zoom > 0 ? (long long)h * zoom : height;
    long long out_w = panels * panel_w + (panels - 1) * GAP;
    if (out_w > IMAGE_MAX_SIDE || panel_h > IMAGE_MAX_SIDE) {
        fprintf(stderr, "inset: the picture would be %lld x %lld pixels, more than %d on a side: a smaller ZOOM or "
                        "region\n", out_w, panel_h, IMAGE_MAX_SIDE);
        return finish(in, panels, 2);
    }
    uint8_t *out = malloc((size_t)out_w * (size_t)panel_h * 3);
    if (out == NULL) {
        fprintf(stderr, "inset: out of memory\n");
        return finish(in, panels, 3);
    }
    memset(out, 0xff, (size_t)out_w * (size_t)panel_h * 3);
    static const uint8_t outline[3] = {OUTLINE_RGB};
    for (int k = 0; k < panels; k++)
        for (int j = 0; j < panel_h; j++)
            for (int i = 0; i < panel_w; i++) {
                int si = zoom > 0 ? x0 + i / zoom : i, sj = zoom > 0 ? y0 + j / zoom : j;
                const uint8_t *from = &in[k][3 * ((size_t)sj * (size_t)width + (size_t)si)];
                bool on_outline = zoom == 0 && (((i == x0 - 1 || i == x0 + w) && j >= y0 - 1 && j <= y0 + h) ||
                                                ((j == y0 - 1 || j == y0 + h) && i >= x0 - 1 && i <= x0 + w));
                memcpy(&out[3 * ((size_t)j * (size_t)out_w + (size_t)(k * (panel_w + GAP) + i))],
                       on_outline ? outline : from, 3);
            }
    bool written = image_write_png_bytes(out, (int)out_w, (int)panel_h, argv[1], err, sizeof err);
    if (!written)
        fprintf(stderr, "%s\n", err);
    free(out);
    return finish(in, panels, written ? 0 : 3);
}

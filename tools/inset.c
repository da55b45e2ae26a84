/* inset.c: `inset OUT.png X Y W H ZOOM IN.png...` sets the same region of several pictures side by
 * side, enlarged, so that single pixels show (chapter 12's walkthrough; a tool, not a chapter).
 *
 * Each input (all of one size) gives a panel: its region of W x H pixels from (X, Y), every pixel drawn
 * as a ZOOM x ZOOM square; panels are GAP white pixels apart. With ZOOM 0 the panels are the whole
 * pictures instead, at their size, with the region outlined, to show where the enlargement comes from.
 * Exit status 0, 2 for a bad command line or an unreadable picture, 3 when OUT cannot be written. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"

#define GAP 6                /* white pixels between panels */
#define PANELS_MAX 8
#define OUTLINE_RGB 0xff, 0x30, 0x30 /* the region's outline on the whole pictures */

int main(int argc, char **argv) {
    if (argc < 8 || argc - 7 > PANELS_MAX) {
        fprintf(stderr, "usage: inset OUT.png X Y W H ZOOM IN.png... (at most %d pictures; ZOOM 0: whole pictures, "
                        "region outlined)\n", PANELS_MAX);
        return 2;
    }
    int x0 = atoi(argv[2]), y0 = atoi(argv[3]), w = atoi(argv[4]), h = atoi(argv[5]), zoom = atoi(argv[6]);
    int panels = argc - 7, width = 0, height = 0;
    uint8_t *in[PANELS_MAX] = {NULL};
    char err[512];
    for (int k = 0; k < panels; k++) {
        int wk, hk;
        in[k] = image_read_rgb(argv[7 + k], &wk, &hk, err, sizeof err);
        if (in[k] == NULL || (k > 0 && (wk != width || hk != height))) {
            fprintf(stderr, "%s\n", in[k] == NULL ? err : "inset: the pictures differ in size");
            return 2;
        }
        width = wk, height = hk;
    }
    if (w < 1 || h < 1 || zoom < 0 || x0 < 0 || y0 < 0 || x0 + w > width || y0 + h > height) {
        fprintf(stderr, "inset: the region %d x %d at (%d, %d) is not inside the %d x %d pictures\n", w, h, x0, y0, width,
                height);
        return 2;
    }
    int panel_w = zoom > 0 ? w * zoom : width, panel_h = zoom > 0 ? h * zoom : height;
    int out_w = panels * panel_w + (panels - 1) * GAP;
    uint8_t *out = malloc((size_t)out_w * (size_t)panel_h * 3);
    if (out == NULL) {
        fprintf(stderr, "inset: out of memory\n");
        return 3;
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
    bool written = image_write_png_bytes(out, out_w, panel_h, argv[1], err, sizeof err);
    if (!written)
        fprintf(stderr, "%s\n", err);
    for (int k = 0; k < panels; k++)
        free(in[k]);
    free(out);
    return written ? 0 : 3;
}

/* web_join.c: joins the bands of rows that the page's workers render apart (web/renders.js) into the
 * PNG of the whole picture, for the WebAssembly build only (make web). The bands are --tile pictures,
 * each the very pixels of the whole picture there; written again by image_write_png_bytes, the encoder
 * the programs use, they give the PNG the program writes for the whole picture, byte for byte. */
#include <emscripten.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "image.h"

#define JOIN_BANDS_MAX 1024                   /* the most bands one picture is cut into */
#define JOIN_BAND_PATH "/join/band-%d.png"    /* where the worker writes band k (k from 0, top first) */
#define JOIN_WHOLE_PATH "/join/whole.png"     /* where the whole picture is written */

/* Reads bands 0 .. count - 1 (the same width, top first), stacks them and writes the whole picture to
 * JOIN_WHOLE_PATH. Returns 0, or 1 with the reason on standard error when a band cannot be read, the
 * widths differ or memory runs out. Called by web/worker.js. */
EMSCRIPTEN_KEEPALIVE int web_join_bands(int count) {
    if (count < 1 || count > JOIN_BANDS_MAX) {
        fprintf(stderr, "web_join_bands: %d bands (1 to %d)\n", count, JOIN_BANDS_MAX);
        return 1;
    }
    char path[64], err[CLI_ERROR_SIZE];
    uint8_t *whole = NULL;
    int width = 0, height = 0;
    for (int k = 0; k < count; k++) {
        int w = 0, h = 0;
        snprintf(path, sizeof path, JOIN_BAND_PATH, k);
        uint8_t *band = image_read_rgb(path, &w, &h, err, sizeof err);
        uint8_t *grown = band == NULL || (k > 0 && w != width) ? NULL
                         : realloc(whole, (size_t)w * (size_t)(height + h) * 3);
        if (grown == NULL) {
            fprintf(stderr, "web_join_bands: band %d: %s\n", k, band == NULL ? err : "a different width, or out of memory");
            free(band);
            free(whole);
            return 1;
        }
        whole = grown;
        memcpy(whole + (size_t)w * (size_t)height * 3, band, (size_t)w * (size_t)h * 3);
        free(band);
        width = w;
        height += h;
    }
    bool written = image_write_png_bytes(whole, width, height, JOIN_WHOLE_PATH, err, sizeof err);
    free(whole);
    if (!written)
        fprintf(stderr, "web_join_bands: %s\n", err);
    return written ? 0 : 1;
}

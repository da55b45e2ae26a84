/* compare.c: `compare A.png B.png [STRIP.png]` prints how far two pictures differ and optionally writes
 * them side by side with their amplified difference (used by `make compare`; a tool, not a chapter).
 * Exit status: 0 when the pictures meet the POV-Ray agreement rule, 1 when not, 2 on bad input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "image.h"
#include "image_compare.h"

#define STRIP_GAIN 16 /* a 1-level difference shows as 16 of 255: visible, not glaring */

int main(int argc, char **argv) {
    if (argc != 3 && argc != 4) {
        fprintf(stderr, "usage: %s A.png B.png [STRIP.png]\n", argv[0]);
        return 2;
    }
    char err[512];
    int wa, ha, wb, hb;
    uint8_t *a = image_read_rgb(argv[1], &wa, &ha, err, sizeof err);
    uint8_t *b = a == NULL ? NULL : image_read_rgb(argv[2], &wb, &hb, err, sizeof err);
    if (a == NULL || b == NULL) {
        fprintf(stderr, "%s\n", err);
        free(a);
        return 2;
    }
    if (wa != wb || ha != hb) {
        fprintf(stderr, "%s is %d x %d but %s is %d x %d\n", argv[1], wa, ha, argv[2], wb, hb);
        free(a);
        free(b);
        return 2;
    }
    struct image_difference d = image_compare(a, b, wa, ha);
    char psnr[32] = "inf";
    if (!isinf(d.psnr))
        snprintf(psnr, sizeof psnr, "%.1f", d.psnr);
    printf("max %d  mean %.4f  within1 %.3f%%  within2 %.3f%%  psnr %s dB  over2 %ld\n", d.max, d.mean,
           100.0 * d.within_1, 100.0 * d.within_2, psnr, d.pixels_over_2);
    int status = image_difference_agrees(&d) ? 0 : 1;
    if (argc == 4) {
        uint8_t *strip = malloc((size_t)wa * 3 * 3 * (size_t)ha);
        if (strip == NULL || (image_compare_strip(a, b, wa, ha, STRIP_GAIN, strip),
                              !image_write_png_bytes(strip, 3 * wa, ha, argv[3], err, sizeof err))) {
            fprintf(stderr, "%s\n", strip == NULL ? "out of memory" : err);
            status = 2;
        }
        free(strip);
    }
    free(a);
    free(b);
    return status;
}

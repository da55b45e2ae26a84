/* compare.c: `compare [--box N] A.png B.png [SIDE.png DIFF.png]` prints how far two pictures differ and
 * optionally writes them side by side (A | B) to SIDE.png and their difference, amplified DIFF_GAIN times,
 * to DIFF.png (used by `make compare`; a tool, not a chapter). With --box N, B is N times as wide and
 * high as A and each N x N block of it is averaged first (box_filter.h: chapter 12's grid).
 * Exit status: 0 when the pictures meet the POV-Ray agreement rule, 1 when not, 2 on bad input (also
 * SIDE.png or DIFF.png naming a picture it reads, or each other, or a file that cannot be created: all
 * refused before anything is read or written). */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "box_filter.h"
#include "image.h"
#include "image_compare.h"
#include "outfile.h"

#define DIFF_GAIN 16 /* a 1-level difference shows as 16 of 255: visible, not glaring */

/* Writes the pictures a and b (width x height) side by side to side_path and their difference, amplified
 * DIFF_GAIN times, to diff_path. Returns true on success; on failure writes the reason into err. */
static bool write_pictures(const uint8_t *a, const uint8_t *b, int width, int height, const char *side_path,
                           const char *diff_path, char *err, size_t err_size) {
    size_t bytes = (size_t)width * (size_t)height * 3;
    uint8_t *side = malloc(2 * bytes), *diff = malloc(bytes);
    bool ok = false;
    if (side == NULL || diff == NULL) {
        snprintf(err, err_size, "out of memory");
    } else {
        image_compare_side_by_side(a, b, width, height, side);
        image_compare_difference(a, b, width, height, DIFF_GAIN, diff);
        ok = image_write_png_bytes(side, 2 * width, height, side_path, err, err_size) &&
             image_write_png_bytes(diff, width, height, diff_path, err, err_size);
    }
    free(side);
    free(diff);
    return ok;
}

/* Whether the outputs argv[3] and argv[4] may be written: neither names an input (argv[1], argv[2]), which
 * writing would destroy, nor the other output, and both can be created. Otherwise false with why. */
static bool outputs_usable(char **argv, char *err, size_t err_size) {
    for (int out = 3; out <= 4; out++)
        for (int in = 1; in <= 2; in++)
            if (outfile_same_file(argv[out], argv[in])) {
                snprintf(err, err_size, "%s names '%s', a picture it reads: writing it would destroy it; give "
                         "another file", out == 3 ? "SIDE.png" : "DIFF.png", argv[out]);
                return false;
            }
    if (outfile_same_file(argv[3], argv[4])) {
        snprintf(err, err_size, "SIDE.png and DIFF.png both name '%s'; give two files", argv[3]);
        return false;
    }
    return outfile_can_create(argv[3], err, err_size) && outfile_can_create(argv[4], err, err_size);
}

int main(int argc, char **argv) {
    int box = 1;
    if (argc >= 3 && strcmp(argv[1], "--box") == 0) {
        /* all of it a decimal number, from 1 to a picture's side: atoi read 4294967297 and "1x" as 1 */
        char *end;
        errno = 0;
        long n = strtol(argv[2], &end, 10);
        if (end == argv[2] || *end != '\0' || errno != 0 || n < 1 || n > IMAGE_MAX_SIDE) {
            fprintf(stderr, "compare: --box '%s' is not a whole number from 1 to %d\n", argv[2], IMAGE_MAX_SIDE);
            return 2;
        }
        box = (int)n;
        argv += 2;
        argc -= 2;
    }
    for (int k = 1; k < argc; k++)
        if (argv[k][0] == '-' && argv[k][1] != '\0') { /* an option in a picture's place: not a file to write */
            fprintf(stderr, "compare: unknown option '%s' (--box N comes first; a picture named so is ./%s)\n",
                    argv[k], argv[k]);
            return 2;
        }
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: compare [--box N] A.png B.png [SIDE.png DIFF.png]\n");
        return 2;
    }
    char err[512];
    if (argc == 5 && !outputs_usable(argv, err, sizeof err)) {
        fprintf(stderr, "compare: %s\n", err);
        return 2;
    }
    int wa, ha, wb, hb;
    uint8_t *a = image_read_rgb(argv[1], &wa, &ha, err, sizeof err);
    uint8_t *b = a == NULL ? NULL
                 : box > 1 ? box_filter_png(argv[2], box, &wb, &hb, err, sizeof err)
                           : image_read_rgb(argv[2], &wb, &hb, err, sizeof err);
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
    if (argc == 5 && !write_pictures(a, b, wa, ha, argv[3], argv[4], err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        status = 2;
    }
    free(a);
    free(b);
    return status;
}

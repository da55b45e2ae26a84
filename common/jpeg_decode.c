/* jpeg_decode.c: a JPEG's pixels as libjpeg gives them, POV-Ray's decoder (chapter 14; jpeg_decode.h
 * says why).
 *
 * stb_image reads the file: the markers, the Huffman-coded coefficients and their quantisation, which
 * every decoder does alike. What libjpeg does its own way is done here, in its arithmetic: the inverse
 * DCT of each 8 x 8 block (its "islow" method, integers with 13 fractional bits), the filling in of colour
 * kept at half resolution ("fancy" upsampling, a 3:1 blend of the nearer and the farther sample, with its
 * rounding), and the conversion from YCbCr to RGB (its tables with 16 fractional bits). stb's own code is
 * compiled into this file alone (STB_IMAGE_STATIC), so that its decoder's parts can be used one by one. */
#include "jpeg_decode.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* stb's decoder, private to this file. The compiler would warn, at the end of the file, of each of its
 * functions this file does not call (static here): not for this file, then. */
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter" /* in the parts STBI_ONLY_JPEG leaves empty */
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/* libjpeg's fixed point: constants with 13 fractional bits in the inverse DCT, and 2 more bits kept
 * between its two passes (jidctint.c); 16 fractional bits in the colour conversion (jdcolor.c). */
#define IDCT_CONST_BITS 13
#define IDCT_PASS1_BITS 2
#define COLOUR_SCALE_BITS 16
#define SAMPLE_CENTRE 128

/* x * 2^13 rounded, the constants of the inverse DCT (FIX(x) in jidctint.c). */
enum {
    FIX_0_298631336 = 2446,
    FIX_0_390180644 = 3196,
    FIX_0_541196100 = 4433,
    FIX_0_765366865 = 6270,
    FIX_0_899976223 = 7373,
    FIX_1_175875602 = 9633,
    FIX_1_501321110 = 12299,
    FIX_1_847759065 = 15137,
    FIX_1_961570560 = 16069,
    FIX_2_053119869 = 16819,
    FIX_2_562915447 = 20995,
    FIX_3_072711026 = 25172
};

/* x / 2^n rounded down, as libjpeg's arithmetic right shift (RIGHT_SHIFT) of a possibly negative x. */
static inline long shift_down(long x, int n) {
    long power = 1L << n;
    return x >= 0 ? x / power : -((-x + power - 1) / power);
}

/* x / 2^n rounded half up, libjpeg's DESCALE. */
static inline long descale(long x, int n) { return shift_down(x + (1L << (n - 1)), n); }

/* The inverse DCT's output level for v (before adding the centre): libjpeg's range-limit table, read at
 * v & 1023, which clamps v + 128 to [0, 255] for v in [-512, 511] and wraps beyond (only a damaged file
 * gets there). */
static inline stbi_uc idct_level(long v) {
    long t = v & 1023;
    return (stbi_uc)(t < 128 ? t + 128 : t < 512 ? 255 : t < 896 ? 0 : t - 896);
}

/* One 1-D pass of the inverse DCT over in[0], in[step], ... in[7 step], into the eight sums of its
 * even and odd parts, scaled by 2^13 (jidctint.c's even part and odd part, shared by both passes). */
static void idct_1d(long in0, long in1, long in2, long in3, long in4, long in5, long in6, long in7, long out[8]) {
    long z1 = (in2 + in6) * FIX_0_541196100;
    long tmp2 = z1 + in6 * -FIX_1_847759065, tmp3 = z1 + in2 * FIX_0_765366865;
    long tmp0 = (in0 + in4) * (1L << IDCT_CONST_BITS), tmp1 = (in0 - in4) * (1L << IDCT_CONST_BITS);
    long tmp10 = tmp0 + tmp3, tmp13 = tmp0 - tmp3, tmp11 = tmp1 + tmp2, tmp12 = tmp1 - tmp2;
    long o0 = in7, o1 = in5, o2 = in3, o3 = in1;
    long s1 = o0 + o3, s2 = o1 + o2, s3 = o0 + o2, s4 = o1 + o3, z5 = (s3 + s4) * FIX_1_175875602;
    o0 *= FIX_0_298631336;
    o1 *= FIX_2_053119869;
    o2 *= FIX_3_072711026;
    o3 *= FIX_1_501321110;
    s1 *= -FIX_0_899976223;
    s2 *= -FIX_2_562915447;
    s3 = s3 * -FIX_1_961570560 + z5;
    s4 = s4 * -FIX_0_390180644 + z5;
    o0 += s1 + s3;
    o1 += s2 + s4;
    o2 += s2 + s3;
    o3 += s1 + s4;
    out[0] = tmp10 + o3, out[7] = tmp10 - o3;
    out[1] = tmp11 + o2, out[6] = tmp11 - o2;
    out[2] = tmp12 + o1, out[5] = tmp12 - o1;
    out[3] = tmp13 + o0, out[4] = tmp13 - o0;
}

/* libjpeg's islow inverse DCT of one block of dequantised coefficients (stb has multiplied them by the
 * table already), in natural order, into 8 rows of 8 samples `stride` apart: columns first, then rows.
 * A column or a row whose AC terms are all 0 takes libjpeg's shortcut, which gives what the full
 * computation would. */
static void idct_islow(stbi_uc *out, int stride, short data[64]) {
    long work[64], sums[8];
    for (int c = 0; c < 8; c++) {
        const short *in = data + c;
        if (in[8] == 0 && in[16] == 0 && in[24] == 0 && in[32] == 0 && in[40] == 0 && in[48] == 0 && in[56] == 0) {
            long dc = (long)in[0] * (1L << IDCT_PASS1_BITS);
            for (int r = 0; r < 8; r++)
                work[8 * r + c] = dc;
            continue;
        }
        idct_1d(in[0], in[8], in[16], in[24], in[32], in[40], in[48], in[56], sums);
        for (int r = 0; r < 8; r++)
            work[8 * r + c] = descale(sums[r], IDCT_CONST_BITS - IDCT_PASS1_BITS);
    }
    for (int r = 0; r < 8; r++, out += stride) {
        const long *w = work + 8 * r;
        if (w[1] == 0 && w[2] == 0 && w[3] == 0 && w[4] == 0 && w[5] == 0 && w[6] == 0 && w[7] == 0) {
            stbi_uc level = idct_level(descale(w[0], IDCT_PASS1_BITS + 3));
            memset(out, level, 8);
            continue;
        }
        idct_1d(w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], sums);
        for (int c = 0; c < 8; c++)
            out[c] = idct_level(descale(sums[c], IDCT_CONST_BITS + IDCT_PASS1_BITS + 3));
    }
}

/* A component's samples: `width` x `height` of them, row r at data + r * stride. */
struct plane {
    const stbi_uc *data;
    int width, height, stride;
};

static const stbi_uc *plane_row(const struct plane *p, int r) {
    return p->data + (size_t)(r < 0 ? 0 : r >= p->height ? p->height - 1 : r) * (size_t)p->stride;
}

/* Row y of the picture's samples of component p, kept at 1 / h_factor of the width and 1 / v_factor of
 * the height (each 1 or 2), filled in to `width` samples as libjpeg's fancy upsampling does (jdsample.c):
 * each new sample 3/4 of the nearer old one and 1/4 of the farther, rounded with its biases; the rows
 * above the first and below the last are those rows again. A row of at most 2 samples is widened by
 * repeating them, as libjpeg does there. Other factors repeat the nearest sample. sum (p's width) and row
 * (twice that) are room to work in. */
static void upsample_row(const struct plane *p, int h_factor, int v_factor, int y, int width, int *sum, stbi_uc *row,
                         stbi_uc *out) {
    int r = y / v_factor;
    const stbi_uc *near = plane_row(p, r);
    bool lower = y % 2 == 1; /* the lower of the two rows made from row r */
    const stbi_uc *far = plane_row(p, lower ? r + 1 : r - 1);
    int n = p->width;
    if (v_factor == 2)
        for (int i = 0; i < n; i++)
            sum[i] = 3 * near[i] + far[i];
    if (h_factor == 1 && v_factor == 1) {
        memcpy(out, near, (size_t)width);
    } else if (h_factor == 1 && v_factor == 2) {
        for (int i = 0; i < width; i++)
            out[i] = (stbi_uc)((sum[i] + (lower ? 2 : 1)) >> 2);
    } else if (h_factor == 2 && v_factor == 1 && n > 2) {
        row[0] = near[0];
        row[1] = (stbi_uc)((near[0] * 3 + near[1] + 2) >> 2);
        for (int i = 1; i < n - 1; i++) {
            row[2 * i] = (stbi_uc)((near[i] * 3 + near[i - 1] + 1) >> 2);
            row[2 * i + 1] = (stbi_uc)((near[i] * 3 + near[i + 1] + 2) >> 2);
        }
        row[2 * n - 2] = (stbi_uc)((near[n - 1] * 3 + near[n - 2] + 1) >> 2);
        row[2 * n - 1] = near[n - 1];
        memcpy(out, row, (size_t)width);
    } else if (h_factor == 2 && v_factor == 2 && n > 2) {
        row[0] = (stbi_uc)((sum[0] * 4 + 8) >> 4);
        row[1] = (stbi_uc)((sum[0] * 3 + sum[1] + 7) >> 4);
        for (int i = 1; i < n - 1; i++) {
            row[2 * i] = (stbi_uc)((sum[i] * 3 + sum[i - 1] + 8) >> 4);
            row[2 * i + 1] = (stbi_uc)((sum[i] * 3 + sum[i + 1] + 7) >> 4);
        }
        row[2 * n - 2] = (stbi_uc)((sum[n - 1] * 3 + sum[n - 2] + 8) >> 4);
        row[2 * n - 1] = (stbi_uc)((sum[n - 1] * 4 + 7) >> 4);
        memcpy(out, row, (size_t)width);
    } else { /* repeated: factors of 2 on a row of at most 2 samples, and any other factors */
        const stbi_uc *source = plane_row(p, y / v_factor);
        for (int i = 0; i < width; i++)
            out[i] = source[i / h_factor];
    }
}

/* The picture's level for a sample from libjpeg's range-limit table: clamped to [0, 255]. */
static inline stbi_uc clamp_level(int v) { return (stbi_uc)(v < 0 ? 0 : v > 255 ? 255 : v); }

/* libjpeg's YCbCr to RGB (jdcolor.c): each term an entry of its tables, with 16 fractional bits, rounded
 * down after half is added: FIX(1.402), FIX(1.772), FIX(0.71414), FIX(0.34414) are the factors times 2^16,
 * rounded. */
static void ycc_to_rgb(int y, int cb, int cr, stbi_uc *rgb) {
    const long one_half = 1L << (COLOUR_SCALE_BITS - 1);
    const long fix_1_40200 = 91881, fix_1_77200 = 116130, fix_0_71414 = 46802, fix_0_34414 = 22554;
    long x_cr = cr - SAMPLE_CENTRE, x_cb = cb - SAMPLE_CENTRE;
    long red = shift_down(fix_1_40200 * x_cr + one_half, COLOUR_SCALE_BITS);
    long blue = shift_down(fix_1_77200 * x_cb + one_half, COLOUR_SCALE_BITS);
    long green = shift_down((-fix_0_34414 * x_cb + one_half) + -fix_0_71414 * x_cr, COLOUR_SCALE_BITS);
    rgb[0] = clamp_level(y + (int)red);
    rgb[1] = clamp_level(y + (int)green);
    rgb[2] = clamp_level(y + (int)blue);
}

enum jpeg_decoded jpeg_decode(const uint8_t *bytes, int size, uint8_t **rgba, int *width, int *height) {
    *rgba = NULL;
    stbi__context context;
    stbi__start_mem(&context, bytes, size);
    stbi__jpeg *j = malloc(sizeof *j);
    if (j == NULL)
        return JPEG_FAILED;
    j->s = &context;
    stbi__setup_jpeg(j);
    j->idct_block_kernel = idct_islow;
    context.img_n = 0; /* so that stbi__cleanup_jpeg is safe */
    if (!stbi__decode_jpeg_image(j)) {
        stbi__cleanup_jpeg(j);
        free(j);
        return JPEG_FAILED;
    }
    int n = context.img_n, w = (int)context.img_x, h = (int)context.img_y;
    /* libjpeg's YCbCr: three components, not marked RGB by their names or an Adobe marker; and grey */
    bool ycc = n == 3 && j->rgb != 3 && !(j->app14_color_transform == 0 && !j->jfif);
    bool whole_factors = true; /* libjpeg takes only sampling factors that divide the largest */
    for (int k = 0; k < n; k++)
        whole_factors = whole_factors && j->img_h_max % j->img_comp[k].h == 0 && j->img_v_max % j->img_comp[k].v == 0;
    if ((n != 1 && !ycc) || !whole_factors) {
        stbi__cleanup_jpeg(j);
        free(j);
        return JPEG_NOT_HANDLED;
    }
    uint8_t *out = malloc((size_t)w * (size_t)h * 4);
    stbi_uc *rows = malloc((size_t)w * 3), *row = malloc(2 * (size_t)w + 2);
    int *sum = malloc(((size_t)w + 1) * sizeof *sum);
    if (out == NULL || rows == NULL || row == NULL || sum == NULL) {
        free(out);
        free(rows);
        free(row);
        free(sum);
        stbi__cleanup_jpeg(j);
        free(j);
        return JPEG_FAILED;
    }
    struct plane planes[3];
    int h_factor[3], v_factor[3];
    for (int k = 0; k < n; k++) {
        planes[k] = (struct plane){j->img_comp[k].data, j->img_comp[k].x, j->img_comp[k].y, j->img_comp[k].w2};
        h_factor[k] = j->img_h_max / j->img_comp[k].h;
        v_factor[k] = j->img_v_max / j->img_comp[k].v;
    }
    for (int y = 0; y < h; y++) {
        for (int k = 0; k < n; k++)
            upsample_row(&planes[k], h_factor[k], v_factor[k], y, w, sum, row, rows + (size_t)k * (size_t)w);
        uint8_t *o = out + (size_t)y * (size_t)w * 4;
        for (int x = 0; x < w; x++, o += 4) {
            if (n == 1)
                o[0] = o[1] = o[2] = rows[x];
            else
                ycc_to_rgb(rows[x], rows[w + x], rows[2 * w + x], o);
            o[3] = 255;
        }
    }
    free(rows);
    free(row);
    free(sum);
    stbi__cleanup_jpeg(j);
    free(j);
    *rgba = out;
    *width = w;
    *height = h;
    return JPEG_DECODED;
}

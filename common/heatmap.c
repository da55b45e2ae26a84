/* heatmap.c: per-pixel cost drawn on a fixed logarithmic colour scale, with its colour bar (chapter 1). */
#include "heatmap.h"

#include <math.h>
#include <stdio.h>

/* The colour ramp, evenly spaced on log(1 + cost): black, blue, red, yellow, white. */
static const vec3 ramp[] = {{0, 0, 0}, {0.1, 0.2, 0.9}, {0.9, 0.15, 0.1}, {1, 0.9, 0.1}, {1, 1, 1}};
#define RAMP_STEPS (sizeof ramp / sizeof ramp[0] - 1)

vec3 heatmap_colour(uint32_t cost) { return heatmap_colour_on(&heatmap_cost_scale, cost); }

vec3 heatmap_colour_on(const struct heatmap_scale *scale, uint32_t value) {
    double level = log1p((double)value) / log1p((double)scale->max);
    if (level >= 1.0)
        return ramp[RAMP_STEPS];
    double position = level * RAMP_STEPS;
    int step = (int)position;
    double blend = position - step;
    return vec3_add(vec3_scale(ramp[step], 1.0 - blend), vec3_scale(ramp[step + 1], blend));
}

/* ---- the colour bar ------------------------------------------------------------------------------
 * A white strip under the picture: the ramp from cost 0 to HEATMAP_MAX_COST, with a tick and its number
 * at every cost in heatmap_ticks. The numbers are drawn with a built-in 5 x 7 bitmap font of digits, so
 * no font library is needed. Everything is measured in units of one font pixel, which is
 * heatmap_bar_scale() image pixels. */

const uint32_t heatmap_ticks[HEATMAP_TICKS] = {0, 1, 10, 100, 1000, HEATMAP_MAX_COST};
const struct heatmap_scale heatmap_cost_scale = {HEATMAP_MAX_COST, heatmap_ticks, HEATMAP_TICKS};

/* The digits 0-9, 5 pixels wide and 7 high: one byte per row, bit 4 the leftmost pixel. */
static const uint8_t digit_rows[10][7] = {
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C},
};
#define DIGIT_WIDTH 5
#define DIGIT_HEIGHT 7
#define DIGIT_ADVANCE 6 /* one blank column between digits */

/* The strip's rows, top to bottom, in font pixels. */
#define BAR_TOP 4        /* white above the bar */
#define BAR_HEIGHT 10    /* the ramp itself */
#define TICK_LENGTH 3    /* a tick below the bar at each marked cost */
#define LABEL_GAP 2      /* between the tick and its number */
#define STRIP_HEIGHT (BAR_TOP + BAR_HEIGHT + TICK_LENGTH + LABEL_GAP + DIGIT_HEIGHT + 4)
/* Room left and right of the bar: half of the widest number ("8192") and a little more. */
#define BAR_MARGIN 14

/* One font pixel per 640 image pixels of width (and at least one): the bar stays readable when the
 * picture is shown shrunk to a page's width. */
int heatmap_bar_scale(int width) { return 1 + width / 640; }

int heatmap_bar_height(int width, int height) {
    int rows = STRIP_HEIGHT * heatmap_bar_scale(width);
    return height + rows <= IMAGE_MAX_SIDE ? rows : 0;
}

/* Returns the column of the bar of `values` at which `value` lies. */
static int bar_x_on(const struct heatmap_scale *values, int width, uint32_t value) {
    int scale = heatmap_bar_scale(width);
    int left = BAR_MARGIN * scale, length = width - 2 * BAR_MARGIN * scale - 1;
    double level = log1p((double)value) / log1p((double)values->max);
    return left + (int)floor(fmin(level, 1.0) * length + 0.5);
}

int heatmap_bar_x(int width, uint32_t cost) { return bar_x_on(&heatmap_cost_scale, width, cost); }

/* Fills the scale x scale block of font pixel (x, y) of the strip that starts at image row top. */
static void font_pixel(struct image *img, int top, int scale, int x, int y, vec3 colour) {
    for (int dy = 0; dy < scale; dy++)
        for (int dx = 0; dx < scale; dx++) {
            int i = x + dx, j = top + y * scale + dy;
            if (i >= 0 && i < img->width && j < img->height)
                image_set(img, i, j, colour);
        }
}

/* Draws the number centred on image column centre, with its top at font row y of the strip. */
static void draw_number(struct image *img, int top, int scale, int centre, int y, uint32_t number) {
    char digits[16];
    int count = snprintf(digits, sizeof digits, "%u", (unsigned)number);
    int left = centre - (count * DIGIT_ADVANCE - 1) * scale / 2;
    for (int k = 0; k < count; k++)
        for (int row = 0; row < DIGIT_HEIGHT; row++)
            for (int column = 0; column < DIGIT_WIDTH; column++)
                if (digit_rows[digits[k] - '0'][row] & (0x10 >> column))
                    font_pixel(img, top, scale, left + (k * DIGIT_ADVANCE + column) * scale, y + row,
                               vec3_make(0, 0, 0));
}

void heatmap_draw_bar(struct image *img, int top) { heatmap_draw_bar_on(img, top, &heatmap_cost_scale); }

void heatmap_draw_bar_on(struct image *img, int top, const struct heatmap_scale *values) {
    int width = img->width, scale = heatmap_bar_scale(width);
    if (img->height - top < STRIP_HEIGHT * scale)
        return; /* no room: the picture was too tall to have a bar */
    for (int j = top; j < img->height; j++)
        for (int i = 0; i < width; i++)
            image_set(img, i, j, vec3_make(1, 1, 1));
    bool labelled = width >= 4 * BAR_MARGIN * scale;
    int left = labelled ? bar_x_on(values, width, 0) : 0, right = labelled ? bar_x_on(values, width, values->max) : width - 1;
    for (int i = left; i <= right; i++) {
        /* the value whose level lies at this column, so that the bar is the ramp itself */
        double level = right > left ? (double)(i - left) / (right - left) : 1.0;
        uint32_t value = (uint32_t)floor(expm1(level * log1p((double)values->max)) + 0.5);
        for (int j = top + BAR_TOP * scale; j < top + (BAR_TOP + BAR_HEIGHT) * scale; j++)
            image_set(img, i, j, heatmap_colour_on(values, value));
    }
    if (!labelled)
        return;
    for (int k = 0; k < values->tick_count; k++) {
        int x = bar_x_on(values, width, values->ticks[k]);
        for (int y = BAR_TOP + BAR_HEIGHT; y < BAR_TOP + BAR_HEIGHT + TICK_LENGTH; y++)
            font_pixel(img, top, scale, x - scale / 2, y, vec3_make(0, 0, 0));
        draw_number(img, top, scale, x, BAR_TOP + BAR_HEIGHT + TICK_LENGTH + LABEL_GAP, values->ticks[k]);
    }
}

/* fig_antialias.c: chapter 12's figure, an edge over the pixel grid (one ray per pixel against the box
 * filter) and where each method puts its rays in one pixel the edge crosses. */
#include <math.h>

#include "figures.h"
#include "supersample.h"
#include "svg.h"

/* The edge: the shape (blue) lies below the line y = EDGE_SLOPE * x + EDGE_OFFSET, in pixels with y
 * down from the top, as the picture's rows run. */
#define EDGE_SLOPE 0.4
#define EDGE_OFFSET 1.2
#define GRID_WIDTH 10
#define GRID_HEIGHT 6
#define TRUE_SIDE 64     /* the box filter is shown as a 64 x 64 grid: near enough the area covered */
#define POINTS_MAX 128   /* rays recorded in one pixel */

/* A view of the edge that records where it was looked at inside pixel (i, j). */
struct recorder {
    int i, j, count;
    svg_point at[POINTS_MAX];
    bool inside[POINTS_MAX]; /* the ray saw the shape */
};

static bool in_shape(double x, double y) { return y > EDGE_SLOPE * x + EDGE_OFFSET; }

/* 1 where a ray sees the shape, 0 where it sees the background: the shape's coverage, averaged. */
static vec3 edge_colour(const void *context, double x, double y) {
    struct recorder *r = (struct recorder *)context;
    bool inside = in_shape(x, y);
    if (r != NULL && x >= r->i && x <= r->i + 1 && y >= r->j && y <= r->j + 1 && r->count < POINTS_MAX) {
        r->at[r->count] = (svg_point){x - r->i, y - r->j};
        r->inside[r->count++] = inside;
    }
    return inside ? vec3_make(1, 1, 1) : vec3_make(0, 0, 0);
}

/* Pixel (i, j) of a grid drawn with its top-left corner at world (0, 0), y down: filled as deep as
 * `covered`, 0 white to 1 the shape's full blue. */
static void pixel(struct svg *s, int i, int j, double covered) {
    svg_rect(s, (svg_point){i, -j}, (svg_point){i + 1, -(j + 1)}, SVG_SURFACE, SVG_THIN, 0.8 * covered);
}

/* The edge line across the grid, from x = 0 to x = width. */
static void edge_line(struct svg *s, double width) {
    svg_line(s, (svg_point){0, -EDGE_OFFSET}, (svg_point){width, -(EDGE_SLOPE * width + EDGE_OFFSET)}, SVG_RAY,
             SVG_SOLID);
}

/* One method's rays in pixel (i, j), enlarged: the pixel shaded as the method colours it, the edge, a dot
 * per ray (filled orange: it saw the shape), and the value under it. */
static void pattern(struct svg *s, double left_px, const char *name, enum antialias_method method, int n, int i,
                    int j) {
    struct recorder seen = {.i = i, .j = j};
    struct sample_view view = {edge_colour, &seen};
    struct antialias a = {method, n, ANTIALIAS_DEFAULT_THRESHOLD, 0, 1};
    vec3 colour;
    int rays;
    /* the adaptive rule needs the pixel's own block: the left and upper neighbours are traced outside it */
    supersample_block(&a, &view, i, j, i + 1, j + 1, &colour, &rays);
    svg_view(s, 0, 0, left_px, 300, 150);
    svg_rect(s, (svg_point){0, 0}, (svg_point){1, -1}, SVG_SURFACE, SVG_THIN, 0.8 * colour.x);
    svg_line(s, (svg_point){0, -(EDGE_SLOPE * i + EDGE_OFFSET - j)}, (svg_point){1, -(EDGE_SLOPE * (i + 1) + EDGE_OFFSET - j)},
             SVG_RAY, SVG_SOLID);
    for (int k = 0; k < seen.count; k++) {
        svg_point p = {seen.at[k].x, -seen.at[k].y};
        svg_circle(s, p, 0.03, seen.inside[k] ? SVG_LIGHT : SVG_INK, SVG_THIN, seen.inside[k] ? 1.0 : 0.0);
    }
    svg_text(s, (svg_point){0.5, 0}, 0, -12, "middle", SVG_INK, "%s", name);
    svg_text(s, (svg_point){0.5, -1}, 0, 22, "middle", SVG_INK, "%d ray%s: %.3f", rays, rays == 1 ? "" : "s", colour.x);
}

void figure_antialias(FILE *out) {
    struct svg s;
    svg_begin(&s, out, 900, 560, "Chapter 12: an edge over the pixel grid, and where each method puts its rays");
    struct sample_view plain = {edge_colour, NULL};

    /* Top: the grid, one ray per pixel centre against the box filter. */
    for (int panel = 0; panel < 2; panel++) {
        double left = panel == 0 ? 40 : 480;
        svg_view(&s, 0, 0, left, 50, 34);
        svg_text_px(&s, left + GRID_WIDTH * 17, 36, "middle", SVG_INK, "%s",
                    panel == 0 ? "one ray through each centre: all or nothing" : "the box filter: the share covered");
        for (int j = 0; j < GRID_HEIGHT; j++)
            for (int i = 0; i < GRID_WIDTH; i++) {
                double covered = panel == 0 ? supersample_grid(&plain, i, j, 1).x
                                            : supersample_grid(&plain, i, j, TRUE_SIDE).x;
                pixel(&s, i, j, covered);
                if (panel == 0)
                    svg_circle(&s, (svg_point){i + 0.5, -(j + 0.5)}, 0.06, in_shape(i + 0.5, j + 0.5) ? SVG_LIGHT : SVG_INK,
                               SVG_THIN, in_shape(i + 0.5, j + 0.5) ? 1.0 : 0.0);
            }
        edge_line(&s, GRID_WIDTH);
    }

    /* Bottom: pixel (5, 3), which the edge crosses, under each method. */
    int i = 5, j = 3;
    svg_text_px(&s, 450, 276, "middle", SVG_INK,
                "pixel (%d, %d) enlarged; the share it covers is %.3f (dots: rays, orange where they meet the shape)", i, j,
                supersample_grid(&plain, i, j, TRUE_SIDE).x);
    pattern(&s, 40, "one ray", ANTIALIAS_NONE, 1, i, j);
    pattern(&s, 215, "grid 4 × 4", ANTIALIAS_GRID, 4, i, j);
    pattern(&s, 390, "jitter 4 × 4", ANTIALIAS_JITTER, 4, i, j);
    pattern(&s, 565, "adaptive 3", ANTIALIAS_ADAPTIVE, 3, i, j);
    pattern(&s, 740, "recursive 3", ANTIALIAS_RECURSIVE, 3, i, j);
    svg_text_px(&s, 450, 540, "middle", SVG_MUTED,
                "adaptive: the centre ray and 3 × 3 more, the pixel's centre differing from a neighbour's; "
                "recursive: corners, then quarters");
    svg_end(&s);
}

/* svg.h: a tiny SVG writer for the walkthroughs' figures (tools/figures; not part of any chapter).
 *
 * A figure is drawn in its own world units (the scene's units, y up); a view maps them to pixels.
 * Every figure uses the same palette, stroke widths and font, so the figures read as one set. The
 * output is byte-for-byte the same on every run (fixed number formats, no dates), so a test can
 * compare a committed figure with what the program draws now. */
#ifndef WHITTED_SVG_H
#define WHITTED_SVG_H

#include <stdbool.h>
#include <stdio.h>

/* A 2D point or direction in a figure's world units. */
typedef struct svg_point {
    double x, y;
} svg_point;

/* The palette: one colour per role, the same in every figure. */
enum svg_colour {
    SVG_INK,     /* labels, axes, outlines */
    SVG_MUTED,   /* construction lines, grids, things in the background */
    SVG_RAY,     /* rays and their directions */
    SVG_SURFACE, /* shapes */
    SVG_NORMAL,  /* normals */
    SVG_LIGHT,   /* lights and the directions to them */
    SVG_HIT,     /* hit points and the distances that find them */
    SVG_ACCENT,  /* a second set of shapes to tell apart from the first (children, the other split) */
    SVG_COLOURS
};

/* Line styles. */
enum svg_style {
    SVG_SOLID = 0,
    SVG_DASHED = 1, /* construction lines: not part of the geometry, a help to read it */
    SVG_ARROW = 2,  /* ends in an arrow head (a direction) */
    SVG_THIN = 4,   /* half the normal stroke width */
};

struct svg {
    FILE *out;
    double scale;       /* pixels per world unit */
    double origin_x;    /* pixel column of world x = 0 */
    double origin_y;    /* pixel row of world y = 0 (rows grow downwards, world y upwards) */
};

/* Starts a width x height pixel figure in `out` (not closed by svg_end) with a white background,
 * the arrow heads of the palette and a <title> for screen readers. The view starts as 1 pixel per
 * unit at the top-left corner; set it with svg_view. */
void svg_begin(struct svg *s, FILE *out, int width, int height, const char *title);

/* Makes world point (x0, y0) land on pixel (px, py), at `scale` pixels per world unit. */
void svg_view(struct svg *s, double x0, double y0, double px, double py, double scale);

/* Ends the figure. */
void svg_end(struct svg *s);

/* Returns a + t * d (a step along a ray), a - b, and the unit vector along d. */
svg_point svg_along(svg_point a, svg_point d, double t);
svg_point svg_minus(svg_point a, svg_point b);
svg_point svg_unit(svg_point d);

/* A segment from a to b, in a palette colour and style (SVG_ARROW puts the head at b). */
void svg_line(struct svg *s, svg_point a, svg_point b, enum svg_colour colour, int style);

/* A polyline or closed polygon through the n points; fill_opacity 0 leaves it unfilled. */
void svg_polygon(struct svg *s, const svg_point *p, int n, bool closed, enum svg_colour colour, int style,
                 double fill_opacity);

/* The axis-aligned rectangle between min and max. */
void svg_rect(struct svg *s, svg_point min, svg_point max, enum svg_colour colour, int style, double fill_opacity);

/* A circle of world radius r. */
void svg_circle(struct svg *s, svg_point centre, double r, enum svg_colour colour, int style, double fill_opacity);

/* A dot of a few pixels: a point that matters (a hit, an eye, a light). */
void svg_dot(struct svg *s, svg_point p, enum svg_colour colour);

/* An arc of radius r_px pixels around `at`, from direction `from` turning to direction `to` the short
 * way: marks an angle. */
void svg_angle(struct svg *s, svg_point at, svg_point from, svg_point to, double r_px, enum svg_colour colour);

/* Text anchored at world point p, moved by (dx, dy) pixels (dy > 0 moves it down); anchor is
 * "start", "middle" or "end". The text is printf-formatted and XML-escaped. */
void svg_text(struct svg *s, svg_point p, double dx, double dy, const char *anchor, enum svg_colour colour,
              const char *format, ...) __attribute__((format(printf, 7, 8)));

/* The same, at a pixel position (captions and legends that do not belong to a world point). */
void svg_text_px(struct svg *s, double px, double py, const char *anchor, enum svg_colour colour,
                 const char *format, ...) __attribute__((format(printf, 6, 7)));

#endif

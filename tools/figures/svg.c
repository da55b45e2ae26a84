/* svg.c: a tiny SVG writer for the walkthroughs' figures (tools/figures; not part of any chapter). */
#include "svg.h"

#include <math.h>
#include <stdarg.h>

/* The palette: readable on white and told apart by readers with the common colour blindnesses
 * (the "Tableau 10" hues). */
static const char *const palette[SVG_COLOURS] = {
    [SVG_INK] = "#222222",  [SVG_MUTED] = "#8c8c8c",   [SVG_RAY] = "#d62728",   [SVG_SURFACE] = "#1f77b4",
    [SVG_NORMAL] = "#2ca02c", [SVG_LIGHT] = "#ff7f0e", [SVG_HIT] = "#9467bd", [SVG_ACCENT] = "#17becf",
};
static const char *const colour_name[SVG_COLOURS] = {
    [SVG_INK] = "ink",   [SVG_MUTED] = "muted", [SVG_RAY] = "ray",  [SVG_SURFACE] = "surface",
    [SVG_NORMAL] = "normal", [SVG_LIGHT] = "light", [SVG_HIT] = "hit", [SVG_ACCENT] = "accent",
};

/* Stroke width in pixels: wide enough to see at GitHub's column width, thin enough for labels. */
#define SVG_STROKE 2.0
/* Label size in pixels: GitHub shows a figure at up to about 880 pixels wide without scaling it. */
#define SVG_FONT_SIZE 15
/* Radius of a dot, in pixels. */
#define SVG_DOT_RADIUS 4.5

void svg_begin(struct svg *s, FILE *out, int width, int height, const char *title) {
    s->out = out;
    svg_view(s, 0, 0, 0, 0, 1);
    fprintf(out, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
                 "font-family=\"DejaVu Sans, Verdana, sans-serif\" font-size=\"%d\">\n",
            width, height, width, height, SVG_FONT_SIZE);
    fprintf(out, "<title>%s</title>\n<defs>\n", title);
    for (int c = 0; c < SVG_COLOURS; c++)
        fprintf(out, "<marker id=\"arrow-%s\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" "
                     "markerHeight=\"7\" orient=\"auto-start-reverse\"><path d=\"M0,0 L10,5 L0,10 z\" fill=\"%s\"/>"
                     "</marker>\n",
                colour_name[c], palette[c]);
    fprintf(out, "</defs>\n<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n", width, height);
}

void svg_view(struct svg *s, double x0, double y0, double px, double py, double scale) {
    s->scale = scale;
    s->origin_x = px - x0 * scale;
    s->origin_y = py + y0 * scale;
}

void svg_end(struct svg *s) { fprintf(s->out, "</svg>\n"); }

svg_point svg_along(svg_point a, svg_point d, double t) { return (svg_point){a.x + t * d.x, a.y + t * d.y}; }

svg_point svg_minus(svg_point a, svg_point b) { return (svg_point){a.x - b.x, a.y - b.y}; }

svg_point svg_unit(svg_point d) {
    double length = hypot(d.x, d.y);
    return (svg_point){d.x / length, d.y / length};
}

static double px_x(const struct svg *s, svg_point p) { return s->origin_x + p.x * s->scale; }
static double px_y(const struct svg *s, svg_point p) { return s->origin_y - p.y * s->scale; }

/* The stroke attributes shared by every outline. */
static void stroke(const struct svg *s, enum svg_colour colour, int style) {
    fprintf(s->out, " stroke=\"%s\" stroke-width=\"%.1f\" stroke-linejoin=\"round\"", palette[colour],
            style & SVG_THIN ? SVG_STROKE / 2 : SVG_STROKE);
    if (style & SVG_DASHED)
        fprintf(s->out, " stroke-dasharray=\"6 4\"");
    if (style & SVG_ARROW)
        fprintf(s->out, " marker-end=\"url(#arrow-%s)\"", colour_name[colour]);
}

static void fill(const struct svg *s, enum svg_colour colour, double opacity) {
    if (opacity > 0)
        fprintf(s->out, " fill=\"%s\" fill-opacity=\"%.2f\"", palette[colour], opacity);
    else
        fprintf(s->out, " fill=\"none\"");
}

void svg_line(struct svg *s, svg_point a, svg_point b, enum svg_colour colour, int style) {
    fprintf(s->out, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"", px_x(s, a), px_y(s, a), px_x(s, b),
            px_y(s, b));
    stroke(s, colour, style);
    fprintf(s->out, "/>\n");
}

void svg_polygon(struct svg *s, const svg_point *p, int n, bool closed, enum svg_colour colour, int style,
                 double fill_opacity) {
    fprintf(s->out, "<%s points=\"", closed ? "polygon" : "polyline");
    for (int k = 0; k < n; k++)
        fprintf(s->out, "%s%.1f,%.1f", k ? " " : "", px_x(s, p[k]), px_y(s, p[k]));
    fprintf(s->out, "\"");
    stroke(s, colour, style);
    fill(s, colour, fill_opacity);
    fprintf(s->out, "/>\n");
}

void svg_rect(struct svg *s, svg_point min, svg_point max, enum svg_colour colour, int style, double fill_opacity) {
    svg_point corners[4] = {min, {max.x, min.y}, max, {min.x, max.y}};
    svg_polygon(s, corners, 4, true, colour, style, fill_opacity);
}

void svg_circle(struct svg *s, svg_point centre, double r, enum svg_colour colour, int style, double fill_opacity) {
    fprintf(s->out, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\"", px_x(s, centre), px_y(s, centre), r * s->scale);
    stroke(s, colour, style);
    fill(s, colour, fill_opacity);
    fprintf(s->out, "/>\n");
}

void svg_dot(struct svg *s, svg_point p, enum svg_colour colour) {
    fprintf(s->out, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\"/>\n", px_x(s, p), px_y(s, p),
            SVG_DOT_RADIUS, palette[colour]);
}

void svg_angle(struct svg *s, svg_point at, svg_point from, svg_point to, double r_px, enum svg_colour colour) {
    svg_point u = svg_unit(from), v = svg_unit(to);
    double cross = u.x * v.y - u.y * v.x;
    /* Pixel rows grow downwards, which turns the sense of rotation over: counter-clockwise in the
     * world (cross > 0) is sweep flag 0 in SVG. */
    fprintf(s->out, "<path d=\"M%.1f,%.1f A%.1f,%.1f 0 0 %d %.1f,%.1f\"", px_x(s, at) + r_px * u.x,
            px_y(s, at) - r_px * u.y, r_px, r_px, cross > 0 ? 0 : 1, px_x(s, at) + r_px * v.x, px_y(s, at) - r_px * v.y);
    stroke(s, colour, SVG_THIN);
    fprintf(s->out, " fill=\"none\"/>\n");
}

/* Writes text with the XML special characters escaped. */
static void text(struct svg *s, double px, double py, const char *anchor, enum svg_colour colour, const char *format,
                 va_list args) {
    char buffer[512];
    vsnprintf(buffer, sizeof buffer, format, args);
    /* A white halo under every label keeps it readable where it crosses a line. */
    fprintf(s->out, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\" fill=\"%s\" stroke=\"#ffffff\" "
                    "stroke-width=\"4\" stroke-linejoin=\"round\" paint-order=\"stroke\">",
            px, py, anchor, palette[colour]);
    for (const char *c = buffer; *c; c++) {
        if (*c == '<')
            fputs("&lt;", s->out);
        else if (*c == '>')
            fputs("&gt;", s->out);
        else if (*c == '&')
            fputs("&amp;", s->out);
        else
            fputc(*c, s->out);
    }
    fprintf(s->out, "</text>\n");
}

void svg_text(struct svg *s, svg_point p, double dx, double dy, const char *anchor, enum svg_colour colour,
              const char *format, ...) {
    va_list args;
    va_start(args, format);
    text(s, px_x(s, p) + dx, px_y(s, p) + dy, anchor, colour, format, args);
    va_end(args);
}

void svg_text_px(struct svg *s, double px, double py, const char *anchor, enum svg_colour colour, const char *format,
                 ...) {
    va_list args;
    va_start(args, format);
    text(s, px, py, anchor, colour, format, args);
    va_end(args);
}

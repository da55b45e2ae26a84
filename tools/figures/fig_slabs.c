/* fig_slabs.c: chapter 5's figure, the slab test: each pair of planes gives an interval of t, and the
 * ray meets the box where the intervals overlap. */
#include "aabb.h"
#include "figures.h"
#include "svg.h"

/* Where the slab intervals are drawn: a t axis from 0 to T_AXIS_END, T_PIXELS pixels per unit of t. */
#define T_AXIS_END 7.0
#define T_PIXELS 36.0

/* Clips the ray in the plane z = 0 to the box between lo and hi (z from -1 to 1, so z never decides)
 * with aabb_clip, the slab test itself. Returns false when nothing is left. */
static bool clip(svg_point lo, svg_point hi, svg_point o, svg_point d, double *t_near, double *t_far) {
    struct aabb box = {vec3_make(lo.x, lo.y, -1), vec3_make(hi.x, hi.y, 1)};
    *t_near = -INFINITY;
    *t_far = INFINITY;
    return aabb_clip(&box, vec3_make(o.x, o.y, 0), aabb_inverse_direction(vec3_make(d.x, d.y, 0)), t_near, t_far);
}

/* One bar of the interval diagram at pixel row y, for t in [t0, t1] (clipped to the axis). */
static void bar(struct svg *s, double y, double t0, double t1, enum svg_colour colour, const char *label) {
    double x0 = 545, end = t1 > T_AXIS_END ? T_AXIS_END : t1;
    svg_point a = {x0 + t0 * T_PIXELS, y}, b = {x0 + end * T_PIXELS, y};
    struct svg px = *s;
    svg_view(&px, 0, 0, 0, 0, 1);
    a.y = -a.y;
    b.y = -b.y;
    svg_rect(&px, (svg_point){a.x, a.y - 5}, (svg_point){b.x, b.y + 5}, colour, SVG_THIN, 0.35);
    svg_text_px(s, x0 - 10, y + 5, "end", colour, "%s", label);
    svg_text_px(s, a.x, y - 10, "middle", colour, "%.2f", t0);
    if (t1 <= T_AXIS_END)
        svg_text_px(s, b.x, y - 10, "middle", colour, "%.2f", t1);
    else
        svg_text_px(s, b.x + 4, y + 5, "start", colour, "→ %.2f", t1);
}

/* Draws one ray in the picture and its three intervals in the diagram, from pixel row y down. */
static void draw_ray(struct svg *s, svg_point lo, svg_point hi, svg_point d, double length, double y, const char *name) {
    svg_point o = {0, 0};
    double x_near, x_far, y_near, y_far, t_near, t_far;
    clip((svg_point){lo.x, -INFINITY}, (svg_point){hi.x, INFINITY}, o, d, &x_near, &x_far);
    clip((svg_point){-INFINITY, lo.y}, (svg_point){INFINITY, hi.y}, o, d, &y_near, &y_far);
    bool hit = clip(lo, hi, o, d, &t_near, &t_far);
    svg_line(s, o, svg_along(o, d, length), SVG_RAY, SVG_ARROW);
    svg_text(s, svg_along(o, d, length), 6, 0, "start", SVG_RAY, "%s", name);
    svg_dot(s, svg_along(o, d, x_near), SVG_SURFACE);
    svg_dot(s, svg_along(o, d, x_far), SVG_SURFACE);
    svg_dot(s, svg_along(o, d, y_near), SVG_ACCENT);
    svg_dot(s, svg_along(o, d, y_far), SVG_ACCENT);
    svg_text_px(s, 545, y - 34, "start", SVG_INK, "ray %s: %s", name,
                hit ? "the intervals overlap, a hit" : "no overlap (x entry > y exit), a miss");
    bar(s, y, x_near, x_far, SVG_SURFACE, "x slab");
    bar(s, y + 40, y_near, y_far, SVG_ACCENT, "y slab");
    if (hit)
        bar(s, y + 80, t_near, t_far, SVG_RAY, "the box");
}

void figure_slabs(FILE *out) {
    svg_point lo = {2, 1}, hi = {5, 3};
    struct svg s;
    svg_begin(&s, out, 900, 470, "Chapter 5: the slab test, entry and exit intervals of t");
    svg_view(&s, 0, 0, 50, 420, 62);
    svg_rect(&s, (svg_point){lo.x, -0.4}, (svg_point){hi.x, 6.5}, SVG_SURFACE, SVG_THIN, 0.08);
    svg_rect(&s, (svg_point){-0.5, lo.y}, (svg_point){7.0, hi.y}, SVG_ACCENT, SVG_THIN, 0.08);
    svg_rect(&s, lo, hi, SVG_INK, SVG_SOLID, 0.10);
    svg_text(&s, (svg_point){(lo.x + hi.x) / 2, -0.4}, 0, 20, "middle", SVG_SURFACE, "x slab: %g ≤ x ≤ %g", lo.x, hi.x);
    svg_text(&s, (svg_point){7.0, lo.y}, 0, 20, "end", SVG_ACCENT, "y slab: %g ≤ y ≤ %g", lo.y, hi.y);
    svg_dot(&s, (svg_point){0, 0}, SVG_INK);
    svg_text(&s, (svg_point){0, 0}, 0, 22, "middle", SVG_INK, "O");
    draw_ray(&s, lo, hi, svg_unit((svg_point){3, 1.6}), 7.2, 150, "A");
    draw_ray(&s, lo, hi, svg_unit((svg_point){1.2, 3}), 6.1, 350, "B");
    svg_text_px(&s, 545, 80, "start", SVG_MUTED, "t from 0 to %g, %g pixels per unit", T_AXIS_END, T_PIXELS);
    svg_end(&s);
}

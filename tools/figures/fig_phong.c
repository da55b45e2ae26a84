/* fig_phong.c: chapter 6's figure, the vectors of the Phong highlight: N, L, the ray D and its mirror R. */
#include "figures.h"
#include "phong.h"
#include "svg.h"

static svg_point flat(vec3 p) { return (svg_point){p.x, p.y}; }

/* Degrees between two unit vectors. */
static double degrees_between(vec3 a, vec3 b) { return acos(vec3_dot(a, b)) * 180.0 / M_PI; }

void figure_phong(FILE *out) {
    vec3 p = vec3_make(0, 0, 0), n = vec3_make(0, 1, 0);
    vec3 eye = vec3_make(-4, 3, 0), light = vec3_make(3, 4.5, 0);
    vec3 d = vec3_normalize(vec3_sub(p, eye));
    vec3 l = vec3_normalize(vec3_sub(light, p));
    vec3 r = phong_reflect(d, n);
    svg_point P = flat(p);

    struct svg s;
    svg_begin(&s, out, 900, 450, "Chapter 6: the vectors of the Phong highlight");
    svg_view(&s, 0, 0, 450, 380, 78);
    svg_line(&s, (svg_point){-5, 0}, (svg_point){5, 0}, SVG_SURFACE, SVG_SOLID);
    svg_rect(&s, (svg_point){-5, -0.5}, (svg_point){5, 0}, SVG_SURFACE, SVG_THIN, 0.08);
    svg_text(&s, (svg_point){5, 0}, 0, 22, "end", SVG_SURFACE, "surface");
    svg_line(&s, flat(eye), P, SVG_RAY, SVG_ARROW);
    svg_dot(&s, flat(eye), SVG_INK);
    svg_text(&s, flat(eye), 0, -12, "middle", SVG_INK, "eye");
    svg_text(&s, svg_along(P, flat(d), -2.3), -6, 18, "end", SVG_RAY, "D, the ray");
    svg_line(&s, P, svg_along(P, flat(r), 3.6), SVG_RAY, SVG_ARROW | SVG_DASHED);
    svg_text(&s, svg_along(P, flat(r), 3.6), 8, 0, "start", SVG_RAY, "R = D − 2 (D·N) N");
    svg_line(&s, P, svg_along(P, flat(n), 3.0), SVG_NORMAL, SVG_ARROW);
    svg_text(&s, svg_along(P, flat(n), 3.0), 0, -10, "middle", SVG_NORMAL, "N");
    svg_line(&s, P, flat(light), SVG_LIGHT, SVG_ARROW);
    svg_dot(&s, flat(light), SVG_LIGHT);
    svg_text(&s, flat(light), 10, 0, "start", SVG_LIGHT, "light");
    svg_text(&s, svg_along(P, flat(l), 2.4), 10, 10, "start", SVG_LIGHT, "L");
    svg_dot(&s, P, SVG_HIT);
    svg_text(&s, P, 0, 22, "middle", SVG_HIT, "P");

    /* the angles: the ray and its mirror make equal angles with N; N·L and R·L are cosines */
    double incidence = degrees_between(vec3_neg(d), n);
    svg_angle(&s, P, flat(vec3_neg(d)), flat(n), 55, SVG_INK);
    svg_text(&s, P, -40, -62, "end", SVG_INK, "%.1f°", incidence);
    svg_angle(&s, P, flat(n), flat(r), 55, SVG_INK);
    svg_text(&s, P, 46, -60, "start", SVG_INK, "%.1f°", degrees_between(n, r));
    svg_angle(&s, P, flat(n), flat(l), 120, SVG_LIGHT);
    svg_text(&s, svg_along(P, svg_unit(flat(vec3_add(n, l))), 132.0 / s.scale), 0, 0, "end", SVG_LIGHT, "θ = %.1f°",
             degrees_between(n, l));
    svg_angle(&s, P, flat(r), flat(l), 170, SVG_RAY);
    svg_text(&s, svg_along(P, flat(vec3_normalize(vec3_add(r, l))), 182.0 / s.scale), 4, 0, "start", SVG_RAY,
             "α = %.1f°", degrees_between(r, l));

    svg_text_px(&s, 20, 30, "start", SVG_LIGHT, "diffuse ∝ N·L = cos θ = %.3f", vec3_dot(n, l));
    svg_text_px(&s, 20, 52, "start", SVG_RAY, "highlight ∝ (R·L)^phong_size, R·L = cos α = %.3f", vec3_dot(r, l));
    svg_text_px(&s, 20, 74, "start", SVG_INK, "(V = −D points back to the eye)");
    svg_end(&s);
}

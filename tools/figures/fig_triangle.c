/* fig_triangle.c: chapter 3's figure, the barycentric coordinates u and v that Moller-Trumbore finds. */
#include "figures.h"
#include "svg.h"
#include "triangle.h"

/* The triangle lies in the plane z = 0 and the ray comes straight at the reader, down -z, aimed at
 * A + HIT_U E1 + HIT_V E2; triangle_intersect then finds u and v again from the ray alone. */
#define HIT_U 0.35
#define HIT_V 0.30
#define RAY_START_Z 4.0

static svg_point flat(vec3 p) { return (svg_point){p.x, p.y}; }

static svg_point centroid(svg_point a, svg_point b, svg_point c) {
    return (svg_point){(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
}

void figure_triangle(FILE *out) {
    vec3 a = vec3_make(0, 0, 0), b = vec3_make(4, 0.6, 0), c = vec3_make(1.3, 3.2, 0);
    vec3 e1 = vec3_sub(b, a), e2 = vec3_sub(c, a);
    vec3 aim = vec3_add(a, vec3_add(vec3_scale(e1, HIT_U), vec3_scale(e2, HIT_V)));
    ray r = {vec3_make(aim.x, aim.y, RAY_START_Z), vec3_make(0, 0, -1)};
    double t = 0, u = 0, v = 0;
    triangle_intersect(a, b, c, &r, RAY_T_MIN, INFINITY, &t, &u, &v);
    svg_point A = flat(a), B = flat(b), C = flat(c), P = flat(ray_at(r, t));
    svg_point along_e1 = flat(vec3_add(a, vec3_scale(e1, u)));

    struct svg s;
    svg_begin(&s, out, 960, 470, "Chapter 3: the barycentric coordinates u and v of a ray's hit on a triangle");
    svg_view(&s, 0, 0, 200, 420, 110);
    /* the three small triangles: each weight is the area of the one opposite its corner */
    svg_polygon(&s, (svg_point[]){P, B, C}, 3, true, SVG_SURFACE, SVG_THIN, 0.10);
    svg_polygon(&s, (svg_point[]){A, P, C}, 3, true, SVG_NORMAL, SVG_THIN, 0.14);
    svg_polygon(&s, (svg_point[]){A, B, P}, 3, true, SVG_LIGHT, SVG_THIN, 0.14);
    svg_polygon(&s, (svg_point[]){A, B, C}, 3, true, SVG_INK, SVG_SOLID, 0);
    svg_text(&s, centroid(P, B, C), 0, 5, "middle", SVG_SURFACE, "1 − u − v");
    svg_text(&s, centroid(A, P, C), 0, 5, "middle", SVG_NORMAL, "u");
    svg_text(&s, centroid(A, B, P), 0, 5, "middle", SVG_LIGHT, "v");
    /* the edges as vectors, and the path A + u E1 + v E2 to the hit */
    svg_line(&s, A, B, SVG_INK, SVG_ARROW);
    svg_line(&s, A, C, SVG_INK, SVG_ARROW);
    svg_line(&s, A, along_e1, SVG_HIT, SVG_DASHED);
    svg_line(&s, along_e1, P, SVG_HIT, SVG_DASHED | SVG_ARROW);
    svg_text(&s, along_e1, 0, 22, "middle", SVG_HIT, "u E1");
    svg_text(&s, svg_along(along_e1, svg_minus(P, along_e1), 0.5), -8, 4, "end", SVG_HIT, "v E2");
    svg_dot(&s, P, SVG_HIT);
    svg_text(&s, P, 10, -8, "start", SVG_HIT, "P");
    svg_text(&s, A, -8, 16, "end", SVG_INK, "A");
    svg_text(&s, B, 10, 5, "start", SVG_INK, "B");
    svg_text(&s, C, 0, -10, "middle", SVG_INK, "C");
    svg_text(&s, svg_along(A, svg_minus(B, A), 0.72), 0, 22, "middle", SVG_INK, "E1 = B − A,  v = 0 along it");
    svg_text(&s, svg_along(A, svg_minus(C, A), 0.6), -10, 0, "end", SVG_INK, "E2 = C − A,  u = 0 along it");
    svg_text(&s, svg_along(B, svg_minus(C, B), 0.6), 10, 0, "start", SVG_INK, "u + v = 1 along BC");

    svg_text_px(&s, 690, 60, "start", SVG_INK, "The ray comes straight at you");
    svg_text_px(&s, 690, 80, "start", SVG_INK, "(along −z) and meets the triangle");
    svg_text_px(&s, 690, 100, "start", SVG_INK, "at t = %g, where Möller–Trumbore", t);
    svg_text_px(&s, 690, 120, "start", SVG_INK, "finds");
    svg_text_px(&s, 710, 150, "start", SVG_HIT, "u = %.2f,  v = %.2f", u, v);
    svg_text_px(&s, 710, 172, "start", SVG_HIT, "P = (1 − u − v) A + u B + v C");
    svg_text_px(&s, 690, 210, "start", SVG_INK, "Each weight is the share of the");
    svg_text_px(&s, 690, 230, "start", SVG_INK, "area of the small triangle");
    svg_text_px(&s, 690, 250, "start", SVG_INK, "opposite its corner.");
    svg_text_px(&s, 690, 285, "start", SVG_INK, "Inside: u ≥ 0, v ≥ 0, u + v ≤ 1.");
    svg_end(&s);
}

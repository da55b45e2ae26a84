/* fig_plane.c: chapter 4's figure, the distance t = (d - n.O) / (n.D) from a ray's origin to a plane. */
#include "figures.h"
#include "plane.h"
#include "svg.h"

void figure_plane(FILE *out) {
    /* the plane y = 1 in the form "normal 0 1 0 distance 1", seen from its side */
    struct plane floor = {vec3_make(0, 1, 0), 1, 0};
    ray r = {vec3_make(0, 4, 0), vec3_normalize(vec3_make(3, -2, 0))};
    double t = 0;
    plane_intersect(&floor, &r, RAY_T_MIN, INFINITY, &t);
    double n_dot_o = vec3_dot(floor.normal, r.origin), n_dot_d = vec3_dot(floor.normal, r.direction);
    svg_point origin = {0, 0}, O = {r.origin.x, r.origin.y}, D = {r.direction.x, r.direction.y};
    svg_point hit = svg_along(O, D, t);

    struct svg s;
    svg_begin(&s, out, 900, 420, "Chapter 4: where a ray meets the plane n · P = d");
    svg_view(&s, 0, 0, 230, 370, 80);
    svg_line(&s, (svg_point){-2.5, floor.distance}, (svg_point){8, floor.distance}, SVG_SURFACE, SVG_SOLID);
    svg_text(&s, (svg_point){8, floor.distance}, 0, -10, "end", SVG_SURFACE, "the plane n · P = d");
    svg_dot(&s, origin, SVG_INK);
    svg_text(&s, origin, 0, 20, "middle", SVG_INK, "world origin");
    svg_line(&s, origin, svg_along(origin, (svg_point){floor.normal.x, floor.normal.y}, floor.distance), SVG_NORMAL,
             SVG_ARROW);
    svg_text(&s, (svg_point){0, floor.distance / 2}, 8, 5, "start", SVG_NORMAL, "n");

    /* the two distances measured along n, as brackets on the left */
    svg_point foot_o = {-1.6, n_dot_o};
    svg_line(&s, (svg_point){-1.6, 0}, foot_o, SVG_MUTED, SVG_THIN);
    svg_line(&s, O, foot_o, SVG_MUTED, SVG_DASHED);
    svg_line(&s, origin, (svg_point){-1.6, 0}, SVG_MUTED, SVG_DASHED);
    svg_text(&s, (svg_point){-1.6, n_dot_o / 2 + 0.5}, -8, 0, "end", SVG_INK, "n · O = %g", n_dot_o);
    svg_text(&s, (svg_point){-1.6, floor.distance / 2}, -8, 5, "end", SVG_INK, "d = %g", floor.distance);
    svg_line(&s, (svg_point){-1.75, floor.distance}, (svg_point){-1.45, floor.distance}, SVG_MUTED, SVG_THIN);
    svg_line(&s, (svg_point){-1.75, n_dot_o}, (svg_point){-1.45, n_dot_o}, SVG_MUTED, SVG_THIN);
    svg_line(&s, (svg_point){-1.75, 0}, (svg_point){-1.45, 0}, SVG_MUTED, SVG_THIN);

    /* the ray, and how far one unit of t moves it along n */
    svg_line(&s, O, hit, SVG_RAY, SVG_ARROW);
    svg_dot(&s, O, SVG_INK);
    svg_text(&s, O, 0, -12, "middle", SVG_INK, "O");
    svg_point step = svg_along(O, D, 1);
    svg_line(&s, step, (svg_point){step.x + 1.2, step.y}, SVG_MUTED, SVG_DASHED);
    svg_line(&s, (svg_point){O.x + D.x + 1.2, O.y}, (svg_point){O.x + D.x + 1.2, step.y}, SVG_RAY, SVG_ARROW | SVG_THIN);
    svg_line(&s, O, (svg_point){O.x + D.x + 1.2, O.y}, SVG_MUTED, SVG_DASHED);
    svg_text(&s, (svg_point){O.x + D.x + 1.2, O.y + n_dot_d / 2}, 8, 5, "start", SVG_RAY,
             "n · D = %.4f: the change along n for each unit of t", n_dot_d);
    svg_text(&s, step, -10, 10, "end", SVG_RAY, "O + 1·D");
    svg_dot(&s, hit, SVG_HIT);
    svg_text(&s, hit, 0, 24, "middle", SVG_HIT, "t = (d − n · O) / (n · D) = (%g − %g) / %.4f = %.4f", floor.distance,
             n_dot_o, n_dot_d, t);
    svg_end(&s);
}

/* fig_sphere.c: chapter 2's figure, the two roots of the ray-sphere quadratic, a miss, and a ray starting inside. */
#include "figures.h"
#include "sphere.h"
#include "svg.h"

/* Draws the sphere (centre C, radius 1) and the roots of the quadratic for one ray along +x in the plane
 * z = 0, as sphere_intersect finds them: the near one from t_min, the far one from just beyond the near
 * one. The roots drawn are where the ray's horizontal line meets the circle, by Pythagoras (half the
 * chord is sqrt(r^2 - h^2) at a height h from the centre), and b and c the quadratic's coefficients for
 * this ray, written out for D = (1, 0, 0): the figure is not a second ray-sphere test (a student copy
 * blanks sphere_intersect). */
static void draw_roots(struct svg *s, const struct sphere *ball, vec3 origin, const char *origin_label) {
    ray r = {origin, vec3_make(1, 0, 0)};
    double along = origin.x - ball->centre.x, height = origin.y - ball->centre.y;
    double half_chord = sqrt(ball->radius * ball->radius - height * height);
    double near = -along - half_chord, far = -along + half_chord;
    double b = along, c = along * along + height * height - ball->radius * ball->radius;
    double hit;
    bool found = sphere_intersect(ball, &r, RAY_T_MIN, INFINITY, &hit);
    svg_point o = {origin.x, origin.y}, d = {1, 0};
    svg_circle(s, (svg_point){ball->centre.x, ball->centre.y}, ball->radius, SVG_SURFACE, SVG_SOLID, 0.12);
    svg_dot(s, (svg_point){ball->centre.x, ball->centre.y}, SVG_SURFACE);
    svg_text(s, (svg_point){ball->centre.x, ball->centre.y}, 0, -10, "middle", SVG_SURFACE, "C");
    if (near < 0)
        svg_line(s, svg_along(o, d, near - 0.4), o, SVG_MUTED, SVG_DASHED);
    svg_line(s, o, svg_along(o, d, far + 0.9), SVG_RAY, SVG_ARROW);
    svg_dot(s, o, SVG_INK);
    svg_text(s, o, 0, -12, "middle", SVG_INK, "%s", origin_label);
    svg_text(s, o, 0, 22, "middle", SVG_INK, "t = 0");
    /* the near root: a hit when it lies beyond t_min, a point behind the ray when it does not */
    if (found && hit == near) {
        svg_dot(s, svg_along(o, d, near), SVG_HIT);
        svg_text(s, svg_along(o, d, near), -6, 22, "end", SVG_HIT, "t = %g: the hit (near root)", near);
    } else {
        svg_circle(s, svg_along(o, d, near), 0.05, SVG_MUTED, SVG_SOLID, 0);
        svg_text(s, svg_along(o, d, near), -4, -12, "end", SVG_MUTED, "t = %g: behind, rejected", near);
    }
    double second;
    bool found_far = sphere_intersect(ball, &r, found && hit == near ? hit : RAY_T_MIN, INFINITY, &second);
    if (found_far && second == far) {
        enum svg_colour colour = found && hit == far ? SVG_HIT : SVG_RAY;
        svg_dot(s, svg_along(o, d, far), colour);
        svg_text(s, svg_along(o, d, far), 6, 22, "start", colour, "t = %g: %s", far,
                 found && hit == far ? "the hit (far root)" : "far root");
    }
    svg_text(s, svg_along(o, d, far + 0.95), 6, 5, "start", SVG_RAY, "D");
    svg_text(s, (svg_point){ball->centre.x, ball->centre.y}, 0, ball->radius * s->scale + 24, "middle", SVG_INK,
             "b = (O − C)·D = %g,  c = |O − C|² − r² = %g,  b² − c = %g", b, c, b * b - c);
}

void figure_sphere(FILE *out) {
    struct sphere ball = {vec3_make(5, 0, 0), 1, 0};
    struct svg s;
    svg_begin(&s, out, 900, 610, "Chapter 2: the two roots of the ray-sphere quadratic, a miss, and a ray from inside");

    svg_view(&s, 0, 0, 70, 175, 100);
    svg_text_px(&s, 20, 28, "start", SVG_INK, "from outside: two roots, the nearer one is the hit");
    draw_roots(&s, &ball, vec3_make(0, 0, 0), "O");
    /* a ray that passes the sphere: the discriminant is negative */
    ray miss = {vec3_make(0, 0, 0), vec3_normalize(vec3_make(5, 1.2, 0))};
    /* b^2 - c = r^2 - d^2, d the distance of the centre from the ray's line */
    double gap = vec3_length(vec3_cross(vec3_sub(ball.centre, miss.origin), miss.direction));
    double t;
    if (!sphere_intersect(&ball, &miss, RAY_T_MIN, INFINITY, &t)) {
        svg_point d = {miss.direction.x, miss.direction.y};
        svg_line(&s, (svg_point){0, 0}, svg_along((svg_point){0, 0}, d, 6.0), SVG_MUTED, SVG_ARROW | SVG_THIN);
        svg_text(&s, svg_along((svg_point){0, 0}, d, 6.0), 8, 5, "start", SVG_MUTED, "b² − c = %.2f < 0: a miss",
                 ball.radius * ball.radius - gap * gap);
    }

    ball.centre = vec3_make(5, -2.9, 0);
    svg_text_px(&s, 20, 335, "start", SVG_INK, "from inside (a refracted ray): the near root is behind, the far one is the hit");
    draw_roots(&s, &ball, vec3_make(4.5, -2.9, 0), "O");
    svg_end(&s);
}

/* fig_recursion.c: chapter 8's figure, reflection and refraction into glass, and total internal
 * reflection on the way out. */
#include "figures.h"
#include "phong.h"
#include "svg.h"
#include "whitted.h"

/* The chapter's glass. */
#define GLASS_IOR 1.5

static svg_point flat(vec3 p) { return (svg_point){p.x, p.y}; }

static double degrees_between(vec3 a, vec3 b) { return acos(vec3_dot(a, b)) * 180.0 / M_PI; }

/* The surface y = 0 with air above and glass below, as one panel. */
static void draw_surface(struct svg *s, const char *title, double title_x) {
    svg_rect(s, (svg_point){-2.8, -2.6}, (svg_point){2.8, 0}, SVG_SURFACE, SVG_THIN, 0.10);
    svg_line(s, (svg_point){-2.8, 0}, (svg_point){2.8, 0}, SVG_SURFACE, SVG_SOLID);
    svg_line(s, (svg_point){0, -2.6}, (svg_point){0, 2.6}, SVG_MUTED, SVG_DASHED | SVG_THIN);
    svg_text(s, (svg_point){-2.8, 0}, 4, -10, "start", SVG_INK, "air, n = 1");
    svg_text(s, (svg_point){-2.8, 0}, 4, 22, "start", SVG_SURFACE, "glass, n = %g", GLASS_IOR);
    svg_text_px(s, title_x, 28, "middle", SVG_INK, "%s", title);
}

void figure_recursion(FILE *out) {
    struct svg s;
    svg_begin(&s, out, 900, 490, "Chapter 8: reflection, refraction and total internal reflection");
    svg_point P = {0, 0};

    /* Left: into the glass at 45 degrees. */
    svg_view(&s, 0, 0, 225, 245, 76);
    draw_surface(&s, "entering: reflected and refracted", 225);
    vec3 n = vec3_make(0, 1, 0); /* faces the incoming ray */
    vec3 d = vec3_normalize(vec3_make(1, -1, 0));
    vec3 r = phong_reflect(d, n), t = d;
    bool refracted = whitted_refract(d, n, 1.0 / GLASS_IOR, &t);
    svg_line(&s, svg_along(P, flat(d), -3.2), P, SVG_RAY, SVG_ARROW);
    svg_text(&s, svg_along(P, flat(d), -3.2), 0, -8, "middle", SVG_RAY, "D");
    svg_line(&s, P, svg_along(P, flat(r), 3.2), SVG_RAY, SVG_ARROW | SVG_DASHED);
    svg_text(&s, svg_along(P, flat(r), 3.2), 0, -8, "middle", SVG_RAY, "R, reflected");
    if (refracted) {
        svg_line(&s, P, svg_along(P, flat(t), 2.6), SVG_HIT, SVG_ARROW);
        svg_text(&s, svg_along(P, flat(t), 2.6), 8, 0, "start", SVG_HIT, "T, refracted");
        svg_angle(&s, P, (svg_point){0, -1}, flat(t), 70, SVG_HIT);
        /* right of T, clear of the ray */
        svg_text(&s, P, 62, 95, "start", SVG_HIT, "θ2 = %.1f°", degrees_between(vec3_neg(n), t));
    }
    svg_angle(&s, P, flat(vec3_neg(d)), (svg_point){0, 1}, 60, SVG_RAY);
    /* each angle's label inside its wedge, far enough out to clear D and R */
    svg_text(&s, P, -45, -115, "middle", SVG_RAY, "θ1 = %.1f°", degrees_between(vec3_neg(d), n));
    svg_angle(&s, P, (svg_point){0, 1}, flat(r), 60, SVG_RAY);
    svg_text(&s, P, 45, -115, "middle", SVG_RAY, "%.1f°", degrees_between(n, r));
    svg_dot(&s, P, SVG_INK);
    svg_text_px(&s, 225, 475, "middle", SVG_INK, "sin θ2 = sin θ1 / %g (Snell)", GLASS_IOR);

    /* Right: leaving the glass beyond the critical angle. The normal faces the ray: it points down. */
    svg_view(&s, 0, 0, 675, 245, 76);
    draw_surface(&s, "leaving: beyond the critical angle", 675);
    vec3 inward = vec3_make(0, -1, 0);
    double critical = asin(1.0 / GLASS_IOR);
    double steep = 50.0 * M_PI / 180.0;
    vec3 d_out = vec3_make(sin(steep), cos(steep), 0);
    vec3 r_out = phong_reflect(d_out, inward), t_out;
    if (!whitted_refract(d_out, inward, GLASS_IOR, &t_out)) {
        svg_line(&s, svg_along(P, flat(d_out), -3.2), P, SVG_RAY, SVG_ARROW);
        svg_text(&s, svg_along(P, flat(d_out), -3.0), -8, -4, "end", SVG_RAY, "D"); /* above the ray */
        svg_line(&s, P, svg_along(P, flat(r_out), 3.2), SVG_RAY, SVG_ARROW);
        /* below the ray, clear of it and of the critical ray's dashed line */
        svg_text(&s, svg_along(P, flat(r_out), 3.0), 0, 22, "end", SVG_RAY, "R: all the light");
        svg_text(&s, P, 30, -20, "start", SVG_RAY, "k < 0: no T");
    }
    vec3 d_critical = vec3_make(-sin(critical), cos(critical), 0);
    svg_line(&s, svg_along(P, flat(d_critical), -2.4), P, SVG_LIGHT, SVG_DASHED | SVG_ARROW);
    svg_angle(&s, P, (svg_point){0, -1}, flat(vec3_neg(d_critical)), 80, SVG_LIGHT);
    svg_text(&s, P, 100, 60, "start", SVG_LIGHT, "θc = %.1f°", critical * 180 / M_PI);
    svg_line(&s, P, (svg_point){-2.6, 0}, SVG_LIGHT, SVG_DASHED | SVG_ARROW);
    svg_text(&s, (svg_point){-1.4, 0}, 0, -40, "middle", SVG_LIGHT, "at θc, T grazes the surface");
    svg_angle(&s, P, (svg_point){0, -1}, flat(vec3_neg(d_out)), 60, SVG_RAY);
    svg_text(&s, P, -30, 80, "end", SVG_RAY, "%.0f°", degrees_between(inward, vec3_neg(d_out)));
    svg_dot(&s, P, SVG_INK);
    svg_text_px(&s, 675, 475, "middle", SVG_INK, "sin θc = 1 / %g", GLASS_IOR);
    svg_end(&s);
}

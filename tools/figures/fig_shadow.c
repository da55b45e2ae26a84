/* fig_shadow.c: chapter 7's figure, the shadow ray's window and its margins, and where acne comes from. */
#include "camera.h"
#include "figures.h"
#include "sphere.h"
#include "svg.h"

/* Chapter 7's red sphere, camera and bright light (scenes/07-shadows.scene), searched for a pixel
 * whose computed hit point lies inside the sphere, so that a shadow ray without margin finds the
 * sphere again at once: a grain of acne. */
struct acne_grain {
    int i, j;         /* the pixel */
    double inside;    /* |P - C| - r: how far the computed point lies off the surface (negative: inside) */
    double t_again;   /* where the shadow ray with t_min = 0 finds the sphere again */
    int grains, lit;  /* of the lit pixels on the sphere, how many would show acne */
};

static struct acne_grain find_acne(void) {
    struct sphere ball = {vec3_make(-1.8, 0.9, 0), 0.9, 0};
    vec3 light = vec3_make(-5, 7, 5);
    struct camera cam;
    char err[256];
    camera_init(&cam, vec3_make(0, 2.2, 7.5), vec3_make(0, 0.7, 0), vec3_make(0, 1, 0), 38, 400, 300, err, sizeof err);
    struct acne_grain found = {-1, -1, 0, 0, 0, 0};
    for (int j = 0; j < cam.height; j++)
        for (int i = 0; i < cam.width; i++) {
            ray r = camera_ray(&cam, i, j);
            double t;
            if (!sphere_intersect(&ball, &r, RAY_T_MIN, INFINITY, &t))
                continue;
            vec3 p = ray_at(r, t);
            vec3 to_light = vec3_sub(light, p);
            double distance = vec3_length(to_light);
            ray shadow = {p, vec3_scale(to_light, 1.0 / distance)};
            if (vec3_dot(sphere_normal(&ball, p), shadow.direction) <= 0)
                continue;
            found.lit++;
            double again;
            if (!sphere_intersect(&ball, &shadow, 0, distance, &again))
                continue;
            found.grains++;
            if (found.i < 0) {
                found = (struct acne_grain){i, j, vec3_length(vec3_sub(p, ball.centre)) - ball.radius, again,
                                            found.grains, found.lit};
            }
        }
    return found;
}

void figure_shadow(FILE *out) {
    struct svg s;
    svg_begin(&s, out, 900, 480, "Chapter 7: the shadow ray's window, and shadow acne");

    /* Left: two points on a floor, one lit, one in the sphere's shadow. */
    struct sphere blocker = {vec3_make(3.2, 2.2, 0), 0.8, 0};
    vec3 light = vec3_make(5.6, 5.4, 0);
    svg_view(&s, 0, 0, 30, 400, 66); /* 66: left_scale below */
    svg_text_px(&s, 220, 28, "middle", SVG_INK, "one shadow ray per light");
    svg_line(&s, (svg_point){0, 0}, (svg_point){6.5, 0}, SVG_SURFACE, SVG_SOLID);
    svg_circle(&s, (svg_point){blocker.centre.x, blocker.centre.y}, blocker.radius, SVG_SURFACE, SVG_SOLID, 0.15);
    svg_dot(&s, (svg_point){light.x, light.y}, SVG_LIGHT);
    svg_text(&s, (svg_point){light.x, light.y}, -10, -6, "end", SVG_LIGHT, "light");
    double xs[2] = {0.8, 5.0};
    for (int k = 0; k < 2; k++) {
        vec3 p = vec3_make(xs[k], 0, 0);
        vec3 to_light = vec3_sub(light, p);
        double d = vec3_length(to_light);
        ray shadow = {p, vec3_scale(to_light, 1.0 / d)};
        double t;
        bool blocked = sphere_intersect(&blocker, &shadow, SHADOW_T_MIN, d - SHADOW_T_MIN, &t);
        svg_point P = {p.x, p.y}, L = {shadow.direction.x, shadow.direction.y};
        /* the margins are 1e-3 long, far too short to see: drawn as gaps of 10 pixels */
        double gap = 10.0 / s.scale;
        svg_line(&s, svg_along(P, L, gap), svg_along(P, L, blocked ? t : d - gap), SVG_RAY, blocked ? SVG_SOLID : SVG_ARROW);
        if (blocked) {
            svg_line(&s, svg_along(P, L, t), svg_along(P, L, d - gap), SVG_MUTED, SVG_DASHED | SVG_THIN);
            svg_dot(&s, svg_along(P, L, t), SVG_HIT);
            /* left of the sphere, above the ray: clear of both */
            svg_text(&s, svg_along(P, L, t), -12, -20, "end", SVG_HIT, "blocked at t = %.2f:", t);
            svg_text(&s, svg_along(P, L, t), -12, -4, "end", SVG_HIT, "S = 0");
        } else {
            svg_text(&s, svg_along(P, L, d / 2), 10, 0, "start", SVG_RAY, "nothing in the window: S = 1");
        }
        svg_dot(&s, P, SVG_INK);
        svg_text(&s, P, 0, 22, "middle", SVG_INK, "P (d = %.2f)", d);
    }
    svg_text_px(&s, 30, 465, "start", SVG_INK, "window: 1e-3 < t < d − 1e-3 (gaps at both ends, not to scale)");

    /* Right: a grain of acne, seen under a microscope. */
    struct acne_grain g = find_acne();
    svg_view(&s, 0, 0, 660, 240, 1);
    /* the point is drawn acne_depth_px pixels inside; the left panel has 66 pixels per unit */
    const double acne_depth_px = 22, left_scale = 66;
    double enlarged = acne_depth_px / -g.inside / left_scale;
    int power = (int)floor(log10(enlarged));
    svg_text_px(&s, 690, 28, "middle", SVG_INK, "acne, drawn about %.0f × 10^%d times larger", enlarged / pow(10, power),
                power);
    svg_rect(&s, (svg_point){-190, -70}, (svg_point){200, 0}, SVG_SURFACE, SVG_THIN, 0.12);
    svg_line(&s, (svg_point){-190, 0}, (svg_point){200, 0}, SVG_SURFACE, SVG_SOLID);
    svg_text(&s, (svg_point){200, -70}, -6, -8, "end", SVG_SURFACE, "inside the sphere");
    svg_point P = {-60, -acne_depth_px}, L = svg_unit((svg_point){0.55, 1});
    svg_line(&s, P, svg_along(P, L, 150), SVG_RAY, SVG_ARROW);
    svg_point again = svg_along(P, L, acne_depth_px / L.y);
    svg_dot(&s, again, SVG_HIT);
    svg_text(&s, again, 10, -10, "start", SVG_HIT, "the surface again, t = %.1e", g.t_again);
    svg_text(&s, svg_along(P, L, 150), 0, -10, "middle", SVG_RAY, "towards the light");
    svg_dot(&s, P, SVG_INK);
    svg_text(&s, P, 0, 22, "middle", SVG_INK, "computed P, %.1e inside", -g.inside); /* within the box */
    svg_text_px(&s, 690, 340, "middle", SVG_INK, "Chapter 7's camera, pixel (%d, %d): the red", g.i, g.j);
    svg_text_px(&s, 690, 360, "middle", SVG_INK, "sphere's hit point rounds to just inside it.");
    svg_text_px(&s, 690, 390, "middle", SVG_INK, "With no margin, %d of the %d lit pixels", g.grains, g.lit);
    svg_text_px(&s, 690, 410, "middle", SVG_INK, "of that sphere find it again, and go dark.");
    svg_text_px(&s, 690, 445, "middle", SVG_RAY, "t = %.1e < 1e-3: ignored, the point is lit.", g.t_again);
    svg_end(&s);
}

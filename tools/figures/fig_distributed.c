/* fig_distributed.c: chapter 13's figures: an area light's umbra and penumbra, computed with
 * soft_shadow_filtered on the floor under a ball, and the thin lens's rays meeting on the focal plane,
 * with the circle of confusion they make elsewhere, computed with thin_lens_ray. */
#include <math.h>
#include <stdio.h>

#include "figures.h"
#include "scene.h"
#include "soft_shadow.h"
#include "sphere.h"
#include "svg.h"
#include "thin_lens.h"
#include "world.h"

/* ---- umbra and penumbra ---------------------------------------------------------------------- */

#define FLOOR_LEFT (-4.0)
#define FLOOR_RIGHT 4.0
#define FLOOR_STEP 0.02
#define LIGHT_POINTS 9 /* the lamp's grid along x; one point along z */

/* The share of `light` reaching floor point x (y = 0, z = 0) in world w. */
static double share_at(const struct world *w, const struct light *light, double x) {
    return soft_shadow_filtered(w, vec3_make(x, 0, 0), light).x;
}

void figure_penumbra(FILE *out) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, NULL};
    static const char text[] = "camera eye 0 2 9 target 0 1 0 fov 40\nimage 8 8\n"
                               "light position 0 6 0 axis1 3 0 0 axis2 0 0 0.001 samples 9 1\n"
                               "light position 0 6 0\n"
                               "sphere centre 0 2.4 0 radius 0.8\n";
    struct scene scene;
    struct world w;
    char err[256];
    if (!scene_parse("penumbra.scene", text, kinds, &scene, err, sizeof err) || !world_init(&w, &scene, err, sizeof err)) {
        fprintf(stderr, "figure_penumbra: %s\n", err);
        return;
    }
    const struct light *lamp = &scene.lights[0], *point = &scene.lights[1];
    struct svg s;
    svg_begin(&s, out, 900, 520, "Chapter 13: umbra and penumbra under an area light, and the share of it each floor point sees");
    svg_view(&s, 0, 0, 300, 400, 50);
    svg_text_px(&s, 300, 24, "middle", SVG_INK, "a lamp 3 wide, 9 points, over a ball");

    /* The lamp, its 9 points, and the floor. */
    vec3 first = soft_shadow_light_point(lamp, vec3_make(0, 0, 0), 0, 0);
    vec3 last = soft_shadow_light_point(lamp, vec3_make(0, 0, 0), LIGHT_POINTS - 1, 0);
    svg_line(&s, (svg_point){first.x, first.y}, (svg_point){last.x, last.y}, SVG_LIGHT, SVG_SOLID);
    for (int u = 0; u < LIGHT_POINTS; u++) {
        vec3 p = soft_shadow_light_point(lamp, vec3_make(0, 0, 0), u, 0);
        svg_dot(&s, (svg_point){p.x, p.y}, SVG_LIGHT);
    }
    svg_text(&s, (svg_point){last.x, last.y}, 10, 4, "start", SVG_LIGHT, "area light");
    svg_circle(&s, (svg_point){0, 2.4}, 0.8, SVG_SURFACE, SVG_SOLID, 0.15);
    svg_line(&s, (svg_point){FLOOR_LEFT, 0}, (svg_point){FLOOR_RIGHT, 0}, SVG_SURFACE, SVG_SOLID);

    /* The floor shaded by the share it sees, and where the umbra and the penumbra end: found from the
     * shares themselves, not from a formula. */
    double umbra_end = 0, penumbra_end = 0, hard_end = 0;
    for (double x = 0; x <= FLOOR_RIGHT; x += FLOOR_STEP) {
        if (share_at(&w, lamp, x) == 0)
            umbra_end = x;
        if (share_at(&w, lamp, x) < 1)
            penumbra_end = x + FLOOR_STEP;
        if (share_at(&w, point, x) == 0)
            hard_end = x + FLOOR_STEP;
    }
    /* The floor under it as a band, one rectangle per run of floor points seeing the same share. */
    double run_start = FLOOR_LEFT, run_share = share_at(&w, lamp, FLOOR_LEFT);
    for (double x = FLOOR_LEFT + FLOOR_STEP; x <= FLOOR_RIGHT + FLOOR_STEP / 2; x += FLOOR_STEP) {
        double share = x <= FLOOR_RIGHT ? share_at(&w, lamp, x) : -1;
        if (share == run_share)
            continue;
        if (run_share < 1)
            svg_rect(&s, (svg_point){run_start, 0}, (svg_point){x, -0.25}, SVG_MUTED, SVG_THIN, 0.9 * (1 - run_share));
        run_start = x;
        run_share = share;
    }
    /* The rays from the lamp's ends that graze the ball bound the two regions (right half). */
    svg_line(&s, (svg_point){first.x, first.y}, (svg_point){umbra_end, 0}, SVG_RAY, SVG_DASHED | SVG_THIN);
    svg_line(&s, (svg_point){last.x, last.y}, (svg_point){penumbra_end, 0}, SVG_RAY, SVG_DASHED | SVG_THIN);
    svg_line(&s, (svg_point){-umbra_end, 0}, (svg_point){last.x, last.y}, SVG_RAY, SVG_DASHED | SVG_THIN);
    svg_line(&s, (svg_point){-penumbra_end, 0}, (svg_point){first.x, first.y}, SVG_RAY, SVG_DASHED | SVG_THIN);
    svg_text(&s, (svg_point){0, -0.25}, 0, 16, "middle", SVG_INK, "umbra");
    svg_text(&s, (svg_point){(umbra_end + penumbra_end) / 2, -0.25}, 0, 16, "middle", SVG_INK, "penumbra");
    svg_text(&s, (svg_point){-(umbra_end + penumbra_end) / 2, -0.25}, 0, 16, "middle", SVG_INK, "penumbra");
    svg_text(&s, (svg_point){3.4, -0.25}, 0, 16, "middle", SVG_INK, "lit");

    /* Right: the share along the floor, the area light's ramp beside the point light's step. */
    svg_view(&s, 0, 0, 720, 330, 38);
    svg_text_px(&s, 720, 24, "middle", SVG_INK, "share of the light reaching the floor");
    svg_line(&s, (svg_point){FLOOR_LEFT, 0}, (svg_point){FLOOR_RIGHT, 0}, SVG_MUTED, SVG_THIN);
    svg_line(&s, (svg_point){FLOOR_LEFT, 5}, (svg_point){FLOOR_RIGHT, 5}, SVG_MUTED, SVG_DASHED | SVG_THIN);
    svg_text(&s, (svg_point){FLOOR_LEFT, 5}, -4, 4, "end", SVG_MUTED, "1");
    svg_text(&s, (svg_point){FLOOR_LEFT, 0}, -4, 4, "end", SVG_MUTED, "0");
    svg_point soft[(int)((FLOOR_RIGHT - FLOOR_LEFT) / FLOOR_STEP) + 2], hard[sizeof soft / sizeof soft[0]];
    int n = 0;
    for (double x = FLOOR_LEFT; x <= FLOOR_RIGHT + 1e-9 && n < (int)(sizeof soft / sizeof soft[0]); x += FLOOR_STEP, n++) {
        soft[n] = (svg_point){x, 5 * share_at(&w, lamp, x)};
        hard[n] = (svg_point){x, 5 * share_at(&w, point, x)};
    }
    svg_polygon(&s, hard, n, false, SVG_MUTED, SVG_DASHED, 0.0);
    svg_polygon(&s, soft, n, false, SVG_LIGHT, SVG_SOLID, 0.0);
    svg_text(&s, (svg_point){0, 0}, 0, 18, "middle", SVG_INK, "floor x");
    svg_text(&s, (svg_point){hard_end, 2.5}, 6, 0, "start", SVG_MUTED, "point light");
    svg_text_px(&s, 720, 372, "middle", SVG_INK, "umbra to x = %.2f, penumbra to x = %.2f;", umbra_end, penumbra_end);
    svg_text_px(&s, 720, 390, "middle", SVG_INK, "the point light's shadow ends at x = %.2f", hard_end);
    svg_text_px(&s, 720, 408, "middle", SVG_INK, "steps: the 9 points' weights (1/16, then 1/8)");
    svg_end(&s);
    world_free(&w);
    scene_free(&scene);
}

/* ---- the thin lens and the circle of confusion ------------------------------------------------ */

#define LENS_APERTURE 1.2
#define FOCAL_DISTANCE 6.0
#define NEAR_DISTANCE 3.5 /* a surface nearer than the focal plane */

void figure_lens(FILE *out) {
    struct camera c;
    char err[256];
    /* The camera at the origin looking down -z; the figure shows the side view, z to the right (as
     * distance in front of the lens) and y up. One pixel tall picture: its middle row. */
    camera_init(&c, vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), 30, 21, 21, err, sizeof err);
    struct lens l = {LENS_APERTURE, vec3_make(0, 0, -FOCAL_DISTANCE), 7};
    struct thin_lens t;
    thin_lens_init(&t, &c, &l, 0);
    struct svg s;
    svg_begin(&s, out, 900, 420, "Chapter 13: a thin lens, its rays meeting on the focal plane, and the circle of confusion");
    svg_view(&s, 0, 0, 90, 210, 100);
    svg_text_px(&s, 450, 24, "middle", SVG_INK, "the rays of one image point, from 7 points of the lens");

    /* The lens, the focal plane and a nearer surface. */
    svg_line(&s, (svg_point){0, -0.6 * LENS_APERTURE}, (svg_point){0, 0.6 * LENS_APERTURE}, SVG_SURFACE, SVG_SOLID);
    svg_text(&s, (svg_point){0, -0.6 * LENS_APERTURE}, 0, 18, "middle", SVG_INK, "lens, D = %.1f", LENS_APERTURE);
    svg_line(&s, (svg_point){FOCAL_DISTANCE, -1.6}, (svg_point){FOCAL_DISTANCE, 1.6}, SVG_MUTED, SVG_DASHED);
    svg_text(&s, (svg_point){FOCAL_DISTANCE, -1.6}, 0, 18, "middle", SVG_INK, "focal plane, F = %.0f", FOCAL_DISTANCE);
    svg_line(&s, (svg_point){NEAR_DISTANCE, -1.6}, (svg_point){NEAR_DISTANCE, 1.6}, SVG_SURFACE, SVG_THIN);
    svg_text(&s, (svg_point){NEAR_DISTANCE, -1.6}, 0, 18, "middle", SVG_INK, "a nearer surface, d = %.1f", NEAR_DISTANCE);

    /* The rays of the middle pixel (10, 10), seen from the side: where each leaves the lens (its y) and
     * where it crosses the nearer surface and the focal plane. */
    double low = INFINITY, high = -INFINITY, focus_low = INFINITY, focus_high = -INFINITY;
    for (int k = 0; k < t.samples; k++) {
        ray r = thin_lens_ray(&t, 10.5, 10.5, k);
        double to_near = NEAR_DISTANCE / -r.direction.z, to_focus = FOCAL_DISTANCE / -r.direction.z;
        double y_near = r.origin.y + to_near * r.direction.y, y_focus = r.origin.y + to_focus * r.direction.y;
        double beyond = (FOCAL_DISTANCE + 2.0) / -r.direction.z;
        svg_point from = {0, r.origin.y}, far = {FOCAL_DISTANCE + 2.0, r.origin.y + beyond * r.direction.y};
        svg_line(&s, from, far, SVG_RAY, SVG_THIN);
        svg_dot(&s, from, SVG_LIGHT);
        svg_dot(&s, (svg_point){NEAR_DISTANCE, y_near}, SVG_HIT);
        low = fmin(low, y_near);
        high = fmax(high, y_near);
        focus_low = fmin(focus_low, y_focus);
        focus_high = fmax(focus_high, y_focus);
    }
    svg_dot(&s, (svg_point){FOCAL_DISTANCE, (focus_low + focus_high) / 2}, SVG_HIT);
    svg_text(&s, (svg_point){NEAR_DISTANCE, high}, 8, -6, "start", SVG_HIT, "spread %.3f", high - low);
    svg_text(&s, (svg_point){FOCAL_DISTANCE, focus_high}, 8, -6, "start", SVG_HIT, "spread %.3f", focus_high - focus_low);
    svg_text_px(&s, 450, 385, "middle", SVG_INK,
                "circle of confusion at d: D |F - d| / F = %.3f; the rays' spread there is %.3f (the lens points are",
                LENS_APERTURE * fabs(FOCAL_DISTANCE - NEAR_DISTANCE) / FOCAL_DISTANCE, high - low);
    svg_text_px(&s, 450, 403, "middle", SVG_INK,
                "7 of a hexagon seen edge-on); on the focal plane only the pixel's own width remains");
    svg_end(&s);
}

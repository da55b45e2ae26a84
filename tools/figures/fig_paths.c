/* fig_paths.c: chapter 15's figures: where cosine-weighted and uniform directions fall over the
 * hemisphere, and the error of the Cornell box against the number of paths, on log scales (the
 * measurement of tests/support/path_proofs.c, with the chapter's own path tracer). */
#include <math.h>
#include <stdio.h>

#include "figures.h"
#include "path_proofs.h"
#include "sampling.h"
#include "svg.h"

#define DIRECTIONS 48 /* drawn on each half-disc */

/* One half-disc: DIRECTIONS directions about the normal +y seen from the side, each a line from the
 * point on the surface, drawn from the numbers of stream `seed`; uniform over the hemisphere, or
 * cosine-weighted. */
static void directions(struct svg *s, double centre_x, bool cosine, uint32_t seed) {
    svg_point at = {centre_x, 0};
    svg_line(s, (svg_point){centre_x - 1.15, 0}, (svg_point){centre_x + 1.15, 0}, SVG_SURFACE, SVG_SOLID);
    svg_line(s, at, (svg_point){centre_x, 1.25}, SVG_NORMAL, SVG_ARROW);
    struct sample_stream rng = sample_stream_start(0, 0, 0, seed);
    for (int k = 0; k < DIRECTIONS; k++) {
        double u1 = sample_stream_next(&rng), u2 = sample_stream_next(&rng);
        vec3 d = cosine ? sampling_cosine_hemisphere(vec3_make(0, 1, 0), u1, u2) : sampling_sphere_direction(u1, u2);
        if (!cosine && d.y < 0)
            d = vec3_neg(d); /* the upper half: uniform over the hemisphere */
        svg_line(s, at, (svg_point){centre_x + d.x, d.y}, SVG_RAY, SVG_THIN);
    }
}

void figure_sampling(FILE *out) {
    struct svg s;
    svg_begin(&s, out, 900, 330, "Chapter 15: uniform and cosine-weighted directions over the hemisphere");
    svg_view(&s, 0, 0, 450, 250, 150);
    svg_text_px(&s, 450, 28, "middle", SVG_INK, "48 directions about the normal, seen from the side");
    directions(&s, -1.5, false, 1);
    directions(&s, 1.5, true, 2);
    svg_text(&s, (svg_point){-1.5, 0}, 0, 30, "middle", SVG_INK, "uniform: density 1 / (2 pi)");
    svg_text(&s, (svg_point){1.5, 0}, 0, 30, "middle", SVG_INK, "cosine-weighted: density cos / pi");
    svg_text(&s, (svg_point){-1.5, 0}, 0, 52, "middle", SVG_MUTED, "as many near the horizon, where cos is small");
    svg_text(&s, (svg_point){1.5, 0}, 0, 52, "middle", SVG_MUTED, "most where cos is large, where the light counts");
    svg_end(&s);
}

void figure_convergence(FILE *out) {
    double slope = 0, rmse[5] = {1, 1, 1, 1, 1};
    char err[512];
    if (!path_proof_convergence("scenes/15-paths.scene", &slope, rmse, err, sizeof err))
        fprintf(stderr, "figures: 15-convergence.svg: %s\n", err);
    struct svg s;
    svg_begin(&s, out, 700, 460, "Chapter 15: the error against the number of paths, log scales");
    /* x: log2 N from 0 to 8; y: log2 RMSE */
    double top = ceil(log2(rmse[0])), bottom = floor(log2(rmse[4])) - 1;
    svg_view(&s, 0, bottom, 110, 390, 330.0 / (top - bottom));
    svg_text_px(&s, 350, 28, "middle", SVG_INK, "RMSE of the Cornell box (white balls, 24 x 24 pixels) against paths a pixel");
    for (int k = 0; k <= 8; k += 2) {
        svg_line(&s, (svg_point){k, bottom}, (svg_point){k, top}, SVG_MUTED, SVG_DASHED | SVG_THIN);
        svg_text(&s, (svg_point){k, bottom}, 0, 20, "middle", SVG_INK, "%d", 1 << k);
    }
    for (double y = bottom; y <= top; y += 1) {
        svg_line(&s, (svg_point){0, y}, (svg_point){8, y}, SVG_MUTED, SVG_DASHED | SVG_THIN);
        svg_text(&s, (svg_point){0, y}, -8, 5, "end", SVG_INK, "%.3g", pow(2, y));
    }
    svg_text(&s, (svg_point){4, bottom}, 0, 44, "middle", SVG_INK, "paths a pixel, N");
    /* the line of slope -1/2 through the first point, and the measured points joined */
    svg_line(&s, (svg_point){0, log2(rmse[0])}, (svg_point){8, log2(rmse[0]) - 4}, SVG_ACCENT, SVG_DASHED);
    svg_point p[5];
    for (int k = 0; k < 5; k++) {
        p[k] = (svg_point){2 * k, log2(rmse[k])};
        svg_dot(&s, p[k], SVG_HIT);
    }
    svg_polygon(&s, p, 5, false, SVG_HIT, SVG_SOLID, 0.0);
    svg_text(&s, (svg_point){8, log2(rmse[0]) - 4}, 0, -12, "end", SVG_ACCENT, "slope -1/2: error ~ 1 / sqrt(N)");
    svg_text(&s, p[2], 12, -10, "start", SVG_HIT, "measured: slope %.2f", slope);
    svg_end(&s);
}

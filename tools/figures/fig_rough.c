/* fig_rough.c: chapter 17's figure, microfacets in three panels: the half vector of a reflection, the GGX
 * distribution of normals for three roughnesses, and masking on a rough profile seen at a grazing angle
 * (the first two drawn with common/microfacet.c's own functions; the profile is a made-up one). */
#include <math.h>

#include "figures.h"
#include "microfacet.h"
#include "sampling.h"
#include "svg.h"

#define PROFILE_FACETS 26       /* the rough profile of the third panel */
#define PROFILE_HEIGHT 0.45     /* its vertices' heights lie within +- this */
#define PROFILE_WIDTH 4.6
#define SEEN_FROM_DEGREES 72.0  /* the eye's angle from the normal in the third panel */
#define RAY_STEP 1e-9           /* a ray leaves its facet by this much before it can be blocked */
#define PARALLEL 1e-15          /* a ray and a facet closer to parallel than this never cross */

/* In the figure's plane, x along the surface and y along its normal: z of the local frame is y here. */
static svg_point plane_of(vec3 w) { return (svg_point){w.x, w.z}; }

static svg_point at(svg_point o, svg_point d, double t) { return svg_along(o, d, t); }

static void half_vector_panel(struct svg *s, svg_point p) {
    double eye = -52.0 * M_PI / 180.0, light = 24.0 * M_PI / 180.0;
    vec3 wo = vec3_make(sin(eye), 0.0, cos(eye)), wi = vec3_make(sin(light), 0.0, cos(light));
    vec3 h = vec3_normalize(vec3_add(wo, wi));
    svg_line(s, at(p, (svg_point){1, 0}, -2.6), at(p, (svg_point){1, 0}, 2.6), SVG_SURFACE, SVG_THIN);
    svg_line(s, p, at(p, (svg_point){0, 1}, 2.4), SVG_NORMAL, SVG_ARROW | SVG_DASHED);
    svg_text(s, at(p, (svg_point){0, 1}, 2.4), 0, -8, "middle", SVG_NORMAL, "n");
    svg_point along = {h.z, -h.x}; /* the microfacet: across h */
    svg_line(s, at(p, along, -0.8), at(p, along, 0.8), SVG_SURFACE, SVG_SOLID);
    svg_line(s, p, at(p, plane_of(wo), 2.3), SVG_RAY, SVG_ARROW);
    svg_text(s, at(p, plane_of(wo), 2.3), 0, -10, "middle", SVG_RAY, "wo, to the eye");
    svg_line(s, p, at(p, plane_of(wi), 2.3), SVG_LIGHT, SVG_ARROW);
    svg_text(s, at(p, plane_of(wi), 2.3), 4, -8, "start", SVG_LIGHT, "wi, to the light");
    svg_line(s, p, at(p, plane_of(h), 1.7), SVG_ACCENT, SVG_ARROW);
    svg_text(s, at(p, plane_of(h), 1.7), 6, 4, "start", SVG_ACCENT, "h");
    svg_angle(s, p, (svg_point){0, 1}, plane_of(h), 70, SVG_ACCENT);
    svg_text(s, p, 0, 24, "middle", SVG_INK, "h = (wo + wi) / |wo + wi|, %.0f° from n", acos(h.z) * 180.0 / M_PI);
    svg_text(s, p, 0, 46, "middle", SVG_MUTED, "the one facet normal that mirrors wo into wi");
}

static void distribution_panel(struct svg *s, svg_point p) {
    static const double roughness[] = {0.3, 0.6, 1.0};
    static const enum svg_colour colour[] = {SVG_RAY, SVG_ACCENT, SVG_LIGHT};
    svg_line(s, at(p, (svg_point){1, 0}, -2.6), at(p, (svg_point){1, 0}, 2.6), SVG_SURFACE, SVG_THIN);
    for (int k = 0; k < 3; k++) {
        double alpha = microfacet_alpha(roughness[k]), peak = microfacet_ggx_d(vec3_make(0, 0, 1), alpha);
        svg_point curve[181];
        for (int d = 0; d <= 180; d++) {
            double theta = (d - 90) * M_PI / 180.0;
            vec3 m = vec3_make(sin(theta), 0.0, cos(theta));
            double r = 2.3 * microfacet_ggx_d(m, alpha) * m.z / peak;
            curve[d] = at(p, plane_of(m), r);
        }
        svg_polygon(s, curve, 181, false, colour[k], SVG_SOLID, 0.0);
        svg_text(s, p, 130, -150 + 20 * k, "start", colour[k], "roughness %.1f: alpha %.2f", roughness[k], alpha);
    }
    svg_text(s, p, 0, 24, "middle", SVG_INK, "D(m) cos θm against the angle of m");
    svg_text(s, p, 0, 46, "middle", SVG_MUTED, "each scaled to the same height: rougher is wider");
}

/* The parameter t > RAY_STEP at which the ray o + t d crosses segment a b, or INFINITY. */
static double crossing(svg_point o, svg_point d, svg_point a, svg_point b) {
    svg_point e = svg_minus(b, a), f = svg_minus(a, o);
    double det = d.x * (-e.y) - d.y * (-e.x);
    if (fabs(det) < PARALLEL)
        return INFINITY;
    double t = (f.x * (-e.y) - f.y * (-e.x)) / det, u = (d.x * f.y - d.y * f.x) / det;
    return t > RAY_STEP && u >= 0.0 && u <= 1.0 ? t : INFINITY;
}

static void masking_panel(struct svg *s, svg_point p) {
    svg_point v[PROFILE_FACETS + 1];
    struct sample_stream rng = sample_stream_start(17, 0, 0, 3);
    for (int k = 0; k <= PROFILE_FACETS; k++)
        v[k] = (svg_point){p.x - PROFILE_WIDTH / 2 + PROFILE_WIDTH * k / PROFILE_FACETS,
                           p.y + PROFILE_HEIGHT * (2.0 * sample_stream_next(&rng) - 1.0)};
    double angle = SEEN_FROM_DEGREES * M_PI / 180.0;
    svg_point wo = {sin(angle), cos(angle)};
    double facing = 0.0, seen = 0.0;
    for (int k = 0; k < PROFILE_FACETS; k++) {
        svg_point e = svg_minus(v[k + 1], v[k]), n = svg_unit((svg_point){-e.y, e.x});
        svg_point mid = at(v[k], e, 0.5);
        double toward = n.x * wo.x + n.y * wo.y;
        bool blocked = false;
        for (int j = 0; j < PROFILE_FACETS && !blocked; j++)
            blocked = j != k && isfinite(crossing(mid, wo, v[j], v[j + 1]));
        double projected = toward > 0.0 ? toward * sqrt(e.x * e.x + e.y * e.y) : 0.0;
        facing += projected;
        seen += blocked ? 0.0 : projected;
        enum svg_colour c = toward <= 0.0 ? SVG_MUTED : blocked ? SVG_LIGHT : SVG_HIT;
        svg_line(s, v[k], v[k + 1], c, toward <= 0.0 ? SVG_THIN : SVG_SOLID);
        if (toward > 0.0 && !blocked)
            svg_line(s, at(mid, wo, 0.9), mid, SVG_RAY, SVG_ARROW | SVG_THIN);
    }
    svg_text(s, at(p, wo, 1.6), 0, -40, "middle", SVG_RAY, "from the eye, %.0f° from n", SEEN_FROM_DEGREES);
    svg_text(s, p, 0, 40, "middle", SVG_INK, "seen (purple), masked (orange), turned away (grey)");
    svg_text(s, p, 0, 62, "middle", SVG_MUTED, "seen: %.0f %% of the area facing the eye", 100.0 * seen / facing);
}

void figure_microfacets(FILE *out) {
    struct svg s;
    svg_begin(&s, out, 1260, 350, "Chapter 17: the half vector, the distribution of normals, masking");
    svg_view(&s, 0, 0, 630, 270, 60);
    svg_text_px(&s, 210, 30, "middle", SVG_INK, "the half vector");
    svg_text_px(&s, 630, 30, "middle", SVG_INK, "the distribution D");
    svg_text_px(&s, 1038, 30, "middle", SVG_INK, "masking G");
    half_vector_panel(&s, (svg_point){-7, 0});
    distribution_panel(&s, (svg_point){0, 0});
    masking_panel(&s, (svg_point){6.8, 0});
    svg_end(&s);
}

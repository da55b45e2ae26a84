/* check_rough.c: the coursework checks of chapter 17: the GGX distribution, the rough metal's BRDF and
 * the density of a reflected direction, against values worked out by hand from the formulas of
 * docs/17-microfacets.md (Walter et al. 2007's D and Lambda, written here in their own form, tan^2 and
 * cos^4, not the code's), and against the integrals they must have (the coursework kit). */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "microfacet.h"

#define ROUGH_PI 3.14159265358979323846

/* Values worked out by hand are compared within this share of themselves: far above rounding, far below
 * any mistake (a forgotten factor is at least 4 % off in every case here). */
#define ROUGH_RELATIVE 1e-9

/* An integral by quadrature is compared within this. */
#define ROUGH_INTEGRAL_TOLERANCE 2e-3

/* The width every hand-worked value uses: alpha = 0.5 (roughness 0.707). */
#define ROUGH_ALPHA 0.5

/* The unit direction at `degrees` from the normal z, turned towards +x (or -x when `towards_minus_x`). */
static vec3 at_angle(double degrees, bool towards_minus_x) {
    double t = degrees * ROUGH_PI / 180.0;
    return vec3_make((towards_minus_x ? -1.0 : 1.0) * sin(t), 0.0, cos(t));
}

/* GGX's D at theta from the normal, in Walter et al.'s form: alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2). */
static double hand_d(double degrees, double alpha) {
    double t = degrees * ROUGH_PI / 180.0, c = cos(t), tan2 = tan(t) * tan(t);
    return alpha * alpha / (ROUGH_PI * c * c * c * c * (alpha * alpha + tan2) * (alpha * alpha + tan2));
}

/* Smith's Lambda for GGX at theta from the normal: (sqrt(1 + alpha^2 tan^2) - 1) / 2. */
static double hand_lambda(double degrees, double alpha) {
    double t = degrees * ROUGH_PI / 180.0;
    return (sqrt(1.0 + alpha * alpha * tan(t) * tan(t)) - 1.0) / 2.0;
}

static bool relatively_near(double got, double expected) {
    return fabs(got - expected) <= ROUGH_RELATIVE * fabs(expected) + 1e-300;
}

/* ---- 17.1 microfacet_ggx_d ------------------------------------------------------------------------ */

/* Says whether D at `degrees` from the normal (turned by phi about it) is the hand-worked value. */
static bool d_is(double degrees, double phi, double alpha, char *why, size_t why_size) {
    double t = degrees * ROUGH_PI / 180.0;
    vec3 m = vec3_make(sin(t) * cos(phi), sin(t) * sin(phi), cos(t));
    char text[64];
    check_calling("microfacet_ggx_d", "the normal %s, alpha %g", check_vec_text(m, text), alpha);
    double got = microfacet_ggx_d(m, alpha), expected = hand_d(degrees, alpha);
    if (relatively_near(got, expected))
        return true;
    snprintf(why, why_size, "D(%s) with alpha %g is %.10g, expected alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) = "
             "%.10g", text, alpha, got, expected);
    return false;
}

CHECK(check_ggx_d_values) {
    if (!d_is(0.0, 0.0, ROUGH_ALPHA, why, why_size)) /* 1 / (pi alpha^2): the peak */
        return false;
    if (!d_is(0.0, 0.0, 0.1, why, why_size))
        return false;
    if (!d_is(30.0, 0.0, ROUGH_ALPHA, why, why_size) || !d_is(45.0, 1.0, ROUGH_ALPHA, why, why_size))
        return false;
    if (!d_is(45.0, 2.5, 0.2, why, why_size) || !d_is(80.0, 4.0, 0.9, why, why_size))
        return false;
    vec3 below = vec3_normalize(vec3_make(0.3, 0.0, -1.0));
    check_calling("microfacet_ggx_d", "a normal below the surface");
    double got = microfacet_ggx_d(below, ROUGH_ALPHA);
    if (got != 0.0) {
        snprintf(why, why_size, "D of a normal pointing below the surface (z < 0) is %g, expected 0: no "
                 "microfacet faces inwards", got);
        return false;
    }
    return true;
}

CHECK(check_ggx_d_projected_area) {
    /* The microfacets' areas projected onto the surface add up to the surface's: the integral of
     * D(m) cos(theta) over the hemisphere is 1, by a midpoint rule in theta (D does not depend on phi). */
    const double alphas[] = {0.1, 0.4, 0.9};
    enum { STEPS = 200000 };
    for (int a = 0; a < 3; a++) {
        check_calling("microfacet_ggx_d", "normals over the whole hemisphere, alpha %g", alphas[a]);
        double sum = 0.0, step = (ROUGH_PI / 2.0) / STEPS;
        for (int i = 0; i < STEPS; i++) {
            double t = (i + 0.5) * step;
            vec3 m = vec3_make(sin(t), 0.0, cos(t));
            sum += microfacet_ggx_d(m, alphas[a]) * cos(t) * sin(t) * 2.0 * ROUGH_PI * step;
        }
        if (!(fabs(sum - 1.0) <= ROUGH_INTEGRAL_TOLERANCE)) {
            snprintf(why, why_size, "with alpha %g the integral of D(m) cos(theta) over the hemisphere is %.6f, "
                     "expected 1 (the microfacets' projected area is the surface's)", alphas[a], sum);
            return false;
        }
    }
    return true;
}

/* ---- 17.2 conductor_eval (through microfacet_eval) ----------------------------------------------- */

/* Says whether the rough metal of reflectance f0 at normal incidence gives `expected` from wo and wi. */
static bool metal_f_is(vec3 f0, vec3 wo, vec3 wi, vec3 expected, const char *what, char *why, size_t why_size) {
    struct microfacet_lobe l = microfacet_conductor_lobe(f0, ROUGH_ALPHA);
    char o[64], i[64], e[64], g[64];
    check_calling("conductor_eval", "a rough metal of alpha %g, the eye along %s, the light along %s", ROUGH_ALPHA,
                  check_vec_text(wo, o), check_vec_text(wi, i));
    vec3 got = microfacet_eval(&l, wo, wi);
    if (relatively_near(got.x, expected.x) && relatively_near(got.y, expected.y) && relatively_near(got.z, expected.z))
        return true;
    snprintf(why, why_size, "%s (alpha %g, wo %s, wi %s): f is %s, expected %s", what, ROUGH_ALPHA, o, i,
             check_vec_text(got, g), check_vec_text(expected, e));
    return false;
}

CHECK(check_metal_mirror_pair) {
    vec3 white = vec3_make(1, 1, 1);
    /* Straight down and straight back: h = z, no masking, F = 1: D(0) / 4. */
    double f = hand_d(0.0, ROUGH_ALPHA) / 4.0;
    if (!metal_f_is(white, vec3_make(0, 0, 1), vec3_make(0, 0, 1), vec3_make(f, f, f),
                    "eye and light along the normal", why, why_size))
        return false;
    /* Eye and light at 60 degrees on either side: h = z again, each direction masked by Lambda(60),
     * G2 = 1 / (1 + 2 Lambda), and 4 cos cos = 1. */
    f = hand_d(0.0, ROUGH_ALPHA) / (1.0 + 2.0 * hand_lambda(60.0, ROUGH_ALPHA));
    return metal_f_is(white, at_angle(60.0, false), at_angle(60.0, true), vec3_make(f, f, f),
                      "eye and light at 60 degrees, mirrored: D / (1 + 2 Lambda(60))", why, why_size);
}

CHECK(check_metal_fresnel_and_half_vector) {
    /* A gold-like F0; the eye at 60 degrees, the light overhead: h at 30 degrees, wo . h = cos 30,
     * Schlick F0 + (1 - F0)(1 - cos 30)^5, G2 = 1 / (1 + Lambda(60)), 4 cos_o cos_i = 2. */
    vec3 f0 = vec3_make(1.0, 0.78, 0.34);
    double c = 1.0 - cos(30.0 * ROUGH_PI / 180.0), c5 = c * c * c * c * c;
    double shape = hand_d(30.0, ROUGH_ALPHA) / (1.0 + hand_lambda(60.0, ROUGH_ALPHA)) / 2.0;
    vec3 expected = vec3_make((f0.x + (1 - f0.x) * c5) * shape, (f0.y + (1 - f0.y) * c5) * shape,
                              (f0.z + (1 - f0.z) * c5) * shape);
    if (!metal_f_is(f0, at_angle(60.0, false), vec3_make(0, 0, 1), expected,
                    "the eye at 60 degrees, the light overhead: Fresnel at the half vector", why, why_size))
        return false;
    /* Light from below a metal: nothing. */
    return metal_f_is(f0, at_angle(60.0, false), vec3_make(0.0, 0.6, -0.8), vec3_make(0, 0, 0),
                      "light from below the surface", why, why_size);
}

/* ---- 17.3 conductor_pdf (through microfacet_pdf) -------------------------------------------------- */

/* Says whether the rough metal's density of wi from wo is `expected`. */
static bool metal_pdf_is(vec3 wo, vec3 wi, double expected, const char *what, char *why, size_t why_size) {
    struct microfacet_lobe l = microfacet_conductor_lobe(vec3_make(1, 1, 1), ROUGH_ALPHA);
    char o[64], i[64];
    check_calling("conductor_pdf", "a rough metal of alpha %g, the eye along %s, the light along %s", ROUGH_ALPHA,
                  check_vec_text(wo, o), check_vec_text(wi, i));
    double got = microfacet_pdf(&l, wo, wi);
    if (relatively_near(got, expected))
        return true;
    snprintf(why, why_size, "%s (alpha %g, wo %s, wi %s): the density is %.10g, expected %.10g", what, ROUGH_ALPHA,
             o, i, got, expected);
    return false;
}

CHECK(check_metal_pdf_values) {
    /* The density of visible normals D_wo(h) = G1(wo) (wo . h) D(h) / wo.z, times d(h)/d(wi) = 1 / (4 wo . h).
     * Along the normal: G1 = 1, h = z: D(0) / 4. */
    if (!metal_pdf_is(vec3_make(0, 0, 1), vec3_make(0, 0, 1), hand_d(0.0, ROUGH_ALPHA) / 4.0,
                      "eye and light along the normal: D(0) / 4", why, why_size))
        return false;
    /* At 60 degrees, mirrored: h = z, wo . h = cos 60 = wo.z: G1(60) D(0) / (4 cos 60). */
    double g1 = 1.0 / (1.0 + hand_lambda(60.0, ROUGH_ALPHA));
    if (!metal_pdf_is(at_angle(60.0, false), at_angle(60.0, true), g1 * hand_d(0.0, ROUGH_ALPHA) / 2.0,
                      "eye and light at 60 degrees, mirrored: G1(60) D(0) / 2", why, why_size))
        return false;
    /* The eye at 60 degrees, the light overhead: h at 30 degrees; wo . h cancels: G1(60) D(30) / (4 cos 60). */
    if (!metal_pdf_is(at_angle(60.0, false), vec3_make(0, 0, 1), g1 * hand_d(30.0, ROUGH_ALPHA) / 2.0,
                      "the eye at 60 degrees, the light overhead: G1(60) D(30) / 2", why, why_size))
        return false;
    return metal_pdf_is(at_angle(60.0, false), vec3_make(0.0, 0.6, -0.8), 0.0, "a direction below the surface", why,
                        why_size);
}

CHECK(check_metal_pdf_integrates_to_one) {
    /* Over every direction above the surface the density adds up to the share of visible normals that
     * reflect wo upwards, never more than 1: all but a sliver for a narrow lobe (alpha 0.05), some 8 %
     * less for alpha 0.3, whose normals that lean far from the eye send it below the surface (lowest[]).
     * Midpoint rule in (cos theta, phi), which the density's peak at the mirror direction does not escape. */
    const double alphas[] = {0.05, 0.3}, lowest[] = {0.99, 0.9};
    enum { STEPS = 1000 };
    for (int a = 0; a < 2; a++) {
        struct microfacet_lobe l = microfacet_conductor_lobe(vec3_make(1, 1, 1), alphas[a]);
        vec3 wo = at_angle(20.0, false);
        check_calling("conductor_pdf", "every direction above a rough metal of alpha %g, the eye at 20 degrees",
                      alphas[a]);
        double sum = 0.0;
        for (int i = 0; i < STEPS; i++) {
            double z = (i + 0.5) / STEPS, s = sqrt(1.0 - z * z);
            for (int j = 0; j < STEPS; j++) {
                double phi = 2.0 * ROUGH_PI * (j + 0.5) / STEPS;
                sum += microfacet_pdf(&l, wo, vec3_make(s * cos(phi), s * sin(phi), z));
            }
        }
        sum *= 2.0 * ROUGH_PI / ((double)STEPS * STEPS);
        if (!(sum <= 1.0 + ROUGH_INTEGRAL_TOLERANCE && sum >= lowest[a])) {
            snprintf(why, why_size, "with alpha %g, the eye at 20 degrees, the density integrates to %.4f over the "
                     "hemisphere, expected between %g and 1 (a density of directions: the Jacobian d(h)/d(wi)?)",
                     alphas[a], sum, lowest[a]);
            return false;
        }
    }
    return true;
}

/* test_microfacet.c: chapter 17's rough lobes (common/microfacet.c): GGX's distribution and masking
 * against closed forms, every sampler against the density it claims by a chi-square test over the
 * sphere (and a wrong density caught by the same test), the densities' integrals, reciprocity, energy,
 * the white furnace's loss against the numerical integral, and the smooth limit. The full grid of
 * roughnesses and angles for the chi-square test runs in make test-long (suite microfacet_long), and so
 * does tests/test_microfacet_faults.c, which builds this file again with each fault of the gallery.
 * This file links with the lobes' modules alone (microfacet, bsdf, sampling, sample_hash). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "bsdf.h"
#include "microfacet.h"
#include "sampling.h"

#define PI 3.14159265358979323846

/* ---- the chi-square test of a sampler against its density (as pbrt's tests) ------------------------- */

/* The sphere of directions in cells of equal angle: theta over [0, pi], phi over [0, 2 pi). */
#define THETA_CELLS 10
#define PHI_CELLS 20
/* Each cell's expected share is its density integrated adaptively: a rectangle of (theta, phi) is
 * halved both ways, at least QUADRATURE_MIN_DEPTH and at most QUADRATURE_DEPTH times, until its four
 * halves' sum (each by a midpoint rule of RECTANGLE_STEPS^2 points) agrees with its own to
 * QUADRATURE_TOLERANCE times its share of the sphere's rectangle. A lobe's density may jump (Phong's
 * at alpha 1 from 1 / (2 pi) to 0 at the edge of its lobe; the refracted density from about 5 to 0 where
 * the microfacet that would refract reaches the horizon): a fixed grid misplaces such jumps by a few
 * thousandths of the whole, and the least depth keeps a jump that clips a rectangle's corner between
 * its points from going unseen. */
#define RECTANGLE_STEPS 4
#define QUADRATURE_MIN_DEPTH 3
#define QUADRATURE_DEPTH 8
#define QUADRATURE_TOLERANCE 1e-4
/* Cells expecting fewer draws than this are pooled into one, so that the statistic is chi-square. */
#define MIN_EXPECTED 5.0
/* The chance that a right sampler fails one test of the whole family (Sidak's correction shares it
 * among the configurations one test runs). */
#define SIGNIFICANCE 0.01
#define QUICK_DRAWS 100000
#define LONG_DRAWS 1000000

typedef bool (*draw_fn)(const struct microfacet_lobe *l, vec3 wo, struct sample_stream *rng, vec3 *wi);
typedef double (*density_fn)(const struct microfacet_lobe *l, vec3 wo, vec3 wi);

struct chi_square {
    double p;            /* the chance of a statistic this large from a right sampler */
    double statistic;
    int degrees;
    double pdf_integral; /* the density integrated over the sphere */
    double drawn_share;  /* the share of draws that gave a direction */
    int impossible;      /* directions drawn where the density is 0 */
};

/* Returns Q(a, x), the regularised upper incomplete gamma function: by its series below a + 1, by its
 * continued fraction (Lentz's method) above. The chi-square's tail is Q(degrees / 2, statistic / 2). */
static double upper_gamma(double a, double x) {
    if (x <= 0.0)
        return 1.0;
    double log_front = a * log(x) - x - lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 1000 && fabs(term) > 1e-16 * fabs(sum); n++) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - sum * exp(log_front);
    }
    double tiny = 1e-300, b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int n = 1; n < 1000; n++) {
        double an = -n * (n - a);
        b += 2.0;
        d = an * d + b;
        d = fabs(d) < tiny ? tiny : d;
        c = b + an / c;
        c = fabs(c) < tiny ? tiny : c;
        d = 1.0 / d;
        double step = d * c;
        h *= step;
        if (fabs(step - 1.0) < 1e-16)
            break;
    }
    return exp(log_front) * h;
}

static vec3 direction_at(double theta, double phi) {
    return vec3_make(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
}

static int cell_of(vec3 w) {
    double theta = acos(fmin(fmax(w.z, -1.0), 1.0)), phi = atan2(w.y, w.x);
    phi = phi < 0.0 ? phi + 2.0 * PI : phi;
    int i = (int)(theta / PI * THETA_CELLS), j = (int)(phi / (2.0 * PI) * PHI_CELLS);
    return (i < THETA_CELLS ? i : THETA_CELLS - 1) * PHI_CELLS + (j < PHI_CELLS ? j : PHI_CELLS - 1);
}

/* A rectangle of (theta, phi) and the density to integrate over it. */
struct rectangle {
    const struct microfacet_lobe *l;
    vec3 wo;
    density_fn density;
    double theta0, theta1, phi0, phi1;
};

/* Returns the density integrated over the rectangle's solid angle by a midpoint rule. */
static double rectangle_sum(struct rectangle r) {
    double d_theta = (r.theta1 - r.theta0) / RECTANGLE_STEPS, d_phi = (r.phi1 - r.phi0) / RECTANGLE_STEPS, sum = 0.0;
    for (int a = 0; a < RECTANGLE_STEPS; a++) {
        double theta = r.theta0 + (a + 0.5) * d_theta;
        for (int b = 0; b < RECTANGLE_STEPS; b++)
            sum += r.density(r.l, r.wo, direction_at(theta, r.phi0 + (b + 0.5) * d_phi)) * sin(theta);
    }
    return sum * d_theta * d_phi;
}

/* Returns the density integrated over the rectangle, whose midpoint sum is `whole`, adaptively. */
static double adaptive_integral(struct rectangle r, double whole, int depth) {
    double theta = 0.5 * (r.theta0 + r.theta1), phi = 0.5 * (r.phi0 + r.phi1);
    struct rectangle parts[4] = {r, r, r, r};
    parts[0].theta1 = parts[1].theta1 = parts[2].theta0 = parts[3].theta0 = theta;
    parts[0].phi1 = parts[2].phi1 = parts[1].phi0 = parts[3].phi0 = phi;
    double sums[4], sum = 0.0;
    for (int k = 0; k < 4; k++)
        sum += sums[k] = rectangle_sum(parts[k]);
    double share = (r.theta1 - r.theta0) * (r.phi1 - r.phi0) / (2.0 * PI * PI);
    if (depth >= QUADRATURE_DEPTH || (depth >= QUADRATURE_MIN_DEPTH && fabs(sum - whole) <= QUADRATURE_TOLERANCE * share))
        return sum;
    sum = 0.0;
    for (int k = 0; k < 4; k++)
        sum += adaptive_integral(parts[k], sums[k], depth + 1);
    return sum;
}

static int by_expected(const void *a, const void *b) {
    const double *x = a, *y = b;
    return (x[0] > y[0]) - (x[0] < y[0]);
}

/* Draws `draws` directions from wo and compares their histogram over the cells with the density's
 * integral over each cell. */
static struct chi_square chi_square_test(const struct microfacet_lobe *l, vec3 wo, draw_fn draw,
                                         density_fn density, int draws, uint32_t seed) {
    enum { CELLS = THETA_CELLS * PHI_CELLS };
    static double cells[CELLS][2]; /* expected, observed */
    struct chi_square r = {0};
    double d_theta = PI / THETA_CELLS, d_phi = 2.0 * PI / PHI_CELLS;
    for (int c = 0; c < CELLS; c++) {
        struct rectangle cell = {l, wo, density, (c / PHI_CELLS) * d_theta, (c / PHI_CELLS + 1) * d_theta,
                                 (c % PHI_CELLS) * d_phi, (c % PHI_CELLS + 1) * d_phi};
        cells[c][0] = adaptive_integral(cell, rectangle_sum(cell), 0);
        cells[c][1] = 0.0;
        r.pdf_integral += cells[c][0];
    }
    int drawn = 0;
    struct sample_stream rng = sample_stream_start(seed, 17, 0, 0);
    for (int k = 0; k < draws; k++) {
        vec3 wi;
        if (!draw(l, wo, &rng, &wi))
            continue;
        drawn++;
        cells[cell_of(wi)][1] += 1.0;
        r.impossible += density(l, wo, wi) <= 0.0;
    }
    r.drawn_share = (double)drawn / draws;
    for (int c = 0; c < CELLS; c++)
        cells[c][0] *= draws;
    qsort(cells, CELLS, sizeof cells[0], by_expected);
    double pooled_expected = 0.0, pooled_observed = 0.0;
    for (int c = 0; c < CELLS; c++) {
        if (pooled_expected < MIN_EXPECTED) { /* the smallest cells, and the first large one if need be */
            pooled_expected += cells[c][0];
            pooled_observed += cells[c][1];
            continue;
        }
        r.statistic += (cells[c][1] - cells[c][0]) * (cells[c][1] - cells[c][0]) / cells[c][0];
        r.degrees++;
    }
    if (pooled_expected > 0.0) {
        r.statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
        r.degrees++;
    }
    r.degrees--;
    r.p = r.degrees > 0 ? upper_gamma(r.degrees / 2.0, r.statistic / 2.0) : 1.0;
    return r;
}

static bool draw_by_the_lobe(const struct microfacet_lobe *l, vec3 wo, struct sample_stream *rng, vec3 *wi) {
    struct microfacet_sample s;
    double u1 = sample_stream_next(rng), u2 = sample_stream_next(rng), u3 = sample_stream_next(rng);
    if (!microfacet_sample(l, wo, u1, u2, u3, &s))
        return false;
    *wi = s.wi;
    return true;
}

/* The wrong sampler: microfacet normals drawn from the whole distribution D(m) m.z (exactly, by its
 * inverse tan^2 = alpha^2 u / (1 - u)) instead of those visible from wo, mirrored as the conductor. */
static bool draw_by_all_normals(const struct microfacet_lobe *l, vec3 wo, struct sample_stream *rng, vec3 *wi) {
    double u = sample_stream_next(rng), phi = 2.0 * PI * sample_stream_next(rng);
    double tan2 = l->alpha * l->alpha * u / (1.0 - u), cos_m = 1.0 / sqrt(1.0 + tan2), sin_m = sqrt(tan2) * cos_m;
    vec3 m = vec3_make(sin_m * cos(phi), sin_m * sin(phi), cos_m);
    double c = vec3_dot(wo, m);
    *wi = vec3_sub(vec3_scale(m, 2.0 * c), wo);
    return c > 0.0 && wi->z > 0.0;
}

static vec3 incident(double cos_theta) {
    double c = fmin(fmax(cos_theta, -1.0), 1.0);
    return vec3_make(sqrt(1.0 - c * c) * 0.8, sqrt(1.0 - c * c) * 0.6, c);
}

enum { PHONG, CONDUCTOR, DIELECTRIC };

static struct microfacet_lobe lobe(int kind, double alpha) {
    vec3 white = vec3_make(1.0, 1.0, 1.0);
    return kind == PHONG       ? microfacet_phong_lobe(white, alpha)
           : kind == CONDUCTOR ? microfacet_conductor_lobe(white, alpha)
                               : microfacet_dielectric_lobe(1.5, white, alpha);
}

static const char *const KIND_NAMES[] = {"phong", "conductor", "dielectric"};

struct configuration {
    int kind;
    double alpha, cos_theta; /* cos_theta < 0: a dielectric seen from inside */
};

/* Runs the chi-square test on each configuration, at the significance shared among them, and checks
 * that the density's integral is the share of draws that gave a direction (the rest of the density,
 * directions below the surface, is where a draw fails). */
static void expect_samplers_match(const struct configuration *c, int count, int draws) {
    double threshold = 1.0 - pow(1.0 - SIGNIFICANCE, 1.0 / count);
    for (int k = 0; k < count; k++) {
        struct microfacet_lobe l = lobe(c[k].kind, c[k].alpha);
        vec3 wo = incident(c[k].cos_theta);
        struct chi_square r = chi_square_test(&l, wo, draw_by_the_lobe, microfacet_pdf, draws, (uint32_t)k + 1);
        cr_log_info("%s alpha %.2f cos %+.2f: chi-square %.1f on %d degrees, p = %.3g; pdf integral %.4f, drawn %.4f",
                    KIND_NAMES[c[k].kind], c[k].alpha, c[k].cos_theta, r.statistic, r.degrees, r.p, r.pdf_integral,
                    r.drawn_share);
        cr_expect(r.p > threshold, "%s alpha %.2f cos %+.2f: chi-square %.1f on %d degrees, p = %.3g < %.3g",
                  KIND_NAMES[c[k].kind], c[k].alpha, c[k].cos_theta, r.statistic, r.degrees, r.p, threshold);
        cr_expect_eq(r.impossible, 0, "%s alpha %.2f cos %+.2f: %d draws where the pdf is 0", KIND_NAMES[c[k].kind],
                     c[k].alpha, c[k].cos_theta, r.impossible);
        /* the drawn share's noise, and the quadrature's error */
        double allowed = 5.0 * sqrt(r.drawn_share * (1.0 - r.drawn_share) / draws) + 1e-4;
        cr_expect(fabs(r.pdf_integral - r.drawn_share) < allowed, "%s alpha %.2f cos %+.2f: pdf integral %.4f, drawn %.4f",
                  KIND_NAMES[c[k].kind], c[k].alpha, c[k].cos_theta, r.pdf_integral, r.drawn_share);
    }
}

/* The quick suite's roughnesses from 0.1 up; the narrowest lobes, alpha 0.05, whose cells take the
 * quadrature longest, are in the long suite's grid. */
Test(microfacet, every_sampler_matches_its_pdf_by_a_chi_square_test) {
    static const struct configuration quick[] = {
        {PHONG, 0.3, 0.5},       {PHONG, 1.0, 0.15},      {CONDUCTOR, 0.1, 0.9},
        {CONDUCTOR, 0.3, 0.5},   {CONDUCTOR, 1.0, 0.15},  {DIELECTRIC, 0.3, 0.5},
        {DIELECTRIC, 1.0, 0.15}, {DIELECTRIC, 0.3, -0.5}, {DIELECTRIC, 0.6, -0.9},
    };
    expect_samplers_match(quick, (int)(sizeof quick / sizeof quick[0]), QUICK_DRAWS);
}

Test(microfacet_long, every_sampler_matches_its_pdf_over_the_grid_of_roughnesses_and_angles, .timeout = 600) {
    static const double alphas[] = {0.05, 0.1, 0.3, 0.6, 1.0}, cosines[] = {0.1, 0.4, 0.7, 1.0};
    struct configuration grid[3 * 5 * 4 + 5 * 4];
    int count = 0;
    for (int kind = PHONG; kind <= DIELECTRIC; kind++)
        for (int a = 0; a < 5; a++)
            for (int c = 0; c < 4; c++)
                grid[count++] = (struct configuration){kind, alphas[a], cosines[c]};
    for (int a = 0; a < 5; a++)
        for (int c = 0; c < 4; c++)
            grid[count++] = (struct configuration){DIELECTRIC, alphas[a], -cosines[c]};
    expect_samplers_match(grid, count, LONG_DRAWS);
}

Test(microfacet, a_sampler_whose_pdf_is_wrong_fails_the_chi_square_test) {
    /* Normals drawn from all of D(m) m.z rather than from those visible: the lobe's pdf (the visible
     * normals') no longer describes the draws. Near the horizon the two differ most. */
    struct microfacet_lobe l = lobe(CONDUCTOR, 0.5);
    struct chi_square wrong = chi_square_test(&l, incident(0.3), draw_by_all_normals, microfacet_pdf, QUICK_DRAWS, 9);
    struct chi_square right = chi_square_test(&l, incident(0.3), draw_by_the_lobe, microfacet_pdf, QUICK_DRAWS, 9);
    cr_log_info("all normals: chi-square %.0f on %d degrees, p = %.3g; visible normals: %.1f, p = %.3g",
                wrong.statistic, wrong.degrees, wrong.p, right.statistic, right.p);
    cr_expect(wrong.p < 1e-6, "the wrong sampler passes: p = %.3g", wrong.p);
    cr_expect(right.p > SIGNIFICANCE, "the right sampler fails: p = %.3g", right.p);
}

Test(microfacet, the_chi_square_tail_is_the_incomplete_gamma_function) {
    /* 2 degrees: the tail is exp(-x / 2); 1 degree: erfc(sqrt(x / 2)); 10 degrees at its 1 % point 23.209 */
    cr_expect(fabs(upper_gamma(1.0, 1.5) - exp(-1.5)) < 1e-12);
    cr_expect(fabs(upper_gamma(0.5, 2.0) - erfc(sqrt(2.0))) < 1e-12);
    cr_expect(fabs(upper_gamma(5.0, 23.209 / 2.0) - 0.01) < 1e-5, "%.6f", upper_gamma(5.0, 23.209 / 2.0));
}

/* ---- the distribution and the masking --------------------------------------------------------------- */

Test(microfacet, alpha_is_the_roughness_squared_once) {
    cr_expect_eq(microfacet_alpha(0.5), 0.25);
    cr_expect_eq(microfacet_alpha(0.2), 0.2 * 0.2);
    cr_expect_eq(microfacet_alpha(1.0), 1.0);
    cr_expect_eq(microfacet_alpha(0.0), 0.0);
    cr_expect_eq(microfacet_alpha(3.0), 1.0);
    cr_expect_eq(microfacet_alpha(-1.0), 0.0);
}

Test(microfacet, every_lobe_has_the_width_alpha_it_is_given) {
    /* Seen and lit from straight above, a GGX lobe shows its peak D(n) = 1 / (pi alpha^2), and the
     * Phong lobe of the matching exponent (n + 2) / (2 pi) = 1 / (pi alpha^2) as well: a lobe that
     * squared alpha again would be 1 / alpha^2 times as high. */
    vec3 up = vec3_make(0.0, 0.0, 1.0);
    for (double alpha = 0.1; alpha < 1.0; alpha += 0.2) {
        double peak = 1.0 / (PI * alpha * alpha);
        struct microfacet_lobe metal = lobe(CONDUCTOR, alpha), glass = lobe(DIELECTRIC, alpha), phong = lobe(PHONG, alpha);
        cr_expect(fabs(microfacet_eval(&metal, up, up).x - peak / 4.0) < 1e-9 * peak, "alpha %.1f", alpha);
        cr_expect(fabs(microfacet_eval(&glass, up, up).x - 0.04 * peak / 4.0) < 1e-9 * peak, "alpha %.1f", alpha);
        cr_expect(fabs(microfacet_eval(&phong, up, up).x - peak) < 1e-9 * peak, "alpha %.1f", alpha);
    }
}

Test(microfacet, the_projected_distribution_integrates_to_one) {
    /* D depends on theta only: 2 pi times the integral of D cos sin over [0, pi / 2], by a fine midpoint
     * rule (the narrowest lobe, alpha 0.01, spans about 0.01 radians, 16 steps of this rule). */
    static const double alphas[] = {0.01, 0.05, 0.2, 0.5, 1.0};
    int steps = 20000;
    for (int a = 0; a < 5; a++) {
        double sum = 0.0, d_theta = PI / 2.0 / steps;
        for (int i = 0; i < steps; i++) {
            double theta = (i + 0.5) * d_theta;
            sum += microfacet_ggx_d(direction_at(theta, 0.0), alphas[a]) * cos(theta) * sin(theta);
        }
        cr_expect(fabs(2.0 * PI * sum * d_theta - 1.0) < 1e-5, "alpha %.2f: %.7f", alphas[a], 2.0 * PI * sum * d_theta);
    }
}

/* Returns the integral of the visible normals' density over the hemisphere of m, with the normals spread
 * by D(m) m.z exactly (as microfacet_albedo does): the density divided by D m.z, averaged. */
static double visible_pdf_integral(vec3 wo, double alpha, int steps) {
    double sum = 0.0;
    for (int i = 0; i < steps; i++) {
        double t = (i + 0.5) / steps, rest = (1.0 - t) * (1.0 - t), u = 1.0 - rest;
        double tan2 = alpha * alpha * u / rest, cos_m = 1.0 / sqrt(1.0 + tan2), sin_m = sqrt(tan2) * cos_m;
        for (int j = 0; j < steps; j++) {
            vec3 m = direction_at(atan2(sin_m, cos_m), 2.0 * PI * (j + 0.5) / steps);
            sum += microfacet_ggx_visible_pdf(wo, m, alpha) / (microfacet_ggx_d(m, alpha) * cos_m) * 2.0 * (1.0 - t);
        }
    }
    return sum / ((double)steps * steps);
}

Test(microfacet, the_visible_normals_pdf_integrates_to_one) {
    static const double alphas[] = {0.05, 0.3, 1.0}, cosines[] = {0.05, 0.5, 1.0};
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) {
            double integral = visible_pdf_integral(incident(cosines[c]), alphas[a], 400);
            cr_expect(fabs(integral - 1.0) < 1e-3, "alpha %.2f cos %.2f: %.5f", alphas[a], cosines[c], integral);
        }
}

Test(microfacet, lambda_and_masking_have_their_closed_forms) {
    vec3 normal = vec3_make(0.0, 0.0, 1.0);
    cr_expect_eq(microfacet_ggx_lambda(normal, 0.7), 0.0);
    cr_expect_eq(microfacet_ggx_g1(vec3_make(1.0, 0.0, 0.0), 0.3), 0.0, "the horizon is masked");
    /* alpha 1: Lambda = (1 / cos - 1) / 2, so G1 = 2 cos / (1 + cos) */
    for (double c = 0.1; c < 1.0; c += 0.2) {
        vec3 w = incident(c);
        cr_expect(fabs(microfacet_ggx_g1(w, 1.0) - 2.0 * c / (1.0 + c)) < 1e-12, "cos %.1f", c);
    }
    /* height-correlated G2: symmetric, at least the uncorrelated product, at most either G1 */
    vec3 wo = incident(0.3), wi = vec3_normalize(vec3_make(-0.5, 0.2, 0.6));
    double g2 = microfacet_ggx_g2(wo, wi, 0.4);
    cr_expect_eq(g2, microfacet_ggx_g2(wi, wo, 0.4));
    cr_expect(g2 >= microfacet_ggx_g1(wo, 0.4) * microfacet_ggx_g1(wi, 0.4));
    cr_expect(g2 <= fmin(microfacet_ggx_g1(wo, 0.4), microfacet_ggx_g1(wi, 0.4)));
}

/* The form Cycles 3.4 writes its lobes in, drawn only to compare with it: its masking the product G1 G1,
 * and its glass's Fresnel that of the surface's normal; the sampler's density the same as the chapter's. */
Test(microfacet, cycles_3_4s_form_differs_from_the_chapters_in_masking_and_glasss_fresnel_only) {
    const double alpha = 0.8, ior = 1.5;
    vec3 wo = incident(0.3), above = vec3_normalize(vec3_make(-0.5, 0.2, 0.6));
    vec3 below = vec3_normalize(vec3_make(-0.6, 0.05, -0.8));
    cr_expect_eq(microfacet_ggx_masking(MICROFACET_CYCLES_3_4, wo, above, alpha),
                 microfacet_ggx_g1(wo, alpha) * microfacet_ggx_g1(above, alpha));
    cr_expect_eq(microfacet_ggx_masking(MICROFACET_CHAPTER, wo, above, alpha), microfacet_ggx_g2(wo, above, alpha));
    /* the microfacet normals joining wo to `above` (a reflection) and to `below` (a refraction into ior) */
    vec3 h = vec3_normalize(vec3_add(wo, above)), m = vec3_normalize(vec3_add(wo, vec3_scale(below, ior)));
    m = vec3_scale(m, m.z < 0.0 ? -1.0 : 1.0);
    double f_normal = bsdf_fresnel(wo.z, 1.0 / ior);
    struct {
        struct microfacet_lobe lobe;
        vec3 wi;
        double fresnel_ratio; /* Cycles' Fresnel over the chapter's */
    } cases[] = {
        {microfacet_conductor_lobe(vec3_make(0.9, 0.6, 0.3), alpha), above, 1.0},
        {microfacet_dielectric_lobe(ior, vec3_make(1.0, 1.0, 1.0), alpha), above,
         f_normal / bsdf_fresnel(vec3_dot(wo, h), 1.0 / ior)},
        {microfacet_dielectric_lobe(ior, vec3_make(1.0, 1.0, 1.0), alpha), below,
         (1.0 - f_normal) / (1.0 - bsdf_fresnel(vec3_dot(wo, m), 1.0 / ior))},
    };
    for (int k = 0; k < 3; k++) {
        cr_expect_eq(cases[k].lobe.form, MICROFACET_CHAPTER, "every constructor's lobe is the chapter's");
        struct microfacet_lobe cycles = cases[k].lobe;
        cycles.form = MICROFACET_CYCLES_3_4;
        vec3 wi = cases[k].wi;
        double ratio = microfacet_ggx_masking(MICROFACET_CYCLES_3_4, wo, wi, alpha) /
                       microfacet_ggx_masking(MICROFACET_CHAPTER, wo, wi, alpha) * cases[k].fresnel_ratio;
        double chapter_f = microfacet_eval(&cases[k].lobe, wo, wi).x, cycles_f = microfacet_eval(&cycles, wo, wi).x;
        cr_expect(chapter_f > 0.0 && fabs(ratio - 1.0) > 0.01, "case %d: f %g, ratio %g", k, chapter_f, ratio);
        cr_expect(fabs(cycles_f - ratio * chapter_f) < 1e-12 * chapter_f, "case %d: %g against %g", k, cycles_f,
                  ratio * chapter_f);
        cr_expect_eq(microfacet_pdf(&cycles, wo, wi), microfacet_pdf(&cases[k].lobe, wo, wi));
    }
}

/* ---- Fresnel -------------------------------------------------------------------------------------- */

Test(microfacet, fresnel_of_a_complex_index_has_its_limits) {
    const struct microfacet_metal *gold = microfacet_metal_named("gold");
    cr_assert(gold);
    cr_expect_null(microfacet_metal_named("brass"));
    const char *const *names;
    cr_expect_eq(microfacet_metal_count(&names), 4);
    for (int i = 0; i < 4; i++)
        cr_expect(microfacet_metal_named(names[i]) != NULL, "%s", names[i]);
    /* normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) */
    vec3 f0 = microfacet_fresnel_conductor(1.0, gold->eta, gold->k);
    double n = gold->eta.x, k = gold->k.x;
    cr_expect(fabs(f0.x - ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k)) < 1e-12);
    cr_expect(f0.x > f0.z + 0.3, "gold reflects red (%.3f) far more than blue (%.3f)", f0.x, f0.z);
    cr_expect(fabs(microfacet_fresnel_conductor(0.0, gold->eta, gold->k).y - 1.0) < 1e-12, "grazing: 1");
    /* k = 0 is a dielectric: chapter 15's Fresnel from air into index 1.5 */
    for (double c = 0.05; c < 1.0; c += 0.15) {
        double mine = microfacet_fresnel_conductor(c, vec3_make(1.5, 1.5, 1.5), vec3_make(0, 0, 0)).x;
        cr_expect(fabs(mine - bsdf_fresnel(c, 1.0 / 1.5)) < 1e-12, "cos %.2f: %.6f against %.6f", c, mine,
                  bsdf_fresnel(c, 1.0 / 1.5));
    }
    vec3 s = microfacet_fresnel_schlick(vec3_make(0.9, 0.5, 0.1), 1.0);
    cr_expect(s.x == 0.9 && s.y == 0.5 && s.z == 0.1);
    cr_expect_eq(microfacet_fresnel_schlick(vec3_make(0.9, 0.5, 0.1), 0.0).z, 1.0);
}

/* ---- reciprocity and energy ------------------------------------------------------------------------- */

static vec3 random_direction(struct sample_stream *rng) {
    return sampling_sphere_direction(sample_stream_next(rng), sample_stream_next(rng));
}

Test(microfacet, every_lobe_is_reciprocal_and_refraction_obeys_the_rule_of_the_indices) {
    struct sample_stream rng = sample_stream_start(3, 5, 7, 11);
    int refractions = 0;
    for (int k = 0; k < 20000; k++) {
        vec3 wo = random_direction(&rng), wi = random_direction(&rng);
        int kind = k % 3;
        struct microfacet_lobe l = lobe(kind, 0.05 + 0.95 * sample_stream_next(&rng));
        double there = microfacet_eval(&l, wo, wi).x, back = microfacet_eval(&l, wi, wo).x;
        if (kind == DIELECTRIC && wo.z * wi.z < 0.0) {
            /* f(wo, wi) / eta(wi)^2 = f(wi, wo) / eta(wo)^2 */
            double eta_wo = wo.z > 0.0 ? 1.0 : 1.5, eta_wi = wi.z > 0.0 ? 1.0 : 1.5;
            there /= eta_wi * eta_wi;
            back /= eta_wo * eta_wo;
            refractions += there > 0.0;
        }
        cr_assert(fabs(there - back) <= 1e-9 * fmax(1.0, fabs(there)), "%s: f(wo, wi) %.12g, f(wi, wo) %.12g",
                  KIND_NAMES[kind], there, back);
        cr_assert(there >= 0.0 && isfinite(there));
    }
    cr_expect(refractions > 500, "only %d refractions checked", refractions);
}

#define ALBEDO_STEPS 256
/* The midpoint rule's error on the albedo at ALBEDO_STEPS (largest for Phong's lobe, whose integrand
 * has an infinite slope at the lobe's rim: 7e-5 at alpha 0.5). */
#define ALBEDO_QUADRATURE_ERROR 2e-4

Test(microfacet, no_lobe_scatters_more_light_than_arrives) {
    static const double alphas[] = {0.05, 0.2, 0.5, 1.0}, cosines[] = {0.02, 0.2, 0.5, 0.8, 1.0};
    for (int kind = PHONG; kind <= DIELECTRIC; kind++)
        for (int a = 0; a < 4; a++)
            for (int c = 0; c < 5; c++)
                for (int side = 1; side >= (kind == DIELECTRIC ? -1 : 1); side -= 2) {
                    struct microfacet_lobe l = lobe(kind, alphas[a]);
                    double e = microfacet_albedo(&l, incident(side * cosines[c]), ALBEDO_STEPS).x;
                    cr_expect(e <= 1.0 + ALBEDO_QUADRATURE_ERROR && e > 0.0, "%s alpha %.2f cos %+.2f: albedo %.6f", KIND_NAMES[kind],
                              alphas[a], side * cosines[c], e);
                }
}

Test(microfacet, the_phong_lobe_reflects_its_reflectance_at_normal_incidence) {
    struct microfacet_lobe l = microfacet_phong_lobe(vec3_make(0.8, 0.5, 0.2), 0.3);
    vec3 e = microfacet_albedo(&l, vec3_make(0, 0, 1), ALBEDO_STEPS);
    cr_expect(fabs(e.x - 0.8) < 1e-4 && fabs(e.y - 0.5) < 1e-4 && fabs(e.z - 0.2) < 1e-4, "%.5f %.5f %.5f", e.x, e.y, e.z);
}

/* Returns the mean of the sampler's weights from wo, and their standard error through *error. */
static double mean_weight(const struct microfacet_lobe *l, vec3 wo, int draws, uint32_t seed, double *error) {
    struct sample_stream rng = sample_stream_start(seed, 0, 1, 2);
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < draws; k++) {
        struct microfacet_sample s;
        double u1 = sample_stream_next(&rng), u2 = sample_stream_next(&rng), u3 = sample_stream_next(&rng);
        if (microfacet_sample(l, wo, u1, u2, u3, &s)) {
            sum += s.weight.x;
            sum2 += s.weight.x * s.weight.x;
        }
    }
    double mean = sum / draws;
    *error = sqrt(fmax(0.0, sum2 / draws - mean * mean) / draws);
    return mean;
}

Test(microfacet, a_white_furnace_conductor_loses_what_the_numerical_integral_says) {
    /* Reflectance 1: every loss is light the single-scattering model lets fall between the microfacets.
     * At alpha 1 and normal incidence D is 1 / pi and the loss has a closed form: the albedo is 1 - ln 2. */
    struct microfacet_lobe rough = lobe(CONDUCTOR, 1.0);
    double closed = microfacet_albedo(&rough, vec3_make(0, 0, 1), ALBEDO_STEPS).x;
    cr_expect(fabs(closed - (1.0 - log(2.0))) < 1e-5, "alpha 1, normal incidence: %.6f, 1 - ln 2 = %.6f", closed,
              1.0 - log(2.0));
    static const double alphas[] = {0.1, 0.5, 1.0}, cosines[] = {0.2, 0.6, 1.0};
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) {
            struct microfacet_lobe l = lobe(CONDUCTOR, alphas[a]);
            vec3 wo = incident(cosines[c]);
            double error, sampled = mean_weight(&l, wo, 100000, (uint32_t)(3 * a + c), &error);
            double integral = microfacet_albedo(&l, wo, ALBEDO_STEPS).x;
            cr_log_info("alpha %.1f cos %.1f: loss %.4f by the integral, %.4f +- %.4f by the sampler", alphas[a],
                        cosines[c], 1.0 - integral, 1.0 - sampled, error);
            cr_expect(fabs(sampled - integral) < 4.0 * error + 1e-4, "alpha %.1f cos %.1f: sampled %.5f +- %.5f, integral %.5f",
                      alphas[a], cosines[c], sampled, error, integral);
        }
}

/* ---- the smooth limit ------------------------------------------------------------------------------- */

#define SMOOTH_ALPHA 1e-3
#define SMOOTH_ANGLE 0.05 /* radians from the mirror (or Snell's) direction ... */
#define SMOOTH_SHARE 0.99 /* ... within which this share of the draws lands: GGX's tails are long */

Test(microfacet, a_nearly_smooth_conductor_is_chapter_15s_mirror) {
    vec3 f0 = vec3_make(0.9, 0.6, 0.3), wo = incident(0.4), mirror = vec3_make(-wo.x, -wo.y, wo.z);
    struct microfacet_lobe l = microfacet_conductor_lobe(f0, SMOOTH_ALPHA);
    struct sample_stream rng = sample_stream_start(1, 1, 1, 1);
    vec3 fresnel = microfacet_fresnel_schlick(f0, wo.z), sum = vec3_make(0, 0, 0);
    int draws = 2000, near = 0;
    for (int k = 0; k < draws; k++) {
        struct microfacet_sample s;
        cr_assert(microfacet_sample(&l, wo, sample_stream_next(&rng), sample_stream_next(&rng), 0.5, &s));
        near += acos(fmin(1.0, vec3_dot(s.wi, mirror))) < SMOOTH_ANGLE;
        sum = vec3_add(sum, s.weight);
    }
    cr_expect(near >= SMOOTH_SHARE * draws, "only %d of %d draws near the mirror direction", near, draws);
    cr_expect(fabs(sum.x / draws - fresnel.x) < 1e-3 && fabs(sum.z / draws - fresnel.z) < 1e-3, "%.5f %.5f against %.5f %.5f",
              sum.x / draws, sum.z / draws, fresnel.x, fresnel.z);
    vec3 e = microfacet_albedo(&l, wo, ALBEDO_STEPS);
    cr_expect(fabs(e.y - fresnel.y) < 1e-3, "albedo %.5f, Fresnel %.5f", e.y, fresnel.y);
}

Test(microfacet, a_nearly_smooth_dielectric_is_chapter_15s_glass) {
    for (int side = 1; side >= -1; side -= 2) {
        vec3 wo = incident(side * 0.8);
        double near = side > 0 ? 1.0 : 1.5, far = side > 0 ? 1.5 : 1.0, eta = near / far;
        struct microfacet_lobe l = microfacet_dielectric_lobe(1.5, vec3_make(1, 1, 1), SMOOTH_ALPHA);
        /* Snell's direction: the tangential part scaled by eta, on the far side */
        vec3 along = vec3_scale(vec3_make(-wo.x, -wo.y, 0.0), eta);
        vec3 snell = vec3_make(along.x, along.y, -side * sqrt(1.0 - vec3_dot(along, along)));
        vec3 mirror = vec3_make(-wo.x, -wo.y, wo.z);
        struct sample_stream rng = sample_stream_start(2, 2, 2, 2);
        int draws = 4000, reflected = 0, close = 0;
        double weight = 0.0;
        for (int k = 0; k < draws; k++) {
            struct microfacet_sample s;
            double u1 = sample_stream_next(&rng), u2 = sample_stream_next(&rng), u3 = sample_stream_next(&rng);
            cr_assert(microfacet_sample(&l, wo, u1, u2, u3, &s));
            close += acos(fmin(1.0, vec3_dot(s.wi, s.transmitted ? snell : mirror))) < SMOOTH_ANGLE;
            reflected += !s.transmitted;
            weight += s.weight.x;
        }
        cr_expect(close >= SMOOTH_SHARE * draws, "side %d: only %d of %d draws near Snell's or the mirror direction",
                  side, close, draws);
        double fresnel = bsdf_fresnel(fabs(wo.z), eta), share = (double)reflected / draws;
        cr_expect(fabs(share - fresnel) < 4.0 * sqrt(fresnel * (1 - fresnel) / draws), "side %d: reflected %.4f, Fresnel %.4f",
                  side, share, fresnel);
        cr_expect(fabs(weight / draws - 1.0) < 2e-3, "side %d: mean weight %.5f", side, weight / draws);
    }
}

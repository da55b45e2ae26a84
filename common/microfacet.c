/* microfacet.c: the GGX microfacet distribution, Smith's masking, the sampling of the visible normals
 * and the Phong, conductor and dielectric lobes built on them (chapter 17, docs/17-rough.md). */
#include "microfacet.h"

#include <complex.h>
#include <math.h>
#include <string.h>

#include "bsdf.h"
#include "sampling.h"

#define PI 3.14159265358979323846

/* A microfacet normal closer to the horizon than this (its z) is treated as lying in it when the
 * visible-normal sampler unstretches it, so that the normal never points below the surface. */
#define MICROFACET_NORMAL_Z_MIN 1e-9

double microfacet_alpha(double roughness) {
    double r = fmin(fmax(roughness, 0.0), 1.0);
    return r * r;
}

static double usable_alpha(double alpha) { return fmax(alpha, MICROFACET_ALPHA_MIN); }

/* ---- the GGX distribution and Smith's masking ------------------------------------------------------ */

/* TASK 17.1: the GGX distribution of microfacet normals */
double microfacet_ggx_d(vec3 m, double alpha) {
    if (m.z <= 0.0)
        return 0.0;
    double a2 = alpha * alpha;
    /* alpha^2 cos^2 + sin^2 for a unit m, the sine from x and y so that it keeps its digits near the pole */
    double denominator = a2 * m.z * m.z + (m.x * m.x + m.y * m.y);
    return a2 / (PI * denominator * denominator);
}

double microfacet_ggx_lambda(vec3 w, double alpha) {
    if (w.z == 0.0)
        return INFINITY;
    double a2_tan2 = alpha * alpha * (w.x * w.x + w.y * w.y) / (w.z * w.z);
    /* (sqrt(1 + x) - 1) / 2 written so that it keeps its digits for small x */
    return a2_tan2 / (2.0 * (sqrt(1.0 + a2_tan2) + 1.0));
}

double microfacet_ggx_g1(vec3 w, double alpha) { return 1.0 / (1.0 + microfacet_ggx_lambda(w, alpha)); }

double microfacet_ggx_g2(vec3 wo, vec3 wi, double alpha) {
    /* the two Lambdas added first, so that swapping wo and wi gives the same number to the last bit */
    return 1.0 / (1.0 + (microfacet_ggx_lambda(wo, alpha) + microfacet_ggx_lambda(wi, alpha)));
}

double microfacet_ggx_masking(enum microfacet_form form, vec3 wo, vec3 wi, double alpha) {
    if (form == MICROFACET_CYCLES_3_4)
        return microfacet_ggx_g1(wo, alpha) * microfacet_ggx_g1(wi, alpha);
    return microfacet_ggx_g2(wo, wi, alpha);
}

vec3 microfacet_ggx_sample_visible(vec3 wo, double alpha, double u1, double u2) {
    /* Stretch the view so that the distribution becomes the hemisphere of alpha 1 ... */
    vec3 v = vec3_normalize(vec3_make(alpha * wo.x, alpha * wo.y, wo.z));
    /* ... where the visible normals are those of a hemisphere seen from v: a uniform point of the disc
     * across v, pushed onto the part of the disc the hemisphere's silhouette shows ... */
    double across2 = v.x * v.x + v.y * v.y;
    vec3 t1 = across2 > 0.0 ? vec3_scale(vec3_make(-v.y, v.x, 0.0), 1.0 / sqrt(across2)) : vec3_make(1.0, 0.0, 0.0);
    vec3 t2 = vec3_cross(v, t1);
    double r = sqrt(u1), phi = 2.0 * PI * u2;
    double p1 = r * cos(phi), p2 = r * sin(phi);
    double s = 0.5 * (1.0 + v.z);
    p2 = (1.0 - s) * sqrt(fmax(0.0, 1.0 - p1 * p1)) + s * p2;
    /* ... lifted onto the hemisphere, and unstretched. */
    double lift = sqrt(fmax(0.0, 1.0 - p1 * p1 - p2 * p2));
    vec3 n = vec3_add(vec3_add(vec3_scale(t1, p1), vec3_scale(t2, p2)), vec3_scale(v, lift));
    return vec3_normalize(vec3_make(alpha * n.x, alpha * n.y, fmax(MICROFACET_NORMAL_Z_MIN, n.z)));
}

double microfacet_ggx_visible_pdf(vec3 wo, vec3 m, double alpha) {
    double facing = vec3_dot(wo, m);
    if (wo.z <= 0.0 || facing <= 0.0)
        return 0.0;
    return microfacet_ggx_g1(wo, alpha) * facing * microfacet_ggx_d(m, alpha) / wo.z;
}

/* ---- Fresnel -------------------------------------------------------------------------------------- */

vec3 microfacet_fresnel_schlick(vec3 f0, double cos_i) {
    double c = 1.0 - fmin(fmax(cos_i, 0.0), 1.0);
    double c5 = c * c * c * c * c;
    return vec3_add(f0, vec3_scale(vec3_sub(vec3_make(1.0, 1.0, 1.0), f0), c5));
}

/* Fresnel's equations with a complex index eta + i k for light from air at cos_i: the amplitudes of
 * the two polarisations, their squared moduli averaged. */
static double fresnel_complex(double cos_i, double eta, double k) {
    double complex n = eta + k * I;
    double sin2_i = 1.0 - cos_i * cos_i;
    double complex cos_t = csqrt(1.0 - sin2_i / (n * n));
    double complex across = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    double complex along = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    double a = cabs(across), b = cabs(along);
    return 0.5 * (a * a + b * b);
}

vec3 microfacet_fresnel_conductor(double cos_i, vec3 eta, vec3 k) {
    double c = fmin(fmax(cos_i, 0.0), 1.0);
    return vec3_make(fresnel_complex(c, eta.x, k.x), fresnel_complex(c, eta.y, k.y),
                     fresnel_complex(c, eta.z, k.z));
}

/* Complex indices n + i k at 650 nm (red), 550 nm (green) and 450 nm (blue), linearly interpolated from
 * the measured optical constants that pbrt-v4 tabulates for these metals (src/pbrt/util/spectrum.cpp:
 * Au_eta, Au_k, Ag_eta, Ag_k, Cu_eta, Cu_k, Al_eta, Al_k, after Palik's Handbook of Optical Constants
 * of Solids). */
static const struct microfacet_metal METALS[] = {
    {"gold", {0.1678, 0.3504, 1.5085}, {3.1378, 2.7141, 1.8788}},
    {"silver", {0.1394, 0.1248, 0.1517}, {4.1288, 3.3396, 2.4704}},
    {"copper", {0.2166, 0.9582, 1.1658}, {3.6377, 2.5771, 2.3939}},
    {"aluminium", {1.4748, 0.9586, 0.6180}, {7.7941, 6.6870, 5.4694}},
};
#define METAL_COUNT ((int)(sizeof METALS / sizeof METALS[0]))
static const char *const METAL_NAMES[METAL_COUNT] = {"gold", "silver", "copper", "aluminium"};

const struct microfacet_metal *microfacet_metal_named(const char *name) {
    for (int i = 0; i < METAL_COUNT; i++)
        if (strcmp(METALS[i].name, name) == 0)
            return &METALS[i];
    return NULL;
}

int microfacet_metal_count(const char *const **names) {
    if (names)
        *names = METAL_NAMES;
    return METAL_COUNT;
}

/* ---- the lobes ------------------------------------------------------------------------------------ */

struct microfacet_lobe microfacet_phong_lobe(vec3 reflectance, double alpha) {
    return (struct microfacet_lobe){.kind = MICROFACET_PHONG, .alpha = alpha, .reflectance = reflectance};
}

double microfacet_phong_exponent(double alpha) {
    double a = usable_alpha(alpha);
    return fmin(fmax(2.0 / (a * a) - 2.0, 0.0), MICROFACET_PHONG_EXPONENT_MAX);
}

struct microfacet_lobe microfacet_conductor_lobe(vec3 f0, double alpha) {
    return (struct microfacet_lobe){.kind = MICROFACET_CONDUCTOR, .alpha = alpha, .reflectance = f0};
}

struct microfacet_lobe microfacet_metal_lobe(const struct microfacet_metal *m, double alpha) {
    return (struct microfacet_lobe){
        .kind = MICROFACET_CONDUCTOR, .alpha = alpha, .exact_fresnel = true, .eta = m->eta, .k = m->k};
}

struct microfacet_lobe microfacet_dielectric_lobe(double ior, vec3 tint, double alpha) {
    return (struct microfacet_lobe){.kind = MICROFACET_DIELECTRIC, .alpha = alpha, .ior = ior, .tint = tint};
}

/* Returns w mirrored about the unit normal m. */
static vec3 reflect(vec3 w, vec3 m) { return vec3_sub(vec3_scale(m, 2.0 * vec3_dot(w, m)), w); }

/* The mirror direction of wo about the macro normal z. */
static vec3 mirror_of(vec3 wo) { return vec3_make(-wo.x, -wo.y, wo.z); }

/* Returns the conductor's Fresnel reflectance at cos_i to its microfacet. */
static vec3 conductor_fresnel(const struct microfacet_lobe *l, double cos_i) {
    return l->exact_fresnel ? microfacet_fresnel_conductor(cos_i, l->eta, l->k)
                            : microfacet_fresnel_schlick(l->reflectance, cos_i);
}

/* The indices on the two sides of a dielectric for a path arriving from wo: its own side's and the
 * other's. */
struct sides {
    double near, far;
};

static struct sides sides_of(const struct microfacet_lobe *l, vec3 wo) {
    return wo.z > 0.0 ? (struct sides){1.0, l->ior} : (struct sides){l->ior, 1.0};
}

/* Returns the microfacet normal (on the outside, z >= 0) that refracts between wo and wi, which lie on
 * opposite sides (the generalised half vector of Walter et al. 2007), or false when there is none:
 * when one of them would have to meet the facet from behind. */
static bool refraction_half_vector(vec3 wo, vec3 wi, struct sides s, vec3 *m) {
    vec3 h = vec3_add(vec3_scale(wo, s.near), vec3_scale(wi, s.far));
    double length = vec3_length(h);
    if (!(length > 0.0))
        return false;
    h = vec3_scale(h, (h.z < 0.0 ? -1.0 : 1.0) / length);
    if (vec3_dot(wo, h) * wo.z <= 0.0 || vec3_dot(wi, h) * wi.z <= 0.0)
        return false;
    *m = h;
    return true;
}

/* d(m) / d(wi) for refraction: the solid angle of half vectors per solid angle of directions wi. */
static double refraction_jacobian(vec3 wo, vec3 wi, vec3 m, struct sides s) {
    double sum = s.near * vec3_dot(wo, m) + s.far * vec3_dot(wi, m);
    return s.far * s.far * fabs(vec3_dot(wi, m)) / (sum * sum);
}

/* Returns the dielectric's Fresnel reflectance for a path from wo meeting the facet m (wo . m of the
 * same sign as wo.z). */
static double dielectric_fresnel(vec3 wo, vec3 m, struct sides s) {
    return bsdf_fresnel(fabs(vec3_dot(wo, m)), s.near / s.far);
}

static vec3 phong_eval(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    double c = vec3_dot(wi, mirror_of(wo));
    if (wo.z <= 0.0 || wi.z <= 0.0 || c <= 0.0)
        return vec3_make(0.0, 0.0, 0.0);
    double n = microfacet_phong_exponent(l->alpha);
    return vec3_scale(l->reflectance, (n + 2.0) / (2.0 * PI) * pow(c, n));
}

static double phong_pdf(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    double c = vec3_dot(wi, mirror_of(wo));
    if (wo.z <= 0.0 || wi.z <= 0.0 || c <= 0.0)
        return 0.0;
    double n = microfacet_phong_exponent(l->alpha);
    return (n + 1.0) / (2.0 * PI) * pow(c, n);
}

/* Returns the direction at cosine u1^(1 / (n + 1)) from the mirror direction, turned by 2 pi u2 about
 * it: the inverse of the Phong lobe's distribution, whose density is (n + 1) / (2 pi) cos^n. */
static vec3 phong_direction(vec3 wo, double n, double u1, double u2) {
    vec3 r = mirror_of(wo), t, b;
    sampling_basis(r, &t, &b);
    double cos_a = pow(u1, 1.0 / (n + 1.0)), sin_a = sqrt(fmax(0.0, 1.0 - cos_a * cos_a));
    double phi = 2.0 * PI * u2;
    return vec3_add(vec3_scale(r, cos_a), vec3_add(vec3_scale(t, sin_a * cos(phi)), vec3_scale(b, sin_a * sin(phi))));
}

/* Returns the rough conductor's f(wo, wi) (microfacet_eval's contract): Fresnel at the half vector h of
 * wo and wi (conductor_fresnel at wo . h) times D(h) times the masking-shadowing G2(wo, wi), over
 * 4 wo.z wi.z; 0 when wo or wi is below the surface. */
/* TASK 17.2: the rough metal's BRDF: Fresnel, distribution and masking over the two cosines */
static vec3 conductor_eval(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    vec3 zero = vec3_make(0.0, 0.0, 0.0);
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return zero;
    vec3 h = vec3_add(wo, wi);
    if (!(vec3_length(h) > 0.0))
        return zero;
    h = vec3_normalize(h);
    double alpha = usable_alpha(l->alpha);
    double shape = microfacet_ggx_d(h, alpha) * microfacet_ggx_masking(l->form, wo, wi, alpha) / (4.0 * wo.z * wi.z);
    return vec3_scale(conductor_fresnel(l, vec3_dot(wo, h)), shape);
}

/* Returns the density per unit solid angle of wi that microfacet_sample gives the rough conductor from wo
 * (microfacet_pdf's contract): it draws a visible normal h (microfacet_ggx_visible_pdf) and reflects wo
 * about it, so the density is that of h = the half vector of wo and wi, carried from normals to
 * directions; 0 when wo or wi is below the surface. */
/* TASK 17.3: the density of a reflected direction: the visible normals' through the half vector's Jacobian */
static double conductor_pdf(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    vec3 h = vec3_add(wo, wi);
    if (!(vec3_length(h) > 0.0))
        return 0.0;
    h = vec3_normalize(h);
    /* the visible normals' density, carried from half vectors to directions: d(h) / d(wi) = 1 / (4 wo.h) */
    return microfacet_ggx_visible_pdf(wo, h, usable_alpha(l->alpha)) / (4.0 * vec3_dot(wo, h));
}

/* A dielectric's pair of directions, seen in the frame where wo is outside (wo.z > 0): both turned over
 * when the path comes from inside, which changes no dot product and no |z|; with the microfacet normal
 * that joins them (the half vector for a reflection, the generalised one for a refraction). */
struct dielectric_pair {
    vec3 wo, wi, m;
    struct sides s;
    bool reflected;
};

/* Fills *p for wo and wi, or returns false when no microfacet joins them. */
static bool dielectric_pair_of(const struct microfacet_lobe *l, vec3 wo, vec3 wi, struct dielectric_pair *p) {
    if (wo.z == 0.0 || wi.z == 0.0)
        return false;
    p->s = sides_of(l, wo);
    p->wo = wo.z < 0.0 ? vec3_neg(wo) : wo;
    p->wi = wo.z < 0.0 ? vec3_neg(wi) : wi;
    p->reflected = p->wi.z > 0.0;
    if (!p->reflected)
        return refraction_half_vector(p->wo, p->wi, p->s, &p->m);
    vec3 h = vec3_add(p->wo, p->wi);
    if (!(vec3_length(h) > 0.0))
        return false;
    p->m = vec3_normalize(h);
    return true;
}

/* Returns the rough dielectric's f(wo, wi) (microfacet_eval's contract): Fresnel times D G2 over
 * 4 |wo.z wi.z| for a reflection, and for a refraction (1 - Fresnel) D G2 through the generalised half
 * vector's Jacobian, tinted (Walter et al. 2007, eq. 21). */
/* TASK 17.2 ALSO: the rough glass's BSDF, whose reflection is the rough metal's */
static vec3 dielectric_eval(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    struct dielectric_pair p;
    if (!dielectric_pair_of(l, wo, wi, &p))
        return vec3_make(0.0, 0.0, 0.0);
    double alpha = usable_alpha(l->alpha);
    double shape = microfacet_ggx_d(p.m, alpha) * microfacet_ggx_masking(l->form, p.wo, p.wi, alpha);
    /* Cycles 3.4's glass weighs its reflection and refraction by the Fresnel of the surface's normal */
    vec3 fresnel_normal = l->form == MICROFACET_CYCLES_3_4 ? vec3_make(0.0, 0.0, 1.0) : p.m;
    double fresnel = dielectric_fresnel(p.wo, fresnel_normal, p.s);
    if (p.reflected) {
        double f = fresnel * shape / (4.0 * p.wo.z * p.wi.z);
        return vec3_make(f, f, f);
    }
    double f = (1.0 - fresnel) * shape * refraction_jacobian(p.wo, p.wi, p.m, p.s) * vec3_dot(p.wo, p.m) /
               fabs(p.wo.z * p.wi.z);
    return vec3_scale(l->tint, f);
}

/* Returns the density of wi that microfacet_sample gives the rough dielectric from wo (microfacet_pdf's
 * contract): the visible normal's density carried to directions, times Fresnel for a reflection or
 * 1 - Fresnel for a refraction (the share with which the third number chooses each). */
/* TASK 17.3 ALSO: the rough glass's density, whose reflection carries the same Jacobian */
static double dielectric_pdf(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    struct dielectric_pair p;
    if (!dielectric_pair_of(l, wo, wi, &p))
        return 0.0;
    double visible = microfacet_ggx_visible_pdf(p.wo, p.m, usable_alpha(l->alpha));
    double fresnel = dielectric_fresnel(p.wo, p.m, p.s);
    if (p.reflected)
        return visible / (4.0 * vec3_dot(p.wo, p.m)) * fresnel;
    return visible * refraction_jacobian(p.wo, p.wi, p.m, p.s) * (1.0 - fresnel);
}

/* Returns wo refracted through the facet m (wo . m > 0) from index s.near into s.far, or false under
 * total internal reflection. */
static bool refract_through(vec3 wo, vec3 m, struct sides s, vec3 *wi) {
    double eta = s.near / s.far, c = vec3_dot(wo, m);
    double sin2_t = eta * eta * (1.0 - c * c);
    if (sin2_t >= 1.0)
        return false;
    *wi = vec3_normalize(vec3_add(vec3_scale(wo, -eta), vec3_scale(m, eta * c - sqrt(1.0 - sin2_t))));
    return true;
}

/* Draws the dielectric's direction in the frame where wo.z > 0 (the caller turns it back). */
static bool dielectric_direction(const struct microfacet_lobe *l, vec3 wo, struct sides s, double u1, double u2,
                                 double u3, vec3 *wi) {
    vec3 m = microfacet_ggx_sample_visible(wo, usable_alpha(l->alpha), u1, u2);
    if (u3 < dielectric_fresnel(wo, m, s) || !refract_through(wo, m, s, wi)) {
        *wi = reflect(wo, m);
        return wi->z > 0.0;
    }
    return wi->z < 0.0;
}

vec3 microfacet_eval(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    switch (l->kind) {
    case MICROFACET_PHONG:
        return phong_eval(l, wo, wi);
    case MICROFACET_CONDUCTOR:
        return conductor_eval(l, wo, wi);
    case MICROFACET_DIELECTRIC:
        return dielectric_eval(l, wo, wi);
    }
    return vec3_make(0.0, 0.0, 0.0);
}

double microfacet_pdf(const struct microfacet_lobe *l, vec3 wo, vec3 wi) {
    switch (l->kind) {
    case MICROFACET_PHONG:
        return phong_pdf(l, wo, wi);
    case MICROFACET_CONDUCTOR:
        return conductor_pdf(l, wo, wi);
    case MICROFACET_DIELECTRIC:
        return dielectric_pdf(l, wo, wi);
    }
    return 0.0;
}

bool microfacet_sample(const struct microfacet_lobe *l, vec3 wo, double u1, double u2, double u3,
                       struct microfacet_sample *s) {
    vec3 wi;
    switch (l->kind) {
    case MICROFACET_PHONG:
        if (wo.z <= 0.0)
            return false;
        wi = phong_direction(wo, microfacet_phong_exponent(l->alpha), u1, u2);
        break;
    case MICROFACET_CONDUCTOR:
        if (wo.z <= 0.0)
            return false;
        wi = reflect(wo, microfacet_ggx_sample_visible(wo, usable_alpha(l->alpha), u1, u2));
        break;
    case MICROFACET_DIELECTRIC: {
        if (wo.z == 0.0)
            return false;
        double side = wo.z > 0.0 ? 1.0 : -1.0;
        if (!dielectric_direction(l, vec3_scale(wo, side), sides_of(l, wo), u1, u2, u3, &wi))
            return false;
        wi = vec3_scale(wi, side);
        break;
    }
    default:
        return false;
    }
    double pdf = microfacet_pdf(l, wo, wi);
    if (!(pdf > 0.0) || !isfinite(pdf))
        return false;
    s->wi = wi;
    s->pdf = pdf;
    s->weight = vec3_scale(microfacet_eval(l, wo, wi), fabs(wi.z) / pdf);
    s->transmitted = wi.z * wo.z < 0.0;
    return true;
}

/* ---- directional albedo by quadrature --------------------------------------------------------------- */

/* The albedo of a GGX lobe, integrated over the microfacet normals m rather than the directions wi: each
 * m sends wo to one reflected direction (and, for a dielectric, one refracted one), so the integral of
 * f |wi.z| over wi is the integral over m of f |wi.z| d(wi)/d(m). The normals are spread by GGX's own
 * distribution of D(m) m.z, whose inverse is exact: tan^2(theta_m) = alpha^2 u / (1 - u), with
 * 1 - u = (1 - t)^2 so that the integrand stays smooth where the normals graze; a midpoint rule in
 * (t, phi). */
static vec3 ggx_albedo(const struct microfacet_lobe *l, vec3 wo, int steps) {
    double alpha = usable_alpha(l->alpha), side = wo.z > 0.0 ? 1.0 : -1.0;
    struct sides s = sides_of(l, wo);
    vec3 up = vec3_scale(wo, side), sum = vec3_make(0.0, 0.0, 0.0);
    for (int i = 0; i < steps; i++) {
        double t = (i + 0.5) / steps, rest = (1.0 - t) * (1.0 - t), u = 1.0 - rest;
        double tan2 = alpha * alpha * u / rest, cos_m = 1.0 / sqrt(1.0 + tan2), sin_m = sqrt(tan2) * cos_m;
        double du_dt = 2.0 * (1.0 - t);
        for (int j = 0; j < steps; j++) {
            double phi = 2.0 * PI * (j + 0.5) / steps;
            vec3 m = vec3_make(sin_m * cos(phi), sin_m * sin(phi), cos_m);
            double c = vec3_dot(up, m);
            if (c <= 0.0)
                continue;
            double per_normal = du_dt / (microfacet_ggx_d(m, alpha) * cos_m); /* d(m) per d(t) d(phi) / 2 pi */
            vec3 wi = reflect(up, m);
            if (wi.z > 0.0) {
                vec3 f = microfacet_eval(l, wo, vec3_scale(wi, side));
                sum = vec3_add_scaled(sum, f, wi.z * 4.0 * c * per_normal);
            }
            if (l->kind == MICROFACET_DIELECTRIC && refract_through(up, m, s, &wi) && wi.z < 0.0) {
                vec3 f = microfacet_eval(l, wo, vec3_scale(wi, side));
                sum = vec3_add_scaled(sum, f, -wi.z / refraction_jacobian(up, wi, m, s) * per_normal);
            }
        }
    }
    return vec3_scale(sum, 1.0 / ((double)steps * steps));
}

/* The albedo of the Phong lobe, over its own lobe: directions at cosine t^(1 / (n + 1)) from the mirror
 * direction cover it with density (n + 1) / (2 pi) cos^n, by which f |wi.z| is divided. */
static vec3 phong_albedo(const struct microfacet_lobe *l, vec3 wo, int steps) {
    double n = microfacet_phong_exponent(l->alpha);
    vec3 sum = vec3_make(0.0, 0.0, 0.0);
    for (int i = 0; i < steps; i++)
        for (int j = 0; j < steps; j++) {
            vec3 wi = phong_direction(wo, n, (i + 0.5) / steps, (j + 0.5) / steps);
            double density = (n + 1.0) / (2.0 * PI) * pow(vec3_dot(wi, mirror_of(wo)), n);
            if (wi.z > 0.0 && density > 0.0)
                sum = vec3_add_scaled(sum, microfacet_eval(l, wo, wi), wi.z / density);
        }
    return vec3_scale(sum, 1.0 / ((double)steps * steps));
}

vec3 microfacet_albedo(const struct microfacet_lobe *l, vec3 wo, int steps) {
    if (l->kind == MICROFACET_PHONG)
        return wo.z > 0.0 ? phong_albedo(l, wo, steps) : vec3_make(0.0, 0.0, 0.0);
    if (wo.z == 0.0 || (l->kind == MICROFACET_CONDUCTOR && wo.z < 0.0))
        return vec3_make(0.0, 0.0, 0.0);
    return ggx_albedo(l, wo, steps);
}

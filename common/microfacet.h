/* microfacet.h: rough surfaces as fields of tiny mirrors (chapter 17, docs/17-rough.md): the GGX
 * (Trowbridge-Reitz) distribution of microfacet normals, Smith's masking and shadowing, the sampling of
 * the visible normals (Heitz 2018), and three lobes built on them -- the normalised Phong lobe, the
 * rough conductor and the rough dielectric (Walter, Marschner, Li and Torrance 2007).
 *
 * Everything here is pure mathematics in the surface's local frame: z is the (shading) normal, x and y
 * any two tangents, and every direction is a unit vector pointing AWAY from the surface: wo towards where
 * the path came from (the eye), wi towards where the light comes from. A direction with z > 0 is on the
 * outside of the surface, z < 0 the inside (only a dielectric lets light there).
 *
 * Roughness, as a scene states it (0 smooth .. 1 very rough), becomes the distribution's width alpha in
 * one place, microfacet_alpha: alpha = roughness^2. Every other function takes alpha. */
#ifndef WHITTED_MICROFACET_H
#define WHITTED_MICROFACET_H

#include <stdbool.h>

#include "vec3.h"

/* Below this alpha a lobe is a mirror for every purpose a picture has: the caller should use chapter
 * 15's smooth mirror or glass (a delta lobe) instead. The lobe functions clamp alpha up to it, so that
 * they never divide by zero. */
#define MICROFACET_ALPHA_MIN 1e-4

/* Returns alpha = roughness^2, the width of the GGX distribution for a scene's roughness in [0, 1]
 * (Burley's remapping, as Blender's Principled BSDF and Glossy BSDF use): the ONE place roughness is
 * squared. Values outside [0, 1] are clamped into it. */
double microfacet_alpha(double roughness);

/* ---- the GGX distribution and Smith's masking ------------------------------------------------------ */

/* Returns D(m), the GGX density of microfacet normals per unit solid angle of m (projected onto the
 * normal it integrates to one: the integral of D(m) m.z over the hemisphere is 1). 0 for m.z <= 0. */
double microfacet_ggx_d(vec3 m, double alpha);

/* Returns Smith's Lambda(w) for GGX: the shadowed share of the microsurface seen from w, as a ratio to
 * the lit share. 0 at normal incidence, growing without bound towards the horizon. */
double microfacet_ggx_lambda(vec3 w, double alpha);

/* Returns G1(w) = 1 / (1 + Lambda(w)): the share of the microfacets facing w that w sees unmasked. */
double microfacet_ggx_g1(vec3 w, double alpha);

/* Returns the height-correlated masking-shadowing G2(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi)), the
 * share of microfacets both directions see (as pbrt-v4 and Cycles from 4.0 use). Symmetric in wo and wi. */
double microfacet_ggx_g2(vec3 wo, vec3 wi, double alpha);

/* Which form of the GGX lobes f takes. The chapter's model is MICROFACET_CHAPTER (0, every constructor's).
 * MICROFACET_CYCLES_3_4 exists ONLY for the comparison with Blender 3.4's Cycles (tools/cycles/), and
 * writes f as Cycles 3.4 does: Smith's masking as two separate terms G1(wo) G1(wi) (its GGX, Glossy and
 * Glass), and a dielectric's Fresnel taken at the surface's normal instead of at each microfacet (its
 * Glass BSDF node weighs a reflecting and a refracting lobe by F(n . wo) and 1 - F(n . wo)). The
 * sampling and the pdf are the same for both forms: only f differs. */
enum microfacet_form {
    MICROFACET_CHAPTER,    /* G2 = 1 / (1 + Lambda(wo) + Lambda(wi)), Fresnel per microfacet (Walter et al.) */
    MICROFACET_CYCLES_3_4, /* G1(wo) G1(wi), a dielectric's Fresnel at the normal: for the comparison only */
};

/* Returns the masking-shadowing of the form `form`: microfacet_ggx_g2, or for MICROFACET_CYCLES_3_4 the
 * product G1(wo) G1(wi) (never larger than G2). */
double microfacet_ggx_masking(enum microfacet_form form, vec3 wo, vec3 wi, double alpha);

/* Returns a microfacet normal m drawn with the density of the normals visible from wo (wo.z > 0),
 * microfacet_ggx_visible_pdf, from two uniform numbers in [0, 1): Heitz 2018's method (stretch the
 * surface to alpha 1, sample the projected hemisphere, unstretch). m.z > 0 and m . wo >= 0. */
vec3 microfacet_ggx_sample_visible(vec3 wo, double alpha, double u1, double u2);

/* Returns D_wo(m) = G1(wo) max(0, wo . m) D(m) / wo.z, the density of the normals visible from wo per
 * unit solid angle of m (wo.z > 0; 0 otherwise). It integrates to one over m. */
double microfacet_ggx_visible_pdf(vec3 wo, vec3 m, double alpha);

/* ---- Fresnel -------------------------------------------------------------------------------------- */

/* Returns Schlick's reflectance F0 + (1 - F0) (1 - cos_i)^5 per channel, for the reflectance f0 at
 * normal incidence and the cosine cos_i in [0, 1] between the direction and the microfacet normal. */
vec3 microfacet_fresnel_schlick(vec3 f0, double cos_i);

/* Returns a conductor's reflectance per channel for unpolarised light arriving from air at cos_i in
 * [0, 1], exactly from its complex index of refraction eta + i k per channel (eta, k > 0). */
vec3 microfacet_fresnel_conductor(double cos_i, vec3 eta, vec3 k);

/* A real metal's complex index of refraction n + i k at three wavelengths standing for red, green and
 * blue (microfacet.c names the source of the numbers). */
struct microfacet_metal {
    const char *name; /* "gold", "silver", "copper", "aluminium" */
    vec3 eta;
    vec3 k;
};

/* Returns the metal called `name`, or NULL when there is none of that name. */
const struct microfacet_metal *microfacet_metal_named(const char *name);

/* Returns the number of metals microfacet_metal_named knows, and through *names (when not NULL) their
 * names in a fixed order, for messages that list them. */
int microfacet_metal_count(const char *const **names);

/* ---- the lobes ------------------------------------------------------------------------------------ */

enum microfacet_kind {
    MICROFACET_PHONG,      /* the normalised Phong lobe about the mirror direction */
    MICROFACET_CONDUCTOR,  /* GGX rough metal: reflection only */
    MICROFACET_DIELECTRIC, /* GGX rough glass: reflection and refraction */
};

/* One rough lobe. Fill it with the microfacet_*_lobe constructors below rather than by hand. */

struct microfacet_lobe {
    enum microfacet_kind kind;
    double alpha;      /* GGX width (Phong: its exponent is microfacet_phong_exponent(alpha)) */
    vec3 reflectance;  /* Phong: its reflectance; conductor (exact_fresnel false): F0 for Schlick */
    bool exact_fresnel; /* conductor: Fresnel from eta + i k instead of Schlick */
    vec3 eta, k;       /* conductor with exact_fresnel: its complex index per channel */
    double ior;        /* dielectric: index of the inside (z < 0) over the outside's */
    vec3 tint;         /* dielectric: what refracted light is multiplied by (chapter 15's glass tint) */
    enum microfacet_form form; /* conductor and dielectric: MICROFACET_CHAPTER (0) but to compare with Cycles */
};

/* Returns the normalised Phong lobe of reflectance `reflectance` and width alpha: f = reflectance
 * (n + 2) / (2 pi) cos^n(angle to the mirror direction), n = microfacet_phong_exponent(alpha). */
struct microfacet_lobe microfacet_phong_lobe(vec3 reflectance, double alpha);

/* Returns the Phong exponent n = 2 / alpha^2 - 2 whose lobe is about as wide as GGX's of width alpha
 * (Walter et al. 2007's correspondence), at most MICROFACET_PHONG_EXPONENT_MAX and at least 0. */
#define MICROFACET_PHONG_EXPONENT_MAX 1e6
double microfacet_phong_exponent(double alpha);

/* Returns the rough conductor with Schlick's Fresnel from the coloured reflectance f0 at normal
 * incidence. */
struct microfacet_lobe microfacet_conductor_lobe(vec3 f0, double alpha);

/* Returns the rough conductor with the exact Fresnel of the metal m. */
struct microfacet_lobe microfacet_metal_lobe(const struct microfacet_metal *m, double alpha);

/* Returns the rough dielectric of index ior (inside over outside, > 0, not 1) whose refracted light is
 * multiplied by tint. */
struct microfacet_lobe microfacet_dielectric_lobe(double ior, vec3 tint, double alpha);

/* Returns f(wo, wi), the lobe's BSDF without the cosine: the light reflected (or, for a dielectric,
 * also refracted) towards wo per unit of light arriving from wi, per unit projected solid angle.
 * 0 where the lobe sends no light (a conductor's or Phong's wi or wo below the surface, a dielectric's
 * directions at the horizon). A dielectric's f carries no change of radiance across the boundary, as
 * chapter 15's glass: a path that enters the glass leaves it again, and the two factors would cancel;
 * it obeys f(wo, wi) / eta(wi)^2 = f(wi, wo) / eta(wo)^2, eta(w) the index on w's side. */
vec3 microfacet_eval(const struct microfacet_lobe *l, vec3 wo, vec3 wi);

/* Returns the density per unit solid angle with which microfacet_sample draws wi from wo: what multiple
 * importance sampling weighs. 0 where the sampler never goes. */
double microfacet_pdf(const struct microfacet_lobe *l, vec3 wo, vec3 wi);

/* One scattered direction. */
struct microfacet_sample {
    vec3 wi;          /* the direction drawn, unit length */
    double pdf;       /* microfacet_pdf(l, wo, wi), > 0 */
    vec3 weight;      /* f(wo, wi) |wi.z| / pdf: what the path's throughput is multiplied by */
    bool transmitted; /* wi is on the other side of the surface from wo (dielectric only) */
};

/* Draws wi from wo with three uniform numbers in [0, 1) (the third chooses between a dielectric's
 * reflection and refraction; the others ignore it). Returns false, and leaves *s undefined, when the
 * draw sends no light (a direction below the surface for a conductor or Phong, wo at the horizon): the
 * path ends there, and that share of the density is missing from microfacet_pdf's integral. */
bool microfacet_sample(const struct microfacet_lobe *l, vec3 wo, double u1, double u2, double u3,
                       struct microfacet_sample *s);

/* Returns the lobe's directional albedo from wo: the integral of f(wo, wi) |wi.z| over every wi, the
 * share of light arriving from wo that the lobe scatters (per channel), by deterministic quadrature
 * with `steps` x `steps` points over the microfacet normals (Phong: over its lobe), independent of
 * microfacet_sample. 1 - albedo is what single scattering loses. steps >= 1. */
vec3 microfacet_albedo(const struct microfacet_lobe *l, vec3 wo, int steps);

#endif

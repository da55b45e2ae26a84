/* rough_surface.c: the rough mirror and frosted glass of chapter 17 as a path_surface (rough_surface.h). */
#include "rough_surface.h"

#include <math.h>

#include "bsdf.h"
#include "sampling.h"

struct rough_surface rough_surface_of_material(const struct material *m, double eta) {
    return rough_surface_in_form(m, eta, MICROFACET_CHAPTER);
}

struct rough_surface rough_surface_in_form(const struct material *m, double eta, enum microfacet_form form) {
    struct bsdf b = bsdf_of_material(m);
    double alpha = microfacet_alpha(m->roughness);
    struct rough_surface r = {.albedo = b.albedo, .p_diffuse = b.p_diffuse, .scale = vec3_make(1, 1, 1)};
    if (b.glass) {
        r.glass = true;
        r.p_diffuse = 0.0;
        r.lobe = microfacet_dielectric_lobe(1.0 / eta, b.tint, alpha);
        r.lobe.form = form;
        return r;
    }
    vec3 white = vec3_make(1, 1, 1);
    vec3 f0 = white; /* SCENE_METAL_NONE: Schlick from 1 is 1 at every angle, scaled by reflection */
    const struct microfacet_metal *metal = NULL;
    if (m->metal == SCENE_METAL_COLOUR)
        f0 = vec3_scale(m->colour, b.mirror);
    else if (m->metal != SCENE_METAL_NONE)
        metal = microfacet_metal_named(scene_metal_names[m->metal]);
    if (m->metal != SCENE_METAL_COLOUR)
        r.scale = vec3_make(b.mirror, b.mirror, b.mirror);
    if (m->lobe == SCENE_LOBE_PHONG) /* the Phong lobe has no Fresnel: a metal's at normal incidence */
        r.lobe = microfacet_phong_lobe(metal != NULL ? microfacet_fresnel_conductor(1.0, metal->eta, metal->k) : f0, alpha);
    else if (metal != NULL)
        r.lobe = microfacet_metal_lobe(metal, alpha);
    else
        r.lobe = microfacet_conductor_lobe(f0, alpha);
    r.lobe.form = form; /* the Phong lobe has neither masking nor Fresnel: it ignores this */
    return r;
}

/* The surface's frame: (t, b, n) orthonormal, n the normal on wo's side. */
struct frame {
    vec3 t, b, n;
};

static struct frame frame_about(vec3 n) {
    struct frame f = {.n = n};
    sampling_basis(n, &f.t, &f.b);
    return f;
}

static vec3 to_local(const struct frame *f, vec3 v) {
    return vec3_make(vec3_dot(v, f->t), vec3_dot(v, f->b), vec3_dot(v, f->n));
}

static vec3 to_world(const struct frame *f, vec3 v) {
    return vec3_add(vec3_add(vec3_scale(f->t, v.x), vec3_scale(f->b, v.y)), vec3_scale(f->n, v.z));
}

static bool claims(const struct material *m) { return m->roughness > 0.0; }

/* f |cos| and the mixture's density, in the local frame. */
static vec3 eval_local(const struct rough_surface *r, vec3 wo, vec3 wi, double *pdf) {
    vec3 f_cos = vec3_make(0, 0, 0);
    *pdf = 0.0;
    if (r->p_diffuse > 0.0 && wi.z > 0.0) {
        f_cos = vec3_scale(r->albedo, wi.z / M_PI);
        *pdf = r->p_diffuse * wi.z / M_PI;
    }
    if (r->p_diffuse < 1.0) {
        vec3 lobe = vec3_mul(r->scale, microfacet_eval(&r->lobe, wo, wi));
        f_cos = vec3_add_scaled(f_cos, lobe, fabs(wi.z));
        *pdf += (1.0 - r->p_diffuse) * microfacet_pdf(&r->lobe, wo, wi);
    }
    return f_cos;
}

static vec3 eval_in_form(enum microfacet_form form, const struct material *m, vec3 normal, vec3 wo, vec3 wi,
                        double eta, double *pdf) {
    struct rough_surface r = rough_surface_in_form(m, eta, form);
    struct frame f = frame_about(normal);
    return eval_local(&r, to_local(&f, wo), to_local(&f, wi), pdf);
}

static bool sample_in_form(enum microfacet_form form, const struct material *m, vec3 normal, vec3 wo, double eta,
                          double u_lobe, double u1, double u2, struct path_scatter *out) {
    struct rough_surface r = rough_surface_in_form(m, eta, form);
    if (r.p_diffuse == 0.0 && vec3_dot(r.scale, r.scale) == 0.0)
        return false; /* black: nothing scatters */
    if (r.glass && eta == 1.0) {
        /* The same index on both sides: no facet bends the light or reflects any (Fresnel is 0), so it goes
         * straight through, tinted, whatever the roughness. The microfacet lobe cannot say so: its half
         * vector wo + wi is 0 there, and would give the direction no density and end the path. */
        *out = (struct path_scatter){.direction = vec3_scale(wo, -1.0), .weight = r.lobe.tint, .pdf = 1.0,
                                     .crossed = true, .delta = true};
        return true;
    }
    struct frame f = frame_about(normal);
    vec3 lo = to_local(&f, wo), li;
    if (u_lobe < r.p_diffuse)
        li = to_local(&f, sampling_cosine_hemisphere(normal, u1, u2));
    else {
        struct microfacet_sample s;
        if (!microfacet_sample(&r.lobe, lo, u1, u2, (u_lobe - r.p_diffuse) / (1.0 - r.p_diffuse), &s))
            return false;
        li = s.wi;
    }
    /* The weight of the mixture, not of the lobe drawn from: each part may have sent the direction. */
    double pdf;
    vec3 f_cos = eval_local(&r, lo, li, &pdf);
    if (!(pdf > 0.0))
        return false;
    out->direction = vec3_normalize(to_world(&f, li));
    out->weight = vec3_scale(f_cos, 1.0 / pdf);
    out->pdf = pdf;
    out->crossed = li.z < 0.0;
    out->delta = false;
    return true;
}

static vec3 eval(const struct material *m, vec3 normal, vec3 wo, vec3 wi, double eta, double *pdf) {
    return eval_in_form(MICROFACET_CHAPTER, m, normal, wo, wi, eta, pdf);
}

static bool sample(const struct material *m, vec3 normal, vec3 wo, double eta, double u_lobe, double u1, double u2,
                   struct path_scatter *out) {
    return sample_in_form(MICROFACET_CHAPTER, m, normal, wo, eta, u_lobe, u1, u2, out);
}

const struct path_surface rough_surface_hook = {claims, eval, sample};

static vec3 eval_cycles_3_4(const struct material *m, vec3 normal, vec3 wo, vec3 wi, double eta, double *pdf) {
    return eval_in_form(MICROFACET_CYCLES_3_4, m, normal, wo, wi, eta, pdf);
}

static bool sample_cycles_3_4(const struct material *m, vec3 normal, vec3 wo, double eta, double u_lobe, double u1,
                             double u2, struct path_scatter *out) {
    return sample_in_form(MICROFACET_CYCLES_3_4, m, normal, wo, eta, u_lobe, u1, u2, out);
}

const struct path_surface rough_surface_hook_cycles_3_4 = {claims, eval_cycles_3_4, sample_cycles_3_4};

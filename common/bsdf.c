/* bsdf.c: Whitted's materials as scattering surfaces, and Fresnel's reflectance (chapter 15). */
#include "bsdf.h"

#include <math.h>

struct bsdf bsdf_of_material(const struct material *m) {
    struct bsdf b = {0};
    b.ior = m->ior;
    if (m->filter + m->transmit > 0.0) {
        b.glass = true;
        b.tint = vec3_add_scaled(vec3_make(m->transmit, m->transmit, m->transmit), m->colour, m->filter);
        return b;
    }
    b.albedo = vec3_scale(m->colour, m->diffuse);
    b.mirror = m->reflection;
    double diffuse_share = vec3_largest(b.albedo);
    b.p_diffuse = diffuse_share + b.mirror > 0.0 ? diffuse_share / (diffuse_share + b.mirror) : 0.0;
    return b;
}

bool bsdf_conserves_energy(const struct scene *s, const struct material *m, char *why, size_t why_size) {
    double colour = vec3_largest(m->colour); /* the largest channel of any colour the surface takes */
    if (m->pigment >= 0) {
        const struct pigment *p = &s->pigments[m->pigment];
        colour = p->pattern == PIGMENT_IMAGE_MAP ? BSDF_MOST_REFLECTANCE /* texels are 0..1 */
                                                 : fmax(vec3_largest(p->colour[0]), vec3_largest(p->colour[1]));
    }
    const double most = BSDF_MOST_REFLECTANCE + BSDF_REFLECTANCE_ROUNDING;
    if (colour > most) {
        snprintf(why, why_size, "material '%s': a colour channel of %g%s; a surface gives back at most the light "
                 "that reaches it, so each channel must be at most 1", m->name, colour,
                 m->pigment >= 0 ? " (its pigment's)" : "");
        return false;
    }
    if (material_passes_light(m))
        return true; /* transmit + filter * colour <= filter + transmit <= 1 */
    double given_back = m->diffuse * colour + m->reflection;
    if (given_back > most) {
        snprintf(why, why_size, "material '%s': diffuse * colour + reflection is %g; a surface gives back at most "
                 "the light that reaches it, so it must be at most 1", m->name, given_back);
        return false;
    }
    return true;
}

double bsdf_fresnel(double cos_i, double eta) {
    double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0)
        return 1.0;
    double cos_t = sqrt(1.0 - sin2_t);
    double across = (eta * cos_i - cos_t) / (eta * cos_i + cos_t); /* s-polarised, field perpendicular */
    double along = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);  /* p-polarised, field in the plane */
    return 0.5 * (across * across + along * along);
}

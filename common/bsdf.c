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
    double diffuse_share = fmax(b.albedo.x, fmax(b.albedo.y, b.albedo.z));
    b.p_diffuse = diffuse_share + b.mirror > 0.0 ? diffuse_share / (diffuse_share + b.mirror) : 0.0;
    return b;
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

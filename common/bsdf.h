/* bsdf.h: how chapter 15 reads a Whitted material as a surface that scatters light (docs/15-paths.md).
 *
 * Chapter 15's surfaces are of three kinds, and every material of the scene format maps onto them:
 *   - glass, when the material lets light through (filter + transmit > 0): a smooth dielectric of index
 *     `ior` that reflects the Fresnel share of the light and refracts the rest, the refracted light
 *     tinted by colour * filter + transmit. Its diffuse, highlight and mirror keys are not used.
 *   - otherwise a Lambertian surface of albedo diffuse * colour (the BRDF albedo / pi), plus a perfect
 *     mirror of reflectance `reflection` (untinted, as POV-Ray's reflection).
 * ambient, phong and phong_size have no place in the rendering equation: the light that ambient stood
 * for is now computed, and POV-Ray's highlight is the reflection of a point light, which paths never see.
 * Emission is the material's own key, added to whatever the surface scatters. */
#ifndef WHITTED_BSDF_H
#define WHITTED_BSDF_H

#include <stdbool.h>

#include "scene.h"

struct bsdf {
    bool glass;
    vec3 tint;        /* glass: what the refracted light is multiplied by */
    double ior;       /* glass: index of refraction of the inside */
    vec3 albedo;      /* Lambertian: diffuse * colour */
    double mirror;    /* the mirror's reflectance */
    double p_diffuse; /* the chance a path scatters by the Lambertian part rather than the mirror: their
                       * shares of the reflected light, the largest channel of the albedo against mirror */
};

/* Returns the surface of material m (already painted by chapter 14's hook when the scene has one). */
struct bsdf bsdf_of_material(const struct material *m);

/* The most of the light reaching it that a surface may give back: all of it. */
#define BSDF_MOST_REFLECTANCE 1.0
/* What a sum such as 0.7 + 0.3 may exceed 1 by in rounding and still count as 1. */
#define BSDF_REFLECTANCE_ROUNDING 1e-12

/* Returns true when material m of scene s gives back at most the light that reaches it, as chapters 15
 * and 17 read it: each channel of its colour (or of every colour its pigment takes) at most 1, and
 * diffuse * colour + reflection at most 1 (glass: transmit + filter * colour, which then is). Else
 * false with "material 'NAME': ..." in why. A path's weight then never grows from bounce to bounce;
 * with a surface that gave back more, the picture's light would add up without bound (a colour of
 * 1e300 seen through glass twice was infinite). */
bool bsdf_conserves_energy(const struct scene *s, const struct material *m, char *why, size_t why_size);

/* Returns the share of light a smooth dielectric reflects (Fresnel's equations for unpolarised light),
 * for a ray whose direction makes cos_i > 0 with the normal on its side, going from index n1 to n2,
 * eta = n1 / n2. 1 under total internal reflection. */
double bsdf_fresnel(double cos_i, double eta);

#endif

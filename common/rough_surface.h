/* rough_surface.h: chapter 17's rough mirrors and frosted glass as a surface of chapter 15's path
 * tracer (path_trace.h's struct path_surface; docs/17-rough.md).
 *
 * A material with roughness > 0 is drawn here instead of by bsdf.h:
 *   - glass (filter + transmit > 0): microfacet.h's rough dielectric of the material's ior, its refracted
 *     light tinted as chapter 15's glass (colour * filter + transmit);
 *   - otherwise chapter 15's Lambertian part (albedo diffuse * colour) plus a rough mirror of
 *     reflectance `reflection` in place of the smooth one: microfacet.h's GGX conductor (or, with
 *     `lobe phong`, the normalised Phong lobe), whose Fresnel the material's `metal` key chooses
 *     (scene.h's enum scene_metal).
 * A path picks the Lambertian part or the mirror with the shares chapter 15 uses (bsdf.h's p_diffuse),
 * and the density it reports for MIS is the mixture's: p_diffuse cos / pi + (1 - p_diffuse) times the
 * lobe's pdf. The width of the lobe is alpha = microfacet_alpha(roughness), squared there only. */
#ifndef WHITTED_ROUGH_SURFACE_H
#define WHITTED_ROUGH_SURFACE_H

#include <stdbool.h>

#include "microfacet.h"
#include "path_trace.h"

/* A material read as a rough surface. */
struct rough_surface {
    vec3 albedo;                 /* the Lambertian part: diffuse * colour */
    double p_diffuse;            /* the chance a path scatters by the Lambertian part */
    struct microfacet_lobe lobe; /* the rough mirror or the frosted glass */
    vec3 scale;                  /* what the lobe's f is multiplied by (the mirror's reflection) */
    bool glass;
};

/* The hook chapter 17 sets in path_world.surface: claims the materials with roughness > 0. */
extern const struct path_surface rough_surface_hook;

/* The same surfaces with their lobes written as Blender 3.4's Cycles writes them (microfacet.h's
 * MICROFACET_CYCLES_3_4: separable masking, glass's Fresnel at the normal). It exists ONLY for the
 * comparison with Cycles (chapter 17's --form cycles-3.4, which tools/cycles/compare-cycles.sh passes);
 * no picture of the chapter uses it. */
extern const struct path_surface rough_surface_hook_cycles_3_4;

/* Returns material m read as a rough surface, for light arriving from the side where the index over
 * the other side's is eta (bsdf_fresnel's eta: the glass's inside over its outside is 1 / eta).
 * Meaningful for any material; the hook uses it for those with roughness > 0. */
struct rough_surface rough_surface_of_material(const struct material *m, double eta);

/* Returns rough_surface_of_material(m, eta) with its lobe in the form `form`. */
struct rough_surface rough_surface_in_form(const struct material *m, double eta, enum microfacet_form form);

#endif

/* whitted.h: recursive ray tracing, Whitted 1980: reflection, refraction and light through glass, as
 * POV-Ray 3.7 computes them (chapter 8; chapters 9 and 10 reuse it unchanged with faster worlds).
 *
 * Colour seen along a ray of level L (the camera ray is level 1) and weight W that hits a surface:
 *   local  = phong_shade with opacity 1 - filter - transmit and filtered shadows
 *   + (colour * filter + transmit) * trace(refracted ray)      if the surface lets light through
 *   + 1.0 * trace(reflected ray)  instead, on total internal reflection (then no mirror term)
 *   + reflection * trace(reflected ray)                        otherwise
 * The indices of refraction come from the ray's interior list (interior.h): nested glass works as in
 * POV-Ray. A ray that would be of level max_depth + 1 is black, and so is one whose weight (W times
 * reflection, or times the largest channel of colour * filter + transmit) is under the scene's
 * adc_bailout. A crossing between equal indices bends nothing and does not use up a level (POV-Ray's
 * rule); it is followed by a loop, at most RAY_MAX_CROSSINGS times, and one camera ray spends at most
 * RAY_TREE_BUDGET secondary rays and area-light shadow rays (ray.h). Secondary rays start on the surface itself and accept hits
 * from ray_t_min(their origin) on. */
#ifndef WHITTED_WHITTED_H
#define WHITTED_WHITTED_H

#include <stdbool.h>

#include "phong.h"
#include "world.h"

/* Returns the refracted direction of unit D through a surface with unit normal N facing D, going from
 * index n1 to n2 (eta = n1 / n2), by Heckbert's formula: eta D + (eta c - sqrt(k)) N with c = -D.N and
 * k = 1 - eta^2 (1 - c^2). Returns false, leaving *out alone, on total internal reflection (k < 0). */
bool whitted_refract(vec3 direction, vec3 normal, double eta, vec3 *out);

/* Returns the colour seen along ray r in world w (a struct world), r being a camera ray (level 1).
 * Matches render_trace_fn. */
vec3 whitted_trace(const void *world, const ray *r);

/* whitted_trace with each light's shadow factor given by `shadow` instead of shadow_filtered (chapter
 * 13 passes its soft shadows of area lights). */
vec3 whitted_trace_shadowed(const void *world, const ray *r, phong_shadow_fn shadow);

#endif

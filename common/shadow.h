/* shadow.h: shadow rays from a surface point to a light (chapter 7; light through glass, chapter 8).
 *
 * A shadow ray leaves the surface point P towards the light at distance d. Only blockers with
 * SHADOW_T_MIN < t < d - SHADOW_T_MIN count: the margin at the start keeps the surface from shadowing
 * itself through rounding ("shadow acne"), the margin at the end keeps a shape that touches the light
 * from blocking it. The scene option `shadow_offset off` drops both margins (t > 0 and t < d) so the
 * acne can be seen and tested. */
#ifndef WHITTED_SHADOW_H
#define WHITTED_SHADOW_H

#include "scene.h"
#include "world.h"

/* Chapter 14 finds the surface a shadow ray crosses at t again, for a uv-mapped pigment, as the nearest
 * hit between t - w and t + w with w = SHADOW_CROSSING_WINDOW * max(1, t): far below the size of any
 * surface, far above the rounding of t. */
#define SHADOW_CROSSING_WINDOW 1e-7

/* Returns (1, 1, 1) when nothing lies between `point` and the light, (0, 0, 0) when anything does:
 * every shape casts an opaque shadow (chapter 7). Counts one shadow ray. `world` is a struct world. */
vec3 shadow_opaque(const void *world, vec3 point, const struct light *light);

/* Returns the share of the light that passes every surface between `point` and the light: the product
 * over each crossing of (colour * filter + transmit), so an opaque shape gives 0 and a glass sphere,
 * crossed twice, transmit squared (chapter 8, as POV-Ray does). With scene.shadow_paint (chapter 14), a
 * material with a pigment filters with the pigment's colour and transmit where the ray crosses it.
 * Counts one shadow ray. */
vec3 shadow_filtered(const void *world, vec3 point, const struct light *light);

/* shadow_filtered towards a point light at `target` (one of an area light's points, chapter 13). */
vec3 shadow_filtered_to(const void *world, vec3 point, vec3 target);

#endif

/* soft_shadow.h: shadows of area lights, soft-edged: POV-Ray 3.7's area_light (chapter 13;
 * docs/13-distributed.md).
 *
 * A point light is either seen or not, and its shadow has a knife edge. An area light (area_light.h)
 * is a rectangle: from a point in the penumbra part of it is hidden and part seen. Here the rectangle
 * is a grid of n1 x n2 point lights, each tried with chapter 8's filtered shadow ray, and the share of
 * light that gets through is their weighted mean. The weights and the order are POV-Ray's, exactly:
 * the grid's four corners are traced, and the rectangle is cut into four (at the middle grid lines)
 * and each quarter treated alike while it spans more than one step of the grid and either the level
 * is under the light's `adaptive` level or two neighbouring corners differ by more than
 * SOFT_SHADOW_THRESHOLD; a rectangle's share is the plain mean of its four corners or of its four
 * quarters. Without `adaptive` every point is traced. Diffuse and highlight still look towards the
 * light's centre, as POV-Ray's do: only the shadow is spread. */
#ifndef WHITTED_SOFT_SHADOW_H
#define WHITTED_SOFT_SHADOW_H

#include "scene.h"

/* POV-Ray's difference between two corners' light (light colour times the share let through), summed
 * over the three channels, above which the adaptive rule cuts a rectangle further. */
#define SOFT_SHADOW_THRESHOLD 0.1

/* POV-Ray's circular lights move every grid point by this much (in units of the side) before pushing
 * it onto the ellipse, so that the centre point has a direction. */
#define SOFT_SHADOW_CIRCULAR_NUDGE 0.001

/* Returns the position of point (u, v) of area light `light` (0 <= u < size1, 0 <= v < size2) as seen
 * from `point` (which matters only for an oriented light): the centre plus the offset along the two
 * axes, (u / (size1 - 1) - 1/2) axis1 + (v / (size2 - 1) - 1/2) axis2 (0 along an axis of one point),
 * pushed onto the ellipse for a circular light. For a point light, its position. */
vec3 soft_shadow_light_point(const struct light *light, vec3 point, int u, int v);

/* Returns the share of `light` reaching `point`, per channel, by the rule above (for a point light,
 * shadow_filtered's). Counts one shadow ray per grid point traced. `world` is a struct world; a
 * phong_shadow_fn (phong.h). */
vec3 soft_shadow_filtered(const void *world, vec3 point, const struct light *light);

#endif

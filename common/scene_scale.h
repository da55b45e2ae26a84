/* scene_scale.h: a warning for scenes too small for the tracer's distance margins, or too far from the
 * origin for their size (chapter 1; the margins are explained in ray.h and chapter 7).
 *
 * RAY_T_MIN and SHADOW_T_MIN are absolute distances, POV-Ray's, chosen for scenes of about unit size.
 * A scene modelled in millimetres as metres (a 30 mm marble as radius 0.015) puts the shadow margin at
 * a tenth of an object: shadows and thin glass go wrong, and the picture no longer matches POV-Ray's. */
#ifndef WHITTED_SCENE_SCALE_H
#define WHITTED_SCENE_SCALE_H

#include <stdbool.h>
#include <stdio.h>

#include "scene.h"

/* A scene is "small" when its extent is under this many shadow margins (SHADOW_T_MIN, 1e-3): under 1
 * unit. Our pictures agree with POV-Ray's down to scenes 0.1 across (docs/povray.md, "Scale"), so the
 * warning comes a factor of ten early; every shipped scene is at least 4 units across. */
#define SCENE_SCALE_MIN_MARGINS 1000.0

/* Returns the scene's extent: the longest side of the box around the eye and every finite shape the
 * program draws (the bounding boxes of its kinds of shape, shape.h, loaded meshes, and chapter 16's
 * instances by their world boxes once it has placed them, s->instance_bounds; planes are infinite and
 * left out). Cannot fail. */
double scene_extent(const struct scene *s);

/* When s has a finite shape and scene_extent(s) < SCENE_SCALE_MIN_MARGINS * SHADOW_T_MIN, prints one warning line to `out`
 * naming the extent, the margins and a factor to scale the scene up by, and returns true. Otherwise,
 * when the scene is under SCENE_SCALE_MIN_MARGINS of the margin a secondary ray takes at its point
 * farthest from the origin (ray_t_min: 1e-9 of the distance, beyond 100,000 units), prints one warning
 * line naming the extent, the distance and the margin, and returns true: reflections and refractions
 * between its surfaces would be lost, and the path tracers' shadows (camera rays still see them, and a
 * Whitted shadow ray keeps its fixed margin). Otherwise prints nothing and returns
 * false. */
bool scene_scale_warn(const struct scene *s, FILE *out);

#endif

/* headlight.h: the stand-in shading of chapters 2 to 5, a white light at the eye (chapter 2).
 *
 * Until chapter 6 brings lights and materials, a surface is lit by one white point light sitting at the
 * camera, diffuse only. Its brightness is then |N . D|: faces turned to the camera are bright, faces seen
 * edge-on are dark, so a shape's form shows from its first picture. POV-Ray draws exactly this with a
 * light_source at the camera and finish { ambient 0 diffuse 1 }, which is how its twin is written. */
#ifndef WHITTED_HEADLIGHT_H
#define WHITTED_HEADLIGHT_H

#include "hit.h"
#include "scene.h"

/* Returns the colour seen along a ray with unit direction `direction` that found `h`: the material's
 * colour times the cosine between the ray and the surface normal. Cannot fail. */
vec3 headlight_shade(const struct scene *s, const struct hit *h, vec3 direction);

#endif

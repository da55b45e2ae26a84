/* embree_ref.h: the pieces of the Embree yardstick (embree_ref.c) that the instance benchmark shares.
 * Only for files built with Embree 3's header (bench/bench.mk). */
#ifndef WHITTED_EMBREE_REF_H
#define WHITTED_EMBREE_REF_H

#include <embree3/rtcore.h>

#include "mesh.h"
#include "ray.h"

/* A new scene on device holding m as one triangle geometry (its vertices rounded to float), not yet
 * committed (built). NULL on failure. */
RTCScene embree_ref_mesh_scene(RTCDevice device, const struct mesh *m);

/* Fills *out with the ray origin + t direction, t_min < t < t_max, rounded to float, at time 0, every
 * mask bit set. */
void embree_ref_set_ray(struct RTCRay *out, vec3 origin, vec3 direction, double t_min, double t_max);

#endif

/* box.h: the axis-aligned box as a renderable shape (chapter 5).
 *
 * The type is declared from chapter 1 on, so that the scene format reads the same in every chapter; the
 * intersection code below (box.c) arrives with chapter 5 and reuses the slab test of aabb.c. */
#ifndef WHITTED_BOX_H
#define WHITTED_BOX_H

#include <stdbool.h>
#include <stddef.h>

#include "hit.h"
#include "ray.h"

struct box {
    vec3 min, max; /* opposite corners, min < max on every axis */
    int material;  /* index into scene.materials */
};

/* Finds the nearest t with t_min < t < t_max where ray r crosses the surface of b: where it enters, or
 * where it leaves when it starts inside. Returns false if there is none. Counts one box test. */
bool box_intersect(const struct box *b, const ray *r, double t_min, double t_max, double *t);

/* Tests r against boxes[0..count) for hits with t_min < t < h->t and keeps the nearest in *h (with the
 * outward normal of the face hit). Returns true when *h was replaced. */
bool box_closest(const struct box *boxes, size_t count, const ray *r, double t_min, struct hit *h);

#endif

/* box.h: the axis-aligned box as a renderable shape (chapter 1 reads its scene line, box_syntax.c;
 * chapter 5 intersects it, box.c: shape.h explains the two halves).
 *
 * Like every shape, its scene-file line is read from chapter 1 on, so that the scene format reads the
 * same in every chapter; the intersection code (box.c) arrives with chapter 5 and reuses the slab
 * test of aabb.c. */
#ifndef WHITTED_BOX_H
#define WHITTED_BOX_H

#include <stdbool.h>
#include <stddef.h>

#include "ray.h"
#include "shape.h"

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

/* The box's scene-file line (box_syntax.c, chapter 1), and the box as a kind of shape (shape.h). */
extern const struct shape_syntax box_syntax;
extern const struct shape_kind box_kind;

#endif

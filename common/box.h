/* box.h: the axis-aligned box as a renderable shape (chapter 5).
 *
 * Like every shape, its scene-file line is read from chapter 1 on (the syntax at the end of this
 * header), so that the scene format reads the same in every chapter; the intersection code (box.c)
 * arrives with chapter 5 and reuses the slab test of aabb.c. */
#ifndef WHITTED_BOX_H
#define WHITTED_BOX_H

#include <stdbool.h>
#include <stddef.h>

#include "hit.h"
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

/* The box's ray queries for the world (struct shape_behaviour, shape.h). */
extern const struct shape_behaviour box_behaviour;

/* ---- the scene-file line: box min X Y Z max X Y Z [material NAME] (read by chapter 1) ----------- */

enum { BOX_MIN, BOX_MAX };

/* Makes the box from its keys (struct shape_syntax's make). */
static inline bool box_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
    struct box *b = item;
    b->min = key_vec3(kv, BOX_MIN);
    b->max = key_vec3(kv, BOX_MAX);
    if (!(b->min.x < b->max.x && b->min.y < b->max.y && b->min.z < b->max.z)) {
        snprintf(why, why_size, "box min must be below max on every axis");
        return false;
    }
    return true;
}

/* Writes the box for POV-Ray: box { <min>, <max> */
static inline void box_write_pov(FILE *out, const void *item) {
    const struct box *b = item;
    fprintf(out, "box { ");
    shape_write_vector(out, b->min);
    fprintf(out, ", ");
    shape_write_vector(out, b->max);
}

static const struct key_spec box_keys[] = {{"min", 3}, {"max", 3}};
static const int box_required[] = {BOX_MIN, BOX_MAX, -1};
static const struct shape_syntax box_syntax = {box_keys, 2, box_required, box_make, box_write_pov};

#endif

#ifdef SHAPE_KIND /* the registration line: see shape_kinds.h */
SHAPE_KIND(box, boxes, BOXES, 5)
#endif

/* interior.h: the list of transparent objects a ray is inside, and POV-Ray 3.7's rule for crossing a
 * surface (chapter 8).
 *
 * Snell's law needs two indices of refraction: the medium the ray is in and the medium it goes into.
 * Deciding "in or out" from the side the normal faces only works for one object in air; a glass in
 * water, an air bubble in water or a marble in a glass of water need more. So every ray carries the
 * objects it is inside, innermost last. Crossing the surface of object X:
 *   - list empty:                  enter X from the air:          n1 = 1,          n2 = ior(X)
 *   - X is the innermost:          leave X into the next one out: n1 = ior(X),     n2 = ior(new top) or 1
 *   - X is on the list, not last:  leave an overlap of two objects: n1 = n2 (nothing bends)
 *   - X is not on the list:        enter X from the innermost:    n1 = ior(top),   n2 = ior(X)
 * and the list gains or loses X. A reflected ray keeps its parent's list; a refracted ray gets the
 * updated one. An object is one entry however many faces it has (a whole mesh is one object). */
#ifndef WHITTED_INTERIOR_H
#define WHITTED_INTERIOR_H

#include <stdbool.h>

#include "ray.h"
#include "world.h"

/* At most RAY_INTERIOR_CAPACITY objects deep (ray.h). */
struct interior_list {
    int count;                          /* objects the ray is inside, 0 in the open air */
    int object[RAY_INTERIOR_CAPACITY];      /* world.h object numbers, outermost first */
    double ior[RAY_INTERIOR_CAPACITY];      /* index of refraction of each */
};

/* Returns the empty list: a ray in the open air (index 1). */
static inline struct interior_list interior_empty(void) { return (struct interior_list){0, {0}, {0}}; }

/* Returns true when `object` is on the list. */
bool interior_contains(const struct interior_list *list, int object);

/* A ray with interior list *list crosses the surface of `object`, whose inside has index of refraction
 * `ior`. Updates *list by the rule above and returns n1 / n2, the ratio Snell's law needs (1.0 exactly
 * when nothing bends). Cannot fail; a full list counts one overflow and stays as it is. */
double interior_cross(struct interior_list *list, int object, double ior);

/* Returns true when `point` is inside mesh m: the ray from it along +z crosses an odd number of m's
 * faces (each tested by triangle_intersect for 0 <= t), as the twin's inside_vector <0, 0, 1> has
 * POV-Ray decide. Meant for closed meshes; cannot fail. */
bool interior_mesh_contains(const struct mesh *m, vec3 point);

/* Returns the list of the transparent objects of world w that contain `point`, in the order the world
 * searches them (struct world), as POV-Ray gives a camera ray that starts inside glass: each kind of
 * shape by its `contains` (shape.h: spheres, boxes, planes on the side the normal points away from;
 * triangles never), meshes by interior_mesh_contains, then chapter 16's instances (w->instances) in the
 * order of their lines, each placed as it is at w->time, its object's mesh tested in its own space.
 * Cannot fail. */
struct interior_list interior_at_point(const struct world *w, vec3 point);

#endif

/* hit.h: what a ray found, and the "keep the nearest" helpers every shape offers (chapter 2).
 *
 * A search for the nearest surface starts with hit_nothing(); each shape's *_closest function replaces
 * the hit only when it finds something nearer than hit.t, and then shrinks hit.t, so later shapes are
 * only tested against a shorter and shorter ray. */
#ifndef WHITTED_HIT_H
#define WHITTED_HIT_H

#include <math.h>
#include <stdbool.h>

#include "vec3.h"

struct hit {
    double t;      /* distance along the ray; INFINITY while nothing has been found */
    vec3 normal;   /* unit geometric normal as the shape defines it (not yet turned to face the ray) */
    int material;  /* index into scene.materials */
    int object;    /* which object was hit, as world.h numbers them (chapter 8's interior list needs it) */
    int face;      /* the triangle hit: its index within its mesh (the mesh is `object`) or among the
                    * triangle lines; -1 for every other shape. Chapter 14 finds a mesh's normals and
                    * texture coordinates with it (world.c and triangle_mesh_closest fill it). */
};

/* Returns an empty hit: nothing found yet, so anything closer than t_max will do. */
static inline struct hit hit_nothing(double t_max) { return (struct hit){t_max, {0, 0, 0}, 0, -1, -1}; }

/* Returns true when a surface was found (t is finite). */
static inline bool hit_found(const struct hit *h) { return isfinite(h->t); }

/* Returns the normal of h turned to face against the ray direction d: the side the ray sees. Every
 * shape is shaded from the side the ray arrives on, as POV-Ray does. */
static inline vec3 hit_facing_normal(const struct hit *h, vec3 d) {
    return vec3_dot(h->normal, d) < 0.0 ? h->normal : vec3_neg(h->normal);
}

#endif

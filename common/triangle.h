/* triangle.h: the triangle and the watertight ray-triangle test (chapter 1 reads its scene line,
 * triangle_syntax.c; chapter 3 intersects it, triangle.c: shape.h explains the two halves). */
#ifndef WHITTED_TRIANGLE_H
#define WHITTED_TRIANGLE_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "ray.h"
#include "shape.h"

struct triangle {
    vec3 a, b, c; /* corners; the winding does not matter: triangles are two-sided */
    int material; /* index into scene.materials */
};

/* Moller-Trumbore, the test chapter 3 teaches first: solves O + tD = (1-u-v)a + ub + vc by Cramer's
 * rule. Same contract as triangle_crossing, but each triangle rounds its own u and v, so a ray that
 * meets an edge shared by two triangles can miss both (see docs/03-triangle.md). Kept for teaching and
 * for the tests that show the leak; the tracer does not use it. Counts nothing. */
bool triangle_crossing_mt(vec3 a, vec3 b, vec3 c, const ray *r, double *t, double *u, double *v);

/* A ray made ready for the watertight test of Woop, Benthin and Wald ("Watertight Ray/Triangle
 * Intersection", JCGT 2(1), 2013). The world's axes are renamed so that the direction's longest
 * component is along z (world axis kz), and the shear
 *     x' = x - sx z,   y' = y - sy z,   z' = sz z
 * makes the direction (0, 0, 1). In those coordinates, with the origin moved to (0, 0, 0), the ray is
 * the z axis. The record depends on the ray alone, so every triangle sees it the same way. */
struct triangle_ray {
    ray ray;           /* the ray itself */
    int kx, ky, kz;    /* the world axes (0, 1, 2 for x, y, z) used as x, y and z */
    double sx, sy, sz; /* the shear: sz = 1 / d[kz], sx = d[kx] sz, sy = d[ky] sz */
};

/* Returns r made ready for triangle_crossing_prepared: one division and a few comparisons, worth
 * doing once per ray when the ray meets many triangles. A zero or NaN direction gives NaN shears,
 * with which every triangle misses. */
static inline struct triangle_ray triangle_ray_make(const ray *r) {
    vec3 d = r->direction;
    double along_x = fabs(d.x), along_y = fabs(d.y), along_z = fabs(d.z);
    int kz = along_x > along_y ? (along_x > along_z ? 0 : 2) : (along_y > along_z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
    double sz = 1.0 / vec3_axis(d, kz);
    return (struct triangle_ray){*r, kx, ky, kz, vec3_axis(d, kx) * sz, vec3_axis(d, ky) * sz, sz};
}

/* The edge function of the edge from p to q, seen from the ray: twice the signed area of the 2D
 * triangle (0, 0), p, q in the sheared plane, px qy - py qx, with its exact sign: zero only when the
 * ray meets the edge's line exactly. The same two corners always give the same number, and given in
 * the other order its exact negative, so two triangles that share an edge agree on it. */
static inline double triangle_edge_function(double px, double py, double qx, double qy) {
    double left = px * qy, right = py * qx;
    if (left != right)
        return left - right; /* rounding keeps the products' order, so this has the exact sign */
    /* Equal rounded products: the exact difference is that of their rounding errors, which fma gives
     * exactly (barring underflow). Returning 0 here made a triangle a few units in the last place
     * across count as hit by rays passing far from it (docs/03-triangle.md). */
    return fma(px, qy, -left) - fma(py, qx, -right);
}

/* Whether the corners a, b, c lie exactly on one line (or coincide): the cross product of two edges is
 * zero. Such a triangle has no normal, and the watertight test below never reports it crossed. */
static inline bool triangle_corners_collinear(vec3 a, vec3 b, vec3 c) {
    vec3 area = vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
    return area.x == 0.0 && area.y == 0.0 && area.z == 0.0;
}

/* The watertight test on the triangle with corners a, b, c, the form the acceleration structures
 * store. Returns true and stores t, u and v (P = (1-u-v)a + ub + vc) when the ray's line crosses the
 * triangle, at any t (the caller checks its window). Points on edges and corners count as inside, for
 * both triangles that share them. A ray that sees the triangle edge-on (all three edge functions
 * zero: parallel to its plane, or a triangle without area) never crosses. Counts nothing. */
static inline bool triangle_crossing_prepared(vec3 a, vec3 b, vec3 c, const struct triangle_ray *s, double *t,
                                              double *u, double *v) {
    /* The corners relative to the origin, in the ray's axes, sheared so that the ray runs along z: the
     * question is now whether the point (0, 0) lies in the 2D triangle (ax, ay), (bx, by), (cx, cy).
     * Each corner is transformed on its own, so a corner that two triangles share lands on the same
     * point for both. */
    vec3 o = s->ray.origin, pa = vec3_sub(a, o), pb = vec3_sub(b, o), pc = vec3_sub(c, o);
    double az = vec3_axis(pa, s->kz), bz = vec3_axis(pb, s->kz), cz = vec3_axis(pc, s->kz);
    double ax = vec3_axis(pa, s->kx) - s->sx * az, ay = vec3_axis(pa, s->ky) - s->sy * az;
    double bx = vec3_axis(pb, s->kx) - s->sx * bz, by = vec3_axis(pb, s->ky) - s->sy * bz;
    double cx = vec3_axis(pc, s->kx) - s->sx * cz, cy = vec3_axis(pc, s->ky) - s->sy * cz;

    /* (0, 0) is inside when it is on the same side of all three edges: all edge functions >= 0 or all
     * <= 0 (both windings, as triangles are two-sided). Zero means on the edge, which is inside for
     * both triangles that share it; NaN (a NaN corner or direction) fails both tests. */
    double w_a = triangle_edge_function(bx, by, cx, cy); /* opposite a: a's barycentric weight */
    double w_b = triangle_edge_function(cx, cy, ax, ay);
    double w_c = triangle_edge_function(ax, ay, bx, by);
    bool inside_positive = w_a >= 0.0 && w_b >= 0.0 && w_c >= 0.0;
    bool inside_negative = w_a <= 0.0 && w_b <= 0.0 && w_c <= 0.0;
    if (!inside_positive && !inside_negative)
        return false;
    double det = w_a + w_b + w_c; /* twice the 2D triangle's signed area */
    if (det == 0.0)
        return false;
    /* Exactly collinear corners have no normal to shade with, even if rounding gave their 2D image an
     * area. Checked here, on the rare path of a crossing, so the common path of a miss pays nothing. */
    if (triangle_corners_collinear(a, b, c))
        return false;

    /* The depths of the corners along the ray, weighted by their barycentric coordinates. */
    double inv_det = 1.0 / det;
    *t = (w_a * az + w_b * bz + w_c * cz) * s->sz * inv_det;
    *u = w_b * inv_det;
    *v = w_c * inv_det;
    return true;
}

/* The watertight test (triangle_crossing_prepared) for a ray not made ready beforehand. The kd-tree
 * and the BVH of chapters 9 and 10 call it, or the prepared form, on the corners the mesh holds, so
 * they find exactly the t and the face the brute-force loop finds. Counts nothing. */
static inline bool triangle_crossing(vec3 a, vec3 b, vec3 c, const ray *r, double *t, double *u, double *v) {
    struct triangle_ray s = triangle_ray_make(r);
    return triangle_crossing_prepared(a, b, c, &s, t, u, v);
}

/* Finds where ray r meets the triangle (a, b, c) with t_min < t < t_max, by the watertight test. On a
 * hit returns true and stores t and the barycentric coordinates u, v of the hit (P = (1-u-v)a + ub +
 * vc); points on edges and corners count as inside. Both faces are hit (two-sided). A ray parallel to
 * the triangle's plane, or a triangle of zero area, is a miss. No absolute epsilon is used, so tiny
 * triangles are hit too. Counts one triangle test. */
bool triangle_intersect(vec3 a, vec3 b, vec3 c, const ray *r, double t_min, double t_max, double *t,
                        double *u, double *v);

/* triangle_intersect for a ray made ready by triangle_ray_make: the same answer, without the per-ray
 * work. Counts one triangle test. */
bool triangle_intersect_prepared(vec3 a, vec3 b, vec3 c, const struct triangle_ray *s, double t_min, double t_max,
                                 double *t, double *u, double *v);

/* Tests r against triangles[0..count) for hits with t_min < t < h->t and keeps the nearest in *h.
 * Returns true when *h was replaced. */
bool triangle_closest(const struct triangle *triangles, size_t count, const ray *r, double t_min,
                      struct hit *h);

struct mesh; /* mesh.h (chapter 3) */

/* Tests r against every face of mesh m, one by one (the brute-force loop that chapters 9 and 10
 * accelerate), for hits with t_min < t < h->t; keeps the nearest in *h with the given material, and in
 * h->face the face's index within m. Returns true when *h was replaced. */
bool triangle_mesh_closest(const struct mesh *m, int material, const ray *r, double t_min, struct hit *h);

/* Below this length, (b - a) x (c - a) is scaled before it is normalised: its square (1e-300) is still
 * far above the smallest normal double, 2.2e-308. */
#define TRIANGLE_NORMAL_MIN_LENGTH 1e-150

/* Returns the unit normal (b - a) x (c - a) of the triangle, by the right-hand rule on its winding,
 * however thin the triangle (not zero: its corners not on one line). */
vec3 triangle_normal(vec3 a, vec3 b, vec3 c);

/* ---- what keeps the acceleration structures' answers the brute-force loop's (chapters 9 to 11) -- */

/* How far outside a triangle the watertight test may report a hit: for a ray starting within a thousand
 * mesh sizes, under about 1e-16 of its distance (triangle.c). The structures grow the box around every
 * triangle by this fraction of the mesh's size, 2^-20 (about 1e-6): ten orders of magnitude more than
 * the rounding, and too little to show in the counters. */
#define TRIANGLE_BOX_PAD (1.0 / 1048576.0)

/* Returns how far the structures grow the box around every face of m, on every side: TRIANGLE_BOX_PAD
 * times the longest side of the box around the corners m's faces use (corners beyond double's range,
 * NaN, left out); 0 when m has no faces. */
double triangle_box_pad(const struct mesh *m);

/* Returns triangle_box_pad's pad for faces whose corners the box from lo to hi holds (the least and
 * greatest of their coordinates, NaN left out): TRIANGLE_BOX_PAD times its longest side. */
double triangle_box_pad_between(vec3 lo, vec3 hi);

/* The exception to that bound: a triangle whose edges b - a and c - a are this close to parallel (the
 * sine of the angle between them is below it, yet not zero). Its test divides by a value that is
 * mostly rounding noise and can report a hit far outside the triangle (measured: 2.6e-4 away, for a
 * triangle whose middle corner is the midpoint of its long edge), so no box can be trusted to hold its
 * hits. Above 1e-6 the error stays below 1e-9 of the ray's distance, well inside the pad. */
#define TRIANGLE_SLIVER_SINE 1e-6

/* Returns true when the triangle (a, b, c) is such a sliver: the structures keep it out of their trees
 * and test it for every ray. Real meshes have few or none. A triangle whose edges have an exactly zero
 * cross product is not a sliver: the test never reports a hit on it. */
bool triangle_is_sliver(vec3 a, vec3 b, vec3 c);

/* The brute-force loop's choice among the faces a ray hits, for a structure that meets them in another
 * order: a hit at t on face `face` replaces the best so far (best_t, on best_face) when it is nearer, or
 * as near on a lower face, since the loop, going up the faces, keeps the first of equal t. */
static inline bool triangle_hit_wins(double t, uint32_t face, double best_t, uint32_t best_face) {
    return t < best_t || (t == best_t && face < best_face);
}

/* ---- the `triangle` line: triangle a X Y Z b X Y Z c X Y Z [material NAME] --------------------- */

/* The largest coordinate a triangle's corner may have, for `triangle` directives and placed meshes
 * alike. The acceleration structures keep boxes in float and the SAH multiplies two sides of a box in
 * float: a side up to 2e18 keeps that area (4e36) below float's largest, 3.4e38, where a corner at
 * 1e39 would not even fit a float box. */
#define TRIANGLE_MAX_COORD KEY_MAX_COORD /* 1e18, shape.h */

/* Returns true when every coordinate of p is within -TRIANGLE_MAX_COORD .. TRIANGLE_MAX_COORD (false
 * for infinity and NaN too). */
static inline bool triangle_corner_in_range(vec3 p) {
    return fabs(p.x) <= TRIANGLE_MAX_COORD && fabs(p.y) <= TRIANGLE_MAX_COORD && fabs(p.z) <= TRIANGLE_MAX_COORD;
}

/* The triangle's scene-file line (triangle_syntax.c, chapter 1), and the `triangle` lines as a kind
 * of shape (shape.h). Mesh faces are not among them: the world tests them behind their boxes, or
 * through a kd-tree or BVH. */
extern const struct shape_syntax triangle_syntax;
extern const struct shape_kind triangle_kind;

#endif

/* transform.h: affine transforms of points, directions, normals and boxes, for placing instances (chapter 16).
 *
 * A transform maps x to M x + t, M a 3 x 3 matrix and t a translation, stored together as the rows of
 * a 3 x 4 matrix whose last column is t. An instance carries one from its object's space to the world
 * and its inverse back: a ray goes into object space through the inverse, a hit comes back through the
 * transform, and a normal comes back through the inverse's transpose (a normal is not a direction: it
 * stays perpendicular to the surface only that way when the scale is not the same on every axis). */
#ifndef WHITTED_TRANSFORM_H
#define WHITTED_TRANSFORM_H

#include <stdbool.h>

#include "aabb.h"
#include "vec3.h"

/* The largest condition number (||M|| ||M^-1||, in the largest-row-sum norm) transform_invert accepts.
 * An inverse loses about log10 of the condition number of double's sixteen digits: at 1e10 six are
 * left, enough to carry a ray into object space and hit the object within a millionth of its size.
 * A scale of 1e-9 on one axis and 1 on the others (an object flattened a billion times) is still
 * accepted; a matrix that squashes space onto a plane or a line (scale 0) is singular and refused. */
#define TRANSFORM_CONDITION_MAX 1e10

/* How far transform_point's result may lie from mesh_transform's for the same pose (uniform scale s,
 * the same rotate and translate) in any coordinate, in units of DBL_EPSILON * (|s| |x|_1 + |t|_inf),
 * x the object point: both compute the same exact number with a handful of roundings each (the
 * matrix's entries are products of up to three sines and cosines and the scale, then a row times x,
 * against mesh.c's three turns in turn). Measured on random poses: at most 1.3 (tests/test_transform.c
 * checks the bound). When at most one angle is not a multiple of 90 degrees and the scale is a power of
 * two, or every angle is a multiple of 90 degrees, the two agree exactly. */
#define TRANSFORM_MESH_ROUNDING 4.0

struct transform {
    double m[3][4]; /* x'_i = m[i][0] x + m[i][1] y + m[i][2] z + m[i][3] */
};

/* Returns the transform that leaves every point where it is. */
struct transform transform_identity(void);

/* Returns the transform of a pose: x' = translate + Rz Ry Rx (scale * x), scale per axis (non-uniform
 * allowed), rotations in degrees about x, then y, then z, in POV-Ray's sense; POV-Ray's `scale <sx, sy,
 * sz> rotate <rx, ry, rz> translate <tx, ty, tz>` and the mesh line's order. The sines and cosines are
 * mesh.c's (exact at multiples of 90 degrees) and the matrix's columns are mesh.c's turn of the scaled
 * axes, so that for a uniform scale transform_point agrees with mesh_transform within
 * TRANSFORM_MESH_ROUNDING (exactly in the cases named there). The caller checks that the scale is not
 * zero (transform_invert refuses the result otherwise). */
struct transform transform_from_pose(vec3 scale, vec3 rotate_degrees, vec3 translate);

/* Returns a after b: the transform taking x to a(b(x)). */
struct transform transform_compose(const struct transform *a, const struct transform *b);

/* Stores the inverse of t in *inverse and returns true; returns false, leaving *inverse alone, when t's
 * matrix is singular (determinant zero or not finite) or ill-conditioned (condition number above
 * TRANSFORM_CONDITION_MAX, or not finite). Computed from the cofactors (the adjugate over the
 * determinant): compose(inverse, t) is the identity within about the condition number times
 * DBL_EPSILON (tests/test_transform.c states and checks the tolerance). */
bool transform_invert(const struct transform *t, struct transform *inverse);

/* Returns M p + t, summed in the order m[i][0] p.x + m[i][1] p.y + m[i][2] p.z, then + t_i. Each
 * coordinate of the result, as computed with its roundings, grows or falls with each coordinate of p
 * (rounding is monotone), so a box's eight corners bound the images of all its points
 * (transform_box). */
vec3 transform_point(const struct transform *t, vec3 p);

/* Returns M v: a direction or a difference of points (no translation). Its length changes with the
 * scale; a ray's direction carried this way keeps the ray's parameter t the same in both spaces. */
vec3 transform_vector(const struct transform *t, vec3 v);

/* Returns (M^-1)^T n, `inverse` being the inverse of the transform that carries the surface: the normal
 * of the carried surface, perpendicular to every carried tangent (transform_vector). Not of unit length:
 * the caller normalises it. */
vec3 transform_normal(const struct transform *inverse, vec3 n);

/* Returns the smallest box holding transform_point of box's eight corners, which holds transform_point
 * of every point of box (see transform_point). The empty box comes back empty. */
struct aabb transform_box(const struct transform *t, struct aabb box);

#endif

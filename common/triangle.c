/* triangle.c: ray-triangle intersection, Moller-Trumbore and the watertight test (chapter 3).
 *
 * Moller-Trumbore (Moller and Trumbore, "Fast, minimum storage ray-triangle intersection", Journal of
 * Graphics Tools 2(1), 1997) solves O + tD = (1-u-v)A + uB + vC for (t, u, v) by Cramer's rule, with
 * E1 = B - A, E2 = C - A, T = O - A, P = D x E2, Q = T x E1 and det = E1 . P:
 *     u = (T . P) / det,   v = (D . Q) / det,   t = (E2 . Q) / det.
 * The hit is inside when u >= 0, v >= 0 and u + v <= 1. Chapter 3 teaches it first. But u and v are
 * rounded per triangle: a ray that meets the edge two triangles share can find u slightly below 0 in
 * one and u + v slightly above 1 in the other, and pass between them.
 *
 * The tracer therefore uses the watertight test (triangle.h, where the acceleration structures can
 * inline it). It moves the ray to the z axis by a shear, so that the question becomes whether the
 * point (0, 0) is inside a 2D triangle, and answers it with three edge functions, each computed from
 * its edge's two corners alone. Why no ray can pass between two triangles that share an edge:
 *  1. Each corner is transformed on its own, by arithmetic that depends only on the corner and the
 *     ray. A shared corner lands on the same 2D point, to the last bit, for every triangle using it.
 *  2. A shared edge's function is computed from the same two points in both triangles, in opposite
 *     order for a consistently wound mesh: the same two rounded products, subtracted the other way,
 *     which gives exactly the negative (floating-point subtraction is antisymmetric). So the two
 *     triangles never disagree about the side of the edge the ray passes, and when the ray is exactly
 *     on it (zero), both count it as inside: the tie rule. Had zero counted as outside for both, a
 *     ray through the edge would miss both, the very leak this replaces.
 *  3. Every sign is exact: if px qy > py qx exactly, the rounded products keep that order (rounding
 *     is monotonic), so when they differ their difference has the exact sign. When they round alike,
 *     the exact difference is that of their rounding errors, each given exactly by fma, and the edge
 *     function returns that rather than 0 (swapped, the errors swap: still the exact negative). So
 *     the computed test is the exact test on the rounded 2D corners, and those still form a closed
 *     surface: in exact arithmetic no line passes between closed triangles that share their edges and
 *     corners. The same holds at shared corners, not only along edges. (A triangle whose three edge
 *     functions are exactly zero is seen edge-on and missed; the ray then runs along it and meets the
 *     triangles beside it, which are not edge-on.)
 * This needs the products rounded on their own, not fused into one multiply-add: the Makefile builds
 * with -ffp-contract=off. Woop, Benthin and Wald recompute an edge function of their float test in
 * double when it comes out zero; we compute in double and recompute a zero from the rounding errors.
 * Returning the zero made a triangle a unit in the last place across, 1.6 units from a ray, count as
 * crossed by it. Products beyond about 1e300 (overflow) would break 3; rounding errors below the
 * smallest double (products below about 1e-290) can only turn an exact sign back into zero, the tie
 * rule's inside, never into the other sign.
 *
 * How exact t is. With all three weights of one sign, t = sz (w_a az + w_b bz + w_c cz) / det is a
 * weighted mean of the corners' depths along the ray: it cannot leave their range, and its rounding
 * error is a few units in the last place of the farthest corner's depth, as for Moller-Trumbore (whose
 * t, on a needle-thin triangle, can land far outside the triangle). The corners' 2D positions are off
 * by a few units in the last place of their distance from the origin, so a reported hit lies within
 * about 1e-16 of that distance of the triangle: the acceleration structures' box pads (2^-20 of the
 * mesh's size) cover that by far.
 *
 * The seed (like many tutorials) rejects |det| < EPSILON with a fixed EPSILON in Moller-Trumbore. That
 * makes small triangles invisible: det scales with the triangle's area, so a triangle with 1e-3 edges
 * has det around 1e-6 and would be rejected by EPSILON = 1e-6 although the ray meets it squarely. Both
 * tests here reject only det == 0 (ray exactly parallel, or zero area). */
#include "triangle.h"

#include "hit.h"
#include "mesh.h"
#include "stats.h"

/* TASK 3.1: Moller-Trumbore ray-triangle intersection */
bool triangle_crossing_mt(vec3 a, vec3 b, vec3 c, const ray *r, double *t, double *u, double *v) {
    vec3 edge1 = vec3_sub(b, a), edge2 = vec3_sub(c, a);
    vec3 p = vec3_cross(r->direction, edge2);
    double det = vec3_dot(edge1, p);
    if (det == 0.0)
        return false;
    double inv_det = 1.0 / det;
    vec3 to_origin = vec3_sub(r->origin, a);
    double hit_u = vec3_dot(to_origin, p) * inv_det;
    if (hit_u < 0.0 || hit_u > 1.0)
        return false;
    vec3 q = vec3_cross(to_origin, edge1);
    double hit_v = vec3_dot(r->direction, q) * inv_det;
    if (hit_v < 0.0 || hit_u + hit_v > 1.0)
        return false;
    /* Two equal corners give det = 0 only in exact arithmetic: rounding can leave a tiny det and noise
     * for u and v that passes the tests above, and such a triangle has no normal to shade with. Its
     * area is checked here, on the rare path of a crossing, so the common path of a miss pays nothing. */
    vec3 area = vec3_cross(edge1, edge2);
    if (area.x == 0.0 && area.y == 0.0 && area.z == 0.0)
        return false;
    *t = vec3_dot(edge2, q) * inv_det;
    *u = hit_u;
    *v = hit_v;
    return true;
}

bool triangle_intersect_prepared(vec3 a, vec3 b, vec3 c, const struct triangle_ray *s, double t_min, double t_max,
                                 double *t, double *u, double *v) {
    stats_thread.triangle_tests++;
    double hit_t, hit_u, hit_v;
    if (!triangle_crossing_prepared(a, b, c, s, &hit_t, &hit_u, &hit_v))
        return false;
    if (!(hit_t > t_min && hit_t < t_max))
        return false;
    *t = hit_t;
    *u = hit_u;
    *v = hit_v;
    return true;
}

bool triangle_intersect(vec3 a, vec3 b, vec3 c, const ray *r, double t_min, double t_max, double *t,
                        double *u, double *v) {
    struct triangle_ray s = triangle_ray_make(r);
    return triangle_intersect_prepared(a, b, c, &s, t_min, t_max, t, u, v);
}

bool triangle_closest(const struct triangle *triangles, size_t count, const ray *r, double t_min,
                      struct hit *h) {
    const struct triangle *nearest = NULL;
    struct triangle_ray s = triangle_ray_make(r);
    double u, v;
    for (size_t k = 0; k < count; k++) {
        const struct triangle *tri = &triangles[k];
        if (triangle_intersect_prepared(tri->a, tri->b, tri->c, &s, t_min, h->t, &h->t, &u, &v))
            nearest = tri;
    }
    if (nearest == NULL)
        return false;
    h->normal = triangle_normal(nearest->a, nearest->b, nearest->c);
    h->material = nearest->material;
    h->object = (int)(nearest - triangles); /* world_closest turns it into the object's number */
    return true;
}

bool triangle_mesh_closest(const struct mesh *m, int material, const ray *r, double t_min, struct hit *h) {
    const struct mesh_face *nearest = NULL;
    struct triangle_ray s = triangle_ray_make(r);
    double u, v;
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *corner = m->faces[k].v;
        if (triangle_intersect_prepared(m->vertices[corner[0]], m->vertices[corner[1]], m->vertices[corner[2]], &s,
                                        t_min, h->t, &h->t, &u, &v))
            nearest = &m->faces[k];
    }
    if (nearest == NULL)
        return false;
    h->normal = triangle_normal(m->vertices[nearest->v[0]], m->vertices[nearest->v[1]], m->vertices[nearest->v[2]]);
    h->material = material;
    h->face = (int)(nearest - m->faces); /* within the mesh; the caller sets the mesh's object number */
    return true;
}

vec3 triangle_normal(vec3 a, vec3 b, vec3 c) {
    vec3 n = vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
    /* A thin triangle's cross product can be so short that its squared length vanishes (a triangle 2
     * long and 1e-170 wide gave an infinite normal and NaN pixels): its largest component is divided
     * out first. Any other keeps the plain formula, bit for bit. */
    return vec3_normalize(vec3_length(n) >= TRIANGLE_NORMAL_MIN_LENGTH ? n : vec3_unit_max(n));
}

double triangle_box_pad(const struct mesh *m) {
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t f = 0; f < m->face_count; f++)
        for (int c = 0; c < 3; c++) {
            vec3 p = m->vertices[m->faces[f].v[c]];
            lo = vec3_min(p, lo); /* p first: a NaN coordinate of p compares false and leaves lo alone */
            hi = vec3_max(p, hi);
        }
    return m->face_count > 0 ? triangle_box_pad_between(lo, hi) : 0.0;
}

double triangle_box_pad_between(vec3 lo, vec3 hi) {
    vec3 side = vec3_sub(hi, lo);
    return TRIANGLE_BOX_PAD * fmax(side.x, fmax(side.y, side.z));
}

bool triangle_is_sliver(vec3 a, vec3 b, vec3 c) {
    vec3 e1 = vec3_sub(b, a), e2 = vec3_sub(c, a);
    double cross = vec3_length(vec3_cross(e1, e2));
    return cross > 0.0 && cross < TRIANGLE_SLIVER_SINE * vec3_length(e1) * vec3_length(e2);
}

/* ---- the `triangle` directive as one kind of shape (shape.h) ------------------------------------ */

static bool closest_triangles(const void *items, size_t count, const ray *r, double t_min, struct hit *h) {
    return triangle_closest(items, count, r, t_min, h);
}

static bool triangle_crossings(const void *items, size_t count, const ray *r, double t_min, double t_max,
                               shape_crossing_visitor visit, void *context) {
    const struct triangle *triangles = items;
    struct triangle_ray prepared = triangle_ray_make(r); /* once for every triangle below */
    double t, u, v;
    for (size_t k = 0; k < count; k++) {
        const struct triangle *tri = &triangles[k];
        if (triangle_intersect_prepared(tri->a, tri->b, tri->c, &prepared, t_min, t_max, &t, &u, &v) &&
            !visit(context, t, tri->material))
            return false;
    }
    return true;
}

static bool triangle_bounds(const void *item, vec3 *min, vec3 *max) {
    const struct triangle *t = item;
    *min = vec3_min(t->a, vec3_min(t->b, t->c));
    *max = vec3_max(t->a, vec3_max(t->b, t->c));
    return true;
}

/* A single triangle has no inside (contains is NULL): only a closed mesh has one. */
const struct shape_kind triangle_kind = {
    .syntax = &triangle_syntax,
    .closest = closest_triangles,
    .crossings = triangle_crossings,
    .bounds = triangle_bounds,
};

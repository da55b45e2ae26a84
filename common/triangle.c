/* triangle.c: Moller-Trumbore ray-triangle intersection (chapter 3).
 *
 * Solve O + tD = (1-u-v)A + uB + vC for (t, u, v) by Cramer's rule, with E1 = B - A, E2 = C - A,
 * T = O - A, P = D x E2, Q = T x E1 and det = E1 . P:
 *     u = (T . P) / det,   v = (D . Q) / det,   t = (E2 . Q) / det.
 * The hit is inside when u >= 0, v >= 0 and u + v <= 1. Moller and Trumbore, "Fast, minimum storage
 * ray-triangle intersection", Journal of Graphics Tools 2(1), 1997.
 *
 * The seed (like many tutorials) rejects |det| < EPSILON with a fixed EPSILON. That makes small
 * triangles invisible: det scales with the triangle's area, so a triangle with 1e-3 edges has
 * det around 1e-6 and would be rejected by EPSILON = 1e-6 although the ray meets it squarely. Only
 * det == 0 (ray exactly parallel, or zero area) is a miss here; a nearly parallel ray gives a huge t or
 * out-of-range u, v, which the tests reject on their own. A triangle whose corners coincide is caught
 * on the hit path (see triangle_crossing in triangle.h, which holds the arithmetic). */
#include "triangle.h"

#include "stats.h"

bool triangle_intersect(vec3 a, vec3 b, vec3 c, const ray *r, double t_min, double t_max, double *t,
                        double *u, double *v) {
    stats_thread.triangle_tests++;
    double hit_t, hit_u, hit_v;
    if (!triangle_crossing(a, b, c, r, &hit_t, &hit_u, &hit_v))
        return false;
    if (!(hit_t > t_min && hit_t < t_max))
        return false;
    *t = hit_t;
    *u = hit_u;
    *v = hit_v;
    return true;
}

bool triangle_closest(const struct triangle *triangles, size_t count, const ray *r, double t_min,
                      struct hit *h) {
    const struct triangle *nearest = NULL;
    double u, v;
    for (size_t k = 0; k < count; k++) {
        const struct triangle *tri = &triangles[k];
        if (triangle_intersect(tri->a, tri->b, tri->c, r, t_min, h->t, &h->t, &u, &v))
            nearest = tri;
    }
    if (nearest == NULL)
        return false;
    h->normal = triangle_normal(nearest->a, nearest->b, nearest->c);
    h->material = nearest->material;
    return true;
}

bool triangle_mesh_closest(const struct mesh *m, int material, const ray *r, double t_min, struct hit *h) {
    const struct mesh_face *nearest = NULL;
    double u, v;
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *corner = m->faces[k].v;
        if (triangle_intersect(m->vertices[corner[0]], m->vertices[corner[1]], m->vertices[corner[2]], r,
                               t_min, h->t, &h->t, &u, &v))
            nearest = &m->faces[k];
    }
    if (nearest == NULL)
        return false;
    h->normal = triangle_normal(m->vertices[nearest->v[0]], m->vertices[nearest->v[1]], m->vertices[nearest->v[2]]);
    h->material = material;
    return true;
}

vec3 triangle_normal(vec3 a, vec3 b, vec3 c) {
    return vec3_normalize(vec3_cross(vec3_sub(b, a), vec3_sub(c, a)));
}

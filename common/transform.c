/* transform.c: affine transforms of points, directions, normals and boxes, for placing instances (chapter 16).
 *
 * The pose's rotation uses mesh.c's sines, cosines and turns (mesh_turn_point), so that an instance
 * rounds as the same mesh written out in world space does wherever one matrix can (transform.h). */
#include "transform.h"

#include <math.h>

#include "mesh.h"

struct transform transform_identity(void) {
    return (struct transform){{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
}

/* Sets column `column` of t's matrix (0..2 the axes, 3 the translation) to v. */
static void set_column(struct transform *t, int column, vec3 v) {
    t->m[0][column] = v.x;
    t->m[1][column] = v.y;
    t->m[2][column] = v.z;
}

struct transform transform_from_pose(vec3 scale, vec3 rotate_degrees, vec3 translate) {
    struct mesh_turn turn = mesh_turn_from_degrees(rotate_degrees);
    struct transform t;
    /* Column j of M is where the object's axis j goes: scaled, then turned. */
    set_column(&t, 0, mesh_turn_point(&turn, vec3_make(scale.x, 0, 0)));
    set_column(&t, 1, mesh_turn_point(&turn, vec3_make(0, scale.y, 0)));
    set_column(&t, 2, mesh_turn_point(&turn, vec3_make(0, 0, scale.z)));
    set_column(&t, 3, translate);
    return t;
}

struct transform transform_compose(const struct transform *a, const struct transform *b) {
    struct transform c;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 4; j++) {
            double sum = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] + a->m[i][2] * b->m[2][j];
            c.m[i][j] = j == 3 ? sum + a->m[i][3] : sum; /* b's translation is carried by a, then a's added */
        }
    }
    return c;
}

/* Returns the largest sum of |entries| of a row of the 3 x 3 part of t: the matrix norm that bounds how
 * much M can stretch a vector in the largest-coordinate norm. */
static double row_sum_norm(const struct transform *t) {
    double largest = 0.0;
    for (int i = 0; i < 3; i++)
        largest = fmax(largest, fabs(t->m[i][0]) + fabs(t->m[i][1]) + fabs(t->m[i][2]));
    return largest;
}

bool transform_invert(const struct transform *t, struct transform *inverse) {
    const double (*m)[4] = t->m;
    /* The cofactors, transposed: the adjugate. inv[i][j] = cofactor(j, i) / det. */
    double adjugate[3][3] = {
        {m[1][1] * m[2][2] - m[1][2] * m[2][1], m[0][2] * m[2][1] - m[0][1] * m[2][2],
         m[0][1] * m[1][2] - m[0][2] * m[1][1]},
        {m[1][2] * m[2][0] - m[1][0] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0],
         m[0][2] * m[1][0] - m[0][0] * m[1][2]},
        {m[1][0] * m[2][1] - m[1][1] * m[2][0], m[0][1] * m[2][0] - m[0][0] * m[2][1],
         m[0][0] * m[1][1] - m[0][1] * m[1][0]},
    };
    double determinant = m[0][0] * adjugate[0][0] + m[0][1] * adjugate[1][0] + m[0][2] * adjugate[2][0];
    if (!(determinant != 0.0 && isfinite(determinant)))
        return false;
    struct transform result;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            result.m[i][j] = adjugate[i][j] / determinant;
    /* x = M^-1 (x' - t) = M^-1 x' - M^-1 t. */
    vec3 moved_back = transform_vector(&result, vec3_make(m[0][3], m[1][3], m[2][3]));
    set_column(&result, 3, vec3_neg(moved_back));
    double condition = row_sum_norm(t) * row_sum_norm(&result);
    if (!(condition <= TRANSFORM_CONDITION_MAX) || !vec3_is_finite(moved_back))
        return false;
    *inverse = result;
    return true;
}

vec3 transform_point(const struct transform *t, vec3 p) {
    const double (*m)[4] = t->m;
    return vec3_make(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                     m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                     m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]);
}

vec3 transform_vector(const struct transform *t, vec3 v) {
    const double (*m)[4] = t->m;
    return vec3_make(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                     m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

vec3 transform_normal(const struct transform *inverse, vec3 n) {
    const double (*m)[4] = inverse->m; /* row i of the transpose is column i of the inverse */
    return vec3_make(m[0][0] * n.x + m[1][0] * n.y + m[2][0] * n.z, m[0][1] * n.x + m[1][1] * n.y + m[2][1] * n.z,
                     m[0][2] * n.x + m[1][2] * n.y + m[2][2] * n.z);
}

struct aabb transform_box(const struct transform *t, struct aabb box) {
    struct aabb result = aabb_empty();
    if (!(box.min.x <= box.max.x && box.min.y <= box.max.y && box.min.z <= box.max.z))
        return result;
    for (int corner = 0; corner < 8; corner++) {
        vec3 p = vec3_make(corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                           corner & 4 ? box.max.z : box.min.z);
        result = aabb_grow(result, transform_point(t, p));
    }
    return result;
}

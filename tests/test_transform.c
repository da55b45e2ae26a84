/* test_transform.c: chapter 16's affine transforms: a pose rounds as mesh_transform does (exactly
 * where one matrix can, within TRANSFORM_MESH_ROUNDING elsewhere), the inverse undoes the transform
 * within a stated tolerance and refuses singular and ill-conditioned matrices, normals carried by the
 * inverse transpose stay perpendicular to carried tangents (and by the matrix itself do not), and a
 * carried box holds every carried point. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "mesh.h"
#include "transform.h"
#include "uniform.h"

/* Returns mesh_transform's image of p (a one-vertex mesh). */
static vec3 mesh_place(vec3 p, double scale, vec3 rotate, vec3 translate) {
    vec3 vertex = p;
    struct mesh m = {.vertices = &vertex, .vertex_count = 1};
    mesh_transform(&m, scale, rotate, translate);
    return vertex;
}

static double largest_abs(vec3 a) { return fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z))); }

#define CASES 2000

/* ---- a pose against mesh_transform -------------------------------------------------------------- */

Test(transform, identity_leaves_points_and_directions_alone) {
    struct transform id = transform_identity();
    vec3 p = {1.5, -2.25, 1e300};
    vec3 q = transform_point(&id, p), v = transform_vector(&id, p);
    cr_expect(q.x == p.x && q.y == p.y && q.z == p.z && v.x == p.x && v.y == p.y && v.z == p.z);
}

Test(transform, quarter_turns_go_where_povray_sends_them) {
    vec3 one = {1, 1, 1}, zero = {0, 0, 0};
    struct transform about_x = transform_from_pose(one, vec3_make(90, 0, 0), zero);
    struct transform about_y = transform_from_pose(one, vec3_make(0, 90, 0), zero);
    struct transform about_z = transform_from_pose(one, vec3_make(0, 0, 90), zero);
    vec3 a = transform_point(&about_x, vec3_make(0, 1, 0)); /* y to z */
    vec3 b = transform_point(&about_y, vec3_make(1, 0, 0)); /* x to -z */
    vec3 c = transform_point(&about_z, vec3_make(1, 0, 0)); /* x to y */
    cr_expect(a.x == 0 && a.y == 0 && a.z == 1, "(%g %g %g)", a.x, a.y, a.z);
    cr_expect(b.x == 0 && b.y == 0 && b.z == -1, "(%g %g %g)", b.x, b.y, b.z);
    cr_expect(c.x == 0 && c.y == 1 && c.z == 0, "(%g %g %g)", c.x, c.y, c.z);
    /* scale first, then rotate, then translate: (1, 0, 0) scaled by 2 on x, turned to y, moved by 5 */
    struct transform pose = transform_from_pose(vec3_make(2, 3, 4), vec3_make(0, 0, 90), vec3_make(5, 5, 5));
    vec3 d = transform_point(&pose, vec3_make(1, 0, 0));
    cr_expect(d.x == 5 && d.y == 7 && d.z == 5, "(%g %g %g)", d.x, d.y, d.z);
}

/* Expects transform_point and mesh_transform to agree exactly (== on each coordinate: only the sign of
 * a zero may differ) on random points for the pose. */
static void expect_same_as_mesh(double scale, vec3 rotate, vec3 translate, uint32_t stream) {
    struct transform t = transform_from_pose(vec3_make(scale, scale, scale), rotate, translate);
    for (uint32_t k = 0; k < 50; k++) {
        vec3 p = uniform_vec3(stream, k, -10, 10);
        vec3 a = transform_point(&t, p), b = mesh_place(p, scale, rotate, translate);
        cr_assert(a.x == b.x && a.y == b.y && a.z == b.z,
                  "scale %g rotate %g %g %g: (%.17g %.17g %.17g) against mesh_transform's (%.17g %.17g %.17g)", scale,
                  rotate.x, rotate.y, rotate.z, a.x, a.y, a.z, b.x, b.y, b.z);
    }
}

Test(transform, one_angle_and_a_power_of_two_scale_round_exactly_as_mesh_transform) {
    static const double powers_of_two[] = {1, 2, 0.5, 1024, 0.125};
    for (uint32_t k = 0; k < CASES; k++) {
        double angle = uniform(1, k, -720, 720);
        int axis = (int)(k % 3);
        double quarter = 90.0 * (double)(k % 4) - 180.0; /* the other two axes: a multiple of 90 */
        vec3 rotate = axis == 0 ? vec3_make(angle, quarter, 0) : axis == 1 ? vec3_make(quarter, angle, -quarter)
                                                                           : vec3_make(0, quarter, angle);
        expect_same_as_mesh(powers_of_two[k % 5], rotate, uniform_vec3(2, k, -100, 100), k);
    }
}

Test(transform, quarter_turns_with_any_scale_round_exactly_as_mesh_transform) {
    for (uint32_t k = 0; k < CASES; k++) {
        vec3 rotate = vec3_make(90.0 * (double)(k % 5), -90.0 * (double)(k / 5 % 4), 270.0 * (double)(k / 20 % 3));
        expect_same_as_mesh(uniform(3, k, 0.01, 100), rotate, uniform_vec3(4, k, -100, 100), k);
    }
}

Test(transform, any_pose_is_within_the_stated_rounding_of_mesh_transform) {
    double worst = 0.0;
    bool some_differ = false;
    for (uint32_t k = 0; k < CASES; k++) {
        double scale = uniform(5, k, 0.01, 100);
        vec3 rotate = uniform_vec3(6, k, -360, 360), translate = uniform_vec3(7, k, -1000, 1000);
        struct transform t = transform_from_pose(vec3_make(scale, scale, scale), rotate, translate);
        for (uint32_t j = 0; j < 20; j++) {
            vec3 p = uniform_vec3(8, 20 * k + j, -10, 10);
            vec3 a = transform_point(&t, p), b = mesh_place(p, scale, rotate, translate);
            double unit = DBL_EPSILON * (fabs(scale) * (fabs(p.x) + fabs(p.y) + fabs(p.z)) + largest_abs(translate));
            double difference = largest_abs(vec3_sub(a, b)) / unit;
            some_differ = some_differ || difference > 0.0;
            worst = fmax(worst, difference);
        }
    }
    cr_log_info("transform_point against mesh_transform: at most %.2f units of the bound", worst);
    cr_expect(worst <= TRANSFORM_MESH_ROUNDING, "%.2f units apart, more than TRANSFORM_MESH_ROUNDING (%g)", worst,
              TRANSFORM_MESH_ROUNDING);
    cr_expect(some_differ, "three angles and any scale never differed: then the exact cases could be wider");
}

/* ---- composing and inverting -------------------------------------------------------------------- */

/* A random pose with a non-uniform scale (each axis 0.01 to 100, either sign). */
static struct transform random_pose(uint32_t k) {
    vec3 scale = uniform_vec3(10, k, 0.01, 100);
    if (k & 1)
        scale.y = -scale.y;
    return transform_from_pose(scale, uniform_vec3(11, k, -360, 360), uniform_vec3(12, k, -100, 100));
}

Test(transform, compose_is_one_after_the_other) {
    for (uint32_t k = 0; k < CASES; k++) {
        struct transform a = random_pose(k), b = random_pose(k + CASES);
        struct transform ab = transform_compose(&a, &b);
        vec3 p = uniform_vec3(13, k, -10, 10);
        vec3 direct = transform_point(&ab, p), stepwise = transform_point(&a, transform_point(&b, p));
        double size = largest_abs(stepwise) + 1e4 * 1e4; /* entries up to 1e4 after two scales of 100 */
        cr_assert(largest_abs(vec3_sub(direct, stepwise)) <= 64 * DBL_EPSILON * size, "case %u", k);
    }
}

/* The tolerance of transform_invert: compose(inverse, t) differs from the identity by at most
 * INVERSE_TOLERANCE * DBL_EPSILON * condition in each entry of the matrix, and the translation by at most
 * that times |t| / ||M|| (the translation's own scale in object space). */
#define INVERSE_TOLERANCE 4.0

/* The largest-row-sum norm of t's matrix. */
static double matrix_norm(const struct transform *t) {
    double largest = 0;
    for (int i = 0; i < 3; i++)
        largest = fmax(largest, fabs(t->m[i][0]) + fabs(t->m[i][1]) + fabs(t->m[i][2]));
    return largest;
}

/* Returns the largest departure of `product` from the identity, matrix entries and translation
 * measured apart: the matrix's in *matrix_error, the translation's in *translation_error. */
static void identity_error(const struct transform *product, double *matrix_error, double *translation_error) {
    *matrix_error = *translation_error = 0;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            *matrix_error = fmax(*matrix_error, fabs(product->m[i][j] - (i == j ? 1.0 : 0.0)));
        *translation_error = fmax(*translation_error, fabs(product->m[i][3]));
    }
}

Test(transform, the_inverse_undoes_the_transform_within_the_stated_tolerance) {
    double worst = 0;
    for (uint32_t k = 0; k < CASES; k++) {
        struct transform t = random_pose(k), inverse;
        cr_assert(transform_invert(&t, &inverse), "case %u refused", k);
        double condition = matrix_norm(&t) * matrix_norm(&inverse);
        double translation = fmax(fabs(t.m[0][3]), fmax(fabs(t.m[1][3]), fabs(t.m[2][3])));
        struct transform back = transform_compose(&inverse, &t), forth = transform_compose(&t, &inverse);
        double matrix_error, translation_error, matrix_error_2, translation_error_2;
        identity_error(&back, &matrix_error, &translation_error);
        identity_error(&forth, &matrix_error_2, &translation_error_2);
        double unit = DBL_EPSILON * condition;
        double measured = fmax(fmax(matrix_error, matrix_error_2) / unit,
                               translation_error / (unit * translation / matrix_norm(&t)));
        worst = fmax(worst, measured);
        cr_assert(measured <= INVERSE_TOLERANCE, "case %u: %g units from the identity (condition %g)", k, measured,
                  condition);
    }
    cr_log_info("inverse times transform: at most %.2f units of DBL_EPSILON * condition from the identity", worst);
}

Test(transform, invert_refuses_singular_and_ill_conditioned_matrices) {
    struct transform inverse = transform_identity(), untouched = inverse;
    vec3 turn = {10, 20, 30}, move = {1, 2, 3};
    struct transform flat = transform_from_pose(vec3_make(1, 0, 1), turn, move);
    cr_expect(!transform_invert(&flat, &inverse), "a zero scale squashes space onto a plane");
    struct transform nearly_flat = transform_from_pose(vec3_make(1, 1e-11, 1), turn, move);
    cr_expect(!transform_invert(&nearly_flat, &inverse), "condition 1e11 is above TRANSFORM_CONDITION_MAX");
    struct transform rank_two = {{{1, 2, 3, 0}, {2, 4, 6, 0}, {0, 0, 1, 0}}};
    cr_expect(!transform_invert(&rank_two, &inverse), "two rows in proportion");
    struct transform not_a_number = transform_identity();
    not_a_number.m[1][1] = NAN;
    cr_expect(!transform_invert(&not_a_number, &inverse));
    struct transform far = transform_identity();
    far.m[0][3] = INFINITY;
    cr_expect(!transform_invert(&far, &inverse), "an infinite translation");
    cr_expect(memcmp(&inverse, &untouched, sizeof inverse) == 0, "a refusal left *inverse alone");
    /* What is accepted: flattened a billion times, and tiny or huge but the same on every axis. */
    struct transform thin = transform_from_pose(vec3_make(1, 1e-9, 1), turn, move);
    cr_expect(transform_invert(&thin, &inverse));
    struct transform tiny = transform_from_pose(vec3_make(1e-9, 1e-9, 1e-9), turn, move);
    cr_expect(transform_invert(&tiny, &inverse));
    struct transform huge = transform_from_pose(vec3_make(1e9, -1e9, 1e9), turn, move);
    cr_expect(transform_invert(&huge, &inverse));
}

/* ---- normals ------------------------------------------------------------------------------------ */

/* Returns the largest |cos| of the angle between a carried normal (by `carry`: 0 the inverse
 * transpose, 1 the matrix itself) and the carried tangents of random planes, over CASES poses with
 * non-uniform scale. */
static double worst_cosine(int carry) {
    double worst = 0;
    for (uint32_t k = 0; k < CASES; k++) {
        struct transform t = random_pose(k), inverse;
        cr_assert(transform_invert(&t, &inverse));
        vec3 n = vec3_normalize(uniform_vec3(20, k, -1, 1));
        vec3 tangent = vec3_normalize(vec3_cross(n, uniform_vec3(21, k, -1, 1)));
        vec3 bitangent = vec3_cross(n, tangent);
        vec3 world_n = carry == 0 ? transform_normal(&inverse, n) : transform_vector(&t, n);
        vec3 ends[2] = {transform_vector(&t, tangent), transform_vector(&t, bitangent)};
        for (int e = 0; e < 2; e++)
            worst = fmax(worst, fabs(vec3_dot(world_n, ends[e])) / (vec3_length(world_n) * vec3_length(ends[e])));
    }
    return worst;
}

/* A carried normal is perpendicular to carried tangents within this cosine (8e-16 measured). */
#define NORMAL_COSINE_TOLERANCE 1e-12

Test(transform, normals_by_the_inverse_transpose_stay_perpendicular_under_non_uniform_scale) {
    double by_inverse_transpose = worst_cosine(0), by_the_matrix = worst_cosine(1);
    cr_log_info("largest |cos|: %.3g by the inverse transpose, %.3g by the matrix", by_inverse_transpose,
                by_the_matrix);
    cr_expect(by_inverse_transpose <= NORMAL_COSINE_TOLERANCE, "%g", by_inverse_transpose);
    /* The gallery's fault, the normal carried by the matrix: far from perpendicular (the test can fail). */
    cr_expect(by_the_matrix > 0.5, "%g", by_the_matrix);
}

/* ---- boxes -------------------------------------------------------------------------------------- */

Test(transform, a_carried_box_holds_every_carried_point) {
    for (uint32_t k = 0; k < CASES; k++) {
        struct transform t = random_pose(k);
        vec3 a = uniform_vec3(30, k, -5, 5), b = uniform_vec3(31, k, -5, 5);
        struct aabb box = {vec3_min(a, b), vec3_max(a, b)};
        struct aabb carried = transform_box(&t, box);
        for (uint32_t j = 0; j < 20; j++) {
            vec3 f = uniform_vec3(32, 20 * k + j, 0, 1);
            vec3 p = vec3_make(box.min.x + f.x * (box.max.x - box.min.x), box.min.y + f.y * (box.max.y - box.min.y),
                               box.min.z + f.z * (box.max.z - box.min.z));
            p = vec3_min(vec3_max(p, box.min), box.max);
            vec3 q = transform_point(&t, p);
            struct aabb point = {q, q};
            cr_assert(aabb_holds(&carried, &point), "case %u point %u outside its box", k, j);
        }
    }
}

Test(transform, a_unit_cube_turned_45_degrees_is_root_2_wide) {
    struct aabb cube = {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};
    struct transform t = transform_from_pose(vec3_make(1, 1, 1), vec3_make(0, 0, 45), vec3_make(10, 0, 0));
    struct aabb turned = transform_box(&t, cube);
    cr_expect_float_eq(turned.max.x - turned.min.x, sqrt(2.0), 1e-15);
    cr_expect_float_eq(turned.max.y, sqrt(0.5), 1e-15);
    cr_expect_float_eq(turned.min.x, 10 - sqrt(0.5), 1e-14);
    cr_expect(turned.min.z == -0.5 && turned.max.z == 0.5);
    struct aabb empty = transform_box(&t, aabb_empty());
    cr_expect(empty.min.x > empty.max.x, "the empty box stays empty");
}

/* test_geometry.c: unit tests of the geometric core against closed-form answers: vectors, the camera,
 * the sphere, triangle and plane intersections, the slab test, 8-bit quantisation and PNG files, and the
 * headlight shading. Every expected value is worked out by hand in the comments next to it. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "aabb.h"
#include "box.h"
#include "camera.h"
#include "headlight.h"
#include "image.h"
#include "plane.h"
#include "sphere.h"
#include "speck_triangle.h"
#include "stats.h"
#include "triangle.h"

#define EXACT 0.0     /* for results that are exact in binary floating point */
#define CLOSE 1e-12   /* for results that go through a square root or a division */

/* ---- helpers ----------------------------------------------------------------------------------- */

static void assert_vec3_near(vec3 got, vec3 want, double tolerance, const char *what) {
    cr_assert(fabs(got.x - want.x) <= tolerance && fabs(got.y - want.y) <= tolerance &&
                  fabs(got.z - want.z) <= tolerance,
              "%s: got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g)", what, got.x, got.y, got.z, want.x,
              want.y, want.z);
}

static ray make_ray(vec3 origin, vec3 direction) { return (ray){origin, vec3_normalize(direction)}; }

/* A ray from (x, y, 0) straight down the -z axis: the probe of most triangle and sphere tests. */
static ray ray_down_z_from(double x, double y) { return make_ray(vec3_make(x, y, 0), vec3_make(0, 0, -1)); }

/* ---- vec3 -------------------------------------------------------------------------------------- */

Test(vec3, add_sub_and_scale_work_per_component) {
    vec3 a = vec3_make(1, 2, 3), b = vec3_make(4, -5, 0.5);
    assert_vec3_near(vec3_add(a, b), vec3_make(5, -3, 3.5), EXACT, "add");
    assert_vec3_near(vec3_sub(a, b), vec3_make(-3, 7, 2.5), EXACT, "sub");
    assert_vec3_near(vec3_scale(a, -2), vec3_make(-2, -4, -6), EXACT, "scale");
    assert_vec3_near(vec3_mul(a, b), vec3_make(4, -10, 1.5), EXACT, "mul");
    assert_vec3_near(vec3_add_scaled(a, b, 2), vec3_make(9, -8, 4), EXACT, "add_scaled");
    assert_vec3_near(vec3_neg(a), vec3_make(-1, -2, -3), EXACT, "neg");
}

Test(vec3, dot_is_the_sum_of_products) {
    cr_assert_eq(vec3_dot(vec3_make(1, 2, 3), vec3_make(4, -5, 6)), 4.0 - 10.0 + 18.0);
    cr_assert_eq(vec3_dot(vec3_make(1, 0, 0), vec3_make(0, 1, 0)), 0.0);
}

Test(vec3, cross_is_right_handed) {
    vec3 x = vec3_make(1, 0, 0), y = vec3_make(0, 1, 0), z = vec3_make(0, 0, 1);
    assert_vec3_near(vec3_cross(x, y), z, EXACT, "x cross y");
    assert_vec3_near(vec3_cross(y, z), x, EXACT, "y cross z");
    assert_vec3_near(vec3_cross(z, x), y, EXACT, "z cross x");
    assert_vec3_near(vec3_cross(y, x), vec3_neg(z), EXACT, "y cross x");
    assert_vec3_near(vec3_cross(vec3_make(1, 2, 3), vec3_make(4, 5, 6)), vec3_make(-3, 6, -3), EXACT, "general");
}

Test(vec3, length_and_normalize_give_a_unit_vector) {
    cr_assert_eq(vec3_length(vec3_make(3, 4, 12)), 13.0);
    vec3 n = vec3_normalize(vec3_make(0, -3, 4));
    assert_vec3_near(n, vec3_make(0, -0.6, 0.8), CLOSE, "normalize");
    cr_assert_float_eq(vec3_length(n), 1.0, CLOSE);
}

Test(vec3, normalize_of_zero_gives_nan) {
    cr_assert(!vec3_is_finite(vec3_normalize(vec3_make(0, 0, 0))));
}

Test(vec3, min_max_and_axis_select_components) {
    vec3 a = vec3_make(1, 5, -2), b = vec3_make(3, -4, -2);
    assert_vec3_near(vec3_min(a, b), vec3_make(1, -4, -2), EXACT, "min");
    assert_vec3_near(vec3_max(a, b), vec3_make(3, 5, -2), EXACT, "max");
    cr_assert_eq(vec3_axis(a, 0), 1.0);
    cr_assert_eq(vec3_axis(a, 1), 5.0);
    cr_assert_eq(vec3_axis(a, 2), -2.0);
}

Test(vec3, is_finite_rejects_nan_and_infinity_in_any_component) {
    cr_assert(vec3_is_finite(vec3_make(1e308, -1e308, 0)));
    cr_assert(!vec3_is_finite(vec3_make(NAN, 0, 0)));
    cr_assert(!vec3_is_finite(vec3_make(0, INFINITY, 0)));
    cr_assert(!vec3_is_finite(vec3_make(0, 0, -INFINITY)));
}

/* ---- camera ------------------------------------------------------------------------------------ */

/* The analytic basis of a camera: forward f, right r, up u (all unit), t = tan(vfov / 2). */
struct basis {
    vec3 f, r, u;
    double t;
};

/* POV-Ray's perspective camera, written from the basis (docs/povray.md): the direction through the centre of pixel
 * (i, j) is normalize(f + (2(i+0.5)/W - 1) t a r + (1 - 2(j+0.5)/H) t u), with a = W / H. */
static vec3 oracle_direction(struct basis b, int width, int height, int i, int j) {
    double a = (double)width / height;
    double x = (2.0 * (i + 0.5) / width - 1.0) * b.t * a;
    double y = (1.0 - 2.0 * (j + 0.5) / height) * b.t;
    return vec3_normalize(vec3_add(b.f, vec3_add(vec3_scale(b.r, x), vec3_scale(b.u, y))));
}

static struct camera make_camera(vec3 eye, vec3 target, vec3 up, double fov, int width, int height) {
    struct camera cam;
    char err[128] = "";
    cr_assert(camera_init(&cam, eye, target, up, fov, width, height, err, sizeof err), "camera_init: %s", err);
    return cam;
}

/* Checks the four corner rays against the oracle's formula, and that every ray has unit length. */
static void check_corners(const struct camera *cam, struct basis b) {
    int w = cam->width, h = cam->height;
    int corners[4][2] = {{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}};
    for (int k = 0; k < 4; k++) {
        ray r = camera_ray(cam, corners[k][0], corners[k][1]);
        char what[64];
        snprintf(what, sizeof what, "pixel (%d, %d)", corners[k][0], corners[k][1]);
        assert_vec3_near(r.direction, oracle_direction(b, w, h, corners[k][0], corners[k][1]), CLOSE, what);
        assert_vec3_near(r.origin, cam->eye, EXACT, "origin");
    }
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            cr_assert_float_eq(vec3_length(camera_ray(cam, i, j).direction), 1.0, CLOSE);
}

static const struct basis looking_down_minus_z = {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}, 1.0};

Test(camera, corner_rays_of_a_4x2_image_match_the_oracle) {
    struct camera cam = make_camera(vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), 90, 4, 2);
    check_corners(&cam, looking_down_minus_z);
    /* Pixel (0, 0): x = -0.75 * t * a = -1.5, y = +0.5; so the direction is normalize(-1.5, 0.5, -1). */
    assert_vec3_near(camera_ray(&cam, 0, 0).direction, vec3_normalize(vec3_make(-1.5, 0.5, -1)), CLOSE, "(0,0)");
    assert_vec3_near(camera_ray(&cam, 3, 1).direction, vec3_normalize(vec3_make(1.5, -0.5, -1)), CLOSE, "(3,1)");
}

Test(camera, centre_ray_of_a_3x3_image_points_exactly_at_the_target) {
    struct camera cam = make_camera(vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), 90, 3, 3);
    assert_vec3_near(camera_ray(&cam, 1, 1).direction, vec3_make(0, 0, -1), EXACT, "centre");
    check_corners(&cam, looking_down_minus_z);
    /* Pixel (0, 0) of a 3x3 image: x = y = 2/3 of the half-size. */
    assert_vec3_near(camera_ray(&cam, 0, 0).direction, vec3_normalize(vec3_make(-2.0 / 3, 2.0 / 3, -1)), CLOSE,
                     "(0,0)");
}

Test(camera, row_zero_is_the_top_and_column_zero_the_left) {
    struct camera cam = make_camera(vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), 60, 5, 3);
    cr_assert_gt(vec3_dot(camera_ray(&cam, 2, 0).direction, cam.up), 0.0);
    cr_assert_lt(vec3_dot(camera_ray(&cam, 2, 2).direction, cam.up), 0.0);
    cr_assert_lt(vec3_dot(camera_ray(&cam, 0, 1).direction, cam.right), 0.0);
    cr_assert_gt(vec3_dot(camera_ray(&cam, 4, 1).direction, cam.right), 0.0);
}

Test(camera, tilted_camera_matches_the_oracle) {
    /* Looking down at 45 degrees: f = (0,-1,-1)/sqrt2, r = (1,0,0), u = r x f = (0,1,-1)/sqrt2. */
    double s = sqrt(0.5);
    struct basis b = {{0, -s, -s}, {1, 0, 0}, {0, s, -s}, 1.0};
    struct camera cam = make_camera(vec3_make(0, 2, 2), vec3_make(0, 1, 1), vec3_make(0, 1, 0), 90, 3, 3);
    assert_vec3_near(camera_ray(&cam, 1, 1).direction, b.f, CLOSE, "centre");
    check_corners(&cam, b);
    /* Pixel (0, 0): f - 2/3 r + 2/3 u = (-2/3, -1/(3 sqrt2), -5/(3 sqrt2)) ~ (-2 sqrt2, -1, -5) / sqrt34. */
    assert_vec3_near(camera_ray(&cam, 0, 0).direction, vec3_scale(vec3_make(-2 * sqrt(2), -1, -5), 1 / sqrt(34)),
                     CLOSE, "(0,0)");
}

Test(camera, non_unit_up_not_orthogonal_to_the_view_is_made_orthonormal) {
    /* up = (2, 3, 4): f x up = (3, -2, 0), so r = (3,-2,0)/sqrt13 and u = r x f = (2,3,0)/sqrt13. */
    double k = 1 / sqrt(13);
    struct basis b = {{0, 0, -1}, {3 * k, -2 * k, 0}, {2 * k, 3 * k, 0}, 1.0};
    struct camera cam = make_camera(vec3_make(1, 1, 1), vec3_make(1, 1, -9), vec3_make(2, 3, 4), 90, 4, 2);
    check_corners(&cam, b);
    assert_vec3_near(cam.up, b.u, CLOSE, "up");
    assert_vec3_near(cam.right, b.r, CLOSE, "right");
    cr_assert_float_eq(vec3_dot(cam.up, cam.forward), 0.0, CLOSE);
}

Test(camera, odd_image_centre_ray_of_a_general_camera_points_at_the_target) {
    vec3 eye = vec3_make(3, -2, 7), target = vec3_make(-1, 4, 0.5);
    struct camera cam = make_camera(eye, target, vec3_make(0.3, 1, 0.2), 35, 7, 5);
    assert_vec3_near(camera_ray(&cam, 3, 2).direction, vec3_normalize(vec3_sub(target, eye)), 1e-15, "centre");
}

/* Calls camera_init with one thing wrong and checks its exact message. */
static void check_camera_refused(vec3 eye, vec3 target, vec3 up, double fov, int width, int height,
                                 const char *message) {
    struct camera cam;
    char err[128] = "";
    cr_assert(!camera_init(&cam, eye, target, up, fov, width, height, err, sizeof err), "accepted: %s", message);
    cr_assert_str_eq(err, message);
}

Test(camera, init_refuses_what_has_no_picture_with_exact_messages) {
    vec3 o = vec3_make(0, 0, 0), ahead = vec3_make(0, 0, -1), up = vec3_make(0, 1, 0);
    check_camera_refused(o, o, up, 60, 4, 3, "camera eye and target are the same point");
    check_camera_refused(o, ahead, vec3_make(0, 0, 2), 60, 4, 3,
                         "camera up vector is zero or parallel to the viewing direction");
    check_camera_refused(o, ahead, vec3_make(0, 0, 0), 60, 4, 3,
                         "camera up vector is zero or parallel to the viewing direction");
    check_camera_refused(o, ahead, up, 0, 4, 3, "camera fov must be between 0 and 180 degrees, got 0");
    check_camera_refused(o, ahead, up, -10, 4, 3, "camera fov must be between 0 and 180 degrees, got -10");
    check_camera_refused(o, ahead, up, 180, 4, 3, "camera fov must be between 0 and 180 degrees, got 180");
    check_camera_refused(o, ahead, up, 60, 0, 3, "image size must be positive, got 0 x 3");
    check_camera_refused(o, ahead, up, 60, 4, -1, "image size must be positive, got 4 x -1");
}

/* ---- sphere ------------------------------------------------------------------------------------ */

/* The unit sphere 5 units down the -z axis. */
static const struct sphere ahead_sphere = {{0, 0, -5}, 1, 0};

/* Intersects r with s over (t_min, t_max); returns t, or -1 for a miss. */
static double sphere_t(const struct sphere *s, ray r, double t_min, double t_max) {
    double t = -1;
    return sphere_intersect(s, &r, t_min, t_max, &t) ? t : -1;
}

Test(sphere, ray_through_the_centre_returns_the_near_root) {
    cr_assert_eq(sphere_t(&ahead_sphere, ray_down_z_from(0, 0), RAY_T_MIN, INFINITY), 4.0);
}

Test(sphere, off_centre_ray_hits_at_the_analytic_distance) {
    /* At x = 0.6 the sphere's surface is at z = -5 + 0.8, so t = 4.2. */
    cr_assert_float_eq(sphere_t(&ahead_sphere, ray_down_z_from(0.6, 0), RAY_T_MIN, INFINITY), 4.2, CLOSE);
}

Test(sphere, tangent_ray_hits_at_the_tangent_point) {
    ray r = ray_down_z_from(1, 0);
    double t = sphere_t(&ahead_sphere, r, RAY_T_MIN, INFINITY);
    cr_assert_eq(t, 5.0);
    assert_vec3_near(ray_at(r, t), vec3_make(1, 0, -5), EXACT, "tangent point");
}

Test(sphere, ray_passing_by_misses) {
    cr_assert_eq(sphere_t(&ahead_sphere, ray_down_z_from(1.001, 0), RAY_T_MIN, INFINITY), -1.0);
    cr_assert_eq(sphere_t(&ahead_sphere, make_ray(vec3_make(0, 0, 0), vec3_make(0, 1, 0)), RAY_T_MIN, INFINITY),
                 -1.0);
}

Test(sphere, a_sphere_small_beside_its_distance_keeps_its_size) {
    /* Radius 1e-9, 8 away: b^2 - c computed as written loses every digit (r^2 is 1e-18 of |O - C|^2, under
     * double's 1.1e-16), and rays passing at many radii would hit. A ray passing at 0.6 r hits 0.8 r before
     * the centre; one at 2 r misses, and so does one at 1.001 r. */
    struct sphere tiny = {{0, 0, -8}, 1e-9, 0};
    cr_assert_float_eq(sphere_t(&tiny, ray_down_z_from(0.6e-9, 0), RAY_T_MIN, INFINITY), 8 - 0.8e-9, 1e-15);
    cr_assert_eq(sphere_t(&tiny, ray_down_z_from(2e-9, 0), RAY_T_MIN, INFINITY), -1.0);
    cr_assert_eq(sphere_t(&tiny, ray_down_z_from(0, 1.001e-9), RAY_T_MIN, INFINITY), -1.0);
    /* the same on a slant: from (0, 1, 0) towards a point 2 r beside the centre */
    vec3 aim = vec3_normalize(vec3_sub(vec3_make(2e-9, 0, -8), vec3_make(0, 1, 0)));
    cr_assert_eq(sphere_t(&tiny, make_ray(vec3_make(0, 1, 0), aim), RAY_T_MIN, INFINITY), -1.0);
}

Test(sphere, ray_from_inside_hits_far_side) {
    ray r = make_ray(vec3_make(0, 0, -5), vec3_make(0, 0, -1));
    cr_assert_eq(sphere_t(&ahead_sphere, r, RAY_T_MIN, INFINITY), 1.0);
}

Test(sphere, sphere_entirely_behind_the_origin_misses) {
    struct sphere behind = {{0, 0, 5}, 1, 0};
    cr_assert_eq(sphere_t(&behind, ray_down_z_from(0, 0), RAY_T_MIN, INFINITY), -1.0);
}

Test(sphere, t_max_before_the_surface_cuts_the_hit_off) {
    cr_assert_eq(sphere_t(&ahead_sphere, ray_down_z_from(0, 0), RAY_T_MIN, 3.9), -1.0);
    cr_assert_eq(sphere_t(&ahead_sphere, ray_down_z_from(0, 0), RAY_T_MIN, 4.0), -1.0); /* t < t_max strictly */
}

Test(sphere, t_min_beyond_the_near_root_gives_the_far_root) {
    cr_assert_eq(sphere_t(&ahead_sphere, ray_down_z_from(0, 0), 4.5, INFINITY), 6.0);
}

Test(sphere, normal_is_outward_and_unit) {
    struct sphere big = {{1, 2, 3}, 2.5, 0};
    vec3 p = vec3_add(big.centre, vec3_scale(vec3_normalize(vec3_make(1, -2, 0.5)), big.radius));
    vec3 n = sphere_normal(&big, p);
    cr_assert_float_eq(vec3_length(n), 1.0, CLOSE);
    assert_vec3_near(n, vec3_normalize(vec3_make(1, -2, 0.5)), CLOSE, "normal");
    assert_vec3_near(sphere_normal(&ahead_sphere, vec3_make(0, 0, -4)), vec3_make(0, 0, 1), EXACT, "front");
}

Test(sphere, closest_keeps_the_nearest_of_several) {
    struct sphere spheres[3] = {{{0, 0, -10}, 1, 1}, {{0, 0, -5}, 1, 2}, {{0, 0, -7}, 1, 3}};
    ray r = ray_down_z_from(0, 0);
    struct hit h = hit_nothing(INFINITY);
    cr_assert(sphere_closest(spheres, 3, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 4.0);
    cr_assert_eq(h.material, 2);
    assert_vec3_near(h.normal, vec3_make(0, 0, 1), EXACT, "normal");
}

Test(sphere, closest_leaves_the_hit_alone_when_nothing_is_nearer) {
    struct hit h = hit_nothing(3.0);
    ray r = ray_down_z_from(0, 0);
    cr_assert(!sphere_closest(&ahead_sphere, 1, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 3.0);
}

Test(sphere, every_intersection_counts_one_sphere_test) {
    stats_reset_thread();
    for (int k = 0; k < 3; k++)
        sphere_t(&ahead_sphere, ray_down_z_from(k, 0), RAY_T_MIN, INFINITY); /* hit, tangent and miss */
    cr_assert_eq(stats_thread.sphere_tests, 3);
    cr_assert_eq(stats_thread.triangle_tests, 0);
}

/* ---- triangle ---------------------------------------------------------------------------------- */

/* A right triangle in the plane z = -2 with legs of 2 along +x and +y from (-1, -1). Its hypotenuse runs
 * through the origin: the point (x, y) has u = (x + 1) / 2, v = (y + 1) / 2. */
static const vec3 tri_a = {-1, -1, -2}, tri_b = {1, -1, -2}, tri_c = {-1, 1, -2};

struct tri_hit {
    bool hit;
    double t, u, v;
};

static struct tri_hit triangle_probe(vec3 a, vec3 b, vec3 c, ray r) {
    struct tri_hit h = {false, -1, -1, -1};
    h.hit = triangle_intersect(a, b, c, &r, RAY_T_MIN, INFINITY, &h.t, &h.u, &h.v);
    return h;
}

/* Probes the standard triangle straight down from (x, y, 0). */
static struct tri_hit probe_down(double x, double y) {
    return triangle_probe(tri_a, tri_b, tri_c, ray_down_z_from(x, y));
}

Test(triangle, inside_hit_has_exact_t_u_and_v) {
    struct tri_hit h = probe_down(0.5, -0.5);
    cr_assert(h.hit);
    cr_assert_eq(h.t, 2.0);
    cr_assert_eq(h.u, 0.75);
    cr_assert_eq(h.v, 0.25);
}

Test(triangle, points_on_edges_are_hits) {
    cr_assert(probe_down(0, -1).hit, "edge a-b (v = 0)");
    cr_assert(probe_down(-1, 0).hit, "edge a-c (u = 0)");
    struct tri_hit h = probe_down(0, 0); /* hypotenuse: u + v = 1 */
    cr_assert(h.hit, "edge b-c (u + v = 1)");
    cr_assert_eq(h.u + h.v, 1.0);
}

Test(triangle, points_on_vertices_are_hits) {
    cr_assert(probe_down(-1, -1).hit, "vertex a");
    cr_assert(probe_down(1, -1).hit, "vertex b");
    cr_assert(probe_down(-1, 1).hit, "vertex c");
}

Test(triangle, points_just_outside_miss) {
    cr_assert(!probe_down(1e-9, 1e-9).hit, "beyond the hypotenuse");
    cr_assert(!probe_down(0, -1 - 1e-9).hit, "below edge a-b");
    cr_assert(!probe_down(-1 - 1e-9, 0).hit, "left of edge a-c");
}

Test(triangle, ray_parallel_to_its_plane_misses) {
    cr_assert(!triangle_probe(tri_a, tri_b, tri_c, make_ray(vec3_make(-2, -0.5, -2), vec3_make(1, 0, 0))).hit,
              "ray inside the plane");
    cr_assert(!triangle_probe(tri_a, tri_b, tri_c, make_ray(vec3_make(-2, -0.5, -1), vec3_make(1, 0.5, 0))).hit,
              "ray above the plane");
}

Test(triangle, zero_area_triangles_miss) {
    vec3 p = vec3_make(0, 0, -2), q = vec3_make(1, 3, -2), r = vec3_make(2, 6, -2);
    cr_assert(!triangle_probe(p, p, q, ray_down_z_from(0.5, 1.5)).hit, "two corners equal");
    cr_assert(!triangle_probe(p, q, r, ray_down_z_from(1, 3)).hit, "collinear, ray through the middle corner");
    cr_assert(!triangle_probe(p, q, r, make_ray(vec3_make(0, 0, 0), vec3_make(1, 3, -2))).hit,
              "collinear, oblique ray through the middle corner");
}

Test(triangle, zero_area_triangle_with_a_repeated_corner_misses_a_ray_through_that_corner) {
    /* A mesh's commonest degenerate face: two equal corners. In exact arithmetic det = 0, but computed
     * det and u, v can be rounding noise of the same size: this ray, aimed at the repeated corner, once
     * came back as a hit at t = 4 (the corner is 4.3 away), with the NaN normal of a zero-area triangle. */
    vec3 a = vec3_make(0, 1, -1), bc = vec3_make(-2, -1, 1), origin = vec3_make(-1.1, 3.2, 0.8);
    struct tri_hit h = triangle_probe(a, bc, bc, make_ray(origin, vec3_sub(bc, origin)));
    cr_assert(!h.hit, "hit at t = %.17g, u = %g, v = %g", h.t, h.u, h.v);
}

Test(triangle, back_face_is_hit_with_the_same_t) {
    struct tri_hit front = probe_down(0.5, -0.5);
    struct tri_hit back = triangle_probe(tri_a, tri_c, tri_b, ray_down_z_from(0.5, -0.5)); /* other winding */
    cr_assert(back.hit);
    cr_assert_eq(back.t, front.t);
    struct tri_hit below = triangle_probe(tri_a, tri_b, tri_c, make_ray(vec3_make(0.5, -0.5, -4), vec3_make(0, 0, 1)));
    cr_assert(below.hit, "seen from the other side");
    cr_assert_eq(below.t, 2.0);
}

Test(triangle, zero_or_nan_direction_misses) {
    cr_assert(!triangle_probe(tri_a, tri_b, tri_c, make_ray(vec3_make(0.5, -0.5, 0), vec3_make(0, 0, 0))).hit);
    cr_assert(!triangle_probe(tri_a, tri_b, tri_c, make_ray(vec3_make(0.5, -0.5, 0), vec3_make(0, NAN, -1))).hit);
}

/* The ray of pixel (112, 16) in the face view of tests/test_watertight.c meets the diagonal edge that
 * these two triangles of the tessellated cube share (the example of docs/03-triangle.md). */
static const vec3 shared_from = {0.75, 0.9375, 1}, shared_to = {0.78125, 0.96875, 1};
static const vec3 below_edge = {0.78125, 0.9375, 1}, above_edge = {0.75, 0.96875, 1};
static const vec3 toward_edge = {0.48906634013963241, 0.60658916530460039, 0.62678840087982934};

Test(triangle, ray_through_that_shared_edge_hits_at_least_one_of_the_triangles) {
    ray r = {{0, 0, 0}, toward_edge}; /* the camera's ray, bit for bit */
    struct tri_hit below = triangle_probe(shared_from, below_edge, shared_to, r);
    struct tri_hit above = triangle_probe(shared_from, shared_to, above_edge, r);
    cr_assert(below.hit || above.hit, "the ray slipped between the two triangles");
}

Test(triangle, tie_rule_a_ray_exactly_on_a_shared_edge_hits_both_triangles_at_the_same_t) {
    /* The square [-1, 1]^2 at z = -2 split along its diagonal; the ray comes straight down onto the
     * diagonal, where the shared edge function is exactly 0 (every product is exact). */
    vec3 low = {-1, -1, -2}, high = {1, 1, -2}, right = {1, -1, -2}, left = {-1, 1, -2};
    struct tri_hit below = triangle_probe(low, right, high, ray_down_z_from(0.25, 0.25));
    struct tri_hit above = triangle_probe(low, high, left, ray_down_z_from(0.25, 0.25));
    cr_assert(below.hit && above.hit, "on the edge counts as inside for both");
    cr_assert_eq(below.t, 2.0);
    cr_assert_eq(above.t, 2.0);
    cr_assert_eq(below.u, 0.0, "on the edge from a to c: b's weight is 0");
    cr_assert_eq(above.v, 0.0, "on the edge from a to b: c's weight is 0");
}

Test(triangle, moller_trumbore_misses_both_triangles_on_that_edge) {
    ray r = {{0, 0, 0}, toward_edge}; /* the camera's ray, bit for bit */
    double t, u, v;
    cr_assert(!triangle_crossing_mt(shared_from, below_edge, shared_to, &r, &t, &u, &v), "u comes out about -2.8e-15");
    cr_assert(!triangle_crossing_mt(shared_from, shared_to, above_edge, &r, &t, &u, &v), "v comes out about -1.4e-15");
    ray inside = make_ray(vec3_make(0, 0, 0), vec3_make(0.77, 0.94, 1)); /* well inside the first */
    cr_assert(triangle_crossing_mt(shared_from, below_edge, shared_to, &inside, &t, &u, &v));
    cr_assert_float_eq(t, vec3_length(vec3_make(0.77, 0.94, 1)), CLOSE, "make_ray normalises the direction");
}

/* The watertight test relies on a*b - c*d being two rounded products and a rounded difference (the
 * Makefile's -ffp-contract=off): then an edge seen from its other end gives exactly the negative. */
Test(triangle, edge_function_is_exactly_antisymmetric) {
    uint64_t state = 12345;
    for (int k = 0; k < 100000; k++) {
        double c[4];
        for (int i = 0; i < 4; i++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            c[i] = ((double)(state >> 11) * 0x1.0p-53 - 0.5) * 8.0;
        }
        double forward = triangle_edge_function(c[0], c[1], c[2], c[3]);
        double backward = triangle_edge_function(c[2], c[3], c[0], c[1]);
        cr_assert(forward == -backward, "e(p, q) = %a but e(q, p) = %a", forward, backward);
    }
}

/* Two products that round to the same number although they differ: (1 + 2^-52)^2 = 1 + 2^-51 + 2^-104
 * rounds to 1 + 2^-51 = (1 + 2^-51) * 1. The edge function is then the difference of the rounding
 * errors, exact: 2^-104 one way round and -2^-104 the other, where a plain difference gives 0. */
Test(triangle, edge_function_of_products_that_round_alike_has_the_exact_value) {
    double p = 1 + 0x1p-52, q = 1 + 0x1p-51;
    cr_assert_eq(p * p, q * 1.0, "the two products must round alike for this test to mean anything");
    cr_assert_eq(triangle_edge_function(p, q, 1.0, p), 0x1p-104, "e = %a", triangle_edge_function(p, q, 1.0, p));
    cr_assert_eq(triangle_edge_function(1.0, p, p, q), -0x1p-104, "e = %a", triangle_edge_function(1.0, p, p, q));
}

/* A triangle a unit in the last place or two across, 1.6 units from the ray's origin: its three
 * corners move to nearly one point of the sheared plane, 1.6 from (0, 0), where two edge functions'
 * products round alike. Counted as 0, "on the edge", they made the ray hit it, 0.1 along, although it
 * passes far from it; their exact signs disagree with the third's. */
Test(triangle, a_triangle_a_few_units_in_the_last_place_across_is_missed_by_a_ray_passing_far_from_it) {
    vec3 a = {SPECK_A}, b = {SPECK_B}, c = {SPECK_C};
    ray r = {{0, 0, 0}, {SPECK_DIRECTION}};
    double t, u, v;
    cr_assert_not(triangle_crossing(a, b, c, &r, &t, &u, &v), "crossed at t = %g", t);
}

/* A right triangle with legs `size` at z = -1, probed through its centroid-ish point. */
static struct tri_hit probe_tiny(double size) {
    vec3 a = vec3_make(0, 0, -1), b = vec3_make(size, 0, -1), c = vec3_make(0, size, -1);
    return triangle_probe(a, b, c, ray_down_z_from(size / 4, size / 4));
}

Test(triangle, tiny_triangles_are_hit) {
    struct tri_hit milli = probe_tiny(1e-3), micro = probe_tiny(1e-5);
    cr_assert(milli.hit, "1e-3 edges");
    cr_assert_float_eq(milli.t, 1.0, CLOSE);
    cr_assert(micro.hit, "1e-5 edges");
    cr_assert_float_eq(micro.t, 1.0, CLOSE);
    cr_assert_float_eq(micro.u, 0.25, 1e-9);
}

Test(triangle, triangle_behind_the_origin_misses) {
    vec3 a = vec3_make(-1, -1, 2), b = vec3_make(1, -1, 2), c = vec3_make(-1, 1, 2);
    cr_assert(!triangle_probe(a, b, c, ray_down_z_from(-0.5, -0.5)).hit);
}

Test(triangle, t_range_is_respected) {
    double t = 0, u = 0, v = 0;
    ray r = ray_down_z_from(-0.5, -0.5);
    cr_assert(!triangle_intersect(tri_a, tri_b, tri_c, &r, RAY_T_MIN, 2.0, &t, &u, &v), "t_max");
    cr_assert(!triangle_intersect(tri_a, tri_b, tri_c, &r, 2.0, INFINITY, &t, &u, &v), "t_min");
}

Test(triangle, normal_follows_the_winding) {
    assert_vec3_near(triangle_normal(tri_a, tri_b, tri_c), vec3_make(0, 0, 1), EXACT, "counter-clockwise");
    assert_vec3_near(triangle_normal(tri_a, tri_c, tri_b), vec3_make(0, 0, -1), EXACT, "clockwise");
    vec3 n = triangle_normal(vec3_make(0, 0, 0), vec3_make(1, 0, 0), vec3_make(0, 1, 1));
    assert_vec3_near(n, vec3_make(0, -sqrt(0.5), sqrt(0.5)), CLOSE, "tilted");
}

/* The standard triangle moved to depth z (the same x, y). */
static struct triangle triangle_at_depth(double z, int material) {
    return (struct triangle){{-1, -1, z}, {1, -1, z}, {-1, 1, z}, material};
}

Test(triangle, closest_keeps_the_nearest) {
    struct triangle tris[3] = {triangle_at_depth(-6, 1), triangle_at_depth(-3, 2), triangle_at_depth(-4, 3)};
    ray r = ray_down_z_from(-0.5, -0.5);
    struct hit h = hit_nothing(INFINITY);
    stats_reset_thread();
    cr_assert(triangle_closest(tris, 3, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 3.0);
    cr_assert_eq(h.material, 2);
    assert_vec3_near(h.normal, vec3_make(0, 0, 1), EXACT, "normal");
    cr_assert_eq(stats_thread.triangle_tests, 3);
}

Test(triangle, mesh_closest_keeps_the_nearest_face) {
    /* Two quads' worth of vertices: faces at z = -5 (far) and z = -2 (near), listed far first. */
    vec3 vertices[6] = {{-1, -1, -5}, {1, -1, -5}, {-1, 1, -5}, {-1, -1, -2}, {1, -1, -2}, {-1, 1, -2}};
    struct mesh_face faces[2] = {{{0, 1, 2}}, {{3, 5, 4}}};
    struct mesh m = {vertices, 6, faces, 2};
    ray r = ray_down_z_from(-0.5, -0.5);
    struct hit h = hit_nothing(INFINITY);
    cr_assert(triangle_mesh_closest(&m, 7, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 2.0);
    cr_assert_eq(h.material, 7);
    assert_vec3_near(h.normal, vec3_make(0, 0, -1), EXACT, "normal of the near face, by its winding");
    struct hit nearer = hit_nothing(1.5);
    cr_assert(!triangle_mesh_closest(&m, 7, &r, RAY_T_MIN, &nearer));
}

/* ---- plane ------------------------------------------------------------------------------------- */

static const struct plane floor_plane = {{0, 1, 0}, -1, 0}; /* y = -1 */

static double plane_t(const struct plane *p, ray r) {
    double t = -1;
    return plane_intersect(p, &r, RAY_T_MIN, INFINITY, &t) ? t : -1;
}

Test(plane, ray_hits_at_the_analytic_t) {
    cr_assert_eq(plane_t(&floor_plane, make_ray(vec3_make(0, 0, 0), vec3_make(0, -1, 0))), 1.0);
    /* Along (0, -0.6, -0.8) the drop of 1 takes t = 1 / 0.6. */
    cr_assert_float_eq(plane_t(&floor_plane, make_ray(vec3_make(0, 0, 0), vec3_make(0, -3, -4))), 1 / 0.6, CLOSE);
}

Test(plane, ray_parallel_to_the_plane_misses) {
    cr_assert_eq(plane_t(&floor_plane, make_ray(vec3_make(0, 0, 0), vec3_make(1, 0, -1))), -1.0);
    cr_assert_eq(plane_t(&floor_plane, make_ray(vec3_make(0, -1, 0), vec3_make(1, 0, 0))), -1.0, "in the plane");
}

Test(plane, plane_behind_the_ray_misses) {
    cr_assert_eq(plane_t(&floor_plane, make_ray(vec3_make(0, 0, 0), vec3_make(0, 1, 0))), -1.0);
}

Test(plane, ray_starting_on_the_plane_misses_but_just_above_hits) {
    cr_assert_eq(plane_t(&floor_plane, make_ray(vec3_make(0, -1, 0), vec3_make(0, -1, 0))), -1.0, "t = 0");
    double t = plane_t(&floor_plane, make_ray(vec3_make(0, -1 + 1e-3, 0), vec3_make(0, -1, 0)));
    cr_assert_float_eq(t, 1e-3, 1e-15);
}

Test(plane, closest_keeps_the_nearest_and_counts_tests) {
    struct plane planes[2] = {{{0, 1, 0}, -3, 1}, {{0, -1, 0}, 2, 2}}; /* y = -3 and y = -2 */
    ray r = make_ray(vec3_make(0, 0, 0), vec3_make(0, -1, 0));
    struct hit h = hit_nothing(INFINITY);
    stats_reset_thread();
    cr_assert(plane_closest(planes, 2, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 2.0);
    cr_assert_eq(h.material, 2);
    assert_vec3_near(h.normal, vec3_make(0, -1, 0), EXACT, "normal as stored");
    cr_assert_eq(stats_thread.plane_tests, 2);
}

Test(plane, closest_takes_a_tie_from_an_earlier_shape_and_the_first_plane_keeps_it) {
    /* POV-Ray tests planes before bounded shapes and replaces a hit only by a strictly nearer one: a
     * plane exactly as far as the hit found before it wins, a plane one ulp farther does not, and of
     * two planes at the same t the first keeps it. Down from the origin, y = -2 is at t = 2 exactly. */
    struct plane planes[2] = {{{0, 1, 0}, -2, 1}, {{0, -1, 0}, 2, 2}}; /* y = -2 twice */
    ray r = make_ray(vec3_make(0, 0, 0), vec3_make(0, -1, 0));
    struct hit h = {2.0, {0, 0, 1}, 9, 5, -1}; /* a box's face, say, found at the same t */
    cr_assert(plane_closest(planes, 2, &r, RAY_T_MIN, &h));
    cr_assert_eq(h.t, 2.0);
    cr_assert_eq(h.material, 1, "the first plane keeps the tie");
    struct hit nearer = {nextafter(2.0, 0.0), {0, 0, 1}, 9, 5, -1};
    cr_assert(!plane_closest(planes, 2, &r, RAY_T_MIN, &nearer));
    cr_assert_eq(nearer.material, 9, "a hit one ulp nearer stays");
}

/* ---- aabb -------------------------------------------------------------------------------------- */

static const struct aabb unit_box = {{0, 0, 0}, {1, 1, 1}};

/* Runs the slab test of `box` for the ray (origin, direction) over [0, infinity); returns the entry t,
 * or -1 for a miss. The direction is not normalised, so that signed zeros survive. */
static double slab_entry(const struct aabb *box, vec3 origin, vec3 direction) {
    double t = -1;
    return aabb_hit(box, origin, aabb_inverse_direction(direction), 0, INFINITY, &t) ? t : -1;
}

Test(aabb, axis_parallel_ray_inside_the_slabs_hits) {
    cr_assert_eq(slab_entry(&unit_box, vec3_make(-5, 0.5, 0.5), vec3_make(1, 0, 0)), 5.0);
    cr_assert_eq(slab_entry(&unit_box, vec3_make(-5, 0.5, 0.5), vec3_make(1, -0.0, -0.0)), 5.0, "negative zeros");
    cr_assert_eq(slab_entry(&unit_box, vec3_make(0.5, 0.5, 3), vec3_make(-0.0, 0, -1)), 2.0);
}

Test(aabb, axis_parallel_ray_outside_a_slab_misses) {
    cr_assert_eq(slab_entry(&unit_box, vec3_make(-5, 2, 0.5), vec3_make(1, 0, 0)), -1.0);
    cr_assert_eq(slab_entry(&unit_box, vec3_make(-5, 2, 0.5), vec3_make(1, -0.0, 0)), -1.0, "negative zero");
    cr_assert_eq(slab_entry(&unit_box, vec3_make(-5, 0.5, -1), vec3_make(1, 0, -0.0)), -1.0, "below in z");
}

Test(aabb, origin_inside_enters_at_t_min) {
    cr_assert_eq(slab_entry(&unit_box, vec3_make(0.5, 0.5, 0.5), vec3_make(1, 2, 3)), 0.0);
    double t = -1;
    vec3 inv = aabb_inverse_direction(vec3_make(0, 1, 0));
    cr_assert(aabb_hit(&unit_box, vec3_make(0.5, 0.5, 0.5), inv, RAY_T_MIN, INFINITY, &t));
    cr_assert_eq(t, RAY_T_MIN);
}

Test(aabb, origin_on_a_face_plane_moving_along_it_hits_within_the_face) {
    /* On the min.x plane below the box, moving up (+y): it runs inside the face x = 0. Here the slab
     * test meets 0 * infinity = NaN, which must not decide: the boundary belongs to the box. */
    cr_assert_eq(slab_entry(&unit_box, vec3_make(0, -1, 0.5), vec3_make(0, 1, 0)), 1.0);
    cr_assert_eq(slab_entry(&unit_box, vec3_make(1, -1, 0.5), vec3_make(-0.0, 1, 0)), 1.0, "max.x plane, -0");
    cr_assert_eq(slab_entry(&unit_box, vec3_make(0, 0.5, 0.5), vec3_make(0, 1, 0)), 0.0, "starting on the face");
}

Test(aabb, origin_on_a_face_plane_outside_the_face_misses) {
    cr_assert_eq(slab_entry(&unit_box, vec3_make(0, -1, 2), vec3_make(0, 1, 0)), -1.0, "beyond max.z");
    cr_assert_eq(slab_entry(&unit_box, vec3_make(0, -1, 0.5), vec3_make(0, -1, 0)), -1.0, "moving away");
    cr_assert_eq(slab_entry(&unit_box, vec3_make(0, -1, -0.5), vec3_make(0, 1, 0)), -1.0, "below min.z");
}

Test(aabb, box_behind_the_ray_misses) {
    cr_assert_eq(slab_entry(&unit_box, vec3_make(5, 0.5, 0.5), vec3_make(1, 0, 0)), -1.0);
    cr_assert_eq(slab_entry(&unit_box, vec3_make(2, 2, 2), vec3_make(1, 1, 1)), -1.0);
}

Test(aabb, entry_distance_of_an_oblique_ray) {
    /* From (-1, -1, 0.5) along (1, 1, 0)/sqrt2 the box is entered at its edge (0, 0, 0.5), t = sqrt2. */
    double t = slab_entry(&unit_box, vec3_make(-1, -1, 0.5), vec3_normalize(vec3_make(1, 1, 0)));
    cr_assert_float_eq(t, sqrt(2), CLOSE);
    double entry = -1;
    cr_assert(!aabb_hit(&unit_box, vec3_make(-1, -1, 0.5), aabb_inverse_direction(vec3_make(1, 1, 0)), 0, 0.5,
                        &entry),
              "t_max before the entry");
}

Test(aabb, grazing_ray_along_an_edge_hits) {
    cr_assert_eq(slab_entry(&unit_box, vec3_make(-1, 1, 1), vec3_make(1, 0, 0)), 1.0);
    cr_assert_eq(slab_entry(&unit_box, vec3_make(-1, 1 + 1e-12, 1), vec3_make(1, 0, 0)), -1.0, "just off");
}

Test(aabb, flat_box_is_hit_by_a_ray_crossing_it) {
    struct aabb flat = {{0, 0, 0}, {1, 0, 1}}; /* min.y == max.y */
    cr_assert_eq(slab_entry(&flat, vec3_make(0.5, 1, 0.5), vec3_make(0, -1, 0)), 1.0);
    cr_assert_float_eq(slab_entry(&flat, vec3_make(0, 1, 0), vec3_normalize(vec3_make(1, -2, 1))), sqrt(6) / 2,
                       CLOSE);
    cr_assert_eq(slab_entry(&flat, vec3_make(2, 1, 0.5), vec3_make(0, -1, 0)), -1.0, "beside it");
}

Test(aabb, null_entry_pointer_is_allowed_and_a_test_is_counted) {
    stats_reset_thread();
    cr_assert(aabb_hit(&unit_box, vec3_make(-1, 0.5, 0.5), aabb_inverse_direction(vec3_make(1, 0, 0)), 0,
                       INFINITY, NULL));
    cr_assert_eq(stats_thread.box_tests, 1);
}

Test(aabb, clip_from_an_unbounded_interval_gives_entry_and_exit) {
    double t_near = -INFINITY, t_far = INFINITY;
    stats_reset_thread();
    cr_assert(aabb_clip(&unit_box, vec3_make(0.5, 0.5, 0.5), aabb_inverse_direction(vec3_make(1, 0, 0)), &t_near,
                        &t_far));
    cr_assert_eq(t_near, -0.5);
    cr_assert_eq(t_far, 0.5);
    cr_assert_eq(stats_thread.box_tests, 0);
}

Test(aabb, normal_names_the_nearest_face) {
    struct aabb box = {{-1, -2, -3}, {1, 2, 3}};
    struct {
        vec3 point, normal;
    } faces[6] = {{{-1, 0.5, 1}, {-1, 0, 0}}, {{1, -0.5, 2}, {1, 0, 0}},  {{0.2, -2, 1}, {0, -1, 0}},
                  {{-0.3, 2, -1}, {0, 1, 0}}, {{0.5, 1, -3}, {0, 0, -1}}, {{-0.5, -1, 3}, {0, 0, 1}}};
    for (int k = 0; k < 6; k++)
        assert_vec3_near(aabb_normal(&box, faces[k].point), faces[k].normal, EXACT, "face normal");
}

Test(aabb, surface_area_of_a_box_a_flat_box_and_the_empty_box) {
    cr_assert_eq(aabb_surface_area((struct aabb){{0, 0, 0}, {1, 2, 3}}), 22.0);
    cr_assert_eq(aabb_surface_area((struct aabb){{0, 0, 0}, {1, 0, 1}}), 2.0);
    cr_assert_eq(aabb_surface_area(aabb_empty()), 0.0);
}

Test(aabb, empty_box_grows_to_hold_its_points) {
    struct aabb b = aabb_empty();
    cr_assert_eq(slab_entry(&b, vec3_make(0, 0, -1), vec3_make(0, 0, 1)), -1.0, "the empty box is never hit");
    b = aabb_grow(b, vec3_make(1, -2, 3));
    assert_vec3_near(b.min, vec3_make(1, -2, 3), EXACT, "min after one point");
    assert_vec3_near(b.max, vec3_make(1, -2, 3), EXACT, "max after one point");
    b = aabb_grow(b, vec3_make(-1, 5, 0));
    assert_vec3_near(b.min, vec3_make(-1, -2, 0), EXACT, "min");
    assert_vec3_near(b.max, vec3_make(1, 5, 3), EXACT, "max");
}

Test(aabb, union_holds_both_boxes_and_ignores_the_empty_box) {
    struct aabb a = {{0, 0, 0}, {1, 1, 1}}, b = {{-2, 0.5, 0.5}, {0.5, 3, 0.7}};
    struct aabb u = aabb_union(a, b);
    assert_vec3_near(u.min, vec3_make(-2, 0, 0), EXACT, "min");
    assert_vec3_near(u.max, vec3_make(1, 3, 1), EXACT, "max");
    struct aabb same = aabb_union(aabb_empty(), a);
    assert_vec3_near(same.min, a.min, EXACT, "min with empty");
    assert_vec3_near(same.max, a.max, EXACT, "max with empty");
}

/* ---- image ------------------------------------------------------------------------------------- */

Test(image, quantize_rounds_half_up_like_povray) {
    static const struct {
        double value;
        int level;
    } cases[] = {{0.1, 26},   {0.25, 64},  {0.5, 128},        {127.49 / 255, 127}, {0.75, 191}, {0.9, 230},
                 {200.5 / 255, 201}, {1.5, 255}, {0.001, 0}, {-0.5, 0},   {0.0, 0},    {1.0, 255}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        cr_assert_eq(image_quantize(cases[k].value), cases[k].level, "%.17g gives %d, want %d", cases[k].value,
                     image_quantize(cases[k].value), cases[k].level);
    cr_assert_eq(image_quantize(NAN), 0);
}

/* Makes a fresh folder under /tmp for one test; the name goes into `dir`. */
static void make_temp_dir(char *dir, size_t size) {
    snprintf(dir, size, "/tmp/whitted-geometry-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
}

/* Returns how many names in `dir` contain ".tmp" (leftover temporary files). */
static int count_temp_files(const char *dir) {
    DIR *d = opendir(dir);
    cr_assert_not_null(d);
    int count = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        count += strstr(e->d_name, ".tmp") != NULL;
    closedir(d);
    return count;
}

Test(image, written_png_reads_back_with_the_exact_bytes) {
    char dir[64], path[96], err[256] = "";
    make_temp_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/small.png", dir);
    struct image img;
    cr_assert(image_create(&img, 3, 2));
    vec3 colours[6];
    for (int k = 0; k < 6; k++) {
        colours[k] = vec3_make(0.1 * k, 1.5 - 0.3 * k, k == 3 ? NAN : 0.5);
        image_set(&img, k % 3, k / 3, colours[k]);
    }
    cr_assert(image_write_png(&img, path, err, sizeof err), "%s", err);
    int width = 0, height = 0;
    uint8_t *rgb = image_read_rgb(path, &width, &height, err, sizeof err);
    cr_assert_not_null(rgb, "%s", err);
    cr_assert_eq(width, 3);
    cr_assert_eq(height, 2);
    for (int k = 0; k < 6; k++) {
        cr_assert_eq(rgb[3 * k + 0], image_quantize(colours[k].x), "pixel %d red", k);
        cr_assert_eq(rgb[3 * k + 1], image_quantize(colours[k].y), "pixel %d green", k);
        cr_assert_eq(rgb[3 * k + 2], image_quantize(colours[k].z), "pixel %d blue", k);
    }
    cr_assert_eq(count_temp_files(dir), 0);
    free(rgb);
    image_free(&img);
    remove(path);
    rmdir(dir);
}

Test(image, writing_into_a_missing_folder_fails_and_leaves_nothing) {
    char dir[64], path[128], expected[192], err[256] = "";
    make_temp_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/missing/out.png", dir);
    uint8_t rgb[3] = {1, 2, 3};
    cr_assert(!image_write_png_bytes(rgb, 1, 1, path, err, sizeof err));
    snprintf(expected, sizeof expected, "%s: cannot create: No such file or directory", path);
    cr_assert_str_eq(err, expected);
    cr_assert_neq(access(path, F_OK), 0);
    cr_assert_eq(count_temp_files(dir), 0);
    rmdir(dir);
}

Test(image, failed_rename_removes_the_temporary_file) {
    /* The target is an existing folder: the PNG is written, but cannot be renamed into place. */
    char dir[64], path[96], expected[160], err[256] = "";
    make_temp_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/folder.png", dir);
    cr_assert_eq(mkdir(path, 0755), 0);
    uint8_t rgb[3] = {1, 2, 3};
    cr_assert(!image_write_png_bytes(rgb, 1, 1, path, err, sizeof err));
    snprintf(expected, sizeof expected, "%s: cannot write: Is a directory", path);
    cr_assert_str_eq(err, expected);
    cr_assert_eq(count_temp_files(dir), 0);
    rmdir(path);
    rmdir(dir);
}

Test(image, reading_a_missing_file_fails_with_its_name) {
    char err[256] = "";
    int width = -1, height = -1;
    cr_assert_null(image_read_rgb("/nonexistent/whitted.png", &width, &height, err, sizeof err));
    cr_assert_str_eq(err, "/nonexistent/whitted.png: cannot open: No such file or directory");
}

Test(image, create_refuses_sizes_outside_the_limits) {
    struct image img;
    cr_assert(!image_create(&img, 0, 5));
    cr_assert_null(img.rgb);
    cr_assert(!image_create(&img, IMAGE_MAX_SIDE + 1, 1));
    cr_assert(image_create(&img, 2, 2));
    image_set(&img, 1, 1, vec3_make(1, 0.5, 0));
    cr_assert_eq(img.rgb[9], 255); /* pixel 3, row 1 column 1 */
    cr_assert_eq(img.rgb[10], 128);
    cr_assert_eq(img.rgb[11], 0);
    cr_assert_eq(img.rgb[0], 0); /* the rest stays black */
    image_free(&img);
    image_free(&img); /* safe twice */
    cr_assert_eq(img.width, 0);
}

/* ---- headlight --------------------------------------------------------------------------------- */

/* Shades a hit with normal n, seen along direction d, on a scene whose material 1 is orange. */
static vec3 headlight_colour(vec3 n, vec3 d) {
    struct material materials[2] = {{.name = "default", .colour = {1, 1, 1}},
                                    {.name = "orange", .colour = {0.8, 0.4, 0.2}}};
    struct scene s = {.materials = materials, .material_count = 2};
    struct hit h = {2.0, n, 1, -1, -1};
    return headlight_shade(&s, &h, vec3_normalize(d));
}

Test(headlight, surface_facing_the_camera_gets_its_full_colour) {
    assert_vec3_near(headlight_colour(vec3_make(0, 0, 1), vec3_make(0, 0, -1)), vec3_make(0.8, 0.4, 0.2), EXACT,
                     "colour");
}

Test(headlight, surface_at_60_degrees_gets_half) {
    vec3 d = vec3_make(sin(M_PI / 3), 0, -cos(M_PI / 3));
    assert_vec3_near(headlight_colour(vec3_make(0, 0, 1), d), vec3_make(0.4, 0.2, 0.1), CLOSE, "colour");
}

Test(headlight, back_side_is_lit_like_the_front) {
    vec3 d = vec3_make(0.3, -0.2, -1);
    vec3 front = headlight_colour(vec3_make(0, 0, 1), d);
    vec3 back = headlight_colour(vec3_make(0, 0, -1), d); /* the normal turned away from the ray */
    assert_vec3_near(back, front, EXACT, "back vs front");
    cr_assert_gt(back.x, 0.0);
}

/* ---- bounding boxes of shapes (each kind's bounds, shape.h) ------------------------------------ */

/* Checks that kind's bounds gives exactly [lo, hi] for `item`. */
static void assert_bounds(const struct shape_kind *kind, const void *item, vec3 lo, vec3 hi) {
    vec3 min, max;
    cr_assert(kind->bounds(item, &min, &max), "%s: no bounds", kind->syntax->keyword);
    cr_assert(min.x == lo.x && min.y == lo.y && min.z == lo.z, "min (%g, %g, %g)", min.x, min.y, min.z);
    cr_assert(max.x == hi.x && max.y == hi.y && max.z == hi.z, "max (%g, %g, %g)", max.x, max.y, max.z);
}

Test(aabb, a_sphere_is_bounded_by_centre_plus_minus_radius) {
    struct sphere s = {vec3_make(1, -2, 3), 0.5, 0};
    assert_bounds(&sphere_kind, &s, vec3_make(0.5, -2.5, 2.5), vec3_make(1.5, -1.5, 3.5));
}

Test(aabb, a_triangle_is_bounded_by_its_corners) {
    struct triangle t = {vec3_make(0, 5, -1), vec3_make(2, -1, 0), vec3_make(-3, 0, 4), 0};
    assert_bounds(&triangle_kind, &t, vec3_make(-3, -1, -1), vec3_make(2, 5, 4));
}

Test(aabb, a_box_is_its_own_bounding_box) {
    struct box b = {vec3_make(-1, 0, 2), vec3_make(1, 3, 4), 0};
    assert_bounds(&box_kind, &b, b.min, b.max);
}

Test(aabb, a_plane_has_no_bounding_box) {
    struct plane p = {vec3_make(0, 1, 0), 2.0, 0};
    vec3 min, max;
    cr_assert_not(plane_kind.bounds(&p, &min, &max));
}

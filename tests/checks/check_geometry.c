/* check_geometry.c: the coursework checks of chapters 1 to 5: camera rays, spheres, triangles, planes,
 * the slab test and boxes, against values worked out by hand (the coursework kit). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "aabb.h"
#include "box.h"
#include "camera.h"
#include "check.h"
#include "plane.h"
#include "sphere.h"
#include "stats.h"
#include "triangle.h"

/* Hits are compared to their exact values within this: far above rounding, far below any mistake. */
#define GEOMETRY_TOLERANCE 1e-9

/* ---- 1.1 camera_ray -------------------------------------------------------------------------- */

/* A 2 x 2 picture, fov 90, from the origin looking down -z with +y up: the half-width and
 * half-height of the image plane at distance 1 are both 1, so pixel (i, j)'s centre is at
 * x = -0.5 or 0.5, y = 0.5 or -0.5, and its ray is that point normalised. */
static bool camera_pixel(int i, int j, char *why, size_t why_size) {
    struct camera cam;
    char err[256];
    if (!camera_init(&cam, vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), 90.0, 2, 2, err, sizeof err)) {
        snprintf(why, why_size, "camera_init refused a plain camera: %s", err);
        return false;
    }
    vec3 expected = vec3_normalize(vec3_make(i == 0 ? -0.5 : 0.5, j == 0 ? 0.5 : -0.5, -1.0));
    check_calling("camera_ray", "pixel (%d, %d) of a 2 x 2 picture, fov 90, eye at the origin looking down -z", i, j);
    ray r = camera_ray(&cam, i, j);
    char e[64], g[64];
    if (!check_vec_near(r.origin, vec3_make(0, 0, 0), GEOMETRY_TOLERANCE)) {
        snprintf(why, why_size, "camera_ray(cam, %d, %d): the ray must start at the eye (0, 0, 0); yours starts at %s",
                 i, j, check_vec_text(r.origin, g));
        return false;
    }
    if (check_vec_near(r.direction, expected, GEOMETRY_TOLERANCE))
        return true;
    const char *hint = "";
    if (!check_near(vec3_length(r.direction), 1.0, 1e-6))
        hint = ": not of unit length (normalise it)";
    else if (check_vec_near(r.direction, vec3_make(expected.x, -expected.y, expected.z), GEOMETRY_TOLERANCE))
        hint = ": upside down? Row j = 0 is the top of the picture";
    else if (check_vec_near(r.direction, vec3_make(-expected.x, expected.y, expected.z), GEOMETRY_TOLERANCE))
        hint = ": mirrored left to right? Column i = 0 is the left edge";
    else if (check_vec_near(r.direction, vec3_normalize(vec3_make(i == 0 ? -1 : 0, j == 0 ? 1 : 0, -1)), 1e-6))
        hint = ": through the pixel's corner? Aim at its centre, i + 0.5";
    snprintf(why, why_size,
             "camera_ray(cam, %d, %d) for a 2 x 2 picture, fov 90, eye at the origin looking down -z: the direction "
             "should be %s, yours is %s%s",
             i, j, check_vec_text(expected, e), check_vec_text(r.direction, g), hint);
    return false;
}

CHECK(check_camera_top_left) { return camera_pixel(0, 0, why, why_size); }
CHECK(check_camera_bottom_right) { return camera_pixel(1, 1, why, why_size); }

/* ---- 2.1 sphere_intersect, 2.2 sphere_normal ---------------------------------------------------- */

static const ray down_z = {{0, 0, 0}, {0, 0, -1}};

/* Asks sphere_intersect about ray r and a sphere, expecting a hit at `expected` (NAN: a miss). */
static bool sphere_case(const char *what, vec3 centre, double radius, const ray *r, double t_max, double expected,
                        char *why, size_t why_size) {
    struct sphere s = {centre, radius, 0};
    double t = NAN;
    char c[64], ray_text[160];
    check_calling("sphere_intersect", "%s: %s and the sphere of radius %g around %s, t_min 1e-9, t_max %g", what,
                  check_ray_text(r, ray_text), radius, check_vec_text(centre, c), t_max);
    bool hit = sphere_intersect(&s, r, 1e-9, t_max, &t);
    if (isnan(expected)) {
        if (!hit)
            return true;
        snprintf(why, why_size, "sphere_intersect: %s: expected a miss; your code returned a hit at t = %.1f", what, t);
        return false;
    }
    if (hit && check_near(t, expected, GEOMETRY_TOLERANCE))
        return true;
    if (!hit) {
        snprintf(why, why_size, "sphere_intersect: the hit is %.1f along the ray for %s; your code returned no hit",
                 expected, what);
        return false;
    }
    double far = vec3_dot(vec3_sub(centre, r->origin), r->direction) + radius;
    snprintf(why, why_size, "sphere_intersect: the hit is %.1f along the ray for %s; your code returned %.1f%s",
             expected, what, t, check_near(t, far, 1e-6) && !check_near(far, expected, 1e-6) ? ": the far root?" : "");
    return false;
}

CHECK(check_sphere_in_front) {
    return sphere_case("a sphere 5 away with radius 1", vec3_make(0, 0, -5), 1.0, &down_z, INFINITY, 4.0, why,
                       why_size);
}

CHECK(check_sphere_from_inside) {
    return sphere_case("a ray starting at the centre of a sphere of radius 2 (it leaves through the far side)",
                       vec3_make(0, 0, 0), 2.0, &down_z, INFINITY, 2.0, why, why_size);
}

CHECK(check_sphere_misses) {
    ray beside = {{3, 0, 0}, {0, 0, -1}};
    return sphere_case("a ray passing 3 from the centre of a sphere of radius 1", vec3_make(0, 0, -5), 1.0, &beside,
                       INFINITY, NAN, why, why_size) &&
           sphere_case("a sphere behind the ray (5 away, the ray points away from it)", vec3_make(0, 0, 5), 1.0,
                       &down_z, INFINITY, NAN, why, why_size) &&
           sphere_case("a sphere 5 away with radius 1, but t_max = 3", vec3_make(0, 0, -5), 1.0, &down_z, 3.0, NAN,
                       why, why_size);
}

/* The window of t is open, t_min < t < t_max: a root exactly at either end is not a hit. A ray that starts
 * on a sphere's surface (a reflected or refracted ray, or a shadow ray, leaves from one) has a root at
 * exactly t = 0; with t_min = 0 that root must not count, or the ray finds the surface it leaves. */
CHECK(check_sphere_open_window) {
    const struct sphere s = {{0, 0, -5}, 1.0, 0};
    const ray on_surface = {{0, 0, -4}, {0, 0, -1}};
    double t = NAN;
    check_calling("sphere_intersect", "a ray from (0, 0, -4), on the surface of the sphere of radius 1 around "
                  "(0, 0, -5), down -z, t_min 0, t_max inf");
    bool hit = sphere_intersect(&s, &on_surface, 0.0, INFINITY, &t);
    if (!hit || !check_near(t, 2.0, GEOMETRY_TOLERANCE)) {
        char got[32] = "no hit";
        if (hit)
            snprintf(got, sizeof got, "a hit at t = %.1f", t);
        snprintf(why, why_size, "sphere_intersect: a ray starting on the surface, at (0, 0, -4), with t_min = 0 must "
                 "leave through the far side at t = 2; your code returned %s%s", got,
                 hit && t == 0.0 ? ": a root exactly at t_min counted, so the ray hits the surface it starts from (the "
                                   "window is open, t > t_min and t < t_max, not >= and <=; in chapter 8 the glass "
                                   "ball's refracted rays would stop where they start)"
                                 : "");
        return false;
    }
    check_calling("sphere_intersect", "a ray from the origin down -z and the sphere of radius 1 around (0, 0, -5), "
                  "t_min 1e-9, t_max 4 (exactly its near root)");
    t = NAN;
    if (sphere_intersect(&s, &down_z, 1e-9, 4.0, &t)) {
        snprintf(why, why_size, "sphere_intersect: the sphere of radius 1 around (0, 0, -5) with t_max = 4, exactly its "
                 "near root, must be a miss (the far root, 6, is beyond t_max too); your code returned a hit at t = "
                 "%.1f: a root exactly at t_max counted (the window is open, t < t_max, not <=; a shadow ray ending "
                 "on the light would be blocked by the light's own surface)", t);
        return false;
    }
    return true;
}

/* One call of sphere_intersect on r, for the counter's check: how much it added to the sphere tests. */
static uint64_t sphere_tests_of_one_call(const ray *r) {
    const struct sphere s = {{0, 0, -5}, 1.0, 0};
    double t;
    uint64_t before = stats_thread.sphere_tests;
    sphere_intersect(&s, r, 1e-9, INFINITY, &t);
    return stats_thread.sphere_tests - before;
}

CHECK(check_sphere_counted) {
    static const ray hit = {{0, 0, 0}, {0, 0, -1}}, miss = {{3, 0, 0}, {0, 0, -1}};
    check_calling("sphere_intersect", "a ray from the origin down -z and the sphere of radius 1 around (0, 0, -5)");
    if (!check_counted_once(sphere_tests_of_one_call(&hit), "sphere_intersect on a ray that hits", "one sphere test",
                            "sphere tests", why, why_size))
        return false;
    check_calling("sphere_intersect", "a ray from (3, 0, 0) down -z and the sphere of radius 1 around (0, 0, -5)");
    return check_counted_once(sphere_tests_of_one_call(&miss), "sphere_intersect on a ray that misses",
                              "one sphere test", "sphere tests", why, why_size);
}

CHECK(check_sphere_normal) {
    struct sphere s = {{1, 2, 3}, 2.0, 0};
    vec3 expected = vec3_normalize(vec3_make(1, -1, 1));
    vec3 p = vec3_add_scaled(s.centre, expected, 2.0);
    char e[64], g[64], q[64];
    check_calling("sphere_normal", "the point %s of the sphere of radius 2 around (1, 2, 3)", check_vec_text(p, q));
    vec3 got = sphere_normal(&s, p);
    if (check_vec_near(got, expected, GEOMETRY_TOLERANCE))
        return true;
    snprintf(why, why_size, "sphere_normal at %s on the sphere of radius 2 around (1, 2, 3): expected %s, got %s%s", q,
             check_vec_text(expected, e), check_vec_text(got, g),
             check_near(vec3_length(got), 2.0, 1e-6) ? ": divide by the radius to make it unit length"
             : check_vec_near(got, vec3_scale(expected, -1), 1e-9) ? ": it points inwards" : "");
    return false;
}

/* ---- 3.1 triangle_crossing_mt (Moller-Trumbore) --------------------------------------------- */
/* The task is the test chapter 3 teaches first. It reports where the ray's line crosses the triangle,
 * at any t: the window of t is the caller's (triangle_intersect). The tracer itself uses the watertight
 * test, which the student reads rather than writes; the picture check 3.P covers it. */

CHECK(check_triangle_hit) {
    vec3 a = {0, 0, -2}, b = {4, 0, -2}, c = {0, 4, -2};
    ray r = {{1, 2, 0}, {0, 0, -1}};
    double t = NAN, u = NAN, v = NAN;
    check_calling("triangle_crossing_mt", "a ray from (1, 2, 0) down -z and the triangle (0, 0, -2), (4, 0, -2), "
                  "(0, 4, -2)");
    bool hit = triangle_crossing_mt(a, b, c, &r, &t, &u, &v);
    if (hit && check_near(t, 2.0, GEOMETRY_TOLERANCE) && check_near(u, 0.25, GEOMETRY_TOLERANCE) &&
        check_near(v, 0.5, GEOMETRY_TOLERANCE))
        return true;
    if (!hit)
        snprintf(why, why_size, "triangle_crossing_mt: a ray from (1, 2, 0) down -z meets the triangle (0, 0, -2), "
                 "(4, 0, -2), (0, 4, -2) at t = 2; your code returned no hit");
    else
        snprintf(why, why_size, "triangle_crossing_mt: a ray from (1, 2, 0) down -z meets the triangle (0, 0, -2), "
                 "(4, 0, -2), (0, 4, -2) at t = 2 with u = 0.25, v = 0.5; yours gave t = %g, u = %g, v = %g%s", t, u, v,
                 check_near(u, 0.5, 1e-9) && check_near(v, 0.25, 1e-9) ? ": u and v swapped?" : "");
    return false;
}

CHECK(check_triangle_misses) {
    vec3 a = {0, 0, -2}, b = {4, 0, -2}, c = {0, 4, -2};
    const struct { ray r; const char *what; } cases[] = {
        {{{3, 3, 0}, {0, 0, -1}}, "a ray from (3, 3, 0) down -z, outside the edge from (4, 0, -2) to (0, 4, -2) "
                                  "(u + v = 1.5: is u + v > 1 tested?)"},
        {{{-1, 1, 0}, {0, 0, -1}}, "a ray from (-1, 1, 0) down -z, beyond the edge x = 0 (u < 0)"},
        {{{1, -1, 0}, {0, 0, -1}}, "a ray from (1, -1, 0) down -z, beyond the edge y = 0 (v < 0)"},
        {{{1, 1, -1}, {1, 0, 0}}, "a ray parallel to the triangle's plane"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double t = NAN, u, v;
        check_calling("triangle_crossing_mt", "%s, and the triangle (0, 0, -2), (4, 0, -2), (0, 4, -2)", cases[k].what);
        if (triangle_crossing_mt(a, b, c, &cases[k].r, &t, &u, &v)) {
            snprintf(why, why_size, "triangle_crossing_mt: %s must miss the triangle (0, 0, -2), (4, 0, -2), "
                     "(0, 4, -2); your code returned a hit at t = %g", cases[k].what, t);
            return false;
        }
    }
    /* Behind the origin: the line still crosses, at t = -2, and the caller's window drops it. */
    ray away = {{1, 1, 0}, {0, 0, 1}};
    double t = NAN, u, v;
    check_calling("triangle_crossing_mt", "a ray from (1, 1, 0) up +z, the triangle (0, 0, -2), (4, 0, -2), (0, 4, -2) "
                  "behind it");
    bool hit = triangle_crossing_mt(a, b, c, &away, &t, &u, &v);
    if (hit && check_near(t, -2.0, GEOMETRY_TOLERANCE))
        return true;
    char got[64] = "no crossing";
    if (hit)
        snprintf(got, sizeof got, "t = %g", t);
    snprintf(why, why_size, "triangle_crossing_mt: a ray from (1, 1, 0) up +z has the triangle behind it: its line "
             "crosses at t = -2 (the caller's window of t rejects it); your code returned %s", got);
    return false;
}

/* ---- 4.1 plane_intersect ----------------------------------------------------------------------- */

CHECK(check_plane_hit) {
    /* The floor y = -1: normal (0, 1, 0), distance -1. A ray down from the origin meets it at t = 1,
     * one at 45 degrees at t = sqrt(2). */
    struct plane floor = {{0, 1, 0}, -1.0, 0};
    ray rays[2] = {{{0, 0, 0}, {0, -1, 0}}, {{0, 0, 0}, {0, -M_SQRT1_2, -M_SQRT1_2}}};
    double expected[2] = {1.0, M_SQRT2};
    for (int k = 0; k < 2; k++) {
        double t = NAN;
        char d[64], got[64] = "no hit";
        check_calling("plane_intersect", "the plane y = -1 (normal (0, 1, 0), distance -1) and a ray from the origin "
                      "along %s", check_vec_text(rays[k].direction, d));
        bool hit = plane_intersect(&floor, &rays[k], 1e-9, INFINITY, &t);
        if (hit && check_near(t, expected[k], GEOMETRY_TOLERANCE))
            continue;
        if (hit)
            snprintf(got, sizeof got, "%.4f", t);
        snprintf(why, why_size, "plane_intersect: the plane y = -1 (normal (0, 1, 0), distance -1) and a ray from the "
                 "origin along %s: the hit is %.4f along the ray; your code returned %s%s", d, expected[k], got,
                 hit && check_near(t, -expected[k], 1e-9) ? ": the sign of the distance?" : "");
        return false;
    }
    return true;
}

CHECK(check_plane_misses) {
    struct plane floor = {{0, 1, 0}, -1.0, 0};
    const struct { ray r; const char *what; } cases[] = {
        {{{0, 0, 0}, {1, 0, 0}}, "a ray parallel to it"},
        {{{0, 0, 0}, {0, 1, 0}}, "a ray pointing up, away from it"},
    };
    for (int k = 0; k < 2; k++) {
        double t = NAN;
        check_calling("plane_intersect", "the plane y = -1 and %s from the origin", cases[k].what);
        if (plane_intersect(&floor, &cases[k].r, 1e-9, INFINITY, &t)) {
            snprintf(why, why_size, "plane_intersect: the plane y = -1 and %s from the origin: expected a miss; your "
                     "code returned a hit at t = %g", cases[k].what, t);
            return false;
        }
    }
    return true;
}

/* One call of plane_intersect on r, for the counter's check: how much it added to the plane tests. */
static uint64_t plane_tests_of_one_call(const ray *r) {
    const struct plane floor = {{0, 1, 0}, -1.0, 0};
    double t;
    uint64_t before = stats_thread.plane_tests;
    plane_intersect(&floor, r, 1e-9, INFINITY, &t);
    return stats_thread.plane_tests - before;
}

CHECK(check_plane_counted) {
    static const ray hit = {{0, 0, 0}, {0, -1, 0}}, miss = {{0, 0, 0}, {0, 1, 0}};
    check_calling("plane_intersect", "the plane y = -1 and a ray from the origin down");
    if (!check_counted_once(plane_tests_of_one_call(&hit), "plane_intersect on a ray that hits", "one plane test",
                            "plane tests", why, why_size))
        return false;
    check_calling("plane_intersect", "the plane y = -1 and a ray from the origin up");
    return check_counted_once(plane_tests_of_one_call(&miss), "plane_intersect on a ray that misses", "one plane test",
                              "plane tests", why, why_size);
}

/* ---- 5.1 the slab test, 5.2 box_intersect ------------------------------------------------------ */

/* Whether ray r runs in the plane of one of the box [-1, 1]^3's faces: a zero direction component with
 * the origin on that face's plane, where (plane - origin) * (1 / 0) is 0 * infinity = NaN. */
static bool in_a_face_plane(ray r) {
    double o[3] = {r.origin.x, r.origin.y, r.origin.z}, d[3] = {r.direction.x, r.direction.y, r.direction.z};
    for (int a = 0; a < 3; a++)
        if (d[a] == 0.0 && fabs(o[a]) == 1.0)
            return true;
    return false;
}

/* Why the slab test may have missed a ray that enters the box at t = expected. */
static const char *missed_hint(ray r) {
    if (in_a_face_plane(r))
        return ": a NaN? The ray runs in a face's plane, so on that axis (plane - origin) * (1 / 0) is "
               "0 * infinity = NaN. Write the comparisons so that a NaN changes nothing, if (t0 > *t_near) "
               "*t_near = t0 (false for NaN), not *t_near = *t_near > t0 ? *t_near : t0 (which takes the NaN), "
               "nor fmin and fmax (which drop the NaN and keep the infinity)";
    if (r.direction.x < 0 || r.direction.y < 0 || r.direction.z < 0)
        return ": the slabs entered from the far side? Moving towards minus, the ray meets the high plane "
               "first: swap t0 and t1 when 1/d < 0";
    return "";
}

/* The box [-1, 1]^3 and a ray: where aabb_hit says it enters (NAN: a miss). */
static bool slab_case(const char *what, ray r, double expected, char *why, size_t why_size) {
    struct aabb b = {{-1, -1, -1}, {1, 1, 1}};
    double entry = NAN;
    char ray_text[160];
    check_calling("clip_to_slab (through aabb_hit)", "the box [-1, 1]^3 and %s, %s", what, check_ray_text(&r, ray_text));
    bool hit = aabb_hit(&b, r.origin, aabb_inverse_direction(r.direction), 0.0, INFINITY, &entry);
    if (isnan(expected) ? !hit : hit && check_near(entry, expected, GEOMETRY_TOLERANCE))
        return true;
    if (isnan(expected))
        snprintf(why, why_size, "the slab test (clip_to_slab in aabb.h, via aabb_hit): the box [-1, 1]^3 and %s, %s: "
                 "expected a miss; it said the ray enters at t = %g", what, ray_text, entry);
    else if (!hit)
        snprintf(why, why_size, "the slab test (clip_to_slab in aabb.h, via aabb_hit): the box [-1, 1]^3 and %s, %s: "
                 "the ray enters at t = %g; it said the ray misses%s", what, ray_text, expected, missed_hint(r));
    else
        snprintf(why, why_size, "the slab test (clip_to_slab in aabb.h, via aabb_hit): the box [-1, 1]^3 and %s, %s: "
                 "the ray enters at t = %g; it said t = %g%s", what, ray_text, expected, entry,
                 check_near(entry, expected + 2.0, 1e-9) ? ": the exit, not the entry? (swap t0 and t1 when 1/d < 0)"
                 : "");
    return false;
}

CHECK(check_slab_hits) {
    return slab_case("a ray", (ray){{0, 0, 5}, {0, 0, -1}}, 4.0, why, why_size) &&
           slab_case("a ray in the negative direction's opposite", (ray){{0, 0, -5}, {0, 0, 1}}, 4.0, why, why_size) &&
           slab_case("a ray from below", (ray){{0.5, -3, 0.5}, {0, 1, 0}}, 2.0, why, why_size) &&
           slab_case("a diagonal ray", (ray){{5, 5, 5}, vec3_normalize(vec3_make(-1, -1, -1))}, 4.0 * sqrt(3.0), why,
                     why_size);
}

CHECK(check_slab_misses) {
    return slab_case("a ray passing beside it", (ray){{3, 0, 5}, {0, 0, -1}}, NAN, why, why_size) &&
           slab_case("a ray pointing away", (ray){{0, 0, 5}, {0, 0, 1}}, NAN, why, why_size) &&
           slab_case("a ray that passes a corner", (ray){{0, 3, 5}, vec3_normalize(vec3_make(0, -1, -0.9))}, NAN, why,
                     why_size);
}

/* Chapter 5's NaN case: a ray running in the plane of a face has an origin on a slab's plane and a zero
 * direction component on that axis. A box's boundary belongs to the box, so the other slabs decide. */
CHECK(check_slab_face_planes) {
    return slab_case("a ray in the plane of the face z = 1", (ray){{-5, 0, 1}, {1, 0, 0}}, 4.0, why, why_size) &&
           slab_case("a ray in the plane of the face z = -1", (ray){{-5, 0, -1}, {1, 0, 0}}, 4.0, why, why_size) &&
           slab_case("a ray in the plane of the face x = 1, moving towards minus z", (ray){{1, 0, 5}, {0, 0, -1}}, 4.0,
                     why, why_size) &&
           slab_case("a ray along the edge where the faces y = 1 and z = 1 meet", (ray){{-5, 1, 1}, {1, 0, 0}}, 4.0,
                     why, why_size) &&
           slab_case("a ray in the plane of the face z = 1 but above the box (y = 2)", (ray){{-5, 2, 1}, {1, 0, 0}},
                     NAN, why, why_size);
}

static bool box_case(const char *what, ray r, double expected, char *why, size_t why_size) {
    struct box b = {{-1, -1, -1}, {1, 1, 1}, 0};
    double t = NAN;
    check_calling("box_intersect", "the box [-1, 1]^3 and %s", what);
    bool hit = box_intersect(&b, &r, 1e-9, INFINITY, &t);
    if (isnan(expected) ? !hit : hit && check_near(t, expected, GEOMETRY_TOLERANCE))
        return true;
    char wanted[64] = "a miss", got[64] = "no hit";
    if (!isnan(expected))
        snprintf(wanted, sizeof wanted, "a hit at t = %g", expected);
    if (hit)
        snprintf(got, sizeof got, "a hit at t = %g", t);
    snprintf(why, why_size, "box_intersect: the box [-1, 1]^3 and %s: expected %s; your code returned %s%s", what,
             wanted, got, !isnan(expected) && !hit && expected < 2 ? ": a ray starting inside hits the box where it "
             "leaves" : "");
    return false;
}

CHECK(check_box_outside) {
    return box_case("a ray from (0, 0, 5) down -z", (ray){{0, 0, 5}, {0, 0, -1}}, 4.0, why, why_size) &&
           box_case("a ray from (3, 0, 5) down -z", (ray){{3, 0, 5}, {0, 0, -1}}, NAN, why, why_size);
}

CHECK(check_box_inside) {
    return box_case("a ray from its centre along +x", (ray){{0, 0, 0}, {1, 0, 0}}, 1.0, why, why_size);
}

/* One call of box_intersect on r, for the counter's check: how much it added to the box tests. */
static uint64_t box_tests_of_one_call(const ray *r) {
    const struct box b = {{-1, -1, -1}, {1, 1, 1}, 0};
    double t;
    uint64_t before = stats_thread.box_tests;
    box_intersect(&b, r, 1e-9, INFINITY, &t);
    return stats_thread.box_tests - before;
}

CHECK(check_box_counted) {
    static const ray hit = {{0, 0, 5}, {0, 0, -1}}, miss = {{3, 0, 5}, {0, 0, -1}};
    check_calling("box_intersect", "the box [-1, 1]^3 and a ray from (0, 0, 5) down -z");
    if (!check_counted_once(box_tests_of_one_call(&hit), "box_intersect on a ray that hits", "one box test",
                            "box tests", why, why_size))
        return false;
    check_calling("box_intersect", "the box [-1, 1]^3 and a ray from (3, 0, 5) down -z");
    return check_counted_once(box_tests_of_one_call(&miss), "box_intersect on a ray that misses", "one box test",
                              "box tests", why, why_size);
}

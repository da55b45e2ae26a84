/* check_textures.c: the coursework checks of chapter 14: the checker pattern and the interpolated normal,
 * on points whose answer is worked out by hand (the coursework kit). */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "mesh_surface.h"
#include "texture.h"

/* Normals are compared within this: far above rounding, far below any mistake. */
#define TEXTURES_TOLERANCE 1e-9

/* ---- 14.1 checker ------------------------------------------------------------------------------ */

/* A checker with the identity transform. */
static struct pigment unit_checker(void) {
    return (struct pigment){.pattern = PIGMENT_CHECKER, .colour = {{0, 0, 0}, {1, 1, 1}}, .scale = {1, 1, 1}};
}

/* Says whether the checker's value at p is `expected`; otherwise fills why. */
static bool checker_is(vec3 p, double expected, const char *where, char *why, size_t why_size) {
    struct pigment c = unit_checker();
    char text[64];
    check_calling("checker", "the point %s", check_vec_text(p, text));
    double got = texture_pattern_value(&c, p);
    if (got == expected)
        return true;
    snprintf(why, why_size, "the checker at %s (%s) is %g, expected %g", text, where, got, expected);
    return false;
}

/* Unit cubes alternate in x, y and z, negative coordinates included (floor, not a cast to int). */
CHECK(check_checker_cubes) {
    return checker_is(vec3_make(0.5, 0.5, 0.5), 0, "the cube at the origin", why, why_size) &&
           checker_is(vec3_make(1.5, 0.5, 0.5), 1, "one cube along x", why, why_size) &&
           checker_is(vec3_make(1.5, 2.5, 0.5), 1, "one along x, two along y", why, why_size) &&
           checker_is(vec3_make(-0.5, 0.5, 0.5), 1, "one cube back along x: floor(-0.5) is -1", why, why_size) &&
           checker_is(vec3_make(-0.5, -0.5, 0.5), 0, "one back along x and one along y", why, why_size);
}

/* A floor at y = 0 hit a hair below 0 still takes the colour of the cube above, as in POV-Ray. */
CHECK(check_checker_boundary) {
    return checker_is(vec3_make(0.5, -1e-12, 0.5), 0, "a hair below the floor at y = 0: POV-Ray adds 1e-10 first",
                      why, why_size) &&
           checker_is(vec3_make(0.5, -1e-6, 0.5), 1, "well below the floor", why, why_size);
}

/* ---- 14.2 mesh_surface_normal -------------------------------------------------------------------- */

/* One triangle (0,0,0), (2,0,0), (0,2,0) whose corners' normals are x, y and z. */
static vec3 corner_points[3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
static vec3 corner_normals[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static struct mesh_face corner_face = {{0, 1, 2}};

static struct scene_mesh corner_mesh(void) {
    return (struct scene_mesh){
        .mesh = {.vertices = corner_points, .vertex_count = 3, .faces = &corner_face, .face_count = 1},
        .corners = {.normals = corner_normals, .normal_count = 3, .normal_faces = &corner_face}};
}

/* Says whether the normal at p is `expected`; otherwise fills why. */
static bool normal_is(vec3 p, vec3 expected, const char *where, char *why, size_t why_size) {
    struct scene_mesh m = corner_mesh();
    vec3 got = {0, 0, 0};
    char text[64], e[64], g[64];
    check_calling("mesh_surface_normal", "the point %s of a triangle whose corner normals are x, y and z",
                  check_vec_text(p, text));
    if (!mesh_surface_normal(&m, 0, p, &got)) {
        snprintf(why, why_size, "mesh_surface_normal at %s (%s) returned false; the corners have normals", text, where);
        return false;
    }
    if (check_vec_near(got, expected, TEXTURES_TOLERANCE))
        return true;
    snprintf(why, why_size, "the normal at %s (%s) is %s, expected %s (length %g)", text, where, check_vec_text(got, g),
             check_vec_text(expected, e), sqrt(got.x * got.x + got.y * got.y + got.z * got.z));
    return false;
}

/* At a corner the normal is that corner's; half way along an edge, the two corners' blended. */
CHECK(check_normal_corners) {
    double h = sqrt(0.5);
    return normal_is(vec3_make(0, 0, 0), vec3_make(1, 0, 0), "corner a", why, why_size) &&
           normal_is(vec3_make(2, 0, 0), vec3_make(0, 1, 0), "corner b", why, why_size) &&
           normal_is(vec3_make(1, 0, 0), vec3_make(h, h, 0), "half way from a to b", why, why_size);
}

/* In the middle the blend of three unit normals is 1/sqrt(3) long: it must be made unit length again. */
CHECK(check_normal_unit) {
    double third = 1.0 / sqrt(3.0);
    return normal_is(vec3_make(2.0 / 3, 2.0 / 3, 0), vec3_make(third, third, third),
                     "the middle: blend, then make it unit length", why, why_size);
}

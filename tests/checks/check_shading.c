/* check_shading.c: the coursework checks of chapters 6 to 8: the Phong model, shadow rays, refraction
 * and the recursion, against values worked out by hand from the formulas in phong.h, shadow.h and
 * whitted.h (the coursework kit). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "phong.h"
#include "plane.h"
#include "scene.h"
#include "shadow.h"
#include "sphere.h"
#include "stats.h"
#include "whitted.h"
#include "world.h"

/* Colours are compared to their exact values within this: far above rounding, far below a mistake. */
#define SHADING_TOLERANCE 1e-9

/* Parses a scene written in the check (camera and image lines added), with the kinds of shape the checks
 * use. False with the reason in why. */
static bool parse(const char *text, struct scene *s, char *why, size_t why_size) {
    static const struct shape_kind *const kinds[] = {&sphere_kind, &plane_kind, NULL};
    char full[2048], err[512];
    snprintf(full, sizeof full, "camera eye 0 0 5  target 0 0 0  fov 40\nimage 8 8\n%s", text);
    if (scene_parse("check.scene", full, kinds, s, err, sizeof err))
        return true;
    snprintf(why, why_size, "the check's own scene did not parse (a framework problem, not your task): %s", err);
    return false;
}

/* parse, then the scene's world (world_init). False with the reason in why; free both otherwise. */
static bool parse_world(const char *text, struct scene *s, struct world *w, char *why, size_t why_size) {
    if (!parse(text, s, why, why_size))
        return false;
    char err[256];
    if (world_init(w, s, err, sizeof err))
        return true;
    snprintf(why, why_size, "world_init failed: %s", err);
    scene_free(s);
    return false;
}

/* ---- 6.1 phong_reflect ----------------------------------------------------------------------- */

CHECK(check_reflect) {
    vec3 d = vec3_normalize(vec3_make(1, -1, 0)), n = vec3_make(0, 1, 0);
    check_calling("phong_reflect", "the direction (0.707, -0.707, 0) and the normal (0, 1, 0)");
    vec3 expected = vec3_normalize(vec3_make(1, 1, 0)), got = phong_reflect(d, n);
    if (check_vec_near(got, expected, SHADING_TOLERANCE))
        return true;
    char e[64], g[64];
    snprintf(why, why_size, "phong_reflect((0.707, -0.707, 0), normal (0, 1, 0)): a ray going down at 45 degrees "
             "leaves going up at 45 degrees, %s; your code returned %s%s", check_vec_text(expected, e),
             check_vec_text(got, g), check_vec_near(got, vec3_scale(expected, -1), 1e-9) ? ": the sign of the 2 (D.N) N term?" : "");
    return false;
}

/* ---- 6.2 phong_shade --------------------------------------------------------------------------- */

/* Shades the origin (normal up, seen from straight above) lit by one white light at `light`, with a
 * material of colour (1, 0.5, 0.25), ambient 0.1, diffuse 0.6, phong 1, phong_size 10 and the ambient
 * light 1: the formula of phong.h worked out here for that one light. */
static bool phong_case(const char *where, vec3 light, char *why, size_t why_size) {
    char text[512];
    snprintf(text, sizeof text,
             "ambient_light 1 1 1\nlight position %.17g %.17g %.17g colour 1 1 1\n"
             "material m colour 1 0.5 0.25 ambient 0.1 diffuse 0.6 phong 1 phong_size 10\nsphere centre 0 -1 0 radius 1 material m\n",
             light.x, light.y, light.z);
    struct scene s;
    if (!parse(text, &s, why, why_size))
        return false;
    const struct material *m = &s.materials[scene_find_material(&s, "m")];
    struct phong_surface at = {vec3_make(0, 0, 0), vec3_make(0, 1, 0), vec3_make(0, -1, 0), m, 1.0};
    check_calling("phong_shade", "the origin, normal (0, 1, 0), seen from above, one white light %s", where);
    vec3 got = phong_shade(&s, &at, NULL, NULL);
    vec3 colour = vec3_make(1, 0.5, 0.25), l = vec3_normalize(light);
    double cosine = l.y, mirror = l.y; /* N = R = (0, 1, 0) here */
    vec3 ambient = vec3_scale(colour, 0.1);
    vec3 diffuse = cosine > 0 ? vec3_scale(colour, 0.6 * cosine) : vec3_make(0, 0, 0);
    double highlight = cosine > 0 && mirror > 0 ? pow(mirror, 10) : 0.0;
    vec3 expected = vec3_add(vec3_add(ambient, diffuse), vec3_make(highlight, highlight, highlight));
    scene_free(&s);
    if (check_vec_near(got, expected, SHADING_TOLERANCE))
        return true;
    char e[64], g[64];
    const char *hint = "";
    if (check_vec_near(got, vec3_sub(expected, ambient), 1e-9))
        hint = ": the ambient term is missing";
    else if (check_vec_near(got, vec3_sub(expected, vec3_make(highlight, highlight, highlight)), 1e-9) && highlight > 0)
        hint = ": the highlight is missing";
    else if (check_vec_near(got, vec3_add(vec3_sub(expected, vec3_make(highlight, highlight, highlight)),
                                          vec3_scale(colour, highlight)), 1e-9) && highlight > 0)
        hint = ": the highlight is tinted by the surface colour; it has the light's colour";
    else if (cosine > 0 && check_vec_near(got, vec3_add(vec3_add(ambient, vec3_scale(colour, 0.6)),
                                                        vec3_make(highlight, highlight, highlight)), 1e-9))
        hint = ": the diffuse term lacks the cosine N.L";
    else if (cosine <= 0)
        hint = ": a light behind the surface adds nothing but the ambient";
    snprintf(why, why_size, "phong_shade at the origin, normal (0, 1, 0), seen from above, colour (1, 0.5, 0.25), "
             "ambient 0.1, diffuse 0.6, phong 1, phong_size 10, one white light %s: expected %s, got %s%s", where,
             check_vec_text(expected, e), check_vec_text(got, g), hint);
    return false;
}

CHECK(check_phong_overhead) { return phong_case("straight above at (0, 10, 0)", vec3_make(0, 10, 0), why, why_size); }
CHECK(check_phong_slanted) { return phong_case("at 45 degrees, (10, 10, 0)", vec3_make(10, 10, 0), why, why_size); }
CHECK(check_phong_behind) { return phong_case("below the surface, (0, -10, 0)", vec3_make(0, -10, 0), why, why_size); }

/* ---- 7.1 shadow_opaque ------------------------------------------------------------------------- */

/* shadow_opaque from `point` to a light at `light` in a scene holding the spheres `spheres`. */
static bool shadow_case(const char *what, const char *spheres, vec3 point, vec3 light, bool lit, char *why,
                        size_t why_size) {
    char text[1024];
    snprintf(text, sizeof text, "light position %.17g %.17g %.17g\n%s", light.x, light.y, light.z, spheres);
    struct scene s;
    struct world w;
    if (!parse_world(text, &s, &w, why, why_size))
        return false;
    char p[64], l[64], g[64];
    check_calling("shadow_opaque", "the point %s and a light at %s, %s", check_vec_text(point, p),
                  check_vec_text(light, l), what);
    vec3 got = shadow_opaque(&w, point, &s.lights[0]);
    world_free(&w);
    scene_free(&s);
    vec3 expected = lit ? vec3_make(1, 1, 1) : vec3_make(0, 0, 0);
    if (check_vec_near(got, expected, 0.0))
        return true;
    snprintf(why, why_size, "shadow_opaque from %s to a light at %s, %s: expected %s, got %s", p, l, what,
             lit ? "(1, 1, 1), lit" : "(0, 0, 0), in shadow", check_vec_text(got, g));
    return false;
}

CHECK(check_shadow_blocked) {
    return shadow_case("a sphere of radius 1 at (0, 5, 0) in between", "sphere centre 0 5 0 radius 1\n",
                       vec3_make(0, 0, 0), vec3_make(0, 10, 0), false, why, why_size);
}

CHECK(check_shadow_clear) {
    return shadow_case("the sphere at (0, 5, 0) is off to the side", "sphere centre 0 5 0 radius 1\n",
                       vec3_make(5, 0, 0), vec3_make(5, 10, 0), true, why, why_size) &&
           shadow_case("the sphere at (0, 5, 0) is beyond the light: only blockers before the light count",
                       "sphere centre 0 5 0 radius 1\n", vec3_make(0, 0, 0), vec3_make(0, 2, 0), true, why, why_size);
}

CHECK(check_shadow_no_acne) {
    /* Points on the surface of the unit sphere, lit from outside: rounding puts the point a hair inside
     * or outside, and a shadow ray from t = 0 may meet the sphere itself at t ~ 1e-16. */
    for (int k = 1; k <= 40; k++) {
        vec3 n = vec3_normalize(vec3_make(sin(k * 1.3), cos(k * 0.7), sin(k * 2.9) + 0.1));
        vec3 p = vec3_scale(n, 1.0);
        char what[256];
        snprintf(what, sizeof what, "the point is on the unit sphere and the light outside it, above the point: "
                 "the sphere must not shadow itself (shadow acne; start the shadow ray at SHADOW_T_MIN)");
        if (!shadow_case(what, "sphere centre 0 0 0 radius 1\n", p, vec3_scale(n, 10.0), true, why, why_size))
            return false;
    }
    return true;
}

/* The margin at the end of the shadow ray: its surface passes SHADOW_T_MIN / 2 below the light, so the
 * sphere holds the light, and meets the shadow ray within the last SHADOW_T_MIN before it. */
CHECK(check_shadow_end_margin) {
    char spheres[128], what[512];
    snprintf(spheres, sizeof spheres, "sphere centre 0 %.17g 0 radius 1\n", 11.0 - SHADOW_T_MIN / 2);
    snprintf(what, sizeof what, "a sphere of radius 1 whose lowest point is %g below the light, within the margin at "
             "the end: a shape that touches the light must not block it (blockers count only for SHADOW_T_MIN < t < "
             "distance - SHADOW_T_MIN)", SHADOW_T_MIN / 2);
    return shadow_case(what, spheres, vec3_make(0, 0, 0), vec3_make(0, 10, 0), true, why, why_size);
}

CHECK(check_shadow_counted) {
    struct scene s;
    struct world w;
    if (!parse_world("light position 0 10 0\nsphere centre 0 5 0 radius 1\n", &s, &w, why, why_size))
        return false;
    check_calling("shadow_opaque", "the point (5, 0, 0) and a light at (5, 10, 0)");
    uint64_t before = stats_thread.shadow_rays;
    shadow_opaque(&w, vec3_make(5, 0, 0), &s.lights[0]);
    uint64_t clear = stats_thread.shadow_rays - before;
    check_calling("shadow_opaque", "the point (0, 0, 0) and a light at (0, 10, 0), a sphere in between");
    before = stats_thread.shadow_rays;
    shadow_opaque(&w, vec3_make(0, 0, 0), &s.lights[0]);
    uint64_t blocked = stats_thread.shadow_rays - before;
    world_free(&w);
    scene_free(&s);
    return check_counted_once(clear, "shadow_opaque towards a light in view", "one shadow ray", "shadow rays", why,
                              why_size) &&
           check_counted_once(blocked, "shadow_opaque towards a light behind a sphere", "one shadow ray",
                              "shadow rays", why, why_size);
}

/* ---- 8.1 whitted_refract ----------------------------------------------------------------------- */

CHECK(check_refract_snell) {
    /* From air into glass (eta = 1 / 1.5) at 45 degrees: sin(out) = sin(45) / 1.5. */
    vec3 d = vec3_normalize(vec3_make(1, -1, 0)), n = vec3_make(0, 1, 0), got = vec3_make(0, 0, 0);
    double s = M_SQRT1_2 / 1.5;
    vec3 expected = vec3_make(s, -sqrt(1 - s * s), 0);
    check_calling("whitted_refract", "the direction (0.707, -0.707, 0), the normal (0, 1, 0) and eta 1/1.5");
    bool ok = whitted_refract(d, n, 1.0 / 1.5, &got);
    if (ok && check_vec_near(got, expected, SHADING_TOLERANCE))
        return true;
    char e[64], g[64];
    snprintf(why, why_size, "whitted_refract((0.707, -0.707, 0), normal (0, 1, 0), eta 1/1.5): into glass at 45 "
             "degrees the ray bends towards the normal, to %s (Snell: sin 45 / 1.5 = %.4f); your code returned %s%s",
             check_vec_text(expected, e), s, ok ? "" : "false (total internal reflection) and ", check_vec_text(got, g));
    return false;
}

CHECK(check_refract_total_internal_reflection) {
    /* From glass into air (eta = 1.5) at 60 degrees: 1.5 sin 60 = 1.3 > 1, no refracted ray. */
    vec3 d = vec3_make(sin(M_PI / 3), -cos(M_PI / 3), 0), n = vec3_make(0, 1, 0), got = vec3_make(7, 7, 7);
    check_calling("whitted_refract", "the direction (0.866, -0.5, 0), the normal (0, 1, 0) and eta 1.5");
    bool refracted = whitted_refract(d, n, 1.5, &got);
    if (!refracted && check_vec_near(got, vec3_make(7, 7, 7), 0.0))
        return true;
    char g[64];
    snprintf(why, why_size, "whitted_refract at 60 degrees from glass (eta 1.5) into air: 1.5 sin 60 = 1.3 > 1, "
             "so it must return false and leave *out alone (total internal reflection); it returned %s%s",
             refracted ? "true with " : "false but wrote ", check_vec_text(got, g));
    return false;
}

/* ---- 8.2 the recursion ------------------------------------------------------------------------- */

/* The colour whitted_trace sees along r in the scene `text`. */
static bool trace_case(const char *what, const char *text, ray r, vec3 expected, char *why, size_t why_size) {
    struct scene s;
    struct world w;
    if (!parse_world(text, &s, &w, why, why_size))
        return false;
    char ray_text[160];
    check_calling("trace (through whitted_trace)", "%s: %s", what, check_ray_text(&r, ray_text));
    vec3 got = whitted_trace(&w, &r);
    world_free(&w);
    scene_free(&s);
    if (check_vec_near(got, expected, SHADING_TOLERANCE))
        return true;
    char e[64], g[64];
    snprintf(why, why_size, "whitted_trace: %s: expected %s, got %s", what, check_vec_text(expected, e),
             check_vec_text(got, g));
    return false;
}

CHECK(check_recursion_mirror) {
    return trace_case("a ray from (0, 1, 0) down at 45 degrees onto a black floor with reflection 0.5, under a "
                      "background (0.2, 0.4, 0.6): it sees half the background in the mirror",
                      "background 0.2 0.4 0.6\nmaterial m colour 1 1 1 ambient 0 diffuse 0 reflection 0.5\n"
                      "plane normal 0 1 0 distance 0 material m\n",
                      (ray){{0, 1, 0}, {0, -M_SQRT1_2, M_SQRT1_2}}, vec3_make(0.1, 0.2, 0.3), why, why_size);
}

/* Two facing mirrors (reflection 0.5, ambient red 1): each level adds half the one before. */
static const char facing_mirrors[] = "ambient_light 1 1 1\nmaterial m colour 1 0 0 ambient 1 diffuse 0 reflection 0.5\n"
                                     "plane normal 0 1 0 distance 0 material m\nplane normal 0 -1 0 distance -2 material m\n";

CHECK(check_recursion_depth) {
    char text[1024];
    snprintf(text, sizeof text, "max_depth 3\n%s", facing_mirrors);
    if (!trace_case("a ray bouncing between two facing red mirrors (y = 0 and y = 2, ambient 1, reflection 0.5), "
                    "max_depth 3: 1 + 0.5 + 0.25 of red, then black",
                    text, (ray){{0, 1, 0}, {0, -1, 0}}, vec3_make(1.75, 0, 0), why, why_size))
        return false;
    snprintf(text, sizeof text, "max_depth 1\n%s", facing_mirrors);
    return trace_case("the same two mirrors with max_depth 1: the camera ray's own surface only",
                      text, (ray){{0, 1, 0}, {0, -1, 0}}, vec3_make(1, 0, 0), why, why_size);
}

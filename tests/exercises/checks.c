/* checks.c: the checks that grade the walkthroughs' build exercises (see exercises.h). Expected values
 * are worked out here from geometry, never taken from the code under test. */
#include "exercises.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "shadow.h"
#include "sphere.h"
#include "world.h"

#define CHECK_TOLERANCE 1e-9 /* analytic values are met to rounding, far below this */

/* Writes the message into why; returns false, so a check can `return fail(...)`. */
static bool fail(char *why, size_t why_size, const char *format, ...) {
    va_list args;
    va_start(args, format);
    vsnprintf(why, why_size, format, args);
    va_end(args);
    return false;
}

static bool near(double a, double b) { return fabs(a - b) <= CHECK_TOLERANCE * fmax(1.0, fabs(b)); }

static ray make_ray(double ox, double oy, double oz, double dx, double dy, double dz) {
    return (ray){vec3_make(ox, oy, oz), vec3_normalize(vec3_make(dx, dy, dz))};
}

/* ---- 2.4 the disc, a kind of shape --------------------------------------------------------------- */

#define DISC_ITEM_MAX 256 /* bytes for one disc: a centre, a normal, a radius and a material need 60 */

/* One disc, in memory the size and alignment of any struct. */
struct disc_item {
    _Alignas(max_align_t) unsigned char bytes[DISC_ITEM_MAX];
};

/* Makes a disc of `kind` in *item with the keys centre, normal and radius (material 0). Returns the
 * kind's make's answer; on false, its reason is in why. */
static bool make_disc(const struct shape_kind *kind, struct disc_item *item, vec3 centre, vec3 normal,
                      double radius, char *why, size_t why_size) {
    const struct shape_syntax *syntax = kind->syntax;
    static const char *const names[] = {"centre", "normal", "radius"};
    struct key_values kv;
    memset(&kv, 0, sizeof kv);
    for (int n = 0; n < 3; n++)
        for (int k = 0; k < syntax->key_count && k < KEY_MAX; k++)
            if (strcmp(syntax->keys[k].name, names[n]) == 0) {
                kv.present[k] = true;
                vec3 v = n == 0 ? centre : normal;
                double values[3] = {n == 2 ? radius : v.x, v.y, v.z};
                memcpy(kv.number[k], values, sizeof values);
            }
    memset(item, 0, sizeof *item);
    why[0] = '\0';
    return syntax->make(&kv, item->bytes, why, why_size);
}

static void set_material(const struct shape_kind *kind, struct disc_item *item, int material) {
    memcpy(item->bytes + kind->syntax->material_offset, &material, sizeof material);
}

/* Counts the crossings the kind reports along r; stores the last t in *t. */
struct crossing_count {
    int count;
    double t;
    int material;
};

static bool count_crossing(void *context, double t, int material) {
    struct crossing_count *c = context;
    c->count++;
    c->t = t;
    c->material = material;
    return true;
}

/* The parts of the kind that every check below needs; false with the reason when one is missing. */
static bool disc_kind_complete(const struct shape_kind *kind, char *why, size_t why_size) {
    const struct shape_syntax *syntax = kind->syntax;
    if (syntax == NULL || syntax->make == NULL || syntax->write_pov == NULL || syntax->keys == NULL ||
        syntax->required == NULL)
        return fail(why, why_size, "the disc has no syntax: does disc_kind point at disc_syntax, with its keys, its "
                    "required keys, a make and a write_pov?");
    if (syntax->keyword == NULL || strcmp(syntax->keyword, "disc") != 0 || syntax->plural == NULL ||
        strcmp(syntax->plural, "discs") != 0)
        return fail(why, why_size, "the disc's line should have the keyword \"disc\" and the plural \"discs\", got "
                    "\"%s\" and \"%s\"", syntax->keyword != NULL ? syntax->keyword : "(none)",
                    syntax->plural != NULL ? syntax->plural : "(none)");
    if (kind->closest == NULL || kind->crossings == NULL || kind->bounds == NULL)
        return fail(why, why_size, "the disc's ray queries are missing: does disc_kind hold closest, crossings "
                    "and bounds?");
    if (syntax->size > DISC_ITEM_MAX || syntax->material_offset + sizeof(int) > syntax->size)
        return fail(why, why_size, "struct disc is %zu bytes with its material at %zu: expected a small struct "
                    "with an int material", syntax->size, syntax->material_offset);
    static const struct key_spec wanted[] = {{"centre", 3}, {"normal", 3}, {"radius", 1}};
    for (int n = 0; n < 3; n++) {
        bool found = false;
        for (int k = 0; k < syntax->key_count; k++)
            found |= strcmp(syntax->keys[k].name, wanted[n].name) == 0 && syntax->keys[k].count == wanted[n].count;
        if (!found)
            return fail(why, why_size, "the disc's keys should include '%s' with %d number%s", wanted[n].name,
                        wanted[n].count, wanted[n].count == 1 ? "" : "s");
    }
    return true;
}

/* The scene line's checks, and the POV-Ray form of a disc facing +y given as normal (0, 2, 0). */
static bool check_disc_syntax(const struct shape_kind *kind, char *why, size_t why_size) {
    struct disc_item item;
    char reason[256];
    vec3 origin = {0, 0, 0}, up = {0, 1, 0};
    if (make_disc(kind, &item, origin, up, 0.0, reason, sizeof reason))
        return fail(why, why_size, "`disc ... radius 0` was accepted: a disc needs a radius above 0");
    if (reason[0] == '\0')
        return fail(why, why_size, "`disc ... radius 0` was refused without a reason in why");
    if (make_disc(kind, &item, origin, vec3_make(0, 0, 0), 1.0, reason, sizeof reason))
        return fail(why, why_size, "`disc ... normal 0 0 0` was accepted: a zero normal gives no plane");
    if (!make_disc(kind, &item, origin, vec3_make(0, 2, 0), 1.0, reason, sizeof reason))
        return fail(why, why_size, "`disc centre 0 0 0 normal 0 2 0 radius 1` was refused: %s", reason);
    char *text = NULL;
    size_t length = 0;
    FILE *out = open_memstream(&text, &length);
    if (out == NULL)
        return fail(why, why_size, "out of memory");
    kind->syntax->write_pov(out, item.bytes);
    fclose(out);
    static const char expected[] = "disc { <0, 0, 0>, <0, 1, 0>, 1";
    bool same = text != NULL && strcmp(text, expected) == 0;
    if (!same)
        fail(why, why_size, "POV-Ray form of `disc centre 0 0 0 normal 0 2 0 radius 1`: expected \"%s\" (the "
             "normal made unit length, no texture, no closing brace), got \"%s\"", expected, text != NULL ? text : "");
    free(text);
    return same;
}

bool check_disc(const struct shape_kind *kind, char *why, size_t why_size) {
    if (!disc_kind_complete(kind, why, why_size) || !check_disc_syntax(kind, why, why_size))
        return false;
    static const struct {
        const char *what;
        ray r;
        double t_max, expected; /* expected t, or -1 for a miss */
    } cases[] = {
        {"straight down onto the disc, 0.5 from its centre", {{0.5, 2, 0}, {0, -1, 0}}, INFINITY, 2.0},
        {"straight down, 1.5 from the centre (outside the radius)", {{1.5, 2, 0}, {0, -1, 0}}, INFINITY, -1},
        {"straight up from below (a disc has two sides)", {{0.3, -3, 0.4}, {0, 1, 0}}, INFINITY, 3.0},
        {"onto the rim, exactly 1 from the centre", {{1, 2, 0}, {0, -1, 0}}, INFINITY, 2.0},
        {"parallel to the disc, in its plane's direction", {{0, 1, 0}, {1, 0, 0}}, INFINITY, -1},
        {"straight down, but t_max = 1.5 ends the ray before the disc", {{0.5, 2, 0}, {0, -1, 0}}, 1.5, -1},
        {"pointing away from the disc", {{0.5, 2, 0}, {0, 1, 0}}, INFINITY, -1},
    };
    char reason[256];
    struct disc_item item;
    make_disc(kind, &item, vec3_make(0, 0, 0), vec3_make(0, 1, 0), 1.0, reason, sizeof reason);
    set_material(kind, &item, 7);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        struct hit h = hit_nothing(cases[k].t_max);
        bool hit = kind->closest(item.bytes, 1, &cases[k].r, RAY_T_MIN, &h);
        if (cases[k].expected < 0 && hit)
            return fail(why, why_size, "disc of radius 1 at the origin facing +y, ray %s: expected a miss, your "
                        "closest returned a hit at t = %g", cases[k].what, h.t);
        if (cases[k].expected >= 0 && !hit)
            return fail(why, why_size, "disc of radius 1 at the origin facing +y, ray %s: expected a hit at t = %g, "
                        "your closest returned a miss", cases[k].what, cases[k].expected);
        if (hit && !near(h.t, cases[k].expected))
            return fail(why, why_size, "disc of radius 1 at the origin facing +y, ray %s: expected t = %g, got %.17g",
                        cases[k].what, cases[k].expected, h.t);
        if (hit && (!near(fabs(h.normal.y), 1.0) || !near(h.normal.x, 0.0) || !near(h.normal.z, 0.0) ||
                    h.material != 7))
            return fail(why, why_size, "disc of radius 1 at the origin facing +y, material 7, ray %s: expected the "
                        "normal (0, +-1, 0) and material 7, got (%g, %g, %g) and %d", cases[k].what, h.normal.x,
                        h.normal.y, h.normal.z, h.material);
        struct crossing_count crossings = {0, 0.0, -1};
        kind->crossings(item.bytes, 1, &cases[k].r, RAY_T_MIN, cases[k].t_max, count_crossing, &crossings);
        int expected_count = cases[k].expected < 0 ? 0 : 1;
        if (crossings.count != expected_count || (expected_count == 1 && (!near(crossings.t, cases[k].expected) ||
                                                                          crossings.material != 7)))
            return fail(why, why_size, "disc of radius 1 at the origin facing +y, ray %s: expected %d crossing%s, "
                        "your crossings reported %d", cases[k].what, expected_count, expected_count == 1 ? " at t = 2 "
                        "or 3 with material 7" : "s", crossings.count);
    }
    /* Two discs in one array, the second nearer: the search must step through the array by the size of a
     * disc and keep the nearest. */
    struct disc_item pair[2];
    make_disc(kind, &pair[0], vec3_make(0, 0, 0), vec3_make(0, 1, 0), 1.0, reason, sizeof reason);
    make_disc(kind, &pair[1], vec3_make(0, 1, 0), vec3_make(0, 1, 0), 1.0, reason, sizeof reason);
    size_t size = kind->syntax->size, material_offset = kind->syntax->material_offset;
    unsigned char both[2 * DISC_ITEM_MAX];
    memcpy(both, pair[0].bytes, size);
    memcpy(both + size, pair[1].bytes, size);
    memcpy(both + material_offset, &(int){3}, sizeof(int));
    memcpy(both + size + material_offset, &(int){4}, sizeof(int));
    ray down = make_ray(0.2, 2, 0.1, 0, -1, 0);
    struct hit h = hit_nothing(INFINITY);
    if (!kind->closest(both, 2, &down, RAY_T_MIN, &h) || !near(h.t, 1.0) || h.material != 4 || h.object != 1)
        return fail(why, why_size, "discs at y = 0 (material 3) and y = 1 (material 4), ray straight down from "
                    "y = 2: expected the nearer at t = 1 with material 4 and object 1 (its index in the array), got "
                    "t = %g, material %d, object %d", h.t, h.material, h.object);
    /* A tilted disc, given with a normal that is not unit length: a ray along its normal from 4 units
     * away meets its centre at t = 4. */
    vec3 tilted = vec3_normalize(vec3_make(1, 1, 1)), at = {1, 2, 3};
    make_disc(kind, &item, at, vec3_make(1, 1, 1), 0.5, reason, sizeof reason);
    ray r = {vec3_add_scaled(at, tilted, 4.0), vec3_neg(tilted)};
    h = hit_nothing(INFINITY);
    if (!kind->closest(item.bytes, 1, &r, RAY_T_MIN, &h) || !near(h.t, 4.0))
        return fail(why, why_size, "disc at (1, 2, 3) facing (1, 1, 1), ray along its normal from 4 away: expected "
                    "t = 4, got %s %.17g (does your code assume the normal is +y, or unit length?)",
                    hit_found(&h) ? "" : "a miss,", h.t);
    /* Its box must hold the rim, and be no larger than the cube around the sphere through the rim. */
    vec3 min, max;
    if (!kind->bounds(item.bytes, &min, &max))
        return fail(why, why_size, "your bounds say the disc has no bounding box; it has one");
    vec3 u = vec3_normalize(vec3_cross(tilted, vec3_make(0, 0, 1))), v = vec3_cross(tilted, u);
    for (int k = 0; k < 64; k++) {
        double angle = 2.0 * M_PI * k / 64.0;
        vec3 rim = vec3_add(at, vec3_add(vec3_scale(u, 0.5 * cos(angle)), vec3_scale(v, 0.5 * sin(angle))));
        for (int a = 0; a < 3; a++)
            if (vec3_axis(rim, a) < vec3_axis(min, a) - CHECK_TOLERANCE ||
                vec3_axis(rim, a) > vec3_axis(max, a) + CHECK_TOLERANCE)
                return fail(why, why_size, "disc at (1, 2, 3) facing (1, 1, 1), radius 0.5: the rim point (%g, %g, %g) "
                            "is outside your bounds (%g, %g, %g) to (%g, %g, %g)", rim.x, rim.y, rim.z, min.x, min.y,
                            min.z, max.x, max.y, max.z);
    }
    for (int a = 0; a < 3; a++)
        if (vec3_axis(min, a) < vec3_axis(at, a) - 0.5 - CHECK_TOLERANCE ||
            vec3_axis(max, a) > vec3_axis(at, a) + 0.5 + CHECK_TOLERANCE)
            return fail(why, why_size, "disc at (1, 2, 3) of radius 0.5: your bounds (%g, %g, %g) to (%g, %g, %g) "
                        "reach beyond the radius", min.x, min.y, min.z, max.x, max.y, max.z);
    return true;
}

/* ---- 3.4 smooth normals ---------------------------------------------------------------------------- */

bool check_vertex_normals(vertex_normals_fn f, char *why, size_t why_size) {
    /* An octahedron, wound outwards, and one vertex that no face uses. By symmetry each corner's normal
     * points straight out. */
    vec3 v[7] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {5, 5, 5}};
    struct mesh_face faces[8];
    int k = 0;
    for (int sx = 0; sx < 2; sx++)
        for (int sy = 0; sy < 2; sy++)
            for (int sz = 0; sz < 2; sz++) {
                uint32_t a = (uint32_t)sx, b = 2 + (uint32_t)sy, c = 4 + (uint32_t)sz;
                bool odd = (sx + sy + sz) % 2 == 1; /* wind each face so its normal points outwards */
                faces[k++] = odd ? (struct mesh_face){{a, c, b}} : (struct mesh_face){{a, b, c}};
            }
    struct mesh m = {v, 7, faces, 8};
    vec3 n[7];
    for (int i = 0; i < 7; i++)
        n[i] = vec3_make(NAN, NAN, NAN);
    f(&m, n);
    for (int i = 0; i < 6; i++)
        if (!near(n[i].x, v[i].x) || !near(n[i].y, v[i].y) || !near(n[i].z, v[i].z))
            return fail(why, why_size, "octahedron with corners at (+-1, 0, 0), (0, +-1, 0), (0, 0, +-1): the normal at "
                        "corner (%g, %g, %g) should point straight out, (%g, %g, %g); got (%g, %g, %g)", v[i].x, v[i].y,
                        v[i].z, v[i].x, v[i].y, v[i].z, n[i].x, n[i].y, n[i].z);
    if (!(n[6].x == 0 && n[6].y == 0 && n[6].z == 0))
        return fail(why, why_size, "a vertex that no face uses should get (0, 0, 0); got (%g, %g, %g)", n[6].x, n[6].y,
                    n[6].z);
    /* Two faces of very different sizes meet at the origin: a large one facing +z (area 50) and a small
     * one facing +x (area 0.5). Weighted by area, the normal is (1, 0, 100) normalised. */
    vec3 w[5] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 1, 0}, {0, 0, 1}};
    struct mesh_face two[2] = {{{0, 1, 2}}, {{0, 3, 4}}};
    struct mesh weighted = {w, 5, two, 2};
    vec3 out[5];
    f(&weighted, out);
    vec3 expected = vec3_normalize(vec3_make(1, 0, 100));
    if (!near(out[0].x, expected.x) || !near(out[0].y, expected.y) || !near(out[0].z, expected.z))
        return fail(why, why_size, "a vertex shared by a triangle of area 50 facing +z and one of area 0.5 facing +x: "
                    "expected (%.6f, 0, %.6f), weighted by area; got (%.6f, %.6f, %.6f)%s", expected.x, expected.z,
                    out[0].x, out[0].y, out[0].z, near(out[0].x, out[0].z) ? " (an unweighted average?)" : "");
    return true;
}

/* ---- 4.4 the cylinder ------------------------------------------------------------------------------ */

bool check_cylinder(cylinder_fn f, char *why, size_t why_size) {
    double s29 = sqrt(29.0);
    static const double none = -1;
    const struct {
        const char *what;
        ray r;
        double expected;
    } cases[] = {
        {"from (-5, 1, 0) along +x: the near side at x = -1", make_ray(-5, 1, 0, 1, 0, 0), 4.0},
        {"from the axis (0, 1, 0) along +x: the inside of the wall", make_ray(0, 1, 0, 1, 0, 0), 1.0},
        {"from (-5, 1, 0.5) along +x: off the axis", make_ray(-5, 1, 0.5, 1, 0, 0), 5.0 - sqrt(0.75)},
        {"from (-5, 3, 0) along +x: above the top (y = 2)", make_ray(-5, 3, 0, 1, 0, 0), none},
        {"from (0, 5, 0) straight down the axis (no caps)", make_ray(0, 5, 0, 0, -1, 0), none},
        {"from (-5, -1, 0) towards (5, 2, 0): rising into the side", make_ray(-5, -1, 0, 5, 2, 0), 4.0 * s29 / 5.0},
        {"from (-5, -3, 0) towards (5, 2, 0): passes below the base", make_ray(-5, -3, 0, 5, 2, 0), none},
        {"from (-5, 1, 0) along -x: pointing away", make_ray(-5, 1, 0, -1, 0, 0), none},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double t = -1;
        bool hit = f(vec3_make(0, 0, 0), 1.0, 2.0, &cases[k].r, RAY_T_MIN, INFINITY, &t);
        if (hit != (cases[k].expected >= 0) || (hit && !near(t, cases[k].expected)))
            return fail(why, why_size, "open cylinder of radius 1 from (0, 0, 0) to (0, 2, 0), ray %s: expected %s%.6g, "
                        "got %s%.6g", cases[k].what, cases[k].expected < 0 ? "a miss" : "t = ",
                        cases[k].expected < 0 ? NAN : cases[k].expected, hit ? "t = " : "a miss", hit ? t : NAN);
    }
    return true;
}

/* ---- 5.4 the bounding sphere ------------------------------------------------------------------------ */

bool check_bounding_sphere(bounding_sphere_fn f, char *why, size_t why_size) {
    enum { POINTS = 200 };
    vec3 v[POINTS];
    uint64_t state = 12345;
    for (int k = 0; k < POINTS; k++) { /* a fixed cloud in the box [-3, 5] x [0, 1] x [2, 4] */
        double u[3];
        for (int a = 0; a < 3; a++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            u[a] = (double)(state >> 11) / 9007199254740992.0;
        }
        v[k] = vec3_make(-3 + 8 * u[0], u[1], 2 + 2 * u[2]);
    }
    struct mesh m = {v, POINTS, NULL, 0};
    vec3 centre;
    double radius;
    f(&m, &centre, &radius);
    /* Written as "not inside" rather than "outside", so that a NaN radius or centre fails too. */
    for (int k = 0; k < POINTS; k++) {
        double d = vec3_length(vec3_sub(v[k], centre));
        if (!(d <= radius * (1 + 1e-12)))
            return fail(why, why_size, "200 points in the box [-3, 5] x [0, 1] x [2, 4]: point (%g, %g, %g) is %g from "
                        "your centre (%g, %g, %g), outside your radius %g", v[k].x, v[k].y, v[k].z, d, centre.x,
                        centre.y, centre.z, radius);
    }
    struct aabb box = aabb_empty();
    for (int k = 0; k < POINTS; k++)
        box = aabb_grow(box, v[k]);
    double box_radius = 0.5 * vec3_length(vec3_sub(box.max, box.min));
    if (!(radius <= box_radius * (1 + 1e-12)))
        return fail(why, why_size, "200 points in the box [-3, 5] x [0, 1] x [2, 4]: your radius %g is larger than "
                    "that of the sphere around their bounding box, %g", radius, box_radius);
    return true;
}

/* ---- 6.4 Blinn's highlight ------------------------------------------------------------------------- */

bool check_blinn(blinn_fn f, char *why, size_t why_size) {
    vec3 n = {0, 0, 1};
    const struct {
        const char *what;
        vec3 light, eye;
        double exponent, expected;
    } cases[] = {
        {"light and eye mirrored about the normal (H = N)", vec3_normalize(vec3_make(1, 0, 1)),
         vec3_normalize(vec3_make(-1, 0, 1)), 10, 1.0},
        {"light on the normal, eye 45 degrees off (H is 22.5 degrees off N)", {0, 0, 1},
         vec3_normalize(vec3_make(1, 0, 1)), 10, pow(cos(M_PI / 8), 10)},
        {"light and eye both 60 degrees off on the same side (H 60 degrees off N)",
         vec3_make(sin(M_PI / 3), 0, cos(M_PI / 3)), vec3_make(sin(M_PI / 3), 0, cos(M_PI / 3)), 4, pow(0.5, 4)},
        {"light below the surface", {0, 0, -1}, vec3_normalize(vec3_make(1, 0, 1)), 10, 0.0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double got = f(n, cases[k].light, cases[k].eye, cases[k].exponent);
        if (!near(got, cases[k].expected))
            return fail(why, why_size, "normal (0, 0, 1), %s, exponent %g: expected %.9f, got %.9f", cases[k].what,
                        cases[k].exponent, cases[k].expected, got);
    }
    return true;
}

/* ---- 7.4 soft shadows -------------------------------------------------------------------------------- */

bool check_area_fraction(area_fraction_fn f, char *why, size_t why_size) {
    /* A ball of radius 0.5 at (0, 1, 0) over the floor, and a 1 x 1 light at height 3 above it. */
    static const char *const text = "camera eye 0 2 8 target 0 0 0 fov 40\nimage 8 8\n"
                                    "sphere centre 0 1 0 radius 0.5\n";
    static const struct shape_kind *const kinds[] = {&sphere_kind, NULL};
    struct scene s;
    char err[256];
    if (!scene_parse("soft-shadow-check.scene", text, kinds, &s, err, sizeof err))
        return fail(why, why_size, "internal: %s", err);
    struct world w;
    if (!world_init(&w, &s, err, sizeof err)) {
        scene_free(&s);
        return fail(why, why_size, "internal: %s", err);
    }
    vec3 corner = {-0.5, 3, -0.5}, edge_u = {1, 0, 0}, edge_v = {0, 0, 1};
    bool ok = true;
    double under = f(&w, vec3_make(0, 0, 0), corner, edge_u, edge_v, 4);
    double aside = f(&w, vec3_make(5, 0, 0), corner, edge_u, edge_v, 4);
    if (under != 0.0)
        ok = fail(why, why_size, "the point (0, 0, 0) right under the ball sees none of the light; got %g", under);
    else if (aside != 1.0)
        ok = fail(why, why_size, "the point (5, 0, 0), far to the side, sees all of the light; got %g", aside);
    /* Walking out from under the ball, the share rises from 0 to 1 through the penumbra, in steps of 1/16
     * with a 4 x 4 grid; with n = 1 it is the hard shadow of a light at the square's centre. */
    bool penumbra = false;
    double previous = 0.0;
    for (double x = 0.0; ok && x <= 3.0; x += 0.05) {
        vec3 p = {x, 0, 0};
        double share = f(&w, p, corner, edge_u, edge_v, 4);
        double sixteenths = share * 16.0;
        struct light centre = {.position = vec3_make(0, 3, 0), .colour = vec3_make(1, 1, 1)};
        double hard = shadow_opaque(&w, p, &centre).x, one = f(&w, p, corner, edge_u, edge_v, 1);
        if (fabs(sixteenths - round(sixteenths)) > 1e-9)
            ok = fail(why, why_size, "at (%g, 0, 0) with a 4 x 4 grid the share must be a whole number of 16ths; got %g",
                      x, share);
        else if (share + 1e-12 < previous)
            ok = fail(why, why_size, "walking out from under the ball the share should never fall; at x = %g it fell "
                      "from %g to %g", x, previous, share);
        else if (one != hard)
            ok = fail(why, why_size, "with n = 1 the one sample is the square's centre (0, 3, 0): at (%g, 0, 0) the hard "
                      "shadow says %g, yours %g", x, hard, one);
        penumbra = penumbra || (share > 0.0 && share < 1.0);
        previous = share;
    }
    if (ok && !penumbra)
        ok = fail(why, why_size, "walking from (0, 0, 0) to (3, 0, 0) no point was in the penumbra (share strictly "
                  "between 0 and 1): are the samples spread over the light?");
    world_free(&w);
    scene_free(&s);
    return ok;
}

/* ---- 8.4 Schlick's Fresnel ------------------------------------------------------------------------ */

bool check_schlick(schlick_fn f, char *why, size_t why_size) {
    double cos_inside = 0.9, sin_out = 1.5 * sqrt(1 - cos_inside * cos_inside);
    double cos_out = sqrt(1 - sin_out * sin_out);
    const struct {
        const char *what;
        double cos_incident, n1, n2, expected;
    } cases[] = {
        {"air to glass (1 to 1.5), head-on", 1.0, 1.0, 1.5, 0.04},
        {"air to glass, grazing (cos = 0)", 0.0, 1.0, 1.5, 1.0},
        {"air to glass, 60 degrees (cos = 0.5)", 0.5, 1.0, 1.5, 0.04 + 0.96 * pow(0.5, 5)},
        {"glass to air, head-on", 1.0, 1.5, 1.0, 0.04},
        {"glass to air at cos = 0.9 (the cosine on the air side is used)", cos_inside, 1.5, 1.0,
         0.04 + 0.96 * pow(1 - cos_out, 5)},
        {"glass to air at cos = 0.5, past the critical angle", 0.5, 1.5, 1.0, 1.0},
        {"between equal media, head-on", 1.0, 1.33, 1.33, 0.0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double got = f(cases[k].cos_incident, cases[k].n1, cases[k].n2);
        if (!near(got, cases[k].expected))
            return fail(why, why_size, "%s: expected a reflected share of %.9f, got %.9f", cases[k].what,
                        cases[k].expected, got);
    }
    return true;
}

/* ---- 9.4 the uniform grid ------------------------------------------------------------------------- */

static bool same_cells(int (*a)[3], const int (*b)[3], int n) {
    for (int k = 0; k < n; k++)
        if (a[k][0] != b[k][0] || a[k][1] != b[k][1] || a[k][2] != b[k][2])
            return false;
    return true;
}

bool check_grid_walk(grid_walk_fn f, char *why, size_t why_size) {
    vec3 lo = {0, 0, 0}, hi = {4, 4, 4};
    int out[64][3];
    static const int along_x[4][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    static const int diagonal[7][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {3, 2, 0}, {3, 3, 0}};
    static const int backwards[3][3] = {{2, 0, 0}, {1, 0, 0}, {0, 0, 0}};
    ray r = make_ray(-1, 0.5, 0.5, 1, 0, 0);
    int n = f(lo, hi, 4, &r, out, 64);
    if (n != 4 || !same_cells(out, along_x, 4))
        return fail(why, why_size, "4 x 4 x 4 grid over [0, 4]^3, ray from (-1, 0.5, 0.5) along +x: expected the cells "
                    "(0,0,0) (1,0,0) (2,0,0) (3,0,0); got %d cells, the first (%d,%d,%d)", n, out[0][0], out[0][1],
                    out[0][2]);
    r = (ray){vec3_make(0.5, 0.2, 0.5), vec3_normalize(vec3_make(1, 1, 0))};
    n = f(lo, hi, 4, &r, out, 64);
    if (n != 7 || !same_cells(out, diagonal, 7))
        return fail(why, why_size, "ray from (0.5, 0.2, 0.5) along (1, 1, 0): expected 7 cells, (0,0,0) (1,0,0) (1,1,0) "
                    "(2,1,0) (2,2,0) (3,2,0) (3,3,0); got %d", n);
    r = make_ray(2.5, 0.5, 0.5, -1, 0, 0);
    n = f(lo, hi, 4, &r, out, 64);
    if (n != 3 || !same_cells(out, backwards, 3))
        return fail(why, why_size, "ray starting inside at (2.5, 0.5, 0.5) along -x: expected (2,0,0) (1,0,0) (0,0,0), "
                    "only cells at t >= 0; got %d cells", n);
    r = make_ray(-1, 5, 0.5, 1, 0, 0);
    n = f(lo, hi, 4, &r, out, 64);
    if (n != 0)
        return fail(why, why_size, "ray from (-1, 5, 0.5) along +x passes above the grid: expected 0 cells, got %d", n);
    r = make_ray(-1, 0.5, 0.5, 1, 0, 0);
    for (int k = 0; k < 64; k++) /* marks in every entry, to see that none past the room is written */
        out[k][0] = out[k][1] = out[k][2] = -7;
    n = f(lo, hi, 4, &r, out, 2);
    if (n != 4 || !same_cells(out, along_x, 2))
        return fail(why, why_size, "with room for only 2 cells, the 4-cell ray must still return 4 and write the first "
                    "2; got %d", n);
    for (int k = 2; k < 64; k++)
        if (out[k][0] != -7 || out[k][1] != -7 || out[k][2] != -7)
            return fail(why, why_size, "with room for only 2 cells (max 2), entry %d of the array was written: a grid "
                        "walk writes at most max cells", k);
    /* Random rays through the grid: every cell that a fine walk along the ray visits must be listed, in the
     * order it is visited. */
    uint64_t state = 99;
    for (int k = 0; k < 200; k++) {
        double u[6];
        for (int a = 0; a < 6; a++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            u[a] = (double)(state >> 11) / 9007199254740992.0;
        }
        vec3 from = {-2 + 8 * u[0], -2 + 8 * u[1], -2 + 8 * u[2]}, to = {4 * u[3], 4 * u[4], 4 * u[5]};
        r = (ray){from, vec3_normalize(vec3_sub(to, from))};
        n = f(lo, hi, 4, &r, out, 64);
        if (n < 0 || n > 10)
            return fail(why, why_size, "a ray through a 4 x 4 x 4 grid crosses at most 10 cells; got %d", n);
        int listed = 0;
        for (double t = 0; t < 20; t += 1e-3) {
            vec3 p = ray_at(r, t);
            if (p.x < 0 || p.y < 0 || p.z < 0 || p.x >= 4 || p.y >= 4 || p.z >= 4)
                continue;
            int cell[3] = {(int)p.x, (int)p.y, (int)p.z};
            while (listed < n && !(out[listed][0] == cell[0] && out[listed][1] == cell[1] && out[listed][2] == cell[2]))
                listed++;
            if (listed == n)
                return fail(why, why_size, "ray from (%g, %g, %g) towards (%g, %g, %g): at t = %g it is in cell (%d,%d,%d), "
                            "which your list does not have in that order", from.x, from.y, from.z, to.x, to.y, to.z, t,
                            cell[0], cell[1], cell[2]);
        }
    }
    return true;
}

/* ---- 10.4 the SAH cost of a split --------------------------------------------------------------------- */

bool check_split_cost(split_cost_fn f, char *why, size_t why_size) {
    /* Four unit cubes along x: two at x in [0, 2], two at x in [10, 12]. Every box's area is 6; two
     * side by side make a 2 x 1 x 1 box of area 10; all four span 12 x 1 x 1, area 50. */
    struct aabb boxes[4] = {{{0, 0, 0}, {1, 1, 1}}, {{1, 0, 0}, {2, 1, 1}}, {{10, 0, 0}, {11, 1, 1}},
                            {{11, 0, 0}, {12, 1, 1}}};
    const struct {
        const char *what;
        int axis;
        double plane, expected;
    } cases[] = {
        {"x = 5, between the pairs: 1 + (10 * 2 + 10 * 2) / 50", 0, 5.0, 1.8},
        {"x = -1, all on the right: 1 + (0 + 50 * 4) / 50", 0, -1.0, 5.0},
        {"x = 0.5, exactly at the first centre, which goes right", 0, 0.5, 5.0},
        {"x = 0.6, one cube left: 1 + (6 * 1 + 46 * 3) / 50", 0, 0.6, 3.88},
        {"y = 0.5, every centre on the plane, all right", 1, 0.5, 5.0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double got = f(boxes, 4, cases[k].axis, cases[k].plane);
        if (!near(got, cases[k].expected))
            return fail(why, why_size, "four unit cubes at x = 0, 1, 10, 11, split at %s: expected %g, got %.9g",
                        cases[k].what, cases[k].expected, got);
    }
    return true;
}

/* ---- 11.4 collapsing a binary BVH into a 4-wide one ------------------------------------------------ */

#define COLLAPSE_ROOM 32 /* 4-wide nodes the check makes room for: the trees below need at most 7 */

/* A box spanning x in [x0, x1], y and z in [0, 1]: its area grows with its length. */
static struct aabb x_span(double x0, double x1) { return (struct aabb){{x0, 0, 0}, {x1, 1, 1}}; }

/* Walks the 4-wide tree out[0 .. nodes) from node `at`: every used slot before the unused ones, at least
 * two used, each node and leaf met once (leaf_seen and node_seen count them). Returns the depth below
 * `at`, or -1 with the reason in why. */
static int walk_wide(const struct bvh4_node *out, int nodes, int at, int leaves, int *leaf_seen, int *node_seen,
                     const char *tree, char *why, size_t why_size) {
    node_seen[at]++;
    int used = 0, depth = 0;
    for (int k = 0; k < 4; k++) {
        int c = out[at].child[k];
        if (c == BVH4_NONE)
            continue;
        if (used++ < k)
            return fail(why, why_size, "%s: 4-wide node %d has a used slot %d after an unused one (BVH4_NONE); put the "
                        "used slots first", tree, at, k), -1;
        if (c < 0) {
            if (BVH_LEAF(c) >= leaves || leaf_seen[BVH_LEAF(c)]++)
                return fail(why, why_size, "%s: 4-wide node %d refers to leaf %d %s", tree, at, BVH_LEAF(c),
                            BVH_LEAF(c) >= leaves ? "which does not exist" : "a second time"), -1;
            continue;
        }
        if (c >= nodes || c == 0 || node_seen[c])
            return fail(why, why_size, "%s: 4-wide node %d refers to node %d, %s", tree, at, c,
                        c >= nodes ? "beyond the nodes you say you made" : "which is already in the tree"), -1;
        int below = walk_wide(out, nodes, c, leaves, leaf_seen, node_seen, tree, why, why_size);
        if (below < 0)
            return -1;
        depth = below + 1 > depth ? below + 1 : depth;
    }
    if (used < 2)
        return fail(why, why_size, "%s: 4-wide node %d has %d used slot%s; every node has at least its binary node's "
                    "two children", tree, at, used, used == 1 ? "" : "s"), -1;
    return depth;
}

/* Collapses `tree` with f and checks the shape: `nodes` 4-wide nodes, every one of `leaves` leaves once,
 * `depth` levels of nodes below the root. */
static bool collapse_case(collapse_fn f, const struct bvh2_node *tree, int leaves, int nodes, int depth,
                          const char *what, struct bvh4_node *out, char *why, size_t why_size) {
    for (int k = 0; k < COLLAPSE_ROOM; k++)
        out[k] = (struct bvh4_node){{BVH4_NONE, BVH4_NONE, BVH4_NONE, BVH4_NONE}};
    int made = f(tree, 0, out, COLLAPSE_ROOM);
    if (made != nodes)
        return fail(why, why_size, "%s: expected %d 4-wide nodes, your bvh4_collapse returned %d", what, nodes, made);
    int leaf_seen[64] = {0}, node_seen[COLLAPSE_ROOM] = {0};
    int got_depth = walk_wide(out, made, 0, leaves, leaf_seen, node_seen, what, why, why_size);
    if (got_depth < 0)
        return false;
    for (int l = 0; l < leaves; l++)
        if (leaf_seen[l] != 1)
            return fail(why, why_size, "%s: leaf %d is not in your 4-wide tree", what, l);
    for (int k = 0; k < made; k++)
        if (node_seen[k] != 1)
            return fail(why, why_size, "%s: 4-wide node %d is not reached from the root out[0]", what, k);
    if (got_depth != depth)
        return fail(why, why_size, "%s: expected %d level%s of nodes below the root, yours has %d", what, depth,
                    depth == 1 ? "" : "s", got_depth);
    return true;
}

bool check_collapse(collapse_fn f, char *why, size_t why_size) {
    struct bvh4_node out[COLLAPSE_ROOM];
    /* A complete binary tree of 15 nodes over 16 leaves (node i has children 2i + 1 and 2i + 2, the
     * leaves numbered from 15), leaf l spanning x in [l, l + 1]. Opening the widest child each time gives
     * a root with four nodes of four leaves each. */
    struct bvh2_node complete[15];
    for (int i = 0; i < 15; i++)
        for (int k = 0; k < 2; k++) {
            int c = 2 * i + 1 + k, first = c, last = c;
            while (first < 15) /* the leaves under c: the leftmost and the rightmost descendant */
                first = 2 * first + 1, last = 2 * last + 2;
            complete[i].child[k] = c < 15 ? c : BVH_LEAF(c - 15);
            complete[i].box[k] = x_span(first - 15, last - 15 + 1);
        }
    if (!collapse_case(f, complete, 16, 5, 1, "a complete binary tree of 15 nodes over 16 leaves (4-wide: a root "
                       "over four nodes of four leaves)", out, why, why_size))
        return false;
    /* Writing only the first `max` nodes, but counting them all. */
    for (int k = 0; k < COLLAPSE_ROOM; k++)
        out[k] = (struct bvh4_node){{7, 7, 7, 7}};
    int made = f(complete, 0, out, 2);
    for (int k = 2; k < COLLAPSE_ROOM; k++)
        if (out[k].child[0] != 7)
            return fail(why, why_size, "the complete tree of 15 nodes with max = 2: your bvh4_collapse wrote out[%d]; "
                        "write only the first max nodes (and still return how many there are)", k);
    if (made != 5)
        return fail(why, why_size, "the complete tree of 15 nodes with max = 2: expected 5 (the nodes it needs), got %d",
                    made);
    /* A chain: node i holds leaf i and node i + 1, the last node two leaves. Each 4-wide node swallows three
     * binary nodes: 9 binary nodes make 3. */
    struct bvh2_node chain[9];
    for (int i = 0; i < 9; i++)
        chain[i] = (struct bvh2_node){{x_span(i, i + 1), x_span(i + 1, 10)}, {BVH_LEAF(i), i < 8 ? i + 1 : BVH_LEAF(9)}};
    if (!collapse_case(f, chain, 10, 3, 2, "a chain of 9 binary nodes, each with a leaf and the next node", out, why,
                       why_size))
        return false;
    /* The widest child is opened, not the first: the root's children are A (x in [0, 10]) and B ([20, 25]);
     * A's are the nodes A0 ([0, 3], area 14) and A1 ([6, 10], area 18), B's two leaves. After A, B (area
     * 22) is the widest, so the root holds A0, A1 and B's two leaves. */
    struct bvh2_node widest[5] = {
        {{x_span(0, 10), x_span(20, 25)}, {1, 2}},                  /* the root: A and B */
        {{x_span(0, 3), x_span(6, 10)}, {3, 4}},                    /* A: A0 and A1 */
        {{x_span(20, 22), x_span(23, 25)}, {BVH_LEAF(4), BVH_LEAF(5)}}, /* B */
        {{x_span(0, 1), x_span(2, 3)}, {BVH_LEAF(0), BVH_LEAF(1)}},   /* A0 */
        {{x_span(6, 7), x_span(9, 10)}, {BVH_LEAF(2), BVH_LEAF(3)}},  /* A1 */
    };
    const char *what = "a root over A (x in [0, 10]) and B ([20, 25]), A over the nodes A0 ([0, 3], area 14) and A1 "
                       "([6, 10], area 18), B over leaves 4 and 5";
    if (!collapse_case(f, widest, 6, 3, 1, what, out, why, why_size))
        return false;
    bool four = false, five = false;
    for (int k = 0; k < 4; k++) {
        four = four || out[0].child[k] == BVH_LEAF(4);
        five = five || out[0].child[k] == BVH_LEAF(5);
    }
    if (!four || !five)
        return fail(why, why_size, "%s: after opening A, the widest interior child is B (area 22), so the root's four "
                    "slots should be A0, A1 and leaves 4 and 5; yours holds %s. Open the child with the largest surface "
                    "area (most rays enter it), not the first one", what, four || five ? "only one of the two leaves" :
                    "neither leaf");
    return true;
}

/* ---- exercise 12.4: n-rooks ------------------------------------------------------------------------ */

#define ROOKS_MAX 16
#define ROOKS_PIXELS 40 /* pixels looked at for the pairings */

/* The column and row of point k of n, or -1 when it is outside [0, 1). */
static int cell_of(double v, int n) { return v >= 0.0 && v < 1.0 ? (int)(v * n) : -1; }

bool check_rooks(rooks_fn f, char *why, size_t why_size) {
    static const int sizes[] = {1, 2, 5, 8, 16};
    double x[ROOKS_MAX], y[ROOKS_MAX], x2[ROOKS_MAX], y2[ROOKS_MAX];
    for (int s = 0; s < 5; s++) {
        int n = sizes[s];
        for (int p = 0; p < ROOKS_PIXELS; p++) {
            int i = p % 7, j = p / 7;
            f(i, j, n, 3, x, y);
            bool column[ROOKS_MAX] = {false}, row[ROOKS_MAX] = {false};
            for (int k = 0; k < n; k++) {
                int c = cell_of(x[k], n), r = cell_of(y[k], n);
                if (c < 0 || r < 0)
                    return fail(why, why_size, "pixel (%d, %d), n = %d: point %d is (%g, %g), outside [0, 1) x [0, 1)",
                                i, j, n, k, x[k], y[k]);
                if (column[c] || row[r])
                    return fail(why, why_size, "pixel (%d, %d), n = %d: point %d (%g, %g) shares its %s with another; "
                                "each of the n columns and rows holds exactly one", i, j, n, k, x[k], y[k],
                                column[c] ? "column" : "row");
                column[c] = row[r] = true;
            }
            f(i, j, n, 3, x2, y2);
            for (int k = 0; k < n; k++)
                if (x2[k] != x[k] || y2[k] != y[k])
                    return fail(why, why_size, "pixel (%d, %d), n = %d: a second call gave other points (point %d: "
                                "(%g, %g), then (%g, %g)); they must come from sample_hash alone", i, j, n, k, x[k],
                                y[k], x2[k], y2[k]);
        }
    }
    /* The pairing of columns with rows changes from pixel to pixel; on the diagonal, every pixel's
     * points line up along it, and the samples of neighbouring pixels form a regular pattern. */
    int diagonal = 0, centred = 0;
    for (int p = 0; p < ROOKS_PIXELS; p++) {
        f(p, 1, 8, 3, x, y);
        bool on_diagonal = true;
        for (int k = 0; k < 8; k++) {
            on_diagonal = on_diagonal && cell_of(x[k], 8) == cell_of(y[k], 8);
            centred += fabs(x[k] * 8 - floor(x[k] * 8) - 0.5) < 1e-9;
        }
        diagonal += on_diagonal;
    }
    if (diagonal > 2)
        return fail(why, why_size, "n = 8: in %d of %d pixels the points lie in the cells (0, 0), (1, 1), ... of the "
                    "diagonal; shuffle which column goes with which row, pixel by pixel", diagonal, ROOKS_PIXELS);
    if (centred > ROOKS_PIXELS)
        return fail(why, why_size, "n = 8: %d of %d points sit at the middle of their column; each should be at a "
                    "random place within its cell", centred, 8 * ROOKS_PIXELS);
    double a[ROOKS_MAX], b[ROOKS_MAX];
    f(2, 3, 8, 3, x, y);
    f(2, 3, 8, 4, a, b);
    bool same = true;
    for (int k = 0; k < 8; k++)
        same = same && a[k] == x[k] && b[k] == y[k];
    if (same)
        return fail(why, why_size, "pixel (2, 3), n = 8: seeds 3 and 4 give the same points; the seed must change them");
    return true;
}

/* ---- exercise 13.4: the concentric map ------------------------------------------------------------- */

#define CONCENTRIC_SIDE 64 /* the square's grid of test points */

bool check_concentric(concentric_fn f, char *why, size_t why_size) {
    double x, y;
    f(0.5, 0.5, &x, &y);
    if (fabs(x) > 1e-12 || fabs(y) > 1e-12)
        return fail(why, why_size, "(0.5, 0.5), the square's centre, went to (%g, %g), not the disc's centre", x, y);
    /* The square's edge goes to the circle's, all the way round: its four sides in turn. */
    for (int k = 0; k < 4 * CONCENTRIC_SIDE; k++) {
        double t = (double)(k % CONCENTRIC_SIDE) / CONCENTRIC_SIDE;
        static const double from[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, along[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        int side = k / CONCENTRIC_SIDE;
        double u = from[side][0] + t * along[side][0], v = from[side][1] + t * along[side][1];
        f(u, v, &x, &y);
        if (fabs(hypot(x, y) - 1) > 1e-9)
            return fail(why, why_size, "(%g, %g) on the square's edge went to (%g, %g), %g from the centre; the "
                        "square's edge must go to the circle's, radius 1", u, v, x, y, hypot(x, y));
    }
    /* Uniform: a grid of the square's cell centres puts a quarter of its points within radius 1/2 and a
     * quarter in each quadrant of the disc, and neighbouring points stay neighbours. */
    int inner = 0, quadrant[4] = {0}, wedge[8] = {0};
    double jump = 0;
    for (int j = 0; j < CONCENTRIC_SIDE; j++)
        for (int i = 0; i < CONCENTRIC_SIDE; i++) {
            double u = (i + 0.5) / CONCENTRIC_SIDE, v = (j + 0.5) / CONCENTRIC_SIDE, x2, y2;
            f(u, v, &x, &y);
            if (hypot(x, y) > 1 + 1e-12)
                return fail(why, why_size, "(%g, %g) went to (%g, %g), outside the unit disc", u, v, x, y);
            inner += hypot(x, y) < 0.5;
            quadrant[(x < 0) + 2 * (y < 0)]++;
            wedge[(int)floor((atan2(y, x) + M_PI / 8) / (M_PI / 4) + 8) % 8]++;
            f(u + 1.0 / CONCENTRIC_SIDE * (i + 1 < CONCENTRIC_SIDE), v, &x2, &y2);
            jump = fmax(jump, hypot(x2 - x, y2 - y));
        }
    int total = CONCENTRIC_SIDE * CONCENTRIC_SIDE;
    if (fabs((double)inner / total - 0.25) > 0.01)
        return fail(why, why_size, "%.1f %% of a uniform grid of the square went within radius 1/2 of the centre; a map "
                    "that keeps areas puts 25 %% there (r = max(|a|, |b|), not its square or root)", 100.0 * inner / total);
    for (int q = 0; q < 4; q++)
        if (fabs((double)quadrant[q] / total - 0.25) > 0.01)
            return fail(why, why_size, "quadrant %d of the disc got %.1f %% of a uniform grid of the square, not 25 %%",
                        q, 100.0 * quadrant[q] / total);
    for (int w = 0; w < 8; w++)
        if (fabs((double)wedge[w] / total - 0.125) > 0.01)
            return fail(why, why_size, "the wedge of 45 degrees around angle %d got %.1f %% of a uniform grid of the "
                        "square, not 12.5 %%: pushing the square's points straight out to the circle crowds them "
                        "towards the diagonals; the angle along each side must grow evenly", 45 * w,
                        100.0 * wedge[w] / total);
    if (jump > 0.1)
        return fail(why, why_size, "neighbouring points of the square's grid went %g apart; the map must be "
                    "continuous (check the angle of each of the four sides)", jump);
    return true;
}

/* ---- exercise 14.4: the cylindrical map ---------------------------------------------------------- */

bool check_cylindrical(cylindrical_fn f, char *why, size_t why_size) {
    static const struct {
        vec3 q;
        double u, v;
    } cases[] = {
        {{1, 0, 0}, 0.0, 0.0},   {{0, 0.5, 1}, 0.25, 0.5}, {{-2, 3, 0}, 0.5, 3.0},
        {{0, -1, -1}, 0.75, -1.0}, {{1, 0.25, 1}, 0.125, 0.25}, {{1, 7, -1e-9}, 1.0 - 1e-9 / (2 * M_PI), 7.0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double u = -1, v = -1;
        vec3 q = cases[k].q;
        if (!f(q, &u, &v))
            return fail(why, why_size, "(%g, %g, %g): returned false, but the point is off the y axis", q.x, q.y, q.z);
        if (!(fabs(u - cases[k].u) < 1e-9) || !(fabs(v - cases[k].v) < 1e-12))
            return fail(why, why_size, "(%g, %g, %g): expected u = %.10g, v = %g, got u = %.10g, v = %g", q.x, q.y, q.z,
                        cases[k].u, cases[k].v, u, v);
        if (!(u >= 0.0 && u < 1.0))
            return fail(why, why_size, "(%g, %g, %g): u = %.17g is outside [0, 1)", q.x, q.y, q.z, u);
    }
    double u, v;
    if (f(vec3_make(0, 2, 0), &u, &v))
        return fail(why, why_size, "(0, 2, 0) is on the y axis: return false there");
    return true;
}

/* ---- exercise 15.4: the cone of a ball of light --------------------------------------------------- */

bool check_cone(cone_fn f, char *why, size_t why_size) {
    vec3 centre = {1, 2, 3}, point = {1, 2 - 4, 3 + 3}; /* 5 away: sin(theta_max) = 0.6, cos = 0.8 */
    double radius = 3, cos_max = 0.8, expected_density = 1.0 / (2.0 * M_PI * (1.0 - cos_max));
    vec3 axis = vec3_normalize(vec3_sub(centre, point)), direction, sum = {0, 0, 0};
    double density;
    if (f(centre, radius, vec3_make(1, 2.5, 3), 0.5, 0.5, &direction, &density))
        return fail(why, why_size, "a point inside the ball: return false");
    enum { SIDE = 64 };
    for (int a = 0; a < SIDE; a++)
        for (int b = 0; b < SIDE; b++) {
            double u1 = (a + 0.5) / SIDE, u2 = (b + 0.5) / SIDE;
            if (!f(centre, radius, point, u1, u2, &direction, &density))
                return fail(why, why_size, "u1 = %g, u2 = %g: returned false, but the point is 5 from the centre of a "
                            "ball of radius 3", u1, u2);
            if (!(fabs(vec3_length(direction) - 1.0) < 1e-9))
                return fail(why, why_size, "u1 = %g, u2 = %g: the direction has length %.12g, not 1", u1, u2,
                            vec3_length(direction));
            if (!(vec3_dot(direction, axis) >= cos_max - 1e-9))
                return fail(why, why_size, "u1 = %g, u2 = %g: the direction is %.4g degrees off the axis, outside the "
                            "cone of half-angle %.4g", u1, u2, acos(fmin(1, vec3_dot(direction, axis))) * 180 / M_PI,
                            acos(cos_max) * 180 / M_PI);
            if (!(fabs(density - expected_density) < 1e-9 * expected_density))
                return fail(why, why_size, "the density is %.9g, expected 1 / (2 pi (1 - cos theta_max)) = %.9g", density,
                            expected_density);
            sum = vec3_add(sum, direction);
        }
    /* Uniform over the cone's solid angle, cos theta is uniform in [cos theta_max, 1]: the directions'
     * mean is the axis times (1 + cos theta_max) / 2, whatever way round the axis they turn. */
    vec3 mean = vec3_scale(sum, 1.0 / (SIDE * SIDE)), expected = vec3_scale(axis, (1.0 + cos_max) / 2);
    if (!(vec3_length(vec3_sub(mean, expected)) < 1e-3))
        return fail(why, why_size, "over a 64 x 64 grid of (u1, u2) the mean direction is (%.4f, %.4f, %.4f), expected "
                    "(%.4f, %.4f, %.4f): uniform over the solid angle makes cos theta uniform, not theta", mean.x,
                    mean.y, mean.z, expected.x, expected.y, expected.z);
    return true;
}

/* ---- exercise 16.4: spherical linear interpolation -------------------------------------------- */

#define SLERP_DEGREES_TOLERANCE 1e-6 /* angles in degrees: slerp meets them to rounding */

/* The unit quaternion of the turn by `degrees` about the axis (x, y, z). */
static void quaternion_turn(double degrees, double x, double y, double z, double q[4]) {
    double length = sqrt(x * x + y * y + z * z), half = degrees * M_PI / 360.0;
    q[0] = cos(half);
    q[1] = sin(half) * x / length;
    q[2] = sin(half) * y / length;
    q[3] = sin(half) * z / length;
}

static double quaternion_dot(const double *a, const double *b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

/* The angle in degrees of the turn that takes unit quaternion a to b, from 0 to 180: the angle between
 * them as 4-vectors (b flipped when that is shorter), doubled; by atan2, which stays exact for small
 * angles where acos of the dot product does not. */
static double quaternion_turn_between(const double *a, const double *b) {
    double sign = quaternion_dot(a, b) < 0 ? -1.0 : 1.0, minus = 0, plus = 0;
    for (int k = 0; k < 4; k++) {
        minus += (a[k] - sign * b[k]) * (a[k] - sign * b[k]);
        plus += (a[k] + sign * b[k]) * (a[k] + sign * b[k]);
    }
    return 4.0 * atan2(sqrt(minus), sqrt(plus)) * 180.0 / M_PI;
}

static bool quaternion_is_unit(const double *q) { return fabs(quaternion_dot(q, q) - 1.0) < 1e-9; }

static bool quaternion_equal(const double *a, const double *b) {
    for (int k = 0; k < 4; k++)
        if (!(fabs(a[k] - b[k]) < 1e-9))
            return false;
    return true;
}

bool check_slerp(slerp_fn f, char *why, size_t why_size) {
    double q0[4], q1[4], out[4];
    quaternion_turn(20, 1, 2, 3, q0);
    quaternion_turn(150, -1, 0.5, 2, q1);
    double whole = quaternion_turn_between(q0, q1); /* about 136 degrees */
    f(q0, q1, 0, out);
    if (!quaternion_equal(out, q0))
        return fail(why, why_size, "t = 0 gave (%.6g, %.6g, %.6g, %.6g), expected q0 = (%.6g, %.6g, %.6g, %.6g)", out[0],
                    out[1], out[2], out[3], q0[0], q0[1], q0[2], q0[3]);
    f(q0, q1, 1, out);
    if (!quaternion_equal(out, q1))
        return fail(why, why_size, "t = 1 gave (%.6g, %.6g, %.6g, %.6g), expected q1 = (%.6g, %.6g, %.6g, %.6g)", out[0],
                    out[1], out[2], out[3], q1[0], q1[1], q1[2], q1[3]);
    for (int k = 1; k < 10; k++) {
        double t = k / 10.0;
        f(q0, q1, t, out);
        if (!quaternion_is_unit(out))
            return fail(why, why_size, "t = %.1f: the result has length %.12g, not 1", t, sqrt(quaternion_dot(out, out)));
        double done = quaternion_turn_between(q0, out), left = quaternion_turn_between(out, q1);
        if (!(fabs(done + left - whole) < SLERP_DEGREES_TOLERANCE))
            return fail(why, why_size, "t = %.1f: the result is %.6g degrees from q0 and %.6g from q1, which adds up to "
                        "more than the %.6g between them: it is off the arc from q0 to q1", t, done, left, whole);
        if (!(fabs(done - t * whole) < SLERP_DEGREES_TOLERANCE))
            return fail(why, why_size, "t = %.1f: the result is %.6g degrees from q0, expected %.1f of the %.6g between q0 "
                        "and q1, %.6g: the speed is not constant%s", t, done, t, whole, t * whole,
                        fabs(done - t * whole) > 0.01 ? " (a linear blend made unit length, nlerp, turns faster in "
                                                        "the middle: weigh q0 and q1 by sines)" : "");
    }
    /* -q1 is the same turn as q1: the way from q0 to it is the same short arc, ending at -q1. */
    double minus_q1[4] = {-q1[0], -q1[1], -q1[2], -q1[3]}, same[4];
    f(q0, q1, 0.5, same);
    f(q0, minus_q1, 0.5, out);
    if (!(fabs(fabs(quaternion_dot(out, same)) - 1.0) < 1e-9))
        return fail(why, why_size, "from q0 to -q1 (the same turn as q1) at t = 0.5, the result is %.6g degrees of turn "
                    "away from the result with q1: the long way round? Flip q1 when q0 . q1 < 0",
                    quaternion_turn_between(out, same));
    f(q0, minus_q1, 1, out);
    if (!quaternion_equal(out, minus_q1) && !quaternion_equal(out, q1))
        return fail(why, why_size, "from q0 to -q1 at t = 1: expected -q1 (or q1, the same turn), got (%.6g, %.6g, %.6g, "
                    "%.6g)", out[0], out[1], out[2], out[3]);
    /* Two turns a millionth of a degree apart: no division by the sine of a tiny angle. */
    double near_q0[4];
    quaternion_turn(20 + 1e-6, 1, 2, 3, near_q0);
    f(q0, near_q0, 0.5, out);
    if (!quaternion_is_unit(out) || !(quaternion_turn_between(q0, out) < 1e-5))
        return fail(why, why_size, "q0 and a turn 1e-6 degrees from it, t = 0.5: the result (%.6g, %.6g, %.6g, %.6g) is "
                    "not a unit quaternion beside them (dividing by the sine of a tiny angle? Blend linearly there)",
                    out[0], out[1], out[2], out[3]);
    return true;
}

/* ---- exercise 17.5: sampling GGX's normals ----------------------------------------------------- */

#define GGX_NORMALS_GRID 200        /* the check draws from a 200 x 200 grid of (u1, u2) midpoints */
#define GGX_NORMALS_SHARE_TOLERANCE 0.01 /* a share of 40,000 stratified draws, far coarser than their error */

bool check_ggx_normals(ggx_normal_fn f, char *why, size_t why_size) {
    const double alphas[] = {0.1, 0.5, 1.0};
    for (int a = 0; a < 3; a++) {
        double alpha = alphas[a];
        /* Under D(m) cos(theta), P(tan^2 theta <= x) = x / (alpha^2 + x): that share of each draw's
         * tan^2 is uniform in [0, 1), so each tenth of it holds a tenth of the draws. */
        int tenths[10] = {0};
        long first_quadrant = 0;
        double sum_x = 0, sum_y = 0;
        for (int i = 0; i < GGX_NORMALS_GRID; i++)
            for (int j = 0; j < GGX_NORMALS_GRID; j++) {
                double u1 = (i + 0.5) / GGX_NORMALS_GRID, u2 = (j + 0.5) / GGX_NORMALS_GRID;
                vec3 m = f(alpha, u1, u2);
                if (!(fabs(vec3_length(m) - 1.0) < 1e-9) || !(m.z > 0.0))
                    return fail(why, why_size, "alpha %g, u1 %g, u2 %g: the normal (%g, %g, %g) is not a unit vector "
                                "above the surface", alpha, u1, u2, m.x, m.y, m.z);
                double tan2 = (m.x * m.x + m.y * m.y) / (m.z * m.z), share = tan2 / (alpha * alpha + tan2);
                tenths[share >= 1.0 ? 9 : (int)(10.0 * share)]++;
                first_quadrant += m.x > 0.0 && m.y > 0.0;
                sum_x += m.x;
                sum_y += m.y;
            }
        double count = (double)GGX_NORMALS_GRID * GGX_NORMALS_GRID;
        for (int k = 0; k < 10; k++)
            if (!(fabs(tenths[k] / count - 0.1) <= GGX_NORMALS_SHARE_TOLERANCE))
                return fail(why, why_size, "alpha %g: %.1f %% of the normals have tan^2 / (alpha^2 + tan^2) between %.1f "
                            "and %.1f, expected 10 %% (their density is not D(m) cos theta: tan^2 theta = alpha^2 u / "
                            "(1 - u)?)", alpha, 100.0 * tenths[k] / count, k / 10.0, (k + 1) / 10.0);
        if (!(fabs(first_quadrant / count - 0.25) <= GGX_NORMALS_SHARE_TOLERANCE) || !(fabs(sum_x / count) < 0.01) ||
            !(fabs(sum_y / count) < 0.01))
            return fail(why, why_size, "alpha %g: %.1f %% of the normals lean towards +x and +y (expected 25 %%), their mean "
                        "leaning is (%.3f, %.3f) (expected 0): the angle about the normal is not uniform",
                        alpha, 100.0 * first_quadrant / count, sum_x / count, sum_y / count);
    }
    return true;
}

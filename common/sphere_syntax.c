/* sphere_syntax.c: the sphere's scene-file line, `sphere centre X Y Z radius R [material NAME]`, and
 * its POV-Ray form (chapter 1: every chapter reads every scene; shape.h explains the two halves). */
#include "sphere.h"

enum { SPHERE_CENTRE, SPHERE_RADIUS };

/* Makes the sphere from its keys (struct shape_syntax's make). */
static bool sphere_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
    struct sphere *s = item;
    s->centre = key_vec3(kv, SPHERE_CENTRE);
    s->radius = kv->number[SPHERE_RADIUS][0];
    if (!(s->radius > 0.0)) {
        snprintf(why, why_size, "sphere radius must be positive, got %g", s->radius);
        return false;
    }
    if (s->radius < SPHERE_MIN_RADIUS || s->radius > KEY_MAX_COORD) {
        snprintf(why, why_size, "sphere radius must be between %g and %g, got " KEY_NUMBER_SHOWN, SPHERE_MIN_RADIUS,
                 KEY_MAX_COORD, KEY_NUMBER(s->radius));
        return false;
    }
    return key_vec3_within(s->centre, KEY_MAX_COORD, "sphere centre", why, why_size);
}

/* Writes the sphere for POV-Ray: sphere { <centre>, radius */
static void sphere_write_pov(FILE *out, const void *item) {
    const struct sphere *s = item;
    fprintf(out, "sphere { ");
    shape_write_vector(out, s->centre);
    fprintf(out, ", %.17g", s->radius);
}

static const struct key_spec sphere_keys[] = {{"centre", 3}, {"radius", 1}};
static const int sphere_required[] = {SPHERE_CENTRE, SPHERE_RADIUS, -1};

const struct shape_syntax sphere_syntax = {
    .keyword = "sphere",
    .plural = "spheres",
    .size = sizeof(struct sphere),
    .material_offset = offsetof(struct sphere, material),
    .keys = sphere_keys,
    .key_count = 2,
    .required = sphere_required,
    .make = sphere_make,
    .write_pov = sphere_write_pov,
};

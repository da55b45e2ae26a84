/* triangle_syntax.c: the triangle's scene-file line, `triangle a X Y Z b X Y Z c X Y Z [material NAME]`,
 * and its POV-Ray form (chapter 1: every chapter reads every scene; shape.h explains the two halves). */
#include "triangle.h"

enum { TRIANGLE_A, TRIANGLE_B, TRIANGLE_C };

/* Makes the triangle from its keys (struct shape_syntax's make). Any three corners within range will
 * do: a triangle of zero area is never hit. A corner out of range is refused, with why. */
static bool triangle_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
    struct triangle *t = item;
    t->a = key_vec3(kv, TRIANGLE_A);
    t->b = key_vec3(kv, TRIANGLE_B);
    t->c = key_vec3(kv, TRIANGLE_C);
    const vec3 corner[3] = {t->a, t->b, t->c};
    for (int k = 0; k < 3; k++)
        if (!triangle_corner_in_range(corner[k])) {
            snprintf(why, why_size, "corner %c is at (%g, %g, %g); coordinates must stay within -%g .. %g",
                     "abc"[k], corner[k].x, corner[k].y, corner[k].z, TRIANGLE_MAX_COORD, TRIANGLE_MAX_COORD);
            return false;
        }
    return true;
}

/* Writes the triangle for POV-Ray: triangle { <a>, <b>, <c> */
static void triangle_write_pov(FILE *out, const void *item) {
    const struct triangle *t = item;
    fprintf(out, "triangle { ");
    shape_write_vector(out, t->a);
    fprintf(out, ", ");
    shape_write_vector(out, t->b);
    fprintf(out, ", ");
    shape_write_vector(out, t->c);
}

static const struct key_spec triangle_keys[] = {{"a", 3}, {"b", 3}, {"c", 3}};
static const int triangle_required[] = {TRIANGLE_A, TRIANGLE_B, TRIANGLE_C, -1};

const struct shape_syntax triangle_syntax = {
    .keyword = "triangle",
    .plural = "triangles",
    .size = sizeof(struct triangle),
    .material_offset = offsetof(struct triangle, material),
    .keys = triangle_keys,
    .key_count = 3,
    .required = triangle_required,
    .make = triangle_make,
    .write_pov = triangle_write_pov,
};

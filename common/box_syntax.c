/* box_syntax.c: the box's scene-file line, `box min X Y Z max X Y Z [material NAME]`, and its POV-Ray
 * form (chapter 1: every chapter reads every scene; shape.h explains the two halves). */
#include "box.h"

enum { BOX_MIN, BOX_MAX };

/* Makes the box from its keys (struct shape_syntax's make). */
static bool box_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
    struct box *b = item;
    b->min = key_vec3(kv, BOX_MIN);
    b->max = key_vec3(kv, BOX_MAX);
    if (!(b->min.x < b->max.x && b->min.y < b->max.y && b->min.z < b->max.z)) {
        snprintf(why, why_size, "box min must be below max on every axis");
        return false;
    }
    return key_vec3_within(b->min, KEY_MAX_COORD, "box min", why, why_size) &&
           key_vec3_within(b->max, KEY_MAX_COORD, "box max", why, why_size);
}

/* Writes the box for POV-Ray: box { <min>, <max> */
static void box_write_pov(FILE *out, const void *item) {
    const struct box *b = item;
    fprintf(out, "box { ");
    shape_write_vector(out, b->min);
    fprintf(out, ", ");
    shape_write_vector(out, b->max);
}

static const struct key_spec box_keys[] = {{"min", 3}, {"max", 3}};
static const int box_required[] = {BOX_MIN, BOX_MAX, -1};

const struct shape_syntax box_syntax = {
    .keyword = "box",
    .plural = "boxes",
    .size = sizeof(struct box),
    .material_offset = offsetof(struct box, material),
    .keys = box_keys,
    .key_count = 2,
    .required = box_required,
    .make = box_make,
    .write_pov = box_write_pov,
    .surface_uv = true, /* texture_box_uv */
};

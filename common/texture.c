/* texture.c: pigments evaluated as POV-Ray 3.7 evaluates them (chapter 14; texture.h). The pattern
 * rules are POV-Ray's own, down to its small offsets, so that a boundary falls where POV-Ray draws it. */
#include "texture.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hit.h"
#include "image_map.h"
#include "memory_budget.h"
#include "mesh_surface.h"
#include "world.h"

/* POV-Ray's EPSILON: added before the checker's floors and to the brick's mortar, so that a point on a
 * boundary (a floor at y = 0) is counted on the upper side. */
#define TEXTURE_EPSILON 1e-10
/* POV-Ray folds a pattern's value with fmod(value, 1.00001), not fmod(value, 1): a value of exactly 1
 * (the far end of a gradient) stays 1 and picks colour2. */
#define TEXTURE_WAVE_PERIOD 1.00001
/* Radial: within this distance of the y axis the angle is meaningless and POV-Ray uses 0.25. */
#define TEXTURE_RADIAL_AXIS 0.001
/* The images of a scene's pigments may take at most this share of the memory the program may use
 * (memory_budget.h): nothing is built from them, but an image of the largest size image_map.h allows
 * takes 1 GiB as floats, from a file of a few hundred kilobytes when its pixels are all alike. */
#define TEXTURE_IMAGE_MEMORY_SHARE 0.5

/* Turns p by -degrees about one axis: the inverse of mesh_transform's turns (POV-Ray's sense). */
static vec3 unturn_x(vec3 p, double degrees) {
    double s = sin(-degrees * M_PI / 180.0), c = cos(-degrees * M_PI / 180.0);
    return (vec3){p.x, p.y * c - p.z * s, p.y * s + p.z * c};
}
static vec3 unturn_y(vec3 p, double degrees) {
    double s = sin(-degrees * M_PI / 180.0), c = cos(-degrees * M_PI / 180.0);
    return (vec3){p.z * s + p.x * c, p.y, p.z * c - p.x * s};
}
static vec3 unturn_z(vec3 p, double degrees) {
    double s = sin(-degrees * M_PI / 180.0), c = cos(-degrees * M_PI / 180.0);
    return (vec3){p.x * c - p.y * s, p.x * s + p.y * c, p.z};
}

vec3 texture_space(const struct pigment *p, vec3 point) {
    vec3 q = vec3_sub(point, p->translate);
    /* A turn by 0 is skipped: it changes nothing, and its sine and cosine cost more than the pattern. */
    if (p->rotate.z != 0.0)
        q = unturn_z(q, p->rotate.z);
    if (p->rotate.y != 0.0)
        q = unturn_y(q, p->rotate.y);
    if (p->rotate.x != 0.0)
        q = unturn_x(q, p->rotate.x);
    return (vec3){q.x / p->scale.x, q.y / p->scale.y, q.z / p->scale.z};
}

/* TASK 14.1: the checker pattern */
static double checker(vec3 q) {
    /* The parity of the sum of floors, taken in double: no cast to int, which a point beyond int's
     * range (or not finite) would make undefined. */
    double sum = floor(q.x + TEXTURE_EPSILON) + floor(q.y + TEXTURE_EPSILON) + floor(q.z + TEXTURE_EPSILON);
    return fabs(fmod(sum, 2.0)) == 1.0 ? 1.0 : 0.0;
}

/* The fractional part of x as POV-Ray's brick takes it: x - (int)x, moved into [0, 1) (trunc: the same
 * for any x, with no cast that a large x would make undefined). */
static double brick_fraction(double x) {
    double f = x - trunc(x);
    return f < 0.0 ? f + 1.0 : f;
}

/* POV-Ray's brick: rows of height size.y; every other row shifted by half a brick along x and z. The
 * mortar is stored as a float in POV-Ray, less twice its EPSILON. */
static double brick(const struct pigment *p, vec3 q) {
    double mortar = (double)(float)(p->mortar - 2.0 * TEXTURE_EPSILON);
    double fudge = TEXTURE_EPSILON + mortar;
    double x = q.x + fudge, y = q.y + fudge, z = q.z + fudge;
    vec3 size = p->brick_size;
    if (brick_fraction(y / size.y) <= mortar / size.y)
        return 0.0; /* the mortar between rows */
    bool odd_row = brick_fraction((y / size.y) * 0.5) > 0.5;
    if (brick_fraction(x / size.x) <= mortar / size.x && !odd_row)
        return 0.0;
    if (brick_fraction(x / size.x + 0.5) <= mortar / size.x && odd_row)
        return 0.0;
    if (brick_fraction(z / size.z) <= mortar / size.z && odd_row)
        return 0.0;
    if (brick_fraction(z / size.z + 0.5) <= mortar / size.z && !odd_row)
        return 0.0;
    return 1.0;
}

/* POV-Ray's ramp wave with frequency 1: the value folded into [0, 1]. */
static double ramp(double value) {
    value = fmod(value, TEXTURE_WAVE_PERIOD);
    if (value < 0.0)
        value -= floor(value);
    return value;
}

static double gradient(const struct pigment *p, vec3 q) {
    double along = vec3_dot(q, p->axis);
    return ramp(along > 1.0 ? fmod(along, 1.0) : along);
}

static double radial(vec3 q) {
    if (fabs(q.x) < TEXTURE_RADIAL_AXIS && fabs(q.z) < TEXTURE_RADIAL_AXIS)
        return ramp(0.25);
    return ramp(0.25 + (atan2(q.x, q.z) + M_PI) / (2.0 * M_PI));
}

double texture_pattern_value(const struct pigment *p, vec3 q) {
    switch (p->pattern) {
    case PIGMENT_CHECKER:
        return checker(q);
    case PIGMENT_BRICK:
        return brick(p, q);
    case PIGMENT_GRADIENT:
        return gradient(p, q);
    case PIGMENT_RADIAL:
        return radial(q);
    case PIGMENT_IMAGE_MAP:
        break;
    }
    return 0.0;
}

struct texture_colour texture_pigment_at(const struct pigment *p, vec3 point) {
    vec3 q = texture_space(p, point);
    if (p->pattern == PIGMENT_IMAGE_MAP) {
        double rgba[4];
        image_map_lookup(p, q, rgba);
        return (struct texture_colour){vec3_make(rgba[0], rgba[1], rgba[2]), 1.0 - rgba[3]};
    }
    /* The value picks colour (0) or colour2 (1), or blends them in between (POV-Ray's colour map). */
    double value = texture_pattern_value(p, q);
    if (value >= 1.0)
        return (struct texture_colour){p->colour[1], 0.0};
    if (!(value > 0.0)) /* NaN too: a point no pattern can place shows colour, never a NaN blend */
        return (struct texture_colour){p->colour[0], 0.0};
    return (struct texture_colour){vec3_add_scaled(p->colour[0], vec3_sub(p->colour[1], p->colour[0]), value), 0.0};
}

struct mesh_uv texture_box_uv(const struct box *b, vec3 point, vec3 normal) {
    vec3 size = vec3_sub(b->max, b->min), q = vec3_sub(point, b->min);
    double x = q.x / size.x, y = q.y / size.y, z = q.z / size.z;
    double ax = fabs(normal.x), ay = fabs(normal.y), az = fabs(normal.z);
    if (ax >= ay && ax >= az) /* the side faces: a band a third high, round from -x */
        return normal.x < 0.0 ? (struct mesh_uv){z / 4.0, 1.0 / 3.0 + y / 3.0}
                              : (struct mesh_uv){3.0 / 4.0 - z / 4.0, 1.0 / 3.0 + y / 3.0};
    if (az >= ay)
        return normal.z < 0.0 ? (struct mesh_uv){1.0 - x / 4.0, 1.0 / 3.0 + y / 3.0}
                              : (struct mesh_uv){1.0 / 4.0 + x / 4.0, 1.0 / 3.0 + y / 3.0};
    return normal.y < 0.0 ? (struct mesh_uv){1.0 / 4.0 + x / 4.0, z / 3.0}
                          : (struct mesh_uv){1.0 / 4.0 + x / 4.0, 1.0 - z / 3.0};
}

/* Returns the box the hit *h is on, or NULL when it is on another shape. */
static const struct box *find_box(const struct scene *s, const struct hit *h) {
    for (size_t k = 0; k < s->kind_count; k++) {
        const struct shape_list *list = &s->shapes[k];
        int index = h->object - world_object_number(s, list, 0);
        if (list->syntax == &box_syntax && index >= 0 && (size_t)index < list->count)
            return &((const struct box *)list->items)[index];
    }
    return NULL;
}

const struct material *texture_paint(const struct scene *s, struct hit *h, vec3 point, struct material *painted) {
    const struct scene_mesh *mesh = mesh_surface_find(s, h);
    size_t face = mesh != NULL ? (size_t)h->face : 0;
    vec3 normal;
    if (mesh != NULL && mesh_surface_normal(mesh, face, point, &normal))
        h->normal = normal; /* a smooth mesh: the corners' normals blended */
    const struct material *m = &s->materials[h->material];
    if (m->pigment < 0)
        return m;
    const struct pigment *p = &s->pigments[m->pigment];
    if (p->uv_mapping) { /* the picture by the surface's own (u, v): (u, v, 0) stands for the point */
        struct mesh_uv uv = {0, 0};
        const struct box *b = mesh == NULL ? find_box(s, h) : NULL;
        if (mesh != NULL)
            mesh_surface_uv(mesh, face, point, &uv);
        else if (b != NULL)
            uv = texture_box_uv(b, point, h->normal);
        point = vec3_make(uv.u, uv.v, 0);
    }
    struct texture_colour c = texture_pigment_at(p, point);
    *painted = *m;
    painted->colour = c.colour;
    painted->transmit = fmin(m->transmit + c.transmit, 1.0 - m->filter);
    return painted;
}

const struct material *texture_paint_shadow(const struct scene *s, struct hit *h, vec3 point,
                                            struct material *painted) {
    const struct material *m = &s->materials[h->material];
    if (m->pigment >= 0) {
        const struct pigment *p = &s->pigments[m->pigment];
        if (p->pattern == PIGMENT_IMAGE_MAP && p->uv_mapping && !p->once && p->image.opaque) {
            *painted = *m;
            painted->filter = 0.0;
            painted->transmit = 0.0;
            return painted;
        }
    }
    return texture_paint(s, h, point, painted);
}

/* The bytes image's texels take. */
static size_t image_bytes(const struct pigment_image *image) {
    return (size_t)image->width * (size_t)image->height * 4 * sizeof *image->texels;
}

/* An earlier pigment of s than k that has read the image file p names, or NULL. */
static const struct pigment *read_before(const struct scene *s, size_t k, const struct pigment *p) {
    for (size_t j = 0; j < k; j++)
        if (s->pigments[j].pattern == PIGMENT_IMAGE_MAP && s->pigments[j].image.texels != NULL &&
            strcmp(s->pigments[j].file, p->file) == 0)
            return &s->pigments[j];
    return NULL;
}

bool texture_load_images(struct scene *s, char *err, size_t err_size) {
    size_t budget = memory_budget_share(TEXTURE_IMAGE_MEMORY_SHARE), taken = 0;
    for (size_t k = 0; k < s->pigment_count; k++) {
        struct pigment *p = &s->pigments[k];
        if (p->pattern != PIGMENT_IMAGE_MAP)
            continue;
        if (p->image.texels == NULL) {
            const struct pigment *same = read_before(s, k, p);
            if (same != NULL) { /* the same file again: one copy of its pixels */
                p->image = same->image;
                p->image.borrowed = true;
                continue;
            }
            char why[1024];
            if (!image_map_read(p->file, &p->image, why, sizeof why)) {
                snprintf(err, err_size, "%s:%d: pigment '%s': %s", s->path, p->line, p->name, why);
                return false;
            }
        }
        taken += p->image.borrowed ? 0 : image_bytes(&p->image);
        if (taken > budget) {
            char why[MEMORY_BUDGET_EXPLAIN_SIZE];
            memory_budget_explain(why, sizeof why, "images", taken, TEXTURE_IMAGE_MEMORY_SHARE);
            snprintf(err, err_size, "%s:%d: pigment '%s': %s", s->path, p->line, p->name, why);
            return false;
        }
    }
    return true;
}

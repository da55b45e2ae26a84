/* pigment_syntax.c: the scene's pigment lines, one table per pattern, and their POV-Ray form (chapter 1:
 * every chapter reads every scene; pigment.h describes the lines, texture.c draws them). */
#include "pigment.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* POV-Ray's default brick: 8 x 3 x 4.5 units with half a unit of mortar. */
#define PIGMENT_DEFAULT_BRICK_X 8.0
#define PIGMENT_DEFAULT_BRICK_Y 3.0
#define PIGMENT_DEFAULT_BRICK_Z 4.5
#define PIGMENT_DEFAULT_MORTAR 0.5

const struct key_spec pigment_transform_keys[PIGMENT_TRANSFORM_KEY_COUNT] = {
    {"scale", 3}, {"rotate", 3}, {"translate", 3}};

bool pigment_make_transform(const struct key_values *kv, int first, struct pigment *p, char *why, size_t why_size) {
    p->scale = kv->present[first] ? key_vec3(kv, first) : vec3_make(1, 1, 1);
    p->rotate = kv->present[first + 1] ? key_vec3(kv, first + 1) : vec3_make(0, 0, 0);
    p->translate = kv->present[first + 2] ? key_vec3(kv, first + 2) : vec3_make(0, 0, 0);
    if (p->scale.x == 0.0 || p->scale.y == 0.0 || p->scale.z == 0.0) {
        snprintf(why, why_size, "pigment '%s': scale must not be 0 along any axis", p->name);
        return false;
    }
    const double scale[3] = {p->scale.x, p->scale.y, p->scale.z};
    for (int k = 0; k < 3; k++)
        if (!(fabs(scale[k]) >= PIGMENT_MIN_SCALE && fabs(scale[k]) <= PIGMENT_MAX_SCALE)) {
            snprintf(why, why_size,
                     "pigment '%s': scale " KEY_NUMBER_SHOWN " is out of range (its size must be from %g to %g)",
                     p->name, KEY_NUMBER(scale[k]), PIGMENT_MIN_SCALE, PIGMENT_MAX_SCALE);
            return false;
        }
    char what[PIGMENT_NAME_MAX + 32];
    snprintf(what, sizeof what, "pigment '%s': rotate", p->name);
    if (!key_vec3_within(p->rotate, PIGMENT_MAX_TURN, what, why, why_size))
        return false;
    snprintf(what, sizeof what, "pigment '%s': translate", p->name);
    return key_vec3_within(p->translate, KEY_MAX_COORD, what, why, why_size);
}

/* ---- the two colours every pattern but the image takes ---------------------------------------- */

enum { KEY_COLOUR, KEY_COLOUR2 }; /* the first two keys of the checker, gradient, brick and radial tables */

/* Reads colour and colour2, each channel from 0 to KEY_MAX_SURFACE. */
static bool make_colours(const struct key_values *kv, struct pigment *p, char *why, size_t why_size) {
    p->colour[0] = key_vec3(kv, KEY_COLOUR);
    p->colour[1] = key_vec3(kv, KEY_COLOUR2);
    for (int k = 0; k < 2; k++) {
        vec3 c = p->colour[k];
        if (c.x < 0.0 || c.y < 0.0 || c.z < 0.0) {
            snprintf(why, why_size, "pigment '%s': %s must not be negative", p->name, k == 0 ? "colour" : "colour2");
            return false;
        }
        if (!(c.x <= KEY_MAX_SURFACE && c.y <= KEY_MAX_SURFACE && c.z <= KEY_MAX_SURFACE)) {
            snprintf(why, why_size, "pigment '%s': %s must be at most %g in each channel, got " KEY_NUMBER_SHOWN " "
                     KEY_NUMBER_SHOWN " " KEY_NUMBER_SHOWN, p->name, k == 0 ? "colour" : "colour2", KEY_MAX_SURFACE,
                     KEY_NUMBER(c.x), KEY_NUMBER(c.y), KEY_NUMBER(c.z));
            return false;
        }
    }
    return true;
}

static const int two_colours_required[] = {KEY_COLOUR, KEY_COLOUR2, -1};

static bool make_checker(const struct key_values *kv, struct pigment *p, char *why, size_t why_size) {
    p->pattern = PIGMENT_CHECKER;
    return make_colours(kv, p, why, why_size);
}

static bool make_radial(const struct key_values *kv, struct pigment *p, char *why, size_t why_size) {
    p->pattern = PIGMENT_RADIAL;
    return make_colours(kv, p, why, why_size);
}

static const struct key_spec two_colour_keys[] = {{"colour", 3}, {"colour2", 3}};

static const struct pigment_syntax checker_syntax = {"checker", two_colour_keys, 2, two_colours_required,
                                                     make_checker};
static const struct pigment_syntax radial_syntax = {"radial", two_colour_keys, 2, two_colours_required,
                                                    make_radial};

/* ---- gradient ------------------------------------------------------------------------------------ */

enum { GRADIENT_AXIS = 2 };
static const struct key_spec gradient_keys[] = {{"colour", 3}, {"colour2", 3}, {"axis", 3}};
static const int gradient_required[] = {KEY_COLOUR, KEY_COLOUR2, GRADIENT_AXIS, -1};

static bool make_gradient(const struct key_values *kv, struct pigment *p, char *why, size_t why_size) {
    p->pattern = PIGMENT_GRADIENT;
    vec3 axis = key_vec3(kv, GRADIENT_AXIS);
    if (axis.x == 0.0 && axis.y == 0.0 && axis.z == 0.0) {
        snprintf(why, why_size, "pigment '%s': axis must not be 0 0 0", p->name);
        return false;
    }
    /* POV-Ray normalises the gradient's vector too; divided by its largest component first, so that
     * squaring 1e200 does not overflow, nor 1e-200 vanish. */
    p->axis = vec3_normalize(vec3_unit_max(axis));
    return make_colours(kv, p, why, why_size);
}

static const struct pigment_syntax gradient_syntax = {"gradient", gradient_keys, 3, gradient_required, make_gradient};

/* ---- brick --------------------------------------------------------------------------------------- */

enum { BRICK_SIZE = 2, BRICK_MORTAR };
static const struct key_spec brick_keys[] = {{"colour", 3}, {"colour2", 3}, {"brick_size", 3}, {"mortar", 1}};

static bool make_brick(const struct key_values *kv, struct pigment *p, char *why, size_t why_size) {
    p->pattern = PIGMENT_BRICK;
    p->brick_size = kv->present[BRICK_SIZE]
                        ? key_vec3(kv, BRICK_SIZE)
                        : vec3_make(PIGMENT_DEFAULT_BRICK_X, PIGMENT_DEFAULT_BRICK_Y, PIGMENT_DEFAULT_BRICK_Z);
    p->mortar = kv->present[BRICK_MORTAR] ? kv->number[BRICK_MORTAR][0] : PIGMENT_DEFAULT_MORTAR;
    if (!(p->brick_size.x > 0.0 && p->brick_size.y > 0.0 && p->brick_size.z > 0.0)) {
        snprintf(why, why_size, "pigment '%s': brick_size must be positive", p->name);
        return false;
    }
    /* A brick is a scale of the pattern, held to a scale's range: at 1e-320 a point's x / size was infinite
     * and every point brick; and the mortar is kept in single precision (POV-Ray's), where 1e39 is infinite. */
    const double sides[3] = {p->brick_size.x, p->brick_size.y, p->brick_size.z};
    for (int k = 0; k < 3; k++)
        if (!(sides[k] >= PIGMENT_MIN_SCALE && sides[k] <= PIGMENT_MAX_SCALE)) {
            snprintf(why, why_size, "pigment '%s': brick_size " KEY_NUMBER_SHOWN " is out of range (each side from %g to "
                     "%g)", p->name, KEY_NUMBER(sides[k]), PIGMENT_MIN_SCALE, PIGMENT_MAX_SCALE);
            return false;
        }
    if (p->mortar < 0.0) {
        snprintf(why, why_size, "pigment '%s': mortar must not be negative", p->name);
        return false;
    }
    if (p->mortar > PIGMENT_MAX_SCALE) {
        snprintf(why, why_size, "pigment '%s': mortar " KEY_NUMBER_SHOWN " is out of range (at most %g)", p->name,
                 KEY_NUMBER(p->mortar), PIGMENT_MAX_SCALE);
        return false;
    }
    return make_colours(kv, p, why, why_size);
}

static const struct pigment_syntax brick_syntax = {"brick", brick_keys, 4, two_colours_required, make_brick};

/* ---- image_map ----------------------------------------------------------------------------------- */

enum { IMAGE_FILE, IMAGE_MAP, IMAGE_INTERPOLATE, IMAGE_WRAP };
static const struct key_spec image_keys[] = {{"file", 0}, {"map", 0}, {"interpolate", 1}, {"wrap", 0}};
static const int image_required[] = {IMAGE_FILE, -1};

/* The file's path is resolved by the parser, which knows the scene's folder; here it is only checked. */
static bool make_image_map(const struct key_values *kv, struct pigment *p, char *why, size_t why_size) {
    p->pattern = PIGMENT_IMAGE_MAP;
    p->mapping = PIGMENT_MAP_PLANAR;
    if (kv->present[IMAGE_MAP]) {
        const char *map = kv->word[IMAGE_MAP];
        if (strcmp(map, "spherical") == 0) {
            p->mapping = PIGMENT_MAP_SPHERICAL;
        } else if (strcmp(map, "uv") == 0) {
            p->uv_mapping = true;
        } else if (strcmp(map, "planar") != 0) {
            snprintf(why, why_size, "pigment '%s': map must be planar, spherical or uv, got '%s'", p->name, map);
            return false;
        }
    }
    p->interpolate = 0;
    if (kv->present[IMAGE_INTERPOLATE]) {
        double interpolate = kv->number[IMAGE_INTERPOLATE][0];
        if (interpolate != 0.0 && interpolate != 2.0) {
            snprintf(why, why_size, "pigment '%s': interpolate must be 0 (nearest) or 2 (bilinear), got " KEY_NUMBER_SHOWN,
                     p->name, KEY_NUMBER(interpolate));
            return false;
        }
        p->interpolate = (int)interpolate;
    }
    p->once = false;
    if (kv->present[IMAGE_WRAP]) {
        const char *wrap = kv->word[IMAGE_WRAP];
        if (strcmp(wrap, "once") == 0) {
            p->once = true;
        } else if (strcmp(wrap, "repeat") != 0) {
            snprintf(why, why_size, "pigment '%s': wrap must be repeat or once, got '%s'", p->name, wrap);
            return false;
        }
    }
    return true;
}

static const struct pigment_syntax image_map_syntax = {"image_map", image_keys, 4, image_required, make_image_map};

const struct pigment_syntax *const pigment_syntaxes[] = {&checker_syntax, &gradient_syntax, &brick_syntax,
                                                         &radial_syntax, &image_map_syntax, NULL};

/* ---- POV-Ray ------------------------------------------------------------------------------------- */

bool pigment_file_is_jpeg(const char *file) {
    const char *dot = strrchr(file, '.');
    return dot != NULL && (strcmp(dot, ".jpg") == 0 || strcmp(dot, ".jpeg") == 0 || strcmp(dot, ".JPG") == 0 ||
                           strcmp(dot, ".JPEG") == 0);
}

const char *pigment_twin_file(const struct pigment *p, char *whole) {
    return realpath(p->file, whole) != NULL ? whole : p->file;
}

bool pigment_twin_file_writable(const char *path) {
    for (const unsigned char *c = (const unsigned char *)path; *c != '\0'; c++)
        if (*c == '"' || *c == '\\' || *c < 0x20 || *c == 0x7f)
            return false;
    return true;
}

static void write_colour(FILE *out, vec3 c, double filter, double transmit) {
    fprintf(out, "rgbft <%.17g, %.17g, %.17g, %.17g, %.17g>", c.x, c.y, c.z, filter, transmit);
}

/* A colour map from colour (at 0) to colour2 (at 1). */
static void write_colour_map(FILE *out, const struct pigment *p, double filter, double transmit) {
    fprintf(out, " color_map { [0 ");
    write_colour(out, p->colour[0], filter, transmit);
    fprintf(out, "] [1 ");
    write_colour(out, p->colour[1], filter, transmit);
    fprintf(out, "] }");
}

void pigment_write_pov(FILE *out, const struct pigment *p, double filter, double transmit) {
    fprintf(out, "pigment { ");
    switch (p->pattern) {
    case PIGMENT_CHECKER:
    case PIGMENT_BRICK:
        fprintf(out, "%s ", p->pattern == PIGMENT_CHECKER ? "checker" : "brick");
        write_colour(out, p->colour[0], filter, transmit);
        fprintf(out, ", ");
        write_colour(out, p->colour[1], filter, transmit);
        if (p->pattern == PIGMENT_BRICK) {
            fprintf(out, " brick_size ");
            shape_write_vector(out, p->brick_size);
            fprintf(out, " mortar %.17g", p->mortar);
        }
        break;
    case PIGMENT_GRADIENT:
        fprintf(out, "gradient ");
        shape_write_vector(out, p->axis);
        write_colour_map(out, p, filter, transmit);
        break;
    case PIGMENT_RADIAL:
        fprintf(out, "radial");
        write_colour_map(out, p, filter, transmit);
        break;
    case PIGMENT_IMAGE_MAP: {
        bool jpeg = pigment_file_is_jpeg(p->file);
        char whole[PATH_MAX];
        const char *file = pigment_twin_file(p, whole);
        fprintf(out, "%simage_map { %s \"%s\" map_type %d", p->uv_mapping ? "uv_mapping " : "", jpeg ? "jpeg" : "png",
                file, (int)p->mapping);
        if (p->interpolate != 0) /* POV-Ray refuses `interpolate 0`: no interpolation is its default */
            fprintf(out, " interpolate %d", p->interpolate);
        /* `filter all` and `transmit all` replace every colour's own transparency in a palette PNG (a tRNS
         * chunk's), so they are written only when the material lets light through itself. */
        fprintf(out, "%s", p->once ? " once" : "");
        if (filter != 0.0 || transmit != 0.0)
            fprintf(out, " filter all %.17g transmit all %.17g", filter, transmit);
        fprintf(out, " }");
        break;
    }
    }
    fprintf(out, "\n    scale ");
    shape_write_vector(out, p->scale);
    fprintf(out, " rotate ");
    shape_write_vector(out, p->rotate);
    fprintf(out, " translate ");
    shape_write_vector(out, p->translate);
    fprintf(out, " }");
}

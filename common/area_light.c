/* area_light.c: the area keys of a light line: their checks and their POV-Ray keywords (read from
 * chapter 1 on, drawn by chapter 13; docs/13-distributed.md). */
#include "area_light.h"

#include <math.h>
#include <string.h>

enum { KEY_AXIS1, KEY_AXIS2, KEY_SAMPLES, KEY_ADAPTIVE, KEY_CIRCULAR, KEY_ORIENT };

const struct key_spec area_light_keys[AREA_LIGHT_KEY_COUNT] = {
    [KEY_AXIS1] = {"axis1", 3},    [KEY_AXIS2] = {"axis2", 3},       [KEY_SAMPLES] = {"samples", 2},
    [KEY_ADAPTIVE] = {"adaptive", 1}, [KEY_CIRCULAR] = {"circular", 0}, [KEY_ORIENT] = {"orient", 0}};

/* Reads an on/off word into *flag; false with the reason in why otherwise. */
static bool on_off(const char *word, const char *key, bool *flag, char *why, size_t why_size) {
    if (strcmp(word, "on") != 0 && strcmp(word, "off") != 0) {
        snprintf(why, why_size, "light %s must be on or off, got '%s'", key, word);
        return false;
    }
    *flag = strcmp(word, "on") == 0;
    return true;
}

/* True when x is a whole number in [lo, hi]. */
static bool whole_in(double x, double lo, double hi) { return x >= lo && x <= hi && x == floor(x); }

bool area_light_make(const struct key_values *kv, struct area_light *a, char *why, size_t why_size) {
    *a = (struct area_light){.adaptive = AREA_LIGHT_NOT_ADAPTIVE};
    bool axes = kv->present[KEY_AXIS1] || kv->present[KEY_AXIS2] || kv->present[KEY_SAMPLES];
    if (axes && !(kv->present[KEY_AXIS1] && kv->present[KEY_AXIS2] && kv->present[KEY_SAMPLES])) {
        snprintf(why, why_size, "an area light needs all of axis1, axis2 and samples");
        return false;
    }
    if (!axes) {
        for (int k = KEY_ADAPTIVE; k <= KEY_ORIENT; k++)
            if (kv->present[k]) {
                snprintf(why, why_size, "light %s needs an area light (axis1, axis2 and samples)",
                         area_light_keys[k].name);
                return false;
            }
        return true;
    }
    const double *n = kv->number[KEY_SAMPLES];
    if (!whole_in(n[0], 1, AREA_LIGHT_MAX_SIZE) || !whole_in(n[1], 1, AREA_LIGHT_MAX_SIZE)) {
        snprintf(why, why_size,
                 "light samples must be whole numbers from 1 to %d, got " KEY_NUMBER_SHOWN " " KEY_NUMBER_SHOWN,
                 AREA_LIGHT_MAX_SIZE, KEY_NUMBER(n[0]), KEY_NUMBER(n[1]));
        return false;
    }
    a->axis1 = key_vec3(kv, KEY_AXIS1);
    a->axis2 = key_vec3(kv, KEY_AXIS2);
    a->size1 = (int)n[0];
    a->size2 = (int)n[1];
    const vec3 axis[2] = {a->axis1, a->axis2};
    for (int k = 0; k < 2; k++) {
        const char *name = k == 0 ? "light axis1" : "light axis2";
        double length = vec3_length_scaled(axis[k]);
        if (length == 0.0) {
            snprintf(why, why_size, "%s is zero: the area light has no rectangle", name);
            return false;
        }
        if (!key_vec3_within(axis[k], KEY_MAX_COORD, name, why, why_size))
            return false;
        if (!(length >= AREA_LIGHT_MIN_AXIS)) {
            snprintf(why, why_size, "%s is " KEY_NUMBER_SHOWN " long; an axis must be at least %g long", name,
                     KEY_NUMBER(length), AREA_LIGHT_MIN_AXIS);
            return false;
        }
    }
    if (vec3_parallel(a->axis1, a->axis2, AREA_LIGHT_MIN_SINE)) {
        snprintf(why, why_size, "light axis1 and axis2 are parallel: the area light has no rectangle");
        return false;
    }
    if (kv->present[KEY_ADAPTIVE]) {
        double level = kv->number[KEY_ADAPTIVE][0];
        if (!whole_in(level, 0, AREA_LIGHT_MAX_ADAPTIVE)) {
            snprintf(why, why_size, "light adaptive must be a whole number from 0 to %d, got " KEY_NUMBER_SHOWN,
                     AREA_LIGHT_MAX_ADAPTIVE, KEY_NUMBER(level));
            return false;
        }
        a->adaptive = (int)level;
    }
    if ((kv->present[KEY_CIRCULAR] && !on_off(kv->word[KEY_CIRCULAR], "circular", &a->circular, why, why_size)) ||
        (kv->present[KEY_ORIENT] && !on_off(kv->word[KEY_ORIENT], "orient", &a->orient, why, why_size)))
        return false;
    if (a->circular && (a->size1 < 2 || a->size2 < 2)) {
        snprintf(why, why_size, "a circular light needs at least 2 samples a side, got %d %d", a->size1, a->size2);
        return false;
    }
    if (a->orient && !a->circular) {
        snprintf(why, why_size, "light orient needs circular on (POV-Ray orients only circular lights)");
        return false;
    }
    return true;
}

void area_light_write_pov(FILE *out, const struct area_light *a) {
    if (!area_light_is_area(a))
        return;
    fprintf(out, " area_light ");
    shape_write_vector(out, a->axis1);
    fprintf(out, ", ");
    shape_write_vector(out, a->axis2);
    fprintf(out, ", %d, %d", a->size1, a->size2);
    if (a->adaptive != AREA_LIGHT_NOT_ADAPTIVE)
        fprintf(out, " adaptive %d", a->adaptive);
    if (a->circular)
        fprintf(out, " circular");
    if (a->orient)
        fprintf(out, " orient");
}

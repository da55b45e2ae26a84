/* lens.c: the lens keys of the camera line: their checks and their POV-Ray keywords (read from chapter
 * 1 on, drawn by chapter 13; docs/13-distributed.md). */
#include "lens.h"

enum { KEY_APERTURE, KEY_FOCAL_POINT, KEY_BLUR_SAMPLES };

const struct key_spec lens_keys[LENS_KEY_COUNT] = {
    [KEY_APERTURE] = {"aperture", 1}, [KEY_FOCAL_POINT] = {"focal_point", 3}, [KEY_BLUR_SAMPLES] = {"blur_samples", 1}};

bool lens_make(const struct key_values *kv, vec3 eye, struct lens *l, char *why, size_t why_size) {
    *l = (struct lens){0.0, eye, LENS_DEFAULT_SAMPLES};
    if (!kv->present[KEY_APERTURE]) {
        if (kv->present[KEY_FOCAL_POINT] || kv->present[KEY_BLUR_SAMPLES]) {
            snprintf(why, why_size, "camera %s needs an aperture",
                     kv->present[KEY_FOCAL_POINT] ? "focal_point" : "blur_samples");
            return false;
        }
        return true;
    }
    l->aperture = kv->number[KEY_APERTURE][0];
    if (l->aperture < 0.0) {
        snprintf(why, why_size, "camera aperture must not be negative, got " KEY_NUMBER_SHOWN, KEY_NUMBER(l->aperture));
        return false;
    }
    if (l->aperture > LENS_MAX_APERTURE) {
        snprintf(why, why_size, "camera aperture must be at most %g, got " KEY_NUMBER_SHOWN, LENS_MAX_APERTURE,
                 KEY_NUMBER(l->aperture));
        return false;
    }
    if (!kv->present[KEY_FOCAL_POINT]) {
        snprintf(why, why_size, "camera aperture needs a focal_point (where the picture is sharp)");
        return false;
    }
    l->focal_point = key_vec3(kv, KEY_FOCAL_POINT);
    if (!key_vec3_within(l->focal_point, KEY_MAX_COORD, "camera focal_point", why, why_size) ||
        !key_vec3_within(eye, KEY_MAX_COORD, "camera eye (with a lens)", why, why_size))
        return false;
    double focal_distance = vec3_length(vec3_sub(l->focal_point, eye));
    if (!(focal_distance > LENS_MIN_FOCAL_DISTANCE)) {
        snprintf(why, why_size, "camera focal_point is the eye: nothing can be in focus there");
        return false;
    }
    if (l->aperture > LENS_MAX_APERTURE_RATIO * focal_distance) {
        snprintf(why, why_size, "camera aperture must be at most %g times the focal_point's distance from the eye "
                 "(%g), got " KEY_NUMBER_SHOWN ": a wider lens blurs everything off the focal plane over the whole "
                 "picture", LENS_MAX_APERTURE_RATIO, focal_distance, KEY_NUMBER(l->aperture));
        return false;
    }
    if (kv->present[KEY_BLUR_SAMPLES]) {
        double n = kv->number[KEY_BLUR_SAMPLES][0];
        if (n != 7 && n != 19 && n != 37) {
            snprintf(why, why_size, "camera blur_samples must be 7, 19 or 37 (1, 2 or 3 rings of the lens's "
                     "hexagonal grid), got " KEY_NUMBER_SHOWN, KEY_NUMBER(n));
            return false;
        }
        l->blur_samples = (int)n;
    }
    return true;
}

void lens_write_pov(FILE *out, const struct lens *l) {
    if (!lens_is_open(l))
        return;
    fprintf(out, "  aperture %.17g\n  focal_point ", 2.0 * l->aperture);
    shape_write_vector(out, l->focal_point);
    fprintf(out, "\n  blur_samples %d\n  variance 0\n", l->blur_samples);
}

/* instance_syntax.c: checking the numbers of the object, instance and key lines and the shutter
 * (chapter 1 reads them; instance_syntax.h). */
#include "instance_syntax.h"

#include <math.h>
#include <stdio.h>

enum { POSE_SCALE, POSE_ROTATE, POSE_TRANSLATE };

const struct key_spec instance_pose_keys[INSTANCE_POSE_KEY_COUNT] = {{"scale", 3}, {"rotate", 3}, {"translate", 3}};

bool instance_chapter_draws(int chapter, int introduced) {
    if (chapter == INSTANCE_CHAPTER && introduced > INSTANCE_BASE_CHAPTER && introduced < INSTANCE_CHAPTER)
        return false;
    return chapter >= introduced;
}

struct scene_pose instance_pose_identity(void) {
    return (struct scene_pose){{1, 1, 1}, {0, 0, 0}, {0, 0, 0}};
}

/* Returns whether a scale factor's size is within INSTANCE_SCALE_MIN .. INSTANCE_SCALE_MAX. */
static bool scale_in_range(double s) {
    return fabs(s) >= INSTANCE_SCALE_MIN && fabs(s) <= INSTANCE_SCALE_MAX;
}

bool instance_pose_make(const struct key_values *kv, const struct scene_pose *base, struct scene_pose *pose,
                        char *why, size_t why_size) {
    *pose = *base;
    if (kv->present[POSE_SCALE])
        pose->scale = key_vec3(kv, POSE_SCALE);
    if (kv->present[POSE_ROTATE])
        pose->rotate = key_vec3(kv, POSE_ROTATE);
    if (kv->present[POSE_TRANSLATE])
        pose->translate = key_vec3(kv, POSE_TRANSLATE);
    vec3 s = pose->scale;
    if (!scale_in_range(s.x) || !scale_in_range(s.y) || !scale_in_range(s.z)) {
        snprintf(why, why_size, "scale is " KEY_NUMBER_SHOWN " " KEY_NUMBER_SHOWN " " KEY_NUMBER_SHOWN
                 "; each factor's size must be between %g and %g (a zero scale flattens the object)",
                 KEY_NUMBER(s.x), KEY_NUMBER(s.y), KEY_NUMBER(s.z), INSTANCE_SCALE_MIN, INSTANCE_SCALE_MAX);
        return false;
    }
    return key_vec3_within(pose->rotate, INSTANCE_ANGLE_MAX, "rotate", why, why_size) &&
           key_vec3_within(pose->translate, KEY_MAX_COORD, "translate", why, why_size);
}

bool instance_key_time_valid(double time, double previous, bool has_previous, char *why, size_t why_size) {
    if (!(time >= 0.0 && time <= 1.0)) {
        snprintf(why, why_size, "key time must be between 0 and 1, got " KEY_NUMBER_SHOWN, KEY_NUMBER(time));
        return false;
    }
    if (has_previous && !(time > previous)) {
        snprintf(why, why_size, "key time " KEY_NUMBER_SHOWN " is not after the instance's previous key's ("
                 KEY_NUMBER_SHOWN "): keys go in increasing time", KEY_NUMBER(time),
                 KEY_NUMBER(previous));
        return false;
    }
    return true;
}

bool instance_shutter_valid(double shutter, char *why, size_t why_size) {
    if (shutter >= 0.0 && shutter <= 1.0)
        return true;
    snprintf(why, why_size, "camera shutter must be between 0 and 1 (clock units), got " KEY_NUMBER_SHOWN,
             KEY_NUMBER(shutter));
    return false;
}

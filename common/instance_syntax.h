/* instance_syntax.h: the numbers of the object, instance and key lines and the camera's shutter, and
 * their limits (chapter 1 reads them, chapter 16 draws them; docs/scene-format.md).
 *
 * An instance is placed by a pose: x_world = translate + Rz Ry Rx (scale * x_object), the scale per
 * axis, the angles in degrees about x, then y, then z (the mesh line's order, and POV-Ray's `scale
 * rotate translate`). A key line gives the pose of one instance at one clock time; between keys each of
 * the nine numbers changes linearly. This module checks the numbers a line gives (the scene reader
 * reads the words and adds file and line to the messages). */
#ifndef WHITTED_INSTANCE_SYNTAX_H
#define WHITTED_INSTANCE_SYNTAX_H

#include <stdbool.h>
#include <stddef.h>

#include "shape.h"
#include "vec3.h"

#define INSTANCE_CHAPTER 16        /* the chapter that draws them */
#define INSTANCE_BASE_CHAPTER 13   /* the chapter it is built on: chapter 13's tracer and sampler */
#define SCENE_OBJECT_MAX 4096      /* object lines in one scene */
#define SCENE_INSTANCE_MAX 1048576 /* instance lines in one scene: a million fit */
#define SCENE_KEY_MAX 1024         /* key lines of one instance */
/* Each scale factor's size: within it a scaled object stays a solid whose inverse transform is exact
 * to a few units in the last place, and a placed coordinate stays far inside KEY_MAX_COORD's range. */
#define INSTANCE_SCALE_MIN 1e-9
#define INSTANCE_SCALE_MAX 1e9
/* The largest angle, in degrees: its sine and cosine still have all their digits' worth of meaning. */
#define INSTANCE_ANGLE_MAX 1e6

/* Whether chapter `chapter` draws what chapter `introduced` brought in: every later chapter does, but
 * chapter 16 is chapter 13's Whitted tracer with instances and time, without chapter 14's pigments and
 * chapter 15's paths and emission (it reads them, and says it ignores them). Cannot fail. */
bool instance_chapter_draws(int chapter, int introduced);

/* Where an instance is at one time: scale (per axis), rotate (degrees about x, y, z), translate. */
struct scene_pose {
    vec3 scale, rotate, translate;
};

/* A key line: the pose of an instance at clock time `time` (0 .. 1). */
struct scene_key {
    double time;
    struct scene_pose pose;
    int line; /* of the key line, for messages */
};

/* The keys every pose takes, in this order: scale X Y Z, rotate X Y Z, translate X Y Z. */
#define INSTANCE_POSE_KEY_COUNT 3
extern const struct key_spec instance_pose_keys[INSTANCE_POSE_KEY_COUNT];

/* The identity pose: scale 1 1 1, no rotation, no translation. */
struct scene_pose instance_pose_identity(void);

/* Fills *pose from the values read for instance_pose_keys, each key not given taken from *base.
 * Returns false with the reason in why (without file and line) when a scale factor's size is outside
 * INSTANCE_SCALE_MIN .. INSTANCE_SCALE_MAX (zero included: a degenerate transform), an angle beyond
 * INSTANCE_ANGLE_MAX, or a translation beyond KEY_MAX_COORD. */
bool instance_pose_make(const struct key_values *kv, const struct scene_pose *base, struct scene_pose *pose,
                        char *why, size_t why_size);

/* Checks a key's time: within 0 .. 1 and, when the instance has keys already (previous >= 0 is the time
 * of its last), after the previous one. Returns false with the reason in why. */
bool instance_key_time_valid(double time, double previous, bool has_previous, char *why, size_t why_size);

/* Checks the camera's shutter: 0 .. 1. Returns false with the reason in why. */
bool instance_shutter_valid(double shutter, char *why, size_t why_size);

#endif

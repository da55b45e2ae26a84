/* check_instances.c: the coursework checks of chapter 16: the box that holds a moving object over the
 * shutter, on motions whose every position the check computes itself (the coursework kit). */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "keyframes.h"
#include "transform.h"

/* ---- 16.3 the motion box ------------------------------------------------------------------------ */

/* Times sampled in the shutter to find where the object goes: far more than any sampling of the
 * student's would need, so a box built from a few times falls short somewhere between them. */
#define MOTION_SAMPLES 4096

/* How much looser than the motion itself a motion box may be, per side, as a share of the object's
 * size in the world (its box's radius about its origin, times its largest scale): the model answer pads
 * by 1/32 of it. */
#define MOTION_LOOSENESS 0.25

/* Where corner c (0..7) of box b goes at `time`. */
static vec3 corner_at(const struct keyframe *keys, size_t count, struct aabb b, int c, double time) {
    struct pose p = keyframes_pose_at(keys, count, time);
    struct transform t = transform_from_pose(p.scale, p.rotate, p.translate);
    vec3 corner = vec3_make(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z);
    return transform_point(&t, corner);
}

static bool box_holds_point(struct aabb b, vec3 p) {
    return p.x >= b.min.x && p.x <= b.max.x && p.y >= b.min.y && p.y <= b.max.y && p.z >= b.min.z && p.z <= b.max.z;
}

/* Checks keyframes_motion_box on one motion over [t0, t1]: the box holds every corner of the object at
 * MOTION_SAMPLES times (and every point of the object is inside the hull of its corners), and no side
 * is more than MOTION_LOOSENESS of the object's size beyond where the corners go. `what` describes the
 * motion in the messages. */
static bool motion_box_fits(const struct keyframe *keys, size_t count, struct aabb object, double t0, double t1,
                            double size, const char *what, char *why, size_t why_size) {
    check_calling("keyframes_motion_box", "%s, shutter [%g, %g]", what, t0, t1);
    struct aabb got = keyframes_motion_box(keys, count, object, t0, t1), swept = aabb_empty();
    char a[64], b[64], p[64];
    for (int s = 0; s <= MOTION_SAMPLES; s++) {
        double time = t0 + (t1 - t0) * s / MOTION_SAMPLES;
        for (int c = 0; c < 8; c++) {
            vec3 point = corner_at(keys, count, object, c, time);
            swept = aabb_grow(swept, point);
            if (!box_holds_point(got, point)) {
                snprintf(why, why_size, "%s, shutter [%g, %g]: your box runs from %s to %s, but at time %.4g a corner "
                         "of the object is at %s, outside it%s", what, t0, t1, check_vec_text(got.min, a),
                         check_vec_text(got.max, b), time, check_vec_text(point, p),
                         time > t0 && time < t1 ? ": a box of the positions at a few times (the ends?) misses where "
                                                  "a turning object goes between them" : "");
                return false;
            }
        }
    }
    double slack = MOTION_LOOSENESS * size;
    if (got.min.x < swept.min.x - slack || got.min.y < swept.min.y - slack || got.min.z < swept.min.z - slack ||
        got.max.x > swept.max.x + slack || got.max.y > swept.max.y + slack || got.max.z > swept.max.z + slack) {
        snprintf(why, why_size, "%s, shutter [%g, %g]: the object goes from %s to %s over the shutter, and your box "
                 "runs from %s to %s, more than %g (a quarter of the object's size) beyond it on some side: a "
                 "box much looser than the motion makes the top level test the instance for rays that miss it",
                 what, t0, t1, check_vec_text(swept.min, a), check_vec_text(swept.max, b), check_vec_text(got.min, p),
                 check_vec_text(got.max, (char[64]){0}), slack);
        return false;
    }
    return true;
}

static struct pose pose_of(vec3 scale, vec3 rotate, vec3 translate) { return (struct pose){scale, rotate, translate}; }

/* A bar 2 long from its pivot along x, 0.24 thick. */
static struct aabb arm_box(void) { return (struct aabb){{0, -0.12, -0.12}, {2, 0.12, 0.12}}; }

CHECK(check_motion_box_translation) {
    /* A unit box sliding 3 along x and 1 up while it grows to twice its size: no turn. */
    struct keyframe keys[2] = {{0, pose_of(vec3_make(1, 1, 1), vec3_make(0, 0, 0), vec3_make(0, 0, 0))},
                               {1, pose_of(vec3_make(2, 2, 2), vec3_make(0, 0, 0), vec3_make(3, 1, 0))}};
    struct aabb unit = {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};
    return motion_box_fits(keys, 2, unit, 0, 1, 2 * sqrt(0.75), "a unit box sliding from (0, 0, 0) to (3, 1, 0) and "
                           "growing to scale 2", why, why_size);
}

CHECK(check_motion_box_turn) {
    /* The arm turns from -45 to +45 degrees about z: at each end its tip is at x = 1.41, halfway at 2. */
    struct keyframe keys[2] = {{0, pose_of(vec3_make(1, 1, 1), vec3_make(0, 0, -45), vec3_make(0, 0, 0))},
                               {1, pose_of(vec3_make(1, 1, 1), vec3_make(0, 0, 45), vec3_make(0, 0, 0))}};
    return motion_box_fits(keys, 2, arm_box(), 0, 1, 2.01, "an arm 2 long turning from -45 to +45 degrees about z",
                           why, why_size);
}

CHECK(check_motion_box_keys_and_shutter) {
    /* Three keys: the arm turns a half turn about y and back while it moves; the shutter is open over
     * part of it only, across the middle key. */
    struct keyframe keys[3] = {{0, pose_of(vec3_make(1, 1, 1), vec3_make(0, 0, 0), vec3_make(0, 0, 0))},
                               {0.5, pose_of(vec3_make(1, 1, 1), vec3_make(0, 180, 0), vec3_make(1, 0, 0))},
                               {1, pose_of(vec3_make(1, 1, 1), vec3_make(0, 0, 0), vec3_make(2, 0, 0))}};
    if (!motion_box_fits(keys, 3, arm_box(), 0.3, 0.6, 2.01, "an arm turning half a turn about y and back over three "
                         "keys (0, 0.5, 1)", why, why_size))
        return false;
    /* A shutter of no length: the box of the pose at that time. */
    return motion_box_fits(keys, 3, arm_box(), 0.75, 0.75, 2.01, "the same arm, a shutter of no length", why, why_size);
}

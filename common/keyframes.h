/* keyframes.h: an instance's pose over time, and the box that holds it over a shutter (chapter 16).
 *
 * A moving instance has keyframes: poses (scale, rotate, translate, as the instance line's) at clock
 * times. Between two keys each of the pose's nine numbers moves linearly with time, so a change of one
 * rotate angle turns the object about that axis; before the first key and after the last the pose
 * holds. With motion blur a camera sample sees the instance at its own time in the shutter [t0, t1],
 * so the top level of the two-level BVH needs a box holding the object at every such time: the motion
 * box. */
#ifndef WHITTED_KEYFRAMES_H
#define WHITTED_KEYFRAMES_H

#include <stddef.h>

#include "aabb.h"
#include "vec3.h"

/* Where an object is put: x_world = translate + Rz Ry Rx (scale * x_object), angles in degrees
 * (transform_from_pose). */
struct pose {
    vec3 scale, rotate, translate;
};

struct keyframe {
    double time;
    struct pose pose;
};

/* The motion box pads the boxes at its sampled times by the most a point can move between two of them
 * (keyframes_motion_box). It samples each stretch of linear motion often enough that this padding is
 * at most this fraction of the object's size in the world (the largest |scale| times its radius about
 * its own origin), so the box is never much looser than the motion itself... */
#define MOTION_BOX_PAD_FRACTION (1.0 / 32.0)

/* ...unless that would take more than this many steps for one stretch between keys (an object moving
 * more than eight times its size, or turning more than about 1.3 turns, within the stretch): then the
 * translation is taken apart from the turning and scaling (keyframes_motion_box), which costs no
 * steps however far it goes. */
#define MOTION_BOX_STEPS_MAX 128

/* Every stretch's box is padded by this many DBL_EPSILONs of the pose's size more (|translate| plus
 * the object's radius in the world times one plus the angles in radians): room for the roundings of
 * the pose, the sines and cosines and the transform, which make the computed point at a time differ
 * from the exact motion. */
#define MOTION_BOX_ROUNDING 64.0

/* Returns the pose at `time` of the `count` (>= 1) keys, which are in increasing time: linear in each
 * of the nine numbers between the two keys around `time`, a key's own pose exactly at its time, the
 * first key's before it and the last key's after it. */
struct pose keyframes_pose_at(const struct keyframe *keys, size_t count, double time);

/* Returns a box holding transform_point(transform_from_pose(keyframes_pose_at(keys, count, t)), p) for
 * every point p of object_box and every time t in [t0, t1] (t0 <= t1; count >= 1, keys in increasing
 * time). Conservative by construction, not by luck of sampling: the shutter is cut at the keys into
 * stretches of linear motion; each stretch is sampled at n + 1 evenly spaced times, the boxes of the
 * object there (transform_box) joined, and the union padded by the most any point of the object can move
 * in half a step: the speed of a point p is at most
 *     |rate of translate| + (|rate of rotate x| + |... y| + |... z|) * largest |scale| * r
 *                         + largest |rate of scale| * r,
 * r being the object box's radius about the object's origin (its farthest corner), rates per unit of
 * time, angles in radians (each turn about one axis moves a point at most its angular rate times its
 * distance from the axis, and turns keep lengths), and a point at a time between two samples is
 * within half a step of one of them. n is chosen so that the padding is about MOTION_BOX_PAD_FRACTION
 * of the object's size. Where that would take more than MOTION_BOX_STEPS_MAX steps, a point is taken
 * as its translation (on a line: inside the box of the stretch's two ends) plus the object turned and
 * scaled (inside that motion's own box, sampled and padded as above without the translation's speed,
 * or, turning too fast for that as well, within the size of the origin, |R S p| <= largest |scale| * r),
 * and the stretch's box is the sum of those two boxes. Everything is padded by MOTION_BOX_ROUNDING
 * more for the roundings. An empty object_box gives the empty box. */
struct aabb keyframes_motion_box(const struct keyframe *keys, size_t count, struct aabb object_box, double t0,
                                 double t1);

#endif

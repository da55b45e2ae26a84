/* test_keyframes.c: chapter 16's keyframes: the pose between keys is linear and holds outside them,
 * and the motion box holds the object at every one of 10,000 sampled times in the shutter for
 * translation, rotation about each axis, scale and their mix, without being much looser than the
 * sampled motion; while a box from the end positions only misses a rotating object's middle. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include "keyframes.h"
#include "transform.h"
#include "uniform.h"

/* ---- the pose between keys ---------------------------------------------------------------------- */

static struct pose pose_of(vec3 scale, vec3 rotate, vec3 translate) { return (struct pose){scale, rotate, translate}; }

static bool same_vec3(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

static bool same_pose(struct pose a, struct pose b) {
    return same_vec3(a.scale, b.scale) && same_vec3(a.rotate, b.rotate) && same_vec3(a.translate, b.translate);
}

Test(keyframes, the_pose_is_linear_between_keys_and_holds_outside_them) {
    struct keyframe keys[] = {
        {0.25, pose_of(vec3_make(1, 1, 1), vec3_make(0, 0, 0), vec3_make(0, 0, 0))},
        {0.5, pose_of(vec3_make(2, 1, 1), vec3_make(0, 90, 0), vec3_make(4, 0, -2))},
        {0.75, pose_of(vec3_make(2, 3, 1), vec3_make(0, 90, 30), vec3_make(4, 8, -2))},
    };
    cr_expect(same_pose(keyframes_pose_at(keys, 3, 0.0), keys[0].pose), "held before the first key");
    cr_expect(same_pose(keyframes_pose_at(keys, 3, 1.0), keys[2].pose), "held after the last key");
    for (int k = 0; k < 3; k++)
        cr_expect(same_pose(keyframes_pose_at(keys, 3, keys[k].time), keys[k].pose), "key %d at its own time", k);
    struct pose middle = keyframes_pose_at(keys, 3, 0.375);
    cr_expect(same_pose(middle, pose_of(vec3_make(1.5, 1, 1), vec3_make(0, 45, 0), vec3_make(2, 0, -1))));
    struct pose later = keyframes_pose_at(keys, 3, 0.6875);
    cr_expect(same_pose(later, pose_of(vec3_make(2, 2.5, 1), vec3_make(0, 90, 22.5), vec3_make(4, 6, -2))));
    struct keyframe one = {0.5, pose_of(vec3_make(3, 3, 3), vec3_make(1, 2, 3), vec3_make(4, 5, 6))};
    cr_expect(same_pose(keyframes_pose_at(&one, 1, 0.1), one.pose));
    cr_expect(same_pose(keyframes_pose_at(&one, 1, 0.9), one.pose));
}

Test(keyframes, the_search_finds_the_right_pair_among_many_keys) {
    enum { COUNT = 1000 };
    static struct keyframe keys[COUNT];
    for (int k = 0; k < COUNT; k++) /* translate.x = 2 time, rotate.z alternating 0 and 10 */
        keys[k] = (struct keyframe){k / (double)(COUNT - 1),
                                    pose_of(vec3_make(1, 1, 1), vec3_make(0, 0, k % 2 ? 10 : 0),
                                            vec3_make(2.0 * k / (COUNT - 1), 0, 0))};
    for (uint32_t j = 0; j < 5000; j++) {
        double time = uniform(40, j, 0, 1);
        struct pose p = keyframes_pose_at(keys, COUNT, time);
        cr_assert(fabs(p.translate.x - 2 * time) <= 1e-12, "time %.17g: %.17g", time, p.translate.x);
        double position = time * (COUNT - 1), within = position - floor(position);
        int left = (int)floor(position);
        double expected = left % 2 ? 10 * (1 - within) : 10 * within;
        cr_assert(fabs(p.rotate.z - expected) <= 1e-9, "time %.17g: %.17g not %.17g", time, p.rotate.z, expected);
    }
}

/* ---- the motion box ----------------------------------------------------------------------------- */

/* A box not centred on the object's origin, so that turns also move its centre. */
static const struct aabb OBJECT_BOX = {{0.5, -0.25, -1.0}, {1.5, 0.75, 0.2}};

/* The sampled times in the shutter (besides its two ends), and random points of the object per time. */
#define SAMPLED_TIMES 10000
#define POINTS_PER_TIME 4

/* How loose the motion box may be. Its contract pads the boxes at the sampled times by at most
 * MOTION_BOX_PAD_FRACTION of the object's size in the world (largest |scale| times its radius about its
 * origin) while the steps are below MOTION_BOX_STEPS_MAX: so each side of the box lies at most that far
 * beyond the hull of the corners sampled at 10,000 times and the keys' (and a hair for rounding). As a
 * factor, the box's extent on each axis is at most LOOSENESS_MAX times the hull's (measured: 1.06 for
 * the translation, 1.10 to 1.12 for the turns and the mix, 1.36 for the scale, whose y extent shrinks
 * to half while the padding follows the largest scale, 3). */
#define LOOSENESS_MAX 1.4
#define PAD_ROUNDING 1e-9

/* Returns where the object's point p is at `time`, as the renderer computes it. */
static vec3 place(const struct keyframe *keys, size_t count, double time, vec3 p) {
    struct pose pose = keyframes_pose_at(keys, count, time);
    struct transform t = transform_from_pose(pose.scale, pose.rotate, pose.translate);
    return transform_point(&t, p);
}

static vec3 corner(struct aabb b, int k) {
    return vec3_make(k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y, k & 4 ? b.max.z : b.min.z);
}

static double largest_component(vec3 a) { return fmax(a.x, fmax(a.y, a.z)); }

static bool holds_point(struct aabb b, vec3 p) {
    return b.min.x <= p.x && p.x <= b.max.x && b.min.y <= p.y && p.y <= b.max.y && b.min.z <= p.z && p.z <= b.max.z;
}

/* Returns the k-th sampled time of [t0, t1]: the two ends first, then uniform random times. */
static double sampled_time(uint32_t k, double t0, double t1) {
    return k == 0 ? t0 : k == 1 ? t1 : uniform(41, k, t0, t1);
}

/* Returns the object's largest size in the world over the keys: largest |scale| times OBJECT_BOX's
 * radius about the origin. */
static double object_size(const struct keyframe *keys, size_t count) {
    double largest = 0;
    for (size_t k = 0; k < count; k++) {
        vec3 s = keys[k].pose.scale;
        largest = fmax(largest, fmax(fabs(s.x), fmax(fabs(s.y), fabs(s.z))));
    }
    vec3 far = vec3_max(vec3_neg(OBJECT_BOX.min), OBJECT_BOX.max); /* its farthest corner's coordinates */
    return largest * vec3_length(far);
}

/* Expects every corner and random point of OBJECT_BOX at SAMPLED_TIMES times in [t0, t1] to lie in the
 * motion box, and the box to be at most `looseness_max` times the sampled corners' hull on each axis; and
 * unless the motion is too fast to sample (past MOTION_BOX_STEPS_MAX), each side at most
 * MOTION_BOX_PAD_FRACTION of the object's size beyond it. */
static void expect_motion_held_within(const char *what, const struct keyframe *keys, size_t count, double t0,
                                      double t1, double looseness_max, bool too_fast_to_sample) {
    struct aabb box = keyframes_motion_box(keys, count, OBJECT_BOX, t0, t1);
    struct aabb hull = aabb_empty();
    for (uint32_t k = 0; k < SAMPLED_TIMES + 2 + count; k++) { /* and the keys' times, where the motion bends */
        double time = k < SAMPLED_TIMES + 2 ? sampled_time(k, t0, t1)
                                            : fmin(t1, fmax(t0, keys[k - SAMPLED_TIMES - 2].time));
        for (int c = 0; c < 8 + POINTS_PER_TIME; c++) {
            vec3 p = c < 8 ? corner(OBJECT_BOX, c)
                           : vec3_make(uniform(42, 4 * k + c, OBJECT_BOX.min.x, OBJECT_BOX.max.x),
                                       uniform(43, 4 * k + c, OBJECT_BOX.min.y, OBJECT_BOX.max.y),
                                       uniform(44, 4 * k + c, OBJECT_BOX.min.z, OBJECT_BOX.max.z));
            vec3 q = place(keys, count, time, p);
            cr_assert(holds_point(box, q), "%s: time %.17g, point %d at (%g %g %g) is outside the motion box", what,
                      time, c, q.x, q.y, q.z);
            if (c < 8)
                hull = aabb_grow(hull, q);
        }
    }
    vec3 extent = vec3_sub(box.max, box.min), sampled = vec3_sub(hull.max, hull.min);
    double looseness = fmax(extent.x / sampled.x, fmax(extent.y / sampled.y, extent.z / sampled.z));
    cr_log_info("%s: the motion box is %.4f times the sampled hull at most", what, looseness);
    cr_expect(looseness <= looseness_max, "%s: the motion box is %.3f times the sampled hull on some axis", what,
              looseness);
    double beyond =
        fmax(largest_component(vec3_sub(hull.min, box.min)), largest_component(vec3_sub(box.max, hull.max)));
    double allowed = MOTION_BOX_PAD_FRACTION * object_size(keys, count) * (1 + PAD_ROUNDING);
    cr_log_info("%s: %.4f beyond the sampled hull, %.4f allowed", what, beyond, allowed);
    cr_expect(too_fast_to_sample || beyond <= allowed, "%s: a side %g beyond the sampled hull, more than %g", what,
              beyond, allowed);
}

static void expect_motion_held(const char *what, const struct keyframe *keys, size_t count, double t0, double t1) {
    expect_motion_held_within(what, keys, count, t0, t1, LOOSENESS_MAX, false);
}

#define STILL_SCALE {1, 1, 1}
#define NO_TURN {0, 0, 0}
#define ORIGIN {0, 0, 0}

Test(motion_box, holds_a_translation) {
    struct keyframe keys[] = {{0, {STILL_SCALE, NO_TURN, ORIGIN}}, {1, {STILL_SCALE, NO_TURN, {3, -1, 2}}}};
    expect_motion_held("translation", keys, 2, 0, 1);
}

Test(motion_box, holds_a_rotation_about_each_axis) {
    struct keyframe about_x[] = {{0, {STILL_SCALE, NO_TURN, ORIGIN}}, {1, {STILL_SCALE, {90, 0, 0}, ORIGIN}}};
    struct keyframe about_y[] = {{0, {STILL_SCALE, {0, -30, 0}, ORIGIN}}, {1, {STILL_SCALE, {0, 200, 0}, ORIGIN}}};
    struct keyframe about_z[] = {{0, {STILL_SCALE, NO_TURN, ORIGIN}}, {1, {STILL_SCALE, {0, 0, 180}, ORIGIN}}};
    expect_motion_held("rotation about x", about_x, 2, 0, 1);
    expect_motion_held("rotation about y", about_y, 2, 0, 1);
    expect_motion_held("rotation about z", about_z, 2, 0, 1);
}

Test(motion_box, holds_a_scale) {
    struct keyframe keys[] = {{0, {STILL_SCALE, NO_TURN, ORIGIN}}, {1, {{2, 0.5, 3}, NO_TURN, ORIGIN}}};
    expect_motion_held("scale", keys, 2, 0, 1);
}

Test(motion_box, holds_a_mix_over_several_keys_and_held_ends) {
    struct keyframe keys[] = {
        {0.3, {{1, 1, 1}, {0, 0, 0}, {0, 0, 0}}},
        {0.5, {{2, 0.5, 1}, {45, 10, -30}, {1, 2, 0}}},
        {0.7, {{0.5, 1.5, 2}, {90, 120, 0}, {-1, 0, 3}}},
    };
    expect_motion_held("mix, shutter over every key and past both ends", keys, 3, 0.1, 1.0);
    expect_motion_held("mix, shutter within one stretch", keys, 3, 0.55, 0.65);
    expect_motion_held("mix, shutter across a key", keys, 3, 0.45, 0.6);
}

/* Faster than MOTION_BOX_STEPS_MAX steps can follow: the box of the translation's path plus the box of
 * the turning alone, or, turning too fast too, the object's size (1.95: OBJECT_BOX's farthest corner
 * from the origin) about the path. */
Test(motion_box, holds_motion_too_fast_to_sample_by_taking_the_translation_apart) {
    struct keyframe spin[] = {{0, {STILL_SCALE, NO_TURN, {5, 0, 0}}}, {1, {STILL_SCALE, {0, 0, 7200}, {5, 0, 0}}}};
    /* twenty turns about z: 3.9 wide on every axis, against 3.36 across x and y and 1.2 along z turned */
    expect_motion_held_within("twenty turns", spin, 2, 0, 1, 3.3, true);
    struct aabb box = keyframes_motion_box(spin, 2, OBJECT_BOX, 0, 1);
    double size = object_size(spin, 2);
    cr_expect(box.min.x <= 5 - size && box.min.x > 5 - size - 1e-10 && box.max.z < size + 1e-10,
              "x from %.17g, z up to %.17g: not the path padded by the size %.17g", box.min.x, box.max.z, size);
    /* a long throw, forty sizes along x while turning 30 degrees: the path's box plus the turn's */
    struct keyframe throw[] = {{0, {STILL_SCALE, NO_TURN, ORIGIN}}, {1, {STILL_SCALE, {0, 0, 30}, {80, 0, 0}}}};
    expect_motion_held_within("a long throw", throw, 2, 0, 1, 1.1, true);
}

Test(motion_box, an_instant_is_the_box_at_that_time_and_an_empty_object_is_empty) {
    struct keyframe keys[] = {{0, {STILL_SCALE, NO_TURN, ORIGIN}}, {1, {{2, 2, 2}, {0, 0, 90}, {1, 1, 1}}}};
    struct aabb instant = keyframes_motion_box(keys, 2, OBJECT_BOX, 0.5, 0.5);
    struct pose p = keyframes_pose_at(keys, 2, 0.5);
    struct transform t = transform_from_pose(p.scale, p.rotate, p.translate);
    struct aabb expected = transform_box(&t, OBJECT_BOX);
    cr_expect(same_vec3(instant.min, expected.min) && same_vec3(instant.max, expected.max));
    struct aabb empty = keyframes_motion_box(keys, 2, aabb_empty(), 0, 1);
    cr_expect(empty.min.x > empty.max.x);
}

/* The classic mistake (a gallery fault of the chapter): a box joining only the object's boxes at the
 * shutter's ends. A cube turning a quarter turn is the same box at both ends, and its corners sweep
 * out beyond that box in between; the rule of keyframes_motion_box is needed. */
Test(motion_box, a_box_from_the_end_positions_only_misses_a_turning_objects_middle) {
    struct aabb cube = {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};
    struct keyframe keys[] = {{0, {STILL_SCALE, NO_TURN, ORIGIN}}, {1, {STILL_SCALE, {0, 0, 90}, ORIGIN}}};
    struct transform at_start = transform_from_pose(keys[0].pose.scale, keys[0].pose.rotate, keys[0].pose.translate);
    struct transform at_end = transform_from_pose(keys[1].pose.scale, keys[1].pose.rotate, keys[1].pose.translate);
    struct aabb ends_only = aabb_union(transform_box(&at_start, cube), transform_box(&at_end, cube));
    struct aabb motion = keyframes_motion_box(keys, 2, cube, 0, 1);
    int missed = 0;
    for (uint32_t k = 0; k < SAMPLED_TIMES; k++) {
        double time = uniform(45, k, 0, 1);
        for (int c = 0; c < 8; c++) {
            vec3 q = place(keys, 2, time, corner(cube, c));
            missed += !holds_point(ends_only, q);
            cr_assert(holds_point(motion, q), "time %.17g corner %d", time, c);
        }
    }
    cr_log_info("the end-positions box missed %d of %d sampled corners", missed, 8 * SAMPLED_TIMES);
    cr_expect(missed > SAMPLED_TIMES, "the end-positions box missed only %d sampled corners", missed);
    cr_expect(motion.max.x >= sqrt(0.5) && motion.max.y >= sqrt(0.5), "the motion box reaches the diagonal");
}

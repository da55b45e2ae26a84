/* keyframes.c: an instance's pose over time, and the box that holds it over a shutter (chapter 16).
 *
 * The motion box is the one place where "a box for every time in an interval" has to be true for
 * infinitely many times; keyframes.h's contract says how a finite number of samples makes it so. */
#include "keyframes.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>

#include "transform.h"

#define RADIANS_PER_DEGREE (M_PI / 180.0)

/* Returns a + f (b - a) for each of the nine numbers. */
static struct pose pose_between(const struct pose *a, const struct pose *b, double f) {
    return (struct pose){vec3_add_scaled(a->scale, vec3_sub(b->scale, a->scale), f),
                         vec3_add_scaled(a->rotate, vec3_sub(b->rotate, a->rotate), f),
                         vec3_add_scaled(a->translate, vec3_sub(b->translate, a->translate), f)};
}

struct pose keyframes_pose_at(const struct keyframe *keys, size_t count, double time) {
    if (!(time > keys[0].time)) /* NaN holds the first pose too */
        return keys[0].pose;
    if (time >= keys[count - 1].time)
        return keys[count - 1].pose;
    /* Binary search for the last key at or before `time`: keys[low].time <= time < keys[high].time. */
    size_t low = 0, high = count - 1;
    while (high - low > 1) {
        size_t middle = low + (high - low) / 2;
        if (keys[middle].time <= time)
            low = middle;
        else
            high = middle;
    }
    if (time == keys[low].time)
        return keys[low].pose;
    double f = (time - keys[low].time) / (keys[high].time - keys[low].time);
    return pose_between(&keys[low].pose, &keys[high].pose, f);
}

/* Returns the box of the object box placed by the pose at `time`, or by that pose without its
 * translation when `translated` is false. */
static struct aabb box_at(const struct keyframe *keys, size_t count, struct aabb object_box, double time,
                          bool translated) {
    struct pose p = keyframes_pose_at(keys, count, time);
    struct transform t = transform_from_pose(p.scale, p.rotate, translated ? p.translate : vec3_make(0, 0, 0));
    return transform_box(&t, object_box);
}

static double largest_abs(vec3 v) { return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))); }
static double sum_abs(vec3 v) { return fabs(v.x) + fabs(v.y) + fabs(v.z); }

/* Returns the radius of box about the origin: the distance of its farthest corner. */
static double radius_about_origin(struct aabb box) {
    return vec3_length(vec3_max(vec3_make(fabs(box.min.x), fabs(box.min.y), fabs(box.min.z)),
                                vec3_make(fabs(box.max.x), fabs(box.max.y), fabs(box.max.z))));
}

/* Returns the union of box_at at steps + 1 evenly spaced times from start to end. */
static struct aabb sampled_box(const struct keyframe *keys, size_t count, struct aabb object_box, double start,
                               double end, int steps, bool translated) {
    struct aabb box = aabb_empty();
    for (int k = 0; k <= steps; k++)
        box = aabb_union(box, box_at(keys, count, object_box, k == steps ? end : start + k * ((end - start) / steps),
                                     translated));
    return box;
}

/* Returns how many steps over `duration` keep half a step's movement at `speed` within
 * MOTION_BOX_PAD_FRACTION of `size`: at least 1; more than MOTION_BOX_STEPS_MAX means too many. */
static double steps_for(double speed, double duration, double size) {
    double steps = size > 0.0 ? ceil(speed * duration / (2.0 * MOTION_BOX_PAD_FRACTION * size)) : 1.0;
    return steps >= 1.0 ? steps : 1.0;
}

/* Returns the box of the object over [start, end] (start < end), during which the pose moves linearly
 * from `from` to `to` (the same pose for a stretch that holds), `radius` being the object box's radius
 * about its origin. keyframes.h gives the reasoning. */
/* TASK 16.3: the box of a moving object over a stretch of the shutter */
static struct aabb stretch_box(const struct keyframe *keys, size_t count, struct aabb object_box, double radius,
                               const struct pose *from, const struct pose *to, double from_time, double to_time,
                               double start, double end) {
    /* The rates of the nine numbers per unit of time (zero while the pose holds). */
    double duration = to_time - from_time;
    struct pose rate = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    if (duration > 0.0)
        rate = (struct pose){vec3_scale(vec3_sub(to->scale, from->scale), 1.0 / duration),
                             vec3_scale(vec3_sub(to->rotate, from->rotate), 1.0 / duration),
                             vec3_scale(vec3_sub(to->translate, from->translate), 1.0 / duration)};
    /* Linear motion takes each number's extremes at the ends of the stretch. */
    double largest_scale = fmax(largest_abs(from->scale), largest_abs(to->scale));
    double size = largest_scale * radius; /* the object's radius in the world */
    double moving = vec3_length(rate.translate); /* the speed the translation gives every point */
    double turning = sum_abs(rate.rotate) * RADIANS_PER_DEGREE * size + largest_abs(rate.scale) * radius;
    double angles = fmax(sum_abs(from->rotate), sum_abs(to->rotate)) * RADIANS_PER_DEGREE;
    double translation = fmax(vec3_length(from->translate), vec3_length(to->translate));
    double rounding = MOTION_BOX_ROUNDING * DBL_EPSILON * (translation + (1.0 + angles) * size);

    double steps = steps_for(moving + turning, end - start, size);
    if (steps <= MOTION_BOX_STEPS_MAX) {
        struct aabb box = sampled_box(keys, count, object_box, start, end, (int)steps, true);
        return aabb_pad(box, (moving + turning) * ((end - start) / steps) / 2.0 + rounding);
    }
    /* Too fast to follow so: the translation apart. A point is its translation (on a line, inside the
     * box of the path's ends) plus the object turned and scaled (inside the box of that motion alone,
     * sampled as above, or, turning too fast for that as well, within `size` of the origin), so it is
     * inside the sum of the two boxes. */
    struct pose a = keyframes_pose_at(keys, count, start), b = keyframes_pose_at(keys, count, end);
    struct aabb path = aabb_grow(aabb_grow(aabb_empty(), a.translate), b.translate);
    struct aabb turned = {{-size, -size, -size}, {size, size, size}};
    steps = steps_for(turning, end - start, size);
    if (steps <= MOTION_BOX_STEPS_MAX)
        turned = aabb_pad(sampled_box(keys, count, object_box, start, end, (int)steps, false),
                          turning * ((end - start) / steps) / 2.0);
    struct aabb sum = {vec3_add(path.min, turned.min), vec3_add(path.max, turned.max)};
    return aabb_pad(sum, rounding);
}

struct aabb keyframes_motion_box(const struct keyframe *keys, size_t count, struct aabb object_box, double t0,
                                 double t1) {
    if (!(object_box.min.x <= object_box.max.x && object_box.min.y <= object_box.max.y &&
          object_box.min.z <= object_box.max.z))
        return aabb_empty();
    double radius = radius_about_origin(object_box);
    struct aabb box = box_at(keys, count, object_box, t0, true);
    /* The clock in count + 1 stretches: before the first key (held), between each two keys (linear),
     * after the last (held). Each one's part of [t0, t1] that is longer than an instant adds its box. */
    for (size_t k = 0; k <= count; k++) {
        const struct keyframe *before = &keys[k == 0 ? 0 : k - 1], *after = &keys[k == count ? count - 1 : k];
        double start = k == 0 ? t0 : fmax(t0, before->time);
        double end = k == count ? t1 : fmin(t1, after->time);
        if (start < end)
            box = aabb_union(box, stretch_box(keys, count, object_box, radius, &before->pose, &after->pose,
                                              before->time, after->time, start, end));
    }
    return box;
}

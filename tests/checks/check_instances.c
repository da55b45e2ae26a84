/* check_instances.c: the coursework checks of chapter 16: a ray carried into an instance and its hit
 * carried back, on a stretched slope whose hits are worked out by hand, and the box that holds a moving
 * object over the shutter, on motions whose every position the check computes itself (the coursework
 * kit). */
#include <math.h>
#include <stdio.h>
#include <sys/stat.h>

#include "check.h"
#include "hit.h"
#include "instance_bvh.h"
#include "instances.h"
#include "keyframes.h"
#include "scene.h"
#include "transform.h"
#include "world.h"

/* Hits are compared with their exact values within this: far above rounding, far below a mistake. */
#define INSTANCE_TOLERANCE 1e-9

/* ---- 16.1 the ray's journey: into object space and back --------------------------------------- */

/* The object: a rectangle of two triangles in the plane x + y = 1 (x from 0 to 1, z from -1 to 1), its
 * normal along (1, 1, 0). */
#define SLOPE_FILE "out/check/slope.obj"
static const char slope_obj[] = "v 1 0 -1\nv 0 1 -1\nv 0 1 1\nv 1 0 1\nf 1 2 3\nf 1 3 4\n";

/* The nearest hit of ray r in a world holding one instance of the slope placed by `placement` (the
 * instance line's keys). False with the reason in why when the check's own scene cannot be made. */
static bool instance_hit(const char *placement, ray r, struct hit *h, bool *found, char *why, size_t why_size) {
    mkdir("out", 0777); /* make check-N makes them; the grader run by hand may not have */
    mkdir("out/check", 0777);
    FILE *f = fopen(SLOPE_FILE, "w");
    if (f == NULL || fputs(slope_obj, f) == EOF || fclose(f) != 0) {
        snprintf(why, why_size, "cannot write the check's mesh %s (a framework problem, not your task)", SLOPE_FILE);
        return false;
    }
    static const struct shape_kind *const kinds[] = {NULL};
    char text[512], err[512];
    snprintf(text, sizeof text, "camera eye 0 0 5  target 0 0 0  fov 40\nimage 8 8\nobject slope %s\n"
             "instance slope %s\n", SLOPE_FILE, placement);
    struct scene s;
    struct world w;
    if (!check_scene_world(text, kinds, &s, &w, why, why_size))
        return false;
    struct instances *in = instances_create(&s, world_mesh_object_number(&s, s.mesh_count), 0, 0, err, sizeof err);
    if (in == NULL) {
        snprintf(why, why_size, "instances_create failed: %s", err);
        world_free(&w);
        scene_free(&s);
        return false;
    }
    w.instances = &in->hook;
    *h = hit_nothing(INFINITY);
    char text_ray[160];
    check_calling("closest_in_instance", "%s, an instance of a slope placed by `%s`", check_ray_text(&r, text_ray),
                  placement);
    *found = world_closest(&w, &r, 0, h);
    instances_free(in);
    world_free(&w);
    scene_free(&s);
    return true;
}

/* Checks one ray against the slope stretched 4 times along x: the world plane x / 4 + y = 1, whose
 * normal is along (1/4, 1, 0) (the inverse transpose of the stretch times (1, 1, 0)), not along (4, 1,
 * 0) (the stretch itself times it). */
static bool stretched_slope_hit(ray r, double expected_t, const char *what, char *why, size_t why_size) {
    struct hit h;
    bool found;
    if (!instance_hit("scale 4 1 1", r, &h, &found, why, why_size))
        return false;
    char rt[160], n[64];
    if (!found) {
        snprintf(why, why_size, "%s, %s: no hit; expected one at t = %g", what, check_ray_text(&r, rt), expected_t);
        return false;
    }
    if (!check_near(h.t, expected_t, INSTANCE_TOLERANCE)) {
        double object_length = vec3_length(vec3_make(r.direction.x / 4, r.direction.y, r.direction.z));
        snprintf(why, why_size, "%s, %s: the hit is at t = %g in the world, where the stretched slope is; your code "
                 "returned t = %.6g%s", what, check_ray_text(&r, rt), expected_t, h.t,
                 check_near(h.t * object_length, expected_t * object_length * object_length, 1e-6) ||
                         check_near(h.t, expected_t * object_length, 1e-6)
                     ? ": a distance in object space? Carry the direction without normalising it, and t is the same "
                       "in both spaces"
                     : "");
        return false;
    }
    vec3 right = vec3_normalize(vec3_make(0.25, 1, 0)), wrong = vec3_normalize(vec3_make(4, 1, 0));
    if (!check_near(fabs(vec3_dot(h.normal, right)), 1, INSTANCE_TOLERANCE) ||
        !check_near(vec3_length(h.normal), 1, INSTANCE_TOLERANCE)) {
        snprintf(why, why_size, "%s, %s: the stretched slope's unit normal is along (0.2425, 0.9701, 0), the inverse "
                 "transpose of the stretch times the object's (1, 1, 0); your code gave %s%s", what,
                 check_ray_text(&r, rt), check_vec_text(h.normal, n),
                 check_near(fabs(vec3_dot(h.normal, wrong)), 1, 1e-6)
                     ? ": the normal carried by the transform itself, which leans it the wrong way when the scale "
                       "differs per axis"
                 : !check_near(vec3_length(h.normal), 1, 1e-6) ? ": not of unit length" : "");
        return false;
    }
    return true;
}

CHECK(check_instance_distance) {
    /* Along x, the stretch shrinks the direction to a quarter in object space: the hit at x = 2 of the
     * world is 8 from x = 10, and 2 in object space if the direction were made unit length there. */
    return stretched_slope_hit((ray){{10, 0.5, 0.1}, {-1, 0, 0}}, 8, "a ray along the stretch", why, why_size);
}

CHECK(check_instance_normal) {
    /* Straight down onto the plane x / 4 + y = 1 at x = 0.8: y = 0.8, 4.2 below y = 5. */
    return stretched_slope_hit((ray){{0.8, 5, -0.3}, {0, -1, 0}}, 4.2, "a ray straight down", why, why_size) &&
           stretched_slope_hit((ray){{3, 3, 0.5}, vec3_normalize(vec3_make(-1, -1, 0))}, 2.2 * M_SQRT2,
                               "a ray at 45 degrees", why, why_size);
}

/* ---- 16.2 refitting the top level -------------------------------------------------------------- */

/* Instances in the refit checks: a row of 32 unit boxes along x, 2 apart, which then move. */
#define ROW_INSTANCES 32

static struct aabb unit_box_at(double x, double y, double z) {
    return (struct aabb){{x - 0.5, y - 0.5, z - 0.5}, {x + 0.5, y + 0.5, z + 0.5}};
}

/* The walk's callback: notes which instances the ray reached. */
static bool note_reached(void *context, size_t index, double t_min, double *t_max) {
    (void)t_min;
    (void)t_max;
    bool *reached = context;
    if (index < ROW_INSTANCES)
        reached[index] = true;
    return true;
}

/* Builds the tree over the row, moves the boxes by `move` (instance k to move(k)) and refits; the new
 * boxes in `moved`. NULL with the reason in why when the build fails. */
static struct instance_bvh *refitted_row(struct aabb (*move)(int), struct aabb moved[ROW_INSTANCES], char *why,
                                         size_t why_size) {
    struct aabb boxes[ROW_INSTANCES];
    for (int k = 0; k < ROW_INSTANCES; k++)
        boxes[k] = unit_box_at(2.0 * k, 0, 0);
    char err[256];
    struct instance_bvh *b = instance_bvh_build(boxes, ROW_INSTANCES, err, sizeof err);
    if (b == NULL) {
        snprintf(why, why_size, "instance_bvh_build failed (a framework problem, not your task): %s", err);
        return NULL;
    }
    for (int k = 0; k < ROW_INSTANCES; k++)
        moved[k] = move(k);
    check_calling("instance_bvh_refit", "a tree over %d unit boxes in a row, after they moved", ROW_INSTANCES);
    instance_bvh_refit(b, moved);
    return b;
}

/* Every box rises by its own amount, and instance 5 jumps far away: boxes grow and move, and a parent
 * of instance 5 must reach out to it. */
static struct aabb rise(int k) { return k == 5 ? unit_box_at(40, 30, -20) : unit_box_at(2.0 * k, 0.25 * k, 0); }

/* Every box moves up by 3 together. */
static struct aabb lift_all(int k) { return unit_box_at(2.0 * k, 3, 0); }

CHECK(check_refit_holds_the_moved_boxes) {
    struct aabb moved[ROW_INSTANCES];
    struct instance_bvh *b = refitted_row(rise, moved, why, why_size);
    if (b == NULL)
        return false;
    char fault[512];
    bool valid = instance_bvh_is_valid(b, moved, ROW_INSTANCES, fault, sizeof fault);
    if (!valid)
        snprintf(why, why_size, "32 unit boxes in a row, each then risen by a quarter of its number and instance 5 "
                 "moved far away to (40, 30, -20): after instance_bvh_refit the structure checker says: %s%s", fault,
                 b->node_count > 0 && !aabb_holds(&b->nodes[0].box, &moved[5])
                     ? " (the root's box does not hold instance 5's new box: is every interior node's box recomputed "
                       "from its children, after they have theirs?)" : "");
    instance_bvh_free(b);
    return valid;
}

CHECK(check_refit_finds_every_instance) {
    struct aabb moved[ROW_INSTANCES];
    struct instance_bvh *b = refitted_row(rise, moved, why, why_size);
    if (b == NULL)
        return false;
    for (int k = 0; k < ROW_INSTANCES; k++) {
        /* A ray straight down through the middle of instance k's new box. */
        vec3 centre = vec3_scale(vec3_add(moved[k].min, moved[k].max), 0.5);
        ray r = {vec3_make(centre.x, centre.y + 100, centre.z), vec3_make(0, -1, 0)};
        bool reached[ROW_INSTANCES] = {false};
        double t_max = INFINITY;
        instance_bvh_walk(b, &r, 0, &t_max, note_reached, reached);
        if (!reached[k]) {
            char rt[160];
            snprintf(why, why_size, "after the row moved (instance 5 far away) and instance_bvh_refit, a walk along %s, "
                     "straight through instance %d's new box, never reached instance %d: a node above it kept a box "
                     "that no longer holds it", check_ray_text(&r, rt), k, k);
            instance_bvh_free(b);
            return false;
        }
    }
    instance_bvh_free(b);
    return true;
}

CHECK(check_refit_keeps_the_tree) {
    struct aabb moved[ROW_INSTANCES];
    struct aabb boxes[ROW_INSTANCES];
    for (int k = 0; k < ROW_INSTANCES; k++)
        boxes[k] = unit_box_at(2.0 * k, 0, 0);
    char err[256];
    struct instance_bvh *before = instance_bvh_build(boxes, ROW_INSTANCES, err, sizeof err);
    struct instance_bvh *b = refitted_row(lift_all, moved, why, why_size);
    if (before == NULL || b == NULL) {
        instance_bvh_free(before);
        instance_bvh_free(b);
        return false;
    }
    bool same = before->node_count == b->node_count;
    for (size_t n = 0; same && n < b->node_count; n++) {
        const struct instance_bvh_node *x = &before->nodes[n], *y = &b->nodes[n];
        same = x->left == y->left && x->right == y->right && x->first == y->first && x->count == y->count;
        /* Moved up by 3 together: each box is the old one moved by 3, exactly. */
        vec3 up = {0, 3, 0};
        same = same && vec3_length(vec3_sub(y->box.min, vec3_add(x->box.min, up))) == 0 &&
               vec3_length(vec3_sub(y->box.max, vec3_add(x->box.max, up))) == 0;
    }
    for (size_t i = 0; same && i < b->instance_count; i++)
        same = before->instances[i] == b->instances[i];
    if (!same)
        snprintf(why, why_size, "32 unit boxes in a row all moved up by 3 together: a refit keeps the tree's nodes and "
                 "the order of its instances as they were, and every node's box is its old one moved up by 3, "
                 "exactly; yours changed the tree or its boxes differ%s",
                 before->node_count != b->node_count ? " (another number of nodes: rebuilt?)" : "");
    instance_bvh_free(before);
    instance_bvh_free(b);
    return same;
}

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

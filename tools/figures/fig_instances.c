/* fig_instances.c: chapter 16's figures: the two levels of an instanced scene and a ray's journey from
 * the world into one instance's object space and back (with the normal carried by the inverse transpose,
 * and by the matrix for contrast), computed with transform_from_pose, transform_invert, transform_point,
 * transform_vector, transform_normal and transform_box; and the box of a turning object over the
 * shutter, from its end positions alone and from keyframes_motion_box. */
#include <math.h>
#include <stdio.h>

#include "figures.h"
#include "keyframes.h"
#include "svg.h"
#include "transform.h"

/* ---- the object: a tree in its own space, two parts, each a leaf of its bottom-level BVH ---------- */

#define TRUNK_CORNERS 4
#define CROWN_CORNERS 3

static const svg_point trunk[TRUNK_CORNERS] = {{-0.15, 0}, {0.15, 0}, {0.15, 0.6}, {-0.15, 0.6}};
static const svg_point crown[CROWN_CORNERS] = {{-0.6, 0.6}, {0.6, 0.6}, {0, 1.8}};

static vec3 lift(svg_point p) { return vec3_make(p.x, p.y, 0); }
static svg_point flat(vec3 p) { return (svg_point){p.x, p.y}; }

static struct aabb outline_box(const svg_point *p, int n) {
    struct aabb box = aabb_empty();
    for (int k = 0; k < n; k++)
        box = aabb_grow(box, lift(p[k]));
    return box;
}

/* Draws the outline p (n corners) carried by t. */
static void draw_outline(struct svg *s, const struct transform *t, const svg_point *p, int n, enum svg_colour colour,
                         double fill) {
    svg_point carried[TRUNK_CORNERS];
    for (int k = 0; k < n; k++)
        carried[k] = flat(transform_point(t, lift(p[k])));
    svg_polygon(s, carried, n, true, colour, SVG_SOLID, fill);
}

static void draw_tree(struct svg *s, const struct transform *t, double fill) {
    draw_outline(s, t, trunk, TRUNK_CORNERS, SVG_SURFACE, fill);
    draw_outline(s, t, crown, CROWN_CORNERS, SVG_SURFACE, fill);
}

/* The nearest crossing of the ray origin + t d (t > 0) with the outline's edges; false when none. Stores
 * the parameter and the edge's outward normal (the outlines run counter-clockwise). */
static bool outline_crossing(const svg_point *p, int n, vec3 origin, vec3 d, double *t_hit, vec3 *normal) {
    bool found = false;
    for (int k = 0; k < n; k++) {
        svg_point a = p[k], b = p[(k + 1) % n], e = svg_minus(b, a);
        double det = d.x * -e.y - d.y * -e.x;
        if (det == 0)
            continue;
        double ax = a.x - origin.x, ay = a.y - origin.y;
        double t = (ax * -e.y - ay * -e.x) / det, u = (d.x * ay - d.y * ax) / det;
        if (t > 0 && u >= 0 && u <= 1 && (!found || t < *t_hit)) {
            found = true;
            *t_hit = t;
            *normal = vec3_normalize(vec3_make(e.y, -e.x, 0));
        }
    }
    return found;
}

/* ---- the two levels and the ray's journey ------------------------------------------------------ */

#define INSTANCES 3
#define SHOWN 1 /* the instance the ray hits, drawn again in object space */

void figure_instances(FILE *out) {
    const vec3 scales[INSTANCES] = {{0.8, 0.8, 1}, {1.6, 0.9, 1}, {0.9, 1.3, 1}};
    const double turns[INSTANCES] = {10, 25, -15};
    const vec3 places[INSTANCES] = {{0.9, 0.2, 0}, {3.2, 0.1, 0}, {5.6, 0.4, 0}};
    struct transform to_world[INSTANCES], to_object[INSTANCES];
    struct aabb object_box = aabb_union(outline_box(trunk, TRUNK_CORNERS), outline_box(crown, CROWN_CORNERS));
    struct aabb world_box[INSTANCES], all = aabb_empty();
    for (int k = 0; k < INSTANCES; k++) {
        to_world[k] = transform_from_pose(scales[k], vec3_make(0, 0, turns[k]), places[k]);
        if (!transform_invert(&to_world[k], &to_object[k])) {
            fprintf(stderr, "figure_instances: instance %d has no inverse\n", k);
            return;
        }
        world_box[k] = transform_box(&to_world[k], object_box);
        all = aabb_union(all, world_box[k]);
    }
    struct svg s;
    svg_begin(&s, out, 900, 470, "Chapter 16: two levels of boxes, and a ray carried into an instance's object space and back");

    /* Left: the world. The top level's leaves are the instances' world boxes, under one root. */
    svg_view(&s, 0, 0, 40, 360, 64);
    svg_text_px(&s, 245, 24, "middle", SVG_INK, "the world: one object placed three times");
    svg_line(&s, (svg_point){-0.4, 0}, (svg_point){6.8, 0}, SVG_MUTED, SVG_THIN);
    svg_rect(&s, flat(all.min), flat(all.max), SVG_INK, SVG_DASHED, 0);
    svg_text(&s, (svg_point){all.min.x, all.max.y}, 4, -6, "start", SVG_INK, "top level: the root's box");
    for (int k = 0; k < INSTANCES; k++) {
        draw_tree(&s, &to_world[k], 0.25);
        svg_rect(&s, flat(world_box[k].min), flat(world_box[k].max), SVG_ACCENT, SVG_THIN, 0.06);
    }
    svg_text(&s, (svg_point){world_box[0].min.x, world_box[0].min.y}, 0, 16, "start", SVG_ACCENT, "instance boxes");
    ray world_ray = {vec3_make(-0.3, 2.1, 0), vec3_normalize(vec3_make(1, -0.3, 0))};

    /* The ray carried into the shown instance's space: the inverse moves the origin and turns and
     * stretches the direction, which is not made unit length again, so t means the same point in both. */
    vec3 object_origin = transform_point(&to_object[SHOWN], world_ray.origin);
    vec3 object_direction = transform_vector(&to_object[SHOWN], world_ray.direction);
    double t_hit = 0;
    vec3 object_normal = {0, 0, 0}, normal_b;
    double t_crown = INFINITY, t_trunk = INFINITY;
    if (outline_crossing(crown, CROWN_CORNERS, object_origin, object_direction, &t_crown, &object_normal))
        t_hit = t_crown;
    if (outline_crossing(trunk, TRUNK_CORNERS, object_origin, object_direction, &t_trunk, &normal_b) && t_trunk < t_crown) {
        t_hit = t_trunk;
        object_normal = normal_b;
    }
    vec3 world_hit = ray_at(world_ray, t_hit), object_hit = vec3_add_scaled(object_origin, object_direction, t_hit);
    vec3 right_normal = vec3_normalize(transform_normal(&to_object[SHOWN], object_normal));
    vec3 wrong_normal = vec3_normalize(transform_vector(&to_world[SHOWN], object_normal));
    svg_line(&s, flat(world_ray.origin), flat(world_hit), SVG_RAY, SVG_ARROW);
    svg_line(&s, flat(world_hit), flat(ray_at(world_ray, t_hit + 2.4)), SVG_RAY, SVG_DASHED | SVG_THIN);
    svg_dot(&s, flat(world_hit), SVG_HIT);
    svg_line(&s, flat(world_hit), flat(vec3_add_scaled(world_hit, right_normal, 0.9)), SVG_NORMAL, SVG_ARROW);
    svg_line(&s, flat(world_hit), flat(vec3_add_scaled(world_hit, wrong_normal, 0.9)), SVG_MUTED, SVG_ARROW | SVG_DASHED);
    svg_text(&s, flat(vec3_add_scaled(world_hit, right_normal, 0.9)), 4, -4, "start", SVG_NORMAL, "(M⁻¹)ᵀ n");
    svg_text(&s, flat(vec3_add_scaled(world_hit, wrong_normal, 0.9)), -4, 14, "end", SVG_MUTED, "M n");
    svg_text(&s, flat(world_ray.origin), 0, -8, "start", SVG_RAY, "ray, |d| = 1");
    svg_text_px(&s, 245, 412, "middle", SVG_INK, "the hit at t = %.3f: the same t in both spaces;", t_hit);
    svg_text_px(&s, 245, 432, "middle", SVG_INK, "the normal by (M⁻¹)ᵀ is square to the surface, by M it is not");

    /* Right: the shown instance's object space, the same ray through the inverse, the bottom level's
     * boxes (a leaf per part). */
    svg_view(&s, 0, 0, 700, 400, 150);
    svg_text_px(&s, 700, 24, "middle", SVG_INK, "its object space: the ray through M⁻¹");
    struct transform identity = transform_identity();
    draw_tree(&s, &identity, 0.25);
    svg_rect(&s, flat(object_box.min), flat(object_box.max), SVG_INK, SVG_DASHED, 0);
    struct aabb trunk_box = outline_box(trunk, TRUNK_CORNERS), crown_box = outline_box(crown, CROWN_CORNERS);
    svg_rect(&s, flat(trunk_box.min), flat(trunk_box.max), SVG_ACCENT, SVG_THIN, 0.06);
    svg_rect(&s, flat(crown_box.min), flat(crown_box.max), SVG_ACCENT, SVG_THIN, 0.06);
    svg_text(&s, (svg_point){object_box.max.x, object_box.max.y}, 4, 0, "start", SVG_INK, "bottom level");
    /* Where the carried ray enters the picture: from the edge of the object's box region. */
    double t_show = fmax(0, t_hit - 1.1);
    svg_line(&s, flat(vec3_add_scaled(object_origin, object_direction, t_show)), flat(object_hit), SVG_RAY, SVG_ARROW);
    svg_dot(&s, flat(object_hit), SVG_HIT);
    svg_line(&s, flat(object_hit), flat(vec3_add_scaled(object_hit, object_normal, 0.5)), SVG_NORMAL, SVG_ARROW);
    svg_text(&s, flat(vec3_add_scaled(object_hit, object_normal, 0.5)), 4, -4, "start", SVG_NORMAL, "n");
    svg_text_px(&s, 700, 432, "middle", SVG_INK, "|M⁻¹ d| = %.3f: t is not a distance here", vec3_length(object_direction));
    svg_text_px(&s, 700, 452, "middle", SVG_INK, "scale (%.1f, %.1f), turned %.0f°", scales[SHOWN].x, scales[SHOWN].y,
                turns[SHOWN]);
    svg_end(&s);
}

/* ---- the box of a turning object over the shutter --------------------------------------------- */

#define ARM_TURN 45.0      /* the arm turns from -ARM_TURN to +ARM_TURN degrees about z over the shutter */
#define ARM_GHOSTS 7       /* positions drawn between the ends */

static const svg_point arm[TRUNK_CORNERS] = {{0, -0.12}, {2, -0.12}, {2, 0.12}, {0, 0.12}};

void figure_motion_box(FILE *out) {
    struct keyframe keys[2] = {
        {0.0, {vec3_make(1, 1, 1), vec3_make(0, 0, -ARM_TURN), vec3_make(0, 0, 0)}},
        {1.0, {vec3_make(1, 1, 1), vec3_make(0, 0, ARM_TURN), vec3_make(0, 0, 0)}},
    };
    struct aabb object_box = outline_box(arm, TRUNK_CORNERS);
    object_box.min.z = -0.12; /* a bar, not a flat plate: its depth as wide as its height */
    object_box.max.z = 0.12;
    struct svg s;
    svg_begin(&s, out, 900, 420, "Chapter 16: a turning arm's box over the shutter, from its end positions and from its motion");
    svg_view(&s, 0, 0, 150, 230, 105);
    svg_text_px(&s, 450, 24, "middle", SVG_INK, "an arm turning from %.0f° to +%.0f° about its pivot while the shutter is open",
                -ARM_TURN, ARM_TURN);
    struct aabb ends = aabb_empty(), swept = aabb_empty();
    for (int g = 0; g <= ARM_GHOSTS + 1; g++) {
        double time = (double)g / (ARM_GHOSTS + 1);
        struct pose p = keyframes_pose_at(keys, 2, time);
        struct transform t = transform_from_pose(p.scale, p.rotate, p.translate);
        struct aabb box = transform_box(&t, object_box);
        bool end = g == 0 || g == ARM_GHOSTS + 1;
        draw_outline(&s, &t, arm, TRUNK_CORNERS, end ? SVG_SURFACE : SVG_MUTED, end ? 0.35 : 0.08);
        if (end)
            ends = aabb_union(ends, box);
        swept = aabb_union(swept, box);
    }
    struct aabb motion = keyframes_motion_box(keys, 2, object_box, 0, 1);
    svg_rect(&s, flat(ends.min), flat(ends.max), SVG_LIGHT, SVG_DASHED, 0.05);
    svg_rect(&s, flat(motion.min), flat(motion.max), SVG_ACCENT, SVG_SOLID, 0);
    svg_dot(&s, (svg_point){0, 0}, SVG_INK);
    svg_text(&s, (svg_point){0, 0}, -8, 4, "end", SVG_INK, "pivot");
    /* The tip at mid-shutter, beyond the end positions' box. */
    struct pose middle = keyframes_pose_at(keys, 2, 0.5);
    struct transform mid = transform_from_pose(middle.scale, middle.rotate, middle.translate);
    vec3 tip = transform_point(&mid, vec3_make(2, 0, 0));
    svg_dot(&s, flat(tip), SVG_HIT);
    svg_text(&s, flat(tip), 8, 4, "start", SVG_HIT, "tip at t = 1/2");
    double x = 700;
    svg_text_px(&s, x, 90, "middle", SVG_LIGHT, "dashed: the box of the two end positions,");
    svg_text_px(&s, x, 110, "middle", SVG_LIGHT, "out to x = %.2f", ends.max.x);
    svg_text_px(&s, x, 150, "middle", SVG_ACCENT, "solid: keyframes_motion_box over the shutter,");
    svg_text_px(&s, x, 170, "middle", SVG_ACCENT, "out to x = %.2f", motion.max.x);
    svg_text_px(&s, x, 210, "middle", SVG_INK, "the pose is linear in the angle, so the tip");
    svg_text_px(&s, x, 230, "middle", SVG_INK, "runs on a circle: at x = %.2f at each end,", 2 * cos(ARM_TURN * M_PI / 180));
    svg_text_px(&s, x, 250, "middle", SVG_HIT, "at x = %.2f halfway, %.2f beyond the dashed box", tip.x, tip.x - ends.max.x);
    svg_text_px(&s, x, 290, "middle", SVG_MUTED, "grey: the arm at %d times between the ends;", ARM_GHOSTS);
    svg_text_px(&s, x, 310, "middle", SVG_MUTED, "their boxes reach x = %.2f", swept.max.x);
    svg_end(&s);
}

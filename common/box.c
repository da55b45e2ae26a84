/* box.c: axis-aligned boxes as shapes, by the slab test (chapter 5). */
#include "box.h"

#include "aabb.h"
#include "hit.h"
#include "stats.h"

/* TASK 5.2: the box as a shape: entry or exit */
bool box_intersect(const struct box *b, const ray *r, double t_min, double t_max, double *t) {
    stats_thread.box_tests++;
    struct aabb bounds = {b->min, b->max};
    double t_enter = -INFINITY, t_leave = INFINITY;
    if (!aabb_clip(&bounds, r->origin, aabb_inverse_direction(r->direction), &t_enter, &t_leave))
        return false;
    if (t_enter > t_min && t_enter < t_max) {
        *t = t_enter;
        return true;
    }
    if (t_leave > t_min && t_leave < t_max) { /* the ray starts inside (or on) the box */
        *t = t_leave;
        return true;
    }
    return false;
}

/* The distance along r to the face of b whose outward normal is n, as POV-Ray's box computes it:
 * (face - origin) / direction along the face's axis, one division. The slab test found the same face
 * by multiplying by 1 / direction, which can land one unit in the last place away. A face that lies in
 * a plane must give exactly the plane's t (plane.c divides too), so that the rule for a tie decides
 * which one a ray meets (plane_closest), not rounding: a glass box standing on the floor would
 * otherwise show the floor through its bottom at some pixels and the void below at others. `t` is
 * the slab test's answer, kept for a ray that runs in the face's plane. */
static double face_distance(const struct box *b, const ray *r, vec3 n, double t) {
    double face, origin, direction;
    if (n.x != 0.0) {
        face = n.x > 0.0 ? b->max.x : b->min.x;
        origin = r->origin.x;
        direction = r->direction.x;
    } else if (n.y != 0.0) {
        face = n.y > 0.0 ? b->max.y : b->min.y;
        origin = r->origin.y;
        direction = r->direction.y;
    } else {
        face = n.z > 0.0 ? b->max.z : b->min.z;
        origin = r->origin.z;
        direction = r->direction.z;
    }
    return direction != 0.0 ? (face - origin) / direction : t;
}

/* The distance along r to the face of b that the slab test met at `t`, by face_distance; its outward
 * normal in *normal. */
static double box_face_hit(const struct box *b, const ray *r, double t, vec3 *normal) {
    struct aabb bounds = {b->min, b->max};
    *normal = aabb_normal(&bounds, ray_at(*r, t));
    return face_distance(b, r, *normal, t);
}

bool box_closest(const struct box *boxes, size_t count, const ray *r, double t_min, struct hit *h) {
    const struct box *nearest = NULL;
    for (size_t k = 0; k < count; k++)
        if (box_intersect(&boxes[k], r, t_min, h->t, &h->t))
            nearest = &boxes[k];
    if (nearest == NULL)
        return false;
    h->t = box_face_hit(nearest, r, h->t, &h->normal);
    h->material = nearest->material;
    h->object = (int)(nearest - boxes); /* world_closest turns it into the object's number */
    return true;
}

/* ---- the box as one kind of shape (shape.h) ----------------------------------------------------- */

static bool closest_boxes(const void *items, size_t count, const ray *r, double t_min, struct hit *h) {
    return box_closest(items, count, r, t_min, h);
}

/* Both crossings of each box: where r enters and, searching on from there, where it leaves; each at
 * the distance box_closest gives (box_face_hit). */
static bool box_crossings(const void *items, size_t count, const ray *r, double t_min, double t_max,
                          shape_crossing_visitor visit, void *context) {
    const struct box *boxes = items;
    for (size_t k = 0; k < count; k++) {
        double t_near, t_far;
        if (!box_intersect(&boxes[k], r, t_min, t_max, &t_near))
            continue;
        vec3 normal;
        if (!visit(context, box_face_hit(&boxes[k], r, t_near, &normal), boxes[k].material))
            return false;
        if (box_intersect(&boxes[k], r, t_near, t_max, &t_far) &&
            !visit(context, box_face_hit(&boxes[k], r, t_far, &normal), boxes[k].material))
            return false;
    }
    return true;
}

static bool box_bounds(const void *item, vec3 *min, vec3 *max) {
    const struct box *b = item;
    *min = b->min;
    *max = b->max;
    return true;
}

/* Inside or on the surface. */
static bool box_contains(const void *item, vec3 point) {
    const struct box *b = item;
    return point.x >= b->min.x && point.x <= b->max.x && point.y >= b->min.y && point.y <= b->max.y &&
           point.z >= b->min.z && point.z <= b->max.z;
}

const struct shape_kind box_kind = {
    .syntax = &box_syntax,
    .closest = closest_boxes,
    .crossings = box_crossings,
    .bounds = box_bounds,
    .contains = box_contains,
};

/* solutions.c: one right answer to each build exercise, and one plausible wrong answer, so that the
 * tests can prove every check passes the first and fails the second (test_exercise_proof.c).
 *
 * For lecturers: these are the model answers. They are named solution_* and wrong_*, not by the
 * names the exercises ask for, so that make exercises still says "not started" until a student writes
 * the real function; `make student` leaves this file out of the student copy. */
#include "solutions.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "sample_hash.h"
#include "sampling.h"
#include "shadow.h"

/* ---- 2.4: the disc, a kind of shape: what common/disc.h and common/disc.c hold in a model answer.
 * Named model_disc here, so that it cannot clash with a student's struct disc. ---- */

struct model_disc {
    vec3 centre;
    vec3 normal;   /* unit length */
    double radius; /* > 0 */
    int material;
};

enum { MODEL_DISC_CENTRE, MODEL_DISC_NORMAL, MODEL_DISC_RADIUS };

/* The scene-file line, `disc centre X Y Z normal X Y Z radius R`. */
static bool model_disc_make(const struct key_values *kv, void *item, char *why, size_t why_size) {
    struct model_disc *d = item;
    d->centre = key_vec3(kv, MODEL_DISC_CENTRE);
    vec3 normal = key_vec3(kv, MODEL_DISC_NORMAL);
    d->radius = kv->number[MODEL_DISC_RADIUS][0];
    if (normal.x == 0.0 && normal.y == 0.0 && normal.z == 0.0) {
        snprintf(why, why_size, "disc normal must not be zero");
        return false;
    }
    if (!(d->radius > 0.0)) {
        snprintf(why, why_size, "disc radius must be positive, got %g", d->radius);
        return false;
    }
    d->normal = vec3_normalize(normal);
    return true;
}

static void model_disc_write_pov(FILE *out, const void *item) {
    const struct model_disc *d = item;
    fprintf(out, "disc { ");
    shape_write_vector(out, d->centre);
    fprintf(out, ", ");
    shape_write_vector(out, d->normal);
    fprintf(out, ", %.17g", d->radius);
}

static const struct key_spec model_disc_keys[] = {{"centre", 3}, {"normal", 3}, {"radius", 1}};
static const int model_disc_required[] = {MODEL_DISC_CENTRE, MODEL_DISC_NORMAL, MODEL_DISC_RADIUS, -1};

static const struct shape_syntax model_disc_syntax = {
    .keyword = "disc",
    .plural = "discs",
    .size = sizeof(struct model_disc),
    .material_offset = offsetof(struct model_disc, material),
    .keys = model_disc_keys,
    .key_count = 3,
    .required = model_disc_required,
    .make = model_disc_make,
    .write_pov = model_disc_write_pov,
};

/* The intersection: t as for a plane, n . (C - O) / (n . D), kept when within the radius. */
static bool disc(const struct model_disc *d, const ray *r, double t_min, double t_max, double *t,
                 bool within_radius) {
    double facing = vec3_dot(d->normal, r->direction);
    if (facing == 0.0)
        return false;
    double hit_t = vec3_dot(d->normal, vec3_sub(d->centre, r->origin)) / facing;
    if (!(hit_t > t_min && hit_t < t_max))
        return false;
    vec3 offset = vec3_sub(ray_at(*r, hit_t), d->centre);
    if (within_radius && vec3_dot(offset, offset) > d->radius * d->radius)
        return false;
    *t = hit_t;
    return true;
}

static bool disc_closest(const void *items, size_t count, const ray *r, double t_min, struct hit *h,
                         bool within_radius) {
    const struct model_disc *discs = items, *nearest = NULL;
    for (size_t k = 0; k < count; k++)
        if (disc(&discs[k], r, t_min, h->t, &h->t, within_radius))
            nearest = &discs[k];
    if (nearest == NULL)
        return false;
    h->normal = nearest->normal;
    h->material = nearest->material;
    h->object = (int)(nearest - discs);
    return true;
}

static bool model_disc_closest(const void *items, size_t count, const ray *r, double t_min, struct hit *h) {
    return disc_closest(items, count, r, t_min, h, true);
}

static bool wrong_disc_closest(const void *items, size_t count, const ray *r, double t_min, struct hit *h) {
    return disc_closest(items, count, r, t_min, h, false); /* the plane, without the radius test */
}

static bool model_disc_crossings(const void *items, size_t count, const ray *r, double t_min, double t_max,
                                 shape_crossing_visitor visit, void *context) {
    const struct model_disc *discs = items;
    for (size_t k = 0; k < count; k++) {
        double t;
        if (disc(&discs[k], r, t_min, t_max, &t, true) && !visit(context, t, discs[k].material))
            return false;
    }
    return true;
}

/* On axis i the rim reaches radius * sqrt(1 - n_i^2) either side of the centre. */
static bool model_disc_bounds(const void *item, vec3 *min, vec3 *max) {
    const struct model_disc *d = item;
    vec3 n = d->normal;
    vec3 extent = vec3_make(d->radius * sqrt(fmax(0.0, 1.0 - n.x * n.x)), d->radius * sqrt(fmax(0.0, 1.0 - n.y * n.y)),
                            d->radius * sqrt(fmax(0.0, 1.0 - n.z * n.z)));
    *min = vec3_sub(d->centre, extent);
    *max = vec3_add(d->centre, extent);
    return true;
}

/* A disc has no inside (contains is NULL), like a single triangle. */
const struct shape_kind solution_disc_kind = {
    .syntax = &model_disc_syntax,
    .closest = model_disc_closest,
    .crossings = model_disc_crossings,
    .bounds = model_disc_bounds,
};
const struct shape_kind wrong_disc_kind = {
    .syntax = &model_disc_syntax,
    .closest = wrong_disc_closest,
    .crossings = model_disc_crossings,
    .bounds = model_disc_bounds,
};

/* ---- 3.4 ---- */
static void vertex_normals(const struct mesh *m, vec3 *normals, bool by_area) {
    for (size_t k = 0; k < m->vertex_count; k++)
        normals[k] = vec3_make(0, 0, 0);
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *v = m->faces[f].v;
        vec3 a = m->vertices[v[0]], b = m->vertices[v[1]], c = m->vertices[v[2]];
        vec3 n = vec3_cross(vec3_sub(b, a), vec3_sub(c, a)); /* length: twice the area */
        if (!by_area)
            n = vec3_normalize(n);
        for (int k = 0; k < 3; k++)
            normals[v[k]] = vec3_add(normals[v[k]], n);
    }
    for (size_t k = 0; k < m->vertex_count; k++)
        if (vec3_length(normals[k]) > 0.0)
            normals[k] = vec3_normalize(normals[k]);
}

void solution_mesh_vertex_normals(const struct mesh *m, vec3 *normals) { vertex_normals(m, normals, true); }
void wrong_mesh_vertex_normals(const struct mesh *m, vec3 *normals) { vertex_normals(m, normals, false); }

/* ---- 4.4 ---- */
/* With the caps or without them; the exercise's cylinder is open, so the version with its far root
 * first is the wrong one here: it reports the far wall. */
static bool cylinder(vec3 base, double radius, double height, const ray *r, double t_min, double t_max, double *t,
                     bool far_first) {
    vec3 o = vec3_sub(r->origin, base), d = r->direction;
    double a = d.x * d.x + d.z * d.z;
    if (a == 0.0)
        return false; /* parallel to the axis: never meets the side */
    double half_b = o.x * d.x + o.z * d.z, c = o.x * o.x + o.z * o.z - radius * radius;
    double discriminant = half_b * half_b - a * c;
    if (discriminant < 0.0)
        return false;
    double root = sqrt(discriminant);
    double roots[2] = {(-half_b - root) / a, (-half_b + root) / a};
    for (int k = 0; k < 2; k++) {
        double candidate = roots[far_first ? 1 - k : k];
        double y = o.y + candidate * d.y;
        if (candidate > t_min && candidate < t_max && y >= 0.0 && y <= height) {
            *t = candidate;
            return true;
        }
    }
    return false;
}

bool solution_cylinder_intersect(vec3 base, double radius, double height, const ray *r, double t_min, double t_max,
                                 double *t) {
    return cylinder(base, radius, height, r, t_min, t_max, t, false);
}

bool wrong_cylinder_intersect(vec3 base, double radius, double height, const ray *r, double t_min, double t_max,
                              double *t) {
    return cylinder(base, radius, height, r, t_min, t_max, t, true);
}

/* ---- 5.4 ---- */
/* Ritter's sphere: start from two far-apart points and grow to take in any point outside. */
void solution_mesh_bounding_sphere(const struct mesh *m, vec3 *centre, double *radius) {
    struct aabb box = aabb_empty();
    for (size_t k = 0; k < m->vertex_count; k++)
        box = aabb_grow(box, m->vertices[k]);
    *centre = vec3_scale(vec3_add(box.min, box.max), 0.5);
    *radius = 0.0;
    for (size_t k = 0; k < m->vertex_count; k++) {
        vec3 to = vec3_sub(m->vertices[k], *centre);
        double d = vec3_length(to);
        if (d > *radius) { /* move the centre towards the point just enough to hold it */
            double grown = 0.5 * (*radius + d);
            *centre = vec3_add_scaled(*centre, to, (grown - *radius) / d);
            *radius = grown;
        }
    }
}

void wrong_mesh_bounding_sphere(const struct mesh *m, vec3 *centre, double *radius) {
    /* The box's centre with the radius of the box's smallest half-extent: misses the far points. */
    struct aabb box = aabb_empty();
    for (size_t k = 0; k < m->vertex_count; k++)
        box = aabb_grow(box, m->vertices[k]);
    *centre = vec3_scale(vec3_add(box.min, box.max), 0.5);
    vec3 half = vec3_scale(vec3_sub(box.max, box.min), 0.5);
    *radius = fmin(half.x, fmin(half.y, half.z));
}

/* ---- 6.4 ---- */
double solution_phong_blinn_highlight(vec3 normal, vec3 to_light, vec3 to_eye, double exponent) {
    if (vec3_dot(normal, to_light) <= 0.0)
        return 0.0;
    vec3 half = vec3_normalize(vec3_add(to_light, to_eye));
    double alignment = vec3_dot(normal, half);
    return alignment > 0.0 ? pow(alignment, exponent) : 0.0;
}

double wrong_phong_blinn_highlight(vec3 normal, vec3 to_light, vec3 to_eye, double exponent) {
    /* Phong's (R . V)^n under Blinn's name. */
    vec3 mirror = vec3_sub(vec3_scale(normal, 2.0 * vec3_dot(normal, to_light)), to_light);
    double alignment = vec3_dot(mirror, to_eye);
    return alignment > 0.0 ? pow(alignment, exponent) : 0.0;
}

/* ---- 7.4 ---- */
static double area_fraction(const void *world, vec3 point, vec3 corner, vec3 edge_u, vec3 edge_v, int n,
                            bool centred) {
    int arrived = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double offset = centred ? 0.5 : 0.0;
            vec3 p = vec3_add_scaled(vec3_add_scaled(corner, edge_u, (i + offset) / n), edge_v, (j + offset) / n);
            struct light sample = {.position = p, .colour = vec3_make(1, 1, 1)};
            arrived += shadow_opaque(world, point, &sample).x > 0.0;
        }
    return (double)arrived / (n * n);
}

double solution_shadow_area_fraction(const void *world, vec3 point, vec3 corner, vec3 edge_u, vec3 edge_v, int n) {
    return area_fraction(world, point, corner, edge_u, edge_v, n, true);
}

double wrong_shadow_area_fraction(const void *world, vec3 point, vec3 corner, vec3 edge_u, vec3 edge_v, int n) {
    return area_fraction(world, point, corner, edge_u, edge_v, n, false); /* cell corners, not centres */
}

/* ---- 8.4 ---- */
static double schlick(double cos_incident, double n1, double n2, bool use_transmitted_cosine) {
    double r0 = (n1 - n2) / (n1 + n2);
    r0 *= r0;
    double c = cos_incident;
    if (n1 > n2 && use_transmitted_cosine) {
        double sin_t = n1 / n2 * sqrt(fmax(0.0, 1.0 - c * c));
        if (sin_t > 1.0)
            return 1.0; /* total internal reflection */
        c = sqrt(1.0 - sin_t * sin_t);
    }
    return r0 + (1.0 - r0) * pow(1.0 - c, 5);
}

double solution_whitted_schlick(double cos_incident, double n1, double n2) {
    return schlick(cos_incident, n1, n2, true);
}

double wrong_whitted_schlick(double cos_incident, double n1, double n2) {
    return schlick(cos_incident, n1, n2, false);
}

/* ---- 9.4 ---- */
/* Amanatides and Woo: step to whichever cell boundary is nearest along the ray. */
static int walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max, bool drop_last) {
    struct aabb box = {lo, hi};
    double t_near = 0.0, t_far = INFINITY;
    if (!aabb_clip(&box, r->origin, aabb_inverse_direction(r->direction), &t_near, &t_far))
        return 0;
    double o[3] = {r->origin.x, r->origin.y, r->origin.z}, d[3] = {r->direction.x, r->direction.y, r->direction.z};
    double low[3] = {lo.x, lo.y, lo.z}, size[3] = {(hi.x - lo.x) / cells, (hi.y - lo.y) / cells, (hi.z - lo.z) / cells};
    int cell[3], step[3];
    double next[3], delta[3];
    for (int a = 0; a < 3; a++) {
        double entry = o[a] + t_near * d[a];
        cell[a] = (int)floor((entry - low[a]) / size[a]);
        cell[a] = cell[a] < 0 ? 0 : cell[a] >= cells ? cells - 1 : cell[a];
        step[a] = d[a] > 0 ? 1 : d[a] < 0 ? -1 : 0;
        double boundary = low[a] + (cell[a] + (step[a] > 0)) * size[a];
        next[a] = step[a] != 0 ? (boundary - o[a]) / d[a] : INFINITY;
        delta[a] = step[a] != 0 ? size[a] / fabs(d[a]) : INFINITY;
    }
    int count = 0;
    for (;;) {
        if (count < max)
            for (int a = 0; a < 3; a++)
                out[count][a] = cell[a];
        count++;
        int axis = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
        if (next[axis] > t_far)
            break;
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= cells)
            break;
        next[axis] += delta[axis];
    }
    return drop_last && count > 1 ? count - 1 : count;
}

int solution_grid_walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max) {
    return walk(lo, hi, cells, r, out, max, false);
}

int wrong_grid_walk(vec3 lo, vec3 hi, int cells, const ray *r, int (*out)[3], int max) {
    return walk(lo, hi, cells, r, out, max, true); /* stops one cell early */
}

/* ---- 10.4 ---- */
static double split_cost(const struct aabb *boxes, int n, int axis, double plane, double traversal) {
    struct aabb all = aabb_empty(), left = aabb_empty(), right = aabb_empty();
    int n_left = 0;
    for (int k = 0; k < n; k++) {
        double centre = 0.5 * (vec3_axis(boxes[k].min, axis) + vec3_axis(boxes[k].max, axis));
        all = aabb_union(all, boxes[k]);
        if (centre < plane) {
            left = aabb_union(left, boxes[k]);
            n_left++;
        } else {
            right = aabb_union(right, boxes[k]);
        }
    }
    double area_left = n_left > 0 ? aabb_surface_area(left) : 0.0;
    double area_right = n_left < n ? aabb_surface_area(right) : 0.0;
    return traversal + (area_left * n_left + area_right * (n - n_left)) / aabb_surface_area(all);
}

double solution_bvh_split_cost(const struct aabb *boxes, int n, int axis, double plane) {
    return split_cost(boxes, n, axis, plane, 1.0);
}

double wrong_bvh_split_cost(const struct aabb *boxes, int n, int axis, double plane) {
    return split_cost(boxes, n, axis, plane, 0.0); /* forgets the cost of the step itself */
}

/* ---- 11.4 ---- */
/* Makes the 4-wide node of binary node `index` and, below it, those of its interior children; returns
 * its index in out. `widest`: open the interior child with the largest area (right), or the first one
 * found (wrong). */
static int collapse_node(const struct bvh2_node *tree, int index, struct bvh4_node *out, int max, int *count,
                         bool widest) {
    int slot[4] = {tree[index].child[0], tree[index].child[1]};
    struct aabb box[4] = {tree[index].box[0], tree[index].box[1]};
    int used = 2;
    while (used < 4) {
        int open = -1;
        for (int k = 0; k < used; k++)
            if (slot[k] >= 0 && (open < 0 || (widest && aabb_surface_area(box[k]) > aabb_surface_area(box[open]))))
                open = k;
        if (open < 0)
            break; /* only leaves left */
        const struct bvh2_node *opened = &tree[slot[open]];
        slot[open] = opened->child[0];
        box[open] = opened->box[0];
        slot[used] = opened->child[1];
        box[used++] = opened->box[1];
    }
    int me = (*count)++;
    struct bvh4_node node;
    for (int k = 0; k < 4; k++)
        node.child[k] = k >= used ? BVH4_NONE : slot[k] < 0 ? slot[k] : collapse_node(tree, slot[k], out, max, count, widest);
    if (me < max)
        out[me] = node;
    return me;
}

int solution_bvh4_collapse(const struct bvh2_node *tree, int root, struct bvh4_node *out, int max) {
    int count = 0;
    collapse_node(tree, root, out, max, &count, true);
    return count;
}

int wrong_bvh4_collapse(const struct bvh2_node *tree, int root, struct bvh4_node *out, int max) {
    int count = 0;
    collapse_node(tree, root, out, max, &count, false); /* opens the first interior child, not the widest */
    return count;
}

/* n-rooks: row r gets a random place in column perm[r], the permutation shuffled (Fisher-Yates) with the
 * pixel's own numbers: index k for the places (2k, 2k + 1), 2n + k for the shuffle. */
static void rooks(int i, int j, int n, uint32_t seed, double *x, double *y, bool shuffle) {
    int perm[256];
    for (int k = 0; k < n; k++)
        perm[k] = k;
    for (int k = n - 1; shuffle && k > 0; k--) {
        int pick = (int)(sample_hash_unit((uint32_t)i, (uint32_t)j, (uint32_t)(2 * n + k), seed) * (k + 1));
        int t = perm[k];
        perm[k] = perm[pick];
        perm[pick] = t;
    }
    for (int r = 0; r < n; r++) {
        x[r] = (perm[r] + sample_hash_unit((uint32_t)i, (uint32_t)j, (uint32_t)(2 * r), seed)) / n;
        y[r] = (r + sample_hash_unit((uint32_t)i, (uint32_t)j, (uint32_t)(2 * r + 1), seed)) / n;
    }
}

void solution_supersample_rooks(int i, int j, int n, uint32_t seed, double *x, double *y) {
    rooks(i, j, n, seed, x, y, true);
}

void wrong_supersample_rooks(int i, int j, int n, uint32_t seed, double *x, double *y) {
    rooks(i, j, n, seed, x, y, false); /* never shuffled: every pixel's rooks on the diagonal */
}

/* The concentric map; the wrong one pushes each point of the square straight out from the centre onto
 * the circle of its square (POV-Ray's circular area lights do that): shells keep their areas, but along
 * each side the points crowd towards the diagonals. */
void solution_thin_lens_concentric(double u, double v, double *x, double *y) {
    double a = 2 * u - 1, b = 2 * v - 1, r, angle;
    if (a == 0 && b == 0) {
        *x = *y = 0;
        return;
    }
    if (fabs(a) > fabs(b)) {
        r = a;
        angle = M_PI / 4 * (b / a);
    } else {
        r = b;
        angle = M_PI / 2 - M_PI / 4 * (a / b);
    }
    *x = r * cos(angle);
    *y = r * sin(angle);
}

void wrong_thin_lens_concentric(double u, double v, double *x, double *y) {
    double a = 2 * u - 1, b = 2 * v - 1, length = hypot(a, b);
    double scale = length > 0 ? fmax(fabs(a), fabs(b)) / length : 0;
    *x = a * scale;
    *y = b * scale;
}

/* The cylindrical map: the longitude by atan2, moved into [0, 1). */
bool solution_image_map_cylindrical(vec3 q, double *u, double *v) {
    if (q.x == 0.0 && q.z == 0.0)
        return false;
    double turn = atan2(q.z, q.x) / (2.0 * M_PI);
    *u = turn < 0.0 ? turn + 1.0 : turn;
    if (*u >= 1.0)
        *u = 0.0;
    *v = q.y;
    return true;
}

bool wrong_image_map_cylindrical(vec3 q, double *u, double *v) {
    if (q.x == 0.0 && q.z == 0.0)
        return false;
    *u = atan2(q.z, q.x) / (2.0 * M_PI); /* not moved into [0, 1): half the turn is negative */
    *v = q.y;
    return true;
}

/* The cone of a ball: cos theta uniform in [cos theta_max, 1], turned about the axis by 2 pi u2. With
 * `uniform_angle` (the wrong answer) theta itself is uniform, which crowds the axis. */
static bool cone(vec3 centre, double radius, vec3 point, double u1, double u2, vec3 *direction, double *density,
                 bool uniform_angle) {
    vec3 to_centre = vec3_sub(centre, point);
    double distance = vec3_length(to_centre);
    if (!(distance > radius))
        return false;
    double sin_max = radius / distance, cos_max = sqrt(1.0 - sin_max * sin_max);
    double cos_theta = uniform_angle ? cos(u1 * acos(cos_max)) : 1.0 - u1 * (1.0 - cos_max);
    double sin_theta = sqrt(fmax(0.0, 1.0 - cos_theta * cos_theta)), phi = 2.0 * M_PI * u2;
    vec3 axis = vec3_scale(to_centre, 1.0 / distance), t, b;
    sampling_basis(axis, &t, &b);
    *direction = vec3_add_scaled(vec3_add_scaled(vec3_scale(axis, cos_theta), t, sin_theta * cos(phi)), b,
                                 sin_theta * sin(phi));
    *density = 1.0 / (2.0 * M_PI * (1.0 - cos_max));
    return true;
}

bool solution_sampling_sphere_cone(vec3 centre, double radius, vec3 point, double u1, double u2, vec3 *direction,
                                   double *density) {
    return cone(centre, radius, point, u1, u2, direction, density, false);
}

bool wrong_sampling_sphere_cone(vec3 centre, double radius, vec3 point, double u1, double u2, vec3 *direction,
                                double *density) {
    return cone(centre, radius, point, u1, u2, direction, density, true);
}

/* Slerp: q0 and q1 (flipped to the short way) weighed by sin((1 - t) theta) and sin(t theta) over
 * sin(theta), theta the angle between them. With `linear` (the wrong answer) the plain blend (1 - t) q0 +
 * t q1 made unit length, nlerp, which has the right ends and arc but turns faster in the middle. */
static void slerp(const double q0[4], const double q1[4], double t, double out[4], bool linear) {
    double dot = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3], sign = 1.0;
    if (dot < 0) {
        dot = -dot;
        sign = -1.0;
    }
    double a = 1.0 - t, b = t;
    if (!linear && dot < 0.9995) {
        double theta = acos(dot);
        a = sin((1.0 - t) * theta) / sin(theta);
        b = sin(t * theta) / sin(theta);
    }
    double length = 0;
    for (int k = 0; k < 4; k++) {
        out[k] = a * q0[k] + sign * b * q1[k];
        length += out[k] * out[k];
    }
    for (int k = 0; k < 4; k++)
        out[k] /= sqrt(length);
}

void solution_keyframes_slerp(const double q0[4], const double q1[4], double t, double out[4]) {
    slerp(q0, q1, t, out, false);
}

void wrong_keyframes_slerp(const double q0[4], const double q1[4], double t, double out[4]) {
    slerp(q0, q1, t, out, true);
}

/* GGX's normals: tan^2 theta = alpha^2 u1 / (1 - u1), the inverse of the share x / (alpha^2 + x) of
 * normals with tan^2 theta below x. With `unsquared` (the wrong answer) tan theta = alpha u1 / (1 - u1),
 * the square root forgotten: the same median, but too many normals near the pole and too many far out. */
static vec3 ggx_normal(double alpha, double u1, double u2, bool unsquared) {
    double tan_theta = unsquared ? alpha * u1 / (1.0 - u1) : alpha * sqrt(u1 / (1.0 - u1));
    double cos_theta = 1.0 / sqrt(1.0 + tan_theta * tan_theta), sin_theta = tan_theta * cos_theta;
    double phi = 2.0 * M_PI * u2;
    return vec3_make(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

vec3 solution_microfacet_ggx_sample_normal(double alpha, double u1, double u2) {
    return ggx_normal(alpha, u1, u2, false);
}

vec3 wrong_microfacet_ggx_sample_normal(double alpha, double u1, double u2) { return ggx_normal(alpha, u1, u2, true); }

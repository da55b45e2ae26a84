/* instances.c: loading objects, placing instances and the two-level queries (chapter 16; instances.h). */
#include "instances.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "fast_bvh_build.h"
#include "infile.h"
#include "interior.h"
#include "memory_budget.h"
#include "mesh_load.h"
#include "stats.h"
#include "triangle.h"

/* ---- placing ------------------------------------------------------------------------------------ */

/* The largest coordinate a placed object may reach, and its least size: a placed mesh's limits
 * (scene_meshes.c), for the same reason: boxes in float, areas in float. */
#define INSTANCES_MAX_COORD TRIANGLE_MAX_COORD
#define INSTANCES_MIN_SIZE 1e-18
#define INSTANCES_MESH_ERROR_SIZE 4352 /* the longest message of a mesh reader kept: a whole path and the reason */

static struct pose pose_of(const struct scene_pose *p) { return (struct pose){p->scale, p->rotate, p->translate}; }

static struct transform transform_of(struct pose p) { return transform_from_pose(p.scale, p.rotate, p.translate); }

bool instances_transform_at(const struct instances *in, size_t k, double time, struct transform *to_world,
                            struct transform *to_object) {
    const struct instance *it = &in->items[k];
    if (it->keys == NULL) {
        *to_world = it->to_world;
        *to_object = it->to_object;
        return true;
    }
    *to_world = transform_of(keyframes_pose_at(it->keys, it->key_count, time));
    return transform_invert(to_world, to_object);
}

/* Writes "scene:line: instance of 'NAME': what" into err and returns false. */
static bool instance_fail(const struct scene *s, const struct scene_instance *si, int line, char *err,
                          size_t err_size, const char *what) {
    snprintf(err, err_size, "%s:%d: instance of '%s': %s", s->path, line, s->objects[si->object].name, what);
    return false;
}

/* Returns whether any scale factor changes sign from pose a to pose b (then it is zero in between). */
static bool scale_flips(struct scene_pose a, struct scene_pose b) {
    return a.scale.x * b.scale.x < 0.0 || a.scale.y * b.scale.y < 0.0 || a.scale.z * b.scale.z < 0.0;
}

/* The spread max|s| / min|s| of a pose's scale factors (none of them 0: a scale is at least 1e-9). */
static double scale_spread(vec3 s) {
    double x = fabs(s.x), y = fabs(s.y), z = fabs(s.z);
    return fmax(fmax(x, y), z) / fmin(fmin(x, y), z);
}

/* Returns whether every pose between keys a and b (the scale and the angles interpolated, no scale factor
 * changing sign) can be inverted accurately: INSTANCES_TURN_SPREAD's bound keeps its condition within
 * TRANSFORM_CONDITION_MAX for any turn when its scale factors' spread is small enough, and that spread is
 * at most the larger of the two keys'. For each two factors interpolated in step, s_i(t) / s_j(t) moves
 * one way only (its rate's sign is that of b_i a_j - a_i b_j, whatever t), so it is largest at a key. (A
 * key's own pose is checked exactly, by pose_valid; between two keys, a turn both keys avoid, the object's
 * thin axis turned half-way between two others, can make the condition up to three times a key's.) */
static bool poses_between_invertible(struct scene_pose a, struct scene_pose b) {
    return INSTANCES_TURN_SPREAD * fmax(scale_spread(a.scale), scale_spread(b.scale)) <= TRANSFORM_CONDITION_MAX;
}

/* Returns whether box b lies within the coordinates a placed object may reach and is not too small. */
static bool box_in_range(struct aabb b) {
    double size = fmax(b.max.x - b.min.x, fmax(b.max.y - b.min.y, b.max.z - b.min.z));
    return fabs(b.min.x) <= INSTANCES_MAX_COORD && fabs(b.min.y) <= INSTANCES_MAX_COORD &&
           fabs(b.min.z) <= INSTANCES_MAX_COORD && fabs(b.max.x) <= INSTANCES_MAX_COORD &&
           fabs(b.max.y) <= INSTANCES_MAX_COORD && fabs(b.max.z) <= INSTANCES_MAX_COORD && size >= INSTANCES_MIN_SIZE;
}

/* Checks one pose of scene instance si (from the instance line or a key at `line`): invertible, and the
 * object placed by it within range. */
static bool pose_valid(const struct instances *in, const struct scene_instance *si, struct scene_pose p, int line,
                       char *err, size_t err_size) {
    struct transform t = transform_of(pose_of(&p)), inverse;
    if (!transform_invert(&t, &inverse))
        return instance_fail(in->scene, si, line, err, err_size, "its transform cannot be inverted accurately "
                             "(its scale factors differ by more than the tracer can carry rays through)");
    if (!box_in_range(transform_box(&t, in->object_boxes[si->object])))
        return instance_fail(in->scene, si, line, err, err_size, "placed out of range (coordinates must stay "
                             "within -1e18 .. 1e18 and the object at least 1e-18 across)");
    return true;
}

/* Makes instance k from its scene line and keys. */
static bool place(struct instances *in, size_t k, char *err, size_t err_size) {
    const struct scene_instance *si = &in->scene->instances[k];
    struct instance *it = &in->items[k];
    it->object = si->object;
    it->material = si->material;
    it->in_tree = in->objects[si->object]->tree_count == in->objects[si->object]->triangle_count;
    if (!pose_valid(in, si, si->pose, si->line, err, err_size))
        return false;
    it->to_world = transform_of(pose_of(&si->pose));
    transform_invert(&it->to_world, &it->to_object);
    if (si->key_count == 0)
        return true;
    it->keys = malloc(si->key_count * sizeof *it->keys);
    if (it->keys == NULL)
        return instance_fail(in->scene, si, si->line, err, err_size, "out of memory for its keys");
    it->key_count = si->key_count;
    for (size_t n = 0; n < si->key_count; n++) {
        const struct scene_key *key = &si->keys[n];
        if (!pose_valid(in, si, key->pose, key->line, err, err_size))
            return false;
        if (n > 0 && scale_flips(si->keys[n - 1].pose, key->pose))
            return instance_fail(in->scene, si, key->line, err, err_size, "a scale factor changes sign since "
                                 "the previous key, so it passes through zero (a flat object) in between");
        if (n > 0 && !poses_between_invertible(si->keys[n - 1].pose, key->pose))
            return instance_fail(in->scene, si, key->line, err, err_size, "between the previous key and this one, "
                                 "a turn can make its transform impossible to invert accurately (a key's scale factors "
                                 "differ by more than a third of what the tracer can carry rays through)");
        it->keys[n] = (struct keyframe){key->time, pose_of(&key->pose)};
    }
    in->info.moving++;
    return true;
}

/* Pads a world box by INSTANCES_BOX_PAD of its size and of its largest coordinate. */
static struct aabb pad_world_box(struct aabb b) {
    double reach = fmax(fmax(fabs(b.min.x), fabs(b.max.x)), fmax(fmax(fabs(b.min.y), fabs(b.max.y)),
                                                                    fmax(fabs(b.min.z), fabs(b.max.z))));
    double size = fmax(b.max.x - b.min.x, fmax(b.max.y - b.min.y, b.max.z - b.min.z));
    return aabb_pad(b, INSTANCES_BOX_PAD * (reach + size));
}

/* Instance k's world box over [t0, t1]. */
static struct aabb instance_box(const struct instances *in, size_t k, double t0, double t1) {
    const struct instance *it = &in->items[k];
    struct aabb object = in->object_boxes[it->object];
    struct aabb world = it->keys == NULL ? transform_box(&it->to_world, object)
                                         : keyframes_motion_box(it->keys, it->key_count, object, t0, t1);
    return pad_world_box(world);
}

bool instances_bounds(const void *instances, vec3 *min, vec3 *max) {
    const struct instances *in = instances;
    for (size_t k = 0; k < in->count; k++) {
        const struct instance *it = &in->items[k];
        struct aabb object = in->object_extents[it->object];
        struct aabb box = it->keys == NULL ? transform_box(&it->to_world, object)
                                           : keyframes_motion_box(it->keys, it->key_count, object, in->t0, in->t1);
        *min = vec3_min(*min, box.min);
        *max = vec3_max(*max, box.max);
    }
    return in->count > 0;
}

double instances_expected_tests(const struct instances *in, int *line, bool *outside) {
    uint32_t crowded = 0;
    double in_tree = in->top != NULL ? instance_bvh_expected_instances(in->top, &crowded) : 0.0;
    *outside = in->outside_count > in_tree;
    *line = in->count == 0 ? 0
            : *outside     ? in->scene->instances[in->outside[0]].line
                           : in->scene->instances[crowded].line;
    return in_tree + (double)in->outside_count;
}

/* ---- loading ------------------------------------------------------------------------------------ */

/* Loads object k's mesh (once) and builds its tree. *meshes_taken, the bytes of the scene's meshes so
 * far, grows by the object's, which may not take it over the meshes' share of memory (memory_budget.h). */
static bool load_object(struct instances *in, struct scene *s, size_t k, size_t *meshes_taken, char *err,
                        size_t err_size) {
    struct scene_object *o = &s->objects[k];
    char why[INSTANCES_MESH_ERROR_SIZE];
    if (o->mesh.vertices == NULL && !mesh_load(o->path, &o->mesh, why, sizeof why)) {
        snprintf(err, err_size, "%s:%d: object '%s': %s", s->path, o->line, o->name, why);
        return false;
    }
    *meshes_taken += mesh_bytes(&o->mesh);
    if (*meshes_taken > memory_budget_share(MEMORY_BUDGET_MESH_SHARE)) {
        memory_budget_explain(why, sizeof why, "meshes", *meshes_taken, MEMORY_BUDGET_MESH_SHARE);
        snprintf(err, err_size, "%s:%d: object '%s': %s", s->path, o->line, o->name, why);
        return false;
    }
    for (size_t v = 0; v < o->mesh.vertex_count; v++)
        if (!(fabs(o->mesh.vertices[v].x) <= INSTANCES_MAX_COORD && fabs(o->mesh.vertices[v].y) <= INSTANCES_MAX_COORD &&
              fabs(o->mesh.vertices[v].z) <= INSTANCES_MAX_COORD)) {
            snprintf(err, err_size, "%s:%d: object '%s': vertex %zu lies beyond -1e18 .. 1e18", s->path, o->line,
                     o->name, v);
            return false;
        }
    in->object_extents[k] = world_mesh_bounds(&o->mesh);
    in->object_boxes[k] = aabb_pad(in->object_extents[k], triangle_box_pad(&o->mesh));
    in->objects[k] = fast_bvh_build(&o->mesh, BVH_SPLIT_SAH, FAST_BVH_RUNG_DEFAULT);
    if (in->objects[k] == NULL) {
        snprintf(err, err_size, "%s:%d: object '%s': out of memory building its BVH (%zu triangles)", s->path, o->line,
                 o->name, o->mesh.face_count);
        return false;
    }
    const struct fast_bvh *b = in->objects[k];
    in->info.object_triangles += o->mesh.face_count;
    in->info.object_bytes +=
        o->mesh.vertex_count * sizeof(vec3) + o->mesh.face_count * sizeof(struct mesh_face) + fast_bvh_bytes(b);
    return true;
}

bool instances_objects_open(const struct scene *s, char *err, size_t err_size) {
    for (size_t k = 0; k < s->object_count; k++) {
        const struct scene_object *o = &s->objects[k];
        char why[INSTANCES_MESH_ERROR_SIZE];
        FILE *file = infile_open(o->path, why, sizeof why);
        if (file == NULL) {
            snprintf(err, err_size, "%s:%d: object '%s': %s", s->path, o->line, o->name, why);
            return false;
        }
        fclose(file);
    }
    return true;
}

/* Builds the top level anew over the instances in the tree. */
static bool build_top(struct instances *in, char *err, size_t err_size) {
    double started = clock_seconds();
    struct instance_bvh *top = NULL;
    if (in->outside_count < in->count) {
        top = instance_bvh_build(in->boxes, in->count, err, err_size);
        if (top == NULL)
            return false;
    }
    instance_bvh_free(in->top);
    in->top = top;
    in->info.top_build_ms = 1e3 * (clock_seconds() - started);
    in->info.top_sah_cost = in->info.top_sah_cost_built = top != NULL ? instance_bvh_sah_cost(top) : 0.0;
    in->info.rebuilds++;
    return true;
}

/* Sets the boxes of the instances for [t0, t1]; those not in the tree get the empty box, which no ray
 * enters (they are tested apart). */
static void compute_boxes(struct instances *in, double t0, double t1) {
    for (size_t k = 0; k < in->count; k++)
        in->boxes[k] = in->items[k].in_tree ? instance_box(in, k, t0, t1) : aabb_empty();
    in->t0 = t0;
    in->t1 = t1;
}

static bool closest_query(const void *structure, const ray *r, double t_min, double time, struct hit *h);
static bool crossing_query(const void *structure, const ray *r, double t_min, double t_max, double time,
                           shape_crossing_visitor visit, void *context);
static void containing_query(const void *structure, vec3 point, double time, world_instance_visitor visit,
                             void *context);

struct instances *instances_create(struct scene *s, int first_object, double t0, double t1, char *err,
                                   size_t err_size) {
    struct instances *in = calloc(1, sizeof *in);
    if (in == NULL)
        return (snprintf(err, err_size, "out of memory"), NULL);
    in->scene = s;
    in->first_object = first_object;
    in->count = s->instance_count;
    in->objects = calloc(s->object_count + 1, sizeof *in->objects);
    in->object_boxes = calloc(s->object_count + 1, sizeof *in->object_boxes);
    in->object_extents = calloc(s->object_count + 1, sizeof *in->object_extents);
    in->items = calloc(in->count + 1, sizeof *in->items);
    in->boxes = calloc(in->count + 1, sizeof *in->boxes);
    in->outside = calloc(in->count + 1, sizeof *in->outside);
    if (in->objects == NULL || in->object_boxes == NULL || in->object_extents == NULL || in->items == NULL ||
        in->boxes == NULL || in->outside == NULL) {
        instances_free(in);
        return (snprintf(err, err_size, "out of memory"), NULL);
    }
    double started = clock_seconds();
    bool ok = true;
    bool *placed = calloc(s->object_count + 1, sizeof *placed); /* an object no instance places is not loaded */
    if (placed == NULL) {
        instances_free(in);
        return (snprintf(err, err_size, "out of memory"), NULL);
    }
    for (size_t n = 0; n < in->count; n++)
        placed[s->instances[n].object] = true;
    size_t meshes_taken = 0; /* the mesh lines' first (scene_load_meshes), then the objects' */
    for (size_t k = 0; k < s->mesh_count; k++) {
        const struct scene_mesh *m = &s->meshes[k];
        meshes_taken += mesh_bytes(&m->mesh) + mesh_corners_bytes(&m->corners, m->mesh.face_count);
    }
    for (size_t k = 0; ok && k < s->object_count; k++)
        if (placed[k])
            ok = load_object(in, s, k, &meshes_taken, err, err_size);
    free(placed);
    in->info.object_build_ms = 1e3 * (clock_seconds() - started);
    for (size_t k = 0; ok && k < in->count; k++) {
        ok = place(in, k, err, err_size);
        if (ok && !in->items[k].in_tree)
            in->outside[in->outside_count++] = k;
        if (ok)
            in->info.instanced_triangles += (double)s->objects[in->items[k].object].mesh.face_count;
    }
    if (ok) {
        compute_boxes(in, t0, t1);
        ok = build_top(in, err, err_size);
    }
    if (!ok) {
        instances_free(in);
        return NULL;
    }
    in->info.objects = s->object_count;
    in->info.instances = in->count;
    in->hook = (struct world_instances){in, closest_query, crossing_query, containing_query};
    return in;
}

bool instances_set_interval(struct instances *in, double t0, double t1, enum instances_update how, char *err,
                            size_t err_size) {
    double started = clock_seconds();
    compute_boxes(in, t0, t1);
    if (in->top == NULL)
        return true;
    if (how == INSTANCES_REBUILD)
        return build_top(in, err, err_size);
    instance_bvh_refit(in->top, in->boxes);
    in->info.top_sah_cost = instance_bvh_sah_cost(in->top);
    if (how == INSTANCES_AUTO && in->info.top_sah_cost > INSTANCES_REBUILD_GROWTH * in->info.top_sah_cost_built)
        return build_top(in, err, err_size);
    in->info.top_build_ms = 1e3 * (clock_seconds() - started);
    in->info.refits++;
    return true;
}

void instances_free(struct instances *in) {
    if (in == NULL)
        return;
    for (size_t k = 0; in->objects != NULL && k < in->scene->object_count; k++)
        fast_bvh_free(in->objects[k]);
    for (size_t k = 0; in->items != NULL && k < in->count; k++)
        free(in->items[k].keys);
    instance_bvh_free(in->top);
    free(in->objects);
    free(in->object_boxes);
    free(in->object_extents);
    free(in->items);
    free(in->boxes);
    free(in->outside);
    free(in);
}

/* ---- the queries -------------------------------------------------------------------------------- */

/* Carries r into the space of the transform whose inverse is to_object: the origin as a point, the
 * direction as a vector, not normalised, so that a point's t is the same in both spaces. */
static ray object_ray(const struct transform *to_object, const ray *r) {
    return (ray){transform_point(to_object, r->origin), transform_vector(to_object, r->direction)};
}

/* The nearest-hit search's state: the world ray and time, and the best hit so far. */
struct closest_search {
    const struct instances *in;
    const ray *r;
    double time;
    struct hit *h;
    bool found;
    size_t best; /* the instance of the hit in h, when found */
};

/* Tests instance k for a hit nearer than the best; among hits at exactly the same t, the lowest
 * instance wins, as in a loop over the instances in order. */
/* TASK 16.1: the ray carried into an instance, its hit carried back */
static void closest_in_instance(struct closest_search *q, size_t k, double t_min) {
    const struct instances *in = q->in;
    struct transform to_world, to_object;
    if (!instances_transform_at(in, k, q->time, &to_world, &to_object))
        return;
    ray local = object_ray(&to_object, q->r);
    double t_max = q->found && k < q->best ? nextafter(q->h->t, INFINITY) : q->h->t, t;
    uint32_t face;
    const struct instance *it = &in->items[k];
    if (!fast_bvh_closest(in->objects[it->object], &local, t_min, t_max, &t, &face))
        return;
    const struct mesh *m = &in->scene->objects[it->object].mesh;
    const uint32_t *c = m->faces[face].v;
    vec3 normal = triangle_normal(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]]);
    q->h->t = t;
    q->h->normal = vec3_normalize(transform_normal(&to_object, normal));
    q->h->material = it->material;
    q->h->object = in->first_object + (int)k;
    q->h->face = (int)face;
    q->found = true;
    q->best = k;
}

/* The top level's callback: one instance in the tree whose box the ray enters. */
static bool visit_closest(void *context, size_t index, double t_min, double *t_max) {
    struct closest_search *q = context;
    closest_in_instance(q, index, t_min);
    *t_max = q->h->t;
    return true;
}

static bool closest_query(const void *structure, const ray *r, double t_min, double time, struct hit *h) {
    const struct instances *in = structure;
    struct closest_search q = {in, r, time, h, false, 0};
    if (in->top != NULL) {
        double t_max = h->t;
        instance_bvh_walk(in->top, r, t_min, &t_max, visit_closest, &q);
    }
    for (size_t n = 0; n < in->outside_count; n++)
        closest_in_instance(&q, in->outside[n], t_min);
    return q.found;
}

/* The crossings search's state. */
struct crossing_search {
    const struct instances *in;
    const ray *r;
    double time, t_max;
    shape_crossing_visitor visit;
    void *context;
    int material;   /* of the instance being walked */
    bool stopped;   /* the visitor asked to stop */
};

static bool visit_face(void *context, double t, uint32_t face) {
    (void)face;
    struct crossing_search *q = context;
    q->stopped = !q->visit(q->context, t, q->material);
    return !q->stopped;
}

/* Passes every crossing of instance k on; returns false when the visitor asked to stop. */
/* TASK 16.1 ALSO: a shadow ray carried into an instance */
static bool cross_instance(struct crossing_search *q, size_t k, double t_min) {
    struct transform to_world, to_object;
    if (!instances_transform_at(q->in, k, q->time, &to_world, &to_object))
        return true;
    ray local = object_ray(&to_object, q->r);
    q->material = q->in->items[k].material;
    fast_bvh_for_each_hit(q->in->objects[q->in->items[k].object], &local, t_min, q->t_max, visit_face, q);
    return !q->stopped;
}

static bool visit_crossings(void *context, size_t index, double t_min, double *t_max) {
    (void)t_max;
    return cross_instance(context, index, t_min);
}

static bool crossing_query(const void *structure, const ray *r, double t_min, double t_max, double time,
                           shape_crossing_visitor visit, void *context) {
    const struct instances *in = structure;
    struct crossing_search q = {in, r, time, t_max, visit, context, 0, false};
    if (in->top != NULL) {
        double limit = t_max;
        instance_bvh_walk(in->top, r, t_min, &limit, visit_crossings, &q);
    }
    for (size_t n = 0; n < in->outside_count && !q.stopped; n++)
        cross_instance(&q, in->outside[n], t_min);
    return !q.stopped;
}

/* The containing search's state: the world point and time, and whom to tell. */
struct containing_search {
    const struct instances *in;
    vec3 point;
    double time;
    world_instance_visitor visit;
    void *context;
    bool stopped; /* the visitor asked to stop */
};

/* Passes instance k on when it lets light through and its object holds the point at the search's time;
 * returns false when the visitor asked to stop. */
/* TASK 16.1 ALSO: a point carried into an instance, to find the glass an eye starts in */
static bool contain_in_instance(struct containing_search *q, size_t k) {
    const struct instances *in = q->in;
    const struct instance *it = &in->items[k];
    if (!material_passes_light(&in->scene->materials[it->material]))
        return true;
    struct transform to_world, to_object;
    if (!instances_transform_at(in, k, q->time, &to_world, &to_object))
        return true;
    vec3 local = transform_point(&to_object, q->point);
    const struct aabb *box = &in->object_boxes[it->object];
    if (local.x < box->min.x || local.x > box->max.x || local.y < box->min.y || local.y > box->max.y ||
        local.z < box->min.z || local.z > box->max.z)
        return true;
    if (!interior_mesh_contains(&in->scene->objects[it->object].mesh, local))
        return true;
    q->stopped = !q->visit(q->context, in->first_object + (int)k, it->material);
    return !q->stopped;
}

static bool visit_containing(void *context, size_t index, double t_min, double *t_max) {
    (void)t_min;
    (void)t_max;
    return contain_in_instance(context, index);
}

/* The top level is walked by a ray from the point with t in [0, 0]: it enters exactly the boxes that
 * hold the point. */
static void containing_query(const void *structure, vec3 point, double time, world_instance_visitor visit,
                             void *context) {
    const struct instances *in = structure;
    struct containing_search q = {in, point, time, visit, context, false};
    if (in->top != NULL) {
        ray at = {point, vec3_make(0, 0, 1)};
        double t_max = 0.0;
        instance_bvh_walk(in->top, &at, 0.0, &t_max, visit_containing, &q);
    }
    for (size_t n = 0; n < in->outside_count && !q.stopped; n++)
        contain_in_instance(&q, in->outside[n]);
}

/* ---- the report --------------------------------------------------------------------------------- */

void instances_report(const struct instances *in, FILE *out, bool detailed) {
    const struct instances_info *i = &in->info;
    size_t keys = 0, top = in->top != NULL ? in->top->node_count * sizeof(struct instance_bvh_node) +
                                              in->top->instance_count * sizeof(uint32_t) : 0;
    for (size_t k = 0; k < in->count; k++)
        keys += in->items[k].key_count * sizeof(struct keyframe);
    /* each instance: its record, its world box, its place in the list of those outside the tree */
    size_t each = sizeof(struct instance) + sizeof(struct aabb) + sizeof(size_t);
    double per_instance = in->count > 0 ? (double)(each * in->count + keys + top) / (double)in->count : 0.0;
    fprintf(out, "instances: %zu of %zu object%s (%zu moving), %.4g triangles instanced from %zu\n", i->instances,
            i->objects, i->objects == 1 ? "" : "s", i->moving, i->instanced_triangles, i->object_triangles);
    fprintf(out, "  objects' meshes and trees   %.1f MB, built in %.1f ms\n", (double)i->object_bytes / 1e6,
            i->object_build_ms);
    fprintf(out, "  per instance                %.0f bytes (with its keys and its share of the top level)\n",
            per_instance);
    fprintf(out, "  top level                   %s in %.2f ms\n", i->refits > 0 ? "last refitted or built" : "built",
            i->top_build_ms);
    if (detailed)
        fprintf(out, "  top level SAH cost          %.3f (%.3f when last built); %zu builds, %zu refits\n",
                i->top_sah_cost, i->top_sah_cost_built, i->rebuilds, i->refits);
}

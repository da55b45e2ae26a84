/* world.c: nearest-hit and all-crossings queries over every shape of a scene (chapter 5).
 *
 * Without an acceleration structure, each mesh is tested behind its bounding box; a ray that misses
 * the box adds the mesh's face count to stats_thread.triangle_tests_culled, the triangle tests the box
 * saved. The box is padded as the hierarchies pad theirs (world_mesh_cull_bounds), so that it never
 * turns away a ray the triangle test would call a hit: this loop is the oracle the structures are
 * tested against. With one (chapters 9 and 10), the structure counts its own work and nothing is culled here. */
#include "world.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stats.h"
#include "triangle.h"

struct aabb world_mesh_bounds(const struct mesh *m) {
    struct aabb bounds = aabb_empty();
    for (size_t k = 0; k < m->face_count; k++)
        for (int c = 0; c < 3; c++)
            bounds = aabb_grow(bounds, m->vertices[m->faces[k].v[c]]);
    return bounds;
}

struct aabb world_mesh_cull_bounds(const struct mesh *m) {
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *v = m->faces[k].v;
        if (triangle_is_sliver(m->vertices[v[0]], m->vertices[v[1]], m->vertices[v[2]]))
            return aabb_everything();
    }
    return aabb_pad(world_mesh_bounds(m), triangle_box_pad(m));
}

int world_object_number(const struct scene *s, const struct shape_list *list, size_t index) {
    size_t number = index;
    for (const struct shape_list *before = s->shapes; before < list; before++)
        number += before->count;
    return (int)number;
}

int world_mesh_object_number(const struct scene *s, size_t index) {
    return world_object_number(s, s->shapes + s->kind_count, index); /* the meshes come after every shape */
}

/* Adds the shapes of `list` to the world's searches: the triangles apart, since the meshes (and the
 * acceleration structures) go with them; then by whether the kind has bounding boxes. */
static void add_shapes(struct world *w, const struct shape_list *list) {
    struct world_shapes shapes = {list->kind, list->items, list->count, world_object_number(w->scene, list, 0)};
    vec3 min, max;
    if (list->syntax == &triangle_syntax)
        w->triangles = shapes;
    else if (list->kind->bounds(list->items, &min, &max))
        w->bounded[w->bounded_count++] = shapes;
    else
        w->unbounded[w->unbounded_count++] = shapes;
}

/* The world of s, with the cull box of every mesh (every_box) or of those light passes through alone. */
static bool init(struct world *w, const struct scene *s, bool every_box, char *err, size_t err_size) {
    memset(w, 0, sizeof *w);
    w->scene = s;
    for (size_t k = 0; k < s->kind_count; k++) {
        const struct shape_list *list = &s->shapes[k];
        if (list->count == 0)
            continue;
        if (list->kind == NULL) {
            snprintf(err, err_size, "%s: %zu %s of no kind (give the scene reader the kinds the program draws)",
                     s->path, list->count, list->syntax->plural);
            return false;
        }
        add_shapes(w, list);
    }
    w->mesh_bounds = calloc(s->mesh_count + 1, sizeof *w->mesh_bounds);
    w->mesh_first_face = calloc(s->mesh_count + 1, sizeof *w->mesh_first_face);
    w->clear_meshes = calloc(s->mesh_count + 1, sizeof *w->clear_meshes);
    if (w->mesh_bounds == NULL || w->mesh_first_face == NULL || w->clear_meshes == NULL) {
        world_free(w);
        snprintf(err, err_size, "out of memory");
        return false;
    }
    w->mesh_first_face[0] = w->triangles.count;
    for (size_t k = 0; k < s->mesh_count; k++) {
        bool passes_light = material_passes_light(&s->materials[s->meshes[k].material]);
        w->mesh_bounds[k] = every_box || passes_light ? world_mesh_cull_bounds(&s->meshes[k].mesh) : aabb_everything();
        w->mesh_first_face[k + 1] = w->mesh_first_face[k] + s->meshes[k].mesh.face_count;
        if (passes_light)
            w->clear_meshes[w->clear_mesh_count++] = k;
    }
    return true;
}

bool world_init(struct world *w, const struct scene *s, char *err, size_t err_size) {
    return init(w, s, true, err, err_size);
}

bool world_init_for_structure(struct world *w, const struct scene *s, char *err, size_t err_size) {
    return init(w, s, false, err, err_size);
}

void world_free(struct world *w) {
    free(w->mesh_bounds);
    free(w->mesh_first_face);
    free(w->clear_meshes);
    w->mesh_bounds = NULL;
    w->mesh_first_face = NULL;
    w->clear_meshes = NULL;
    w->clear_mesh_count = 0;
}

/* The object a face of the acceleration structure belongs to: the `triangle` directives come first,
 * then the faces of each mesh in order. Stores in *local the face's index within its mesh (or among the
 * triangle lines). */
static int accel_face_object(const struct world *w, uint32_t face, int *local) {
    *local = (int)face;
    if (face < w->triangles.count)
        return w->triangles.first_object + (int)face;
    /* The first mesh whose faces end after `face`, found by halving: mesh_first_face only ever grows, and a
     * scene may hold a hundred thousand meshes, so a look at each would cost every hit that much. */
    const struct scene *s = w->scene;
    size_t low = 0, high = s->mesh_count;
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (face < w->mesh_first_face[middle + 1])
            high = middle;
        else
            low = middle + 1;
    }
    if (low == s->mesh_count)
        return -1; /* not reached: the structure holds only these faces */
    *local = (int)(face - w->mesh_first_face[low]);
    return world_mesh_object_number(s, low);
}

/* Triangles through the acceleration structure: one query replaces all triangle and mesh loops. */
static bool accel_closest(const struct world *w, const ray *r, double t_min, struct hit *h) {
    const struct world_accel *a = w->accel;
    double t;
    uint32_t face;
    if (!a->closest(a->structure, r, t_min, h->t, &t, &face))
        return false;
    const vec3 *v = a->triangles->vertices;
    const uint32_t *corner = a->triangles->faces[face].v;
    h->t = t;
    h->normal = triangle_normal(v[corner[0]], v[corner[1]], v[corner[2]]);
    h->material = a->materials[face];
    h->object = accel_face_object(w, face, &h->face);
    return true;
}

/* Finds the nearest hit among one kind's shapes; the kind leaves the index within its array in
 * h->object, which becomes the object's number. */
static bool closest_of_kind(const struct world_shapes *k, const ray *r, double t_min, struct hit *h) {
    if (k->count == 0 || !k->kind->closest(k->items, k->count, r, t_min, h))
        return false;
    h->face = k->kind->syntax == &triangle_syntax ? h->object : -1; /* the line's index among them */
    h->object += k->first_object;
    return true;
}

/* The triangles: the `triangle` directives and each mesh behind its bounding box, or the structure.
 * Sets h->object to the number of the object that replaced the hit. */
static bool closest_triangle(const struct world *w, const ray *r, double t_min, struct hit *h) {
    const struct scene *s = w->scene;
    if (w->accel != NULL)
        return accel_closest(w, r, t_min, h);
    bool found = closest_of_kind(&w->triangles, r, t_min, h);
    vec3 inv_direction = aabb_inverse_direction(r->direction);
    for (size_t k = 0; k < s->mesh_count; k++) {
        const struct mesh *m = &s->meshes[k].mesh;
        if (!aabb_hit(&w->mesh_bounds[k], r->origin, inv_direction, t_min, h->t, NULL)) {
            stats_thread.triangle_tests_culled += m->face_count;
        } else if (triangle_mesh_closest(m, s->meshes[k].material, r, t_min, h)) {
            h->object = world_mesh_object_number(s, k); /* a whole mesh is one object */
            found = true;
        }
    }
    return found;
}

bool world_closest(const struct world *w, const ray *r, double t_min, struct hit *h) {
    bool found = false;
    for (size_t k = 0; k < w->bounded_count; k++)
        found |= closest_of_kind(&w->bounded[k], r, t_min, h);
    found |= closest_triangle(w, r, t_min, h);
    for (size_t k = 0; k < w->unbounded_count; k++)
        found |= closest_of_kind(&w->unbounded[k], r, t_min, h);
    if (w->instances != NULL) /* chapter 16 */
        found |= w->instances->closest(w->instances->structure, r, t_min, w->time, h);
    return found;
}

/* ---- all crossings, for shadows ---------------------------------------------------------------- */

/* Passes each triangle hit found by the acceleration structure on with its material. */
struct accel_visit {
    const struct world_accel *accel;
    world_crossing_visitor visit;
    void *context;
    bool stopped; /* the visitor returned false */
};

static bool visit_accel_face(void *context, double t, uint32_t face) {
    struct accel_visit *v = context;
    v->stopped = !v->visit(v->context, t, v->accel->materials[face]);
    return !v->stopped;
}

/* The crossings of one kind's shapes; returns false if the visitor asked to stop. */
static bool cross_kind(const struct world_shapes *k, const ray *r, double t_min, double t_max,
                       world_crossing_visitor visit, void *context) {
    return k->count == 0 || k->kind->crossings(k->items, k->count, r, t_min, t_max, visit, context);
}

/* The crossings of the triangles: the `triangle` directives and each mesh behind its bounding box, or
 * the structure's. Returns false if the visitor asked to stop. */
static bool cross_triangles(const struct world *w, const ray *r, double t_min, double t_max,
                            world_crossing_visitor visit, void *context) {
    const struct scene *s = w->scene;
    if (w->accel != NULL) {
        struct accel_visit forward = {w->accel, visit, context, false};
        w->accel->for_each_hit(w->accel->structure, r, t_min, t_max, visit_accel_face, &forward);
        return !forward.stopped;
    }
    if (!cross_kind(&w->triangles, r, t_min, t_max, visit, context))
        return false;
    struct triangle_ray prepared = triangle_ray_make(r); /* once for every mesh triangle below */
    double t, u, v;
    vec3 inv_direction = aabb_inverse_direction(r->direction);
    for (size_t k = 0; k < s->mesh_count; k++) {
        const struct mesh *m = &s->meshes[k].mesh;
        if (!aabb_hit(&w->mesh_bounds[k], r->origin, inv_direction, t_min, t_max, NULL)) {
            stats_thread.triangle_tests_culled += m->face_count;
            continue;
        }
        for (size_t f = 0; f < m->face_count; f++) {
            const uint32_t *corner = m->faces[f].v;
            if (triangle_intersect_prepared(m->vertices[corner[0]], m->vertices[corner[1]], m->vertices[corner[2]],
                                            &prepared, t_min, t_max, &t, &u, &v) &&
                !visit(context, t, s->meshes[k].material))
                return false;
        }
    }
    return true;
}

void world_for_each_crossing(const struct world *w, const ray *r, double t_min, double t_max,
                             world_crossing_visitor visit, void *context) {
    for (size_t k = 0; k < w->bounded_count; k++)
        if (!cross_kind(&w->bounded[k], r, t_min, t_max, visit, context))
            return;
    if (!cross_triangles(w, r, t_min, t_max, visit, context))
        return;
    for (size_t k = 0; k < w->unbounded_count; k++)
        if (!cross_kind(&w->unbounded[k], r, t_min, t_max, visit, context))
            return;
    if (w->instances != NULL) /* chapter 16 */
        w->instances->for_each_crossing(w->instances->structure, r, t_min, t_max, w->time, visit, context);
}

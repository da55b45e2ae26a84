/* world.c: nearest-hit and all-crossings queries over every shape of a scene (chapter 5).
 *
 * Without an acceleration structure, each mesh is tested behind its bounding box; a ray that misses
 * the box adds the mesh's face count to stats_thread.triangle_tests_culled, the triangle tests the box
 * saved. With one (chapters 9 and 10), the structure counts its own work and nothing is culled here. */
#include "world.h"

#include <stdio.h>
#include <stdlib.h>

#include "stats.h"

struct aabb world_mesh_bounds(const struct mesh *m) {
    struct aabb bounds = aabb_empty();
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *corner = m->faces[k].v;
        bounds = aabb_union(bounds, aabb_of_triangle(m->vertices[corner[0]], m->vertices[corner[1]],
                                                     m->vertices[corner[2]]));
    }
    return bounds;
}

/* Where a kind of shape the scene has comes in the search: 0 for shapes with a bounding box (spheres,
 * boxes: few, and a near hit shortens the ray before the meshes' boxes are tested), 1 for the
 * triangles, 2 for shapes without bounds (planes), which no box can turn away. */
static int search_rank(const struct scene *s, size_t kind) {
    if (kind == SHAPE_TRIANGLES)
        return 1;
    vec3 min, max;
    return shape_kinds[kind].behaviour->bounds(s->shapes[kind].items, &min, &max) ? 0 : 2;
}

bool world_init(struct world *w, const struct scene *s, char *err, size_t err_size) {
    w->scene = s;
    w->accel = NULL;
    w->mesh_bounds = NULL;
    for (size_t kind = 0; kind < SHAPE_KIND_COUNT; kind++)
        if (s->shapes[kind].count > 0 && shape_kinds[kind].behaviour == NULL) {
            snprintf(err, err_size, "%s: this program does not link the code of %s (add its module to the "
                     "chapter's MODULES_NN in the Makefile)", s->path, shape_kinds[kind].plural);
            return false;
        }
    w->kind_count = 0;
    for (int rank = 0; rank <= 2; rank++)
        for (size_t kind = 0; kind < SHAPE_KIND_COUNT; kind++) {
            if ((kind != SHAPE_TRIANGLES && s->shapes[kind].count == 0) || search_rank(s, kind) != rank)
                continue;
            const struct shape_behaviour *b = kind == SHAPE_TRIANGLES ? NULL : shape_kinds[kind].behaviour;
            w->kinds[w->kind_count++] = (struct world_kind){kind, s->shapes[kind].items, s->shapes[kind].count,
                                                            b != NULL ? b->closest : NULL,
                                                            b != NULL ? b->crossings : NULL};
        }
    w->mesh_bounds = calloc(s->mesh_count + 1, sizeof *w->mesh_bounds);
    if (w->mesh_bounds == NULL) {
        snprintf(err, err_size, "out of memory");
        return false;
    }
    for (size_t k = 0; k < s->mesh_count; k++)
        w->mesh_bounds[k] = world_mesh_bounds(&s->meshes[k].mesh);
    return true;
}

void world_free(struct world *w) {
    free(w->mesh_bounds);
    w->mesh_bounds = NULL;
}

void *world_create(struct scene *s, char *err, size_t err_size) {
    struct world *w = malloc(sizeof *w);
    if (w == NULL) {
        snprintf(err, err_size, "out of memory");
        return NULL;
    }
    if (!world_init(w, s, err, err_size)) {
        free(w);
        return NULL;
    }
    return w;
}

void world_destroy(void *world) {
    world_free(world);
    free(world);
}

int world_shape_object_number(const struct scene *s, size_t kind, size_t index) {
    size_t number = index;
    for (size_t before = 0; before < kind; before++)
        number += s->shapes[before].count;
    return (int)number;
}

int world_object_number(const struct scene *s, enum world_object_kind kind, size_t index) {
    switch (kind) {
    case WORLD_SPHERE: return world_shape_object_number(s, SHAPE_SPHERES, index);
    case WORLD_BOX: return world_shape_object_number(s, SHAPE_BOXES, index);
    case WORLD_TRIANGLE: return world_shape_object_number(s, SHAPE_TRIANGLES, index);
    case WORLD_PLANE: return world_shape_object_number(s, SHAPE_PLANES, index);
    case WORLD_MESH: break;
    }
    return world_shape_object_number(s, SHAPE_KIND_COUNT, index); /* the meshes come after every shape */
}

/* The object a face of the acceleration structure belongs to: the `triangle` directives come first,
 * then the faces of each mesh in order. */
static int accel_face_object(const struct scene *s, uint32_t face) {
    if (face < s->triangle_count)
        return world_object_number(s, WORLD_TRIANGLE, face);
    size_t first = s->triangle_count;
    for (size_t k = 0; k < s->mesh_count; k++) {
        first += s->meshes[k].mesh.face_count;
        if (face < first)
            return world_object_number(s, WORLD_MESH, k);
    }
    return -1; /* not reached: the structure holds only these faces */
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
    h->object = accel_face_object(w->scene, face);
    return true;
}

/* The triangles: the `triangle` directives and each mesh behind its bounding box, or the structure.
 * Sets h->object to the number of the object that replaced the hit. */
static bool closest_triangle(const struct world *w, const ray *r, double t_min, struct hit *h) {
    const struct scene *s = w->scene;
    if (w->accel != NULL)
        return accel_closest(w, r, t_min, h);
    bool found = triangle_closest(s->triangles, s->triangle_count, r, t_min, h);
    if (found)
        h->object = world_object_number(s, WORLD_TRIANGLE, (size_t)h->object);
    vec3 inv_direction = aabb_inverse_direction(r->direction);
    for (size_t k = 0; k < s->mesh_count; k++) {
        const struct mesh *m = &s->meshes[k].mesh;
        if (!aabb_hit(&w->mesh_bounds[k], r->origin, inv_direction, t_min, h->t, NULL)) {
            stats_thread.triangle_tests_culled += m->face_count;
        } else if (triangle_mesh_closest(m, s->meshes[k].material, r, t_min, h)) {
            h->object = world_object_number(s, WORLD_MESH, k); /* a whole mesh is one object */
            found = true;
        }
    }
    return found;
}

bool world_closest(const struct world *w, const ray *r, double t_min, struct hit *h) {
    bool found = false;
    for (const struct world_kind *k = w->kinds; k < w->kinds + w->kind_count; k++) {
        if (k->closest == NULL) {
            found |= closest_triangle(w, r, t_min, h);
        } else if (k->closest(k->items, k->count, r, t_min, h)) {
            /* A kind's closest leaves the index within its array; the world numbers every object. */
            h->object = world_shape_object_number(w->scene, k->kind, (size_t)h->object);
            found = true;
        }
    }
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
    if (!shape_kinds[SHAPE_TRIANGLES].behaviour->crossings(s->triangles, s->triangle_count, r, t_min, t_max,
                                                           visit, context))
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
    for (const struct world_kind *k = w->kinds; k < w->kinds + w->kind_count; k++) {
        bool go_on;
        if (k->crossings == NULL)
            go_on = cross_triangles(w, r, t_min, t_max, visit, context);
        else
            go_on = k->crossings(k->items, k->count, r, t_min, t_max, visit, context);
        if (!go_on)
            return;
    }
}

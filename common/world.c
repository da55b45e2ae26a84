/* world.c: nearest-hit and all-crossings queries over every shape of a scene (chapter 5).
 *
 * Without an acceleration structure, each mesh is tested behind its bounding box; a ray that misses
 * the box adds the mesh's face count to stats_thread.triangle_tests_culled, the triangle tests the box
 * saved. With one (chapters 9 and 10), the structure counts its own work and nothing is culled here. */
#include "world.h"

#include <stdio.h>
#include <stdlib.h>

#include "box.h"
#include "plane.h"
#include "sphere.h"
#include "stats.h"
#include "triangle.h"

struct aabb world_mesh_bounds(const struct mesh *m) {
    struct aabb bounds = aabb_empty();
    for (size_t k = 0; k < m->face_count; k++) {
        const uint32_t *corner = m->faces[k].v;
        bounds = aabb_union(bounds, aabb_of_triangle(m->vertices[corner[0]], m->vertices[corner[1]],
                                                     m->vertices[corner[2]]));
    }
    return bounds;
}

bool world_init(struct world *w, const struct scene *s, char *err, size_t err_size) {
    w->scene = s;
    w->accel = NULL;
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

int world_object_number(const struct scene *s, enum world_object_kind kind, size_t index) {
    size_t before[] = {0, s->sphere_count, s->box_count, s->triangle_count, s->mesh_count};
    size_t number = index;
    for (int k = 0; k <= (int)kind; k++)
        number += before[k];
    return (int)number;
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

/* Sets h->object when `found`: the shape just tested replaced the hit. */
static bool note_object(bool found, struct hit *h, const struct scene *s, enum world_object_kind kind, size_t k) {
    if (found)
        h->object = world_object_number(s, kind, k);
    return found;
}

bool world_closest(const struct world *w, const ray *r, double t_min, struct hit *h) {
    const struct scene *s = w->scene;
    bool found = false;
    for (size_t k = 0; k < s->sphere_count; k++)
        found |= note_object(sphere_closest(&s->spheres[k], 1, r, t_min, h), h, s, WORLD_SPHERE, k);
    for (size_t k = 0; k < s->box_count; k++)
        found |= note_object(box_closest(&s->boxes[k], 1, r, t_min, h), h, s, WORLD_BOX, k);
    if (w->accel != NULL) {
        found |= accel_closest(w, r, t_min, h);
    } else {
        for (size_t k = 0; k < s->triangle_count; k++)
            found |= note_object(triangle_closest(&s->triangles[k], 1, r, t_min, h), h, s, WORLD_TRIANGLE, k);
        vec3 inv_direction = aabb_inverse_direction(r->direction);
        for (size_t k = 0; k < s->mesh_count; k++) {
            const struct mesh *m = &s->meshes[k].mesh;
            if (aabb_hit(&w->mesh_bounds[k], r->origin, inv_direction, t_min, h->t, NULL))
                found |= note_object(triangle_mesh_closest(m, s->meshes[k].material, r, t_min, h), h, s, WORLD_MESH, k);
            else
                stats_thread.triangle_tests_culled += m->face_count;
        }
    }
    for (size_t k = 0; k < s->plane_count; k++)
        found |= note_object(plane_closest(&s->planes[k], 1, r, t_min, h), h, s, WORLD_PLANE, k);
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

/* Returns false if the visitor asked to stop. */
static bool cross_spheres(const struct scene *s, const ray *r, double t_min, double t_max,
                          world_crossing_visitor visit, void *context) {
    for (size_t k = 0; k < s->sphere_count; k++) {
        double t_near, t_far;
        if (!sphere_intersect(&s->spheres[k], r, t_min, t_max, &t_near))
            continue;
        if (!visit(context, t_near, s->spheres[k].material))
            return false;
        if (sphere_intersect(&s->spheres[k], r, t_near, t_max, &t_far) &&
            !visit(context, t_far, s->spheres[k].material))
            return false;
    }
    return true;
}

static bool cross_boxes(const struct scene *s, const ray *r, double t_min, double t_max,
                        world_crossing_visitor visit, void *context) {
    for (size_t k = 0; k < s->box_count; k++) {
        double t_near, t_far;
        if (!box_intersect(&s->boxes[k], r, t_min, t_max, &t_near))
            continue;
        if (!visit(context, t_near, s->boxes[k].material))
            return false;
        if (box_intersect(&s->boxes[k], r, t_near, t_max, &t_far) && !visit(context, t_far, s->boxes[k].material))
            return false;
    }
    return true;
}

static bool cross_triangles(const struct world *w, const ray *r, double t_min, double t_max,
                            world_crossing_visitor visit, void *context) {
    const struct scene *s = w->scene;
    struct triangle_ray prepared = triangle_ray_make(r); /* once for every triangle below */
    double t, u, v;
    for (size_t k = 0; k < s->triangle_count; k++) {
        const struct triangle *tri = &s->triangles[k];
        if (triangle_intersect_prepared(tri->a, tri->b, tri->c, &prepared, t_min, t_max, &t, &u, &v) &&
            !visit(context, t, tri->material))
            return false;
    }
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
    const struct scene *s = w->scene;
    if (!cross_spheres(s, r, t_min, t_max, visit, context) || !cross_boxes(s, r, t_min, t_max, visit, context))
        return;
    if (w->accel != NULL) {
        struct accel_visit forward = {w->accel, visit, context, false};
        w->accel->for_each_hit(w->accel->structure, r, t_min, t_max, visit_accel_face, &forward);
        if (forward.stopped)
            return;
    } else if (!cross_triangles(w, r, t_min, t_max, visit, context)) {
        return;
    }
    for (size_t k = 0; k < s->plane_count; k++) {
        double t;
        if (plane_intersect(&s->planes[k], r, t_min, t_max, &t) && !visit(context, t, s->planes[k].material))
            return;
    }
}

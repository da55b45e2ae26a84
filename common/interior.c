/* interior.c: the ray's interior list and POV-Ray 3.7's crossing rule (chapter 8). */
#include "interior.h"

#include "stats.h"
#include "triangle.h"

bool interior_contains(const struct interior_list *list, int object) {
    for (int k = 0; k < list->count; k++)
        if (list->object[k] == object)
            return true;
    return false;
}

/* Removes entry k, keeping the order of the others. */
static void remove_at(struct interior_list *list, int k) {
    for (int j = k + 1; j < list->count; j++) {
        list->object[j - 1] = list->object[j];
        list->ior[j - 1] = list->ior[j];
    }
    list->count--;
}

static void push(struct interior_list *list, int object, double ior) {
    if (list->count == RAY_INTERIOR_CAPACITY) {
        stats_thread.interior_overflows++;
        return;
    }
    list->object[list->count] = object;
    list->ior[list->count] = ior;
    list->count++;
}

double interior_cross(struct interior_list *list, int object, double ior) {
    if (list->count == 0) { /* from the air into the object */
        push(list, object, ior);
        return 1.0 / ior;
    }
    int top = list->count - 1;
    if (list->object[top] == object) { /* out of the innermost object, into the one around it or air */
        remove_at(list, top);
        return list->count == 0 ? ior : ior / list->ior[list->count - 1];
    }
    for (int k = 0; k < top; k++) {
        if (list->object[k] == object) { /* out of an overlap: it belonged to the object entered last */
            remove_at(list, k);
            return 1.0;
        }
    }
    double from = list->ior[top]; /* into a new object from the innermost one */
    push(list, object, ior);
    return from / ior;
}

/* ---- a camera inside glass --------------------------------------------------------------------- */

static bool is_transparent(const struct scene *s, int material) {
    return material_passes_light(&s->materials[material]);
}

/* Pushes every transparent shape of one kind that contains `point`. A kind without an inside (a
 * single triangle) adds nothing. */
static void add_containing(struct interior_list *list, const struct scene *s, const struct world_shapes *k,
                           vec3 point) {
    if (k->count == 0 || k->kind->contains == NULL)
        return;
    const struct shape_syntax *syntax = k->kind->syntax;
    for (size_t n = 0; n < k->count; n++) {
        const void *item = shape_item(syntax, k->items, n);
        int material = shape_material(syntax, item);
        if (is_transparent(s, material) && k->kind->contains(item, point))
            push(list, k->first_object + (int)n, s->materials[material].ior);
    }
}

/* Returns true when p is in box b or on its surface. */
static bool aabb_contains(const struct aabb *b, vec3 p) {
    return p.x >= b->min.x && p.x <= b->max.x && p.y >= b->min.y && p.y <= b->max.y && p.z >= b->min.z &&
           p.z <= b->max.z;
}

bool interior_mesh_contains(const struct mesh *m, vec3 point) {
    ray up = {point, vec3_make(0, 0, 1)};
    int crossings = 0;
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *c = m->faces[f].v;
        double t, u, v;
        if (triangle_intersect(m->vertices[c[0]], m->vertices[c[1]], m->vertices[c[2]], &up, 0.0, INFINITY, &t, &u, &v))
            crossings++;
    }
    return crossings % 2 == 1;
}

/* What push_instance needs: the list, the scene, and where the instances' entries begin. */
struct instance_search {
    struct interior_list *list;
    const struct scene *s;
    int first; /* the list's first entry from an instance */
};

/* Pushes a transparent instance that holds the point, keeping the instances' entries in the order of
 * their lines (increasing object number), whatever order the top level finds them in. */
static bool push_instance(void *context, int object, int material) {
    struct instance_search *q = context;
    struct interior_list *list = q->list;
    push(list, object, q->s->materials[material].ior);
    for (int k = list->count - 1; k > q->first && list->object[k - 1] > list->object[k]; k--) {
        int other = list->object[k - 1];
        double ior = list->ior[k - 1];
        list->object[k - 1] = list->object[k];
        list->ior[k - 1] = list->ior[k];
        list->object[k] = other;
        list->ior[k] = ior;
    }
    return true;
}

struct interior_list interior_at_point(const struct world *w, vec3 point) {
    const struct scene *s = w->scene;
    struct interior_list list = interior_empty();
    for (size_t k = 0; k < w->bounded_count; k++)
        add_containing(&list, s, &w->bounded[k], point);
    add_containing(&list, s, &w->triangles, point);
    for (size_t n = 0; n < w->clear_mesh_count; n++) { /* the meshes that let light through */
        size_t k = w->clear_meshes[n];
        const struct scene_mesh *m = &s->meshes[k];
        if (aabb_contains(&w->mesh_bounds[k], point) && interior_mesh_contains(&m->mesh, point))
            push(&list, world_mesh_object_number(s, k), s->materials[m->material].ior);
    }
    for (size_t k = 0; k < w->unbounded_count; k++)
        add_containing(&list, s, &w->unbounded[k], point);
    if (w->instances != NULL) { /* chapter 16's, last, as world_closest searches them */
        struct instance_search q = {&list, s, list.count};
        w->instances->for_each_containing(w->instances->structure, point, w->time, push_instance, &q);
    }
    return list;
}

/* emitter.c: gathering the emitting surfaces and choosing points on them (chapter 15). */
#include "emitter.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "box.h"
#include "plane.h"
#include "sampling.h"
#include "sphere.h"
#include "triangle.h"

double emitter_power(vec3 radiance) { return (radiance.x + radiance.y + radiance.z) / 3.0; }

static bool emits(const struct material *m) { return emitter_power(m->emission) > 0.0; }

int emitter_add_area_lights(struct scene *s, char *err, size_t err_size) {
    size_t areas = 0;
    for (size_t k = 0; k < s->light_count; k++)
        areas += area_light_is_area(&s->lights[k].area);
    int points = (int)(s->light_count - areas);
    if (areas == 0)
        return points;
    struct shape_list *list = NULL;
    for (size_t k = 0; k < s->kind_count; k++)
        if (s->shapes[k].syntax == &triangle_syntax)
            list = &s->shapes[k];
    struct material *materials = realloc(s->materials, (s->material_count + areas) * sizeof *materials);
    if (materials != NULL)
        s->materials = materials;
    struct triangle *triangles = list == NULL ? NULL : realloc(list->items, (list->count + 2 * areas) * sizeof *triangles);
    if (materials == NULL || triangles == NULL) {
        snprintf(err, err_size, "out of memory");
        return -1;
    }
    list->items = triangles;
    for (size_t k = 0, n = 0; k < s->light_count; k++) {
        const struct light *l = &s->lights[k];
        if (!area_light_is_area(&l->area))
            continue;
        int material = (int)s->material_count++;
        s->materials[material] = (struct material){.colour = {0, 0, 0}, .phong_size = 1.0, .ior = 1.0, .pigment = -1,
                                                   .emission = l->colour};
        snprintf(s->materials[material].name, sizeof s->materials[material].name, "area light %zu", ++n);
        vec3 h1 = vec3_scale(l->area.axis1, 0.5), h2 = vec3_scale(l->area.axis2, 0.5);
        vec3 c00 = vec3_sub(vec3_sub(l->position, h1), h2), c10 = vec3_sub(vec3_add(l->position, h1), h2);
        vec3 c11 = vec3_add(vec3_add(l->position, h1), h2), c01 = vec3_add(vec3_sub(l->position, h1), h2);
        triangles[list->count++] = (struct triangle){c00, c10, c11, material};
        triangles[list->count++] = (struct triangle){c00, c11, c01, material};
    }
    return points;
}

/* Appends one piece, growing the array as needed (capacity in *capacity). */
static bool add(struct emitter_list *list, size_t *capacity, struct emitter e) {
    if (list->count == *capacity) {
        size_t bigger = *capacity == 0 ? 16 : 2 * *capacity;
        struct emitter *items = realloc(list->items, bigger * sizeof *items);
        if (items == NULL)
            return false;
        list->items = items;
        *capacity = bigger;
    }
    list->items[list->count++] = e;
    return true;
}

static struct emitter triangle_piece(vec3 a, vec3 b, vec3 c, vec3 radiance) {
    vec3 e1 = vec3_sub(b, a), e2 = vec3_sub(c, a);
    return (struct emitter){.shape = EMITTER_TRIANGLE, .a = a, .e1 = e1, .e2 = e2,
                            .area = 0.5 * vec3_length(vec3_cross(e1, e2)), .radiance = radiance};
}

/* The twelve triangles of a box's faces. */
static bool add_box(struct emitter_list *list, size_t *capacity, const struct box *b, vec3 radiance) {
    for (int axis = 0; axis < 3; axis++) {
        int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; side++) {
            double corner[4][3];
            for (int k = 0; k < 4; k++) {
                corner[k][axis] = side == 0 ? vec3_axis(b->min, axis) : vec3_axis(b->max, axis);
                corner[k][u] = (k == 1 || k == 2) ? vec3_axis(b->max, u) : vec3_axis(b->min, u);
                corner[k][v] = k >= 2 ? vec3_axis(b->max, v) : vec3_axis(b->min, v);
            }
            vec3 p[4];
            for (int k = 0; k < 4; k++)
                p[k] = vec3_make(corner[k][0], corner[k][1], corner[k][2]);
            if (!add(list, capacity, triangle_piece(p[0], p[1], p[2], radiance)) ||
                !add(list, capacity, triangle_piece(p[0], p[2], p[3], radiance)))
                return false;
        }
    }
    return true;
}

bool emitter_list_build(struct emitter_list *list, const struct accel_world *w, char *err, size_t err_size) {
    memset(list, 0, sizeof *list);
    const struct scene *s = w->world.scene;
    size_t capacity = 0;
    bool ok = true;
    const struct mesh *all = &w->triangles;
    for (size_t f = 0; ok && f < all->face_count; f++) {
        const struct material *m = &s->materials[w->materials[f]];
        const uint32_t *v = all->faces[f].v;
        if (emits(m))
            ok = add(list, &capacity, triangle_piece(all->vertices[v[0]], all->vertices[v[1]], all->vertices[v[2]],
                                                     m->emission));
    }
    const struct shape_list *spheres = scene_shapes(s, &sphere_syntax);
    for (size_t k = 0; ok && spheres != NULL && spheres->kind != NULL && k < spheres->count; k++) {
        const struct sphere *sp = &((const struct sphere *)spheres->items)[k];
        const struct material *m = &s->materials[sp->material];
        if (emits(m))
            ok = add(list, &capacity, (struct emitter){.shape = EMITTER_SPHERE, .centre = sp->centre, .radius = sp->radius,
                                                       .area = 4.0 * M_PI * sp->radius * sp->radius,
                                                       .radiance = m->emission});
    }
    const struct shape_list *boxes = scene_shapes(s, &box_syntax);
    for (size_t k = 0; ok && boxes != NULL && boxes->kind != NULL && k < boxes->count; k++) {
        const struct box *b = &((const struct box *)boxes->items)[k];
        if (emits(&s->materials[b->material]))
            ok = add_box(list, &capacity, b, s->materials[b->material].emission);
    }
    const struct shape_list *planes = scene_shapes(s, &plane_syntax);
    for (size_t k = 0; ok && planes != NULL && planes->kind != NULL && k < planes->count; k++) {
        const struct plane *p = &((const struct plane *)planes->items)[k];
        if (emits(&s->materials[p->material])) {
            /* shapes keep no line of their own: the message points at the material's, which gives off the light */
            snprintf(err, err_size,
                     "%s:%d: plane %zu has the emissive material '%s': an infinite surface cannot be an emitter "
                     "(give the emission to a box or triangles)", s->path, s->materials[p->material].line, k + 1,
                     s->materials[p->material].name);
            emitter_list_free(list);
            return false;
        }
    }
    if (ok && list->count > 0)
        ok = (list->cumulative = malloc(list->count * sizeof *list->cumulative)) != NULL;
    if (!ok) {
        emitter_list_free(list);
        snprintf(err, err_size, "out of memory");
        return false;
    }
    double sum = 0.0;
    for (size_t k = 0; k < list->count; k++) {
        sum += list->items[k].area * emitter_power(list->items[k].radiance);
        list->cumulative[k] = sum;
    }
    list->total_power = sum;
    /* A sphere of radius 1e200 would make this sum infinite; the scene reader now refuses such a radius
     * (at most KEY_MAX_COORD, as every coordinate), so this is the last line of defence, not the first. */
    if (!isfinite(sum)) {
        snprintf(err, err_size, "%s: the emitters' total power (emission times area) is beyond double's range: "
                 "an emitter is too large for its emission", s->path);
        emitter_list_free(list);
        return false;
    }
    return true;
}

void emitter_list_free(struct emitter_list *list) {
    free(list->items);
    free(list->cumulative);
    memset(list, 0, sizeof *list);
}

bool emitter_sample(const struct emitter_list *list, double u_pick, double u1, double u2, struct emitter_sample *out) {
    if (list->count == 0 || !(list->total_power > 0.0))
        return false;
    /* The first piece whose cumulative power exceeds u_pick times the total: a binary search. */
    double target = u_pick * list->total_power;
    size_t lo = 0, hi = list->count - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (list->cumulative[mid] > target)
            hi = mid;
        else
            lo = mid + 1;
    }
    const struct emitter *e = &list->items[lo];
    if (e->shape == EMITTER_TRIANGLE) {
        out->point = sampling_triangle(e->a, e->e1, e->e2, u1, u2);
        out->normal = vec3_normalize(vec3_cross(e->e1, e->e2));
    } else {
        out->normal = sampling_sphere_direction(u1, u2);
        out->point = vec3_add_scaled(e->centre, out->normal, e->radius);
    }
    out->radiance = e->radiance;
    out->density = emitter_density(list, e->radiance);
    return true;
}

double emitter_density(const struct emitter_list *list, vec3 radiance) {
    return list->total_power > 0.0 ? emitter_power(radiance) / list->total_power : 0.0;
}

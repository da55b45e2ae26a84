/* accel.c: gathering a scene's triangles and routing the world's queries through a kd-tree (chapter 9). */
#include "accel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"
#include "clock.h"
#include "kdtree.h"
#include "text_escape.h"
#include "triangle.h"

/* Copies every triangle of s into one mesh, with each face's material beside it. A scene whose only
 * triangles are one mesh's has them gathered already: that mesh is used as it is (borrowed from the
 * scene, not copied), which spares copying the large models (a copy of the 350k-triangle teapot's
 * 8 MB took 6 to 25 ms, as the fresh pages came). */
static bool gather_triangles(struct accel_world *w, const struct scene *s) {
    const struct shape_list *lines = scene_shapes(s, &triangle_syntax); /* the `triangle` lines */
    const struct triangle *triangles = lines->items;
    size_t vertices = 3 * lines->count, faces = lines->count;
    for (size_t k = 0; k < s->mesh_count; k++) {
        vertices += s->meshes[k].mesh.vertex_count;
        faces += s->meshes[k].mesh.face_count;
    }
    if (vertices > UINT32_MAX)
        return false;
    struct mesh *all = &w->triangles;
    w->materials = big_alloc((faces + 1) * sizeof *w->materials, true); /* big_alloc.h: 2 MB pages */
    if (w->materials == NULL)
        return false;
    if (lines->count == 0 && s->mesh_count == 1 && faces > 0) {
        *all = s->meshes[0].mesh;
        w->triangles_borrowed = true;
        for (size_t f = 0; f < faces; f++)
            w->materials[f] = s->meshes[0].material;
        return true;
    }
    all->vertices = big_alloc((vertices + 1) * sizeof *all->vertices, true);
    all->faces = big_alloc((faces + 1) * sizeof *all->faces, true);
    if (all->vertices == NULL || all->faces == NULL)
        return false;
    size_t v = 0, f = 0;
    for (size_t k = 0; k < lines->count; k++, f++) {
        const struct triangle *t = &triangles[k];
        all->vertices[v] = t->a;
        all->vertices[v + 1] = t->b;
        all->vertices[v + 2] = t->c;
        all->faces[f] = (struct mesh_face){{(uint32_t)v, (uint32_t)v + 1, (uint32_t)v + 2}};
        w->materials[f] = t->material;
        v += 3;
    }
    for (size_t k = 0; k < s->mesh_count; k++) {
        const struct mesh *m = &s->meshes[k].mesh;
        memcpy(all->vertices + v, m->vertices, m->vertex_count * sizeof *m->vertices);
        for (size_t j = 0; j < m->face_count; j++, f++) {
            for (int c = 0; c < 3; c++)
                all->faces[f].v[c] = m->faces[j].v[c] + (uint32_t)v;
            w->materials[f] = s->meshes[k].material;
        }
        v += m->vertex_count;
    }
    all->vertex_count = v;
    all->face_count = f;
    return true;
}

bool accel_world_init(struct accel_world *w, const struct scene *s, bool structure_follows, char *err,
                      size_t err_size) {
    memset(w, 0, sizeof *w);
    if (!(structure_follows ? world_init_for_structure : world_init)(&w->world, s, err, err_size))
        return false;
    if (!gather_triangles(w, s)) {
        accel_world_free(w);
        snprintf(err, err_size, "out of memory");
        return false;
    }
    w->accel.triangles = &w->triangles;
    w->accel.materials = w->materials;
    w->summary.name = "none (brute force behind per-mesh boxes)";
    return true;
}

void accel_world_free(struct accel_world *w) {
    if (w->structure != NULL && w->free_structure != NULL)
        w->free_structure(w->structure);
    world_free(&w->world);
    if (!w->triangles_borrowed)
        mesh_free(&w->triangles);
    free(w->materials);
    memset(w, 0, sizeof *w);
}

struct accel_world *accel_world_create(struct scene *s, const struct accel_choice *c, char *err, size_t err_size) {
    struct accel_world *w = malloc(sizeof *w);
    if (w == NULL || !accel_world_init(w, s, c->kind != ACCEL_NONE, err, err_size)) {
        if (w == NULL)
            snprintf(err, err_size, "out of memory");
        free(w);
        return NULL;
    }
    if (c->kind == ACCEL_KDTREE && !accel_world_use_kdtree(w, c->sah ? KD_SPLIT_SAH : KD_SPLIT_SEED, err, err_size)) {
        accel_world_destroy(w);
        return NULL;
    }
    return w;
}

void accel_world_destroy(void *world) {
    accel_world_free(world);
    free(world);
}

/* The kd-tree's queries in the shape the world expects. */
static bool kdtree_closest_any(const void *tree, const ray *r, double t_min, double t_max, double *t,
                               uint32_t *face) {
    return kdtree_closest(tree, r, t_min, t_max, t, face);
}

static bool kdtree_occluded_any(const void *tree, const ray *r, double t_min, double t_max) {
    return kdtree_occluded(tree, r, t_min, t_max);
}

static void kdtree_for_each_hit_any(const void *tree, const ray *r, double t_min, double t_max,
                                    world_hit_visitor visit, void *context) {
    kdtree_for_each_hit(tree, r, t_min, t_max, visit, context);
}

static void kdtree_free_any(void *tree) { kdtree_free(tree); }

/* The message for --split given with --accel none; returns accel_parse_option's -1. */
static int split_without_structure(void) {
    fprintf(stderr, "--split chooses how a structure is built, and --accel none builds none: give one or the other\n");
    return -1;
}

int accel_parse_option(struct accel_choice *c, unsigned allowed, const char *option, const char *value) {
    static const char *kinds[] = {"none", "kdtree", "bvh"};
    if (strcmp(option, "--accel") == 0) {
        for (int k = 0; k < 3; k++)
            if ((allowed & (1u << k)) && value != NULL && strcmp(value, kinds[k]) == 0) {
                c->kind = (enum accel_kind)k;
                return c->kind == ACCEL_NONE && c->split_given ? split_without_structure() : 2;
            }
        fprintf(stderr, "--accel needs one of:");
        for (int k = 0; k < 3; k++)
            if (allowed & (1u << k))
                fprintf(stderr, " %s", kinds[k]);
        char got[256];
        text_escape(value != NULL ? value : "", got, sizeof got); /* the value comes from the command line */
        fprintf(stderr, "; got '%s'\n", got);
        return -1;
    }
    if (strcmp(option, "--split") == 0) {
        if (value != NULL && (strcmp(value, "sah") == 0 || strcmp(value, "seed") == 0)) {
            c->sah = strcmp(value, "sah") == 0;
            c->split_given = true;
            return c->kind == ACCEL_NONE ? split_without_structure() : 2;
        }
        char got[256];
        text_escape(value != NULL ? value : "", got, sizeof got);
        fprintf(stderr, "--split needs 'sah' or 'seed' (the seed's rule), got '%s'\n", got);
        return -1;
    }
    return 0;
}

void accel_report(const struct accel_world *w, const struct stats *total, bool detailed) {
    const struct accel_summary *a = &w->summary;
    uint64_t rays = total->primary_rays + total->shadow_rays + total->reflected_rays + total->refracted_rays;
    if (w->triangles.face_count == 0) { /* an empty structure: its build time would be the clock's noise */
        printf("acceleration: none needed, the scene has no triangles\n");
        return;
    }
    printf("acceleration: %s over %zu triangles\n", a->name, w->triangles.face_count);
    if (w->structure == NULL)
        return;
    printf("  build            %12.1f ms\n", a->build_ms);
    if (!detailed)
        return;
    printf("  nodes            %12zu (%zu leaves, depth %zu)\n", a->nodes, a->leaves, a->max_depth);
    if (rays == 0)
        return;
    printf("  per ray (all kinds): %.2f node visits, %.2f triangle tests\n",
           (double)total->node_visits / (double)rays, (double)total->triangle_tests / (double)rays);
    if (a->sah_cost > 0.0)
        printf("  predicted by the SAH: %.2f per ray crossing the scene's box at random (node visits and\n"
               "  triangle tests weighted by the structure's cost constants)\n", a->sah_cost);
}

bool accel_world_use_kdtree(struct accel_world *w, int split, char *err, size_t err_size) {
    double started = clock_seconds();
    struct kdtree *tree = kdtree_build(&w->triangles, (enum kd_split)split);
    double build_ms = 1e3 * (clock_seconds() - started);
    if (tree == NULL) {
        snprintf(err, err_size, "out of memory building the kd-tree");
        return false;
    }
    struct kdtree_info info;
    kdtree_get_info(tree, &info);
    w->summary = (struct accel_summary){split != KD_SPLIT_SEED ? "kd-tree (SAH)" : "kd-tree (seed's rule)",
                                        build_ms, info.nodes, info.leaves, info.max_depth, info.sah_cost};
    w->structure = tree;
    w->free_structure = kdtree_free_any;
    w->accel.structure = tree;
    w->accel.closest = kdtree_closest_any;
    w->accel.occluded = kdtree_occluded_any;
    w->accel.for_each_hit = kdtree_for_each_hit_any;
    w->world.accel = &w->accel;
    return true;
}

/* world.h: the scene's shapes made ready for ray queries, starting with per-mesh bounding boxes
 * (chapter 5; chapters 9 and 10 plug an acceleration structure in through struct world_accel).
 *
 * Chapters 2 to 4 test every ray against every triangle of every mesh. The first speed-up is the
 * cheapest: a ray that misses a mesh's bounding box cannot hit any of its triangles, so one box test
 * replaces thousands of triangle tests. Planes have no bounding box and are always tested. */
#ifndef WHITTED_WORLD_H
#define WHITTED_WORLD_H

#include <stdbool.h>
#include <stdint.h>

#include "aabb.h"
#include "hit.h"
#include "scene.h"

/* Calls back for one triangle hit (t, face index); returns false to stop the enumeration. */
typedef bool (*world_hit_visitor)(void *context, double t, uint32_t face);

/* An acceleration structure over all triangles of a scene (chapters 9 and 10), seen through its
 * three queries. `triangles` holds every triangle of the scene (the `triangle` directives first, then
 * the faces of each mesh in order) and `materials` the material of each face. */
struct world_accel {
    const void *structure;
    const struct mesh *triangles;
    const int *materials;
    /* nearest face hit with t_min < t < t_max; the lowest face index among equal t */
    bool (*closest)(const void *structure, const ray *r, double t_min, double t_max, double *t, uint32_t *face);
    /* any face hit with t_min < t < t_max */
    bool (*occluded)(const void *structure, const ray *r, double t_min, double t_max);
    /* every face hit with t_min < t < t_max, each once, until visit returns false */
    void (*for_each_hit)(const void *structure, const ray *r, double t_min, double t_max,
                         world_hit_visitor visit, void *context);
};

/* Calls back for one instance (its object number, its material); returns false to stop. */
typedef bool (*world_instance_visitor)(void *context, int object, int material);

/* Instances of objects, each placed by its own transform and perhaps moving (chapter 16; instances.h),
 * seen through three queries at a time on the scene's clock. */
struct world_instances {
    const void *structure;
    /* the nearest instance surface with t_min < t < h->t at clock time `time`, kept in *h as
     * world_closest keeps any hit (world-space normal, the instance's material and object number, the
     * face within its object); returns true when *h was replaced */
    bool (*closest)(const void *structure, const ray *r, double t_min, double time, struct hit *h);
    /* every instance face crossed with t_min < t < t_max at `time`, passed to visit with the instance's
     * material until visit returns false; returns false when it did */
    bool (*for_each_crossing)(const void *structure, const ray *r, double t_min, double t_max, double time,
                              shape_crossing_visitor visit, void *context);
    /* every instance that lets light through (material_passes_light) and whose object holds `point` at
     * `time` (the point carried into its object's space, tested by interior_mesh_contains, interior.h),
     * passed to visit with its object number and material, in no set order, until visit returns false */
    void (*for_each_containing)(const void *structure, vec3 point, double time, world_instance_visitor visit,
                                void *context);
};

/* The shapes of one kind as the world searches them. */
struct world_shapes {
    const struct shape_kind *kind; /* its ray queries (shape.h) */
    const void *items;             /* the scene's array of that kind */
    size_t count;
    int first_object;              /* the object number of items[0] (see world_object_number) */
};

struct world {
    const struct scene *scene;
    struct aabb *mesh_bounds;        /* one box per scene mesh (world_mesh_cull_bounds); owned */
    size_t *mesh_first_face;         /* per scene mesh, and one past the last: the number the structures
                                      * give its first face (the triangle lines come first); owned. Kept
                                      * here because a program may free a mesh once it is gathered
                                      * (chapter 11) */
    size_t *clear_meshes;            /* the numbers of the scene meshes that let light through, in order:
                                      * the only ones whose inside interior.c asks about; owned */
    size_t clear_mesh_count;
    const struct world_accel *accel; /* NULL: triangles by brute force with box culling */
    const struct world_instances *instances; /* chapter 16's instances; NULL: none */
    double time;                     /* the clock time the queries see the instances at (chapter 16): each
                                      * camera sample traces through its own copy of the world */
    /* The kinds of shape the queries visit, in this order: those with bounding boxes (spheres, boxes:
     * few, and a near hit shortens the ray before the meshes' boxes are tested), the triangles with the
     * meshes, then those without bounds (planes), which no box can turn away. Kinds without shapes are
     * left out. */
    struct world_shapes bounded[SCENE_KIND_MAX];
    size_t bounded_count;
    struct world_shapes triangles;   /* the `triangle` lines; count 0 when there are none */
    struct world_shapes unbounded[SCENE_KIND_MAX];
    size_t unbounded_count;
};

/* Makes the world of scene s (meshes already loaded), whose shapes must all be of kinds the program
 * draws (scene_drop_unsupported), and computes the bounding box of every mesh and the number of its
 * first face among all the scene's triangles. Free with world_free.
 * On failure returns false, with nothing to free and the reason in err: "out of memory", or
 * "scene: 2 spheres of no kind ..." for shapes whose list has no kind. */
bool world_init(struct world *w, const struct scene *s, char *err, size_t err_size);

/* world_init for a world whose triangles a structure will answer for (chapter 9 on: accel.c), where a
 * mesh's bounding box is read only to test a point against the inside of a mesh that light passes
 * through (interior.c): only those meshes' boxes are computed, the others left as the box of all
 * space, which nothing reads. The boxes of the 350k-triangle teapot took 5 to 9 ms, one thread. */
bool world_init_for_structure(struct world *w, const struct scene *s, char *err, size_t err_size);

/* Frees what world_init allocated. Safe on a zeroed world. */
void world_free(struct world *w);

/* Returns the bounding box of mesh m (the empty box for a mesh without vertices). */
struct aabb world_mesh_bounds(const struct mesh *m);

/* Returns the box world_init culls m's rays with: world_mesh_bounds(m) grown by triangle_box_pad(m) on
 * every side, since the triangle test rounds and may call a ray a hair outside a face a hit (on the
 * edge of a flat mesh, whose box is flat, the unpadded slab test can miss that ray); all of space when
 * m has a sliver (triangle_is_sliver), whose hits no pad holds. triangle.h states the bound. */
struct aabb world_mesh_cull_bounds(const struct mesh *m);

/* Every object of a scene has a number, kept in struct hit.object (chapter 8's interior list tells
 * objects apart by it): the shapes list by list in the scene's order (scene.h), then the meshes (one
 * number for a whole mesh, which is one object with one inside). */

/* Returns the number of the index-th shape of `list` (one of s's lists). Cannot fail. */
int world_object_number(const struct scene *s, const struct shape_list *list, size_t index);

/* Returns the number of s's index-th mesh. Cannot fail. */
int world_mesh_object_number(const struct scene *s, size_t index);

/* Finds the nearest surface with t_min < t < h->t along r among all shapes, kind by kind in the order
 * of struct world (chapter 16's instances last), and keeps it in *h (with the object's number in h->object).
 * Returns true when *h was replaced. Without w->accel, a mesh whose bounding box r misses within
 * (t_min, h->t) is not tested, and its face count is added to stats_thread.triangle_tests_culled. */
bool world_closest(const struct world *w, const ray *r, double t_min, struct hit *h);

/* Calls visit(context, t, material) for every crossing of a surface by r with t_min < t < t_max: both
 * crossings of a sphere or box, each triangle (an instance's too), each plane. Stops as soon as visit returns false.
 * Used for shadows (chapters 7 and 8). Without w->accel, a mesh whose bounding box r misses within
 * (t_min, t_max) is not tested, and its face count is added to stats_thread.triangle_tests_culled. */
typedef shape_crossing_visitor world_crossing_visitor;
void world_for_each_crossing(const struct world *w, const ray *r, double t_min, double t_max,
                             world_crossing_visitor visit, void *context);

#endif

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

/* One kind of shape the world searches: its array and its queries, looked up once by world_init. */
struct world_kind {
    size_t kind;        /* index into shape_kinds (enum shape_kind_index) */
    const void *items;  /* the scene's array of that kind */
    size_t count;
    /* the kind's behaviour (shape.h); NULL for the triangles, which the world searches itself */
    bool (*closest)(const void *items, size_t count, const ray *r, double t_min, struct hit *h);
    bool (*crossings)(const void *items, size_t count, const ray *r, double t_min, double t_max,
                      shape_crossing_visitor visit, void *context);
};

struct world {
    const struct scene *scene;
    struct aabb *mesh_bounds;        /* one box per scene mesh; owned */
    const struct world_accel *accel; /* NULL: triangles by brute force with box culling */
    /* The kinds of shape the queries visit, in this order: those the scene has and that have bounding
     * boxes, then the triangles (always), then those without bounds. */
    struct world_kind kinds[SHAPE_KIND_COUNT];
    size_t kind_count;
};

/* Computes the bounding box of every mesh of s (meshes already loaded). Returns false and writes
 * "out of memory" into err on failure, or "scene: this program does not link the code of discs ..."
 * when s holds shapes of a kind whose module the program does not link. Free with world_free. */
bool world_init(struct world *w, const struct scene *s, char *err, size_t err_size);

/* Frees what world_init allocated. Safe on a zeroed world. */
void world_free(struct world *w);

/* The same as world_init on a new heap-allocated world, in the shape of struct chapter's prepare:
 * returns the world, or NULL with the reason in err. Free with world_destroy. */
void *world_create(struct scene *s, char *err, size_t err_size);

/* Frees a world made by world_create. */
void world_destroy(void *world);

/* Returns the bounding box of mesh m (the empty box for a mesh without vertices). */
struct aabb world_mesh_bounds(const struct mesh *m);

/* Every object of a scene has a number, kept in struct hit.object (chapter 8's interior list tells
 * objects apart by it): the shapes kind by kind in the order of shape_kinds.h, then the meshes (one
 * number for a whole mesh, which is one object with one inside). */
enum world_object_kind { WORLD_SPHERE, WORLD_BOX, WORLD_TRIANGLE, WORLD_MESH, WORLD_PLANE };

/* Returns the number of the index-th object of the given kind in s. Cannot fail. */
int world_object_number(const struct scene *s, enum world_object_kind kind, size_t index);

/* Returns the number of the index-th shape of kind `kind` (an index into shape_kinds) in s; with kind
 * SHAPE_KIND_COUNT, of the index-th mesh. Cannot fail. */
int world_shape_object_number(const struct scene *s, size_t kind, size_t index);

/* Finds the nearest surface with t_min < t < h->t along r among all shapes, kind by kind in the order
 * of w->kinds, and keeps it in *h (with the object's number in h->object).
 * Returns true when *h was replaced. Without w->accel, a mesh whose bounding box r misses within
 * (t_min, h->t) is not tested, and its face count is added to stats_thread.triangle_tests_culled. */
bool world_closest(const struct world *w, const ray *r, double t_min, struct hit *h);

/* Calls visit(context, t, material) for every crossing of a surface by r with t_min < t < t_max: both
 * crossings of a sphere or box, each triangle, each plane. Stops as soon as visit returns false.
 * Used for shadows (chapters 7 and 8). Without w->accel, a mesh whose bounding box r misses within
 * (t_min, t_max) is not tested, and its face count is added to stats_thread.triangle_tests_culled. */
typedef shape_crossing_visitor world_crossing_visitor;
void world_for_each_crossing(const struct world *w, const ray *r, double t_min, double t_max,
                             world_crossing_visitor visit, void *context);

#endif

/* accel.h: plugs an acceleration structure into the world's triangle queries (chapter 9; the BVH
 * half, accel_world_use_bvh, arrives with chapter 10 in accel_bvh.c).
 *
 * Spheres, boxes and planes (every kind of shape but triangles) are few and stay in their loops.
 * Triangles are many: every `triangle` directive and every mesh face of the scene is gathered into one
 * mesh, the structure is built over it, and the world asks the structure instead of looping over the
 * triangles. */
#ifndef WHITTED_ACCEL_H
#define WHITTED_ACCEL_H

#include <stdbool.h>
#include <stddef.h>

#include "stats.h"
#include "world.h"

/* What was built, for the chapter's report. */
struct accel_summary {
    const char *name;     /* e.g. "BVH (SAH)"; "none" for brute force */
    double build_ms;      /* time taken to build the structure */
    size_t nodes, leaves, max_depth;
    double sah_cost;      /* the structure's predicted cost per ray (surface area heuristic), in
                             triangle tests; 0 when the structure does not report one */
};

struct accel_world {
    struct world world;        /* first, so a struct accel_world * can be used as a struct world * */
    struct world_accel accel;  /* the queries of the structure in use */
    struct mesh triangles;     /* every triangle of the scene: `triangle` directives first, then meshes */
    bool triangles_borrowed;   /* triangles is the scene's one mesh itself (its only triangles), not a copy */
    int *materials;            /* the material of each face of `triangles` */
    void *structure;           /* the kd-tree or BVH; NULL when triangles are tested one by one */
    void (*free_structure)(void *structure);
    struct accel_summary summary;
};

/* Sets up w for scene s (meshes loaded) with no structure yet: triangles by brute force behind the
 * per-mesh bounding boxes, as in chapter 5. With structure_follows, the caller will give w a
 * structure before any query, and the meshes' boxes the brute force needs are not made
 * (world_init_for_structure). Returns false with "out of memory" in err on failure. */
bool accel_world_init(struct accel_world *w, const struct scene *s, bool structure_follows, char *err,
                      size_t err_size);

/* Frees everything w owns. Safe on a zeroed accel_world. */
void accel_world_free(struct accel_world *w);

/* Builds a kd-tree over all triangles with the given split rule (an enum kd_split) and routes the
 * world's triangle queries through it. Returns false with "out of memory" in err on failure. */
bool accel_world_use_kdtree(struct accel_world *w, int split, char *err, size_t err_size);

/* The same with a bounding volume hierarchy (an enum bvh_split). Defined in accel_bvh.c (chapter 10). */
bool accel_world_use_bvh(struct accel_world *w, int split, char *err, size_t err_size);

/* Which structure a chapter program was asked for on its command line. */
enum accel_kind { ACCEL_NONE, ACCEL_KDTREE, ACCEL_BVH };

struct accel_choice {
    enum accel_kind kind;
    bool sah;        /* --split sah (the default), else the seed's rule: kd-tree by the axis holding
                        most objects, BVH by the median */
    bool split_given; /* --split was on the command line: --accel none, which builds nothing, refuses it */
};

/* Reads --accel KIND (one of the kinds allowed by the mask 1 << ACCEL_...) and --split RULE into *c,
 * in the shape of struct chapter's parse_option: returns 2 when the option was used, 0 when it is
 * not one of these, -1 after printing why the value is wrong, or why the two do not go together
 * (--split with --accel none, in either order: no structure is built, so no rule would be used). */
int accel_parse_option(struct accel_choice *c, unsigned allowed, const char *option, const char *value);

/* Makes a heap-allocated accel_world for s with the structure `c` asks for when it is chapter 9's (none
 * or the kd-tree). A later chapter's structure is that chapter's to add: for ACCEL_BVH the world is made
 * without one, for accel_world_use_bvh (chapter 10) or accel_world_use_fast_bvh (chapter 11). Returns
 * it, or NULL with the reason in err. Free with accel_world_destroy. */
struct accel_world *accel_world_create(struct scene *s, const struct accel_choice *c, char *err, size_t err_size);

/* Frees a heap-allocated accel_world and what it owns. */
void accel_world_destroy(void *world);

/* Prints what was built and its build time; with `detailed`, also its shape and what tracing it cost
 * per ray, beside the cost the SAH predicted. `total` holds the counters of the whole render. A scene
 * without triangles gets the one line "acceleration: none needed, the scene has no triangles". */
void accel_report(const struct accel_world *w, const struct stats *total, bool detailed);

#endif

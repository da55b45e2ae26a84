/* instances.h: objects placed many times, some of them moving, on a two-level BVH (chapter 16;
 * docs/16-instances.md).
 *
 * Each object line's mesh is loaded once, in its own space, and gets one chapter-11 BVH (the bottom
 * level, at FAST_BVH_RUNG_DEFAULT). Each instance line places an object by a transform, fixed or, with
 * key lines, changing over the clock. A second BVH over the instances' world boxes (the top level,
 * instance_bvh.h) finds which instances a ray may meet; the ray is carried into each one's object
 * space by the inverse transform, its direction carried without normalising, so that the parameter t of
 * a point is the same in both spaces, and walks the object's BVH; a hit comes back with the same t and
 * its normal carried by the inverse transpose. A moving instance's box holds it over the whole interval
 * the frame is exposed (keyframes_motion_box), and each ray sees it at the ray's own time.
 *
 * Per frame the top level is either refitted (the same tree, its boxes recomputed bottom-up) or rebuilt.
 * All queries are safe from several threads at once and add to the calling thread's counters:
 * instance_node_visits for the top level, node_visits, box_tests and triangle_tests for the bottom.
 *
 * Instance k is object number first_object + k (hit.object), so chapter 8's interior list tells two
 * glass instances of one object apart. A camera ray that starts inside a transparent instance starts
 * with it on its interior list: interior_at_point asks the world's instances (struct world_instances'
 * for_each_containing), each placed as it is at the ray's time. */
#ifndef WHITTED_INSTANCES_H
#define WHITTED_INSTANCES_H

#include <stdbool.h>
#include <stddef.h>

#include "aabb.h"
#include "fast_bvh.h"
#include "instance_bvh.h"
#include "keyframes.h"
#include "transform.h"
#include "world.h"

/* An instance's world box is its object's box carried by the transform, padded by this share of its
 * size plus its largest coordinate's size: room for the rounding of a ray's trip into object space (a
 * few units in the last place times the transform's condition number, which transform_invert keeps
 * below TRANSFORM_CONDITION_MAX = 1e10, so about 1e-6 of the numbers involved). */
#define INSTANCES_BOX_PAD 1e-5

/* How much a turn can worsen a pose's condition: for M = R S (a turn R of a diagonal scale S), the
 * row-sum norms transform_invert uses give ||R S|| <= sqrt(3) max|s| and ||S^-1 R^T|| <= sqrt(3) / min|s|,
 * so its condition is at most 3 max|s| / min|s| whatever the turn; the hundredth more covers the
 * roundings of the turned axes and of the interpolated scale. Between two keys, whose turn is not known
 * in advance, each key's scale factors must keep INSTANCES_TURN_SPREAD max|s| / min|s| within
 * TRANSFORM_CONDITION_MAX (the poses in between spread no wider than the wider key). */
#define INSTANCES_TURN_SPREAD 3.03

/* How the top level follows the instances from one frame to the next. */
enum instances_update {
    INSTANCES_REFIT,   /* keep the tree, recompute its boxes bottom-up */
    INSTANCES_REBUILD, /* build a new tree over the new boxes */
    INSTANCES_AUTO     /* refit, unless the refitted tree's SAH cost has grown past INSTANCES_REBUILD_GROWTH
                        * times the cost of the last tree built: then rebuild */
};

/* The rule INSTANCES_AUTO follows: a refit is kept while its SAH cost stays within this factor of the
 * last build's. Measured on 2000 bunnies each wandering across an 80-unit square over 11 frames (160 x
 * 100 pixels, two cores): refitted only, the top level's SAH cost grew from 19.9 to 759 and the run took
 * 1.3 to 1.8 s; rebuilt every frame it stayed at 23 +- 1, in 0.6 to 0.9 s; by this rule, 0.54 to 0.57 s.
 * A build costs little beside a frame (0.03 ms for the 41 instances of the chapter's scene, 52 ms for
 * 10,000, 3.7 s for a million), and a tree whose cost has grown by a quarter costs every ray of the frame
 * about that much more at the top level, so the rule rebuilds as soon as the growth is worth one. */
#define INSTANCES_REBUILD_GROWTH 1.25

/* One placed object. */
struct instance {
    int object;                   /* index into the scene's objects */
    int material;
    struct keyframe *keys;        /* the pose over time; NULL for a fixed instance */
    size_t key_count;
    struct transform to_world;    /* a fixed instance's transform and its inverse */
    struct transform to_object;
    bool in_tree;                 /* false: its object has slivers, whose hits no box holds: every ray tests it */
};

/* What building and holding the instances cost, for --stats. */
struct instances_info {
    size_t objects, instances, moving;
    size_t object_triangles;      /* triangles of all objects, each counted once */
    double instanced_triangles;   /* triangles of all instances: what writing them out would hold */
    size_t object_bytes;          /* the objects' meshes and bottom-level trees */
    double object_build_ms;       /* building the bottom level */
    double top_build_ms;          /* the last build or refit of the top level */
    double top_sah_cost;          /* the top level's SAH cost now, and right after it was last built */
    double top_sah_cost_built;
    size_t rebuilds, refits;      /* builds (the first included) and refits of the top level */
};

struct instances {
    const struct scene *scene;
    int first_object;             /* hit.object of instance 0; instance k is first_object + k */
    struct fast_bvh **objects;    /* one tree per scene object, in object space */
    struct aabb *object_boxes;    /* each object's box, padded as world_mesh_cull_bounds pads a mesh's */
    struct aabb *object_extents;  /* each object's box, unpadded: what the scale warning measures */
    struct instance *items;
    size_t count;
    struct aabb *boxes;           /* each instance's world box over [t0, t1] */
    size_t *outside;              /* the instances not in the tree (their object has slivers) */
    size_t outside_count;
    struct instance_bvh *top;     /* NULL when no instance is in the tree */
    double t0, t1;                /* the interval the boxes hold the instances over */
    struct world_instances hook;  /* the queries, for struct world */
    struct instances_info info;
};

/* Whether the file of every object line of s opens (infile_open), placed by an instance or not: an
 * object no instance places is never loaded (instances_create), but a file name that does not open is
 * a mistake to report, not to pass over. Returns false with "file:line: object 'NAME': why" in err. */
bool instances_objects_open(const struct scene *s, char *err, size_t err_size);

/* Loads the mesh of every object of scene s that an instance places (once, with the mesh readers of
 * scene_load_meshes; objects no instance places are left unloaded) and builds its tree, then places every instance (its keys checked: each pose's transform invertible within
 * TRANSFORM_CONDITION_MAX, no scale changing sign between keys, every pose between two keys invertible
 * whatever its turn (INSTANCES_TURN_SPREAD), the placed object inside the range a
 * mesh may be placed in) and builds the top level over the interval [t0, t1]. Instance k's hits carry
 * object number first_object + k. Returns the instances (free with instances_free) or NULL with
 * "file:line: what is wrong" in err. */
struct instances *instances_create(struct scene *s, int first_object, double t0, double t1, char *err,
                                   size_t err_size);

/* Moves the instances to the interval [t0, t1] (a new frame): recomputes every box and then refits or
 * rebuilds the top level as `how` says. Returns false with the reason in err when memory runs out
 * (the instances are then left as they were). */
bool instances_set_interval(struct instances *in, double t0, double t1, enum instances_update how, char *err,
                            size_t err_size);

/* The transform of instance k at clock time `time` and its inverse. Returns false when the pose there
 * cannot be inverted (not for the instances instances_create accepts). */
bool instances_transform_at(const struct instances *in, size_t k, double time, struct transform *to_world,
                            struct transform *to_object);

/* The scene's measure of the instances (scene_bounds_fn, scene.h), for the scale warning (scene_scale.h):
 * grows [*min, *max] by the world box of every instance of `instances` (a struct instances), its
 * object's unpadded box carried by its transform (a moving one's held over the interval the top level
 * holds it over now, instances_set_interval, by keyframes_motion_box), so that a fixed instance counts
 * as much as the same mesh placed by a mesh line, and returns true when there is an instance. Chapter 16 sets it as the scene's
 * instance_bounds once the instances are placed. Cannot fail. */
bool instances_bounds(const void *instances, vec3 *min, vec3 *max);

/* Frees in and everything it owns (not the scene). Safe on NULL. */
void instances_free(struct instances *in);

/* Prints what was built, its memory per instance and build times; with `detailed`, also the top level's
 * SAH cost and how often it was refitted and rebuilt. */
void instances_report(const struct instances *in, FILE *out, bool detailed);

/* Instances carried into per ray beyond which a scene is refused, or noted, by chapter 16 (unless
 * --no-limit, or --quiet for the note): instances on top of one another defeat the top level, which
 * then hands every ray to each of them. A ray carried into an instance costs about 100 ns on one core
 * (100,000 instances of a triangle in one place: 1.6e9 of them in 169 s): at 1e7 a second, the limit is
 * more than a day and the note a quarter of an hour. */
#define INSTANCES_TEST_LIMIT 1e12
#define INSTANCES_TEST_LARGE 1e10

/* Returns how many instances a ray is expected to be carried into: the top level's expectation
 * (instance_bvh_expected_instances) and the instances outside the tree, which every ray tests. Stores
 * in *line the scene line of an instance where they crowd most (0 for no instances), and in *outside
 * whether those outside the tree (the instances of objects with sliver faces) are the most of them. */
double instances_expected_tests(const struct instances *in, int *line, bool *outside);

#endif
